"""No function of the library, the agents or the scripts takes more than 10
parameters (self and cls not counted): physics kernels group their
arguments into the named structures of ``physics/layout.py`` (``Balls``,
``Geometry``, ``Motion``, ``ChunkScratch`` ...), ``simulate`` its less
common options into ``SimOptions``, the bots theirs into structures such as
``PotLimits`` or the lookahead's ``Budget``."""
import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
MAX_PARAMETERS = 10


def parameter_counts(source: str):
    """(function name, parameters but self and cls) of every function in ``source``."""
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs + [a.vararg, a.kwarg] if x]
            yield node.name, len([n for n in names if n not in ("self", "cls")])


def test_no_function_over_ten_parameters():
    files = [p for d in ("billiards_env", "agents", "scripts") for p in sorted((ROOT / d).rglob("*.py"))]
    counts = [(path.relative_to(ROOT).as_posix(), name, n) for path in files
              for name, n in parameter_counts(path.read_text())]
    assert len(counts) > 1000  # the walk saw the packages
    over = [f"{f}: {name} ({n})" for f, name, n in counts if n > MAX_PARAMETERS]
    assert not over, "functions over 10 parameters (group them in a named structure): " + ", ".join(over)


def test_the_count_sees_every_kind_of_parameter():
    src = "def f(a, /, b, *c, d, **e): pass\nclass K:\n    def m(self, x): pass\n"
    assert dict(parameter_counts(src)) == {"f": 5, "m": 1}

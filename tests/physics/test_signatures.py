"""No function of the physics package takes more than 10 parameters (self
and cls not counted): kernels group their arguments into the named
structures of ``physics/layout.py`` (``Balls``, ``Geometry``, ``Motion``,
``ChunkScratch`` ...), and ``simulate`` its less common options into
``SimOptions``."""
import ast
import pathlib

import billiards_env.physics as physics

MAX_PARAMETERS = 10
# Known exceptions, each to be removed with the rewrite that ends it: the
# Mathavan et al. (2010) cushion model is being rewritten on its own branch.
ALLOWED = {("cushion/mathavan2010.py", "_rates"), ("cushion/mathavan2010.py", "_mid_rates"),
           ("cushion/mathavan2010.py", "_integrate")}


def parameter_counts(source: str):
    """(function name, parameters but self and cls) of every function in ``source``."""
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            names = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs + [a.vararg, a.kwarg] if x]
            yield node.name, len([n for n in names if n not in ("self", "cls")])


def test_no_function_over_ten_parameters():
    root = pathlib.Path(physics.__file__).parent
    counts = [(path.relative_to(root).as_posix(), name, n)
              for path in sorted(root.rglob("*.py")) for name, n in parameter_counts(path.read_text())]
    assert len(counts) > 100  # the walk saw the package
    over = [f"{f}: {name} ({n})" for f, name, n in counts if n > MAX_PARAMETERS and (f, name) not in ALLOWED]
    assert not over, "functions over 10 parameters (group them in a named structure): " + ", ".join(over)


def test_the_count_sees_every_kind_of_parameter():
    src = "def f(a, /, b, *c, d, **e): pass\nclass K:\n    def m(self, x): pass\n"
    assert dict(parameter_counts(src)) == {"f": 5, "m": 1}

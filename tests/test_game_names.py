"""Outside ``billiards_env/rules/`` (the games' registry, ``rules.games``, and the rulesets) no library module
names a game: a branch on the game, a per-game list or a default reads the registry (a ``GameSpec`` field,
``DEFAULT_GAME``, ``bot_games``) or the game's rules (``Rules.game_ball``, ``groups``, ...) instead, so a sixth
game needs no edit there (``tests/envs/test_toy_game.py`` registers one and plays it through them).

The scan: every string constant of a module of billiards_env/ outside rules/ (docstrings and other bare string
statements not counted) that is a registered game's name or title, or holds its Gymnasium id
(``Billiards-<id_stem>-v``), must be allowed by ``ALLOWED``: the literals that are not game references (a
physics preset, a table style or a rack layout named like a game, a bot's or a one-player task's name) and the
few that are by design, each counted in its file and each with its reason. An entry whose count no longer
matches fails as well, so the list stays exact."""
from __future__ import annotations

import ast
import re
from collections import Counter
from pathlib import Path

from billiards_env.rules import GAMES

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "billiards_env"

# (module under billiards_env/, literal): (times it occurs there, why it is not a game reference or stays one)
ALLOWED = {
    # the physics' presets, table styles and rack layouts of snooker's equipment (PhysicsParams.snooker,
    # Table.snooker, rack(..., "snooker")); the rules name the ones a game plays on (Rules.table_style, .physics)
    ("physics/params.py", "snooker"): (1, "the snooker balls' physics preset's name"),
    ("physics/state.py", "snooker"): (2, "the snooker rack layout"),
    ("physics/table.py", "snooker"): (1, "Table.snooker()'s style"),
    ("rendering/draw.py", "snooker"): (1, "the ball colours of the snooker table style"),
    ("testing/fuzzing.py", "snooker"): (4, "the fuzzed table and rack layout of snooker equipment"),
    # bots by name: the snooker bot (bots/snooker.py, written for snooker; its spec's default_bot and own_bots
    # link it to the game)
    ("bots/registry.py", "snooker"): (3, "the snooker bot's name: BOT_NAMES, FIXED_NAMES, make_bot"),
    ("bots/snooker.py", "snooker"): (2, "the snooker bot's own name"),
    # the one-player task Billiards-NineBall-v1 (envs.tasks), not the two-player game
    ("envs/tasks/nine_ball.py", "nine_ball"): (1, "the one-player task's name in the task registry"),
    # studies of one game by definition
    ("studies/championship.py", "eight_ball"): (1, "the 2011 computer pool championship's protocol is 8-ball"),
    ("studies/snooker_bench.py", "snooker"): (2, "the study of snooker (its GAME) and the snooker rack layout"),
    ("studies/bench/cli.py", "snooker"): (3, "the benchmark's snooker section (studies.snooker_bench), by name"),
    # the benchmark's tasks are fixed by design: its protocol names each env id (counted whatever its version,
    # ``ANY_VERSION``: a game's new version moves the protocol with it) and the snooker bot as reference and
    # opponent (a new game joins the benchmark with a new protocol version)
    ("benchmark/protocol.py", "Billiards-NineBall2P-v*"): (1, "a benchmark task's env id"),
    ("benchmark/protocol.py", "Billiards-EightBall-v*"): (1, "a benchmark task's env id"),
    ("benchmark/protocol.py", "Billiards-TenBall-v*"): (1, "a benchmark task's env id"),
    ("benchmark/protocol.py", "Billiards-ThreeCushion-v*"): (1, "a benchmark task's env id"),
    ("benchmark/protocol.py", "Billiards-Snooker-v*"): (1, "a benchmark task's env id"),
    ("benchmark/protocol.py", "snooker"): (2, "the snooker bot: the snooker task's reference and opponent"),
}
ANY_VERSION = re.compile(r"(Billiards-\w+-v)\d+")  # an env id's version, read as any (``v*``) in ``ALLOWED``


def _words() -> tuple[dict, dict]:
    """The registered games' names and titles, and their Gymnasium ids' stems ``Billiards-<id_stem>-v``."""
    exact = {}
    for name, spec in GAMES.items():
        exact[name] = exact[spec.title] = name
    return exact, {f"Billiards-{spec.id_stem}-v": name for name, spec in GAMES.items()}


def game_literals(source: str, exact: dict, ids: dict) -> Counter:
    """The string constants of ``source`` that name a game (``exact``: names and titles) or hold its id (a
    stem of ``ids``), counted; docstrings and other bare string statements are not counted."""
    tree = ast.parse(source)
    bare = {id(n.value) for n in ast.walk(tree) if isinstance(n, ast.Expr) and isinstance(n.value, ast.Constant)}
    found = Counter()
    for n in ast.walk(tree):
        if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in bare:
            if n.value in exact or any(stem in n.value for stem in ids):
                found[n.value] += 1
    return found


def library_game_literals() -> Counter:
    """(module under billiards_env/, literal) -> count over every module outside rules/ (an env id's version read
    as ``v*``)."""
    exact, ids = _words()
    found = Counter()
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE).as_posix()
        if rel.startswith("rules/"):
            continue
        for literal, k in game_literals(path.read_text(), exact, ids).items():
            found[(rel, ANY_VERSION.sub(r"\1*", literal))] += k
    return found


def test_no_module_outside_rules_names_a_game():
    found = library_game_literals()
    assert len(list(PACKAGE.rglob("*.py"))) > 100  # the walk saw the package
    new = [f"{f}: {lit!r} x{k}" + (f" (allowed x{ALLOWED[f, lit][0]})" if (f, lit) in ALLOWED else "")
           for (f, lit), k in sorted(found.items()) if k > ALLOWED.get((f, lit), (0,))[0]]
    assert not new, ("a game named outside rules/: read the registry (rules.games: a GameSpec field, "
                     "DEFAULT_GAME, bot_games) or the game's rules instead, or, if the literal is no game "
                     "reference, add it to ALLOWED with its reason:\n" + "\n".join(new))
    stale = [f"{f}: {lit!r} allowed x{k}, found x{found.get((f, lit), 0)}"
             for (f, lit), (k, _) in sorted(ALLOWED.items()) if found.get((f, lit), 0) < k]
    assert not stale, "ALLOWED counts more than the modules hold (lower or drop the entries):\n" + "\n".join(stale)


def test_the_scan_sees_names_titles_and_ids_but_not_docstrings():
    exact, ids = _words()
    src = ('"""A docstring naming snooker and nine_ball."""\n'
           'def f(game="nine_ball"):\n'
           '    """eight_ball in a docstring."""\n'
           '    "a bare string: three_cushion"\n'
           '    if game == "snooker" or game in ("ten_ball", "three-cushion"):\n'
           '        return "Billiards-Snooker-v1", f"{game}: snooker", "snookers"\n')
    assert game_literals(src, exact, ids) == Counter({"nine_ball": 1, "snooker": 1, "ten_ball": 1,
                                                      "three-cushion": 1, "Billiards-Snooker-v1": 1})

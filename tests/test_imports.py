"""The import graph of billiards_env, agents and scripts has no cycle.

Every ``import`` / ``from ... import`` statement counts, at module level and
inside functions; relative imports are resolved against the importing
module's package; ``from pkg import name`` is an edge to ``pkg.name`` when
that is a module, else to ``pkg``. Scripts import each other as top-level
modules (``scripts/`` is on ``sys.path`` when they run)."""
from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("billiards_env", "agents", "scripts")


def module_files() -> dict[str, Path]:
    mods = {}
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            parts = list(path.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            mods[".".join(parts)] = path
    return mods


def _resolve(name: str, current: str, mods: dict) -> str | None:
    if name in mods:
        return name
    if current.startswith("scripts.") and f"scripts.{name}" in mods:  # sibling script on sys.path
        return f"scripts.{name}"
    return None


def import_graph() -> dict[str, set[str]]:
    mods = module_files()
    graph: dict[str, set[str]] = {m: set() for m in mods}
    for mod, path in mods.items():
        is_pkg = path.name == "__init__.py"
        package = mod if is_pkg else mod.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")
                    base = base[:len(base) - (node.level - 1)]
                    base = ".".join(base + ([node.module] if node.module else []))
                else:
                    base = node.module
                for a in node.names:
                    full = f"{base}.{a.name}"
                    targets.append(full if _resolve(full, mod, mods) else base)
            for t in targets:
                r = _resolve(t, mod, mods)
                if r is not None and r != mod:
                    graph[mod].add(r)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """A cycle [m0, m1, ..., m0] of the directed graph, or None (depth-first search)."""
    WHITE, GREY, BLACK = 0, 1, 2
    colour = {m: WHITE for m in graph}
    stack: list[str] = []

    def visit(m):
        colour[m] = GREY
        stack.append(m)
        for n in sorted(graph[m]):
            if colour[n] == GREY:
                return stack[stack.index(n):] + [n]
            if colour[n] == WHITE:
                found = visit(n)
                if found:
                    return found
        stack.pop()
        colour[m] = BLACK
        return None

    for m in sorted(graph):
        if colour[m] == WHITE:
            found = visit(m)
            if found:
                return found
    return None


def test_cycle_finder_finds_a_cycle():
    g = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}
    assert find_cycle(g) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_graph_sees_function_level_and_relative_imports():
    g = import_graph()
    assert "billiards_env.envs.tasks.registry" in g["billiards_env.envs.config"]  # relative, module level
    assert "billiards_env.physics.validation" in g["billiards_env.envs.core"]  # inside a method
    assert "agents.plotting" in g["agents.sb3.training"]  # inside a function
    assert "agents.sb3.training" in g["scripts.train"]


def test_no_import_cycle():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


# Layers, lowest first: a module may import its own layer and the layers below, never above.
# The bot contract (views, plans, the preview, the turn the env and the preview share, the action
# codec) lies below both the bots and the envs; envs and rendering share a layer above the bots (the
# envs take bots as opponents and render themselves); the cycle test above keeps them acyclic.
LAYERS = (
    ("billiards_env.physics",),
    ("billiards_env.rules",),
    ("billiards_env.contract",),
    ("billiards_env.bots",),
    ("billiards_env.envs", "billiards_env.rendering"),
    ("billiards_env.studies", "billiards_env.testing", "billiards_env"),
    ("billiards_env.play",),  # the play server: an app on top of the library (nothing in it is imported below)
    ("agents",),
    ("scripts",),
)


def layer_of(mod: str) -> int:
    best, depth = None, -1
    for k, prefixes in enumerate(LAYERS):
        for p in prefixes:
            if (mod == p or mod.startswith(p + ".")) and p.count(".") > depth:
                best, depth = k, p.count(".")
    assert best is not None, f"{mod} is in no layer"
    return best


def test_layers_only_look_down():
    """physics below rules below the bot contract below the bots below the envs, the library below agents and
    scripts (so no bots module imports envs):
    no import (lazy ones included) reaches up a layer."""
    bad = [f"{a} (layer {layer_of(a)}) imports {b} (layer {layer_of(b)})"
           for a, targets in import_graph().items() for b in sorted(targets) if layer_of(b) > layer_of(a)]
    assert not bad, "imports that reach up:\n" + "\n".join(bad)


def test_layer_check_sees_a_violation():
    assert layer_of("billiards_env.physics.simulate") == 0 and layer_of("billiards_env.contract.turn") == 2
    assert layer_of("billiards_env.bots.ghost") == 3 and layer_of("billiards_env.envs.games.core") == 4
    assert layer_of("billiards_env") == 5 and layer_of("billiards_env.play.app") == 6
    assert layer_of("agents.sb3.training") == 7
    assert layer_of("billiards_env.envs.games.versus") < layer_of("agents.evaluation.entrants")

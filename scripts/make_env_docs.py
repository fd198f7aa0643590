#!/usr/bin/env python
"""Write docs/environments.md from the task registry: one section per
registered task (its spec, the class docstring of its ``Task``, and its
default configuration from its YAML file) and the spec shared by every task
(observation, action, reward, info, configuration: ``billiards._COMMON_DOC``).

    python scripts/make_env_docs.py            # rewrite docs/environments.md
    python scripts/make_env_docs.py --check    # exit 1 if the file is stale
"""
from __future__ import annotations

import argparse
import inspect
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
OUT = ROOT / "docs" / "environments.md"


def _md(text: str) -> str:
    """The reStructuredText of the docstrings as Markdown: ``code`` -> `code`,
    **bold** kept, simple tables (``====  ====`` borders) -> pipe tables."""
    lines = inspect.cleandoc(text).splitlines()
    out, i = [], 0
    while i < len(lines):
        line = lines[i]
        if re.fullmatch(r"=+( +=+)+", line.strip()):
            indent = len(line) - len(line.lstrip())
            starts = [m.start() + indent for m in re.finditer(r"=+", line.strip())]
            border = lambda k: re.fullmatch(r"=+( +=+)+", lines[k].strip()) is not None  # noqa: E731
            rows, j, n_borders, header_rows = [], i + 1, 1, 0
            while j < len(lines):
                row = lines[j]
                j += 1
                if border(j - 1):
                    n_borders += 1
                    if j >= len(lines) or not lines[j].strip():  # closing border
                        break
                    header_rows = len(rows)  # a border inside the table ends the header
                elif row.strip():
                    cells = [row[a:b].strip() for a, b in zip(starts, starts[1:] + [None])]
                    if cells[0] or not rows:
                        rows.append(cells)
                    else:  # continuation line: append to the cells of the row above
                        rows[-1] = [f"{p} {c}".strip() for p, c in zip(rows[-1], cells)]
            head, body = (rows[0], rows[1:]) if header_rows == 1 else (None, rows)
            if head is None or not any(head):
                head = [""] * len(starts)
            out.append("| " + " | ".join(head) + " |")
            out.append("|" + "|".join("---" for _ in starts) + "|")
            out += ["| " + " | ".join(c.replace("|", "\\|") for c in r) + " |" for r in body]
            i = j
            continue
        out.append(line)
        i += 1
    text = "\n".join(out)
    return re.sub(r"``([^`]+)``", r"`\1`", text)


def _defaults(path: Path) -> str:
    """The task's YAML as a table: a section's keys one row each (``equipment.table``), a mapping in one cell."""
    import yaml

    def rows(d: dict, prefix: str = ""):
        for k, v in d.items():
            if isinstance(v, dict) and any(isinstance(x, dict) for x in v.values()):
                yield from rows(v, f"{prefix}{k}.")
                continue
            if isinstance(v, dict):
                v = ", ".join(f"{a}: {b}" for a, b in v.items())
            yield f"| `{prefix}{k}` | {v} |"

    return "| key | default |\n|---|---|\n" + "\n".join(rows(yaml.safe_load(path.read_text())))


# How the envs are made and used with Gymnasium: the section after the table of ids.
USING = [
    "## Making and using the envs", "",
    "**The ids.** Importing `billiards_env` registers every id. Gymnasium 1.x loads no plugins (the "
    "`gymnasium.envs` entry points of Gymnasium 0.x are gone), so in a process that has not imported the package, "
    "name the module in the id: Gymnasium imports the part before the colon first.", "",
    "```python",
    "import gymnasium as gym",
    "",
    "env = gym.make(\"billiards_env:Billiards-PotOne-v1\")   # no import needed",
    "vec = gym.make_vec(\"billiards_env:Billiards-PotOne-v1\", num_envs=256, vectorization_mode=\"vector_entry_point\")",
    "",
    "import billiards_env                                  # or import the package once: then the bare ids",
    "env = gym.make(\"Billiards-PotOne-v1\")",
    "```", "",
    "**The env's own methods.** `gym.make` returns the env inside Gymnasium's wrappers (the order and "
    "passive checks, and a time limit where the id has one), and Gymnasium 1.x wrappers pass no attribute through. The task's own "
    "methods, `view()`, `actions_of(plan)`, `actions_to_shots(actions)`, `shots_to_actions(shots)`, "
    "`shot_context()` and `set_state(state)`, are on `env.unwrapped` (Gymnasium's convention; "
    "`env.get_wrapper_attr(\"view\")` finds them too): `env.unwrapped.view()`. The native vector env of "
    "`make_vec(..., vectorization_mode=\"vector_entry_point\")` is not wrapped and has them itself.", "",
    "**Worker processes.** `gym.make_vec(id, num_envs=n, vectorization_mode=\"async\")` runs each table in a "
    "worker process, forked on Linux. The simulator's threads (numba's GNU OpenMP) do not survive a fork, so a "
    "process forked from one that has run the simulator runs its kernels on one thread, with the same results "
    "bit for bit (`billiards_env/physics/forking.py`; the first time, the one-thread kernels compile). "
    "`vector_kwargs={\"context\": \"forkserver\"}` starts fresh workers instead. The native vector env, all "
    "tables in one batched simulator call, is the fast way to many tables.",
]


def render() -> str:
    import billiards_env  # noqa: F401  (registers the tasks)
    from billiards_env.envs import billiards
    from billiards_env.envs.tasks import TASKS

    builtin = [t for t in TASKS.values() if type(t).__module__.startswith("billiards_env.")]
    parts = ["<!-- Generated by scripts/make_env_docs.py from the task docstrings (billiards_env/envs/tasks/) "
             "and billiards_env/envs/tasks/defaults/*.yaml: edit those, then re-run the script. -->",
             "# Environments", "",
             "One step is one shot: the cue ball is struck, the table is simulated until every ball rests, and "
             "the observation is the resting table. Each task has a single-table class (`<Name>Env`, a "
             "`gymnasium.Env`) and a native vector class (`<Name>VectorEnv`, a `gymnasium.vector.VectorEnv` "
             "shooting every table with one batched simulator call), registered side by side "
             "(`gymnasium.make(id)`, `gymnasium.make_vec(id, num_envs=n, "
             "vectorization_mode=\"vector_entry_point\")`). Adding a task: [adding_a_task.md](adding_a_task.md).",
             "", "| id | task | classes | config |", "|---|---|---|---|"]
    for t in builtin:
        rel = t.default_config_path.relative_to(ROOT)
        parts.append(f"| [`{t.env_id}`](#{t.env_id.lower()}) | `{t.name}` | "
                     f"`{t.class_prefix}Env`, `{t.class_prefix}VectorEnv` | `{rel}` |")
    parts += ["", *USING]
    for t in builtin:
        parts += ["", f"## {t.env_id}", "", _md(t.__doc__), "",
                  "Observation, action, reward, info: [common to every task](#common-to-every-task). "
                  f"Defaults (`{t.default_config_path.relative_to(ROOT)}`; keys: `TaskConfig`, the `equipment` "
                  "section: [configuration.md](configuration.md#the-equipment-section)):", "",
                  _defaults(t.default_config_path)]
    parts += ["", "## Common to every task", "", _md(billiards._COMMON_DOC), "",
              "### Vector env: seeding and autoreset", "", _md(billiards.BilliardsVectorEnv.__doc__)]
    return "\n".join(parts).rstrip() + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="only check that the file is up to date")
    a = ap.parse_args(argv)
    text = render()
    if a.check:
        if not OUT.exists() or OUT.read_text() != text:
            print(f"{OUT} is stale: run python scripts/make_env_docs.py")
            return 1
        return 0
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(text)
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

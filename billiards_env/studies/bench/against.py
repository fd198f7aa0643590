"""This tree against another revision: the other revision checked out in a
temporary worktree, both trees' numba caches warmed, then every section run
in both trees in turn, a fresh process per run (the tree's own
``scripts/benchmark.py --worker``, PYTHONPATH set to the tree, the same
seeds), ``rounds`` times with the order alternating; the result is both
trees' median rows."""
from __future__ import annotations

import dataclasses
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .options import ROOT, RunOptions
from .report import ROW_KEY
from .trees import checked_out, revision, share_numba_cache

# The worker protocol, which every revision's scripts/benchmark.py since the
# first --against (4e85f32) understands: --worker ROWS.json --only SECTION
# --batch N --repeats N [--quick] [--scene TEXT ...]; it writes the section's
# rows as a JSON list to ROWS.json.


@dataclasses.dataclass(frozen=True)
class Comparison:
    """``rev``: the other revision; ``sections``: the --only names, in order;
    ``rounds``: interleaved rounds per tree; ``run``: the sections' options."""
    rev: str
    sections: tuple[str, ...]
    rounds: int = 3
    run: RunOptions = RunOptions()


def worker_command(tree: Path, opts: RunOptions, section: str, json_path: Path, warm: bool = False) -> list[str]:
    """The command running ``section`` in ``tree``'s own benchmark script
    (``warm``: the smallest run, which only compiles or loads the kernels)."""
    cmd = [sys.executable, str(tree / "scripts" / "benchmark.py"), "--worker", str(json_path), "--only", section,
           "--batch", str(2 if warm else opts.batch), "--repeats", str(1 if warm else opts.repeats)]
    if opts.quick or warm:
        cmd.append("--quick")
    for part in opts.scene or []:
        cmd += ["--scene", part]
    return cmd


def run_in_tree(tree: Path, opts: RunOptions, section: str, warm: bool = False) -> list[dict]:
    """Run one section in a fresh process that imports ``tree``'s billiards_env."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rows.json"
        others = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p and Path(p).resolve() != ROOT]
        env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tree)] + others)}
        out = subprocess.run(worker_command(tree, opts, section, path, warm), cwd=tree, env=env,
                             capture_output=True, text=True)
        if out.returncode != 0:
            hint = ("\n(its scripts/benchmark.py has no --worker mode: the revision predates --against, "
                    "4e85f32, and cannot be compared)" if "unrecognized arguments: --worker" in out.stderr else "")
            raise RuntimeError(f"benchmark section {section!r} failed in {tree}:\n{out.stderr[-3000:]}{hint}")
        return json.loads(path.read_text())


def medians(runs: list[dict], **tags) -> list[dict]:
    """One row per ``ROW_KEY``: the first run's row with every float the
    median over the runs, plus ``tags`` and the number of ``rounds``."""
    groups = {}
    for r in runs:
        groups.setdefault(tuple(r.get(k) for k in ROW_KEY), []).append(r)
    out = []
    for rs in groups.values():
        med = dict(rs[0])
        for k, v in rs[0].items():
            if isinstance(v, float):
                med[k] = statistics.median(r[k] for r in rs)
        med.update(**tags, rounds=len(rs))
        out.append(med)
    return out


def against(comp: Comparison) -> list[dict]:
    """Interleaved runs of every section of ``comp`` in this tree and in
    ``comp.rev``; returns both trees' median rows, tagged with their revisions."""
    new_rev = revision(ROOT)
    with checked_out(comp.rev) as old_tree:
        old_rev = revision(old_tree)
        trees = {"new": (ROOT, new_rev), "old": (old_tree, old_rev)}
        n = share_numba_cache(ROOT, old_tree)
        print(f"this tree {new_rev} against {comp.rev} = {old_rev} (temporary worktree {old_tree}; "
              f"{n} cached kernel files shared)", flush=True)
        warmed = [s for s in comp.sections if s != "cold"]
        for label, (tree, rev) in trees.items():  # compile (or load) every variant before timing
            t0 = time.perf_counter()
            for section in warmed:
                run_in_tree(tree, comp.run, section, warm=True)
            print(f"  warmed {label} tree ({rev}) in {time.perf_counter() - t0:.0f} s", flush=True)
        runs = {"new": [], "old": []}
        for k in range(comp.rounds):
            order = ("new", "old") if k % 2 == 0 else ("old", "new")
            for section in comp.sections:
                for label in order:
                    runs[label] += run_in_tree(trees[label][0], comp.run, section)
            print(f"  round {k + 1}/{comp.rounds} done", flush=True)
    out = []
    for label, (_, rev) in trees.items():
        other = trees["old" if label == "new" else "new"][1]
        out += medians(runs[label], revision=rev, compared_with=other, tree=label)
    return out

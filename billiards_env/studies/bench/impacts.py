"""The models section's per-impact cost: each cushion model resolving the
same single impacts, timed in one jitted loop per model, the models taking
turns in every repeat (so a busy machine slows them alike); and the same
for a model module as it was at another git revision (``BASELINE``: the
Mathavan integration before its stick rule and step control were redone),
loaded from that revision's source into this process."""
from __future__ import annotations

import importlib.util
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np

from billiards_env.physics import PhysicsParams
from billiards_env.physics import constants as C
from billiards_env.physics import cushion

from .options import ROOT, RunOptions

# (label, revision, module) timed beside the registered models, if git has it
BASELINE = ("mathavan2010 at df93ffd (its midpoint scheme)", "df93ffd", "mathavan2010")


def impact_set(n: int, seed: int = 1) -> np.ndarray:
    """n impacts (vx, vy, wx, wy, wz) on a cushion of normal (0, 1): speeds
    0.05 - 12 m/s at up to 89 degrees from the normal, spins to 400 rad/s."""
    rng = np.random.default_rng(seed)
    v = rng.uniform(0.05, 12.0, n)
    a = rng.uniform(-1.55, 1.55, n)
    return np.column_stack([v * np.sin(a), -v * np.cos(a), rng.uniform(-400.0, 400.0, (n, 3))])


def _loop(resolve):
    """A jitted loop resolving every impact of X (returns a checksum, so
    the work is not optimised away)."""
    @numba.njit(nogil=True)
    def run(X, p):
        total = 0.0
        for i in range(X.shape[0]):
            out = resolve(X[i, 0], X[i, 1], X[i, 2], X[i, 3], X[i, 4], 0.0, 1.0, -X[i, 1], p[C.P_E_C], p)
            total += out[0] + out[1] + out[2] + out[3] + out[4]
        return total
    return run


def module_at(rev: str, name: str):
    """cushion/<name>.py as it was at git revision ``rev``, imported as a
    sibling module (its relative imports resolve to this tree's helpers);
    None if git or the revision is not available."""
    rel = f"billiards_env/physics/cushion/{name}.py"
    try:
        src = subprocess.run(["git", "-C", str(ROOT), "show", f"{rev}:{rel}"], capture_output=True, text=True,
                             check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    path = Path(tempfile.mkdtemp(prefix="cushion-at-")) / f"{name}_at_{rev}.py"
    path.write_text(src)
    modname = f"{cushion.__name__}._{name}_at_{rev}"
    spec = importlib.util.spec_from_file_location(modname, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[modname] = mod
    spec.loader.exec_module(mod)
    return mod


def impact_rows(opts: RunOptions, P: PhysicsParams | None = None) -> list[dict]:
    """µs per impact of plain reflection, each registered cushion model and
    ``BASELINE``, on ``impact_set`` (2,000 impacts; quick: 200), median of
    ``opts.repeats`` (at least 5) interleaved rounds, with the ratio to the
    baseline measured in the same run."""
    P = P or PhysicsParams.standard()
    p = P.as_array()
    X = impact_set(200 if opts.quick else 2000)
    models = {"reflection (no cushion friction)": cushion.reflection.resolve,
              **{name: m.resolve for name, m in cushion.MODELS.items()}}
    label, rev, name = BASELINE
    base = module_at(rev, name)
    if base is not None:
        models[label] = base.resolve
    loops = {k: _loop(f) for k, f in models.items()}
    for run in loops.values():  # compile
        run(X[:2], p)
    times = {k: [] for k in loops}
    for _ in range(max(5, opts.repeats)):
        for k, run in loops.items():
            t0 = time.perf_counter()
            run(X, p)
            times[k].append(time.perf_counter() - t0)
    us = {k: 1e6 * statistics.median(t) / len(X) for k, t in times.items()}
    rows = []
    for k, u in us.items():
        row = dict(section="models", scene="one cushion impact", solver="-", effects=k, batch=len(X),
                   us_per_impact=u, vs_baseline=u / us[label] if label in us else None)
        rows.append(row)
        print(f"  cushion impact {k:44s} {u:9.3f} µs", flush=True)
    return rows

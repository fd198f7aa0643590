"""What accuracy costs in time: the step solver against the exact event solver.

One fixed, seeded set of shots per scene (random two-ball shots, 9-ball
breaks, random shots on the tables the breaks leave; ``studies.scenes``) runs
through the event solver (the reference) and the step solver at a list of
time steps. Per (scene, solver, dt) the study measures the time per shot
(batched and single-table, median), the final position error against the
reference (median / 95th percentile, mm), the fraction of shots whose
outcome differs (set of pocketed balls or first contact) and the fraction
whose sequence of ball-ball / cushion / jaw / pocket events (with ball ids)
diverges. Then the same for the event solver with physics effects switched
off, and the event solver's own sensitivity to a 1e-6 rad aim or 1e-6 m/s
speed perturbation: the floor any solver's error is read against.

``run_models`` compares, on the same shots, each non-default model choice
(``MODEL_VARIANTS``, all effects on) with the default models.

``run`` / ``run_models`` measure, ``write`` / ``write_models`` write the
tables (Markdown and CSV) and the plot; ``scripts/accuracy_vs_time.py`` is
the command line.
"""
from __future__ import annotations

import csv
import math
import pathlib
import sys
import time

import numpy as np
from tqdm import tqdm

from billiards_env.physics import BallState, Effects, Models, PhysicsParams, Table, simulate
from billiards_env.physics.models import REGISTRIES
from billiards_env.physics.constants import EV_BALL_BALL, EV_CUSHION, EV_JAW_TIP, EV_POCKET
from billiards_env.studies import scenes

DTS = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5)
QUICK_DTS = (1e-2, 1e-3, 1e-4)
SCENE_NAMES = ("two_ball", "break", "post_break")
SCENE_SEEDS = {"two_ball": 11, "break": 12, "post_break": 13}
# each effect switched off alone, except pockets: a closed box has no
# pocketed set to compare, so its outcomes are not comparable
EFFECT_VARIANTS = {k: v for k, v in Effects.each_off().items() if k not in ("all", "no pockets", "minimal")}
# each non-default model alone (the others default), all effects on
MODEL_VARIANTS = {f"{field}: {name}": Models(**{field: name}) for field, registry in REGISTRIES.items()
                  for name in sorted(registry) if name != getattr(Models(), field)}
MODEL_REPEATS = 20  # batched runs per model row (the fastest counts)
COLLISION_KINDS = (EV_BALL_BALL, EV_CUSHION, EV_JAW_TIP, EV_POCKET)
SAME_TIME = 1e-9  # s: events closer than this count as simultaneous (order-free)


# ------------------------------------------------------------ comparisons --
def event_sequence(log) -> tuple:
    """Ball-ball/cushion/jaw/pocket events as (kind, id, id) in time order;
    events at the same instant (within SAME_TIME, e.g. the chain through a
    frozen rack) are sorted, since their order carries no physics."""
    keep = np.isin(log.kind, COLLISION_KINDS)
    t, k, ij = log.time[keep], log.kind[keep], log.balls[keep]
    out, group, t0 = [], [], None
    for tt, kk, (i, j) in zip(t, k, ij):
        if t0 is not None and tt - t0 > SAME_TIME:
            out += sorted(group)
            group = []
        if not group:
            t0 = tt
        group.append((int(kk), int(i), int(j)))
    out += sorted(group)
    return tuple(out)


def compare(ref, res, idx) -> dict:
    """Per-shot comparison of ``res`` (a SimResult on shots ``idx``) with the
    reference SimResult ``ref`` (on all shots)."""
    rp, xp = ref.state.pocket[idx] >= 0, res.state.pocket >= 0
    pocket_diff = np.any(rp != xp, axis=1)
    first_diff = ref.first_contact[idx] != res.first_contact
    both_on = ~rp & ~xp
    d = np.linalg.norm(ref.state.pos[idx] - res.state.pos, axis=2)
    d = np.where(both_on, d, -np.inf).max(axis=1)
    err = np.where(np.isfinite(d), d, np.nan) * 1e3  # mm; NaN if no ball stayed on both tables
    order = None
    if ref.events is not None and res.events is not None:
        order = np.array([event_sequence(ref.events[e]) != event_sequence(res.events[k])
                          for k, e in enumerate(idx)])
    return dict(err_mm=err, outcome=pocket_diff | first_diff, order=order,
                truncated=res.truncated | ref.truncated[idx])


def collisions_per_shot(res) -> float:
    return float(np.mean([np.isin(lg.kind, COLLISION_KINDS).sum() for lg in res.events]))


def _stat(x, q):
    x = x[np.isfinite(x)]
    return float(np.percentile(x, q)) if len(x) else float("nan")


# ---------------------------------------------------------------- timing --
def timed(state, table, params, **kw):
    t0 = time.perf_counter()
    res = simulate(state, table, params, **kw)
    return res, time.perf_counter() - t0


def batch_time(state, table, params, first=None, cheap=1.0, repeats=3, **kw) -> float:
    """Wall time of one batched ``simulate`` call: the fastest of up to
    ``repeats`` runs while a run takes < ``cheap`` s (the machine is shared,
    so noise only ever adds time); ``first`` is an already measured run."""
    ts = [] if first is None else [first]
    while len(ts) < repeats and (not ts or min(ts) < cheap):
        ts.append(timed(state, table, params, **kw)[1])
    return min(ts)


def single_times(state, table, params, k, **kw) -> float:
    """Median wall time of simulating shots 0..k-1 one table at a time."""
    ts = []
    for e in range(k):
        _, t = timed(state.take([e]), table, params, **kw)
        ts.append(t)
    return float(np.median(ts))


def perturb(state: BallState, dphi: float = 0.0, dspeed: float = 0.0) -> BallState:
    """The same shot with the cue ball's aim turned by ``dphi`` (rad) and its
    speed raised by ``dspeed`` (m/s): velocity and cue spin rotate/scale
    together, exactly as strike_velocity with phi + dphi, speed + dspeed."""
    out = state.copy()
    v = out.vel[:, 0]
    sp = np.hypot(v[:, 0], v[:, 1])
    f = (sp + dspeed) / sp
    c, s = math.cos(dphi), math.sin(dphi)
    vx, vy = v[:, 0].copy(), v[:, 1].copy()
    out.vel[:, 0, 0] = f * (c * vx - s * vy)
    out.vel[:, 0, 1] = f * (s * vx + c * vy)
    wx, wy = out.omega[:, 0, 0].copy(), out.omega[:, 0, 1].copy()
    out.omega[:, 0, 0] = f * (c * wx - s * wy)
    out.omega[:, 0, 1] = f * (s * wx + c * wy)
    out.omega[:, 0, 2] *= f
    return out


# ------------------------------------------------------------------ study --
def run(shots: int = 200, dts=DTS, seed: int = 0, single: int = 5, budget: float = 120.0,
        min_shots: int = 20) -> dict:
    """Run the study: ``shots`` seeded shots per scene (scene seeds offset by
    ``seed``), the step solver at each of ``dts`` (s), ``single`` shots timed
    one table at a time (the event solver: at least 20), each finer (scene,
    dt) cell cut to the first shots that fit ``budget`` wall seconds (at
    least ``min_shots``; 0 = no limit). Returns the rows of the three tables
    (``acc``, ``eff``, ``sens``) and the run's timings, for the writers below."""
    if shots < 1:
        raise ValueError("shots must be >= 1")
    params = PhysicsParams.standard()
    table = Table.pool(9)
    n = shots
    dts = tuple(dts)
    k_single = min(single, n)
    k_event = min(max(single, 20), n)  # the event solver is cheap: time more single shots
    t_start = time.perf_counter()

    batches = {name: scenes.build(name, table, params, n, seed=SCENE_SEEDS[name] + seed) for name in SCENE_NAMES}

    # warm-up: compile (or load from the disk cache) every variant before timing
    for name in SCENE_NAMES:
        one = batches[name].take([0])
        simulate(one, table, params, solver="event", record=True)
        simulate(one, table, params, solver="event")
        simulate(one, table, params, solver="step", dt=1e-2, record=True)
        simulate(one, table, params, solver="step", dt=1e-2)
        for eff in EFFECT_VARIANTS.values():
            simulate(one, table, params, solver="event", effects=eff)
    warm = time.perf_counter() - t_start

    n_cells = len(SCENE_NAMES) * (1 + len(dts) + len(EFFECT_VARIANTS) + 2)
    bar = tqdm(total=n_cells, desc="accuracy", unit="cell", file=sys.stderr)
    acc_rows, eff_rows, sens_rows = [], [], []
    refs = {}
    for name in SCENE_NAMES:
        st = batches[name]
        bar.set_postfix_str(f"{name} event")
        ref = simulate(st, table, params, solver="event", record=True)
        t_batch = batch_time(st, table, params, solver="event")
        t_single = single_times(st, table, params, k_event, solver="event")
        refs[name] = ref
        acc_rows.append(dict(scene=name, solver="event", dt="", shots=n, time_batched_ms=1e3 * t_batch / n,
                             time_single_ms=1e3 * t_single, events_per_shot=float(ref.n_events.mean()),
                             collisions_per_shot=collisions_per_shot(ref), err_median_mm=0.0, err_p95_mm=0.0,
                             err_max_mm=0.0, outcome_differs=0.0, order_diverges=0.0,
                             truncated=float(ref.truncated.mean()), sim_time_s=float(ref.time.mean())))
        bar.update(1)

        # step solver, coarse to fine; the cost of the next dt is predicted
        # from the last one and the shot set cut to fit --budget if needed
        cost_per_step = None  # wall seconds per simulated (table-second / dt)
        for dt in dts:
            bar.set_postfix_str(f"{name} step dt={dt:g}")
            m = n
            if cost_per_step is not None and budget > 0:
                # batched run + single-table timings (one thread, about 2x slower each)
                per_shot = cost_per_step * ref.time / dt
                total = np.cumsum(per_shot) + 2.0 * per_shot[:k_single].sum()
                m = max(int(np.searchsorted(total, budget, side="right")), min(n, min_shots))
            idx = np.arange(m)
            sub = st.take(idx)
            res, t_rec = timed(sub, table, params, solver="step", dt=dt, record=True)
            if t_rec < 5.0:  # cheap: time again without recording
                t_batch = batch_time(sub, table, params, solver="step", dt=dt)
            else:  # recording costs < 1% of a run this long
                t_batch = t_rec
            cost_per_step = t_batch / max(res.time.sum() / dt, 1.0)
            ks = min(k_single, m)
            t_single = single_times(sub, table, params, ks, solver="step", dt=dt)
            c = compare(ref, res, idx)
            acc_rows.append(dict(scene=name, solver="step", dt=dt, shots=m, time_batched_ms=1e3 * t_batch / m,
                                 time_single_ms=1e3 * t_single, events_per_shot=float(res.n_events.mean()),
                                 collisions_per_shot=collisions_per_shot(res),
                                 err_median_mm=_stat(c["err_mm"], 50), err_p95_mm=_stat(c["err_mm"], 95),
                                 err_max_mm=_stat(c["err_mm"], 100), outcome_differs=float(c["outcome"].mean()),
                                 order_diverges=float(c["order"].mean()), truncated=float(c["truncated"].mean()),
                                 sim_time_s=float(res.time.mean())))
            bar.update(1)

        # physics effects (event solver) against the all-effects reference
        idx = np.arange(n)
        t_ref = next(r for r in acc_rows if r["scene"] == name and r["solver"] == "event")
        eff_rows.append(dict(scene=name, effects="all (reference)", time_batched_ms=t_ref["time_batched_ms"],
                             time_single_ms=t_ref["time_single_ms"], speedup=1.0,
                             events_per_shot=t_ref["events_per_shot"], err_median_mm=0.0, err_p95_mm=0.0,
                             outcome_differs=0.0, order_diverges=0.0))
        for label, eff in EFFECT_VARIANTS.items():
            bar.set_postfix_str(f"{name} {label}")
            res = simulate(st, table, params, solver="event", effects=eff, record=True)
            t_batch = batch_time(st, table, params, solver="event", effects=eff)
            t_single = single_times(st, table, params, k_event, solver="event", effects=eff)
            c = compare(ref, res, idx)
            tb = 1e3 * t_batch / n
            eff_rows.append(dict(scene=name, effects=label, time_batched_ms=tb, time_single_ms=1e3 * t_single,
                                 speedup=t_ref["time_batched_ms"] / tb, events_per_shot=float(res.n_events.mean()),
                                 err_median_mm=_stat(c["err_mm"], 50), err_p95_mm=_stat(c["err_mm"], 95),
                                 outcome_differs=float(c["outcome"].mean()),
                                 order_diverges=float(c["order"].mean())))
            bar.update(1)

        # sensitivity of the event solver to tiny shot perturbations
        for label, kw in (("aim +1e-6 rad", dict(dphi=1e-6)), ("speed +1e-6 m/s", dict(dspeed=1e-6))):
            bar.set_postfix_str(f"{name} {label}")
            res = simulate(perturb(st, **kw), table, params, solver="event", record=True)
            c = compare(ref, res, idx)
            sens_rows.append(dict(scene=name, perturbation=label, shots=n, err_median_mm=_stat(c["err_mm"], 50),
                                  err_p95_mm=_stat(c["err_mm"], 95), err_max_mm=_stat(c["err_mm"], 100),
                                  frac_err_above_1mm=float(np.mean(np.nan_to_num(c["err_mm"]) > 1.0)),
                                  outcome_differs=float(c["outcome"].mean()),
                                  order_diverges=float(c["order"].mean())))
            bar.update(1)
    bar.close()
    return dict(acc=acc_rows, eff=eff_rows, sens=sens_rows, warm=warm, total=time.perf_counter() - t_start,
                shots=n, dts=dts)


def run_models(shots: int = 200, seed: int = 0, single: int = 20) -> dict:
    """Each of ``MODEL_VARIANTS`` against the default models (event solver,
    all effects) on the study's seeded shots: time per shot (batched and
    ``single`` shots one table at a time), events per shot, final position
    error and how often the outcome differs or the event order diverges
    (the columns of the effects table)."""
    if shots < 1:
        raise ValueError("shots must be >= 1")
    params, table, n = PhysicsParams.standard(), Table.pool(9), shots
    k = min(single, n)
    t_start = time.perf_counter()
    batches = {name: scenes.build(name, table, params, n, seed=SCENE_SEEDS[name] + seed) for name in SCENE_NAMES}
    variants = {"default (reference)": Models(), **MODEL_VARIANTS}
    for models in variants.values():  # compile (or load) every variant before timing
        one = batches[SCENE_NAMES[0]].take([0])
        simulate(one, table, params, solver="event", models=models, record=True)
        simulate(one, table, params, solver="event", models=models)
    warm = time.perf_counter() - t_start
    rows, idx = [], np.arange(n)
    for name in SCENE_NAMES:
        st = batches[name]
        ref = simulate(st, table, params, solver="event", record=True)
        t_ref = None
        for label, models in variants.items():
            res = simulate(st, table, params, solver="event", models=models, record=True)
            # fastest of MODEL_REPEATS: these runs take milliseconds, so a
            # busy machine's noise would otherwise decide the speed-up
            tb = 1e3 * batch_time(st, table, params, repeats=MODEL_REPEATS, solver="event", models=models) / n
            t_ref = t_ref or tb
            c = compare(ref, res, idx)
            rows.append(dict(scene=name, models=label, time_batched_ms=tb,
                             time_single_ms=1e3 * single_times(st, table, params, k, solver="event", models=models),
                             speedup=t_ref / tb, events_per_shot=float(res.n_events.mean()),
                             err_median_mm=_stat(c["err_mm"], 50), err_p95_mm=_stat(c["err_mm"], 95),
                             outcome_differs=float(c["outcome"].mean()), order_diverges=float(c["order"].mean())))
    return dict(models=rows, shots=n, warm=warm, total=time.perf_counter() - t_start)


# ---------------------------------------------------------------- output --
def write(out: dict, out_dir) -> list[pathlib.Path]:
    """Write a ``run`` result to ``out_dir``: accuracy.csv, effects.csv,
    sensitivity.csv, accuracy.png and accuracy.md (which shows the plot)."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    write_csv(out_dir / "accuracy.csv", out["acc"])
    write_csv(out_dir / "effects.csv", out["eff"])
    write_csv(out_dir / "sensitivity.csv", out["sens"])
    plot(out_dir / "accuracy.png", out)
    write_markdown(out_dir / "accuracy.md", out, "accuracy.png")
    return [out_dir / f for f in ("accuracy.md", "accuracy.csv", "effects.csv", "sensitivity.csv", "accuracy.png")]


def write_models(out: dict, out_dir) -> list[pathlib.Path]:
    """Write a ``run_models`` result to ``out_dir``: models.csv and models.md."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    write_csv(out_dir / "models.csv", out["models"])
    L = ["# Model choices against the default models", "",
         f"{out['shots']} seeded shots per scene (the shots of accuracy.md), event solver, standard physics, all "
         "effects on. Reference: the default models (`Models()`: constant ball-ball friction, han2005 cushion); "
         "each row changes one model. Columns as in the physics-effects table of accuracy.md: speed-up = "
         f"reference time / row time (batched, fastest of {MODEL_REPEATS} runs); *outcome differs*: set of pocketed balls or the cue ball's first "
         "contact differs from the reference's.", "",
         "| scene | models | time/shot batched (ms) | time/shot single (ms) | speed-up | events/shot | "
         "pos. error median (mm) | pos. error p95 (mm) | outcome differs | order diverges |",
         "|---|---|---|---|---|---|---|---|---|---|"]
    for r in out["models"]:
        L.append(f"| {r['scene']} | {r['models']} | {_f(r['time_batched_ms'])} | {_f(r['time_single_ms'])} | "
                 f"{r['speedup']:.2f}x | {_f(r['events_per_shot'])} | {_f(r['err_median_mm'])} | "
                 f"{_f(r['err_p95_mm'])} | {_pct(r['outcome_differs'])} | {_pct(r['order_diverges'])} |")
    L += ["", f"Run time: {out['total']:.0f} s including {out['warm']:.0f} s warm-up (compile or cache load).", ""]
    (out_dir / "models.md").write_text("\n".join(L))
    return [out_dir / "models.csv", out_dir / "models.md"]


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def _f(x, nd=3):
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    if x == 0:
        return "0"
    return f"{x:.{nd}g}"


def _pct(x):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{100 * x:.1f}%"


def verdict(acc) -> list[str]:
    """Per scene: the cheapest step dt whose outcomes match the reference on
    >= 99% of shots, against the event solver's time."""
    lines = []
    for name in SCENE_NAMES:
        ev = next(r for r in acc if r["scene"] == name and r["solver"] == "event")
        ok = [r for r in acc if r["scene"] == name and r["solver"] == "step" and r["outcome_differs"] <= 0.01]
        if not ok:
            best = min((r for r in acc if r["scene"] == name and r["solver"] == "step"),
                       key=lambda r: r["outcome_differs"])
            lines.append(f"- **{name}**: no step dt matches the event solver's outcomes on >= 99% of shots "
                         f"(best: dt = {best['dt']:g} s, {_pct(best['outcome_differs'])} differ, "
                         f"{_f(best['time_batched_ms'])} ms/shot vs event {_f(ev['time_batched_ms'])} ms/shot).")
            continue
        cheapest = min(ok, key=lambda r: r["time_batched_ms"])
        ratio = cheapest["time_batched_ms"] / ev["time_batched_ms"]
        lines.append(f"- **{name}**: cheapest step dt with >= 99% matching outcomes: dt = {cheapest['dt']:g} s, "
                     f"{_f(cheapest['time_batched_ms'])} ms/shot batched = {ratio:.3g}x the event solver's "
                     f"{_f(ev['time_batched_ms'])} ms/shot; event solver "
                     f"{'faster' if ratio > 1 else 'SLOWER'}.")
    return lines


def write_markdown(path, out, png_name):
    acc, eff, sens = out["acc"], out["eff"], out["sens"]
    L = [f"# Accuracy vs time per shot", "",
         f"{out['shots']} seeded shots per scene on a 9 ft pool table (standard physics, all effects). "
         "Reference: the event solver. Time per shot: *batched* = wall time of one `simulate` call on the "
         "whole batch (fastest of 3 when under 1 s) / shots (numba-parallel over tables, 2 cores); *single* = median wall time of "
         "`simulate` on one table. Position error: per shot the largest distance between a ball's final "
         "position and the reference's, over balls on the table in both; median and 95th percentile over "
         "shots. *Outcome differs*: set of pocketed balls or the cue ball's first contact differs. "
         "*Order diverges*: the sequence of ball-ball/cushion/jaw/pocket events with their ids differs "
         "(events at the same instant compared as a set). Events/shot: the event solver counts motion "
         "transitions too; *collisions/shot* counts only kinds 1-4 for both solvers.", "",
         f"![error vs time per shot]({png_name})", "",
         "## Solvers", "",
         "| scene | solver | dt (s) | shots | time/shot batched (ms) | time/shot single (ms) | events/shot | "
         "collisions/shot | pos. error median (mm) | pos. error p95 (mm) | outcome differs | order diverges | truncated |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in acc:
        L.append(f"| {r['scene']} | {r['solver']} | {_f(r['dt']) if r['dt'] != '' else '-'} | {r['shots']} | "
                 f"{_f(r['time_batched_ms'])} | {_f(r['time_single_ms'])} | {_f(r['events_per_shot'])} | "
                 f"{_f(r['collisions_per_shot'])} | {_f(r['err_median_mm'])} | {_f(r['err_p95_mm'])} | "
                 f"{_pct(r['outcome_differs'])} | {_pct(r['order_diverges'])} | {_pct(r['truncated'])} |")
    L += ["", "Target: the event solver is both the most accurate and faster than any step dt that matches its "
          "outcomes on >= 99% of shots.", ""] + verdict(acc)
    L += ["", "## Physics effects (event solver, vs all effects on)", "",
          "| scene | effects | time/shot batched (ms) | time/shot single (ms) | speed-up | events/shot | "
          "pos. error median (mm) | pos. error p95 (mm) | outcome differs | order diverges |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in eff:
        L.append(f"| {r['scene']} | {r['effects']} | {_f(r['time_batched_ms'])} | {_f(r['time_single_ms'])} | "
                 f"{r['speedup']:.2f}x | {_f(r['events_per_shot'])} | {_f(r['err_median_mm'])} | "
                 f"{_f(r['err_p95_mm'])} | {_pct(r['outcome_differs'])} | {_pct(r['order_diverges'])} |")
    L += ["", "## Sensitivity (event solver, shot perturbed by 1e-6)", "",
          "The error floor any solver is read against: how far the exact solution itself moves when the "
          "shot changes by far less than any player or policy controls.", "",
          "| scene | perturbation | shots | pos. error median (mm) | pos. error p95 (mm) | pos. error max (mm) | "
          "shots with error > 1 mm | outcome differs | order diverges |",
          "|---|---|---|---|---|---|---|---|---|"]
    for r in sens:
        L.append(f"| {r['scene']} | {r['perturbation']} | {r['shots']} | {_f(r['err_median_mm'])} | "
                 f"{_f(r['err_p95_mm'])} | {_f(r['err_max_mm'])} | {_pct(r['frac_err_above_1mm'])} | "
                 f"{_pct(r['outcome_differs'])} | {_pct(r['order_diverges'])} |")
    L += ["", f"Run time: {out['total']:.0f} s including {out['warm']:.0f} s warm-up (compile or cache load).", ""]
    pathlib.Path(path).write_text("\n".join(L))


def plot(path, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    acc, sens = out["acc"], out["sens"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    colors = dict(zip(SCENE_NAMES, ("tab:blue", "tab:orange", "tab:green")))
    for name in SCENE_NAMES:
        rows = [r for r in acc if r["scene"] == name and r["solver"] == "step"]
        ev = next(r for r in acc if r["scene"] == name and r["solver"] == "event")
        t = np.array([r["time_batched_ms"] for r in rows])
        err = np.array([r["err_median_mm"] for r in rows])
        out_d = np.array([r["outcome_differs"] for r in rows])
        col = colors[name]
        ax1.plot(t, err, "o-", color=col, label=f"{name}: step")
        for r, x, y in zip(rows, t, err):
            ax1.annotate(f"{r['dt']:g}", (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7, color=col)
        floor = [r["err_median_mm"] for r in sens if r["scene"] == name and r["perturbation"].startswith("aim")][0]
        fl = floor if floor > 0 else np.nan
        ax1.plot([ev["time_batched_ms"]], [fl if np.isfinite(fl) else np.nanmin(err) / 10], "*", ms=16,
                 color=col, markeredgecolor="k", label=f"{name}: event (y = its sensitivity)")
        if np.isfinite(fl):
            ax1.axhline(fl, color=col, ls=":", lw=1)
        ax2.plot(t, 100 * np.maximum(out_d, 1e-4) , "o-", color=col, label=f"{name}: step")
        s_out = [r["outcome_differs"] for r in sens if r["scene"] == name and r["perturbation"].startswith("aim")][0]
        ax2.plot([ev["time_batched_ms"]], [100 * max(s_out, 1e-4)], "*", ms=16, color=col, markeredgecolor="k",
                 label=f"{name}: event (1e-6 rad aim change)")
    ax1.set(xscale="log", yscale="log", xlabel="wall time per shot, batched (ms)",
            ylabel="final position error, median (mm)",
            title="Step solver vs event solver (labels: dt in s)")
    ax2.set(xscale="log", yscale="log", xlabel="wall time per shot, batched (ms)",
            ylabel="shots with a different outcome (%)", title="Outcome changes (0 drawn at 0.01%)")
    ax1.grid(True, which="both", alpha=0.3); ax2.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=7); ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)

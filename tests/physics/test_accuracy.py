"""Accuracy study: the step solver converges as dt shrinks, the event solver
matches closed-form answers, and the study (library and script) runs."""
import csv
import dataclasses
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from billiards_env.physics import BallState, PhysicsParams, Table, simulate, strike_velocity
from billiards_env.physics import constants as C
from billiards_env.studies import accuracy, scenes

ROOT = pathlib.Path(__file__).resolve().parents[2]
P = PhysicsParams.standard()
BIG = Table.pocketless(20.0, 20.0)
REL = 1e-9


def _one_ball(x=2.0, y=2.0):
    return BallState.from_positions([[[x, y]]])


def _event(log, kind, ball=0):
    """Time and state of ball ``ball``'s first event of ``kind``; nothing but
    motion transitions may come before it."""
    k = np.nonzero((log.kind == kind) & (log.balls[:, 0] == ball))[0]
    assert len(k) >= 1, f"no {C.EVENT_NAMES[kind]} event of ball {ball}"
    assert np.all(np.isin(log.kind[:k[0]], (C.EV_START, C.EV_SLIDE_ROLL, C.EV_ROLL_STOP, C.EV_SPIN_STOP)))
    return log.time[k[0]], log.states[k[0], 0]


def test_step_error_shrinks_with_dt():
    box = Table.pocketless(1.27, 2.54)  # no pockets: no outcome discontinuities
    shots = scenes.two_ball(box, P, 8, seed=5)
    ref = simulate(shots, box, P, solver="event")
    med = []
    for dt in (1e-2, 1e-3, 1e-4):
        res = simulate(shots, box, P, solver="step", dt=dt)
        err = np.linalg.norm(res.state.pos - ref.state.pos, axis=2).max(axis=1)
        med.append(np.median(err))
    assert med[0] > med[1] > med[2], med
    assert med[2] < 1e-3  # under a millimetre at dt = 1e-4


@pytest.mark.parametrize("v0,phi", [(1.0, 0.0), (2.5, 0.7), (4.0, 2.0)])
def test_stun_ball_slides_then_rolls(v0, phi):
    s = strike_velocity(_one_ball(10.0, 10.0), phi, v0, 0.0, 0.0, P)
    res = simulate(s, BIG, P, solver="event", record=True)
    t, st = _event(res.events[0], C.EV_SLIDE_ROLL)
    mg = P.mu_s * P.g
    assert t == pytest.approx(2 * v0 / (7 * mg), rel=REL, abs=0)
    d = np.hypot(st[0] - 10.0, st[1] - 10.0)
    assert d == pytest.approx(12 * v0 ** 2 / (49 * mg), rel=REL, abs=0)
    assert np.hypot(st[2], st[3]) == pytest.approx(5 / 7 * v0, rel=REL, abs=0)
    assert math.atan2(st[1] - 10.0, st[0] - 10.0) == pytest.approx(phi, abs=1e-12)
    assert st[7] == C.ROLLING


@pytest.mark.parametrize("v", [0.3, 1.5])
def test_rolling_ball_roll_out(v):
    s = _one_ball(3.0, 3.0)
    s.vel[0, 0] = (v, 0.0)
    s.omega[0, 0] = (0.0, v / P.R, 0.0)  # rolling: contact point at rest
    res = simulate(s, BIG, P, solver="event", record=True)
    t, st = _event(res.events[0], C.EV_ROLL_STOP)
    assert t == pytest.approx(v / (P.mu_r * P.g), rel=REL, abs=0)
    assert res.state.pos[0, 0, 0] - 3.0 == pytest.approx(v ** 2 / (2 * P.mu_r * P.g), rel=REL, abs=0)
    assert res.state.pos[0, 0, 1] == 3.0
    assert not np.any(res.events[0].kind == C.EV_SLIDE_ROLL)


@pytest.mark.parametrize("wz", [30.0, -7.5])
def test_spin_decay_time(wz):
    s = _one_ball()
    s.omega[0, 0, 2] = wz
    res = simulate(s, BIG, P, solver="event", record=True)
    t, st = _event(res.events[0], C.EV_SPIN_STOP)
    assert t == pytest.approx(abs(wz) / (5 * P.mu_sp * P.g / (2 * P.R)), rel=REL, abs=0)
    assert np.array_equal(res.state.pos[0, 0], [2.0, 2.0])
    assert res.time[0] == t


@pytest.mark.parametrize("mu_b", [0.0, 0.06, 0.3])
def test_stun_head_on_leaves_cue_at_restitution_fraction(mu_b):
    params = dataclasses.replace(P, mu_b=mu_b)
    v0, D = 3.0, 0.5  # object ball centre 2R + D ahead: still sliding at impact
    s = BallState.from_positions([[[5.0, 5.0], [5.0 + 2 * params.R + D, 5.0]]])
    s = strike_velocity(s, 0.0, v0, 0.0, 0.0, params)
    assert D < 12 * v0 ** 2 / (49 * params.mu_s * params.g)
    res = simulate(s, BIG, params, solver="event", record=True)
    log = res.events[0]
    k = np.nonzero(log.kind == C.EV_BALL_BALL)[0][0]
    v_impact = math.sqrt(v0 ** 2 - 2 * params.mu_s * params.g * D)  # sliding decelerates at mu_s g
    cue, obj = log.states[k]
    assert tuple(log.balls[k]) == (0, 1)
    assert cue[2] == pytest.approx((1 - params.e_b) / 2 * v_impact, rel=REL, abs=0)
    assert obj[2] == pytest.approx((1 + params.e_b) / 2 * v_impact, rel=REL, abs=0)
    assert abs(cue[3]) < 1e-12 and abs(obj[3]) < 1e-12


def test_event_sequence_ignores_order_within_an_instant():
    class Log:
        def __init__(self, t, k, b):
            self.time, self.kind, self.balls = np.array(t), np.array(k), np.array(b)

    a = Log([0, 0.1, 0.1, 0.3, 0.5], [0, 1, 1, 5, 2], [[0, -1], [1, 3], [1, 7], [2, -1], [3, 1]])
    b = Log([0, 0.1, 0.1, 0.5], [0, 1, 1, 2], [[0, -1], [1, 7], [1, 3], [3, 1]])
    c = Log([0, 0.1, 0.2, 0.5], [0, 1, 1, 2], [[0, -1], [1, 7], [1, 3], [3, 1]])
    assert accuracy.event_sequence(a) == accuracy.event_sequence(b)
    assert accuracy.event_sequence(a) != accuracy.event_sequence(c)


def test_quick_study_writes_table_and_plot(tmp_path):
    out = tmp_path / "acc"
    r = subprocess.run([sys.executable, str(ROOT / "scripts" / "accuracy_vs_time.py"), "--quick", "--out", str(out)],
                       cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    for f in ("accuracy.md", "accuracy.csv", "effects.csv", "sensitivity.csv", "accuracy.png"):
        assert (out / f).stat().st_size > 0, f
    assert (out / "accuracy.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = list(csv.DictReader(open(out / "accuracy.csv")))
    assert len(rows) == 3 * (1 + 3)  # 3 scenes x (event + 3 step dts)
    assert {r["scene"] for r in rows} == {"two_ball", "break", "post_break"}
    for r in rows:
        assert float(r["time_batched_ms"]) > 0 and float(r["time_single_ms"]) > 0
        if r["solver"] == "event":
            assert float(r["err_median_mm"]) == 0
    eff = list(csv.DictReader(open(out / "effects.csv")))
    assert len(eff) == 3 * 6
    sens = list(csv.DictReader(open(out / "sensitivity.csv")))
    assert len(sens) == 3 * 2
    md = (out / "accuracy.md").read_text()
    for part in ("## Solvers", "## Physics effects", "## Sensitivity", "accuracy.png", "| break | step | 0.001 |"):
        assert part in md

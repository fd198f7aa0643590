"""Simulator checks against closed-form answers and conservation laws
(the slide/roll/spin closed forms and the step solver's convergence are in
test_accuracy.py). Closed forms follow Alciatore's technical proofs (slide and roll,
the 90-degree rule, throw)."""
import dataclasses
import math

import numpy as np
import pytest

from billiards_env.physics import (BallState, Effects, PhysicsParams, Table, rack, random_placement,
                                   set_num_threads, simulate, strike, strike_velocity)
from billiards_env.physics import constants as C

REL = 1e-9


def _ball_ball_event(log):
    k = list(log.kind).index(C.EV_BALL_BALL)
    return k, log.states[k]


def test_strike_follows_hookes_law_and_torque(params):
    s = BallState.from_positions([[0.6, 0.6]])
    out = strike(s, phi=0.3, draw=0.2, a=0.1, b=0.4, params=params)
    v = params.k * params.contact_time * 0.2 / params.m
    np.testing.assert_allclose(out.vel[0, 0], v * np.array([math.cos(0.3), math.sin(0.3)]), rtol=1e-14)
    # b = 2/5 gives natural roll: the contact point with the felt does not slip
    ux = out.vel[0, 0, 0] - params.R * out.omega[0, 0, 1]
    uy = out.vel[0, 0, 1] + params.R * out.omega[0, 0, 0]
    assert abs(ux) < 1e-12 and abs(uy) < 1e-12
    # side offset a gives spin about z of 5 v a / (2R)
    assert out.omega[0, 0, 2] == pytest.approx(2.5 * v * 0.1 / params.R, rel=1e-14)
    assert np.all(s.vel == 0)  # input untouched


def test_max_draw_gives_a_hard_break(params):
    assert 9.5 < params.max_speed < 10.5
    seed = PhysicsParams.seed()
    assert 0.01 < seed.max_speed < 0.1  # the original parameter set: a few cm/s


def test_miscue_raises(params):
    s = BallState.from_positions([[0.6, 0.6]])
    with pytest.raises(ValueError, match="miscue"):
        strike(s, 0.0, 0.1, a=0.4, b=0.4, params=params)


def test_stun_cut_shot_splits_at_90_degrees(big_box):
    """e_b = 1, no ball-ball friction, stun cue ball (no spin at impact):
    the two balls leave at right angles (the 90-degree rule, Alciatore)."""
    p = dataclasses.replace(PhysicsParams.standard(), e_b=1.0, mu_b=0.0, mu_s=0.0)
    R = p.R
    cut = math.radians(30)
    obj = np.array([10.0, 10.0])
    cue = obj - 2 * R * np.array([math.sin(cut), math.cos(cut)]) - [0, 0.5]
    # aim the cue ball so it reaches the contact position with the given cut
    contact = obj - 2 * R * np.array([math.sin(cut), math.cos(cut)])
    phi = math.atan2(*(contact - cue)[::-1])
    s = strike_velocity(BallState.from_positions([cue, obj]), phi, 2.0, 0.0, 0.0, p)
    r = simulate(s, big_box, p, record=True)
    k, st = _ball_ball_event(r.events[0])
    v_cue, v_obj = st[0, 2:4], st[1, 2:4]
    cosang = v_cue @ v_obj / np.linalg.norm(v_cue) / np.linalg.norm(v_obj)
    assert abs(cosang) < 1e-12
    # energy and momentum of the frictionless elastic impact are conserved
    assert np.linalg.norm(v_cue) ** 2 + np.linalg.norm(v_obj) ** 2 == pytest.approx(4.0, rel=1e-12)
    np.testing.assert_allclose(v_cue + v_obj, 2.0 * np.array([math.cos(phi), math.sin(phi)]), atol=1e-12)


@pytest.mark.parametrize("solver,dt", [("event", None), ("step", 1e-3)])
def test_impacts_conserve_momentum_and_never_add_energy(pool, params, solver, dt):
    s = random_placement(pool, params, 6, 64, seed=3)
    rng = np.random.default_rng(4)
    s = strike_velocity(s, rng.uniform(0, 2 * np.pi, 64), rng.uniform(0.5, 8, 64),
                        rng.uniform(-0.3, 0.3, 64), rng.uniform(-0.3, 0.3, 64), params)
    r = simulate(s, pool, params, solver=solver, dt=dt, diagnostics=True)
    energy_gain, momentum_err, min_gap, off_table = r.diagnostics.T
    assert np.all(energy_gain <= 1e-12)
    assert np.all(momentum_err <= 1e-12)
    assert np.all(min_gap >= -1e-9)
    assert np.all(off_table == 0)
    assert not r.truncated.any()
    assert np.all(np.isfinite(r.state.pos))


def test_results_do_not_depend_on_batch_size_or_threads(pool, params):
    s = rack(pool, params, "nine", 8, seed=11)
    rng = np.random.default_rng(12)
    s = strike_velocity(s, np.pi / 2 + rng.normal(0, 0.02, 8), rng.uniform(3, 9, 8),
                        rng.uniform(-0.3, 0.3, 8), rng.uniform(-0.3, 0.3, 8), params)
    for solver, dt in (("event", None), ("step", 1e-3)):
        set_num_threads(2)
        whole = simulate(s, pool, params, solver=solver, dt=dt)
        set_num_threads(1)
        single = [simulate(s.take([e]), pool, params, solver=solver, dt=dt) for e in range(8)]
        set_num_threads(2)
        for e in range(8):
            assert np.array_equal(whole.state.pos[e], single[e].state.pos[0])
            assert np.array_equal(whole.state.pocket[e], single[e].state.pocket[0])
            assert whole.n_events[e] == single[e].n_events[0]


def test_pocketed_ball_leaves_play(pool, params):
    # a ball rolled straight into the bottom-left corner pocket along the diagonal
    s = BallState.from_positions([[0.4, 0.4]])
    s = strike_velocity(s, -3 * math.pi / 4, 2.0, 0.0, 0.4, params)
    r = simulate(s, pool, params, record=True)
    assert r.state.pocket[0, 0] == 0
    assert r.events[0].kind[-1] == C.EV_POCKET


def test_event_log_reconstructs_the_final_state(pool, params):
    s = rack(pool, params, "nine", 1, seed=5)
    s = strike_velocity(s, math.pi / 2, 6.0, 0.1, -0.2, params)
    r = simulate(s, pool, params, record=True)
    log = r.events[0]
    last = {}
    for k in range(len(log)):
        for slot in range(2 if log.kind[k] == C.EV_BALL_BALL else 1):
            last[int(log.balls[k, slot])] = log.states[k, slot]
    for i, st in last.items():
        if r.state.pocket[0, i] < 0:
            np.testing.assert_allclose(st[:2], r.state.pos[0, i], atol=1e-12)


@pytest.mark.parametrize("solver,dt", [("event", None), ("step", 1e-4)])
def test_cushion_hits_after_contact_count_only_after_the_first_contact(pool, params, solver, dt):
    """A cue ball sent into the side rail before it reaches the object ball
    hits a cushion that does not count as after contact; the object ball's
    cushion hits all do (it is at rest until it is touched)."""
    pos = np.array([[[0.40, 1.00], [0.90, 1.60]],    # rail first: cue ball goes left, never meets ball 1
                    [[0.635, 1.00], [0.635, 1.40]]])  # contact first: straight at ball 1, which runs to the foot rail
    s = strike_velocity(BallState.from_positions(pos), np.array([math.pi, math.pi / 2]), 1.5, 0.0, 0.0, params)
    res = simulate(s, pool, params, solver=solver, dt=dt)
    assert res.first_contact.tolist() == [-1, 1]
    assert res.cushion_hits[0, 0] >= 1 and res.cushion_hits_after_contact[0].sum() == 0
    assert res.cushion_hits[1, 1] >= 1
    np.testing.assert_array_equal(res.cushion_hits_after_contact[1, 1:], res.cushion_hits[1, 1:])
    assert np.all(res.cushion_hits_after_contact <= res.cushion_hits)

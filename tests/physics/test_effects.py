"""Effects switch physics on and off: each changes outcomes where
it matters and not where it cannot, and every combination compiles its own
kernel."""
import dataclasses
import math

import numpy as np
import pytest

from billiards_env.physics import BallState, Effects, Models, Table, random_placement, simulate, strike_velocity
from billiards_env.physics.effects import OPT_IN
from billiards_env.physics.kernels import make_kernel

ALL = Effects()


def _off(name):
    return dataclasses.replace(ALL, **{name: False})


def _final(state, table, params, effects, solver="event"):
    return simulate(state, table, params, solver=solver, dt=1e-3 if solver == "step" else None, effects=effects)


def _rail_shot(params, side):
    """A ball sent at 30 degrees into the bottom rail of a closed box."""
    s = BallState.from_positions([[0.6, 0.5]])
    return strike_velocity(s, -math.radians(60), 2.0, side, 0.0, params)


def test_side_spin_changes_the_rebound_only_with_cushion_friction(params):
    box = Table.pocketless(1.27, 2.54)
    plain, english = _rail_shot(params, 0.0), _rail_shot(params, 0.4)
    with_friction = [_final(s, box, params, ALL).state.pos[0, 0] for s in (plain, english)]
    assert np.linalg.norm(with_friction[0] - with_friction[1]) > 0.02
    nofric = _off("cushion_friction")
    without = [_final(s, box, params, nofric).state.pos[0, 0] for s in (plain, english)]
    # without cushion friction, side spin cannot act on the rail: same path
    np.testing.assert_allclose(without[0], without[1], atol=1e-12)


def test_vertical_spin_matters_only_with_side_spin(params):
    box = Table.pocketless(1.27, 2.54)
    english = _rail_shot(params, 0.4)
    a = _final(english, box, params, ALL).state.pos
    b = _final(english, box, params, _off("vertical_spin")).state.pos
    assert np.linalg.norm(a - b) > 0.02
    # no side spin and a frictionless rail: vertical spin cannot arise
    plain = _rail_shot(params, 0.0)
    nofric = _off("cushion_friction")
    a = _final(plain, box, params, nofric).state.pos
    b = _final(plain, box, params, dataclasses.replace(nofric, vertical_spin=False)).state.pos
    np.testing.assert_allclose(a, b, atol=1e-12)


def _cut_shot(params, b=0.0):
    box = Table.pocketless(3.0, 3.0)
    s = BallState.from_positions([[1.5, 1.0], [1.5 + 1.2 * params.R, 1.6]])
    return box, strike_velocity(s, math.pi / 2, 1.5, 0.0, b, params)


def test_ball_friction_throws_a_cut_shot_and_not_a_full_hit(params):
    box, cut = _cut_shot(params)
    a = _final(cut, box, params, ALL).state.pos[0, 1]
    b = _final(cut, box, params, _off("ball_friction")).state.pos[0, 1]
    assert np.linalg.norm(a - b) > 0.01  # throw moves the object ball's path
    s = BallState.from_positions([[1.5, 1.0], [1.5, 1.6]])
    # full stun hit: no slip at the contact, so friction has nothing to act on
    s = strike_velocity(s, math.pi / 2, 1.5, 0.0, 0.0, params)
    a = simulate(s, box, params, effects=ALL, record=True).events[0]
    b = simulate(s, box, params, effects=_off("ball_friction"), record=True).events[0]
    ka, kb = list(a.kind).index(1), list(b.kind).index(1)
    np.testing.assert_allclose(a.states[ka, 1, 2:4], b.states[kb, 1, 2:4], atol=1e-12)


def test_sliding_and_spin_change_a_draw_shot(params):
    box, _ = _cut_shot(params)
    s = BallState.from_positions([[1.5, 1.0], [1.5, 1.35]])
    draw = strike_velocity(s, math.pi / 2, 3.0, 0.0, -0.5, params)
    full = _final(draw, box, params, ALL).state.pos[0, 0]
    assert full[1] < 1.35 - 2 * params.R - 0.1  # the cue ball draws back
    for name in ("sliding", "spin"):
        other = _final(draw, box, params, _off(name)).state.pos[0, 0]
        assert np.linalg.norm(full - other) > 0.05, name


def test_rolling_ball_is_the_same_with_spin_on_and_off(params):
    """A ball that rolls to rest without touching anything carries only
    rolling spin: the point-mass model gives the same path."""
    box = Table.pocketless(3.0, 3.0)
    s = BallState.from_positions([[1.5, 0.5]])
    s = strike_velocity(s, 1.1, 0.5, 0.0, 0.4, params)  # natural roll from the start
    a = _final(s, box, params, ALL)
    b = _final(s, box, params, Effects.minimal())
    np.testing.assert_allclose(a.state.pos, b.state.pos, rtol=0, atol=1e-12)
    assert a.time[0] == pytest.approx(b.time[0], rel=1e-12)


@pytest.mark.parametrize("solver", ["event", "step"])
def test_pockets_off_makes_a_closed_box(pool, params, solver):
    s = random_placement(pool, params, 8, 32, seed=21)
    rng = np.random.default_rng(22)
    s = strike_velocity(s, rng.uniform(0, 2 * np.pi, 32), rng.uniform(4, 10, 32), 0.0, 0.0, params)
    on = _final(s, pool, params, ALL, solver)
    off = _final(s, pool, params, _off("pockets"), solver)
    assert on.pocketed.any()
    assert not off.pocketed.any()
    R = params.R
    x, y = off.state.pos[..., 0], off.state.pos[..., 1]
    assert np.all((x >= R - 1e-9) & (x <= pool.width - R + 1e-9) & (y >= R - 1e-9) & (y <= pool.length - R + 1e-9))


def test_pockets_do_not_matter_far_from_them(params, pool):
    s = BallState.from_positions([[0.6, 1.0], [0.62, 1.4]])
    s = strike_velocity(s, math.pi / 2, 0.8, 0.1, 0.1, params)
    a = _final(s, pool, params, ALL).state.pos
    b = _final(s, pool, params, _off("pockets")).state.pos
    np.testing.assert_allclose(a, b, atol=0)


def test_each_effect_set_compiles_its_own_kernel():
    k1 = make_kernel("event", Effects(), Models())
    k2 = make_kernel("event", Effects.minimal(), Models())
    assert k1 is not k2
    assert make_kernel("event", Effects(), Models()) is k1  # memoised
    # equivalent settings share one kernel
    assert Effects(spin=False).key() == Effects(spin=False, ball_friction=False).key()


def test_each_off_lists_every_effect_once():
    sets = Effects.each_off()
    assert sets["all"] == Effects.all() and sets["minimal"] == Effects.minimal()
    singles = {k: v for k, v in sets.items() if k not in ("all", "minimal")}
    default_on = [f.name for f in dataclasses.fields(Effects) if f.name not in OPT_IN]  # opt-in: off by default
    assert len(singles) == len(default_on)
    for eff in singles.values():
        assert sum(not getattr(eff, name) for name in default_on) == 1
        assert not any(getattr(eff, name) for name in OPT_IN)
    assert len({v.key() for v in sets.values()}) == len(sets)  # distinct kernels


def test_unknown_effect_is_rejected():
    with pytest.raises(ValueError, match="unknown effects"):
        Effects.from_dict({"spinn": False})

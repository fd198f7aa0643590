"""Bad inputs fail loudly with an error naming the problem, and never modify
the caller's arrays."""
import dataclasses
import math

import numpy as np
import pytest

from billiards_env.physics import BallState, PhysicsParams, SimOptions, Table, simulate, strike, strike_velocity

P = PhysicsParams.standard()
R = P.R
T = Table.pool(9)


def good():
    return strike_velocity(BallState.from_positions(np.array([(0.5, 0.5), (0.5, 1.0)])), 1.0, 1.0, params=P)


def unchanged(s, fn, exc, match):
    copies = [a.copy() for a in (s.pos, s.vel, s.omega, s.pocket)]
    with pytest.raises(exc, match=match):
        fn(s)
    for a, c in zip((s.pos, s.vel, s.omega, s.pocket), copies):
        np.testing.assert_array_equal(a, c)


def test_overlapping_balls():
    s = good(); s.pos[0, 1] = s.pos[0, 0] + (2 * R - 1e-6, 0)
    unchanged(s, lambda s: simulate(s, T, P), ValueError, "overlap")


def test_off_table_ball():
    s = good(); s.pos[0, 1] = (-0.2, 1.0)
    unchanged(s, lambda s: simulate(s, T, P), ValueError, "off the table")


@pytest.mark.parametrize("field", ["pos", "vel", "omega"])
@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_nan_inf(field, bad):
    s = good(); getattr(s, field)[0, 0, 0] = bad
    unchanged(s, lambda s: simulate(s, T, P), ValueError, f"{field} contains NaN or infinite")


def test_miscue():
    s = good()
    unchanged(s, lambda s: strike(s, 0.0, 0.1, 0.45, 0.3, P), ValueError, "miscue")


def test_negative_draw():
    s = good()
    unchanged(s, lambda s: strike(s, 0.0, -0.1, 0, 0, P), ValueError, "draw must be >= 0")


def test_unknown_solver():
    unchanged(good(), lambda s: simulate(s, T, P, solver="rk4"), ValueError, "unknown solver")


@pytest.mark.parametrize("dt", [None, 0.0, -1e-3, math.nan])
def test_step_dt(dt):
    unchanged(good(), lambda s: simulate(s, T, P, solver="step", dt=dt), ValueError, "dt|time step")


def test_wrong_shape_and_dtype():
    s = good()
    bad = BallState(s.pos[:, :, :1].copy(), s.vel, s.omega, s.pocket)
    unchanged(bad, lambda s: simulate(s, T, P), ValueError, "pos must have shape")
    bad = BallState(s.pos.astype(np.float32), s.vel, s.omega, s.pocket)
    unchanged(bad, lambda s: simulate(s, T, P), TypeError, "float64")
    bad = BallState(s.pos, s.vel, s.omega, s.pocket.astype(np.float64))
    unchanged(bad, lambda s: simulate(s, T, P), TypeError, "pocket must be an integer")


@pytest.mark.parametrize("options,exc,match", [
    ((100, True), TypeError, "options must be a SimOptions"),
    (SimOptions(max_events=-1), ValueError, "max_events must be a non-negative integer"),
    (SimOptions(max_events=2.5), ValueError, "max_events must be a non-negative integer"),
    (SimOptions(max_events=True), ValueError, "max_events must be a non-negative integer"),
    (SimOptions(validate="no"), TypeError, "validate must be True or False")])
def test_bad_options(options, exc, match):
    unchanged(good(), lambda s: simulate(s, T, P, options=options), exc, match)


def test_options_cap_events_and_skip_validation():
    """``SimOptions.max_events`` cuts a table off at that many events
    (truncated); ``validate=False`` skips the input checks (an off-table
    ball that ``simulate`` would refuse)."""
    s = good()
    full = simulate(s, T, P)
    assert full.n_events[0] > 2 and not full.truncated[0]
    cut = simulate(s, T, P, options=SimOptions(max_events=2))
    assert cut.n_events[0] == 2 and cut.truncated[0]
    s.pos[0, 1] = (-0.2, 1.0)
    simulate(s, T, P, options=SimOptions(validate=False))
    with pytest.raises(ValueError, match="off the table"):
        simulate(s, T, P)


@pytest.mark.parametrize("field,value,match", [("mu_s", -0.1, "mu_s"), ("mu_b", -1.0, "mu_b"),
                                               ("e_b", 1.01, "e_b"), ("e_c", 1.5, "e_c")])
def test_bad_params(field, value, match):
    with pytest.raises(ValueError, match=match):
        dataclasses.replace(P, **{field: value})

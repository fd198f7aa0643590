"""Convergence of the Mathavan et al. (2010) cushion integration
(physics/cushion/mathavan2010.py) against an independent integration of the
same equations: tests/physics/mathavan_midpoint.py (the previous midpoint
scheme with its own stick landing) at 64 times its 200 impulse steps, in
units of the impact's speed scale V = |v| + R |w|. The figures each
assertion guards are the module docstring's (measured on 300 impacts with
the code in this file: ``errors(300, seed=2)``)."""
import math

import numpy as np

import mathavan_midpoint
from billiards_env.physics import PhysicsParams
from billiards_env.physics import constants as C
from billiards_env.physics.cushion import mathavan2010

P = PhysicsParams.standard()
PV = P.as_array()
R = P.R
N = mathavan_midpoint.IMPULSE_STEPS
TOL = mathavan2010.STEP_TOL
# The reference itself: 64 x against 128 x the steps agree within this (V).
REF_TOL = 1e-6
# The targets (the Dormand-Prince rework): every impact within 1e-5 V of the reference, and
# half the step (32 x tighter a tolerance for a fifth-order pair) changing
# it by less than 1e-6 V.
TARGET, HALF = 1e-5, 1e-6


def impacts(n, seed):
    """Random impacts on the cushion with normal (0, 1): speeds 0.05 - 12
    m/s at angles up to 89 degrees from the normal, spins to 400 rad/s."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        V = rng.uniform(0.05, 12.0)
        a = rng.uniform(-1.55, 1.55)
        yield (V * math.sin(a), -V * math.cos(a), *rng.uniform(-400.0, 400.0, 3))


def _scale(v):
    return math.hypot(v[0], v[1]) + R * math.sqrt(v[2] ** 2 + v[3] ** 2 + v[4] ** 2)


def _dist(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return float(np.abs(np.r_[a[:2] - b[:2], R * (a[2:] - b[2:])]).max())


def _ref(v, steps, p=PV):
    return mathavan_midpoint._resolve_steps(*v, 0.0, 1.0, P.e_c, p, steps)


def _run(v, tol, p=PV):
    return mathavan2010._resolve_tol(*v, 0.0, 1.0, P.e_c, p, tol)


def errors(n, seed, p=PV, check_every=4):
    """Per impact (error at STEP_TOL against the reference, STEP_TOL
    against STEP_TOL / 32, and for every ``check_every``-th impact the
    reference at 64 N against 128 N steps, else 0), in units of V."""
    out = []
    for i, v in enumerate(impacts(n, seed)):
        s = _scale(v)
        ref = _ref(v, 64 * N, p)
        a = _run(v, TOL, p)
        check = _dist(ref, _ref(v, 128 * N, p)) / s if i % check_every == 0 else 0.0
        out.append((_dist(a, ref) / s, _dist(a, _run(v, TOL / 32, p)) / s, check))
    return np.array(out)


def test_mathavan_converges_on_random_impacts():
    """At STEP_TOL every impact is within TARGET of the converged reference
    and half the step changes none by HALF or more; the median error is
    below 1e-8 V (measured: 8e-11 V). The reference is converged: 64 N and
    128 N steps agree within REF_TOL."""
    e = errors(40, seed=13)
    err, half, ref = e[:, 0], e[:, 1], e[:, 2]
    assert ref.max() < REF_TOL
    assert err.max() < TARGET
    assert half.max() < HALF
    assert np.median(err) < 1e-8


def test_mathavan_frictionless_felt_reference():
    """Without felt friction (mu_s = 0) the reference's cushion stick rule
    is exact; on impacts that roll, slide and stick at the cushion the two
    integrations agree within 1e-7 V."""
    p = PV.copy()
    p[C.P_MU_S] = 0.0
    for v in impacts(12, seed=4):
        ref = _ref(v, 64 * N, p)
        assert _dist(_run(v, TOL, p), ref) / _scale(v) < 1e-7


def test_mathavan_error_follows_the_tolerance():
    """The error estimate controls the error: on impacts whose slips never
    end (side spin 300 rad/s against the slide, no felt friction) the
    error against a 1e4 x tighter run is below the tolerance at STEP_TOL,
    and 1000 x looser a tolerance makes it at least 100 x larger (measured:
    500 - 800 x)."""
    p = PV.copy()
    p[C.P_MU_S] = 0.0
    for V, a in ((2.0, 0.3), (5.0, -0.6), (9.0, 0.9)):
        v = (V * math.sin(a), -V * math.cos(a), 0.0, 0.0, 300.0 * (1 if a > 0 else -1))
        ref = _run(v, 1e-4 * TOL, p)
        loose = _dist(_run(v, 1e3 * TOL, p), ref) / _scale(v)
        tight = _dist(_run(v, TOL, p), ref) / _scale(v)
        assert 0.0 < tight < TOL and loose > 100.0 * tight

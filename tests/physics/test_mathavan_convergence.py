"""Convergence of the Mathavan et al. (2010) cushion integration
(physics/cushion/mathavan2010.py): errors against 64 times the impulse steps,
in units of the impact's speed scale V = |v| + R |w|. The figures each
assertion guards are the module docstring's (measured on 300 impacts with
the code in this file: ``errors(300, seed=2)``)."""
import math

import numpy as np

from billiards_env.physics import PhysicsParams
from billiards_env.physics import constants as C
from billiards_env.physics.cushion import mathavan2010

P = PhysicsParams.standard()
PV = P.as_array()
R = P.R
N = mathavan2010.IMPULSE_STEPS
# The reference itself: 64 x against 128 x the steps agree within this (V).
REF_TOL = 1e-6


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


def _run(v, steps, p=PV):
    return mathavan2010._resolve_steps(*v, 0.0, 1.0, P.e_c, p, steps)


def errors(n, seed, p=PV, check_every=4):
    """Per impact (error at N steps against 64 N, N against 2 N, and for
    every ``check_every``-th impact 64 N against 128 N, else 0), in units
    of V."""
    out = []
    for i, v in enumerate(impacts(n, seed)):
        s = _scale(v)
        ref = _run(v, 64 * N, p)
        a = _run(v, N, p)
        check = _dist(ref, _run(v, 128 * N, p)) / s if i % check_every == 0 else 0.0
        out.append((_dist(a, ref) / s, _dist(a, _run(v, 2 * N, p)) / s, check))
    return np.array(out)


def test_mathavan_converges_on_random_impacts():
    """At IMPULSE_STEPS: median error below 1e-7 V, at least 90% of the
    impacts within 1e-5 V and none beyond 2e-4 V (the version before this
    one: up to 4e-4 V, its stick rule first order); halving the step
    changes the median impact by less than 1e-7 V. The reference is
    converged: 64 N and 128 N steps agree within REF_TOL."""
    e = errors(40, seed=13)
    err, half, ref = e[:, 0], e[:, 1], e[:, 2]
    assert ref.max() < REF_TOL
    assert np.median(err) < 1e-7
    assert np.mean(err < 1e-5) >= 0.9
    assert err.max() < 2e-4
    assert np.median(half) < 1e-7


def test_mathavan_second_order_while_sliding():
    """Without felt friction (mu_s = 0) on impacts whose cushion slip never
    ends (side spin 300 rad/s against the slide), the integration is the
    midpoint rule on a smooth right-hand side: doubling the steps divides
    the error by about 4 (between 3 and 5)."""
    p = PV.copy()
    p[C.P_MU_S] = 0.0
    for V, a in ((2.0, 0.3), (5.0, -0.6), (9.0, 0.9)):
        v = (V * math.sin(a), -V * math.cos(a), 0.0, 0.0, 300.0 * (1 if a > 0 else -1))
        ref = _run(v, 64 * N, p)
        e1, e2 = _dist(_run(v, N // 2, p), ref), _dist(_run(v, N, p), ref)
        assert e1 > 0.0 and 3.0 < e1 / e2 < 5.0

"""The impact-parameter aim (``aim: impact``): action a0 sets how full the
cue ball hits the legal target ball, not an angle.

A straight cue-ball path that passes the object ball's centre at
perpendicular distance ``b`` (the impact parameter) touches it when
``|b| < 2R``; at contact the line of centres makes the angle
``theta = asin(b / 2R)`` with the path, and without friction between the
balls the object ball leaves along that line (the ghost-ball construction:
the ghost ball is the cue ball at contact, centre 2R from the object ball's
centre on the line object ball -> pocket). ``b = 0`` is a full hit,
``|b| -> 2R`` the thinnest touch. Pool players aim this way: the
"ball-hit fraction" (the overlap of the two balls seen along the aim line)
is ``1 - |b| / 2R = 1 - sin(cut angle)`` (D. Alciatore, "Dr. Dave",
billiards.colostate.edu: the ball-hit fraction and cut-angle plots of his
technical proof TP A.16).

Convention: ``a0 = sin(theta)`` with theta the object ball's departure
angle measured counter-clockwise from the cue ball's path, so a0 in [-1, 1]
spans every hit from the thinnest on one side through full to the thinnest
on the other, and ``b = 2R * a0``. The object ball goes left of the path for
a0 > 0, which needs the cue ball to pass right of its centre: the aim turns
clockwise from the line cue -> target by ``asin(b / d)``,

    phi = angle(cue -> target) - asin(2R * a0 / d),   d = centre distance.

Balls at rest never overlap, so ``d >= 2R >= |b|``; ``b / d`` is clipped to
[-1, 1] in any case. Balls in the way are not considered: the shot is
simulated like any other, and the first ball the cue ball meets is the one
it hits. Friction between the balls (throw) turns the object ball by a few
degrees from theta; the policy learns that. Tables without a legal target
fall back to the relative aim's origin 0: phi = pi * a0 (as ``relative``).
"""
from __future__ import annotations

import math

import numba

_jit = numba.njit(cache=True, nogil=True)


@_jit
def impact_to_phi(a0, base, tgt, pos, R):
    """Aim angle (rad, wrapped to [-pi, pi)) of impact action ``a0`` (clipped to
    [-1, 1]) on a table with cue -> target direction ``base``, target ``tgt``
    (-1 none: ``base + pi * a0``) and positions ``pos`` [B, 2]."""
    a0 = min(max(a0, -1.0), 1.0)
    if tgt < 0:
        phi = base + math.pi * a0
    else:
        d = math.hypot(pos[tgt, 0] - pos[0, 0], pos[tgt, 1] - pos[0, 1])
        phi = base - math.asin(min(max(2.0 * R * a0 / d, -1.0), 1.0))
    return (phi + math.pi) % (2 * math.pi) - math.pi


@_jit
def phi_to_impact(phi, base, tgt, pos, R):
    """The inverse of ``impact_to_phi``: the a0 (clipped to [-1, 1]) whose aim
    is ``phi``. Aims that miss the target map to the nearer thinnest touch
    (+-1); aims turned more than 90 degrees away map to the sign of the turn."""
    rel = (phi - base + math.pi) % (2 * math.pi) - math.pi
    if tgt < 0:
        return rel / math.pi
    if abs(rel) >= 0.5 * math.pi:
        return -1.0 if rel > 0 else 1.0
    d = math.hypot(pos[tgt, 0] - pos[0, 0], pos[tgt, 1] - pos[0, 1])
    return min(max(-d * math.sin(rel) / (2.0 * R), -1.0), 1.0)


@_jit
def impact_phis(a0, base, tgt, pos, R, out):
    """``impact_to_phi`` for n tables: a0, base, tgt [n], pos [n, B, 2] -> ``out`` [n]."""
    for e in range(a0.shape[0]):
        out[e] = impact_to_phi(a0[e], base[e], tgt[e], pos[e], R)


@_jit
def impact_actions(phi, base, tgt, pos, R, out):
    """``phi_to_impact`` for n tables -> ``out`` [n]."""
    for e in range(phi.shape[0]):
        out[e] = phi_to_impact(phi[e], base[e], tgt[e], pos[e], R)

"""Stroke speeds from distances (numpy, vectorised).

A ball rolling a distance d with rolling resistance mu_r loses v^2 by
2 mu_r g d; an object ball leaves the collision sliding without spin and
reaches rolling at 5/7 of its launch speed; a cue ball struck with height
offset b ends its slide at 5/7 (1 + b) of its strike speed (conservation of
angular momentum about the contact point, Alciatore's technical proofs on
stun and roll); the cut transfers about cos(theta) (1 + e_b) / 2 of the cue
ball's speed to the object ball.
"""
from __future__ import annotations

import numpy as np

from ...physics import PhysicsParams


def required_speed(d_cg, d_op, cut, params: PhysicsParams, b: float = 0.0, margin: float = 1.25,
                   v_arrive: float = 0.35) -> np.ndarray:
    """Cue-ball strike speed (m/s) that carries the object ball ``d_op`` metres
    to the pocket and still arriving at ``v_arrive`` m/s, times ``margin``.

    Object ball: launch speed v_o slides to 5/7 v_o, then rolls with
    deceleration mu_r g: v_o = 7/5 sqrt(v_arrive^2 + 2 mu_r g d_op). Cut
    transfer: v_c = v_o / (cos(cut) (1 + e_b) / 2). Cue ball to the ghost:
    strike speed v0 = sqrt(v_c^2 + 2 mu_r g d_cg) / f where f = 5/7 (1 + b)
    (capped to [5/7, 1]) is the slide loss of a centre/draw hit.
    """
    v_o = 1.4 * np.sqrt(v_arrive ** 2 + 2 * params.mu_r * params.g * d_op)
    v_c = v_o / (np.maximum(np.cos(cut), 0.15) * (1 + params.e_b) / 2)
    return np.minimum(margin * rolling_strike_speed(d_cg, v_c, params, b), params.max_speed)


def rolling_strike_speed(distance, v_arrive, params: PhysicsParams, b: float = 0.0) -> np.ndarray:
    """Strike speed (m/s) with which the cue ball, struck at height offset
    ``b``, arrives ``distance`` metres away at ``v_arrive``: the slide ends at
    f = 5/7 (1 + b) of the strike speed (capped to [5/7, 1]), then rolling
    resistance takes 2 mu_r g d of v^2 (not capped to the max speed)."""
    f = min(max(5.0 / 7.0 * (1 + b), 5.0 / 7.0), 1.0)
    return np.sqrt(np.square(v_arrive) + 2 * params.mu_r * params.g * np.asarray(distance)) / f

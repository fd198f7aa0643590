"""The cue strike.

Hooke's law impulse: the cue drawn back a distance x gives the cue ball the
impulse J = k x dt (dt the contact time), so v = k dt x / m along the aim.
The impulse acts at the contact point r = R(-sqrt(1 - a^2 - b^2) d + a s + b z)
(d the aim direction, s = d x z to the right, a side and b height offsets in
units of R), so omega = (r x J) / I with I = 2/5 m R^2, which reduces to
omega = 5 v / (2R) (a z + b (z x d)) (Alciatore's technical proofs on tip offset; level cue, no
squirt). b = 2/5 gives natural roll; b < 0 draw; a > 0 right english.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .params import PhysicsParams, draw_to_speed, speed_to_draw  # noqa: F401 (the cue's speed law, re-exported)
from .state import BallState
from .validation import as_batch_vector, check_finite


@dataclasses.dataclass(frozen=True, eq=False)
class Shots:
    """A batch of cue strikes, the arguments of ``strike_velocity``: float64
    arrays [N] of the aim ``phi`` (rad, counter-clockwise from +x), the
    cue-ball ``speed`` (m/s) and the tip offsets ``a`` (side, + = right
    english) and ``b`` (height, + = follow) in units of R. Scalars and
    arrays are broadcast to one shape; ``phi, speed, a, b = shots`` unpacks."""

    phi: np.ndarray
    speed: np.ndarray
    a: np.ndarray
    b: np.ndarray

    def __post_init__(self):
        arrays = np.broadcast_arrays(*(np.atleast_1d(np.asarray(getattr(self, f), dtype=np.float64))
                                       for f in ("phi", "speed", "a", "b")))
        for f, v in zip(("phi", "speed", "a", "b"), arrays):
            object.__setattr__(self, f, np.array(v))  # own, writable copies

    def __len__(self) -> int:
        return len(self.phi)

    def __iter__(self):
        return iter((self.phi, self.speed, self.a, self.b))

    @classmethod
    def of_arrays(cls, phi: np.ndarray, speed: np.ndarray, a: np.ndarray, b: np.ndarray) -> "Shots":
        """Shots over float64 arrays [N] of one length that the caller hands
        over (not copied, not checked): for code that built them itself,
        such as the envs' action mapping."""
        shots = object.__new__(cls)
        for f, v in zip(("phi", "speed", "a", "b"), (phi, speed, a, b)):
            object.__setattr__(shots, f, v)
        return shots

    def take(self, idx) -> "Shots":
        """The shots at ``idx`` (an index array or mask)."""
        return Shots(self.phi[idx], self.speed[idx], self.a[idx], self.b[idx])


def strike(state: BallState, phi, draw, a=0.0, b=0.0, params: PhysicsParams | None = None) -> BallState:
    """A new state with the cue ball (ball 0) struck. ``phi`` aim angle (rad,
    counter-clockwise from +x), ``draw`` cue draw distance (m, 0..max_draw),
    ``a``/``b`` side/height offsets in units of R. Each is a scalar or an
    array of shape [E]. The input state is not modified."""
    params = params or PhysicsParams.standard()
    phi, draw, a, b = _shot_arrays(state, phi, draw, a, b, "draw")
    if np.any(draw < 0):
        raise ValueError(f"draw must be >= 0 (a distance), got min {draw.min()}")
    if np.any(draw > params.max_draw * (1 + 1e-12)):
        raise ValueError(f"draw must be <= max_draw = {params.max_draw} m, got max {draw.max()}")
    off = np.hypot(a, b)
    if np.any(off > params.miscue_limit):
        k = int(np.argmax(off))
        raise ValueError(f"miscue: contact offset |(a, b)| = {off[k]:.4g} R in env {k} exceeds the "
                         f"miscue limit {params.miscue_limit} R")
    if np.any(state.pocket[:, 0] >= 0):
        raise ValueError("the cue ball is pocketed in some environment; place it on the table before striking")
    return _struck(state, phi, draw_to_speed(draw, params), a, b, params)


def strike_velocity(state: BallState, phi, speed, a=0.0, b=0.0, params: PhysicsParams | None = None) -> BallState:
    """As ``strike`` but with the cue-ball speed (m/s) given directly
    (``strike_velocity(state, *shots, params=params)`` strikes ``Shots``)."""
    params = params or PhysicsParams.standard()
    phi, speed, a, b = _shot_arrays(state, phi, speed, a, b, "speed")
    if np.any(speed < 0):
        raise ValueError("speed must be >= 0")
    return _struck(state, phi, speed, a, b, params)


def _shot_arrays(state: BallState, phi, x, a, b, x_name: str) -> tuple:
    """The four shot arguments as checked float64 arrays [E] (``x`` the draw or the speed)."""
    E = state.n_envs
    return (as_batch_vector(phi, E, "phi"), as_batch_vector(x, E, x_name), as_batch_vector(a, E, "a"),
            as_batch_vector(b, E, "b"))


def _struck(state: BallState, phi, speed, a, b, params: PhysicsParams) -> BallState:
    check_finite(state)
    out = state.copy()
    apply_strike(out, phi, speed, a, b, params.R)
    return out


def apply_strike(state: BallState, phi: np.ndarray, speed: np.ndarray, a: np.ndarray, b: np.ndarray,
                 R: float) -> None:
    """Set the cue ball's velocity and spin in ``state`` (modified in place)
    from checked float64 arrays [E] (the formulas of the module docstring):
    ``strike_velocity`` after its checks, and the envs, whose shots come from
    actions they checked once at their boundary."""
    dx, dy = np.cos(phi), np.sin(phi)
    state.vel[:, 0, 0] = speed * dx
    state.vel[:, 0, 1] = speed * dy
    k = 2.5 * speed / R
    state.omega[:, 0, 0] = k * b * (-dy)
    state.omega[:, 0, 1] = k * b * dx
    state.omega[:, 0, 2] = k * a

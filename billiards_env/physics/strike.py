"""The cue strike.

Hooke's law impulse: the cue drawn back a distance x gives the cue ball the
impulse J = k x dt (dt the contact time), so v = k dt x / m along the cue.
The impulse acts at the contact point r = R(-sqrt(1 - a^2 - b^2) d + a s + b z)
(d the aim direction, s = d x z to the right, a side and b height offsets in
units of R), so omega = (r x J) / I with I = 2/5 m R^2, which reduces to
omega = 5 v / (2R) (a z + b (z x d)) (Alciatore's technical proofs on tip offset; level cue, no
squirt). b = 2/5 gives natural roll; b < 0 draw; a > 0 right english.

The elevated cue (``theta``, radians above the horizontal, butt up; issue
46). The cue's axis, the direction of its force on the ball, is
f = cos(theta) d - sin(theta) z, and the tip offsets are measured in the
plane across the cue: sideways along s and "up" along the cue's own up
u = sin(theta) d + cos(theta) z, so the contact point is
r = R(a s + b u - c f), c = sqrt(1 - a^2 - b^2) (the point of the ball the
tip meets, on the side facing the cue; at theta = 0 the level formula
above). The impulse J f at r gives (``cue_strike_3d``)

    v     = (J/m) f              = v0 (cos(theta) d - sin(theta) z)
    omega = (r x J f) / I        = 5 v0 / (2R) (a (cos(theta) z + sin(theta) d) - b s)

with v0 = J/m the cue-ball speed (the spring's, as for the level cue: the
cue's mass is not modelled). The spin's magnitude 5 v0 sqrt(a^2 + b^2) / (2R)
does not depend on the elevation and its axis is across the cue
(omega . f = 0); elevating the cue turns the side offset's spin from
english (about z) towards massé spin about the aim line (sin(theta) d): on
the felt the sliding contact point u = v - R omega x z then has a sideways
part, and the ball curves. This is Leckie & Greenspan's (2006) cue-strike
model with the offsets in the cue's frame, as Alciatore derives it
(technical proof TP A-30, the source pooltool cites) and as pooltool's main
branch (``stick_ball/instantaneous_point``) transforms its offsets into the
ball's frame; pooltool also models the cue's mass (a speed that falls with
the offset) and squirt, which this model leaves out at every elevation, as
the level strike always has.

A downward cue drives the ball into the slate (v_z = -v0 sin(theta) < 0).
``strike`` and ``strike_velocity`` give the cue ball the horizontal part of v
and all three components of omega. The vertical part goes into the state's
``air`` (its vertical velocity) where the state has one: simulated with
``Effects(airborne=True)``, the slate's reaction, its friction and the jump
that follows are ``airborne.land`` at t = 0. A planar state (``air`` None)
drops it: the planar simulator's slate takes it without friction and
without a rebound.
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
    english) and ``b`` (height, + = follow) in units of R, and the cue's
    elevation ``theta`` (rad above the horizontal, 0 .. pi/2; default 0, the
    level cue). Scalars and arrays are broadcast to one shape;
    ``phi, speed, a, b = shots`` unpacks the four level-cue arguments (the
    elevation is ``shots.theta``, passed as ``theta=``)."""

    phi: np.ndarray
    speed: np.ndarray
    a: np.ndarray
    b: np.ndarray
    theta: np.ndarray = 0.0

    def __post_init__(self):
        arrays = np.broadcast_arrays(*(np.atleast_1d(np.asarray(getattr(self, f), dtype=np.float64))
                                       for f in _FIELDS))
        for f, v in zip(_FIELDS, arrays):
            object.__setattr__(self, f, np.array(v))  # own, writable copies

    def __len__(self) -> int:
        return len(self.phi)

    def __iter__(self):
        return iter((self.phi, self.speed, self.a, self.b))

    @classmethod
    def of_arrays(cls, phi: np.ndarray, speed: np.ndarray, a: np.ndarray, b: np.ndarray,
                  theta: np.ndarray | None = None) -> "Shots":
        """Shots over float64 arrays [N] of one length that the caller hands
        over (not copied, not checked): for code that built them itself,
        such as the envs' action mapping. ``theta`` None: the level cue
        (zeros)."""
        shots = object.__new__(cls)
        theta = np.zeros(len(phi)) if theta is None else theta
        for f, v in zip(_FIELDS, (phi, speed, a, b, theta)):
            object.__setattr__(shots, f, v)
        return shots

    @property
    def elevated(self) -> np.ndarray | None:
        """``theta`` where some shot is elevated, else None (the level strike's
        own arithmetic: what ``strike_velocity`` and ``apply_strike`` take)."""
        return self.theta if np.any(self.theta != 0) else None

    def take(self, idx) -> "Shots":
        """The shots at ``idx`` (an index array or mask)."""
        return Shots(self.phi[idx], self.speed[idx], self.a[idx], self.b[idx], self.theta[idx])


_FIELDS = ("phi", "speed", "a", "b", "theta")


# The steepest cue: vertical (a massé cue stands up to about 90 degrees); a cue
# below the horizontal would have to pass through the slate.
MAX_ELEVATION = np.pi / 2


def strike(state: BallState, phi, draw, a=0.0, b=0.0, params: PhysicsParams | None = None,
           theta=0.0) -> BallState:
    """A new state with the cue ball (ball 0) struck. ``phi`` aim angle (rad,
    counter-clockwise from +x), ``draw`` cue draw distance (m, 0..max_draw),
    ``a``/``b`` side/height offsets in units of R (across the cue), ``theta``
    the cue's elevation above the horizontal (rad, 0..pi/2; 0, the default,
    is the level cue). Each is a scalar or an array of shape [E]. The input
    state is not modified. An elevated cue's velocity into the slate is not
    kept (module docstring)."""
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
    return _struck(state, phi, draw_to_speed(draw, params), a, b, params, _elevation(state, theta))


def strike_velocity(state: BallState, phi, speed, a=0.0, b=0.0, params: PhysicsParams | None = None,
                    theta=0.0) -> BallState:
    """As ``strike`` but with the cue-ball speed (m/s) given directly
    (``strike_velocity(state, *shots, params=params)`` strikes ``Shots``)."""
    params = params or PhysicsParams.standard()
    phi, speed, a, b = _shot_arrays(state, phi, speed, a, b, "speed")
    if np.any(speed < 0):
        raise ValueError("speed must be >= 0")
    return _struck(state, phi, speed, a, b, params, _elevation(state, theta))


def _shot_arrays(state: BallState, phi, x, a, b, x_name: str) -> tuple:
    """The four shot arguments as checked float64 arrays [E] (``x`` the draw or the speed)."""
    E = state.n_envs
    return (as_batch_vector(phi, E, "phi"), as_batch_vector(x, E, x_name), as_batch_vector(a, E, "a"),
            as_batch_vector(b, E, "b"))


def _elevation(state: BallState, theta):
    """The cue's elevation as a checked float64 array [E], or None when it
    is 0 everywhere (the level strike's own arithmetic)."""
    theta = as_batch_vector(theta, state.n_envs, "theta")
    if np.any((theta < 0) | (theta > MAX_ELEVATION)):
        raise ValueError(f"theta (the cue's elevation) must lie in [0, pi/2] rad, got min {theta.min()} "
                         f"and max {theta.max()}")
    return theta if np.any(theta != 0) else None


def _struck(state: BallState, phi, speed, a, b, params: PhysicsParams, theta=None) -> BallState:
    check_finite(state)
    out = state.copy()
    apply_strike(out, phi, speed, a, b, params.R, theta)
    return out


def apply_strike(state: BallState, phi: np.ndarray, speed: np.ndarray, a: np.ndarray, b: np.ndarray,
                 R: float, theta: np.ndarray | None = None) -> None:
    """Set the cue ball's velocity and spin in ``state`` (modified in place)
    from checked float64 arrays [E] (the formulas of the module docstring):
    ``strike_velocity`` after its checks, and the envs, whose shots come from
    actions they checked once at their boundary. ``theta``: the cue's
    elevation (None: the level cue). The velocity into the slate goes into
    ``state.air`` where the state has it (simulated by
    ``Effects(airborne=True)``: the slate's rebound, a jump); a planar state
    (``air`` None) drops it, as the planar simulator's slate takes it."""
    if theta is not None:
        v, w = cue_strike_3d(phi, speed, a, b, theta, R)
        state.vel[:, 0, :] = v[:, :2]
        state.omega[:, 0, :] = w
        if state.air is not None:
            state.air[:, 0, 1] = v[:, 2]
        return
    dx, dy = np.cos(phi), np.sin(phi)
    state.vel[:, 0, 0] = speed * dx
    state.vel[:, 0, 1] = speed * dy
    k = 2.5 * speed / R
    state.omega[:, 0, 0] = k * b * (-dy)
    state.omega[:, 0, 1] = k * b * dx
    state.omega[:, 0, 2] = k * a


def cue_strike_3d(phi, speed, a, b, theta, R: float) -> tuple[np.ndarray, np.ndarray]:
    """The cue ball's velocity and spin just after the strike of a cue
    elevated ``theta`` (module docstring): float64 arrays ``v`` and
    ``omega`` of shape [..., 3] (x, y, z; z up), the arguments' broadcast
    shape. ``v[..., 2] = -speed sin(theta)`` is the velocity into the slate.

    At theta = 0 the result is the level strike's, bit for bit: cos(0) = 1
    multiplies exactly, and the massé terms k a sin(theta) d, zero there,
    are not added (adding a zero could turn a -0.0 into +0.0)."""
    phi, speed, a, b, theta = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64)
                                                    for x in (phi, speed, a, b, theta)))
    dx, dy = np.cos(phi), np.sin(phi)
    ct, st = np.cos(theta), np.sin(theta)
    h = speed * ct  # the horizontal speed
    v = np.empty(phi.shape + (3,))
    v[..., 0] = h * dx
    v[..., 1] = h * dy
    v[..., 2] = -(speed * st)
    k = 2.5 * speed / R
    w = np.empty(phi.shape + (3,))
    masse = k * a * st  # spin about the aim line d
    for i, level, along in ((0, k * b * (-dy), dx), (1, k * b * dx, dy)):
        term = masse * along
        w[..., i] = np.where(term != 0, level + term, level)
    w[..., 2] = k * a * ct
    return v, w

"""Input checks at the Python boundary: each raises a ValueError or TypeError
that names the problem, before anything is modified."""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from . import constants as C


def finite_number(v, name: str, lo: float | None = None) -> float:
    """``v`` as a float: a finite int or float (not a bool), at least ``lo`` if given."""
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ValueError(f"{name} must be a finite number, got {v!r}")
    if lo is not None and v < lo:
        raise ValueError(f"{name} must be >= {lo}, got {v!r}")
    return float(v)


def as_batch_vector(x, E: int, name: str) -> np.ndarray:
    arr = np.asarray(x, dtype=np.float64)
    if arr.ndim == 0:
        arr = np.full(E, float(arr))
    if arr.shape != (E,):
        raise ValueError(f"{name} must be a scalar or have shape ({E},), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinite values")
    return arr.copy()


def check_arrays(state) -> None:
    for name, arr, dims in (("pos", state.pos, 2), ("vel", state.vel, 2), ("omega", state.omega, 3)):
        if not isinstance(arr, np.ndarray):
            raise TypeError(f"BallState.{name} must be a numpy array, got {type(arr).__name__}")
        if arr.dtype != np.float64:
            raise TypeError(f"BallState.{name} must be float64, got {arr.dtype}")
        if arr.ndim != 3 or arr.shape[2] != dims:
            raise ValueError(f"BallState.{name} must have shape [E, B, {dims}], got {arr.shape}")
    E, B = state.pos.shape[:2]
    if E < 1 or B < 1:
        raise ValueError(f"BallState needs at least one table and one ball, got shape {state.pos.shape}")
    for name, arr in (("vel", state.vel), ("omega", state.omega)):
        if arr.shape[:2] != (E, B):
            raise ValueError(f"BallState.{name} has shape {arr.shape}, expected [{E}, {B}, ...] like pos")
    if not isinstance(state.pocket, np.ndarray) or state.pocket.shape != (E, B):
        raise ValueError(f"BallState.pocket must be an integer array of shape ({E}, {B})")
    if not np.issubdtype(state.pocket.dtype, np.integer):
        raise TypeError(f"BallState.pocket must be an integer array, got {state.pocket.dtype}")


def check_finite(state) -> None:
    for name in ("pos", "vel", "omega"):
        arr = getattr(state, name)
        if not np.all(np.isfinite(arr)):
            bad = np.argwhere(~np.isfinite(arr))[0]
            raise ValueError(f"BallState.{name} contains NaN or infinite values (first at index {tuple(bad)})")


def check_air(state, airborne: bool) -> None:
    """``state.air`` (optional): [E, B, 2] float64, finite, no ball below the
    slate; balls off the slate or moving vertically only where the effect
    ``airborne`` is simulated."""
    air = state.air
    if air is None:
        return
    E, B = state.pos.shape[:2]
    if not isinstance(air, np.ndarray) or air.dtype != np.float64 or air.shape != (E, B, 2):
        raise ValueError(f"BallState.air must be a float64 array of shape ({E}, {B}, 2) (height above the slate, "
                         f"vertical velocity), got {getattr(air, 'shape', type(air).__name__)}")
    if not np.all(np.isfinite(air)):
        raise ValueError("BallState.air contains NaN or infinite values")
    on = state.pocket < 0
    if np.any(on & (air[..., 0] < 0)):
        e, i = np.argwhere(on & (air[..., 0] < 0))[0]
        raise ValueError(f"ball {i} in env {e} is below the slate (height {air[e, i, 0]} m)")
    if not airborne and np.any(on[..., None] & (air != 0)):
        e, i = np.argwhere(on & (air != 0).any(axis=2))[0]
        raise ValueError(f"ball {i} in env {e} is off the slate or moving vertically (BallState.air "
                         f"{tuple(air[e, i])}); the planar simulator cannot move it: simulate with "
                         "Effects(airborne=True)")


def check_placement(state, table, params, pockets: bool) -> None:
    """No two balls on the table overlap by more than OVERLAP_TOL (in 3D
    where ``state.air`` gives heights); every ball on the table lies on the
    playing surface."""
    R = params.R
    on = state.pocket < 0
    ok = table.contains(state.pos.reshape(-1, 2), R, C.OVERLAP_TOL, pockets).reshape(on.shape)
    bad = on & ~ok
    if bad.any():
        e, i = np.argwhere(bad)[0]
        raise ValueError(f"ball {i} in env {e} at {tuple(np.round(state.pos[e, i], 6))} is off the table "
                         f"or inside a pocket/cushion ({table.name})")
    d = state.pos[:, :, None, :] - state.pos[:, None, :, :]
    dist = np.hypot(d[..., 0], d[..., 1])
    if state.air is not None:
        dist = np.hypot(dist, state.air[:, :, None, 0] - state.air[:, None, :, 0])
    both = on[:, :, None] & on[:, None, :]
    B = state.pos.shape[1]
    both &= ~np.eye(B, dtype=bool)[None]
    over = both & (dist < 2 * R - C.OVERLAP_TOL)
    if over.any():
        e, i, j = np.argwhere(over)[0]
        raise ValueError(f"balls {i} and {j} in env {e} overlap: centres {dist[e, i, j]:.9f} m apart, "
                         f"less than 2R = {2 * R:.9f} m")


def check_keys(cls, d: dict, where: str) -> None:
    """Raise a ValueError naming any key of ``d`` that is not a field of the
    dataclass ``cls`` (configs reject typos instead of ignoring them)."""
    if not isinstance(d, dict):
        raise ValueError(f"{where} must be a mapping, got {type(d).__name__}")
    names = {f.name for f in dataclasses.fields(cls)}
    unknown = set(d) - names
    if unknown:
        raise ValueError(f"unknown key(s) {sorted(unknown)} in {where}; known keys: {sorted(names)}")

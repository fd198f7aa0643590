"""Execution noise: how a struck shot differs from the one intended.

The model (the one every env and every bot uses): Gaussian errors, standard
deviations ``NoiseConfig`` (aim in degrees, cue-ball speed in m/s, side and
height tip offsets in mm), applied to a ``Shots`` batch by ``perturb``:

    phi   += z0 * aim_deg (in radians)
    speed  = clip(speed + z1 * speed_sd, 0, max_speed)
    a     += z2 * side_mm / R,   b += z3 * height_mm / R
    (a, b) scaled radially just inside the miscue disc |(a, b)| <= miscue_limit

with ``z`` [n, 4] standard normals drawn by the caller (the envs draw them
from per-table streams, bots from their own generators). The ``tournament``
preset's deviations follow the execution noise of the computer pool
tournaments (Archibald, Altman and Shoham, "Analysis of a winning
computational billiards player", IJCAI 2009: Gaussian noise on the shot
parameters, a "high" level of five times the standard one).
"""
from __future__ import annotations

import dataclasses
import math

import numba
import numpy as np

from .strike import Shots
from .validation import check_keys, finite_number

# radial clip just inside the miscue limit: strike's own check is strict (|(a, b)| < limit)
OFFSET_SAFETY = 1.0 - 1e-9

NOISE_PRESETS = {
    "none": dict(aim_deg=0.0, speed=0.0, side_mm=0.0, height_mm=0.0),
    # tournament-level execution error
    "tournament": dict(aim_deg=0.125, speed=0.075, side_mm=0.5, height_mm=0.5),
    # five times the tournament standard deviations (the high-noise level of computer pool tournaments)
    "high": dict(aim_deg=0.625, speed=0.375, side_mm=2.5, height_mm=2.5),
}


@dataclasses.dataclass(frozen=True)
class NoiseConfig:
    """Gaussian execution noise (standard deviations) on the aim angle
    (degrees), the cue-ball speed (m/s) and the side / height offsets (mm;
    converted to units of R when applied). Presets: ``none``, ``tournament``, ``high``
    (5x tournament)."""

    aim_deg: float = 0.0
    speed: float = 0.0
    side_mm: float = 0.0
    height_mm: float = 0.0

    def __post_init__(self):
        for f in dataclasses.fields(self):
            object.__setattr__(self, f.name, finite_number(getattr(self, f.name), f"noise.{f.name}", 0.0))

    @property
    def enabled(self) -> bool:
        return any(getattr(self, f.name) > 0 for f in dataclasses.fields(self))

    @classmethod
    def preset(cls, name: str) -> "NoiseConfig":
        if name not in NOISE_PRESETS:
            raise ValueError(f"unknown noise preset {name!r}; choose one of {sorted(NOISE_PRESETS)}")
        return cls(**NOISE_PRESETS[name])

    @classmethod
    def from_any(cls, v) -> "NoiseConfig":
        """A preset name, a mapping (optionally with ``preset`` plus overrides), a NoiseConfig or None."""
        if v is None:
            return cls()
        if isinstance(v, NoiseConfig):
            return v
        if isinstance(v, str):
            return cls.preset(v)
        if isinstance(v, dict):
            d = dict(v)
            base = cls.preset(d.pop("preset")).to_dict() if "preset" in d else {}
            check_keys(cls, d, "noise config")
            return cls(**{**base, **d})
        raise ValueError(f"noise must be a preset name, a mapping or a NoiseConfig, got {type(v).__name__}")

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)


_jit = numba.njit(cache=True, nogil=True)


@_jit
def clip_offset(a, b, limit):
    """(a, b) scaled radially just inside the disc of radius ``limit``."""
    lim = limit * OFFSET_SAFETY
    r = math.hypot(a, b)
    f = lim / max(r, 1e-300) if r > lim else 1.0
    return a * f, b * f


@_jit
def _clip_offsets(a, b, limit):
    for e in range(a.shape[0]):
        a[e], b[e] = clip_offset(a[e], b[e], limit)


def perturb(shots: Shots, z: np.ndarray, noise: NoiseConfig, params) -> Shots:
    """``shots`` [n] struck with execution errors from standard normals ``z``
    [n, 4] (already multiplied by any per-table noise factor); see the
    module docstring. Returns new arrays."""
    R = params.R
    phi = shots.phi + z[:, 0] * math.radians(noise.aim_deg)
    speed = np.clip(shots.speed + z[:, 1] * noise.speed, 0.0, params.max_speed)
    a = shots.a + z[:, 2] * noise.side_mm * 1e-3 / R
    b = shots.b + z[:, 3] * noise.height_mm * 1e-3 / R
    _clip_offsets(a, b, params.miscue_limit)  # a, b are new arrays here
    return Shots.of_arrays(phi, speed, a, b)


VARIABLE_NOISE_MAX = 5.0  # the ``variable`` level: the tournament deviations times a factor uniform in [0, 5] per game


@dataclasses.dataclass(frozen=True)
class NoiseLevel:
    """A named level of execution noise, the games' and the bots' one
    vocabulary: the deviations ``config`` (a ``NoiseConfig``) times a factor
    drawn per game uniform in ``spread`` ((1, 1): the deviations as they
    are). ``NOISE_LEVELS`` names the built-in levels: ``none``,
    ``tournament``, ``high`` (5x tournament) and ``variable`` (tournament
    times a factor in [0, 5] per game, the 2011 computer pool championship's
    varying level); any other ``NoiseConfig`` is the level ``custom``."""

    name: str
    config: NoiseConfig
    spread: tuple = (1.0, 1.0)

    @property
    def variable(self) -> bool:
        """The factor is drawn per game (the spread is not (1, 1))."""
        return tuple(self.spread) != (1.0, 1.0)

    @classmethod
    def of(cls, v) -> "NoiseLevel":
        """A level from a ``NoiseLevel``, a level's name (``NOISE_LEVELS``), a ``NoiseConfig`` or a mapping of
        its fields (optionally with ``preset``), or None (no noise)."""
        if isinstance(v, NoiseLevel):
            return v
        if isinstance(v, str):
            if v not in NOISE_LEVELS:
                raise ValueError(f"unknown noise level {v!r}; choose one of {list(NOISE_LEVELS)} "
                                 "(or give the deviations: a NoiseConfig or a mapping of its fields)")
            return NOISE_LEVELS[v]
        return cls("custom", NoiseConfig.from_any(v))


NOISE_LEVELS: dict[str, NoiseLevel] = {
    **{name: NoiseLevel(name, NoiseConfig.preset(name)) for name in NOISE_PRESETS},
    "variable": NoiseLevel("variable", NoiseConfig.preset("tournament"), (0.0, VARIABLE_NOISE_MAX)),
}

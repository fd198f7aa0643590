"""Physical parameters of balls, felt, cushions and cue (SI units).

Presets:
- ``seed``: the project's original constants, kept as a preset
  (m = 0.5 kg, k = 10 N/m, contact time 10 ms, mu_s 0.2, mu_r 0.01, mu_b 0.1,
  e = 1). They give cue-ball speeds of a few cm/s.
- ``standard``: regulation pool. Ball mass and radius from the WPA
  specification; felt friction from Alciatore ("The Illustrated Principles of
  Pool and Billiards", technical proofs); ball-ball restitution 0.95 and friction 0.06
  from Alciatore's throw analysis and Marlow; cushion restitution 0.85, friction 0.2 and
  nose height 0.04 m (about 7R/5, which is 0.040005 m) from Han (2005), "Dynamics in
  carom and three cushion billiards"; spinning friction 0.0127 as used by pooltool
  (Kiefl); the cushion's tangential to normal contact stiffness 0.826 (the
  ``stronge`` model; omega_t / omega_n = sqrt(3.5 kt_kn) = 1.7, pooltool 0.6.0's
  default, in Stronge's (2018) range 1 to 2).
- ``snooker``: ``standard`` with snooker balls: diameter 52.5 mm (WPBSA
  Official Rules, Section 1: 52.5 mm +- 0.05 mm), mass 0.140 kg (pooltool's
  ``SNOOKER_GENERIC`` ball parameters) and the cushion nose at the same
  fraction of the ball's diameter as ``standard``'s (0.04 / 0.05715, an
  assumption: no source gives it); felt, cushion and cue constants are
  ``standard``'s (docs/rules.md, snooker's simplifications).
- ``carom``: three-cushion equipment on the carom match table (``Table.carom()``).
  Balls per the UMB equipment article: diameter 61-61.5 mm (61.5 mm here, as
  pooltool's ``BILLIARD_GENERIC`` ball), mass 205-220 g (0.210 kg, pooltool's
  value, inside the range); cushion nose 37 mm above the bed (UMB). Cloth:
  sliding friction 0.2 and rolling resistance 0.01, cushion friction 0.15, as
  pooltool's ``BILLIARD_GENERIC`` ball parameters (its three-cushion default);
  pooltool says of them that they are not well researched, and no measured
  value for a heated carom cloth was found, so they are the pool cloth's
  sliding and rolling values (Alciatore) - a simplification (docs/rules.md).
  The rest as ``standard``; the cue's spring scaled by the mass ratio so a
  full draw still gives ~10 m/s.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from . import constants as C


@dataclasses.dataclass(frozen=True)
class PhysicsParams:
    """Ball, felt, cushion and cue constants. Build with ``.standard()`` or
    ``.seed()`` and change any field with ``dataclasses.replace``."""

    m: float = 0.170            # ball mass (kg)
    R: float = 0.028575         # ball radius (m): 2.25 in diameter
    g: float = 9.81             # gravity (m/s^2)
    mu_s: float = 0.2           # sliding friction, ball-felt
    mu_r: float = 0.01          # rolling resistance, ball-felt
    mu_sp: float = 0.0127       # spinning friction (vertical-axis spin decays at 5 mu_sp g / 2R)
    mu_b: float = 0.06          # ball-ball friction
    e_b: float = 0.95           # ball-ball restitution
    e_c: float = 0.85           # ball-cushion restitution (Han 2005)
    f_c: float = 0.2            # ball-cushion friction (Han 2005)
    h_c: float = 0.04           # cushion nose height above the felt (m), ~7R/5 (Han 2005; 7R/5 is 0.040005 m)
    kt_kn: float = 0.826        # cushion's tangential / normal contact stiffness (stronge): omega_t/omega_n = 1.7, pooltool 0.6.0's default
    k: float = 5666.7           # cue spring constant (N/m): max draw gives ~10 m/s
    contact_time: float = 0.001  # cue-ball contact time (s)
    max_draw: float = 0.3       # longest cue draw distance (m)
    miscue_limit: float = 0.5   # largest |(a, b)| offset, in units of R

    @classmethod
    def standard(cls) -> "PhysicsParams":
        return cls()

    @classmethod
    def seed(cls) -> "PhysicsParams":
        # The original constants; the cushion treated like a ball-ball
        # impact: restitution e = 1 and the ball-ball friction.
        return cls(m=0.5, R=0.028575, mu_s=0.2, mu_r=0.01, mu_sp=0.0127,
                   mu_b=0.1, e_b=1.0, e_c=1.0, f_c=0.1, h_c=1.4 * 0.028575,
                   k=10.0, contact_time=0.01, max_draw=0.3)

    @classmethod
    def snooker(cls) -> "PhysicsParams":
        R = 0.02625
        return cls(m=0.140, R=R, h_c=0.04 * R / 0.028575)

    @classmethod
    def carom(cls) -> "PhysicsParams":
        """Carom balls, cloth and cushion height (module docstring)."""
        m = 0.210
        return cls(m=m, R=0.0615 / 2, mu_s=0.2, mu_r=0.01, f_c=0.15, h_c=0.037, k=cls.k * m / cls.m)

    @classmethod
    def preset(cls, name: str) -> "PhysicsParams":
        presets = {"standard": cls.standard, "seed": cls.seed, "carom": cls.carom, "snooker": cls.snooker}
        if name not in presets:
            raise ValueError(f"unknown physics preset {name!r}; choose one of {sorted(presets)}")
        return presets[name]()

    def __post_init__(self):
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
                raise ValueError(f"PhysicsParams.{f.name} must be a finite number, got {v!r}")
        for name in ("m", "R", "g", "k", "contact_time", "max_draw", "miscue_limit"):
            if getattr(self, name) <= 0:
                raise ValueError(f"PhysicsParams.{name} must be positive, got {getattr(self, name)}")
        for name in ("mu_s", "mu_r", "mu_sp", "mu_b", "f_c"):
            if getattr(self, name) < 0:
                raise ValueError(f"PhysicsParams.{name} (a friction coefficient) must be >= 0, got {getattr(self, name)}")
        if self.mu_r <= 0:
            raise ValueError("PhysicsParams.mu_r must be > 0: without rolling resistance no ball ever stops")
        for name in ("e_b", "e_c"):
            v = getattr(self, name)
            if not 0.0 <= v <= 1.0:
                raise ValueError(f"PhysicsParams.{name} (a restitution) must lie in [0, 1], got {v}")
        if not self.R < self.h_c < 2 * self.R:
            raise ValueError(f"PhysicsParams.h_c must lie between R and 2R (cushion nose above the ball's equator), got {self.h_c}")
        if not 1.0 / 3.5 < self.kt_kn < 4.0 / 3.5:
            raise ValueError("PhysicsParams.kt_kn must lie in (1/3.5, 4/3.5) (omega_t / omega_n = sqrt(3.5 kt_kn) "
                             f"in (1, 2), where Stronge's three regimes hold), got {self.kt_kn}")
        if not 0 < self.miscue_limit < 1:
            raise ValueError(f"PhysicsParams.miscue_limit must lie in (0, 1), got {self.miscue_limit}")

    @property
    def inertia(self) -> float:
        """Moment of inertia of a solid sphere, 2/5 m R^2."""
        return 0.4 * self.m * self.R ** 2

    @property
    def max_speed(self) -> float:
        """Cue-ball speed of the longest draw (``draw_to_speed``)."""
        return draw_to_speed(self.max_draw, self)

    def as_array(self) -> np.ndarray:
        """Parameter vector in the layout the kernels read (constants.P_*)."""
        out = np.empty(C.N_PARAMS, dtype=np.float64)
        out[C.P_M] = self.m
        out[C.P_R] = self.R
        out[C.P_G] = self.g
        out[C.P_MU_S] = self.mu_s
        out[C.P_MU_R] = self.mu_r
        out[C.P_MU_SP] = self.mu_sp
        out[C.P_MU_B] = self.mu_b
        out[C.P_E_B] = self.e_b
        out[C.P_E_C] = self.e_c
        out[C.P_F_C] = self.f_c
        out[C.P_H_C] = self.h_c
        out[C.P_KT_KN] = self.kt_kn
        return out

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> "PhysicsParams":
        d = dict(d)
        preset = d.pop("preset", "standard")
        base = cls.preset(preset)
        unknown = set(d) - {f.name for f in dataclasses.fields(cls)}
        if unknown:
            raise ValueError(f"unknown PhysicsParams fields: {sorted(unknown)}")
        return dataclasses.replace(base, **{k: float(v) for k, v in d.items()})


def draw_to_speed(draw, params: PhysicsParams):
    """Cue-ball speed (m/s) of a cue drawn back ``draw`` metres: v = k dt x / m
    (Hooke's law impulse J = k x dt, see ``strike``). Scalars or arrays. The
    one definition of the cue's speed law (``strike`` re-exports it)."""
    return params.k * params.contact_time * draw / params.m


def speed_to_draw(speed, params: PhysicsParams):
    """Inverse of ``draw_to_speed``: the cue draw (m) giving cue-ball speed
    ``speed`` (m/s), x = v m / (k dt). Not clipped to [0, max_draw]."""
    return speed * params.m / (params.k * params.contact_time)

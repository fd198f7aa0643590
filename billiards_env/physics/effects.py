"""Which physical effects a scene simulates.

Each combination compiles its own kernel (``kernels.make_kernel``): the
flags are compile-time constants of numba closures, and ``ball_friction`` /
``cushion_friction`` pick the frictionless or the chosen ``Models`` model.
Branches on the flags are pruned when the kernel compiles, so an effect that
is off is never executed. ``pockets`` needs no flag in the kernel (the table's
geometry then has no pockets or jaws), so it shares the kernel of the same
effects with pockets. A new combination compiles once and is cached on disk.
"""
from __future__ import annotations

import dataclasses


@dataclasses.dataclass(frozen=True)
class Effects:
    """Physics effects of a scene.

    - ``spin``: balls carry angular velocity. Off: point masses that roll
      from the start (rolling resistance only, no slide phase, frictionless
      collisions, no spin transfer).
    - ``sliding``: felt sliding friction acts over time. Off: a ball that
      would slide takes at once the rolling state its slide would end in
      (same final velocity by conservation of angular momentum about the
      contact point, zero slide time and distance).
    - ``vertical_spin``: spin about the vertical axis (side spin, english).
    - ``ball_friction``: ball-ball friction (throw and spin transfer; the
      ``Models`` friction law, constant mu_b by default).
    - ``cushion_friction``: cushion friction and spin (the ``Models``
      cushion model, Han 2005 by default); off: a plain reflection with the
      cushion restitution.
    - ``pockets``: six pockets with jaws; off: a closed box.
    - ``airborne``: balls leave the slate (an elevated cue's jump, flight
      under gravity, bounces on the slate, contacts in flight, balls driven
      off the table: ``airborne``, ``ball_ball.flight``, ``cushion.rail``;
      both solvers). Off, the default: the planar simulator, whose kernels
      it leaves as they are. An opt-in effect: ``each_off``, ``minimal``,
      ``key`` and ``to_dict`` name it only when it is on, so every set and
      record without it is what it was before it existed
      (docs/physics.md, "The third dimension").

    Rolling resistance is always on: without it no ball ever stops.
    """

    spin: bool = True
    sliding: bool = True
    vertical_spin: bool = True
    ball_friction: bool = True
    cushion_friction: bool = True
    pockets: bool = True
    airborne: bool = False

    @classmethod
    def all(cls) -> "Effects":
        return cls()

    @classmethod
    def minimal(cls) -> "Effects":
        return cls(spin=False, sliding=False, vertical_spin=False,
                   ball_friction=False, cushion_friction=False, pockets=False)

    @classmethod
    def each_off(cls) -> dict[str, "Effects"]:
        """All effects, each effect switched off alone, and the minimal set,
        by name: the sets the benchmark times and the fuzzer checks."""
        sets = {"all": cls.all()}
        for f in dataclasses.fields(cls):
            if f.name in OPT_IN:
                continue
            sets[f"no {f.name.replace('_', ' ')}"] = cls(**{f.name: False})
        sets["minimal"] = cls.minimal()
        return sets

    @classmethod
    def from_dict(cls, d: dict | None) -> "Effects":
        d = dict(d or {})
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = set(d) - names
        if unknown:
            raise ValueError(f"unknown effects {sorted(unknown)}; known: {sorted(names)}")
        for k, v in d.items():
            if not isinstance(v, bool):
                raise ValueError(f"effect {k!r} must be true or false, got {v!r}")
        return cls(**d)

    def normalized(self) -> "Effects":
        """Switch off what a disabled parent makes meaningless, so that
        equivalent settings share one compiled kernel."""
        if not self.spin:
            return dataclasses.replace(self, sliding=False, vertical_spin=False,
                                       ball_friction=False, cushion_friction=False)
        return self

    def key(self) -> tuple:
        n = self.normalized()
        key = (n.spin, n.sliding, n.vertical_spin, n.ball_friction, n.cushion_friction, n.pockets)
        return key + ("airborne",) if n.airborne else key

    def to_dict(self) -> dict:
        """The fields by name; an opt-in effect only when it is on."""
        return {k: v for k, v in dataclasses.asdict(self).items() if k not in OPT_IN or v}


# Effects that are off by default and that the sets and records above name
# only when on (``Effects`` docstring).
OPT_IN = ("airborne",)

"""Which model resolves each interaction.

Registries (name -> model module), one per interaction:
- ``ball_ball_friction``: ``ball_ball.FRICTION_LAWS``, the friction law of
  the Coulomb ball-ball model (used when ``Effects.ball_friction`` is on;
  off: frictionless impacts);
- ``cushion``: ``cushion.MODELS``, the cushion model with friction (used
  when ``Effects.cushion_friction`` is on; off: plain reflection).

The felt (sliding, rolling, spinning friction) has one model, ``motion``.
Docs: docs/models.md.
"""
from __future__ import annotations

import dataclasses

from . import ball_ball, cushion

REGISTRIES = {
    "ball_ball_friction": ball_ball.FRICTION_LAWS,
    "cushion": cushion.MODELS,
}


@dataclasses.dataclass(frozen=True)
class Models:
    """Model choice per interaction (names from ``REGISTRIES``); the
    defaults are the models the project has always used."""

    ball_ball_friction: str = "constant"
    cushion: str = "han2005"

    def __post_init__(self):
        for name, registry in REGISTRIES.items():
            value = getattr(self, name)
            if value not in registry:
                raise ValueError(f"unknown {name} model {value!r}; registered: {sorted(registry)}")

    @classmethod
    def from_dict(cls, d: dict | None) -> "Models":
        """From a mapping such as the YAML ``models:`` section; missing
        entries keep their defaults."""
        d = dict(d or {})
        unknown = set(d) - set(REGISTRIES)
        if unknown:
            raise ValueError(f"unknown model interactions {sorted(unknown)}; known: {sorted(REGISTRIES)}")
        return cls(**d)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)

    def key(self) -> tuple:
        return (self.ball_ball_friction, self.cushion)

    def resolved(self, effects) -> tuple[str, str]:
        """Names of the ball-ball and cushion models a kernel uses under
        ``effects`` (switched-off effects pick the frictionless models):
        equivalent choices share one compiled kernel."""
        n = effects.normalized()
        bb = f"coulomb/{self.ball_ball_friction}" if n.ball_friction else "frictionless"
        cu = self.cushion if n.cushion_friction else "reflection"
        return bb, cu

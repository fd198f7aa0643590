"""What a benchmark run measures: the options every section reads, and the
names of the sections."""
from __future__ import annotations

import dataclasses
from pathlib import Path

# the checkout holding this package (its git tree, results/benchmark)
ROOT = Path(__file__).resolve().parents[3]

# --only name -> the ``section`` of its rows ("games" writes its own table)
SECTION_NAMES = {"solver": "solver", "effects": "effects", "models": "models", "airborne": "airborne", "env": "env",
                 "cold": "cold start", "rllib": "rllib"}
DEFAULT_SECTIONS = ("solver", "effects", "env", "cold")


@dataclasses.dataclass(frozen=True)
class RunOptions:
    """``batch``: tables per simulator call; ``repeats``: timed repeats per
    figure; ``quick``: the sections' small sizes; ``scene``: keep only scenes
    (or env ids) containing one of these (None: all)."""
    batch: int = 1024
    repeats: int = 5
    quick: bool = False
    scene: tuple[str, ...] | None = None

    @classmethod
    def make(cls, batch: int | None = None, repeats: int | None = None, quick: bool = False, scene=None):
        """Unset sizes from ``quick``: batch 1024 / 64, repeats 5 / 2."""
        return cls(batch or (64 if quick else 1024), repeats or (2 if quick else 5), quick,
                   tuple(scene) if scene else None)

    def keeps(self, name: str) -> bool:
        return not self.scene or any(part in name for part in self.scene)

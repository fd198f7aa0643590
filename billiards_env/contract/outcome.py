"""``ShotOutcome``: what one shot did on each table of a one-player task,
before any rule is applied; what a task's ``judge`` reads, from the env's
step and from a bot's preview alike."""
from __future__ import annotations

import dataclasses

import numpy as np

from ..physics.constants import OFF_TABLE


@dataclasses.dataclass(frozen=True, eq=False)
class ShotOutcome:
    """What happened on one shot of each of ``n`` tables, before any rule is
    applied: arrays [n] unless noted. ``pocketed`` [n, B] marks the balls
    this shot put in a pocket (ball 0 the cue ball), ``off_table`` [n, B]
    those it drove off the table (``BallState.pocket`` >= ``OFF_TABLE``; only
    with the airborne effect; None: none); ``pocket_after`` [n, B] is
    ``BallState.pocket`` after it (-1 on the table, a pocket id, or an
    off-table code);
    ``first_contact`` the first ball the cue ball touched (-1 none);
    ``target`` the legal target before the shot (-1 none); for a task
    with ``contacts`` set, the cue ball's contacts in order (``contacts``
    [n, K, 2], ``n_contacts`` [n]: ``physics.SimResult``'s), else None."""

    pocketed: np.ndarray
    pocket_after: np.ndarray
    first_contact: np.ndarray
    target: np.ndarray
    contacts: np.ndarray | None = None
    n_contacts: np.ndarray | None = None
    off_table: np.ndarray | None = None

    def __post_init__(self):
        if self.off_table is None:
            object.__setattr__(self, "off_table", np.zeros(np.shape(self.pocketed), dtype=bool))

    @classmethod
    def of(cls, pocket_before: np.ndarray, pocket_after: np.ndarray, **fields) -> "ShotOutcome":
        """The outcome from ``BallState.pocket`` before and after the shot [n, B] (and the other ``fields``):
        balls in a pocket (codes 0 .. OFF_TABLE - 1) and balls off the table (OFF_TABLE and above) told apart."""
        was_on = np.asarray(pocket_before) < 0
        after = np.asarray(pocket_after)
        return cls(pocketed=(after >= 0) & (after < OFF_TABLE) & was_on, pocket_after=pocket_after,
                   off_table=(after >= OFF_TABLE) & was_on, **fields)

    @property
    def scratch(self) -> np.ndarray:
        """The cue ball was lost: pocketed, or driven off the table (WPA's "Cue Ball Scratch or off the Table")."""
        return self.pocketed[:, 0] | self.off_table[:, 0]

    @property
    def n_pocketed(self) -> np.ndarray:
        """Object balls pocketed by the shot."""
        return self.pocketed[:, 1:].sum(axis=1)

    @property
    def contact(self) -> np.ndarray:
        """The cue ball hit the legal target first."""
        return (self.first_contact == self.target) & (self.target > 0)

    @property
    def cleared(self) -> np.ndarray:
        """No object ball is left on the table."""
        return np.all(self.pocket_after[:, 1:] >= 0, axis=1)

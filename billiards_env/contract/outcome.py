"""``ShotOutcome``: what one shot did on each table of a one-player task,
before any rule is applied; what a task's ``judge`` reads, from the env's
step and from a bot's preview alike."""
from __future__ import annotations

import dataclasses

import numpy as np


@dataclasses.dataclass(frozen=True, eq=False)
class ShotOutcome:
    """What happened on one shot of each of ``n`` tables, before any rule is
    applied: arrays [n] unless noted. ``pocketed`` [n, B] marks the balls
    pocketed by this shot (ball 0 the cue ball); ``pocket_after`` [n, B] is
    the pocket id of every ball after it (-1 on the table);
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

    @property
    def scratch(self) -> np.ndarray:
        """The cue ball was pocketed."""
        return self.pocketed[:, 0]

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

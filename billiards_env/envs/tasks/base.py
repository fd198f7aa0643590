"""What a task is: the ``Task`` base class and the outcome of one shot.

A task is a small object (one instance per task, shared by every env of that
task) whose methods are batched functions over tables:

- ``validate(cfg)``: task-specific checks of a ``TaskConfig`` (ValueError);
- ``reset(core, idx)``: the start states of new episodes on tables ``idx``,
  drawn from the tables' own random streams (``core.streams``);
- ``legal_target(pos, pocket)``: the ball each table must hit first;
- ``judge(shot)``: foul, success and termination of the shots just played;
- ``reward_terms(w, shot, potential_before, potential_after)``: the reward,
  term by term.

``BilliardsCore`` (``envs/core.py``) does everything that does not depend on
the rules (actions, noise, simulation, observation) and calls these methods.
The class docstring of a task is its spec: the env classes built from it
(``envs/billiards.py``) use it as theirs, and ``docs/environments.md`` is
generated from it.
"""
from __future__ import annotations

import dataclasses
from importlib import resources
from pathlib import Path

import numba
import numpy as np

from ...contract.outcome import ShotOutcome  # noqa: F401  (a task judges it; defined with the bot contract)
from ...physics import BallState

# The tasks' default YAML files are package data, so an installed wheel finds them.
CONFIG_DIR = Path(str(resources.files("billiards_env.envs.tasks") / "defaults"))

REWARD_TERMS = ("pocket", "scratch", "foul", "contact", "success", "shaping")


@numba.njit(cache=True, nogil=True)
def lowest_ball_on_table(pocket, out):
    """Per table: the lowest-numbered object ball still on the table (-1 if none)."""
    for e in range(pocket.shape[0]):
        t = -1
        for b in range(1, pocket.shape[1]):
            if pocket[e, b] < 0:
                t = b
                break
        out[e] = t


@dataclasses.dataclass(frozen=True, eq=False)
class Judgement:
    """A task's ruling on the shots of ``ShotOutcome``: bool arrays [n]."""

    foul: np.ndarray
    success: np.ndarray
    terminated: np.ndarray


class Task:
    """Base class of the tasks (subclass it; see ``pot_one.py`` for a short one).

    Class attributes: ``name`` (the ``task`` key of the YAML config),
    ``env_id`` (the Gymnasium id), ``class_prefix`` (env classes
    ``<prefix>Env`` and ``<prefix>VectorEnv``) and ``config_path`` (the
    default YAML; ``None``: ``billiards_env/envs/tasks/defaults/<name>.yaml``); ``reward_names``
    the keys ``reward_terms`` returns (default ``REWARD_TERMS``).
    """

    name: str = ""
    env_id: str = ""
    class_prefix: str = ""
    config_path: Path | None = None
    reward_names: tuple = REWARD_TERMS  # the keys of reward_terms, in order
    contacts: int = 0  # the cue ball's contacts kept in order for ``judge`` (``ShotOutcome.contacts``); 0 none

    # --- configuration ------------------------------------------------------
    @property
    def default_config_path(self) -> Path:
        return Path(self.config_path) if self.config_path is not None else CONFIG_DIR / f"{self.name}.yaml"

    def validate(self, cfg) -> None:
        """Task-specific checks of a ``TaskConfig`` (raise ``ValueError``); none by default."""

    # --- episodes -----------------------------------------------------------
    def reset(self, core, idx: np.ndarray) -> BallState:
        """Start states (balls at rest) of new episodes on tables ``idx``."""
        raise NotImplementedError

    # --- rules --------------------------------------------------------------
    def legal_target(self, pos: np.ndarray, pocket: np.ndarray) -> np.ndarray:
        """The ball each table must hit first, int64 [n] (-1 if none): by
        default the lowest-numbered object ball on the table."""
        out = np.empty(len(pocket), dtype=np.int64)
        lowest_ball_on_table(pocket, out)
        return out

    def judge(self, shot: ShotOutcome) -> Judgement:
        raise NotImplementedError

    def reward_terms(self, w, shot: ShotOutcome, judged: Judgement, potential_before: np.ndarray,
                     potential_after: np.ndarray) -> dict:
        """The reward terms (``REWARD_TERMS``, weights ``w``: a ``RewardConfig``),
        float64 arrays [n]: ``pocket`` per object ball pocketed on a legal shot
        (no foul, no scratch), ``scratch``, ``foul``, ``contact`` (legal target
        hit first), ``success`` and ``shaping`` = w * (gamma Phi(s') - Phi(s))
        with Phi(s') = 0 in terminal states."""
        scratch = shot.scratch
        legal = ~judged.foul & ~scratch
        phi1 = np.where(judged.terminated, 0.0, potential_after)
        terms = {
            "pocket": w.pocket * shot.n_pocketed * legal,
            "scratch": w.scratch * scratch,
            "foul": w.foul * judged.foul,
            "contact": w.contact * shot.contact,
            "success": w.success * judged.success,
            "shaping": w.shaping * (w.gamma * phi1 - potential_before),
        }
        return {k: v + 0.0 for k, v in terms.items()}  # float64 (weights are floats); + 0.0: no negative zeros

    def __repr__(self) -> str:
        return f"{type(self).__name__}(name={self.name!r}, env_id={self.env_id!r})"


def random_tables(core, idx: np.ndarray) -> BallState:
    """Balls at uniformly random, non-overlapping positions (``core.place``)."""
    return BallState.from_positions(core.place(idx))


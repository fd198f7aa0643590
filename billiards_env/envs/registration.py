"""Registration of the Billiards tasks with Gymnasium (also the
``gymnasium.envs`` entry point declared in pyproject.toml).

The ids come from the task registry (``envs/tasks/``): registering a task
registers its id, so ``register_envs`` only makes sure every registered
task's id is known to Gymnasium (idempotent).
"""
from __future__ import annotations

from .tasks import TASKS, register_gym_ids

# The built-in ids and their (single-table, vector) class names, as registered at import.
ENV_IDS = {t.env_id: (f"{t.class_prefix}Env", f"{t.class_prefix}VectorEnv") for t in TASKS.values()}


def register_envs() -> None:
    """Register every task's Gymnasium id (idempotent)."""
    register_gym_ids()

"""Registration of the Billiards tasks with Gymnasium, done when
``billiards_env`` is imported (``billiards_env/__init__.py``).

Gymnasium 1.x loads no plugins: an id is known once the module that
registers it is imported. So either ``import billiards_env`` before
``gym.make("Billiards-PotOne-v1")``, or name the module in the id,
``gym.make("billiards_env:Billiards-PotOne-v1")`` (Gymnasium imports the
part before the colon first; ``gym.make_vec`` too).

The ids come from the task registry (``envs/tasks/``): registering a task
registers its id, so ``register_envs`` only makes sure every registered
task's id is known to Gymnasium (idempotent).
"""
from __future__ import annotations

from .tasks import TASKS, register_gym_ids

# The built-in ids and their (single-table, vector) class names, as registered at import.
ENV_IDS = {t.env_id: (f"{t.class_prefix}Env", f"{t.class_prefix}VectorEnv") for t in TASKS.values()}


def game_ids() -> dict:
    """Every registered two-player game's id -> (single-agent class against a fixed opponent, vector entry point),
    from the games' registry (``rules.games``; ``envs.games.catalog`` generates the classes)."""
    from ..rules import GAMES
    from .games.catalog import entry_points
    return {spec.env_id: entry_points(name) for name, spec in GAMES.items()}


# The built-in games' ids, as registered at import.
GAME_IDS = game_ids()


def register_envs() -> None:
    """Register every task's Gymnasium id and every registered game's (idempotent: call it again after
    ``register_game`` to register a game added later)."""
    from gymnasium.envs.registration import register, registry

    register_gym_ids()
    for env_id, (entry, vector) in game_ids().items():
        if env_id not in registry:
            register(id=env_id, entry_point=entry, vector_entry_point=vector)

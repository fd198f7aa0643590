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


# The two-player games: id -> (single-agent class against a fixed opponent, self-play vector entry point).
GAME_IDS = {
    "Billiards-NineBall2P-v1": ("billiards_env.envs.games.single:NineBall2PEnv",
                                "billiards_env.envs.games.vector:nine_ball_vector"),
    "Billiards-EightBall-v1": ("billiards_env.envs.games.single:EightBallEnv",
                               "billiards_env.envs.games.vector:eight_ball_vector"),
    "Billiards-TenBall-v1": ("billiards_env.envs.games.single:TenBallEnv",
                             "billiards_env.envs.games.vector:ten_ball_vector"),
    "Billiards-ThreeCushion-v1": ("billiards_env.envs.games.single:ThreeCushionEnv",
                                  "billiards_env.envs.games.vector:three_cushion_vector"),
    "Billiards-Snooker-v1": ("billiards_env.envs.games.single:SnookerEnv",
                             "billiards_env.envs.games.vector:snooker_vector"),
}


def register_envs() -> None:
    """Register every task's Gymnasium id and the two-player games' (idempotent)."""
    from gymnasium.envs.registration import register, registry

    register_gym_ids()
    for env_id, (entry, vector) in GAME_IDS.items():
        if env_id not in registry:
            register(id=env_id, entry_point=entry, vector_entry_point=vector)

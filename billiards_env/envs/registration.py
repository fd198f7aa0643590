"""Registration of the Billiards tasks with Gymnasium (also the
``gymnasium.envs`` entry point declared in pyproject.toml)."""
from __future__ import annotations

ENV_IDS = {
    "Billiards-PotOne-v0": ("PotOneEnv", "PotOneVectorEnv"),
    "Billiards-RunOut-v0": ("RunOutEnv", "RunOutVectorEnv"),
    "Billiards-NineBall-v0": ("NineBallEnv", "NineBallVectorEnv"),
}


def register_envs() -> None:
    """Register every task (idempotent)."""
    from gymnasium.envs.registration import register, registry

    for env_id, (single, vector) in ENV_IDS.items():
        if env_id in registry:
            continue
        register(id=env_id, entry_point=f"billiards_env.envs.billiards:{single}",
                 vector_entry_point=f"billiards_env.envs.billiards:{vector}")

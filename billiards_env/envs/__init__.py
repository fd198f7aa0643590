"""Gymnasium environments over the batched billiards simulator."""
from .billiards import (BilliardsEnv, BilliardsVectorEnv, NineBallEnv, NineBallVectorEnv, PotOneEnv,
                        PotOneVectorEnv, RunOutEnv, RunOutVectorEnv)
from .config import NoiseConfig, RewardConfig, TaskConfig
from .registration import ENV_IDS, register_envs

__all__ = ["BilliardsEnv", "BilliardsVectorEnv", "PotOneEnv", "PotOneVectorEnv", "RunOutEnv", "RunOutVectorEnv",
           "NineBallEnv", "NineBallVectorEnv", "TaskConfig", "RewardConfig", "NoiseConfig", "ENV_IDS",
           "register_envs"]

"""Gymnasium environments over the batched billiards simulator."""
from ..physics.strike import Shots, draw_to_speed, speed_to_draw
from .billiards import (BilliardsEnv, BilliardsVectorEnv, NineBallEnv, NineBallVectorEnv, PotOneEnv,
                        PotOneVectorEnv, RunOutEnv, RunOutVectorEnv, env_classes)
from .config import NoiseConfig, RewardConfig, TaskConfig
from .core import ShotContext
from .registration import ENV_IDS, register_envs
from .tasks import TASKS, Task, get_task, register_task

__all__ = ["BilliardsEnv", "BilliardsVectorEnv", "PotOneEnv", "PotOneVectorEnv", "RunOutEnv", "RunOutVectorEnv",
           "NineBallEnv", "NineBallVectorEnv", "env_classes", "TaskConfig", "RewardConfig", "NoiseConfig",
           "ENV_IDS", "register_envs", "Task", "TASKS", "register_task", "get_task", "Shots", "ShotContext",
           "draw_to_speed", "speed_to_draw"]

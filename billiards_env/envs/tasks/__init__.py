"""The tasks: one module per task, registered here (one line per task).

Adding a task: a module holding a ``Task`` subclass (its spec as the class
docstring), a YAML file ``billiards_env/envs/tasks/defaults/<name>.yaml`` with its defaults, and
one ``register_task(...)`` line (here, or in your own code for a task
defined outside the package). See docs/adding_a_task.md.
"""
from .base import REWARD_TERMS, Judgement, ShotOutcome, Task
from .nine_ball import NineBall
from .pot_one import PotOne
from .registry import TASKS, get_task, register_gym_ids, register_task
from .run_out import RunOut
from .three_cushion_point import ThreeCushionPoint

register_task(PotOne())
register_task(RunOut())
register_task(NineBall())
register_task(ThreeCushionPoint())

__all__ = ["Task", "ShotOutcome", "Judgement", "REWARD_TERMS", "TASKS", "register_task", "get_task",
           "register_gym_ids", "PotOne", "RunOut", "NineBall", "ThreeCushionPoint"]

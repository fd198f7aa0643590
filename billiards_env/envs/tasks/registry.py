"""The task registry: task name -> ``Task``; registering a task also
registers its Gymnasium id (``entry_point`` and ``vector_entry_point`` side
by side, both classes generated from the task by ``envs/billiards.py``)."""
from __future__ import annotations

from .base import Task

TASKS: dict[str, Task] = {}
ENV_MODULE = "billiards_env.envs.billiards"  # where the generated env classes live


def register_task(task: Task, *, replace: bool = False) -> Task:
    """Add ``task`` (an instance of a ``Task`` subclass) to the registry and
    register ``task.env_id`` with Gymnasium. Registering the same task class
    again is a no-op; another task under a taken name or id needs ``replace=True``."""
    if not isinstance(task, Task):
        raise TypeError(f"register_task takes a Task instance, got {type(task).__name__}")
    for attr in ("name", "env_id", "class_prefix"):
        if not isinstance(getattr(task, attr), str) or not getattr(task, attr):
            raise ValueError(f"{type(task).__name__}.{attr} must be a non-empty string")
    old = TASKS.get(task.name)
    clash = [t for t in TASKS.values() if t.env_id == task.env_id and t.name != task.name]
    if not replace:
        if old is not None and type(old) is not type(task):
            raise ValueError(f"task name {task.name!r} is taken by {old!r} (pass replace=True)")
        if clash:
            raise ValueError(f"env id {task.env_id!r} is taken by {clash[0]!r}")
    if old is not None and type(old) is type(task) and not replace:
        return old
    TASKS[task.name] = task
    _register_gym_id(task, force=replace)
    return task


def _register_gym_id(task: Task, force: bool = False) -> None:
    from gymnasium.envs.registration import register, registry

    if task.env_id in registry and not force:
        return
    if task.env_id in registry:
        del registry[task.env_id]
    register(id=task.env_id, entry_point=f"{ENV_MODULE}:{task.class_prefix}Env",
             vector_entry_point=f"{ENV_MODULE}:{task.class_prefix}VectorEnv")


def register_gym_ids() -> None:
    """(Re-)register the Gymnasium id of every registered task (idempotent)."""
    for task in TASKS.values():
        _register_gym_id(task)


def get_task(name: str) -> Task:
    """The registered task ``name`` (ValueError naming the registered ones otherwise)."""
    try:
        return TASKS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown task {name!r}; registered tasks: {sorted(TASKS)}") from None

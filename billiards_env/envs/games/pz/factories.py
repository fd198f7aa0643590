"""``env``, ``raw_env`` and ``parallel_env`` of one game, from its AEC class.

The games are turn-based, and a player who scores shoots again, so the
agents do not take turns in a fixed cycle: PettingZoo's ``aec_to_parallel``
(which steps every agent once per cycle, in order) does not apply. The
``ParallelEnv`` is PettingZoo's turn-based conversion
(``turn_based_aec_to_parallel``): ``step(actions)`` plays the action of the
agent to move only, and every other action is ignored; ``infos[agent]
["active_agent"]`` names the agent to move after ``reset`` and after every
step (the observation says it too).
"""
from __future__ import annotations

from pettingzoo.utils.conversions import turn_based_aec_to_parallel_wrapper
from pettingzoo.utils.wrappers import OrderEnforcingWrapper


class TurnBasedParallelEnv(turn_based_aec_to_parallel_wrapper):
    """PettingZoo's turn-based ``ParallelEnv`` over an AEC game; its
    ``reset`` names the agent to move (``infos[agent]["active_agent"]``), as
    its ``step`` does."""

    def reset(self, seed=None, options=None):
        observations, infos = super().reset(seed=seed, options=options)
        infos = {agent: {**info, "active_agent": self.aec_env.agent_selection} for agent, info in infos.items()}
        return observations, infos


def factories(aec_class):
    """The module-level ``(env, raw_env, parallel_env)`` of ``aec_class``;
    each takes what the class takes (a ``GameConfig`` or its fields as
    keywords, e.g. ``max_shots=40``)."""
    name = aec_class.metadata["name"]

    def raw_env(config=None, **overrides):
        return aec_class(config, **overrides)

    def env(config=None, **overrides):
        return OrderEnforcingWrapper(raw_env(config, **overrides))

    def parallel_env(config=None, **overrides):
        return TurnBasedParallelEnv(raw_env(config, **overrides))

    raw_env.__doc__ = f"``{name}``: the AEC env ``{aec_class.__name__}`` itself, unwrapped."
    env.__doc__ = f"``{name}``: the AEC env in PettingZoo's ``OrderEnforcingWrapper`` (reset before step, and so on)."
    parallel_env.__doc__ = (f"``{name}``: a turn-based ``ParallelEnv``; each step plays the action of the agent to "
                            "move (``infos[agent]['active_agent']``) and ignores the others (``factories`` module).")
    return env, raw_env, parallel_env

"""The games' PettingZoo modules (``billiards_env.envs.games.pz``): every
module's ``env()``, ``raw_env()`` and ``parallel_env()`` pass PettingZoo's
own checks, and the turn-based ``parallel_env`` plays exactly the AEC game,
the acting agent's action only."""
import importlib

import numpy as np
import pytest

pytest.importorskip("pettingzoo")
from pettingzoo import AECEnv, ParallelEnv  # noqa: E402
from pettingzoo.test import api_test, parallel_api_test  # noqa: E402

from billiards_env.envs.games.pz import MODULES  # noqa: E402

MAX_SHOTS = 40  # games cut short keep the API checks fast
CYCLES = 300  # AEC steps (api_test) and parallel steps (parallel_api_test) per check
SHORT = {"three_cushion_v0": {"rule_options": {"max_innings": 6}}}  # three-cushion has no max_shots cut of its own


def _game(name):
    return importlib.import_module(f"billiards_env.envs.games.pz.{name}")


def _kwargs(name):
    return dict(max_shots=MAX_SHOTS, **SHORT.get(name, {}))


@pytest.mark.parametrize("name", MODULES)
def test_factories_and_api(name):
    game = _game(name)
    raw = game.raw_env(**_kwargs(name))
    assert isinstance(raw, AECEnv) and raw.metadata["name"] == f"billiards_{name}"
    assert game.env().unwrapped.__class__ is raw.__class__
    api_test(game.env(**_kwargs(name)), num_cycles=CYCLES, verbose_progress=False)
    par = game.parallel_env(**_kwargs(name))
    assert isinstance(par, ParallelEnv) and par.unwrapped.__class__ is raw.__class__
    parallel_api_test(par, num_cycles=CYCLES)


@pytest.mark.parametrize("name", ["nine_ball_v0", "three_cushion_v0"])
def test_parallel_env_plays_the_acting_agents_action_only(name):
    """Seeded alike, the parallel env given a random action for every agent
    and the AEC env given the acting agent's action only play the same game;
    ``infos[agent]["active_agent"]`` is the AEC env's ``agent_selection``."""
    game = _game(name)
    par, aec = game.parallel_env(**_kwargs(name)), game.raw_env(**_kwargs(name))
    obs, infos = par.reset(seed=5)
    aec.reset(seed=5)
    rng = np.random.default_rng(0)
    for _ in range(12):
        if not par.agents:
            break
        mover = aec.agent_selection
        assert all(infos[a]["active_agent"] == mover for a in par.agents)
        np.testing.assert_array_equal(obs[mover], aec.observe(mover))
        actions = {a: rng.uniform(-1, 1, par.action_space(a).shape).astype(np.float32) for a in par.agents}
        obs, rewards, terms, truncs, infos = par.step(actions)
        aec.step(actions[mover])
        assert rewards == aec.rewards

"""Gymnasium as its users expect it: an id with the module named in it
(``billiards_env:Billiards-...``) in a process that has not imported the
package, and ``make_vec(..., vectorization_mode="async")`` (forked workers)
in a process that has already run the simulator."""
import os
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401 (registers the ids)
from billiards_env.physics import forking

ROOT = Path(__file__).resolve().parents[2]
ID = "Billiards-PotOne-v1"
FRESH_PROCESS_TIMEOUT_S = 600  # imports, and the kernel's compile on a cold cache


def test_make_with_the_module_in_the_id_in_a_fresh_process():
    code = ("import sys, gymnasium as gym\n"
            "assert 'billiards_env' not in sys.modules\n"
            f"env = gym.make('billiards_env:{ID}')\n"
            "obs, info = env.reset(seed=0)\n"
            "env.step(env.action_space.sample())\n"
            f"vec = gym.make_vec('billiards_env:{ID}', num_envs=3, vectorization_mode='vector_entry_point')\n"
            "print(type(env.unwrapped).__name__, vec.num_envs, obs.shape)\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=FRESH_PROCESS_TIMEOUT_S)
    assert out.returncode == 0, out.stderr[-3000:]
    assert out.stdout.split()[:2] == ["PotOneEnv", "3"]


def test_extra_methods_are_on_unwrapped():
    """``gym.make`` wraps the env; its own methods are on ``env.unwrapped``
    (Gymnasium's convention, docs/environments.md)."""
    env = gym.make(ID)
    env.reset(seed=0)
    assert not hasattr(env, "shot_context")
    for name in ("view", "actions_of", "actions_to_shots", "shot_context"):
        assert callable(getattr(env.unwrapped, name))
    assert env.get_wrapper_attr("shot_context") == env.unwrapped.shot_context


@pytest.mark.skipif(not hasattr(os, "fork"), reason="needs fork(2)")
def test_async_vector_env_after_the_simulator_ran_here():
    """This process has run the simulator (its OpenMP threads started); the
    async vector env's forked workers run the serial kernels and play as the
    sync vector env does, bit for bit."""
    single = gym.make(ID)
    single.reset(seed=1)
    single.step(single.action_space.sample())
    assert forking.threads_usable()
    sync = gym.make_vec(ID, num_envs=2, vectorization_mode="sync")
    asyn = gym.make_vec(ID, num_envs=2, vectorization_mode="async")
    try:
        assert asyn.metadata.get("autoreset_mode") == sync.metadata.get("autoreset_mode")
        a, b = asyn.reset(seed=7)[0], sync.reset(seed=7)[0]
        assert np.array_equal(a, b)
        rng = np.random.default_rng(0)
        for _ in range(3):
            actions = rng.uniform(-1, 1, asyn.action_space.shape).astype(np.float32)
            got, want = asyn.step(actions), sync.step(actions)
            for x, y in zip(got[:4], want[:4]):
                assert np.array_equal(x, y)
    finally:
        asyn.close()
        sync.close()

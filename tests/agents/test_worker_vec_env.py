"""The training tables split over worker processes (agents.sb3.worker_vec_env)."""
from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.config import load_config  # noqa: E402
from agents.sb3.checkpoints import restore_streams, stream_state  # noqa: E402
from agents.sb3.training import build_env, table_spec  # noqa: E402
from agents.sb3.worker_vec_env import WorkerVecEnv, cpu_seconds, find_workers  # noqa: E402

GAMES = "configs/ppo_games.yaml"
N_ENVS, STEPS, SEED = 8, 6, 7


def _cfg(*sets):
    # the agent against ghost (GameVersusVectorEnv): tables whose opponents draw random numbers too
    return load_config(GAMES, "Billiards-NineBall2P-v1", [f"n_envs={N_ENVS}", "env_kwargs={opponent: ghost}",
                                                          "normalize.obs=false", "normalize.reward=false", *sets])


def _play(env, actions):
    env.seed(SEED)
    out = [env.reset()]
    for a in actions:
        env.step_async(a)
        out.append(env.step_wait())
    return out


def test_two_workers_deal_the_tables_of_one_process():
    """Same seed: the same racks as the tables in this process (table i of
    worker j is table j * n/2 + i, its stream keyed alike), then steps of the
    same form in table order. The opponents' own random choices come from
    one generator per worker (GameVersusVectorEnv), so the games then differ."""
    cfg = _cfg()
    one = table_spec(cfg).build(N_ENVS, None)
    two = WorkerVecEnv(table_spec(cfg), N_ENVS, 2)
    try:
        assert two.observation_space == one.observation_space and two.action_space == one.action_space
        one.action_space.seed(0)
        actions = [np.array([one.action_space.sample() for _ in range(N_ENVS)]) for _ in range(STEPS)]
        a, b = _play(one, actions), _play(two, actions)
        np.testing.assert_array_equal(a[0], b[0])
        np.testing.assert_array_equal(stream_state(one)[0], stream_state(two)[0])
        for (obs1, rew1, done1, info1), (obs2, rew2, done2, info2) in zip(a[1:], b[1:]):
            assert obs2.shape == obs1.shape and obs2.dtype == obs1.dtype and rew2.dtype == rew1.dtype
            assert done2.shape == (N_ENVS,) and len(info2) == N_ENVS and info2[0].keys() >= {"success", "foul"}
            for i in np.flatnonzero(done2):
                assert info2[i]["terminal_observation"].shape == obs2.shape[1:]
        assert sum(d.sum() for _, _, d, _ in b[1:]) > 0, "no game ended: terminal observations went untested"
        total, critical = cpu_seconds(two)  # both workers played: each adds CPU to the total
        workers = two.worker_cpu_seconds()
        assert len(workers) == 2 and min(workers) > 0 and total > critical > max(workers)
        assert len(set(cpu_seconds(one))) == 1  # no workers: the critical path is the total
        assert two.get_attr("render_mode") == [None] * N_ENVS
    finally:
        one.close()
        two.close()


def test_restored_streams_come_back_in_every_worker():
    """restore_streams gives each worker its slice of the saved keys and
    counters, however far the play has moved them."""
    cfg = _cfg("train.env_workers=2")
    env, _ = build_env(cfg, SEED)
    try:
        assert find_workers(env) is not None
        env.reset()
        saved = stream_state(env)
        other = (saved[0][::-1].copy(), saved[1] + np.arange(N_ENVS, dtype=saved[1].dtype))  # every row differs
        for state in (other, saved):
            restore_streams(env, *state)
            for x, y in zip(stream_state(env), state):
                np.testing.assert_array_equal(x, y)
            env.step_async(np.array([env.action_space.sample() for _ in range(N_ENVS)]))
            env.step_wait()
    finally:
        env.close()


def test_workers_that_do_not_divide_the_tables_are_an_error():
    with pytest.raises(ValueError, match="env_workers"):
        _cfg("train.env_workers=3")
    with pytest.raises(ValueError, match="do not split evenly"):
        WorkerVecEnv(table_spec(_cfg()), N_ENVS, 3)


def test_a_failing_worker_names_its_error():
    spec = table_spec(_cfg())._replace(env_id="Billiards-NoSuchGame-v1")
    with pytest.raises(RuntimeError, match="(?s)env worker 0 failed.*NoSuchGame"):
        WorkerVecEnv(spec, N_ENVS, 2)


def test_training_in_workers_checkpoints_and_resumes(tmp_path):
    """A run whose tables live in two workers (and whose updates overlap the
    rollouts: agents.sb3.overlap) writes checkpoints with every table's
    streams and resumes from them to the configured step count."""
    from agents.sb3.checkpoints import latest_checkpoint
    from agents.sb3.training import train

    sets = ["ppo.n_steps=4", "ppo.batch_size=32", "ppo.n_epochs=1", "policy.net_arch=[16]",  # rollouts of 32
            "train.env_workers=2", "train.overlap_updates=true", "train.checkpoint_every=32", "train.eval_every=0",
            "train.eval_episodes=0",
            "train.progress_bar=false", "train.tensorboard=false"]
    first = train(_cfg(*sets, "train.total_timesteps=64"), tmp_path, "pytest")
    ck = latest_checkpoint(tmp_path)
    assert first["timesteps"] == 64 and ck is not None and ck.steps == 32
    with np.load(ck.normalizer_path) as z:
        assert len(z["stream_keys"]) == N_ENVS
    again = train(_cfg(*sets, "train.total_timesteps=96"), tmp_path, "pytest", resume=True)
    assert again["resumed"]["from_step"] == ck.steps == 32 and again["timesteps"] == 96

"""The Ray RLlib backend and distributed evaluation (agents.rllib.backend,
agents.rllib.evaluation): local training through the native vector entry point, a
checkpoint loaded into the evaluation harness, a two-node cluster on one
machine, distributed evaluation equal to local evaluation, an EnvRunner
killed mid-run, and resuming a stopped run.

The Ray tests need ``ray[rllib]`` (the ``ray`` extra). Without it they are
skipped, except under CI (environment variable ``CI`` set), where a missing
Ray fails. Every Ray instance here is small (one or two CPUs) and shut down
after use.
"""
from __future__ import annotations

import csv
import math
import os
import signal
import time

import numpy as np
import pytest

from agents.config import load_config

# one Ray user at a time: with pytest-xdist, every test of this group runs in the same worker, one after another
pytestmark = pytest.mark.xdist_group("ray")

# Tiny runs: 2 EnvRunners x 16 tables, 64-step batches, one SGD pass.
TINY = ["rllib.num_env_runners=2", "rllib.num_envs_per_env_runner=16", "rllib.train_batch_size_per_learner=64",
        "rllib.minibatch_size=64", "rllib.num_epochs=1", "train.progress_bar=false", "train.tensorboard=false"]


@pytest.fixture(scope="module")
def local_ray(ray_module):
    """A local Ray instance with 2 CPUs (one per EnvRunner), shared by this
    module's tests and shut down after them (the two-node test, last, makes
    its own cluster)."""
    ray = ray_module
    ray.shutdown()
    from agents.rllib.backend import start_ray
    start_ray(num_cpus=2)
    yield ray
    ray.shutdown()


def _cfg(*extra):
    return load_config(None, "Billiards-PotOne-v1", TINY + list(extra))


def _progress(run_dir) -> list[dict]:
    with open(run_dir / "progress.csv") as f:
        return list(csv.DictReader(f))


# ------------------------------------------------------------ no ray needed --
def test_vector_features_wrapper_matches_the_sb3_wrapper():
    """The Gymnasium wrapper the EnvRunners step gives the observations and
    env actions of the SB3 wrapper on the same seeded tables."""
    import gymnasium as gym

    import billiards_env  # noqa: F401
    from agents.interface.features import ShotFeatures, VectorShotFeatures
    from agents.sb3.vec_env import make_sb3_vec_env

    n = 8
    sb3 = make_sb3_vec_env("Billiards-PotOne-v1", n, seed=3)
    sb3 = ShotFeatures(sb3, sb3.unwrapped, True, 0.004, "residual")
    venv = VectorShotFeatures(gym.make_vec("Billiards-PotOne-v1", num_envs=n, vectorization_mode="vector_entry_point",
                                           autoreset_mode="next_step"), True, 0.004, "residual")
    obs_a = sb3.reset()
    obs_b, _ = venv.reset(seed=3)
    assert venv.single_observation_space.shape == (obs_a.shape[1],)
    np.testing.assert_array_equal(obs_a, obs_b)
    acts = np.random.default_rng(0).uniform(-1, 1, (n, 4)).astype(np.float32)
    _, r_a, d_a, _ = sb3.step(acts)
    obs_b, r_b, term, trunc, _ = venv.step(acts)
    np.testing.assert_array_equal(r_a, np.asarray(r_b, dtype=np.float32))  # the SB3 adapter hands out float32
    assert (d_a == (term | trunc)).all() and d_a.all()
    obs_b, *_ = venv.step(acts)  # next-step autoreset: the new tables, with their features
    assert obs_b.shape == obs_a.shape and np.isfinite(obs_b).all()


# ---------------------------------------------------------------- ray tests --
def test_local_run_steps_the_vector_env_and_loads_into_the_harness(local_ray, tmp_path):
    from agents.evaluation.harness import evaluate, load_trained
    from agents.rllib.backend import train
    from agents.rllib.policy import RLlibPolicy, checkpoints

    run = tmp_path / "run"
    s = train(_cfg("train.total_timesteps=192", "train.checkpoint_every=64"), run, "test")
    # each EnvRunner steps the task's own batched vector env (one simulator
    # call for its 16 tables), not Gymnasium's per-env SyncVectorEnv loop
    assert len(s["env_runners"]) == 2
    for r in s["env_runners"]:
        assert r["env_class"] == "PotOneVectorEnv" and r["num_envs"] == 16
    rows = _progress(run)
    assert len(rows) >= 3 and int(rows[-1]["timesteps"]) >= 192
    assert all(math.isfinite(float(r["mean_reward"])) for r in rows)
    assert all(0.0 <= float(r["success_rate"]) <= 1.0 for r in rows)
    assert len(checkpoints(run)) >= 3
    for name in ("config.yaml", "command.txt", "train_summary.json"):
        assert (run / name).exists()
    policy = load_trained(run)
    assert isinstance(policy, RLlibPolicy)
    res = evaluate(lambda env: policy.bind(env), "Billiards-PotOne-v1", 64, 12345, "none", name=policy.name)
    assert res.n_episodes == 64 and math.isfinite(res.mean_reward)
    # the policy is deterministic: the same seeds give the same episodes
    again = evaluate(lambda env: policy.bind(env), "Billiards-PotOne-v1", 64, 12345, "none")
    assert again.per_episode == res.per_episode
    # a trained residual policy stays near the ghost-ball shot: far above random (~3%)
    assert res.success_rate > 0.3


def test_unknown_rllib_setting_is_an_error_naming_it(ray_module):
    from agents.rllib.backend import algo_config

    with pytest.raises(ValueError, match="learning_rate"):
        algo_config(_cfg("rllib.learning_rate=1e-3"))
    with pytest.raises(ValueError, match="num_envs_per_env_runner"):
        algo_config(_cfg("rllib.num_envs_per_env_runner=0"))


def test_distributed_evaluation_equals_local(local_ray, tmp_path):
    from agents.evaluation.harness import evaluate_policies
    from agents.rllib.evaluation import evaluate_spec

    specs = ["random", "ghost", "search8"]
    kw = dict(env_id="Billiards-PotOne-v1", n_episodes=48, seed=777, noises=["none", "tournament"], batch_size=16)
    local = evaluate_policies(specs, **kw)
    dist = evaluate_policies(specs, **kw, run=evaluate_spec)
    assert [r.policy for r in dist] == [r.policy for r in local]
    for a, b in zip(local, dist):
        assert a.per_episode == b.per_episode, (a.policy, a.noise)
        assert a.success_rate == b.success_rate and a.mean_reward == b.mean_reward


def test_killed_env_runner_is_restarted_and_training_continues(local_ray):
    from ray.rllib.utils.metrics import ENV_RUNNER_RESULTS, NUM_ENV_STEPS_SAMPLED_LIFETIME

    from agents.rllib.backend import algo_config, env_runner_facts

    algo = algo_config(_cfg()).build_algo()
    try:
        steps = lambda res: res[ENV_RUNNER_RESULTS][NUM_ENV_STEPS_SAMPLED_LIFETIME]  # noqa: E731
        before = steps(algo.train())
        pids = [f["pid"] for f in env_runner_facts(algo)]
        assert len(pids) == 2
        os.kill(pids[0], signal.SIGKILL)
        after = before
        deadline = time.time() + 180
        while time.time() < deadline:
            after = steps(algo.train())
            if algo.env_runner_group.num_healthy_remote_env_runners() == 2 and after >= before + 3 * 64:
                break
        assert after >= before + 3 * 64  # training went on
        new_pids = [f["pid"] for f in env_runner_facts(algo)]
        assert len(new_pids) == 2 and pids[0] not in new_pids  # the dead runner was replaced
    finally:
        algo.stop()


def test_resume_continues_from_the_last_checkpoint(local_ray, tmp_path):
    from agents.rllib.backend import train
    from agents.rllib.policy import checkpoints

    run = tmp_path / "run"
    cfg = _cfg("train.total_timesteps=256", "train.checkpoint_every=128")
    first = train(cfg, run, "first", stop_after_iterations=2)
    assert first["timesteps"] == 128 and [c.name for c in checkpoints(run)] == ["steps_128"]
    second = train(cfg, run, "second", resume=True)
    assert second["timesteps"] >= 256
    steps = [int(r["timesteps"]) for r in _progress(run)]
    assert steps == sorted(steps) and steps[0] == 64 and steps[-1] >= 256  # one log, no step twice
    assert (run / "command.txt").read_text().split() == ["first", "second"]


# ------------------------------------------------------------ lean sampling --
def test_push_batch_equals_rllibs_pushes_row_by_row(ray_module):
    """``push_batch`` leaves RLlib's ``RunningStat`` (count, mean, sum of
    squared deviations and their deltas since the last merge) as pushing the
    rows one by one does, from an empty stat and after a merge reset."""
    from ray.rllib.utils.filter import RunningStat

    from agents.rllib.sampling import push_batch

    rng = np.random.default_rng(0)
    one, batched = RunningStat((5,)), RunningStat((5,))
    for k, m in enumerate((1, 7, 300, 2)):
        x = rng.normal(3.0, 2.0, (m, 5))
        for row in x:
            one.push(row)
        push_batch(batched, x)
        if k == 1:  # what a merge does to the deltas
            for rs in (one, batched):
                rs.num_pushes_delta = 0
                rs.mean_delta_array[:] = 0.0
                rs.sum_sq_diff_delta_array[:] = 0.0
    assert batched.num_pushes == one.num_pushes == 310 and batched.num_pushes_delta == one.num_pushes_delta == 302
    for field in ("mean_array", "mean_delta_array", "sum_sq_diff_array", "sum_sq_diff_delta_array"):
        np.testing.assert_allclose(getattr(batched, field), getattr(one, field), rtol=1e-12, atol=1e-9)


def test_lean_observation_filter_matches_rllibs_filter(ray_module):
    """The batched filter ends each step with RLlib's filter state, scales
    every table with the statistics after the step (RLlib's filter: the last
    table of the step alike) and writes the scaled observations and the
    filter's space into the episodes."""
    import gymnasium as gym
    from ray.rllib.connectors.env_to_module import MeanStdFilter as RLlibFilter
    from ray.rllib.env.single_agent_episode import SingleAgentEpisode

    from agents.rllib.sampling import MeanStdFilter

    obs_space = gym.spaces.Box(-np.inf, np.inf, (6,), np.float32)
    act_space = gym.spaces.Box(-1.0, 1.0, (2,), np.float32)
    ref, lean = RLlibFilter(clip_by_value=3.0), MeanStdFilter(clip_by_value=3.0)
    for filt in (ref, lean):  # as RLlib's pipeline sets them
        filt.input_action_space = act_space
        filt.input_observation_space = obs_space
    assert type(lean).__name__ == type(ref).__name__  # the name RLlib files the state under in checkpoints
    rng = np.random.default_rng(1)
    for _ in range(3):
        raw = rng.normal(2.0, 5.0, (16, 6)).astype(np.float32)
        outs = []
        for filt in (ref, lean):
            eps = []
            for row in raw:
                e = SingleAgentEpisode(observation_space=obs_space, action_space=act_space)
                e.add_env_reset(observation=row.copy(), infos={})
                eps.append(e)
            filt(rl_module=None, batch={}, episodes=eps)
            outs.append(np.stack([e.get_observations(-1) for e in eps]))
            assert all(e.observation_space is filt.observation_space for e in eps)
        rs = lean._filters[None].running_stats
        expect = np.clip((raw - rs.mean) / (rs.std + 1e-8), -3.0, 3.0)
        np.testing.assert_allclose(outs[1], expect, rtol=1e-5, atol=1e-5)
        np.testing.assert_allclose(outs[1][-1], outs[0][-1], rtol=1e-5, atol=1e-5)
        assert np.max(np.abs(outs[1])) <= 3.0
    from ray.rllib.utils.filter import RunningStat

    a, b = (RunningStat.from_state(f.get_state()[None]["running_stats"][0]) for f in (ref, lean))
    assert a.num_pushes == b.num_pushes == 48 and a.num_pushes_delta == b.num_pushes_delta == 48
    for key in ("mean_array", "mean_delta_array", "sum_sq_diff_array", "sum_sq_diff_delta_array"):
        np.testing.assert_allclose(getattr(b, key), getattr(a, key), rtol=1e-9)


def test_lean_runner_gives_the_learner_complete_episodes(ray_module):
    """A lean EnvRunner (built in this process, 16 tables) returns one-step
    PotOne episodes with filtered observations, the sampled (unclipped)
    actions, their log-probs and terminated flags; the lean and RLlib's own
    configurations share the filter's checkpoint name."""
    from ray.rllib.env.single_agent_env_runner import SingleAgentEnvRunner

    from agents.rllib.backend import algo_config

    cfg = load_config(None, "Billiards-PotOne-v1", ["rllib.num_env_runners=0", "rllib.num_envs_per_env_runner=16"])
    runner = SingleAgentEnvRunner(config=algo_config(cfg, lean=True))
    try:
        eps = runner.sample(num_timesteps=64)
        assert sum(len(e) for e in eps) >= 64
        for e in eps:
            assert len(e) == 1 and e.is_terminated
            obs = e.get_observations()
            assert obs.shape == (2,) + runner.env.single_observation_space.shape and np.all(np.abs(obs) <= 10.0)
            assert np.all(np.isfinite(e.get_extra_model_outputs("action_logp")))
        actions = np.concatenate([e.get_actions() for e in eps])
        assert np.max(np.abs(actions)) > 1.0  # stored as sampled (std 1 before log_std_init): the env clips them
        names = [type(c).__name__ for c in runner._env_to_module.connectors]
        assert "MeanStdFilter" in names
    finally:
        runner.stop()


def test_tuned_gc_is_undone_after_the_block(ray_module):
    """The driver's collector is tuned only while it trains: inside the block
    the young threshold is raised and the objects frozen, afterwards the
    thresholds are the old ones and nothing stays frozen."""
    import gc

    from agents.rllib.sampling import WORKER_GC_GEN0_THRESHOLD, tuned_gc

    before = gc.get_threshold()
    with tuned_gc():
        assert gc.get_threshold()[0] == WORKER_GC_GEN0_THRESHOLD and gc.get_freeze_count() > 0
    assert gc.get_threshold() == before and gc.get_freeze_count() == 0


def test_process_cpu_account_sees_a_busy_child():
    """The benchmark's CPU account (``/proc``) finds a child process of this
    one and charges it the CPU it burnt."""
    import subprocess
    import sys

    from agents.rllib.bench import cpu_account, process_tree_cpu

    if not os.path.isdir("/proc"):
        pytest.skip("no /proc (not Linux)")
    child = subprocess.Popen([sys.executable, "-c",
                              "import time, sys\nt = time.process_time()\nwhile time.process_time() - t < 0.4: pass\n"
                              "sys.stdout.write('done\\n'); sys.stdout.flush(); time.sleep(5)"],
                             stdout=subprocess.PIPE, text=True)
    try:
        before = process_tree_cpu(os.getpid())
        assert child.stdout.readline().strip() == "done"
        after = process_tree_cpu(os.getpid())
        assert child.pid in after
        cpu, waits = cpu_account(before, after, os.getpid(), {child.pid})
        assert 0.2 <= cpu["runner"] <= 1.0 and set(waits) == {child.pid}
    finally:
        child.kill()
        child.wait()


@pytest.mark.slow
def test_two_node_cluster_places_env_runners_on_both_nodes(tmp_path, ray_module):
    ray = ray_module
    from ray.cluster_utils import Cluster

    from agents.rllib.backend import train

    ray.shutdown()
    cluster = Cluster(initialize_head=True, head_node_args={"num_cpus": 1})
    try:
        cluster.add_node(num_cpus=1)
        cluster.wait_for_nodes()
        ray.init(address=cluster.address)
        alive = {n["NodeID"] for n in ray.nodes() if n["Alive"]}
        assert len(alive) == 2
        s = train(_cfg("train.total_timesteps=128", "train.checkpoint_every=0"), tmp_path / "run", "two nodes",
                  address=cluster.address)
        assert {r["node_id"] for r in s["env_runners"]} == alive
        assert s["timesteps"] >= 128 and math.isfinite(s["env_steps_per_s"])
    finally:
        ray.shutdown()
        cluster.shutdown()

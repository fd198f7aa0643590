"""The two-player games against a fixed opponent, batched
(``billiards_env.envs.games.versus``), and the agent machinery on them
(``agents.interface.game_view``): the batched env is ``GameEnv`` on many tables, every
observation is one the agent acts on, ball in hand is placed where the view
shows it, and a PPO menu agent trains and evaluates on both games."""
import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401 (registers the ids)
from billiards_env.envs.games.vector import GameVectorEnv
from billiards_env.envs.games.versus import AGENT, GameVersusVectorEnv
from billiards_env.rules import records as R

IDS = ["Billiards-NineBall2P-v1", "Billiards-EightBall-v1"]


def versus(env_id, n, **kw):
    return gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", **kw)


@pytest.mark.parametrize("env_id", IDS)
def test_every_observation_is_the_agents_and_rewards_end_games(env_id):
    env = versus(env_id, 8, opponent="ghost", autoreset_mode="same_step", max_shots=60)
    assert isinstance(env, GameVersusVectorEnv)
    obs, info = env.reset(seed=5)
    rng = np.random.default_rng(0)
    ended = 0
    for _ in range(25):
        assert (env.core.constraints().shooter == AGENT).all() and not env.core.constraints().over.any()
        assert env.observation_space.contains(obs)
        obs, r, term, trunc, info = env.step(rng.uniform(-1, 1, (8, 8)).astype(np.float32))
        done = term | trunc
        assert set(np.unique(r)) <= {-1.0, 0.0, 1.0} and not r[~term].any()
        np.testing.assert_array_equal(info["success"], term & (r == 1.0))
        if done.any():
            assert info["_final_obs"].tolist() == done.tolist() and np.isfinite(info["final_obs"]).all()
        ended += done.sum()
    assert ended > 0


def test_one_table_is_the_single_agent_env():
    """With one table and next-step autoreset the vector env plays exactly like ``GameEnv`` (same seed, actions)."""
    vec = versus("Billiards-NineBall2P-v1", 1, opponent="random", noise="tournament")
    single = gym.make("Billiards-NineBall2P-v1", opponent="random", noise="tournament").unwrapped
    ov, _ = vec.reset(seed=7)
    os_, _ = single.reset(seed=7)
    rng = np.random.default_rng(1)
    for _ in range(40):
        np.testing.assert_array_equal(ov[0], os_)
        a = rng.uniform(-1, 1, 8).astype(np.float32)
        ov, rv, tv, trv, _ = vec.step(a[None])
        os_, rs, ts, trs, _ = single.step(a)
        assert (rv[0], tv[0], trv[0]) == (rs, ts, trs)
        if ts or trs:
            break
    else:
        pytest.fail("the game did not end in 40 agent shots")


def test_same_seed_same_games():
    runs = []
    for _ in range(2):
        env = versus("Billiards-EightBall-v1", 6, opponent="ghost-safety", noise="tournament")
        obs, _ = env.reset(seed=3)
        rng = np.random.default_rng(2)
        seq = [obs]
        for _ in range(6):
            seq.append(env.step(rng.uniform(-1, 1, (6, 8)))[0])
        runs.append(np.stack(seq))
    np.testing.assert_array_equal(runs[0], runs[1])


def test_entry_point_without_opponent_is_self_play():
    assert isinstance(versus("Billiards-EightBall-v1", 2), GameVectorEnv)
    with pytest.raises(ValueError, match="opponent"):
        versus("Billiards-EightBall-v1", 2, autoreset_mode="same_step")
    with pytest.raises(ValueError, match="autoreset_mode"):
        versus("Billiards-EightBall-v1", 2, opponent="ghost", autoreset_mode="disabled")


def _ball_in_hand(env, rng, steps=60):
    """Random shots until some table has the agent in hand (not the break); returns those tables."""
    env.reset(seed=11)
    for _ in range(steps):
        c = env.core.constraints()
        k = np.nonzero((c.ball_in_hand != R.IN_HAND_NONE) & ~c.is_break)[0]
        if len(k):
            return k
        env.step(rng.uniform(-1, 1, (env.num_envs, 8)))
    pytest.fail("no ball in hand in 60 random shots")


def test_view_places_the_cue_ball_where_the_shot_is_played_from():
    from agents.interface.game_view import agent_native
    env = versus("Billiards-NineBall2P-v1", 16, opponent="ghost")
    rng = np.random.default_rng(4)
    k = _ball_in_hand(env, rng)
    view = agent_native(env)
    assert agent_native(env) is view
    st, R_ = view.state, env.core.params.R
    assert (st.pocket[k, 0] == -1).all()
    for j in k:  # the placed cue ball overlaps no ball on the table
        on = np.nonzero(st.pocket[j, 1:] < 0)[0] + 1
        assert (np.linalg.norm(st.pos[j, on] - st.pos[j, 0], axis=1) >= 2 * R_ - 1e-12).all()
    a = view.complete_actions(np.zeros((16, 4), dtype=np.float32))
    np.testing.assert_allclose(env.core.codec(np.arange(16)).placement_of(a[k].astype(np.float64)), st.pos[k, 0], atol=1e-5)
    spot = st.pos[k, 0].copy()
    obs, r, term, trunc, info = env.step(a)
    np.testing.assert_allclose(info["placement"][k], spot, atol=1e-5)


def test_view_shots_keep_their_aim_and_the_menu_calls_its_pocket():
    """A menu item's shot reaches the env with the menu's absolute aim, from the placed cue ball; the called pocket
    is the item's pocket."""
    from agents.interface import choice
    from agents.interface.features import transform_actions
    from agents.interface.game_view import agent_native
    env = versus("Billiards-EightBall-v1", 16, opponent="ghost")
    k = _ball_in_hand(env, np.random.default_rng(5))
    view = agent_native(env)
    items = np.tile([[2, choice.SPEED_LEVELS.index(1.0), choice.HEIGHT_LEVELS.index(0.0)]], (16, 1))
    a = transform_actions(view, items, "choice", 1.0)
    assert a.shape == (16, 8)
    m = choice.menu(view)
    idx = np.arange(16)
    play = ~env.core.constraints().is_break
    # the core reads a0 relative to the aim origin seen from the placed cue ball
    env.core.state.pos[k, 0], env.core.state.pocket[k, 0] = view.state.pos[k, 0], -1
    env.core._changed()
    shots = env.core.actions_to_shots(a[:, :4].astype(np.float64), idx)
    d = (shots.phi - m.phi[:, 2] + np.pi) % (2 * np.pi) - np.pi
    np.testing.assert_allclose(d[play], 0.0, atol=1e-5)
    assert (env.core.codec(idx).called_pocket(a.astype(np.float64))[play] == 2).all()


def test_game_baselines_and_names():
    from agents.evaluation.harness import evaluate
    from agents.evaluation.policies import make_policy
    r = evaluate(lambda env: make_policy("ghost-safety", env), "Billiards-NineBall2P-v1", 24, 0, "none",
                 env_kwargs={"opponent": "ghost"})
    assert r.policy == "ghost-safety" and 0 <= r.success_rate <= 1 and r.shots_per_episode >= 1
    from agents.sb3.vec_env import make_sb3_vec_env
    with pytest.raises(ValueError, match="two-player"):
        make_policy("ghost-safety", make_sb3_vec_env("Billiards-PotOne-v1", 2))


@pytest.mark.parametrize("env_id", IDS)
def test_menu_agent_trains_and_evaluates(env_id, tmp_path):
    from agents.sb3.policy import SB3Policy
    from agents.config import CONFIG_DIR, load_config
    from agents.evaluation.harness import evaluate, game_opponent
    from agents.sb3.training import train
    cfg = load_config(CONFIG_DIR / "ppo_games.yaml", env_id,
                      ["n_envs=16", "ppo.n_steps=8", "ppo.batch_size=64", "train.total_timesteps=256",
                       "train.checkpoint_every=0", "train.eval_every=128", "train.eval_every_episodes=16",
                       "train.tensorboard=false"])
    s = train(cfg, tmp_path)
    assert s["timesteps"] == 256 and 0 <= s["held_out"]["ghost_target"] <= 1
    pol = SB3Policy.load(tmp_path)
    r = evaluate(lambda env: pol.bind(env), env_id, 16, 1, "tournament",
                 env_kwargs=game_opponent(env_id, pol.env_kwargs, None))  # a self-play run plays ghost
    assert r.n_episodes == 16 and 0 <= r.success_rate <= 1
    # the saved model also plays matches on a self-play core, either side breaking (studies.matches)
    from agents.evaluation.entrants import bot_factory
    from billiards_env.studies.matches import play_pairing
    game = "nine_ball" if "Nine" in env_id else "eight_ball"
    m = play_pairing(str(tmp_path), "ghost", game, n_racks=3, seed=0, noise="none", max_shots=40,
                     bot_factory=bot_factory)
    assert m.n == 6 and m.a_broke.sum() == 3


def test_benchmark_rows_of_a_game(tmp_path):
    """The benchmark trains and tabulates a game like a one-player task; with every config of the table
    (``--all``) the game's PPO row comes from configs/ppo_games.yaml, its SAC row from configs/sac.yaml."""
    from agents.benchmark import Budget, markdown_table, run_benchmark, table_configs
    quick = ("n_envs=16", "policy.net_arch=[16]", "ppo.n_steps=8", "ppo.batch_size=64", "ppo.n_epochs=1",
             "sac.learning_starts=64", "sac.batch_size=64", "sac.gradient_steps=1", "sac.buffer_size=4096")
    kw = dict(budget=Budget(steps=256, episodes=16, curve_points=2, curve_episodes=16, extra=quick))
    rows = run_benchmark(tmp_path, ["Billiards-EightBall-v1"], ["ppo", "sac"], **kw)
    assert [(r["env_id"], r["algo"]) for r in rows] == [("Billiards-EightBall-v1", "sac")]  # no PPO block in ppo.yaml
    r = rows[0]
    assert 0 <= r["ghost_success"] <= 1 and set(r["eval"]) == {"none", "tournament"}
    rows = run_benchmark(tmp_path, ["Billiards-EightBall-v1"], ["ppo", "sac"], configs=table_configs(), **kw)
    assert [(r["algo"], r["config"]) for r in rows] == [("ppo", "configs/ppo_games.yaml"), ("sac", "configs/sac.yaml")]
    md = markdown_table(rows, tmp_path)
    assert "| EightBall-v1 | SAC | configs/sac.yaml" in md and "| EightBall-v1 | PPO | configs/ppo_games.yaml" in md


def test_game_run_checkpoints_and_resumes(tmp_path):
    from agents.config import CONFIG_DIR, load_config
    from agents.sb3.training import train
    over = ["n_envs=16", "policy.net_arch=[16]", "ppo.n_steps=8", "ppo.batch_size=64", "train.checkpoint_every=128",
            "train.tensorboard=false", "train.eval_every=0"]
    path = CONFIG_DIR / "ppo_games.yaml"
    train(load_config(path, "Billiards-NineBall2P-v1", over + ["train.total_timesteps=384"]), tmp_path)
    s = train(load_config(path, "Billiards-NineBall2P-v1", over + ["train.total_timesteps=512"]), tmp_path,
              resume=True)
    assert s["timesteps"] == 512 and s["resumed"]["from_step"] in (256, 384)


def test_evaluation_names_the_opponent():
    from agents.evaluation.harness import evaluate_policies
    r = evaluate_policies(["ghost"], "Billiards-EightBall-v1", 8, 0, opponent="ghost-safety")
    assert len(r) == 1 and r[0].n_episodes == 8
    with pytest.raises(ValueError, match="two-player"):
        evaluate_policies(["ghost"], "Billiards-PotOne-v1", 8, 0, opponent="ghost")


def test_ball_in_hand_spot_keeps_clear_of_every_ball():
    """The straight-in placement checks every ball of the table (it once looped over the table count instead,
    which skipped balls on small batches and read past the array on large ones)."""
    from billiards_env.bots.ghost import PLACE_CLEAR, GhostBot, PotGeometry
    from billiards_env.envs.games import GameConfig, GameCore
    core = GameCore(GameConfig(game="nine_ball"), 1)
    pol, geo = GhostBot(), PotGeometry(core.table, core.params)
    R_ = core.params.R
    pos = np.zeros((1, 10, 2))
    pos[0, :, 0] = np.linspace(0.2, 1.0, 10)
    pos[0, :, 1] = 2.2
    pos[0, 1] = (0.35, 0.45)        # the legal ball, near a corner pocket
    on = np.ones((1, 10), dtype=bool)
    on[0, 0] = False
    on[0, 9] = False
    targets = np.zeros((1, 10), dtype=bool)
    targets[0, 1] = True
    first = pol.placements(geo, pos, on, targets, np.array([False]))[0]
    u = (pos[0, 1] - first) / np.linalg.norm(pos[0, 1] - first)
    # a ball beside that spot, clear of the shot's path but within 2R + PLACE_CLEAR of the spot
    pos[0, 9], on[0, 9] = first + (2 * R_ + PLACE_CLEAR / 2) * np.array([-u[1], u[0]]), True
    spot = pol.placements(geo, pos, on, targets, np.array([False]))[0]
    d = np.linalg.norm(pos[0, 1:][on[0, 1:]] - spot, axis=1)
    assert (d >= 2 * R_ + PLACE_CLEAR - 1e-12).all() and not np.allclose(spot, first)

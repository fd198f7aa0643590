"""The two-player game environments: PettingZoo's and Gymnasium's own
checks, the vector env against single games, properties of thousands of
random games, ball in hand, and the match harness."""
import math

import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401 (registers the ids)
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.rules.placement import HEAD_STRING
from billiards_env.envs.games.vector import GameVectorEnv
from billiards_env.rules import records as R
from billiards_env.testing.positions import game_table

from billiards_env.rules import GAMES as REGISTRY

# every registered game (the registry's order), its id and its action's size
GAMES = list(REGISTRY)
IDS = [REGISTRY[g].env_id for g in GAMES]
ACTION_DIMS = {g: GameCore(GameConfig(game=g), 1).action_dim for g in GAMES}  # a8: the called / nominated ball
POTTING = [g for g in GAMES if REGISTRY[g].words.pockets and REGISTRY[g].default_bot == "ghost"]  # ghost's games


def aec_class(game):
    from billiards_env.envs.games.aec import aec_class
    return aec_class(game)


@pytest.mark.parametrize("game", GAMES)
def test_pettingzoo_api(game):
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import api_test
    api_test(aec_class(game)(max_shots=40), num_cycles=300, verbose_progress=False)


@pytest.mark.parametrize("env_id,game", list(zip(IDS, GAMES)))
def test_single_agent_check_env(env_id, game):
    from gymnasium.utils.env_checker import check_env
    env = gym.make(env_id, max_shots=40)
    check_env(env.unwrapped, skip_render_check=True)
    obs, info = env.reset(seed=3)
    d = ACTION_DIMS[game]
    assert env.observation_space.contains(obs) and env.action_space.shape == (d,)
    v = gym.make_vec(env_id, num_envs=3, vectorization_mode="vector_entry_point")
    assert isinstance(v, GameVectorEnv) and v.single_action_space.shape == (d,)


@pytest.mark.parametrize("game", GAMES)
def test_vector_env_equals_single_games(game):
    """Table k of a vector env seeded s plays exactly like the AEC env seeded s + k under the same actions."""
    pytest.importorskip("pettingzoo")
    N, seed = 4, 11
    vec = GameVectorEnv(N, game=game, noise="tournament")
    obs, info = vec.reset(seed=seed)
    singles = [aec_class(game)(noise="tournament") for _ in range(N)]
    for k, s in enumerate(singles):
        s.reset(seed=seed + k)
    rng = np.random.default_rng(0)
    alive = np.ones(N, dtype=bool)
    compared = 0
    for _ in range(12):
        a = rng.uniform(-1, 1, (N, ACTION_DIMS[game]))
        for k, s in enumerate(singles):
            if alive[k]:
                np.testing.assert_array_equal(obs[k], s.observe(s.agent_selection))
                assert info["to_move"][k] == int(s.agent_selection[-1])
                s.step(a[k].astype(np.float32))
                compared += 1
        obs, r, term, trunc, info = vec.step(a.astype(np.float32))
        for k, s in enumerate(singles):
            if alive[k]:
                np.testing.assert_array_equal(obs[k], s.observe(s.possible_agents[0]))
                assert info["called_ball"][k] == s.infos["player_0"]["called_ball"]
                if term[k] or trunc[k]:
                    assert s.terminations[s.agent_selection] == term[k]
                    assert s.rewards["player_0"] == info["rewards"][k, 0]
                    alive[k] = False
    assert compared >= 12


@pytest.mark.parametrize("game,n_tables", [("nine_ball", 2000), ("eight_ball", 2000)])
def test_random_games_properties(game, n_tables):
    """Random policies: every game ends within the shot cap; no ball is lost
    or duplicated; the player to move follows the shot records exactly."""
    cap = 150
    core = GameCore(GameConfig(game=game, max_shots=cap, noise="tournament"), n_tables)
    core.streams.seed(np.arange(n_tables), np.arange(n_tables) + 7)
    core.reset_tables(np.arange(n_tables))
    rng = np.random.default_rng(1)
    R_ = core.params.R
    live = np.ones(n_tables, dtype=bool)
    steps = 0
    while live.any():
        idx = np.nonzero(live)[0]
        before = core.game.shooter[idx].copy()
        on_before = core.state.pocket[idx] < 0
        out = core.step(rng.uniform(-1.1, 1.1, (len(idx), 8)), idx)
        rec = out["record"]
        steps += 1
        assert (rec.shooter == before).all()
        assert (core.game.shooter[idx] == np.where(rec.turn_over, 1 - before, before)).all()
        on = core.state.pocket[idx] < 0
        # balls leave the table only by being pocketed on this shot, return only by a respot or a placement
        came_back = on & ~on_before
        assert not came_back[:, 1:][~rec.respot[:, 1:]].any()
        pk = out["info"]["pocketed"][:, 1:]  # object balls (the cue ball may come back by ball in hand)
        assert (pk == (on_before & ~on)[:, 1:] | (pk & rec.respot[:, 1:])).all()
        pos = core.state.pos[idx]
        d = np.linalg.norm(pos[:, :, None] - pos[:, None], axis=-1)
        both = on[:, :, None] & on[:, None]
        d[:, np.arange(d.shape[1]), np.arange(d.shape[1])] = np.inf
        assert (d[both] >= 2 * R_ - 1e-9).all(), "two balls overlap (a duplicated ball)"
        done = out["terminated"] | out["truncated"]
        assert not (out["terminated"] & out["truncated"]).any()
        live[idx[done]] = False
        assert steps <= cap + 1
    g = core.game
    assert ((g.winner >= 0) == g.over).all() and (g.over | (g.shots >= cap)).all()
    assert g.over.mean() > 0.5


def test_ball_in_hand_illegal_placement_is_moved_and_reported():
    core = GameCore(GameConfig(game="eight_ball"), 1)
    core.streams.seed([0], [0])
    core.reset_tables([0], [0])
    # the break: ball in hand behind the head string; ask for a spot on the rack
    a = np.zeros((1, 8))
    a[0, 4:6] = core.placement_to_actions(core.state.pos[0, 1][None])[0]
    out = core.step(a, [0])
    xy = out["info"]["placement"][0]
    assert out["info"]["placement_moved"][0]
    assert xy[1] <= HEAD_STRING * core.table.length
    # a spot on top of a ball is moved to the nearest free spot, reported
    core.game.ball_in_hand[0] = R.IN_HAND_ANYWHERE
    core.game.over[0] = False
    core.game.phase[0] = R.PHASE_PLAY
    core._changed()
    on = np.nonzero(core.state.pocket[0, 1:] < 0)[0] + 1
    target = core.state.pos[0, on[0]].copy()
    spot, moved = core.legal_placement(target[None], [0])
    d = np.linalg.norm(core.state.pos[0, on] - spot[0], axis=1)
    assert moved[0] and d.min() >= 2 * core.params.R
    assert np.linalg.norm(spot[0] - target) < 3 * core.params.R  # the nearest free spot, not just any


@pytest.mark.parametrize("game", POTTING)
def test_ghost_beats_random(game):
    """The match harness: the rule-aware ghost-ball policy beats random in at
    least 95% of 200 games (100 racks, each side breaking once)."""
    from billiards_env.studies.matches import play_pairing
    r = play_pairing("ghost", "random", game, n_racks=100, seed=0, noise="tournament")
    s = r.summary()
    assert s["games"] == 200 and s["a_win_rate"] >= 0.95, s
    assert r.a_broke.sum() == 100


# ------------------------------------------------ rules through the simulator --
def nine_ball_table(balls: dict):
    """A 9-ball core of one table in open play with the balls of ``balls`` on the table (``testing.positions``)."""
    return game_table("nine_ball", balls)


def shoot(core, phi, speed):
    from billiards_env.physics.strike import Shots
    a = core.codec([0]).encode(Shots(np.array([phi]), np.array([speed]), np.zeros(1), np.zeros(1)))
    return core.step(a, [0])


PARKED = {b: (0.2 + 0.1 * (b - 2), 2.2) for b in range(2, 10)}  # balls 2..9 out of the way at the foot end


def test_sim_legal_pot_keeps_the_table():
    core = nine_ball_table({0: (0.32, 0.32), 1: (0.2, 0.2), **PARKED})  # straight in, the cue ball stunned
    out = shoot(core, math.atan2(-1, -1), 1.5)
    assert out["info"]["pocketed"][0, 1] and out["record"].legal[0] and not out["record"].turn_over[0]


def test_sim_wrong_ball_first():
    core = nine_ball_table({0: (0.635, 1.0), 1: (0.2, 0.4), **PARKED})  # straight at the 6 at (0.6, 2.2)
    out = shoot(core, math.atan2(1.2, -0.035), 2.0)
    assert out["info"]["first_contact"][0] == 6 and out["record"].foul[0] == R.FOUL_WRONG_BALL
    assert core.constraints().ball_in_hand[0] == R.IN_HAND_ANYWHERE and core.game.shooter[0] == 1


def test_sim_scratch_and_ball_in_hand_next():
    core = nine_ball_table({0: (0.3, 0.3), 1: (0.9, 1.5), **PARKED})
    out = shoot(core, math.atan2(-1, -1), 1.5)  # straight into the corner pocket, touching nothing
    assert out["record"].foul[0] == R.FOUL_SCRATCH and core.state.pocket[0, 0] >= 0
    a = np.zeros((1, 8))
    a[0, 4:6] = core.placement_to_actions(np.array([[0.635, 1.0]]))[0]
    out = shoot_with(core, a)
    assert abs(out["info"]["placement"][0, 1] - 1.0) < 1e-9 and not out["info"]["placement_moved"][0]


def shoot_with(core, a):
    return core.step(a, [0])


@pytest.mark.parametrize("speed", [1.0, 1.1])
def test_sim_rail_before_contact_does_not_count(speed):
    """The cue ball banks off the head rail, then nudges the 1: nothing
    reaches a rail after the contact, so it is a foul."""
    core = nine_ball_table({0: (0.635, 0.3), 1: (0.635, 0.6), **PARKED})
    out = shoot(core, -math.pi / 2, speed)
    assert out["info"]["first_contact"][0] == 1
    assert out["record"].foul[0] == R.FOUL_NO_RAIL


def test_render_game_state_and_gif(tmp_path):
    from billiards_env.rendering.game import render_game, status_lines
    from billiards_env.studies.game_animation import save_game_animation
    core = GameCore(GameConfig(game="eight_ball"), 1)
    core.streams.seed([0], [0])
    core.reset_tables([0], [1])
    img = render_game(core, 0)
    assert img.ndim == 3 and img.shape[0] > img.shape[1] and img.dtype == np.uint8
    lines = status_lines(core, 0)
    assert "P1 to move" in lines[0] and "behind the head string" in lines[0] and "groups: P0 open" in lines[1]
    from billiards_env.rendering import Animation
    path = save_game_animation(tmp_path / "game.gif", "nine_ball", ("ghost", "random"), seed=1,
                               anim=Animation(fps=4, speedup=8.0, hold=1, ppm=60), max_shots=3)
    import imageio.v3 as iio
    frames = iio.imread(path)
    assert path.exists() and len(frames) >= 4


@pytest.mark.parametrize("game, call, score", [("ten_ball", "call the ball and its pocket", None),
                                               ("three_cushion", None, "score: P0 0, P1 0")])
def test_status_lines_say_each_games_call_and_score(game, call, score):
    """The raster panel words the call as the game asks it and shows a score in games to points."""
    from billiards_env.rendering.game import status_lines
    core = GameCore(GameConfig(game=game), 1)
    core.streams.seed([0], [0])
    core.reset_tables([0], [0])
    if call:  # every shot after the break needs a call
        shoot(core, math.pi / 2, 7.0)
        assert core.constraints().call_needed[0]
    lines = status_lines(core, 0)
    if call:
        assert call in lines[0] and "on the 8" not in lines[0]
    if score:
        assert score in lines[1]


def test_noise_levels():
    """high = 5x the tournament deviations; variable = a factor in [0, 5] per
    game, drawn from the table's stream (the same rack seed, the same factor)."""
    from billiards_env.envs.config import NoiseConfig
    t, h = NoiseConfig.preset("tournament"), NoiseConfig.preset("high")
    assert all(getattr(h, f) == pytest.approx(5 * getattr(t, f)) for f in ("aim_deg", "speed", "side_mm", "height_mm"))
    core = GameCore(GameConfig(game="nine_ball", noise="variable"), 400)
    core.streams.seed(np.arange(400), np.tile(np.arange(200), 2))
    core.reset_tables(np.arange(400))
    f = core.noise_scale
    assert (f >= 0).all() and (f <= 5).all() and f.max() > 4 and f.min() < 1
    np.testing.assert_array_equal(f[:200], f[200:])
    assert core.config.noise.config == t and core.config.noise.spread == (0.0, 5.0)
    assert GameCore(GameConfig(noise="high"), 2).config.noise.config == h


def test_stable_baselines3_trains_on_the_single_agent_env():
    sb3 = pytest.importorskip("stable_baselines3")
    env = gym.make("Billiards-NineBall2P-v1", max_shots=30)
    model = sb3.PPO("MlpPolicy", env, n_steps=32, batch_size=32, n_epochs=1, seed=0, device="cpu")
    model.learn(64)
    obs, _ = env.reset(seed=0)
    action, _ = model.predict(obs, deterministic=True)
    assert env.action_space.contains(action)


def test_search_policy_plays_legal_game():
    """search<K> is built on the same hooks: on a position with an easy pot it keeps the table."""
    from billiards_env.bots import make_bot
    from billiards_env.envs.games.play import bot_actions
    core = nine_ball_table({0: (0.32, 0.32), 1: (0.2, 0.2), **PARKED})
    out = core.step(bot_actions(core, make_bot("search16", seed=0), [0]), [0])
    assert out["record"].legal[0] and out["info"]["pocketed"][0, 1] and not out["record"].turn_over[0]


@pytest.mark.slow
def test_match_script_with_a_saved_model(tmp_path):
    """scripts/match.py through a subprocess: a PPO model saved after a few
    steps on the single-agent env enters a match against random; JSON,
    Markdown and plot are written."""
    import json
    import subprocess
    import sys
    from pathlib import Path
    sb3 = pytest.importorskip("stable_baselines3")
    env = gym.make("Billiards-NineBall2P-v1", max_shots=20)
    model = sb3.PPO("MlpPolicy", env, n_steps=16, batch_size=16, n_epochs=1, seed=0, device="cpu")
    model.learn(16)
    model.save(tmp_path / "model.zip")
    root = Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, str(root / "scripts" / "match.py"), "--racks", "3", "--max-shots", "20",
                          "--policies", "random", str(tmp_path / "model.zip"), "--out", str(tmp_path)],
                         capture_output=True, text=True, cwd=root, timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    doc = json.loads((tmp_path / "nine_ball_tournament.json").read_text())
    assert doc["pairings"][0]["games"] == 6 and len(doc["ratings"]) == 2
    assert (tmp_path / "nine_ball_tournament.png").exists() and (tmp_path / "nine_ball_tournament.md").exists()

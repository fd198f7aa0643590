"""The learned leaf value (bots.learned.value) and the lookahead's leaf_value hook."""
from __future__ import annotations


import numpy as np
import pytest

from billiards_env.bots import is_bot_name, make_bot
from billiards_env.bots.game_lookahead import GameLookahead
from billiards_env.bots.learned import value as V
from billiards_env.envs.games import GameConfig, GameCore

GAMES = ("nine_ball", "eight_ball")


def _views(game, n=6, seed=3):
    """Views of ``n`` seeded tables a few random shots into a game (not breaks)."""
    core = GameCore(GameConfig(game=game, noise="tournament"), n)
    core.streams.seed(np.arange(n), seed + np.arange(n))
    core.reset_tables(np.arange(n), np.zeros(n, dtype=np.int64))
    ghost = make_bot("ghost", seed=seed)
    from billiards_env.envs.games.play import play_round
    for _ in range(3):
        live = np.nonzero(~core.game.over)[0]
        play_round(core, [ghost, ghost], live)
    live = np.nonzero(~core.game.over)[0]
    return core.view(live)


def _plans_equal(p, q):
    for f in ("shots", "placement", "declare", "pocket"):
        a, b = getattr(p, f), getattr(q, f)
        if hasattr(a, "phi"):
            for g in ("phi", "speed", "a", "b"):
                np.testing.assert_array_equal(getattr(a, g), getattr(b, g))
        else:
            np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("game", GAMES)
def test_hook_default_is_position_value(game):
    """leaf_value=None (the default) plays exactly what an explicit position_value valuer plays, and a
    different valuer changes the choice somewhere (the hook is used)."""
    view = _views(game)
    base = GameLookahead(seed=4, n_pots=3, n_eval=6, n_eval_safe=2, n_samples=3)
    explicit = GameLookahead(seed=4, n_pots=3, n_eval=6, n_eval_safe=2, n_samples=3,
                             leaf_value=lambda v, pos, on, tg, hand, e: base.position_value(v, e, on, tg))
    _plans_equal(base.act(view), explicit.act(view))
    other = GameLookahead(seed=4, n_pots=3, n_eval=6, n_eval_safe=2, n_samples=3,
                          leaf_value=lambda v, pos, on, tg, hand, e: 1.0 - base.position_value(v, e, on, tg))
    assert not np.array_equal(other.act(view).shots.phi, base.act(view).shots.phi)


def test_features_mirror_and_network_round_trip(tmp_path):
    view = _views("nine_ball")
    geo = GameLookahead()
    ease = geo.leave_ease(view, view.pos, view.on_table, view.targets, view.in_hand)
    x = V.value_features(view.game, view.table.width, view.table.length, view.pos, view.on_table, view.targets,
                         view.ball_in_hand, ease)
    B = view.n_balls
    assert x.shape == (view.n, V.feature_size(B)) and np.isfinite(x).all()
    m = V.mirror_features(x, B)
    np.testing.assert_allclose(V.mirror_features(m, B), x)
    on = view.on_table
    np.testing.assert_allclose(m[:, 0:2 * B:2][on], 1.0 - x[:, 0:2 * B:2][on])
    rng = np.random.default_rng(0)
    from agents.league.fit import init_net
    net = init_net(x.shape[1], (5, 4), x.mean(0), x.std(0) + 1.0, rng)
    net.save(tmp_path / "v", dict(game="nine_ball"))
    back, doc = V.load_value(tmp_path / "v")
    np.testing.assert_array_equal(back(x), net(x))
    assert doc["hidden"] == [5, 4] and 0 < net(x).min() and net(x).max() < 1
    # with the correction's output layer at zero the value is the lookahead's position_value
    zero = V.ValueNet(net.weights[:-1] + (0 * net.weights[-1],), net.biases[:-1] + (0 * net.biases[-1],),
                      net.mean, net.std)
    np.testing.assert_allclose(zero(x), geo.position_value(view, ease, view.on_table, view.targets), rtol=1e-12)
    with pytest.raises(ValueError, match="no value network"):
        V.load_value(tmp_path / "missing")
    with pytest.raises(ValueError, match="takes inputs"):
        net(x[:, :3])


def test_value_lookahead_loads_by_name_without_torch_and_replays_identically(played_twice_without_torch):
    games = [g for g in GAMES if (V.VALUE_DIR / f"{g}.json").exists()]
    if not games:
        pytest.skip("no value network shipped")
    assert is_bot_name("value-lookahead")
    out = played_twice_without_torch([(g, "value-lookahead") for g in games], n_racks=1, max_shots=16)
    for g in games:
        first, second = out[g]
        assert first == second and sum(first[1]) > 4


def test_shipped_cards_match_their_weights():
    for g in GAMES:
        if (V.VALUE_DIR / f"{g}.json").exists():
            net, doc = V.load_value(V.VALUE_DIR / g)
            assert doc["game"] == g and net.in_dim == V.feature_size(16 if g == "eight_ball" else 10)
            assert doc["league"]["generations"] >= 1 and doc["league"]["wall_seconds"] > 0


def test_blind_leaf_value_changes_only_the_tables_without_a_pot(tmp_path):
    from agents.league.fit import init_net
    view = _views("nine_ball", n=12)
    geo = GameLookahead()
    ease = geo.leave_ease(view, view.pos, view.on_table, view.targets, view.in_hand)
    ease[::3] = 0.0  # some tables as if no pot were open
    x = V.value_features(view.game, view.table.width, view.table.length, view.pos, view.on_table, view.targets,
                         view.ball_in_hand, ease)
    net = init_net(x.shape[1], (4,), x.mean(0), x.std(0) + 1.0, np.random.default_rng(2))
    net = V.ValueNet(net.weights[:-1] + (net.weights[-1] + 0.5,), net.biases, net.mean, net.std)  # nonzero output
    args = (view, view.pos, view.on_table, view.targets, view.ball_in_hand, ease)
    blind, every = V.LeafValue({"nine_ball": net})(*args), V.LeafValue({"nine_ball": net}, where="all")(*args)
    pv = geo.position_value(view, ease, view.on_table, view.targets)
    np.testing.assert_array_equal(blind[ease > 0], pv[ease > 0])
    np.testing.assert_allclose(blind[ease <= 0], every[ease <= 0])
    assert not np.allclose(blind[ease <= 0], pv[ease <= 0])
    with pytest.raises(ValueError, match="where must be one of"):
        V.LeafValue(where="some")


def test_value_lookahead_is_an_opponent_of_the_game_env_and_plays_the_aec_env():
    import gymnasium as gym

    import billiards_env  # noqa: F401
    from billiards_env.envs.games.aec import NineBallAECEnv

    if not (V.VALUE_DIR / "nine_ball.json").exists():
        pytest.skip("no value network shipped")
    env = gym.make("Billiards-NineBall2P-v1", opponent="value-lookahead")
    obs, _ = env.reset(seed=2)
    obs, *_ = env.step(env.action_space.sample())
    assert np.isfinite(obs).all()
    aec = NineBallAECEnv()
    aec.reset(seed=3)
    bot = make_bot("value-lookahead", seed=1)
    for _ in range(3):
        *_, term, trunc, _ = aec.last()
        if term or trunc:
            break
        a = aec.bot_action(bot.act(aec.bot_view()))
        assert aec.action_space(aec.agent_selection).contains(a)
        aec.step(a)


def test_balls_eases_feature_a_network_that_round_trips_and_starts_as_position_value(tmp_path):
    """The balls' own eases: in [0, 1], 0 for the cue ball and pocketed balls, the shooter's best legal pot
    among the from-cue eases; a network with them saves, loads (its card says so) and, untrained, is position_value."""
    from agents.league.fit import init_net
    view = _views("nine_ball", n=8)
    geo = GameLookahead()
    B, on = view.n_balls, view.on_table
    balls = V.ball_eases(geo, view, view.pos, on, view.ball_in_hand)
    anywhere, from_cue = balls[:, :B], balls[:, B:]
    assert balls.shape == (view.n, 2 * B) and (balls >= 0).all() and (balls <= 1).all()
    assert (balls[:, [0, B]] == 0).all() and (anywhere[~on] == 0).all() and (from_cue[~on] == 0).all()
    assert anywhere.max() > 0 and from_cue.max() > 0
    ease = geo.leave_ease(view, view.pos, on, view.targets, view.in_hand)
    np.testing.assert_allclose(np.where(view.targets & on, from_cue, 0).max(axis=1), ease, rtol=1e-12)
    x = V.value_features(view.game, view.table.width, view.table.length, view.pos, on, view.targets,
                         view.ball_in_hand, ease, balls)
    assert x.shape == (view.n, V.feature_size(B, ball_eases=True)) and V.n_balls_of(x.shape[1], True) == B
    np.testing.assert_allclose(V.mirror_features(x, B)[:, -2 * B:], balls)   # the eases are mirror images' too
    net = init_net(x.shape[1], (4,), x.mean(0), x.std(0) + 1.0, np.random.default_rng(1), ball_eases=True)
    np.testing.assert_allclose(net(x), geo.position_value(view, ease, on, view.targets), rtol=1e-12)
    net = V.ValueNet(net.weights[:-1] + (net.weights[-1] + 0.5,), net.biases, net.mean, net.std, True)
    net.save(tmp_path / "b", dict(game="nine_ball"))
    back, doc = V.load_value(tmp_path / "b")
    assert back.ball_eases and doc["ball_eases"] is True and doc["format_version"] == V.FORMAT_VERSION
    np.testing.assert_array_equal(back(x), net(x))
    leaf = V.LeafValue({"nine_ball": back}, where="all")
    np.testing.assert_allclose(leaf(view, view.pos, on, view.targets, view.ball_in_hand, ease), net(x), rtol=1e-12)

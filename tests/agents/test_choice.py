"""``action_mode: choice`` (agents/interface/choice.py): the shot menu, its features,
its action space in the wrappers, config validation and a training round trip."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.interface import choice  # noqa: E402
from billiards_env.bots import geometry as G  # noqa: E402
from agents.sb3.policy import SB3Policy  # noqa: E402
from agents.config import load_config  # noqa: E402
from agents.evaluation.harness import evaluate  # noqa: E402
from agents.interface.features import ShotFeatures  # noqa: E402
from agents.sb3.vec_env import make_sb3_vec_env  # noqa: E402
from billiards_env.physics import simulate, strike_velocity  # noqa: E402
from billiards_env.physics.strike import Shots  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
NINE = "Billiards-NineBall-v1"
NOMINAL = (choice.SPEED_LEVELS.index(1.0), choice.HEIGHT_LEVELS.index(0.0))


def _wrapped(n=32, seed=3):
    env = make_sb3_vec_env(NINE, n, seed=seed)
    w = ShotFeatures(env, env.unwrapped, True, 1.0, "choice")
    return env, w, w.reset()


def test_menu_space_and_features():
    env, w, obs = _wrapped()
    nat = env.unwrapped
    P, F = len(nat.table.pockets), len(choice.CONTACT_FULLNESS) + choice.N_KICKS
    assert list(w.action_space.nvec) == [P + F, len(choice.SPEED_LEVELS), len(choice.HEIGHT_LEVELS)]
    assert obs.shape == (32, env.observation_space.shape[0] + 6 * P + 2 * F)
    contact = obs[:, -2 * F:].reshape(32, F, 2)
    assert set(np.unique(contact[..., 0])) <= {0.0, 1.0} and (contact[..., 1] >= 0).all()
    env.close()


def test_a_pocket_item_is_that_pockets_ghost_ball_shot():
    env, w, _ = _wrapped()
    nat = env.unwrapped
    st, tgt = nat.state, nat.legal_target()
    sh = G.ghost_shots(st.pos, st.on_table, tgt, nat.table, nat.params, 0.0)
    k = np.arange(32) % len(nat.table.pockets)
    ar = np.arange(32)
    speed = G.required_speed(sh["d_cg"][ar, k], sh["d_op"][ar, k], sh["cut"][ar, k], nat.params, margin=1.0)
    expect = nat.shots_to_actions(Shots(sh["phi"][ar, k], speed, np.zeros(32), np.zeros(32)))
    got = choice.choice_actions(nat, np.column_stack([k, np.full(32, NOMINAL[0]), np.full(32, NOMINAL[1])]))
    np.testing.assert_allclose(got, np.clip(expect, -1, 1).astype(np.float32), atol=1e-6)
    env.close()


def test_open_contact_shots_hit_the_legal_ball_first_at_their_fullness():
    env, w, _ = _wrapped(64)
    nat = env.unwrapped
    st, tgt, p = nat.state, nat.legal_target(), nat.params
    full = np.asarray(choice.CONTACT_FULLNESS)
    phi, length, blocked = G.contact_shots(st.pos, st.on_table, tgt, full, p.R, nat.table.width,
                                           nat.table.length)
    e, f = np.nonzero(~blocked)
    assert len(e) > 100
    speed = G.rolling_strike_speed(length[e, f], choice.CONTACT_ARRIVAL, p)
    res = simulate(strike_velocity(st.take(e), phi[e, f], speed, 0.0 * speed, 0.0 * speed, p), nat.table, p)
    assert (res.first_contact == tgt[e]).all()
    # the path's end is 2R from the target's centre, offset 2R * fullness across the path
    u = np.stack([np.cos(phi[e, f]), np.sin(phi[e, f])], axis=1)
    end = st.pos[e, 0] + length[e, f, None] * u
    rel = st.pos[e, tgt[e]] - end
    np.testing.assert_allclose(np.hypot(*rel.T), 2 * p.R, rtol=1e-9)
    cross = u[:, 0] * rel[:, 1] - u[:, 1] * rel[:, 0]
    np.testing.assert_allclose(cross, 2 * p.R * full[f], atol=1e-12)  # > 0: the target lies left of the path
    assert math.isclose(float(G.rolling_strike_speed(0.0, 1.0, p)), 1.4)
    env.close()


def test_bad_choices_and_modes_are_refused():
    env, w, _ = _wrapped(4)
    with pytest.raises(ValueError, match="choice actions"):
        w.step(np.array([[99, 0, 0]] * 4))
    with pytest.raises(ValueError, match="action_mode"):
        load_config(ROOT / "configs" / "ppo.yaml", overrides=["action_mode=menu"])
    env.close()


def test_choice_training_round_trip(tmp_path):
    from agents.sb3.training import train
    over = ["n_envs=16", "train.total_timesteps=1024", "train.progress_bar=false", "train.checkpoint_every=512",
            "policy.net_arch=[16, 16]", "ppo.n_steps=32", "ppo.batch_size=128", "ppo.n_epochs=1",
            "train.eval_every=0"]
    cfg = load_config(ROOT / "configs" / "ppo_nineball.yaml", overrides=over)
    assert cfg.action_mode == "choice" and cfg.env_id == NINE
    train(cfg, tmp_path / "run", "pytest")
    pol = SB3Policy.load(tmp_path / "run")
    assert pol.action_mode == "choice"
    res = evaluate(lambda env: pol.bind(env), NINE, 16, seed=2)
    assert res.n_episodes == 16 and res.shots_per_episode >= 1


def test_kicks_reach_a_ball_hidden_behind_another():
    """Cue ball, a blocker and the legal ball in a row along the table:
    every straight contact is blocked, and so are the kicks off the short
    rails (their legs run through the blocker); the kicks off the long rails
    are open (their rebound points lie 0.5 m from the side pockets), and a
    kick at 1.3 times its nominal speed hits the legal ball first."""
    env, w, _ = _wrapped(1)
    nat = env.unwrapped
    W, L = nat.table.width, nat.table.length
    pos = np.full((10, 2), -1.0)
    pos[0], pos[2], pos[1] = (0.3, L / 2 - 0.9), (0.3, L / 2 - 0.5), (0.3, L / 2 - 0.1)  # cue, blocker 2, target 1
    on = np.zeros(10, dtype=bool)
    on[:3] = True
    from billiards_env.physics import BallState
    state = BallState.from_positions(np.where(on[:, None], pos, 0.0)[None])
    state.pocket[0, ~on] = 0  # balls 3..9 pocketed
    nat.set_state(state)
    tgt = nat.legal_target()
    assert tgt[0] == 1
    p, t = nat.params, nat.table
    full = np.asarray(choice.CONTACT_FULLNESS)
    assert G.contact_shots(nat.state.pos, nat.state.on_table, tgt, full, p.R, W, L)[2].all()
    phi, path, blocked = G.kick_shots(nat.state.pos, nat.state.on_table, tgt, p.R, W, L, t.pockets)
    assert list(~blocked[0]) == [True, True, False, False]  # the left and right rails; not the short ones
    np.testing.assert_allclose(path[0, 0], np.hypot(2 * 0.3 - 2 * p.R, 0.8) - 2 * p.R, rtol=1e-12)
    k = 1  # the far rail: the longer kick
    v = 1.3 * G.rolling_strike_speed(path[0, k], choice.KICK_ARRIVAL, p)
    res = simulate(strike_velocity(nat.state, phi[:, k], np.array([v]), np.zeros(1), np.zeros(1), p), t, p)
    assert res.first_contact[0] == 1
    env.close()


def test_shot_stats_counts_add_up(load_script):
    """scripts/shot_stats.py: every shot is classified once; rates lie in [0, 1]."""
    mod = load_script("shot_stats")
    r = mod.shot_stats("ghost", NINE, 40, seed=5)
    n = r["counts"]
    assert n["shots"] == round(r["shots_per_episode"] * 40) and n["shots"] >= 40
    closed = n["shots"] - n["open"]
    assert n["closed_pot"] + n["closed_miss"] + n["closed_fail"] == closed
    assert n["open_pot"] + n["open_fail"] <= n["open"] and n["leave_open"] <= n["pots_on"]
    assert all(0.0 <= r[k] <= 1.0 for k in r if k.endswith(("_share", "_open", "_closed", "_after_pot")))


def test_menu_is_built_once_per_state_and_rebuilt_after_a_step():
    """The observation's features and the next actions read one menu; a step
    (a new state) gives a new one, equal to a menu built from scratch."""
    env, w, _ = _wrapped(16)
    nat = env.unwrapped
    m = choice.menu(nat)
    choice.contact_features(nat)
    choice.choice_actions(nat, np.zeros((16, 3), dtype=np.int64))
    assert choice.menu(nat) is m
    w.step(np.column_stack([np.full(16, 6), np.full(16, NOMINAL[0]), np.full(16, NOMINAL[1])]))
    after = choice.menu(nat)
    assert after is not m
    fresh = choice._build_menu(nat, nat.shot_context())
    for f in ("phi", "speed", "open_", "length"):
        np.testing.assert_array_equal(getattr(after, f), getattr(fresh, f))
    env.close()

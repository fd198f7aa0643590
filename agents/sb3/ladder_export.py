"""Trained stable-baselines3 game models as ladder agents
(``billiards_env.bots.learned.ladder``): the actor network and observation
statistics as numpy arrays (``numpy_network``), checked against the torch
policy on seeded game positions (``check``), and the agent's JSON card
(``export``; ``scripts/export_ladder.py``)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import yaml

from billiards_env.bots.learned import ladder as L
from billiards_env.bots.learned.mlp import NORM_EPS, MLPPolicy, ObsNorm

from .policy import SB3Network, SB3Policy

GAME_OF_ENV = {"Billiards-NineBall2P-v1": "nine_ball", "Billiards-EightBall-v1": "eight_ball",
               "Billiards-TenBall-v1": "ten_ball"}


def numpy_network(policy: SB3Policy, activation: str, clip: float) -> MLPPolicy:
    """The actor of an SB3 ``MlpPolicy`` over a ``MultiDiscrete`` action as an ``MLPPolicy``."""
    net = policy.model.policy
    layers = [m for m in net.mlp_extractor.policy_net if hasattr(m, "weight")] + [net.action_net]
    ws = tuple(m.weight.detach().cpu().numpy().astype(np.float32) for m in layers)
    bs = tuple(m.bias.detach().cpu().numpy().astype(np.float32) for m in layers)
    vn = policy.vecnormalize
    norm = None
    if vn is not None:
        rms = getattr(vn, "obs_rms", None)
        mean, var = (rms.mean, rms.var) if rms is not None else (vn.mean, vn.var)
        norm = ObsNorm(np.asarray(mean, np.float64), np.asarray(var, np.float64), clip, NORM_EPS)
    nvec = tuple(int(v) for v in policy.model.action_space.nvec)
    return MLPPolicy(ws, bs, activation, nvec, norm)


def model_path(run: Path, steps: int | None) -> Path:
    path = run / "checkpoints" / f"model_{steps}_steps.zip" if steps else run / "model.zip"
    if not path.exists():
        have = sorted(p.name for p in (run / "checkpoints").glob("model_*_steps.zip"))
        raise FileNotFoundError(f"{path} does not exist; the run has: {', '.join(have) or 'no checkpoints'}")
    return path


def training_info(run: Path, steps: int | None) -> dict:
    if steps:
        state = json.loads((run / "checkpoints" / f"model_{steps}_steps_state.json").read_text())
        return dict(training_steps=int(state["steps"]), training_wall_s=round(float(state["elapsed_s"]), 1))
    summary = json.loads((run / "train_summary.json").read_text()) if (run / "train_summary.json").exists() else {}
    wall = summary.get("train_wall_s")  # train()'s summary (agents.sb3.training)
    return dict(training_steps=int(summary.get("timesteps", 0)) or None,
                training_wall_s=None if wall is None else round(float(wall), 1))


def check(net: MLPPolicy, policy: SB3Policy, game: str, n: int, seed: int = 0) -> int:
    """Play ``n`` seeded positions (a ghost-bot game on n // 8 tables, 8
    shots each) and compare the numpy network's actions with the torch
    policy's on every one; returns the positions compared."""
    from billiards_env.bots import make_bot
    from billiards_env.bots.learned.policy import ViewPolicy
    from billiards_env.envs.games import GameConfig, GameCore
    from billiards_env.envs.games.play import bot_actions

    tables = max(n // 8, 1)
    core = GameCore(GameConfig(game=game, noise="tournament"), tables)
    core.streams.seed(np.arange(tables), seed + np.arange(tables))
    core.reset_tables(np.arange(tables), np.zeros(tables, dtype=np.int64))
    mover = make_bot("ghost", seed=seed)
    ours = ViewPolicy(net, "numpy", policy.features, policy.aim_scale, policy.action_mode)
    theirs = SB3Network(policy.model, policy.vecnormalize)
    done = 0
    for _ in range(8):
        live = np.flatnonzero(~core.game.over)
        if not len(live):
            break
        obs, _ = ours.observe(core.view(live))
        a, b = net.act(obs), theirs.act(obs)
        if not np.array_equal(a, b):
            bad = np.flatnonzero((a != b).any(axis=1))
            raise AssertionError(f"numpy and torch actions differ on {len(bad)} of {len(a)} positions")
        done += len(a)
        core.step(bot_actions(core, mover, live), live)
    return done


def export(run: Path, name: str, steps: int | None = None, version: int = 1, out: Path = L.LADDER_DIR,
           n_check: int = 256) -> dict:
    """Write ``<out>/<game>/<name>.npz`` and ``.json`` from ``run``'s
    checkpoint at ``steps`` (default its final model); returns the card."""
    if not L.is_ladder_name(name):
        raise ValueError(f"a ladder agent is named ladder-<k>, got {name!r}")
    run = Path(run)
    cfg = yaml.safe_load((run / "config.yaml").read_text())
    env_id = cfg["env_id"]
    if env_id not in GAME_OF_ENV:
        raise ValueError(f"{run}: trained on {env_id}, not a two-player game ({', '.join(GAME_OF_ENV)})")
    if cfg.get("action_mode") != "choice" or cfg.get("algo") != "ppo":
        raise ValueError(f"{run}: the ladder takes PPO over the shot menu (action_mode: choice)")
    game = GAME_OF_ENV[env_id]
    path = model_path(run, steps)
    policy = SB3Policy.load(path)
    clip = float((cfg.get("normalize") or {}).get("clip_obs", 10.0))
    net = numpy_network(policy, (cfg.get("policy") or {}).get("activation", "tanh"), clip)
    compared = check(net, policy, game, n_check) if n_check else 0
    card = dict(format=L.FORMAT, format_version=L.FORMAT_VERSION, name=name, version=int(version),
                game=game, env_id=env_id,
                architecture=dict(hidden=[int(w.shape[0]) for w in net.weights[:-1]], activation=net.activation,
                                  nvec=list(net.nvec), obs_dim=net.obs_dim),
                obs_norm=dict(clip=clip, eps=NORM_EPS) if net.norm is not None else None,
                agent=dict(features=policy.features, aim_scale=policy.aim_scale, action_mode=policy.action_mode),
                trained_against=(cfg.get("env_kwargs") or {}).get("opponent", "self-play"),
                **training_info(run, steps),
                source=dict(run=run.name, model=path.name,
                            command=(run / "command.txt").read_text().strip() if (run / "command.txt").exists()
                            else None),
                checked_positions=compared, source_config=cfg)
    folder = Path(out) / game
    folder.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(folder / f"{name}.npz", **net.arrays())
    (folder / f"{name}.json").write_text(json.dumps(card, indent=1) + "\n")
    L.load_network.cache_clear()
    return card

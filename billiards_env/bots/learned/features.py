"""What a learned shot policy reads and how its action becomes the env's:
the agent-side observation features and the action modes (numpy only; the
training wrappers of ``agents.interface.features`` and the shipped ladder
bots, ``bots.learned.ladder``, use the same functions).

The env observation is raw ball positions; turning them into a precise aim
(the pocket acceptance at 1 m is about +-1.5 deg of object-ball direction)
is a hard function for an MLP to learn in a few minutes. With
``features: true`` the agent appends, for each of the 6 pockets, the
ghost-ball construction's numbers (``billiards_env.bots.geometry``):

- the ghost-ball aim relative to the env's aim origin, in (scaled) action units,
- cut angle / (pi/2), cue->ghost and object->pocket distances / diagonal,
- the ghost-ball speed model's cue draw in action units,
- 1 if the shot is geometrically open (cut < 88 deg, no ball in the way), else 0.

The policy must still choose the pocket, correct the aim for throw, and pick
speed and spin. ``aim_scale`` (< 1) maps the policy's a0 to ``aim_scale * a0``
of the env's aim range (+-pi * aim_scale around the cue -> target line), so
the policy's action noise and resolution are spent where shots are.

``action_mode: residual`` (residual RL, Johannink et al. 2019): the policy's
action is a *correction* to the ghost-ball baseline's shot (aim offset of up
to +-pi * aim_scale, speed factor exp(0.5 a1), side/height spin), so it
starts at the baseline and learns what the geometry leaves out (throw,
speed, spin against scratches). The correction is applied in shot space
(``Shots``) and mapped to the env's action once.

``action_mode: choice`` (``bots.learned.menu``): the policy picks an item of a
shot menu (a pocket's ghost-ball shot or a safe contact shot), a speed
level and a tip height; its contact features are appended too.

A "native" env here is anything with the one-player reading interface:
``state``, ``table``, ``params``, ``legal_target()``, ``aim_origin()``,
``shot_context()``, ``shots_to_actions`` (a one-player vector env, or a game
seen as one, ``bots.learned.game_view.OnePlayerView``).
"""
from __future__ import annotations

import math

import numpy as np

from ...physics.strike import Shots, speed_to_draw
from .. import geometry as G
from . import menu as choice

N_FEAT_PER_POCKET = 6
ACTION_MODES = ("direct", "residual", "choice")


def check_action_mode(mode: str) -> None:
    if mode not in ACTION_MODES:
        raise ValueError(f"action_mode must be one of {ACTION_MODES}, got {mode!r}")


def n_features(native) -> int:
    return N_FEAT_PER_POCKET * len(native.table.pockets)


def shot_features(native, aim_scale: float = 1.0, ghost: dict | None = None) -> np.ndarray:
    """Features [N, 6 * P] of the native vector env's current tables
    (``ghost``: their ``geometry.ghost_shots``, when already computed)."""
    st = native.state
    table, params = native.table, native.params
    tgt = np.asarray(native.legal_target(), dtype=np.int64)
    has = tgt > 0
    tgt_c = np.where(has, tgt, 1 if st.n_balls > 1 else 0)
    sh = ghost if ghost is not None else G.ghost_shots(st.pos, st.on_table, tgt_c, table, params, 0.0)
    E, P = sh["phi"].shape
    diag = math.hypot(table.width, table.length)
    base = native.aim_origin()  # the env's aim origin (relative aim: the cue -> target direction)
    rel = (sh["phi"] - base[:, None]) / math.pi
    rel = (rel + 1.0) % 2.0 - 1.0
    rel = np.clip(rel / aim_scale, -1.5, 1.5)
    speed = G.required_speed(sh["d_cg"], sh["d_op"], sh["cut"], params)
    draw = np.clip(speed_to_draw(speed, params), 0.0, params.max_draw)
    cfg = getattr(native, "config", None)
    lo = getattr(cfg, "min_draw", 0.0) if cfg is not None else 0.0
    draw_act = 2.0 * (draw - lo) / (params.max_draw - lo) - 1.0
    open_ = (sh["valid"] & ~sh["blocked"]).astype(np.float64)
    f = np.stack([rel, sh["cut"] / (math.pi / 2), sh["d_cg"] / diag, sh["d_op"] / diag, draw_act, open_], axis=2)
    f[~has] = 0.0
    return f.reshape(E, P * N_FEAT_PER_POCKET).astype(np.float32)


def scale_actions(actions: np.ndarray, aim_scale: float) -> np.ndarray:
    a = np.array(actions, dtype=np.float32, copy=True)
    a[:, 0] = np.clip(a[:, 0], -1.0, 1.0) * aim_scale
    return a


def residual_actions(native, actions: np.ndarray, aim_scale: float, speed_scale: float = 0.5,
                     spin_scale: float = 1.0) -> np.ndarray:
    """Residual mode: the policy's action corrects the ghost-ball shot
    (``geometry.ghost_ball_shot``: easiest open pocket, model speed, centre
    hit), in shot space: aim phi = ghost phi + pi * aim_scale * a0; speed =
    ghost speed * exp(speed_scale * a1) (at most max_speed); side/height =
    spin_scale * (a2, a3) of the miscue limit. The corrected shots are mapped
    to the env's actions once (``shots_to_actions``)."""
    a = np.clip(np.asarray(actions, dtype=np.float64), -1.0, 1.0)
    params, st = native.params, native.state
    tgt = np.asarray(native.legal_target(), dtype=np.int64)
    has = tgt > 0
    ghost = G.ghost_ball_shot(st.pos, st.on_table, np.where(has, tgt, 1), native.table, params)
    lim = params.miscue_limit
    shots = Shots(ghost.phi + math.pi * aim_scale * a[:, 0],
                  np.minimum(ghost.speed * np.exp(speed_scale * a[:, 1]), params.max_speed),
                  spin_scale * a[:, 2] * lim, spin_scale * a[:, 3] * lim)
    out = np.asarray(native.shots_to_actions(shots), dtype=np.float64)
    out[~has] = a[~has]  # no target (cannot happen on PotOne): pass the action through
    return np.clip(out, -1.0, 1.0).astype(np.float32)


def transform_actions(native, actions, mode: str, aim_scale: float) -> np.ndarray:
    """The policy's actions -> the env's, for ``mode`` (``ACTION_MODES``);
    on a game (``OnePlayerView``) completed to the game's 8 components."""
    if mode == "residual":
        a = residual_actions(native, actions, aim_scale)
    elif mode == "choice":
        a = choice.choice_actions(native, actions)
    else:
        a = scale_actions(np.clip(actions, -1.0, 1.0), aim_scale)
    complete = getattr(native, "complete_actions", None)
    if complete is None:
        return a
    return complete(a, np.asarray(actions).reshape(len(a), -1)[:, 0] if mode == "choice" else None)


def agent_features(native, features: bool, aim_scale: float, mode: str) -> np.ndarray | None:
    """What the agent appends to the env's observation: the ghost-ball
    features (``features``), then the menu's contact features (mode
    ``choice``); None if nothing."""
    ghost = choice.menu(native).ghost if mode == "choice" else None  # the menu's own ghost-ball shots
    parts = [shot_features(native, aim_scale, ghost)] if features else []
    if mode == "choice":
        parts.append(choice.contact_features(native))
    return np.concatenate(parts, axis=1) if parts else None


def n_agent_features(native, features: bool, mode: str) -> int:
    return (n_features(native) if features else 0) + (choice.N_CONTACT_FEATURES if mode == "choice" else 0)

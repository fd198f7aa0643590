"""``action_mode: choice``: the policy picks a shot from a menu.

A pool player first chooses *what* to play (which pocket, or just a safe
touch on the legal ball when nothing pots), then how hard and with which
spin. With continuous actions that first choice is a jump between distant
aims, which a Gaussian policy rarely makes (``residual`` is tied to the
ghost-ball shot's pocket; ``direct`` settles on one pocket). Here the
action is ``MultiDiscrete([C, S, H])``:

- ``c`` < P (pockets): the ghost-ball shot into pocket ``c``
  (``geometry.ghost_shots``), at ``required_speed`` (no margin);
- ``c`` >= P: a *contact* shot, a hit of fullness ``CONTACT_FULLNESS[c - P]``
  on the legal ball (``geometry.contact_shots``), at the speed that reaches
  it with ``CONTACT_ARRIVAL`` m/s: a legal shot that keeps the turn where
  misses are free (NineBall, RunOut);
- the last ``N_KICKS`` items: one-rail *kicks*, a full hit on the legal ball
  off each rail (``geometry.kick_shots``), at the speed that reaches it
  with ``KICK_ARRIVAL`` m/s: what is left when every straight path to the
  legal ball is blocked;
- ``s``: the speed times ``SPEED_LEVELS[s]``;
- ``h``: the tip's height offset ``HEIGHT_LEVELS[h]`` x the miscue limit
  (draw below 0, follow above); no side spin.

Nothing is simulated to build the menu: its aims are geometry, and which
item pots, scratches or leaves a next shot is what the policy learns. The
observation gets, per pocket, the ghost-ball features of
``bots.learned.features.shot_features`` and, per contact shot and kick, whether its
path is open and its length (``contact_features``).
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np
from gymnasium import spaces

from ...physics.strike import Shots

from .. import geometry as G

# Fullness (impact parameter / 2R) of the contact shots: full, half-ball each side, thin each side.
CONTACT_FULLNESS = (0.0, 0.35, -0.35, 0.7, -0.7, 0.9, -0.9)
CONTACT_ARRIVAL = 0.5   # m/s at contact: moves the object ball a little, keeps the cue ball near
N_KICKS = 4             # one per rail
# m/s at contact if the rail took nothing; it takes (1 - e^2) of the normal speed's energy, and more with spin
KICK_ARRIVAL = 2.0
SPEED_LEVELS = (0.6, 0.8, 1.0, 1.3, 1.7, 2.3, 3.0)
HEIGHT_LEVELS = (-0.7, -0.35, 0.0, 0.35, 0.7)


def n_items(native) -> int:
    return len(native.table.pockets) + len(CONTACT_FULLNESS) + N_KICKS


def action_space(native) -> spaces.MultiDiscrete:
    return spaces.MultiDiscrete([n_items(native), len(SPEED_LEVELS), len(HEIGHT_LEVELS)])


N_CONTACT_FEATURES = 2 * (len(CONTACT_FULLNESS) + N_KICKS)


@dataclass(frozen=True)
class Menu:
    """Every table's menu for one state of a native env."""
    context: object      # the env's ShotContext of that state: the same object while the state is unchanged
    ghost: dict          # geometry.ghost_shots of the legal balls (also the agent's pocket features)
    phi: np.ndarray      # [E, C] aims
    speed: np.ndarray    # [E, C] nominal strike speeds
    open_: np.ndarray    # [E, F + N_KICKS] contact shots' and kicks' paths open
    length: np.ndarray   # [E, F + N_KICKS] their path lengths (m)


_MENUS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # native env -> the Menu of its last state


def menu(native) -> Menu:
    """The menu of the native env's current tables, built once per state:
    the observation's features and the next step's actions read the same
    one. The env caches its ``shot_context()`` until the state changes, so
    the same context object means the same positions."""
    ctx = native.shot_context()
    m = _MENUS.get(native)
    if m is None or m.context is not ctx:
        m = _MENUS[native] = _build_menu(native, ctx)
    return m


def _build_menu(native, ctx) -> Menu:
    st, table, params = native.state, native.table, native.params
    tgt = np.asarray(ctx.target, dtype=np.int64)
    tgt = np.where(tgt > 0, tgt, 1 if st.n_balls > 1 else 0)
    sh = G.ghost_shots(st.pos, st.on_table, tgt, table, params, 0.0)
    v_pot = G.required_speed(sh["d_cg"], sh["d_op"], sh["cut"], params, margin=1.0)
    phi_c, length, blocked = G.contact_shots(st.pos, st.on_table, tgt, np.asarray(CONTACT_FULLNESS), params.R,
                                             table.width, table.length)
    v_contact = G.rolling_strike_speed(length, CONTACT_ARRIVAL, params)
    phi_k, length_k, blocked_k = G.kick_shots(st.pos, st.on_table, tgt, params.R, table.width, table.length,
                                              table.pockets)
    v_kick = G.rolling_strike_speed(length_k, KICK_ARRIVAL, params)
    return Menu(ctx, sh, np.concatenate([sh["phi"], phi_c, phi_k], axis=1),
                np.concatenate([v_pot, v_contact, v_kick], axis=1), ~np.concatenate([blocked, blocked_k], axis=1),
                np.concatenate([length, length_k], axis=1))


def contact_features(native) -> np.ndarray:
    """Features [E, N_CONTACT_FEATURES]: per contact shot and kick, 1 if its
    path is open (``geometry.contact_shots``, ``kick_shots``) and its length
    / table diagonal."""
    m = menu(native)
    diag = math.hypot(native.table.width, native.table.length)
    f = np.stack([m.open_.astype(np.float64), m.length / diag], axis=2).reshape(len(m.length), -1)
    return f.astype(np.float32)


def choice_actions(native, actions) -> np.ndarray:
    """Menu choices int [E, 3] -> the env's actions float32 [E, 4]."""
    a = np.asarray(actions).reshape(-1, 3).astype(np.int64)
    nvec = action_space(native).nvec
    if (a < 0).any() or (a >= nvec[None]).any():
        raise ValueError(f"choice actions must lie in [0, {list(nvec)}) per column, got {a.min(0)}..{a.max(0)}")
    m = menu(native)
    phi, speed = m.phi, m.speed
    ar = np.arange(len(a))
    params = native.params
    v = np.minimum(speed[ar, a[:, 0]] * np.asarray(SPEED_LEVELS)[a[:, 1]], params.max_speed)
    height = np.asarray(HEIGHT_LEVELS)[a[:, 2]] * params.miscue_limit
    shots = Shots(phi[ar, a[:, 0]], v, np.zeros(len(a)), height)
    return np.clip(np.asarray(native.shots_to_actions(shots), dtype=np.float32), -1.0, 1.0)

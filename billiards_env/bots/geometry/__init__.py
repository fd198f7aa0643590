"""Ghost-ball geometry: the shots a pool player sees on a table.

The ghost-ball construction (Alciatore, "The Illustrated Principles of Pool
and Billiards", ghost-ball aiming): to send the object ball at O towards an
aim point P, the cue ball must arrive at the *ghost ball* G = O - 2R *
unit(P - O), so the cue aims at G. The cut angle theta is the angle between
the cue's path (C -> G) and the object ball's path (O -> P); the object
ball leaves with about v_c * cos(theta) * (1 + e_b) / 2 of the cue ball's
speed v_c. A pot is open when no other ball lies within 2R of either path
and the object ball comes into the pocket within its acceptance angle.

One job per module:

- ``lines``: the construction's scalar kernels (ghost ball, cut, approach to a
  pocket, segment distance, blocked path), written once;
- ``pockets``: each pocket's aim point, axis, side / corner and limit;
- ``speed``: the stroke speed that carries a pot (rolling and slide losses);
- ``batched``: every pocket's ghost-ball shot over a batch of tables
  (arrays), the easiest or open pockets, the ghost-ball shot, straight
  contact and one-rail kick shots: used by the one-player bots
  (``bots.one_player``, ``bots.lookahead``) and the agents' features and
  shot menu;
- ``breaks``: the seeded 9-ball break (the NineBall task's and ``ghost``'s);
- ``game``: the game bots' per-table searches (``bots.ghost``,
  ``bots.search``): the easiest legal pot, a ball-in-hand spot, open lines.

The two callers of ``lines`` measure lengths and angles as they always
have, so that the agents' features, the one-player baselines' figures and
the game bots' match records stay bit-identical: ``batched`` rounds a
length as ``np.linalg.norm`` (``lines.line_length``) and takes numpy's
vectorised arccos / arctan2; ``game`` takes ``math.hypot`` and libm's acos /
atan2. On an AVX-512 machine (numpy 2.4, numba 0.68) they differ in the
last bit on 16% (hypot against the norm), 9% (arccos) and 8% (arctan2) of
random inputs, and the game bots moved onto the batched rounding lost
bit-identity at once (a 9-ball pairing of ``ghost-safety`` and
``search64``, 24 games, ended differently).
"""
from .batched import (KICK_POCKET_CLEAR, choose_pocket, contact_shots, ghost_ball_shot, ghost_shots,
                      kick_shots, open_pots, pot_cost)
from .game import (PotLimits, SpotLimits, best_pots, nearest_open_target, open_lines,
                   straight_in_spots)
from .pockets import pocket_aim_points, pocket_axes, pocket_limits, side_pocket_mask
from .speed import required_speed, rolling_strike_speed

__all__ = ["KICK_POCKET_CLEAR", "choose_pocket", "contact_shots", "ghost_ball_shot", "ghost_shots", "kick_shots",
           "open_pots", "pot_cost", "PotLimits", "SpotLimits", "best_pots", "nearest_open_target", "open_lines",
           "straight_in_spots", "pocket_aim_points", "pocket_axes", "pocket_limits", "side_pocket_mask",
           "required_speed", "rolling_strike_speed"]

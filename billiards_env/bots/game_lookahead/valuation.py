"""How the lookahead values a previewed shot: the ease of the next
shooter's best pot (``pots``) and the value of the table to the mover
(1 for a win, 0 for a loss; the leave's ``position_value`` if the mover
keeps the table, 1 minus the opponent's if the turn passes)."""
from __future__ import annotations

import math

import numpy as np

from ...physics.noise import NoiseConfig
from ...rules import records as RR
from .pots import (BLOCK_CLEAR, HAND_DCG, MAX_CUT, MIN_AIM_SIGMA, ROLL_MIN, PocketModel, PotArrays, _leave_ease,
                   _pot_table, position_value)


class Valuation:
    """The geometry and the valuation of ``GameLookahead`` (a mixin: it reads the bot's ``model``,
    ``sigma_model``, ``v_none``, ``v_full`` and ``leaf_value``)."""

    def pockets(self, view) -> PocketModel:
        m = self.model
        if m is None or m.table is not view.table or m.params is not view.params:
            self.model = m = PocketModel(view)
        return m

    def _lim(self, view):
        aim = max(math.radians(view.noise.aim_deg), MIN_AIM_SIGMA)
        return (view.params.R, BLOCK_CLEAR, MAX_CUT, aim, self.sigma_model, HAND_DCG)

    def pot_table(self, view, pos, on, targets, cue, hand):
        """``_pot_table`` over tables (cue ball at ``cue`` [n, 2], ``hand`` [n]): dict of [n, B, P] arrays."""
        n, B = pos.shape[:2]
        P = len(self.pockets(view).aims)
        out = PotArrays(*(np.zeros((n, B, P)) for _ in PotArrays._fields))
        _pot_table(np.ascontiguousarray(pos), np.ascontiguousarray(on), np.ascontiguousarray(targets),
                   np.ascontiguousarray(cue, dtype=np.float64), np.ascontiguousarray(hand, dtype=np.bool_),
                   self.pockets(view).arrays(), self._lim(view), out)
        return out._asdict()

    def leave_ease(self, view, pos, on, targets, hand) -> np.ndarray:
        """[n] the ease of the shooter's best pot on tables after a shot (``hand``: ball in hand)."""
        out = np.empty(len(pos))
        _leave_ease(np.ascontiguousarray(pos), np.ascontiguousarray(on), np.ascontiguousarray(targets),
                    np.ascontiguousarray(hand, dtype=np.bool_), self.pockets(view).arrays(), self._lim(view), out)
        return out

    def pot_speed(self, view, dcg, dop, cut) -> np.ndarray:
        """The cue-ball speed that just drops a ball (rolling after a stun hit, slowed by rolling resistance)."""
        p = view.params
        dec = 2.0 * p.mu_r * p.g
        v_ob = np.sqrt(dec * dop + ROLL_MIN ** 2) * 7.0 / 5.0
        v_c = v_ob / np.maximum(np.cos(cut), 0.25)
        return np.sqrt(v_c ** 2 + dec * dcg) * 7.0 / 5.0

    def values(self, view, pv) -> np.ndarray:
        """The mover's value of each previewed shot (module docstring, step 3)."""
        rec, nxt = pv.record, pv.next
        hand = nxt.ball_in_hand != RR.IN_HAND_NONE
        e = self.leave_ease(view, pv.pos, pv.on_table, nxt.targets, hand)
        if self.leaf_value is None:
            v = self.position_value(view, e, pv.on_table, nxt.targets)
        else:
            v = self.leaf_value(view, pv.pos, pv.on_table, nxt.targets, nxt.ball_in_hand, e)
        keep = nxt.shooter == rec.shooter
        val = np.where(keep, v, 1.0 - v)
        return np.where(rec.game_over, (rec.winner == rec.shooter).astype(np.float64), val)

    def position_value(self, view, ease, on, targets) -> np.ndarray:
        """``position_value`` of tables after shots (the next shooter's chance from their best pot's ease)."""
        return position_value(ease, self.v_none, self.v_full)

    def noise(self, view):
        return "env" if view.noise.enabled else NoiseConfig.from_any("tournament")

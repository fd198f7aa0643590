"""Whole two-player games as replays.

A ``GameRecorder`` listens to a ``GameCore`` (``core.listeners``; the core
must keep event logs: ``GameCore(..., record=True)``, or an env made with a
``render_mode``) and writes every turn of the tables it watches into one
``Replay`` per game: each shot from its event log, each pass (after a
push-out the shot handed back, no ball moving) as a still entry, so a shot is
never written twice. A game starts at the break (or wherever the recorder
joined) and ends when the game is over or cut at the shot cap; the next
turn on that table starts the next game.

Each entry's ``info["game"]`` holds the game around that turn, in words as
well as numbers: the shooter, the state before the turn and after it (who
is to move, ball in hand and where it may go, the legal targets, fouls in a
row, the 8-ball groups, push-out / pass / call, the score: points in the
games to a score, else games won on that table), the declaration, the called pocket, where the cue ball was
placed, the ruling's fields and one sentence of ruling
(``game_words.ruling_words``). The replay's top-level ``game`` entry holds
the game's name, the players, the head string and the pockets' names. The
format: docs/replay.md.
"""
from __future__ import annotations

import numpy as np

from ..rules import HEAD_STRING
from ..rules.placement import d_of
from .game_words import (ball_ids, call_words, end_words, foul_words, game_words, group_words, in_hand_words,
                         player_labels, pocket_names, ruling_words, words_of)
from .replay import Replay

DEFAULT_PLAYERS = ("", "")


def state_words(core, k: int, score) -> dict:
    """Where table ``k``'s game stands, for the next turn."""
    c, g = core.constraints(), core.game
    groups = [group_words(x) for x in g.group[k]] if core.rules.groups else None
    return {"to_move": int(c.shooter[k]), "ball_in_hand": in_hand_words(c.ball_in_hand[k]),
            "targets": np.nonzero(c.targets[k])[0].astype(int).tolist(), "break": bool(c.is_break[k]),
            "push_out_allowed": bool(c.push_out_allowed[k]), "may_pass": bool(c.may_pass[k]),
            "call_needed": bool(c.call_needed[k]), "fouls": g.fouls[k].astype(int).tolist(), "groups": groups,
            "shots": int(g.shots[k]), "over": bool(g.over[k]), "winner": int(g.winner[k]),
            "score": [int(x) for x in (g.score[k] if core.rules.to_points else score)],
            "score_of": "points" if core.rules.to_points else "games won",
            "call": call_words(core.config.game) if c.call_needed[k] else None,
            **({"ball_ids": ball_ids(core, k, int(c.shooter[k]))} if core.rules.own_cue_balls else {})}


def game_entry(core, players, labels, start, pockets_named=None) -> dict:
    """A game replay's top-level ``game`` entry: the game's name and title, the players and their labels, the
    head string, the pockets' names and the game state before the break (``start``); and, where the game's words
    or its table have them, ``ball_names`` (each ball's name by ball number, from the registry's ``GameWords``:
    snooker's colours, the carom balls; absent for numbered pool balls), ``pockets: false`` (a carom game: no
    pockets) and ``d`` ([cx, cy, r] m: the D, where a ball in hand "in the D" goes)."""
    t, words = core.table, words_of(core.config.game)
    out = {"name": core.config.game, "title": game_words(core.config.game), "players": list(players),
           "labels": list(labels), "head_string": HEAD_STRING * t.length,
           "pocket_names": pocket_names(core.pockets) if pockets_named is None else pockets_named, "start": start}
    if words.balls:
        out["ball_names"] = list(words.balls)
    if not words.pockets:
        out["pockets"] = False
    d = d_of(t)
    if d is not None:
        out["d"] = [float(x) for x in d]
    return out


class GameRecorder:
    """Record tables ``tables`` of ``core`` (a ``GameCore`` with
    ``record=True``), one ``Replay`` per game. ``players``: the two
    players' names (the viewer shows them beside the labels); ``meta``: the
    replays' ``meta`` (a title, the seed, ...). The rulings call the players
    'Player 1' and 'Player 2' (player numbers 0 and 1). ``games(k)``: the games of
    table ``k`` recorded so far, the one in progress last."""

    def __init__(self, core, tables=(0,), players=DEFAULT_PLAYERS, meta: dict | None = None):
        if not getattr(core, "record", False):
            raise ValueError("the GameCore keeps no event logs: create it with record=True (an env: with "
                             "render_mode='rgb_array')")
        if len(players) != 2:
            raise ValueError(f"players must name the two players, got {players!r}")
        tables = [int(k) for k in np.atleast_1d(tables)]
        bad = [k for k in tables if not 0 <= k < core.n_envs]
        if bad:
            raise ValueError(f"tables {bad} are not tables of the core (it has {core.n_envs})")
        self.core, self.tables = core, tables
        self.players, self.meta = [str(p) for p in players], dict(meta or {})
        self.labels = player_labels(2)
        self._games = {k: [] for k in tables}
        self._open = {k: False for k in tables}      # the last game of table k is still being played
        self._score = {k: [0, 0] for k in tables}
        self._before: dict = {}
        self._last_log = {k: None for k in tables}
        self._pocket_names = pocket_names(core.pockets)
        core.listeners.append(self)

    def detach(self) -> None:
        """Stop recording (the games so far stay)."""
        if self in self.core.listeners:
            self.core.listeners.remove(self)

    def games(self, k: int = 0) -> list[Replay]:
        return list(self._games[k])

    def take_finished(self, k: int = 0, unfinished: bool = False) -> list[Replay]:
        """Remove and return table ``k``'s finished games (and the one in progress, if ``unfinished``)."""
        n = len(self._games[k]) - (1 if self._open[k] and not unfinished else 0)
        if unfinished:
            self._open[k] = False
        done, self._games[k] = self._games[k][:n], self._games[k][n:]
        return done

    def _new_game(self, core, k: int) -> None:
        t = core.table
        vs = " v ".join(f"{lab} ({p})" if p else lab for lab, p in zip(self.labels, self.players))
        meta = {"title": f"{game_words(core.config.game)}: {vs}",
                **self.meta, "game": core.config.game, "players": self.players, "game_number": len(self._games[k])}
        rep = Replay.for_table(t, core.params, core.effects, n_balls=core.n_balls, meta=meta)
        rep.data["game"] = game_entry(core, self.players, self.labels, state_words(core, k, self._score[k]),
                                      self._pocket_names)
        self._games[k].append(rep)
        self._open[k] = True
        self._last_log[k] = core.last_events[k]  # a log from before this game is not this game's

    # --- the core's listener protocol ---------------------------------------------
    def before_step(self, core, idx, actions) -> None:
        for j, k in enumerate(np.asarray(idx).tolist()):
            if k not in self._games:
                continue
            if not self._open[k] or core.game.shots[k] == 0 and len(self._games[k][-1]) > 0:
                self._new_game(core, k)
            self._before[k] = (state_words(core, k, self._score[k]), core.state.pos[k].copy(),
                               core.state.pocket[k].copy(), np.asarray(actions[j], dtype=np.float64).copy())

    def after_step(self, core, idx, out) -> None:
        info, rec = out["info"], out["record"]
        for j, k in enumerate(np.asarray(idx).tolist()):
            if k not in self._games:
                continue
            before, pos, pocket, action = self._before.pop(k)
            s = int(rec.shooter[j])
            over, cut = bool(out["terminated"][j]), bool(out["truncated"][j])
            if over and int(rec.winner[j]) >= 0:
                self._score[k][int(rec.winner[j])] += 1
            called = int(info["called_pocket"][j])
            words = words_of(core.config.game)
            nominated = int(info["called_ball"][j]) if words.nominates else -1
            if words.nominates:  # a nomination names a ball, not a pocket
                called = -1
            game = {"shooter": s, "before": before, "game_name": core.config.game,
                    "nominated": nominated if nominated > 0 else None,
                    "passed": bool(info["passed"][j]), "push_out": bool(rec.push_out[j]),
                    "declared": "pass" if info["passed"][j] else ("push-out" if rec.push_out[j] else None),
                    "called_pocket": self._pocket_names[called] if called >= 0 else None,
                    "placement": (np.asarray(info["placement"][j]).tolist()
                                  if before["ball_in_hand"] != "none" and not info["passed"][j] else None),
                    "placement_moved": bool(info["placement_moved"][j]),
                    "legal": bool(rec.legal[j]), "foul": foul_words(rec.foul[j]), "turn_over": bool(rec.turn_over[j]),
                    "game_over": bool(rec.game_over[j]), "winner": int(rec.winner[j]),
                    "end": end_words(rec.end[j]) if rec.game_over[j] else None, "truncated": cut,
                    "pocketed": np.nonzero(info["pocketed"][j])[0].astype(int).tolist(),
                    "respotted": np.nonzero(rec.respot[j])[0].astype(int).tolist(),
                    "after": state_words(core, k, self._score[k])}
            off = np.nonzero(info["off_table"][j])[0] if "off_table" in info else ()
            if len(off):  # balls driven off the table (a foul; only with the airborne effect)
                game["off_table"] = off.astype(int).tolist()
            if core.rules.to_points:  # games to a score: the shot's points, the score after it
                game["points"] = int(info["points"][j])
                game["score"] = np.asarray(info["score"][j]).astype(int).tolist()
            if core.rules.replaces and rec.replaced[j]:  # snooker: the balls replaced after a miss (no stroke)
                game["replaced"], game["declared"] = True, "replace"
            game["ruling"] = ruling_words(game, self.labels)
            rep = self._games[k][-1]
            shot_info = {"action": action.tolist(), "game": game}
            if core.rules.own_cue_balls:  # the ball in each slot: slot 0 is the shooter's (the starter's is white)
                shot_info["ball_ids"] = ball_ids(core, k, s)
            if info["passed"][j]:
                rep.add_still(pos, pocket, info=shot_info)
            else:
                log = core.last_events[k]
                if log is None or log is self._last_log[k]:
                    raise RuntimeError(f"table {k}: the core kept no new event log for a played shot")
                self._last_log[k] = log
                rep.add_log(log, info=shot_info, duration=float(info["sim_time"][j]))
            if over or cut:
                self._open[k] = False

"""One game on the play server: a ``GameCore`` of one table, its
``GameRecorder`` and the bots of the players who are not people.

Every turn goes through the library: a person's shot is encoded with the
table's ``ActionCodec`` (``contract.codec``) and played by
``GameCore.step``, a bot's through ``envs.games.play.bot_actions``, so the
rules, the simulator and the record are the ones every env and match uses.
The recorder (``rendering.game_replay``) writes each turn as a replay entry;
the page animates those entries with the replay viewer, and the saved file
is that replay's viewer page (``rendering.html.replay_html``).
"""
from __future__ import annotations

import math
import threading
import time

import numpy as np

from ..bots.registry import default_bot, make_bot
from ..envs.games import GameConfig, GameCore
from ..envs.games.play import bot_actions
from ..rendering.game_replay import GameRecorder, game_entry, state_words
from ..rendering.game_words import ball_ids, game_words, pocket_names, words_of
from ..rendering.replay import Replay
from ..rules import records as R
from ..rules.placement import FOOT_SPOT, HEAD_STRING, KITCHEN_GAP, d_of
from ..rules.snooker import FIRST_COLOUR
from ..contract.codec import MAX_ACTION_ELEVATION
from ..physics.params import draw_to_speed
from ..physics.strike import Shots
from ..physics.state import SPOT_CLEAR, SPOT_EDGE

HUMAN = "human"          # a player's name for a person at the screen
MAX_SHOTS = 200          # shot cap of a played game (GameConfig.max_shots): a draw after this many shots


class PlayError(Exception):
    """A request the game cannot take: ``status`` (an HTTP 4xx or 503 code), a message saying what is wrong,
    and any ``headers`` of the answer (a 503's Retry-After)."""

    def __init__(self, status: int, message: str, headers: dict | None = None):
        super().__init__(message)
        self.status, self.message, self.headers = int(status), str(message), dict(headers or {})


def placement_problem(core: GameCore, xy) -> str | None:
    """Why the cue ball may not be placed at ``xy`` on table 0 (None: it may),
    by the library's own legal-placement test (``GameCore.legal_placement``)."""
    x, y = float(xy[0]), float(xy[1])
    _, moved = core.legal_placement(np.array([[x, y]]), [0])
    if not moved[0]:
        return None
    t, Rb, s = core.table, core.params.R, core.state
    edge = Rb + SPOT_EDGE
    # in a player's words: where it is wrong, not coordinates in metres (the page shows the spot)
    if not (edge <= x <= t.width - edge and edge <= y <= t.length - edge):
        return "the cue ball there is off the bed or touches a cushion: place it a little further in"
    if core.constraints().ball_in_hand[0] == R.IN_HAND_KITCHEN and y > HEAD_STRING * t.length - KITCHEN_GAP:
        return "the cue ball there is beyond the head string: place it behind the line (the kitchen)"
    d = d_of(t)
    if core.constraints().ball_in_hand[0] == R.IN_HAND_D and not (y <= d[1] - KITCHEN_GAP and
                                                                   math.hypot(x - d[0], y - d[1]) <= d[2]):
        return "the cue ball there is outside the D: place it inside the half circle on the baulk line"
    d = np.hypot(s.pos[0, 1:, 0] - x, s.pos[0, 1:, 1] - y)
    on = s.pocket[0, 1:] < 0
    hit = np.nonzero(on & (d < 2 * Rb + SPOT_CLEAR))[0]
    if len(hit):
        return f"the cue ball there overlaps {ball_said(core, int(hit[0]) + 1)}"
    return "the cue ball there lies over a pocket"


def ball_said(core: GameCore, slot: int) -> str:
    """Ball ``slot`` of table 0 in a refusal: 'ball 3' in the pool games, by name where the game names its balls
    (the registry's ``GameWords.balls``: 'the yellow'; three-cushion's slots through ``game_words.ball_ids``)."""
    words = words_of(core.config.game)
    if not words.balls:
        return f"ball {slot}"
    ids = ball_ids(core, 0)
    return words.ball(ids[slot] if ids is not None and 0 <= slot < len(ids) else slot)


class Session:
    """A game between two players (each ``HUMAN`` or a bot name of
    ``bots.registry``) on ``game`` (a name of ``envs.games.GAMES``), seeded
    with ``seed``; ``breaker``: who breaks (0 or 1); ``noise``: the shot
    noise of ``GameConfig`` (``none`` by default: a person's shot is played
    as aimed); ``airborne``: the balls fly (``Effects(airborne=True)``) and a
    person's shot may elevate the cue (``elevation``, up to
    ``contract.codec.MAX_ACTION_ELEVATION``: jump and massé shots)."""

    def __init__(self, gid: str, game: str, players, seed: int, breaker: int = 0, noise: str = "none",
                 airborne: bool = False):
        self.id, self.seed, self.players = gid, int(seed), [str(p) for p in players]
        air = {"effects": {"airborne": True}} if airborne else {}
        self.core = GameCore(GameConfig(game=game, noise=noise, max_shots=MAX_SHOTS, **air), 1, record=True)
        self.core.streams.seed([0], [self.seed])
        self.bots = [None if p == HUMAN else make_bot(p, seed=self.seed + k) for k, p in enumerate(self.players)]
        self.core.reset_tables([0], breaker=np.array([int(breaker)]))
        names = [("you" if self.players.count(HUMAN) == 1 else f"person {k + 1}") if p == HUMAN else p
                 for k, p in enumerate(self.players)]
        self.names = names
        self.recorder = GameRecorder(self.core, (0,), players=names,
                                     meta={"seed": self.seed, "played_on": "billiards_env play server"})
        self.start = state_words(self.core, 0, [0, 0])
        self.start_pos, self.start_pocket = self.core.state.pos[0].copy(), self.core.state.pocket[0].copy()
        self.lock = threading.Lock()
        self.inputs: list[dict] = []   # every turn as it was asked for (a person's request, or {"bot": name})
        self.timings: list[dict] = []  # seconds per turn: "think" (the bot) and "play" (step and record)

    # --- what the page shows ----------------------------------------------------
    @property
    def game(self) -> str:
        return self.core.config.game

    def replay(self) -> Replay | None:
        """The game's replay so far (None before the first turn)."""
        games = self.recorder.games(0)
        return games[-1] if games else None

    def shots(self, since: int = 0) -> list[dict]:
        rep = self.replay()
        return [] if rep is None else rep.shots[since:]

    @property
    def turn(self) -> int:
        """The number of the turn to be played next (turns played so far): a shot request names it, so a
        request sent twice, or for a turn another tab has played, is refused instead of played again."""
        return len(self.timings)

    def finished(self) -> bool:
        """Whether the game is over (won, or cut at the shot cap)."""
        g = self.core.game
        return bool(g.over[0]) or bool(g.shots[0] >= self.core.config.max_shots)

    def n_shots(self) -> int:
        rep = self.replay()
        return 0 if rep is None else len(rep)

    def rack_entry(self, rep: Replay) -> None:
        """Add the rack as a still entry to ``rep`` (the page's first picture, before any shot)."""
        lab = ["Player 1", "Player 2"]
        who = lab[self.start["to_move"]]
        rep.add_still(self.start_pos, self.start_pocket, info={"game": {
            "shooter": self.start["to_move"], "before": self.start, "after": self.start, "legal": True,
            "passed": False, "rack": True, "ruling": f"The rack. {who} ({self.names[self.start['to_move']]}) breaks."}})

    def page_replay(self) -> Replay:
        """The replay the page starts from: the rack, then every turn so far."""
        c = self.core
        rep = Replay.for_table(c.table, c.params, c.effects, n_balls=c.n_balls, meta={
            "title": f"{game_words(self.game)}: Player 1 ({self.names[0]}) v Player 2 ({self.names[1]})",
            "seed": self.seed})
        recorded = self.replay()
        if recorded is not None:
            rep.data["game"] = dict(recorded.data["game"])
        else:
            rep.data["game"] = game_entry(c, self.names, ["Player 1", "Player 2"], self.start)
        self.rack_entry(rep)
        rep.data["shots"].extend(self.shots())
        return rep

    def state(self) -> dict:
        """Where the game stands and what the player to move may do."""
        c, k = self.core, 0
        cons, g = c.constraints(), c.game
        st = state_words(c, k, self._score())
        to_move = int(cons.shooter[k])
        over = bool(g.over[k]) or bool(g.shots[k] >= c.config.max_shots)
        p, t = c.params, c.table
        st.update({
            "id": self.id, "game": self.game, "title": game_words(self.game), "seed": self.seed,
            "players": self.players, "names": self.names, "over": over, "truncated": over and not bool(g.over[k]),
            "human_to_move": not over and self.bots[to_move] is None, "in_hand_code": int(cons.ball_in_hand[k]),
            "calls_ball": bool(c.rules.calls_ball), "calls_pocket": not words_of(self.game).nominates,
            "n_shots": self.n_shots(), "points": g.score[k].astype(int).tolist() if c.rules.to_points else None,
            "target": getattr(c.rules, "target", None), "turn": self.turn,
            "pos": c.state.pos[k].tolist(), "on_table": (c.state.pocket[k] < 0).tolist(),
            "limits": {"speed_min": float(draw_to_speed(c.config.min_draw, p)), "speed_max": float(p.max_speed),
                       "tip_max": float(p.miscue_limit), "R": float(p.R), "width": float(t.width),
                       "length": float(t.length), "head_string": HEAD_STRING * t.length,
                       "foot_spot": [t.width / 2, FOOT_SPOT * t.length],
                       "kitchen_y_max": HEAD_STRING * t.length - KITCHEN_GAP, "edge": float(p.R + SPOT_EDGE),
                       "clear": float(2 * p.R + SPOT_CLEAR),
                       "d": None if d_of(t) is None else d_of(t).tolist(), "kitchen_gap": KITCHEN_GAP,
                       "max_ball": int(c.n_balls - 1)},
            "pockets": c.pockets.tolist(), "hint_bot": default_bot(self.game), "pocket_names": pocket_names(c.pockets),
            "ball_names": self.ball_names(),
        })
        if c.airborne:  # the option's own entries: the cue's steepest elevation (rad), balls that fly
            st["airborne"] = True
            st["limits"]["elevation_max"] = float(MAX_ACTION_ELEVATION)
        return st

    def ball_names(self) -> list[str]:
        """Each ball on the table by slot (the ``pos`` rows), in the game's words (the registry's ``GameWords``):
        'the cue ball', 'the 7'; snooker's 'the red', 'the pink'; three-cushion's 'the white' (slot 0 holds the
        cue ball of the player to move: ``game_words.ball_ids``)."""
        c, words = self.core, words_of(self.game)
        ids = ball_ids(c, 0) or list(range(c.n_balls))
        return [words.ball(i) for i in ids]

    def _score(self):
        rep = self.replay()
        if rep is None or not rep.shots:
            return [0, 0]
        return rep.shots[-1]["info"]["game"]["after"]["score"]

    # --- turns --------------------------------------------------------------------
    def _check_turn(self, player, turn=None) -> int:
        c = self.core
        if turn is not None and turn != self.turn:
            raise PlayError(409, f"this request is for turn {turn}, which has already been played: the game is at "
                                 f"turn {self.turn} (read its state again)" if turn < self.turn else
                            f"this request is for turn {turn}, but the game is at turn {self.turn}")
        if self.finished():
            raise PlayError(409, "the game is over: start a new one")
        to_move = int(c.constraints().shooter[0])
        if player is not None and player != to_move:
            raise PlayError(409, f"it is Player {to_move + 1}'s turn, not Player {player + 1}'s")
        return to_move

    def human_shot(self, req: dict) -> list[dict]:
        """Play a person's turn ``req`` (checked by ``app.shot_request``; its ``turn``, when given, must be
        ``self.turn``): returns the new replay entries."""
        c = self.core
        to_move = self._check_turn(req.get("player"), req.get("turn"))
        if self.bots[to_move] is not None:
            raise PlayError(409, f"it is the bot's turn ({self.players[to_move]}): ask it to play (POST .../bot)")
        cons = c.constraints()
        declare = req.get("declare")
        if declare == "pass" and not cons.may_pass[0]:
            raise PlayError(400, "putting the opponent back in is not allowed now (only right after the opponent's "
                                 "foul)" if words_of(self.game).nominates else
                            "passing the shot back is not allowed now (only right after the opponent's "
                            "push-out, or in 10-ball after an illegal pot)")
        if declare == "push_out" and not cons.push_out_allowed[0]:
            raise PlayError(400, "a push-out is not allowed now (only on the shot right after the break)")
        placement = None
        if cons.ball_in_hand[0] != R.IN_HAND_NONE and declare != "pass":
            xy = req.get("placement")
            if xy is None:  # where it lies, or the nearest legal spot (the break's head spot is on the string)
                xy = c.legal_placement(c.state.pos[0, :1].copy(), [0])[0][0].tolist()
            problem = placement_problem(c, xy)
            if problem:
                raise PlayError(400, problem)
            placement = np.array([xy], dtype=np.float64)
        elif req.get("placement") is not None and declare != "pass":
            raise PlayError(400, "the cue ball is not in hand: it is played from where it lies (leave out placement)")
        pocket = req.get("pocket")
        nominating = words_of(self.game).nominates  # the call is a ball alone (snooker's nomination), no pocket
        if pocket is not None and nominating:
            raise PlayError(400, f"{game_words(self.game)} has no called pockets (leave out pocket; nominate a ball)")
        if cons.call_needed[0] and declare != "pass" and pocket is None and not nominating:
            raise PlayError(400, "this shot needs a called pocket: click a pocket (pocket 0..5)")
        ball = req.get("ball")
        if ball is not None and (not c.rules.calls_ball or ball > c.n_balls - 1):
            raise PlayError(400, f"ball {ball} cannot be called here" if c.rules.calls_ball else
                            f"{game_words(self.game)} has no called balls")
        if ball is not None and ball > 0 and c.state.pocket[0, ball] >= 0:
            raise PlayError(400, f"{ball_said(c, ball)} is not on the table")
        if nominating and ball is not None:
            ball = self._nomination(ball, cons)
        elif nominating:  # none nominated: the colour hit first counts (an obvious nomination), as a bot's -1
            ball = 0
        codec = c.codec([0])
        shots = (req["aim"], req["speed"], req.get("side", 0.0), req.get("height", 0.0))
        if req.get("elevation"):  # an elevated cue (a game started with airborne; app.shot_request checked it)
            shots = Shots(*shots, req["elevation"])
        actions = codec.encode(shots,
                               placement=placement, declare=np.array([declare is not None]),
                               pocket=None if pocket is None else np.array([pocket]),
                               ball=None if ball is None else np.array([ball]))
        self.inputs.append(dict(req))
        return self._play(actions, 0.0)

    def _nomination(self, ball: int, cons) -> int:
        """Snooker: check a nominated ``ball`` (a colour after a red; a free ball: any ball on the table)."""
        if not cons.call_needed[0]:
            raise PlayError(400, "no nomination is asked for now (only a colour after a potted red, or a free ball)")
        free = not bool(self.core.game.phase[0] == R.PHASE_COLOUR)
        if ball == 0 or (not free and ball < FIRST_COLOUR):
            raise PlayError(400, f"{ball_said(self.core, ball)} cannot be nominated: after a red, nominate a colour "
                                 f"({FIRST_COLOUR}..{self.core.n_balls - 1}: yellow .. black)" if not free else
                            f"{ball_said(self.core, ball)} cannot be nominated as the free ball: nominate an object "
                            f"ball on the table")
        return ball

    def bot_shot(self, turn: int | None = None) -> list[dict]:
        """Let the bot to move play its turn (``turn``, when given, must be ``self.turn``): the new replay entries."""
        to_move = self._check_turn(None, turn)
        bot = self.bots[to_move]
        if bot is None:
            raise PlayError(409, f"it is Player {to_move + 1}'s turn, a person's: no bot to ask")
        t0 = time.perf_counter()
        actions = bot_actions(self.core, bot, [0])
        self.inputs.append({"bot": self.players[to_move]})
        return self._play(actions, time.perf_counter() - t0)

    def _play(self, actions, think: float) -> list[dict]:
        n0 = self.n_shots()
        t0 = time.perf_counter()
        self.core.step(np.asarray(actions, dtype=np.float64), np.array([0]))
        self.timings.append({"think": think, "play": time.perf_counter() - t0})
        return self.shots(n0)

    def hint(self) -> dict:
        """The game's default bot's shot (``ghost``; three-cushion ``carom``: ``bots.registry.default_bot``) for
        the player to move, in the page's terms (aim, speed, tip, placement, call)."""
        self._check_turn(None)
        plan = make_bot(default_bot(self.core.config.game), seed=self.seed).act(self.core.view([0]))
        out = {"aim": float(plan.phi[0]) % (2 * math.pi), "speed": float(plan.speed[0]), "side": float(plan.a[0]),
               "height": float(plan.b[0]), "turn": self.turn}  # turn: the position this hint is for
        if not np.isnan(plan.placement[0, 0]):
            out["placement"] = plan.placement[0].tolist()
        if plan.pocket[0] >= 0 and not words_of(self.game).nominates:
            out["pocket"] = int(plan.pocket[0])
        if words_of(self.game).nominates:  # snooker: the bot's nomination, and its choice to put the offender back in
            cons = self.core.constraints()
            if plan.ball[0] > 0 and cons.call_needed[0]:
                out["ball"] = int(plan.ball[0])
            if plan.declare[0] and cons.may_pass[0]:
                out["declare"] = "pass"
        return out

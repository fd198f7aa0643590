"""The play server's web app (Starlette): the page, and a JSON API over
``Session`` games kept in a bounded store.

Routes (every answer to a bad request is a 4xx JSON ``{"error": ...}``
saying what is wrong; nothing else is served):

=======================================  ==================================================
``GET /``                                the lobby: pick a game and an opponent
``GET /game/{id}``                       the table: the replay viewer with the play panel
``GET /api/options``                     the games, bots and noise levels on offer
``POST /api/games``                      a new game: ``{game, opponent, seed?, breaker?, noise?}``
``GET /api/games/{id}``                  its state and every replay entry so far
``POST /api/games/{id}/place``           ``{x, y}``: may the cue ball go there? (and the nearest legal spot)
``POST /api/games/{id}/shot``            a person's turn: ``{player, aim, speed, side?, height?,
                                         placement?, declare?, pocket?, ball?}``
``POST /api/games/{id}/bot``             the bot to move plays its turn
``GET /api/games/{id}/hint``             the game's own bot's shot for the player to move
``GET /api/games/{id}/replay.html``      the game so far as one self-contained replay page
=======================================  ==================================================
"""
from __future__ import annotations

import collections
import json
import math
import secrets
import threading
from pathlib import Path

import numpy as np

from ..bots.registry import BOT_NAMES, DEFAULT_SEARCH_K, is_bot_name
from ..bots.registry import DEFAULT_BOTS, default_bot, make_bot
from ..bots.learned.ladder import ladder_names
from ..envs.games import GAMES
from ..envs.games.core import NOISE_LEVELS
from ..rendering.game_words import game_words
from ..rendering.html import replay_html
from .session import HUMAN, PlayError, Session, placement_problem

MAX_GAMES = 32            # games kept in memory; the least recently used is dropped beyond this
MAX_BODY = 16 * 1024      # bytes: the largest request body read (a shot is ~200)
MAX_SEED = 2 ** 63 - 1    # seeds are taken modulo 2**64 by the streams; larger ones are refused as typos
# the lobby's list: the bot registry's names (search<K> at its default K; a module:factory bot only when the
# server is started with it, ``--bot``: a request never makes the server import code)
OFFERED_BOTS = tuple(sorted((f"search{DEFAULT_SEARCH_K}" if n == "search<K>" else n for n in BOT_NAMES
                             if "<" not in n or n == "search<K>"), key=lambda n: n != "ghost"))  # ghost first
# the bots that play the pool games (the games without a bot of their own in bots.registry.DEFAULT_BOTS)
POOL_BOTS = ("ghost", "ghost-safety", f"search{DEFAULT_SEARCH_K}", "lookahead", "random")
HERE = Path(__file__).resolve().parent


def game_bots(game: str) -> list[str]:
    """The opponents the lobby offers for ``game``: its default bot first, then the pool bots on the pool
    games (a game with a bot of its own, snooker or three-cushion, adds ``random`` only), then the game's
    shipped ladder rungs (``ladder-1``..: 9-ball and 8-ball)."""
    own = default_bot(game)
    rest = ("random",) if game in DEFAULT_BOTS else POOL_BOTS
    return [own] + [b for b in rest if b != own] + ladder_names(game)
DECLARATIONS = ("push_out", "pass")
SHOT_FIELDS = {"player", "aim", "speed", "side", "height", "placement", "declare", "pocket", "ball"}
NEW_FIELDS = {"game", "opponent", "players", "seed", "breaker", "noise"}


# --- request checks -----------------------------------------------------------------
def _number(req, key, lo=-math.inf, hi=math.inf, default=None):
    v = req.get(key, default)
    if v is None:
        raise PlayError(400, f"'{key}' is required")
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise PlayError(400, f"'{key}' must be a finite number, got {json.dumps(v)[:40]}")
    if not lo <= v <= hi:
        raise PlayError(400, f"'{key}' = {v} is out of range [{lo:.6g}, {hi:.6g}]")
    return float(v)


def _integer(req, key, lo, hi):
    v = req.get(key)
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise PlayError(400, f"'{key}' must be an integer from {lo} to {hi}, got {json.dumps(v)[:40]}")
    return int(v)


def _fields(req, allowed):
    if not isinstance(req, dict):
        raise PlayError(400, f"the request body must be a JSON object, got {type(req).__name__}")
    extra = sorted(set(req) - allowed)
    if extra:
        raise PlayError(400, f"unknown field {extra[0]!r}; expected some of {sorted(allowed)}")


def shot_request(req, lim: dict) -> dict:
    """A person's turn checked field by field against the table's limits (``Session.state()["limits"]``)."""
    _fields(req, SHOT_FIELDS)
    out = {"player": _integer(req, "player", 0, 1) if "player" in req else None}
    declare = req.get("declare")
    if declare is not None and declare not in DECLARATIONS:
        raise PlayError(400, f"'declare' must be one of {list(DECLARATIONS)} or null, got {json.dumps(declare)[:40]}")
    out["declare"] = declare
    out["aim"] = _number(req, "aim", -2 * math.pi, 2 * math.pi, 0.0 if declare == "pass" else None)
    vmin, vmax = lim["speed_min"], lim["speed_max"]
    out["speed"] = _number(req, "speed", vmin, vmax, vmin if declare == "pass" else None)
    out["side"] = _number(req, "side", -lim["tip_max"], lim["tip_max"], 0.0)
    out["height"] = _number(req, "height", -lim["tip_max"], lim["tip_max"], 0.0)
    if math.hypot(out["side"], out["height"]) > lim["tip_max"] + 1e-12:
        raise PlayError(400, f"the tip offset ({out['side']}, {out['height']}) R is beyond the miscue limit "
                             f"{lim['tip_max']} R")
    if req.get("placement") is not None:
        p = req["placement"]
        if not (isinstance(p, list) and len(p) == 2):
            raise PlayError(400, "'placement' must be [x, y] in metres")
        out["placement"] = [_number({"x": p[0]}, "x", 0.0, lim["width"]), _number({"y": p[1]}, "y", 0.0, lim["length"])]
    if req.get("pocket") is not None:
        out["pocket"] = _integer(req, "pocket", 0, 5)
    if req.get("ball") is not None:
        out["ball"] = _integer(req, "ball", 0, lim["max_ball"])
    return out


def new_request(req, extra_bots=()) -> dict:
    """A new game's request checked; ``extra_bots``: bot specs the server was started with (``--bot``)."""
    _fields(req, NEW_FIELDS)
    game = req.get("game", "nine_ball")
    if game not in GAMES:
        raise PlayError(400, f"unknown game {json.dumps(game)[:40]}; choose one of {list(GAMES)}")
    if "players" in req:
        players = req["players"]
        if not (isinstance(players, list) and len(players) == 2):
            raise PlayError(400, "'players' must name two players: [\"human\" or a bot name, ...]")
    else:
        players = [HUMAN, req.get("opponent", default_bot(game))]
    for p in players:
        if p in extra_bots:
            continue
        if not isinstance(p, str) or not (p == HUMAN or is_bot_name(p)) or ":" in p:
            raise PlayError(400, f"unknown player {json.dumps(p)[:40]}: '{HUMAN}' or a bot name "
                                 f"({', '.join(n for n in BOT_NAMES if ':' not in n)})")
    noise = req.get("noise", "none")
    if noise not in NOISE_LEVELS:
        raise PlayError(400, f"unknown noise {json.dumps(noise)[:40]}; choose one of {list(NOISE_LEVELS)}")
    seed = req.get("seed")
    seed = secrets.randbelow(2 ** 31) if seed is None else _integer(req, "seed", 0, MAX_SEED)
    breaker = _integer(req, "breaker", 0, 1) if "breaker" in req else 0
    return {"game": game, "players": players, "seed": seed, "breaker": breaker, "noise": noise}


# --- the store ------------------------------------------------------------------------
class Store:
    """At most ``limit`` games, the least recently used dropped first."""

    def __init__(self, limit: int = MAX_GAMES):
        self.limit, self.games, self.lock = int(limit), collections.OrderedDict(), threading.Lock()

    def add(self, session: Session) -> None:
        with self.lock:
            self.games[session.id] = session
            while len(self.games) > self.limit:
                self.games.popitem(last=False)

    def get(self, gid: str) -> Session:
        with self.lock:
            s = self.games.get(gid)
            if s is None:
                raise PlayError(404, f"no game {gid[:40]!r} on this server (it holds the {self.limit} most "
                                     "recently used games; start a new one)")
            self.games.move_to_end(gid)
            return s


def create_app(max_games: int = MAX_GAMES, extra_bots=()):
    """The Starlette app. ``max_games``: games kept in memory (``MAX_GAMES``); ``extra_bots``: more
    bot specs to offer (``module:factory`` bots of your own, docs/bots.md)."""
    from starlette.applications import Starlette
    from starlette.exceptions import HTTPException
    from starlette.requests import Request
    from starlette.responses import HTMLResponse, JSONResponse, Response
    from starlette.routing import Route

    store = Store(max_games)
    extra_bots = tuple(extra_bots)
    for spec in extra_bots:
        make_bot(spec)  # a bad spec fails here, at start, with the registry's message

    def error(status, message):
        return JSONResponse({"error": message}, status_code=status)

    async def body(request: Request):
        raw = await request.body()
        if len(raw) > MAX_BODY:
            raise PlayError(413, f"the request body has {len(raw)} bytes; at most {MAX_BODY} are read")
        if not raw:
            return {}
        try:
            return json.loads(raw)
        except (ValueError, UnicodeDecodeError) as exc:
            raise PlayError(400, f"the request body is not valid JSON ({exc})") from None

    def guarded(fn):
        async def handler(request: Request):
            try:
                return await fn(request)
            except PlayError as exc:
                return error(exc.status, exc.message)
        return handler

    def run(fn, *args):
        from starlette.concurrency import run_in_threadpool
        return run_in_threadpool(fn, *args)

    def locked(session, fn, *args):
        with session.lock:
            return fn(*args)

    async def lobby(request):
        return HTMLResponse((HERE / "lobby.html").read_text())

    async def options(request):
        per_game = {g: game_bots(g) + list(extra_bots) for g in GAMES}
        offered = list(dict.fromkeys(list(OFFERED_BOTS) + [b for g in GAMES for b in per_game[g]]))
        return JSONResponse({"games": [{"id": g, "title": game_words(g), "default_bot": default_bot(g),
                                        "bots": per_game[g]} for g in GAMES],
                             "bots": offered, "bot_names": list(BOT_NAMES), "human": HUMAN,
                             "noise": list(NOISE_LEVELS), "max_games": store.limit})

    async def new_game(request):
        req = new_request(await body(request), extra_bots)
        s = await run(lambda: Session(secrets.token_hex(8), req["game"], req["players"], req["seed"],
                                      req["breaker"], req["noise"]))
        store.add(s)
        return JSONResponse(await run(locked, s, s.state), status_code=201)

    async def game_page(request):
        s = store.get(request.path_params["gid"])
        page = await run(locked, s, lambda: replay_html(s.page_replay()))
        panel = (HERE / "panel.html").read_text().replace("__GAME_ID__", s.id)
        return HTMLResponse(page.replace("</body>", panel + "\n</body>", 1))

    async def game_state(request):
        s = store.get(request.path_params["gid"])
        return JSONResponse(await run(locked, s, lambda: {"state": s.state(), "shots": s.shots()}))

    async def place(request):
        s = store.get(request.path_params["gid"])
        req = await body(request)
        _fields(req, {"x", "y"})

        def check():
            lim = s.state()["limits"]
            xy = [_number(req, "x", -1.0, lim["width"] + 1.0), _number(req, "y", -1.0, lim["length"] + 1.0)]
            if s.core.game.over[0]:
                raise PlayError(409, "the game is over: start a new one")
            if s.core.constraints().ball_in_hand[0] == 0:
                raise PlayError(409, "the cue ball is not in hand")
            spot, _ = s.core.legal_placement(np.array([xy]), [0])
            problem = placement_problem(s.core, xy)
            return {"legal": problem is None, "problem": problem, "nearest": spot[0].tolist()}
        return JSONResponse(await run(locked, s, check))

    async def shot(request):
        s = store.get(request.path_params["gid"])
        raw = await body(request)

        def play():
            req = shot_request(raw, s.state()["limits"])
            return {"shots": s.human_shot(req), "state": s.state()}
        return JSONResponse(await run(locked, s, play))

    async def bot(request):
        s = store.get(request.path_params["gid"])
        raw = await body(request)
        _fields(raw, set())
        return JSONResponse(await run(locked, s, lambda: {"shots": s.bot_shot(), "state": s.state(),
                                                          "think": s.timings[-1]["think"]}))

    async def hint(request):
        s = store.get(request.path_params["gid"])
        return JSONResponse(await run(locked, s, s.hint))

    async def saved(request):
        s = store.get(request.path_params["gid"])
        rep = s.replay()
        if rep is None or len(rep) == 0:
            raise PlayError(409, "no shot has been played yet: nothing to save")
        page = await run(locked, s, lambda: replay_html(rep))
        name = f"{s.game}_{s.id}.html"
        return Response(page, media_type="text/html",
                        headers={"Content-Disposition": f'attachment; filename="{name}"'})

    async def not_found(request, exc):
        status = getattr(exc, "status_code", 404)
        msg = {404: f"nothing at {request.url.path[:80]!r} (this server serves its page and /api only)",
               405: f"{request.method} is not allowed on {request.url.path[:80]!r}"}.get(status, str(exc.detail))
        return error(status, msg)

    async def server_error(request, exc):
        return error(500, f"the server failed on this request ({type(exc).__name__}: {exc})")

    g = "/api/games/{gid}"
    routes = [Route("/", guarded(lobby)), Route("/api/options", guarded(options)),
              Route("/api/games", guarded(new_game), methods=["POST"]),
              Route("/game/{gid}", guarded(game_page)), Route(g, guarded(game_state)),
              Route(g + "/place", guarded(place), methods=["POST"]), Route(g + "/shot", guarded(shot), methods=["POST"]),
              Route(g + "/bot", guarded(bot), methods=["POST"]), Route(g + "/hint", guarded(hint)),
              Route(g + "/replay.html", guarded(saved))]
    app = Starlette(routes=routes, exception_handlers={HTTPException: not_found, Exception: server_error})
    app.state.store = store
    return app

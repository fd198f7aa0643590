"""The play server's web app (Starlette): the page, and a JSON API over
``Session`` games kept in a bounded store.

Routes (every error answer, whatever the request, is JSON ``{"error": ...}``
naming the problem: 4xx for a request the server will not take, 503 when
every place for a game is taken by a game in play; nothing else is served;
``guard`` checks every request first, ``store`` keeps the games):

=======================================  ==================================================
``GET /``                                the lobby: pick a game and an opponent
``GET /game/{id}``                       the table: the replay viewer with the play panel
``GET /api/options``                     the games, bots and noise levels on offer
``POST /api/games``                      a new game: ``{game, opponent, seed?, breaker?, noise?}``
``GET /api/games/{id}``                  its state and every replay entry so far
``POST /api/games/{id}/place``           ``{x, y}``: may the cue ball go there? (and the nearest legal spot)
``POST /api/games/{id}/shot``            a person's turn: ``{turn, player, aim, speed, side?, height?,
                                         placement?, declare?, pocket?, ball?}`` (``turn``: the
                                         state's, so a repeated request is refused, 409)
``POST /api/games/{id}/bot``             the bot to move plays its turn: ``{turn?}``
``GET /api/games/{id}/hint``             the game's own bot's shot for the player to move
``GET /api/games/{id}/replay.html``      the game so far as one self-contained replay page
=======================================  ==================================================
"""
from __future__ import annotations

import json
import math
import re
import secrets
from pathlib import Path

import numpy as np

from ..bots.registry import BOT_NAMES, COUNTED, DEFAULT_SEARCH_K, is_bot_name
from ..bots.registry import default_bot, make_bot
from ..bots.learned.ladder import ladder_names
from ..envs.games import GAMES
from ..physics.noise import NOISE_LEVELS
from ..rules import DEFAULT_GAME, bot_games, get_game
from ..rendering.game_words import game_words
from ..rendering.html import replay_html
from .guard import BODY_TIMEOUT_S, MAX_BODY, Guard, parse_json
from .session import HUMAN, PlayError, Session, placement_problem
from .store import FINISHED_IDLE_S, GAME_IDLE_S, MAX_GAMES, Store

__all__ = ["MAX_BODY", "MAX_GAMES", "MAX_SEED", "MAX_SEARCH_K", "MAX_CAROM_K", "create_app", "new_request",
           "shot_request", "bot_problem", "PlayError"]

MAX_SEED = 2 ** 63 - 1    # seeds are taken modulo 2**64 by the streams; larger ones are refused as typos
MAX_SEARCH_K = 1024       # search<K>: 16x the default 64, <= 45 ms a shot measured (K = 16,384: 0.35 s and +40 MB)
MAX_CAROM_K = 1536        # carom<K>: 16x the default 96; <= 45 ms a shot measured (K = 6,144: 90 ms)
MAX_TURN = 10 ** 6        # a turn number past any game (games are cut at session.MAX_SHOTS shots)
BUDGETS = {"search": MAX_SEARCH_K, "carom": MAX_CAROM_K}
# the lobby's list: the bot registry's names (search<K> at its default K; a module:factory bot only when the
# server is started with it, ``--bot``: a request never makes the server import code)
OFFERED_BOTS = tuple(sorted((f"search{DEFAULT_SEARCH_K}" if n == "search<K>" else n for n in BOT_NAMES
                             if "<" not in n or n == "search<K>"), key=lambda n: n != "ghost"))  # ghost first
# the bots that play the pool games (the games without bots of their own: the registry's own_bots, rules.games)
POOL_BOTS = ("ghost", "ghost-safety", f"search{DEFAULT_SEARCH_K}", "lookahead", "random")
# and the strongest players, where the game has them (bot_problem): the search within 50 ms a shot, the Expert
# Iteration players, the strongest without search
STRONG_BOTS = ("champion", "exit-search", "exit-fast", "champion-fast")
HERE = Path(__file__).resolve().parent


def game_bots(game: str) -> list[str]:
    """The opponents the lobby offers for ``game``: its default bot first, then the pool bots and the strongest
    players that can play it on the pool games (a game with bots of its own, its spec's ``own_bots``: snooker or
    three-cushion, adds them and ``random`` only), then the game's shipped ladder rungs (``ladder-1``..)."""
    own, spec = default_bot(game), get_game(game)
    rest = spec.own_bots + ("random",) if spec.own_bots else POOL_BOTS + STRONG_BOTS
    return [own] + [b for b in rest if b != own and bot_problem(b, game) is None] + ladder_names(game)
DECLARATIONS = ("push_out", "pass")
SHOT_FIELDS = {"turn", "player", "aim", "speed", "side", "height", "elevation", "placement", "declare", "pocket",
               "ball"}
NEW_FIELDS = {"game", "opponent", "players", "seed", "breaker", "noise", "airborne"}


# --- request checks -----------------------------------------------------------------
def _shown(v) -> str:
    """A request value as the error message quotes it (at most 40 characters)."""
    try:
        text = json.dumps(v)
    except (ValueError, TypeError, RecursionError):
        text = type(v).__name__
    return text[:40] + ("..." if len(text) > 40 else "")


def _number(req, key, lo=-math.inf, hi=math.inf, default=None):
    v = req.get(key, default)
    if v is None:
        raise PlayError(400, f"'{key}' is required")
    try:
        x = None if isinstance(v, bool) or not isinstance(v, (int, float)) else float(v)
    except OverflowError:
        x = None
    if x is None or not math.isfinite(x):
        raise PlayError(400, f"'{key}' must be a finite number, got {_shown(v)}")
    if not lo <= x <= hi:
        raise PlayError(400, f"'{key}' = {_shown(v)} is out of range [{lo:.6g}, {hi:.6g}]")
    return x


def _integer(req, key, lo, hi):
    v = req.get(key)
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise PlayError(400, f"'{key}' must be an integer from {lo} to {hi}, got {_shown(v)}")
    return int(v)


def _choice(req, key, options, default):
    """``req[key]`` (or ``default``), which must be one of the strings ``options``."""
    v = req.get(key, default)
    if not isinstance(v, str) or v not in options:
        raise PlayError(400, f"unknown {key} {_shown(v)}; choose one of {list(options)}")
    return v


def _json_type(v) -> str:
    return {list: "an array", str: "a string", bool: "true or false", int: "a number", float: "a number",
            type(None): "null"}.get(type(v), type(v).__name__)


def _fields(req, allowed):
    if not isinstance(req, dict):
        raise PlayError(400, f"the request body must be a JSON object, got {_json_type(req)}")
    extra = sorted(set(req) - allowed)
    if extra:
        raise PlayError(400, f"unknown field {extra[0]!r}; expected some of {sorted(allowed)}")


def shot_request(req, lim: dict) -> dict:
    """A person's turn checked field by field against the table's limits (``Session.state()["limits"]``)."""
    _fields(req, SHOT_FIELDS)
    if "turn" not in req:
        raise PlayError(400, "'turn' is required: the number of the turn this shot is for (the state's 'turn'), so "
                             "that a request sent twice is not played twice")
    out = {"turn": _integer(req, "turn", 0, MAX_TURN),
           "player": _integer(req, "player", 0, 1) if "player" in req else None}
    declare = req.get("declare")
    if declare is not None and (not isinstance(declare, str) or declare not in DECLARATIONS):
        raise PlayError(400, f"'declare' must be one of {list(DECLARATIONS)} or null, got {_shown(declare)}")
    out["declare"] = declare
    out["aim"] = _number(req, "aim", -2 * math.pi, 2 * math.pi, 0.0 if declare == "pass" else None)
    vmin, vmax = lim["speed_min"], lim["speed_max"]
    out["speed"] = _number(req, "speed", vmin, vmax, vmin if declare == "pass" else None)
    out["side"] = _number(req, "side", -lim["tip_max"], lim["tip_max"], 0.0)
    out["height"] = _number(req, "height", -lim["tip_max"], lim["tip_max"], 0.0)
    if math.hypot(out["side"], out["height"]) > lim["tip_max"] + 1e-12:
        raise PlayError(400, f"the tip offset ({out['side']}, {out['height']}) R is beyond the miscue limit "
                             f"{lim['tip_max']} R")
    if req.get("elevation") is not None:  # the cue's elevation (rad): games started with airborne only
        if "elevation_max" not in lim:
            raise PlayError(400, "this game is played with a level cue: 'elevation' needs a game started with "
                                 "\"airborne\": true (jump and masse shots)")
        out["elevation"] = _number(req, "elevation", 0.0, lim["elevation_max"])
    if req.get("placement") is not None:
        p = req["placement"]
        if not (isinstance(p, list) and len(p) == 2):
            raise PlayError(400, f"'placement' must be [x, y] in metres, got {_shown(p)}")
        out["placement"] = [_number({"x": p[0]}, "x", 0.0, lim["width"]), _number({"y": p[1]}, "y", 0.0, lim["length"])]
    if req.get("pocket") is not None:
        out["pocket"] = _integer(req, "pocket", 0, 5)
    if req.get("ball") is not None:
        out["ball"] = _integer(req, "ball", 0, lim["max_ball"])
    return out


def new_request(req, extra_bots=()) -> dict:
    """A new game's request checked; ``extra_bots``: bot specs the server was started with (``--bot``)."""
    _fields(req, NEW_FIELDS)
    game = _choice(req, "game", tuple(GAMES), DEFAULT_GAME)
    if "players" in req:
        players = req["players"]
        if not (isinstance(players, list) and len(players) == 2):
            raise PlayError(400, f"'players' must name two players: [\"human\" or a bot name, ...], got "
                                 f"{_shown(players)}")
    else:
        players = [HUMAN, req.get("opponent", default_bot(game))]
    for p in players:
        if p == HUMAN or isinstance(p, str) and p in extra_bots:
            continue
        if _bot_family(p) is None:
            raise PlayError(400, f"unknown player {_shown(p)}: '{HUMAN}' or a bot name "
                                 f"({', '.join(n for n in BOT_NAMES if ':' not in n)})")
        problem = bot_problem(p, game)
        if problem:
            raise PlayError(400, problem)
    noise = _choice(req, "noise", tuple(NOISE_LEVELS), "none")
    seed = req.get("seed")
    seed = secrets.randbelow(2 ** 31) if seed is None else _integer(req, "seed", 0, MAX_SEED)
    breaker = _integer(req, "breaker", 0, 1) if "breaker" in req else 0
    airborne = req.get("airborne", False)
    if not isinstance(airborne, bool):
        raise PlayError(400, f"'airborne' must be true or false (balls that fly: jump and masse shots), got "
                             f"{_shown(airborne)}")
    return {"game": game, "players": players, "seed": seed, "breaker": breaker, "noise": noise, "airborne": airborne}


# --- which bots play what ----------------------------------------------------------------
def _bot_family(name) -> str | None:
    """``search``, ``carom``, ``ladder`` or the bot's own name for a built-in bot's name in plain ASCII
    (None: not a built-in bot's name; ``module:factory`` is never taken by request)."""
    if not isinstance(name, str) or ":" in name:
        return None
    if re.fullmatch(r"(search|carom)[0-9]+", name):  # a budget's family, whatever K: budget_problem judges K
        return name.rstrip("0123456789")           # (before the registry, which turns an int of 4,300+ digits away
    try:                                           # with a ValueError, and search0 away as no name at all)
        if not is_bot_name(name):
            return None
    except ValueError:
        return None
    m = re.fullmatch(r"(search|carom)[0-9]*|(ladder)-[0-9]+|[a-z-]+", name)
    return None if m is None else (m.group(1) or m.group(2) or name)


def budget_problem(name: str) -> str | None:
    """Why the budget K of ``search<K>`` / ``carom<K>`` is refused (None: from 1 to its ``BUDGETS`` limit)."""
    m = re.fullmatch(r"(search|carom)([0-9]+)", name)
    if m is None:
        return None
    kind, digits = m.group(1), m.group(2).lstrip("0") or "0"
    limit = BUDGETS[kind]
    if len(digits) <= len(str(limit)) and 1 <= int(digits) <= limit:
        return None
    shown = digits[:12] + ("..." if len(digits) > 12 else "")
    return (f"{kind}<K> takes K from 1 to {limit} candidates, not {shown} (a larger K costs seconds and "
            f"memory on every shot)")


def _value_network_games() -> list[str]:
    from ..bots.learned.value import VALUE_DIR
    return sorted(p.stem for p in Path(VALUE_DIR).glob("*.json"))


def bot_problem(name: str, game: str) -> str | None:
    """Why the built-in bot ``name`` cannot play ``game`` on this server (None: it can)."""
    from ..bots.learned.proposal_bot import shipped_games
    family, title = _bot_family(name), game_words(game)
    problem = budget_problem(name)
    if problem:
        return problem
    spec, own = get_game(game), bot_games(family)
    if own and game not in own:
        return f"the {name} bot plays {' and '.join(game_words(g) for g in own)} only, not {title}"
    if not spec.words.pockets and family not in spec.own_bots + ("random",):
        able = [f"{b}<K>" if b in COUNTED else b for b in spec.own_bots + ("random",)]
        return f"the {name} bot pots balls and {title} has no pockets: choose {' or '.join(able)}"
    if family == "ladder" and name not in ladder_names(game):
        return f"no {name} is shipped for {title} (its rungs: {', '.join(ladder_names(game)) or 'none'})"
    if family == "value-lookahead" and game not in _value_network_games():
        return f"value-lookahead has no value network for {title} (it plays {', '.join(_value_network_games())})"
    shipped = shipped_games(family) if family in ("exit-search", "exit-fast") else None
    if shipped is not None and game not in shipped:
        return (f"{name} has no trained network for {title} (it plays "
                f"{', '.join(game_words(g) for g in shipped) or 'no game yet'})")
    if family == "champion-fast" and spec.champion_fast is None:
        return f"champion-fast has no player for {title} (no player without search is measured for it)"
    return None



def create_app(max_games: int = MAX_GAMES, extra_bots=(), allowed_hosts=None, idle_s: float = GAME_IDLE_S,
               finished_idle_s: float = FINISHED_IDLE_S, body_timeout: float = BODY_TIMEOUT_S):
    """The Starlette app. ``max_games``: games kept in memory (``MAX_GAMES``; a game in play is never dropped:
    ``store``); ``extra_bots``: more bot specs to offer (``module:factory`` bots of your own, docs/bots.md);
    ``allowed_hosts``: the Host names answered (None: any); ``idle_s`` / ``finished_idle_s``: when a game may
    be dropped for a new one; ``body_timeout``: seconds for a request body to arrive (``guard``)."""
    from starlette.applications import Starlette
    from starlette.exceptions import HTTPException
    from starlette.middleware import Middleware
    from starlette.requests import Request
    from starlette.responses import HTMLResponse, JSONResponse, Response
    from starlette.routing import Route

    store = Store(max_games, idle_s, finished_idle_s)
    extra_bots = tuple(extra_bots)
    for spec in extra_bots:
        make_bot(spec)  # a bad spec fails here, at start, with the registry's message

    def error(status, message, headers=None):
        return JSONResponse({"error": message}, status_code=status, headers=headers)

    async def body(request: Request):
        return parse_json(await request.body())  # the Guard has read it, at most MAX_BODY bytes

    def guarded(fn):
        async def handler(request: Request):
            try:
                return await fn(request)
            except PlayError as exc:
                return error(exc.status, exc.message, exc.headers)
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

    def start(req) -> Session:
        try:
            return Session(secrets.token_hex(8), req["game"], req["players"], req["seed"], req["breaker"],
                           req["noise"], req.get("airborne", False))
        except (ValueError, TypeError) as exc:  # a bot that cannot be made for this game (its own message)
            raise PlayError(400, f"the game could not be set up: {exc}") from None

    async def new_game(request):
        req = new_request(await body(request), extra_bots)
        full = store.full_problem()
        if full:  # refused before a table is built
            raise full
        s = await run(start, req)
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

        def play():  # checked and played under the game's lock: two requests for one turn play it once
            req = shot_request(raw, s.state()["limits"])
            return {"shots": s.human_shot(req), "state": s.state()}
        return JSONResponse(await run(locked, s, play))

    async def bot(request):
        s = store.get(request.path_params["gid"])
        raw = await body(request)
        _fields(raw, {"turn"})
        turn = _integer(raw, "turn", 0, MAX_TURN) if "turn" in raw else None
        return JSONResponse(await run(locked, s, lambda: {"shots": s.bot_shot(turn), "state": s.state(),
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
        return error(500, f"the server failed on this request ({type(exc).__name__}: {str(exc)[:200]})")

    g = "/api/games/{gid}"
    routes = [Route("/", guarded(lobby)), Route("/api/options", guarded(options)),
              Route("/api/games", guarded(new_game), methods=["POST"]),
              Route("/game/{gid}", guarded(game_page)), Route(g, guarded(game_state)),
              Route(g + "/place", guarded(place), methods=["POST"]), Route(g + "/shot", guarded(shot), methods=["POST"]),
              Route(g + "/bot", guarded(bot), methods=["POST"]), Route(g + "/hint", guarded(hint)),
              Route(g + "/replay.html", guarded(saved))]
    guard = Middleware(Guard, allowed_hosts=allowed_hosts, max_body=MAX_BODY, body_timeout=body_timeout)
    app = Starlette(routes=routes, middleware=[guard],
                    exception_handlers={HTTPException: not_found, Exception: server_error})
    app.state.store = store
    return app

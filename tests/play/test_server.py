"""The play server's API against a server started on 127.0.0.1 by the test:
clear 4xx answers to bad requests, a bounded request fuzzer (malformed,
deep, huge and mistyped input among valid requests) after which the server
still plays, and a saved game that opens as a replay. The limits at the
socket level, the store's bound and the turn numbers: test_server_limits.py."""
from __future__ import annotations

import json
import math
import random
import time
from pathlib import Path

import numpy as np
import pytest

FUZZ_REQUESTS = 400   # random and malformed requests per fuzz run (seconds on 2 cores)
FUZZ_SECONDS = 120    # s: the fuzz run's bound (its 400 requests took 3.2 s measured on the 2-core machine)


def new_game(server, **kw):
    status, st = server("POST", "/api/games", {"game": "nine_ball", "opponent": "ghost", "seed": 11, **kw})
    assert status == 201, st
    return st


@pytest.mark.parametrize("body, status, words", [
    ({"aim": 1.0}, 400, "'speed' is required"),
    ({"aim": 99, "speed": 2}, 400, "'aim' = 99 is out of range"),
    ({"aim": 1.0, "speed": 50}, 400, "'speed' = 50 is out of range"),
    ({"aim": 1.0, "speed": 2, "side": 0.45, "height": 0.45}, 400, "beyond the miscue limit"),
    ({"aim": 1.0, "speed": 2, "placement": [0.6, 1.9]}, 400, "beyond the head string"),
    ({"aim": 1.0, "speed": 2, "placement": [0.01, 0.3]}, 400, "off the bed or touches a cushion"),
    ({"aim": 1.0, "speed": 2, "player": 1}, 409, "it is Player 1's turn, not Player 2's"),
    ({"aim": 1.0, "speed": 2, "declare": "push_out"}, 400, "a push-out is not allowed now"),
    ({"aim": 1.0, "speed": 2, "declare": "pass"}, 400, "passing the shot back is not allowed"),
    ({"aim": 1.0, "speed": 2, "declare": "foo"}, 400, "'declare' must be one of"),
    ({"aim": "left", "speed": 2}, 400, "'aim' must be a finite number"),
    ({"aim": True, "speed": 2}, 400, "'aim' must be a finite number"),
    ({"aim": 1.0, "speed": 2, "spin": 1}, 400, "unknown field 'spin'"),
    ([1, 2], 400, "must be a JSON object"),
])
def test_bad_shots_say_what_is_wrong(server, body, status, words):
    g = new_game(server)
    if isinstance(body, dict):
        got, answer = server.shot(g["id"], body)
    else:
        got, answer = server("POST", f"/api/games/{g['id']}/shot", body)
    assert got == status and words in answer["error"], answer


def test_bad_requests_of_every_kind(server):
    g = new_game(server)
    assert server.raw("POST", f"/api/games/{g['id']}/shot", b"{not json")[0] == 400
    assert "not valid JSON" in json.loads(server.raw("POST", f"/api/games/{g['id']}/shot", b"{")[1])["error"]
    assert server.raw("POST", f"/api/games/{g['id']}/shot", b"x" * 20000)[0] == 413
    assert server("POST", "/api/games", {"game": "croquet"})[0] == 400
    assert "unknown game" in server("POST", "/api/games", {"game": "croquet"})[1]["error"]
    assert "unknown player" in server("POST", "/api/games", {"opponent": "deep-blue"})[1]["error"]
    assert "unknown player" in server("POST", "/api/games", {"opponent": "os:system"})[1]["error"]  # no imports by request
    assert server("GET", "/api/games/nosuchgame")[0] == 404
    assert server("GET", "/../../etc/passwd")[0] == 404
    assert server("GET", "/billiards_env/play/app.py")[0] == 404
    assert server("DELETE", f"/api/games/{g['id']}")[0] == 405
    assert server("POST", f"/api/games/{g['id']}/bot")[0] == 409   # a person is to move
    assert "nothing to save" in server("GET", f"/api/games/{g['id']}/replay.html")[1]["error"]
    status, r = server("POST", f"/api/games/{g['id']}/place", {"x": 0.635, "y": 0.3})
    assert status == 200 and r["legal"] and r["problem"] is None


def test_a_placement_on_a_ball_is_refused(server):
    """Two people: a break, then a shot that touches nothing (a foul) gives ball in hand anywhere."""
    g = new_game(server, seed=4, opponent="human")
    gid = g["id"]
    assert server.shot(gid, {"player": 0, "aim": math.pi / 2, "speed": 8.0})[0] == 200
    st = server("GET", f"/api/games/{gid}")[1]["state"]
    cue = np.array(st["pos"][0])
    away = math.atan2(-cue[1], 0.0) if cue[1] > 0.3 else math.atan2(1.0, 0.0)  # towards the head rail, slowly
    r = server.shot(gid, {"player": st["to_move"], "aim": away, "speed": 0.34})[1]
    assert "state" in r, r
    st = r["state"]
    assert st["ball_in_hand"] == "anywhere", r["shots"][-1]["info"]["game"]["ruling"]
    ball = st["pos"][st["targets"][0]]
    status, r = server.shot(gid, {"player": st["to_move"], "aim": 0.0, "speed": 2.0,
                                                           "placement": ball})
    assert status == 400 and f"overlaps ball {st['targets'][0]}" in r["error"], r
    r = server("POST", f"/api/games/{gid}/place", {"x": ball[0], "y": ball[1]})[1]
    assert not r["legal"] and "overlaps ball" in r["problem"] and r["nearest"] != ball
    status, r = server.shot(gid, {"player": st["to_move"], "aim": 0.0, "speed": 2.0,
                                                           "placement": r["nearest"]})
    assert status == 200, r


def _junk(rng: random.Random):
    return rng.choice([None, True, -1, 0, 1e308, -1e-300, "", "x" * 50, [], [1, 2, 3], {}, {"a": 1}, 3.5, "NaN",
                       10 ** 19, -(2 ** 64), [[[[1]]]], {"a": {"b": [None]}}, "\u0000", "search131072"])


def _nested(rng: random.Random, depth: int) -> bytes:
    """``depth`` arrays or objects inside one another (the tester's 8,000-deep array among them)."""
    opener, closer = rng.choice([(b"[", b"]"), (b'{"a":', b"}")])
    return opener * depth + b"1" + closer * depth


# bodies no JSON library should turn into a 500: deep nesting, numbers past a float, literals JSON does not have
HOSTILE_BODIES = [
    lambda rng, turn: _nested(rng, rng.choice([9, 100, 1000, 8000])),
    lambda rng, turn: b'{"turn": %d, "aim": %s, "speed": 2}' % (turn, rng.choice([b"1" + b"0" * 400, b"1e400",
                                                                                  b"-1e999", b"9" * 5000])),
    lambda rng, turn: b'{"turn": %d, "aim": %s, "speed": 2}' % (turn, rng.choice([b"NaN", b"Infinity", b"-Infinity"])),
    lambda rng, turn: b'{"turn": %d, "aim": 1, "speed": 2, "placement": %s}' % (turn, _nested(rng, 3000)),
    lambda rng, turn: b'{"turn": ' + rng.choice([b"1" * 30, b"-1", b"0.5", b"true", b'"0"', b"null"]) + b', "aim": 1}',
    lambda rng, turn: b'"' + b"\\" * rng.randint(1, 3000) + b'"',
    lambda rng, turn: rng.choice([b"\xff\xfe{}", b'{"aim": "\xc3\x28"}', b"\x00" * 10, b" ", b"[]", b"null"]),
]


def _new_game_body(rng: random.Random) -> dict:
    """A new game's request with wrong types, unknown names and budgets out of range among valid ones."""
    return {"game": rng.choice(["nine_ball", "8ball", None, 9, [1], {}, "three_cushion"]),
            "opponent": rng.choice(["ghost", "random", "", 5, "x:y", ["ghost"], "search131072", "search0",
                                    "search\u00b2", "carom" + "9" * 30, "ladder-99", "snooker", "value-lookahead",
                                    "search1024", "search" + "1" * 5000]),
            "seed": rng.choice([1, -5, 2 ** 70, "s", None, 1.5, True]),
            "noise": rng.choice(["none", "tournament", [], {}, 3, None])}


def _fuzz_request(rng: random.Random, gid: str, turn: int):
    """A random request: a valid-looking shot (for the game's turn, or a wrong one) with some fields broken, a
    hostile body, a new game with wrong fields, an unknown route or method, or junk bytes."""
    kind = rng.random()
    if kind < 0.45:
        body = {"turn": turn if rng.random() < 0.85 else rng.choice([turn - 1, turn + 1, 0]),
                "player": rng.choice([0, 1]), "aim": rng.uniform(-8, 8), "speed": rng.uniform(-1, 12),
                "side": rng.uniform(-0.6, 0.6), "height": rng.uniform(-0.6, 0.6)}
        if rng.random() < 0.3:
            body["placement"] = [rng.uniform(-0.2, 1.5), rng.uniform(-0.2, 2.8)]
        if rng.random() < 0.2:
            body["declare"] = rng.choice(["push_out", "pass", "resign", None])
        if rng.random() < 0.2:
            body["pocket"] = rng.choice([-1, 0, 3, 5, 6, 2.5])
        for k in rng.sample(sorted(body), rng.randint(0, 2)):
            body[k] = _junk(rng)
        if rng.random() < 0.1:
            body[rng.choice(["aim2", "__proto__", "x" * 30])] = 1
        return "POST", f"/api/games/{gid}/shot", json.dumps(body).encode()
    if kind < 0.55:
        path = rng.choice([f"/api/games/{gid}/shot", f"/api/games/{gid}/place", "/api/games", f"/api/games/{gid}/bot"])
        return "POST", path, rng.choice(HOSTILE_BODIES)(rng, turn)
    if kind < 0.62:
        return "POST", f"/api/games/{gid}/place", json.dumps({"x": _junk(rng), "y": rng.uniform(-2, 4)}).encode()
    if kind < 0.72:
        return "POST", "/api/games", json.dumps(_new_game_body(rng)).encode()
    if kind < 0.76:
        return "POST", f"/api/games/{gid}/bot", json.dumps({"turn": rng.choice([turn, turn - 1, "x", None])}).encode()
    if kind < 0.85:
        data = bytes(rng.getrandbits(8) for _ in range(rng.randint(0, 64)))
        return rng.choice(["POST", "PUT"]), rng.choice([f"/api/games/{gid}/shot", "/api/games", f"/api/games/{gid}/bot"]), data
    path = rng.choice(["/api/games/" + "z" * rng.randint(1, 300), f"/api/games/{gid}/hint", "/static/x", "/%2e%2e/",
                       f"/game/{gid}x", f"/api/games/{gid}/replay.html", "/api/options"])
    return rng.choice(["GET", "POST", "DELETE"]), path, None


def test_fuzzed_requests_get_answers_and_the_server_still_plays(server):
    """Every answer to a random, malformed, hostile or mistyped request is a 4xx (never a 5xx) with a JSON error
    that names the problem; a game that ends is replaced, so shots keep being played between the bad requests."""
    rng = random.Random(29)
    gid, turn = new_game(server, seed=21)["id"], 0
    counts, t0 = {}, time.monotonic()
    for k in range(FUZZ_REQUESTS):
        method, path, data = _fuzz_request(rng, gid, turn)
        status, raw = server.raw(method, path, data)
        counts[status] = counts.get(status, 0) + 1
        assert status < 500, (method, path, data[:300] if data else data, raw[:300])
        if status >= 400:
            answer = json.loads(raw)
            assert isinstance(answer["error"], str) and answer["error"], answer
        st = server("GET", f"/api/games/{gid}")[1]["state"]
        if not st["over"] and not st["human_to_move"]:
            assert server("POST", f"/api/games/{gid}/bot", {"turn": st["turn"]})[0] == 200
            st = server("GET", f"/api/games/{gid}")[1]["state"]
        if st["over"]:
            gid = new_game(server, seed=100 + k)["id"]
            st = server("GET", f"/api/games/{gid}")[1]["state"]
        turn = st["turn"]
        assert time.monotonic() - t0 < FUZZ_SECONDS, f"{k} requests took over {FUZZ_SECONDS} s"
    assert counts.get(400, 0) > FUZZ_REQUESTS // 4 and counts.get(200, 0) + counts.get(201, 0) > 0, counts
    assert counts.get(409, 0) > 0 and counts.get(404, 0) + counts.get(405, 0) > 0, counts
    # still plays: a fresh game, a break and the bot's reply
    g2 = new_game(server, seed=5)
    assert server.shot(g2["id"], {"player": 0, "aim": math.pi / 2, "speed": 8.0})[0] == 200
    status, r = server("POST", f"/api/games/{g2['id']}/bot")
    assert status in (200, 409), r  # 409 when the breaker stays at the table


def test_saved_game_is_the_recorded_replay(server, tmp_path):
    from billiards_env.rendering.replay import Replay
    g = new_game(server, seed=8)
    gid = g["id"]
    server.shot(gid, {"player": 0, "aim": math.pi / 2, "speed": 8.0})
    status, page = server.raw("GET", f"/api/games/{gid}/replay.html")
    assert status == 200 and b"billiards-replay" in page and b'src="http' not in page and b"href=\"http" not in page
    shots = server("GET", f"/api/games/{gid}")[1]["shots"]
    start = page.index(b'id="replay-data">') + len(b'id="replay-data">')
    data = json.loads(page[start:page.index(b"</script>", start)].decode().replace("<\\/", "</"))
    assert Replay.from_dict(data).shots == shots and len(shots) >= 1
    assert np.isfinite(Replay.from_dict(data).positions_at(0.5)[0]).all()


def test_ten_ball_calls_are_checked(server):
    """10-ball: after the break every shot needs a called pocket; the called ball must be on the table."""
    g = new_game(server, game="ten_ball", opponent="human", seed=2)
    gid = g["id"]
    assert g["title"] == "10-ball" and not g["call_needed"]
    r = server.shot(gid, {"player": 0, "aim": math.pi / 2, "speed": 8.0})[1]
    st = r["state"]
    if st["over"]:
        pytest.fail("the 10 went down on the break: pick another seed")
    assert st["call_needed"] and st["calls_ball"]
    body = {"player": st["to_move"], "aim": 0.3, "speed": 1.0}
    if st["ball_in_hand"] != "none":
        body["placement"] = server("POST", f"/api/games/{gid}/place", {"x": 0.6, "y": 0.3})[1]["nearest"]
    status, r = server.shot(gid, body)
    assert status == 400 and "needs a called pocket" in r["error"]
    gone = [b for b in range(1, 11) if not st["on_table"][b]]
    if gone:
        status, r = server.shot(gid, {**body, "pocket": 1, "ball": gone[0]})
        assert status == 400 and "not on the table" in r["error"]
    assert server.shot(gid, {**body, "pocket": 1, "ball": 11})[0] == 400
    status, r = server.shot(gid, {**body, "pocket": 1, "ball": st["targets"][0]})
    assert status == 200 and r["shots"][-1]["info"]["game"]["called_pocket"] is not None


def test_a_bot_of_your_own_only_when_the_server_offers_it():
    from billiards_env.play.app import PlayError, new_request
    spec = "billiards_env.bots.registry:make_bot"
    with pytest.raises(PlayError, match="unknown player"):
        new_request({"opponent": spec})
    assert new_request({"opponent": spec}, extra_bots=(spec,))["players"] == ["human", spec]


def test_every_game_of_the_library_plays(server):
    """Each game the lobby offers (read from envs.games.GAMES): a break by the person, then a bot's turn."""
    games = [g["id"] for g in server("GET", "/api/options")[1]["games"]]
    from billiards_env.envs.games import GAMES
    assert games == list(GAMES)
    for game in games:
        from billiards_env.bots.registry import default_bot  # the pool bots cannot play three-cushion
        g = new_game(server, game=game, seed=12, breaker=1, opponent=default_bot(game))
        status, r = server("POST", f"/api/games/{g['id']}/bot")
        assert status == 200 and r["shots"][0]["info"]["game"]["before"]["break"], r
        assert server("GET", f"/api/games/{g['id']}/hint")[0] in (200, 409)


def _play_hints_until(server, gid, done, turns=40):
    """Play the hint's shot (the game's default bot's) for whoever is to move until ``done(state)``."""
    st = server("GET", f"/api/games/{gid}")[1]["state"]
    for _ in range(turns):
        if done(st) or st["over"]:
            return st
        h = server("GET", f"/api/games/{gid}/hint")[1]
        h.pop("declare", None)
        status, r = server.shot(gid, {"player": st["to_move"], **h})
        assert status == 200, r
        st = r["state"]
    pytest.fail(f"not reached in {turns} turns")


def test_snooker_nomination_put_back_and_the_d(server):
    """Snooker between two people: the break-off from outside the D is refused; after a potted red the
    nomination must be a colour (no pocket), and a nominated black played at another colour is a foul worth 7;
    the incoming player then puts the offender back in (the page's button: declare "pass")."""
    g = new_game(server, game="snooker", opponent="human", seed=2)
    gid, lim = g["id"], g["limits"]
    assert g["ball_in_hand"] == "in the D" and g["points"] == [0, 0] and not g["calls_pocket"] and lim["d"]
    status, r = server.shot(gid, {"player": 0, "aim": 1.5, "speed": 3.0,
                                                           "placement": [lim["width"] / 2, lim["length"] / 2]})
    assert status == 400 and "outside the D" in r["error"], r
    st = _play_hints_until(server, gid, lambda s: s["call_needed"] and not s["may_pass"])
    assert st["targets"] == list(range(16, 22)), st["targets"]   # the colours are on after a red
    h = server("GET", f"/api/games/{gid}/hint")[1]
    shot = {"player": st["to_move"], **{k: v for k, v in h.items() if k not in ("ball", "declare")}}
    assert "pocket" not in h and h.get("ball", 16) in st["targets"], h
    red = next(b for b in range(1, 16) if st["on_table"][b])
    status, r = server.shot(gid, {**shot, "ball": red})
    assert status == 400 and "nominate a colour" in r["error"], r
    status, r = server.shot(gid, {**shot, "ball": 21, "pocket": 2})
    assert status == 400 and "no called pockets" in r["error"], r
    if h.get("ball") == 21:
        pytest.fail("the hint plays at the black: pick another seed")
    shooter, before = st["to_move"], st["points"]
    status, r = server.shot(gid, {**shot, "ball": 21})   # the black nominated
    assert status == 200, r
    st, ruled = r["state"], r["shots"][-1]["info"]["game"]
    assert ruled["foul"] and st["points"][1 - shooter] == before[1 - shooter] + 7, (ruled["ruling"], st["points"])
    assert st["to_move"] == 1 - shooter and st["may_pass"]
    status, r = server.shot(gid, {"player": 1 - shooter, "declare": "pass"})
    assert status == 200 and r["shots"][-1]["info"]["game"]["passed"], r
    assert r["state"]["to_move"] == shooter and not r["state"]["may_pass"]
    status, r = server.shot(gid, {"player": shooter, "declare": "pass"})
    assert status == 400 and "putting the opponent back in is not allowed now" in r["error"], r


def test_three_cushion_turn_scores_and_no_pockets(server):
    """Three-cushion against the game's own bot (``carom`` when no opponent is named): no pockets to call,
    the points and the target in the state, and a person's turn then the bot's reply."""
    status, g = server("POST", "/api/games", {"game": "three_cushion", "seed": 3})
    assert status == 201 and g["players"] == ["human", "carom"] and g["hint_bot"] == "carom", g
    assert g["pockets"] == [] and not g["call_needed"] and g["points"] == [0, 0] and g["target"] >= 1
    gid = g["id"]
    h = server("GET", f"/api/games/{gid}/hint")[1]
    assert "pocket" not in h and "placement" not in h, h
    status, r = server.shot(gid, {"player": 0, **h})
    assert status == 200, r
    ruled, st = r["shots"][-1]["info"]["game"], r["state"]
    assert st["points"] == ruled["score"] and sum(st["points"]) == ruled["points"] in (0, 1), (ruled, st["points"])
    if not st["human_to_move"]:
        status, r = server("POST", f"/api/games/{gid}/bot")
        assert status == 200 and r["state"]["points"] == r["shots"][-1]["info"]["game"]["score"], r


def test_the_lobby_offers_each_game_its_bots(server):
    """Each game's opponents: its default bot first, the pool bots on the pool games, the ladder where shipped."""
    games = {g["id"]: g for g in server("GET", "/api/options")[1]["games"]}
    from billiards_env.bots.learned.ladder import ladder_names
    for game in ("nine_ball", "eight_ball"):
        rungs = ladder_names(game)
        assert rungs[:3] == ["ladder-1", "ladder-2", "ladder-3"]
        assert games[game]["bots"][0] == "ghost" and games[game]["bots"][-len(rungs):] == rungs
    assert not any(b.startswith("ladder") for b in games["ten_ball"]["bots"] + games["snooker"]["bots"])
    assert games["three_cushion"]["default_bot"] == "carom" and "ghost" not in games["three_cushion"]["bots"]
    assert games["snooker"]["bots"][0] == "snooker"
    docs = (Path(__file__).parents[2] / "docs" / "play.md").read_text()  # the page says which rungs the lobby lists
    assert f"`ladder-1`..`{ladder_names('nine_ball')[-1]}` on 9-ball and 8-ball" in docs
    assert ladder_names("nine_ball") == ladder_names("eight_ball")
    status, g = server("POST", "/api/games", {"game": "nine_ball", "opponent": "ladder-3", "seed": 1, "breaker": 1})
    assert status == 201 and server("POST", f"/api/games/{g['id']}/bot")[0] == 200


def test_a_game_with_jump_shots(server):
    """``airborne: true`` starts a game whose balls fly: the state gives the cue's steepest elevation, a
    person's shot elevated 40 degrees makes the cue ball jump (slate events in the shot's log); a level-cue
    game refuses an elevation, naming the switch; bad values are refused."""
    from billiards_env.contract.codec import MAX_ACTION_ELEVATION
    from billiards_env.physics import constants as C
    plain = new_game(server)
    assert "airborne" not in plain and "elevation_max" not in plain["limits"]
    got, answer = server.shot(plain["id"], {"aim": math.pi / 2, "speed": 2, "elevation": 0.5})
    assert got == 400 and "airborne" in answer["error"], answer
    assert "'airborne' must be true or false" in server("POST", "/api/games", {"airborne": "yes"})[1]["error"]
    g = new_game(server, airborne=True)
    assert g["airborne"] and g["limits"]["elevation_max"] == pytest.approx(MAX_ACTION_ELEVATION)
    got, answer = server.shot(g["id"], {"aim": math.pi / 2, "speed": 2, "elevation": 1.2})
    assert got == 400 and "'elevation' = 1.2 is out of range" in answer["error"], answer
    got, answer = server.shot(g["id"], {"aim": math.pi / 2, "speed": 6, "elevation": math.radians(40)})
    assert got == 200, answer
    core = server.app.state.store.get(g["id"]).core
    assert core.airborne and (np.asarray(core.last_events[0].kind) == C.EV_SLATE).any()

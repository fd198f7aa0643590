"""The play server never breaks (the issue's cases, each measured on 127.0.0.1):
the body limit enforced while reading (a large or lying body answered at once
and its connection closed, a short one answered within the read timeout),
malformed input of any depth or size a 400 naming the problem, bot budgets
bounded, a store that never drops a game in play, a turn number on every shot
(a repeated request is refused, not played twice), and JSON for every error,
the Host check and the HTTP parser's included."""
from __future__ import annotations

import json
import socket
import threading
import time
import urllib.parse

import pytest

from billiards_env.play.app import MAX_BODY, MAX_CAROM_K, MAX_SEARCH_K
from billiards_env.play.guard import MAX_DEPTH, MAX_INT_DIGITS, nesting_problem, parse_json
from billiards_env.play.session import PlayError
from billiards_env.play.store import Store
from tests.play.conftest import start_server

BODY_TIMEOUT_S = 1.0     # s: the test servers' body read timeout (the default, 10 s, would only slow the tests)
IDLE_S = 3.0             # s: the small store's idle time before a game may be dropped (the burst of 40 requests
#                          must end inside it: at 1 s it did not on 2 cores at a load average of 10)
ANSWER_WITHIN_S = 2.0    # s: "at once": an answer that needs no body comes well inside this (ms measured)
BIG_BODY = 50 * 1024 * 1024  # bytes: the tester's 50 MB body


@pytest.fixture(scope="module")
def tight():
    """A server with a short body timeout (the shared one's store and limits otherwise)."""
    from billiards_env.play.server import warm_up
    warm_up()
    srv, client = start_server(max_games=64, body_timeout=BODY_TIMEOUT_S)
    yield client
    srv.should_exit = True


def _address(client) -> tuple[str, int]:
    u = urllib.parse.urlsplit(client.url)
    return u.hostname, u.port


def _read_answer(sock: socket.socket, timeout: float) -> tuple[int, dict, bytes, bool]:
    """(status, headers, body, closed) of the one answer on ``sock``; ``closed``: the server closed after it."""
    sock.settimeout(timeout)
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = sock.recv(65536)
        assert chunk, f"the connection closed without an answer: {data!r}"
        data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    status = int(lines[0].split()[1])
    headers = {k.strip().lower(): v.strip() for k, _, v in (line.partition(":") for line in lines[1:])}
    while len(body) < int(headers.get("content-length", 0)):
        chunk = sock.recv(65536)
        assert chunk, "the connection closed in the middle of the answer"
        body += chunk
    try:
        closed = sock.recv(1) == b""
    except (ConnectionResetError, socket.timeout):
        closed = True  # reset: closed with the unread rest of a body; timeout: left open (checked by the caller)
    return status, headers, body, closed


def _send(client, head: bytes, body: bytes = b"", timeout: float = 10.0):
    """Send a raw request and read its answer: (status, headers, JSON body, closed, seconds)."""
    with socket.create_connection(_address(client), timeout=timeout) as sock:
        t0 = time.monotonic()
        sock.sendall(head + body)
        status, headers, data, closed = _read_answer(sock, timeout)
        return status, headers, json.loads(data), closed, time.monotonic() - t0


def _head(method: str, path: str, extra: str = "", host: str = "127.0.0.1") -> bytes:
    return f"{method} {path} HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\n{extra}\r\n".encode()


def _new(client, **kw) -> dict:
    status, g = client("POST", "/api/games", {"game": "nine_ball", "opponent": "ghost", "seed": 3, **kw})
    assert status == 201, g
    return g


# --- the body limit, enforced while reading ----------------------------------------------------
def test_a_lying_content_length_is_answered_at_once_and_closed(tight):
    """The tester's Content-Length: 1e9 with a short body: 413 at once, the connection closed (it hung)."""
    status, _, answer, closed, took = _send(tight, _head("POST", "/api/games", "Content-Length: 1000000000\r\n"),
                                            b'{"game": "nine_ball"}')
    assert status == 413 and f"at most {MAX_BODY}" in answer["error"] and closed and took < ANSWER_WITHIN_S, answer
    status, _, answer, closed, _ = _send(tight, _head("POST", "/api/games", "Content-Length: 1e9\r\n"), b"{}")
    assert status == 400 and "Content-Length" in answer["error"] and closed, answer  # h11's own 400, as JSON


def test_a_50_mb_body_is_not_read(tight):
    """A 50 MB body (the tester's took 268 ms to be read in full before its 413): the 413 comes before the
    client has sent a fraction of it, and the server closes the connection instead of reading on."""
    sent, stopped = [0], threading.Event()
    sock = socket.create_connection(_address(tight), timeout=10)

    def pour():
        try:
            sock.sendall(_head("POST", "/api/games", f"Content-Length: {BIG_BODY}\r\n"))
            chunk = b" " * 65536
            while sent[0] < BIG_BODY:
                sock.sendall(chunk)
                sent[0] += len(chunk)
        except OSError:
            pass  # the server closed the connection: what this test wants
        stopped.set()
    t0 = time.monotonic()
    threading.Thread(target=pour, daemon=True).start()
    try:
        status, _, body, closed = _read_answer(sock, 10)
        took = time.monotonic() - t0
        assert stopped.wait(10), "the server went on reading the body"
    finally:
        sock.close()
    assert status == 413 and "at most" in json.loads(body)["error"] and closed, body
    assert took < ANSWER_WITHIN_S and sent[0] < BIG_BODY // 4, (took, sent[0])


def test_a_chunked_body_stops_at_the_limit(tight):
    """No Content-Length (chunked): the body is counted as it arrives and refused just past MAX_BODY."""
    chunk = b"%x\r\n%s\r\n" % (4096, b" " * 4096)
    with socket.create_connection(_address(tight), timeout=10) as sock:
        sock.sendall(_head("POST", "/api/games", "Transfer-Encoding: chunked\r\n"))
        for _ in range(MAX_BODY // 4096 + 1):
            sock.sendall(chunk)
        status, _, body, closed = _read_answer(sock, 10)
    assert status == 413 and "reading stopped there" in json.loads(body)["error"] and closed, body


def test_a_short_body_is_answered_within_the_read_timeout(tight):
    """A body shorter than its Content-Length: 408 once the read timeout passes, the connection closed."""
    status, _, answer, closed, took = _send(tight, _head("POST", "/api/games", "Content-Length: 100\r\n"), b'{"ga')
    assert status == 408 and f"within {BODY_TIMEOUT_S:g} s" in answer["error"] and closed, answer
    assert BODY_TIMEOUT_S * 0.9 <= took < BODY_TIMEOUT_S + ANSWER_WITHIN_S, took


def test_the_server_answers_while_a_body_hangs(tight):
    """A connection waiting for its body holds nobody else up."""
    with socket.create_connection(_address(tight), timeout=10) as sock:
        sock.sendall(_head("POST", "/api/games", "Content-Length: 50\r\n") + b"{")
        t0 = time.monotonic()
        assert tight("GET", "/api/options")[0] == 200 and time.monotonic() - t0 < ANSWER_WITHIN_S


# --- every error is JSON, the Host check's and the parser's included ------------------------------
def test_a_foreign_host_gets_a_json_400(tight):
    status, _, answer, closed, _ = _send(tight, _head("GET", "/api/options", host="evil.example"))
    assert status == 400 and "evil.example" in answer["error"] and "127.0.0.1" in answer["error"] and closed, answer
    assert _send(tight, _head("GET", "/api/options", host="localhost:1234"))[0] == 200
    status, answer = tight("GET", "/no/such/page")
    assert status == 404 and "nothing at" in answer["error"]


def test_a_malformed_request_line_gets_a_json_400(tight):
    status, _, answer, closed, _ = _send(tight, b"GET /api/options HTTP/1.1\r\nHost: 127.0.0.1\r\nBad Header\r\n\r\n")
    assert status == 400 and "not valid HTTP/1.1" in answer["error"] and closed, answer


# --- malformed input of any depth or size: a 400 naming the problem -------------------------------
@pytest.mark.parametrize("body, words", [
    (b"[" * 8000 + b"]" * 8000, f"more than {MAX_DEPTH} deep"),                 # the tester's 500 (RecursionError)
    (b'{"game": ' + b"[" * 5000 + b"]" * 5000 + b"}", f"more than {MAX_DEPTH} deep"),
    (b'{"seed": 1' + b"0" * 400 + b"}", f"at most {MAX_INT_DIGITS} are taken"),  # 10**400
    (b'{"seed": 1e400}', "beyond a float's range"),
    (b'{"seed": NaN}', "NaN, which is not a JSON number"),
    (b'{"seed": -Infinity}', "-Infinity, which is not a JSON number"),
    (b'{"game": [1]}', "unknown game [1]"),
    (b'{"noise": {}}', "unknown noise {}"),
    (b'{"opponent": 5}', "unknown player 5"),
    (b'{"players": "ghost"}', "'players' must name two players"),
    (b'{"seed": 1.5}', "'seed' must be an integer"),
    (b'{"breaker": "0"}', "'breaker' must be an integer"),
    (b'"a string"', "must be a JSON object, got a string"),
    (b"\xff\xfe{}", "not UTF-8 text"),
    (b'{"game": "nine_ball",}', "not valid JSON"),
])
def test_malformed_new_games_say_what_is_wrong(tight, body, words):
    status, answer = tight.raw("POST", "/api/games", body)
    answer = json.loads(answer)
    assert status == 400 and words in answer["error"], answer


@pytest.mark.parametrize("fields, words", [
    ({"aim": 10 ** 19}, "'aim' = 10000000000000000000 is out of range"),
    ({"aim": [[[1]]]}, "'aim' must be a finite number"),
    ({"turn": "0"}, "'turn' must be an integer"),
    ({"turn": -1}, "'turn' must be an integer"),
    ({"turn": True}, "'turn' must be an integer"),
    ({"placement": "here"}, "'placement' must be [x, y]"),
    ({"placement": [0.5, 0.5, 0.5]}, "'placement' must be [x, y]"),
    ({"declare": ["pass"]}, "'declare' must be one of"),
    ({"pocket": 2.5}, "'pocket' must be an integer"),
])
def test_mistyped_shots_say_what_is_wrong(tight, fields, words):
    g = _new(tight)
    status, answer = tight("POST", f"/api/games/{g['id']}/shot", {"turn": 0, "aim": 1.0, "speed": 2.0, **fields})
    assert status == 400 and words in answer["error"], answer


def test_the_tester_aim_of_10_to_the_400(tight):
    g = _new(tight)
    status, answer = tight.raw("POST", f"/api/games/{g['id']}/shot",
                               b'{"turn": 0, "aim": 1' + b"0" * 400 + b', "speed": 2}')
    assert status == 400 and "digits" in json.loads(answer)["error"], answer


def test_the_json_reader():
    assert nesting_problem('{"a": "[[[[[[[[[[[[[[[[[[[[[[[["}') is None  # brackets inside a string are text
    assert nesting_problem('["\\"", [[[[[[[[[1]]]]]]]]]') is not None
    assert parse_json(b'{"placement": [0.5, 1.25], "seed": 12}') == {"placement": [0.5, 1.25], "seed": 12}
    assert parse_json(b"  ") == {}
    with pytest.raises(PlayError, match="digits"):
        parse_json(b"-" + b"9" * (MAX_INT_DIGITS + 1))


# --- bot budgets ------------------------------------------------------------------------------------
@pytest.mark.parametrize("opponent, game, words", [
    ("search131072", "nine_ball", f"K from 1 to {MAX_SEARCH_K}"),    # the tester's: 3.2 s and +120 MB a shot
    (f"search{MAX_SEARCH_K + 1}", "nine_ball", f"K from 1 to {MAX_SEARCH_K}"),
    ("search0", "nine_ball", f"K from 1 to {MAX_SEARCH_K}"),
    ("search" + "9" * 4400, "nine_ball", "not 999999999999..."),    # past int()'s digit limit: no ValueError
    (f"carom{MAX_CAROM_K + 1}", "three_cushion", f"K from 1 to {MAX_CAROM_K}"),
    ("search\u00b2", "nine_ball", "unknown player"),                # a digit to str.isdigit, not to int()
    ("ghost", "three_cushion", "has no pockets"),
    ("carom", "nine_ball", "plays three-cushion only"),
    ("snooker", "nine_ball", "plays snooker only"),
    ("ladder-99", "nine_ball", "no ladder-99 is shipped for 9-ball"),
    ("ladder-1", "snooker", "no ladder-1 is shipped for snooker"),
    ("value-lookahead", "ten_ball", "no value network for 10-ball"),
])
def test_bots_out_of_budget_or_game_are_refused(tight, opponent, game, words):
    status, answer = tight("POST", "/api/games", {"game": game, "opponent": opponent, "seed": 1})
    assert status == 400 and words in answer["error"], answer


def test_the_largest_budgets_play(tight):
    for game, bot in (("nine_ball", f"search{MAX_SEARCH_K}"), ("three_cushion", f"carom{MAX_CAROM_K}"),
                      ("nine_ball", "search1")):
        status, g = tight("POST", "/api/games", {"game": game, "players": [bot, bot], "seed": 2})
        assert status == 201, g
        status, r = tight("POST", f"/api/games/{g['id']}/bot", {"turn": 0})
        assert status == 200 and r["state"]["turn"] == 1, r


# --- the turn a request is for ----------------------------------------------------------------------
def test_four_identical_shots_at_once_play_one(tight):
    """The tester's four simultaneous identical requests played two; with the turn named, one plays, three get
    409 saying that turn was played."""
    g = _new(tight, opponent="human")
    body = {"turn": g["turn"], "player": 0, "aim": 1.5707963267948966, "speed": 8.0}
    barrier, got = threading.Barrier(4), []

    def send():
        barrier.wait()
        got.append(tight("POST", f"/api/games/{g['id']}/shot", body))
    threads = [threading.Thread(target=send) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    assert sorted(s for s, _ in got) == [200, 409, 409, 409], got
    assert all("turn 0, which has already been played" in a["error"] for s, a in got if s == 409), got
    st = tight("GET", f"/api/games/{g['id']}")[1]
    assert len(st["shots"]) == 1 and st["state"]["turn"] == 1


def test_a_shot_names_its_turn(tight):
    g = _new(tight)
    status, answer = tight("POST", f"/api/games/{g['id']}/shot", {"aim": 1.0, "speed": 2.0})
    assert status == 400 and "'turn' is required" in answer["error"], answer
    status, answer = tight("POST", f"/api/games/{g['id']}/shot", {"turn": 3, "aim": 1.0, "speed": 2.0})
    assert status == 409 and "the game is at turn 0" in answer["error"], answer
    status, answer = tight("POST", f"/api/games/{g['id']}/bot", {"turn": 5})
    assert status == 409 and "for turn 5" in answer["error"], answer
    assert tight("GET", f"/api/games/{g['id']}")[1]["state"]["turn"] == 0  # nothing was played


# --- the store: bounded, and a game in play is never dropped -----------------------------------------
def test_a_burst_of_new_games_does_not_drop_a_game_in_play():
    """The tester's 40 games in 0.33 s dropped a person's open game. Here (3 places, a game may go after
    IDLE_S without a request) the burst fills the free places and then gets 503 with a JSON error and
    Retry-After; the person's game still plays; once the others have been idle, a new game takes the place
    of the one left longest, and asking for that one says plainly that it was dropped (410)."""
    srv, client = start_server(max_games=3, idle_s=IDLE_S)
    try:
        mine = _new(client)["id"]
        answers = [client("POST", "/api/games", {"game": "nine_ball", "opponent": "ghost", "seed": k})
                   for k in range(40)]
        made = [a["id"] for s, a in answers if s == 201]
        refused = [a for s, a in answers if s == 503]
        assert len(made) == 2 and len(refused) == 38, [s for s, _ in answers]
        assert "all of them in play" in refused[0]["error"] and "try again in" in refused[0]["error"], refused[0]
        req_status, _ = client.raw("POST", "/api/games", b'{"seed": 1}')
        assert req_status == 503
        status, r = client.shot(mine, {"player": 0, "aim": 1.5707963267948966, "speed": 8.0})
        assert status == 200, r
        end = time.monotonic() + IDLE_S * 1.5
        while time.monotonic() < end:  # the person keeps playing (asking for the state), the others are left
            assert client("GET", f"/api/games/{mine}")[0] == 200
            time.sleep(IDLE_S / 5)
        assert client("POST", "/api/games", {"game": "nine_ball", "seed": 9})[0] == 201
        status, answer = client("GET", f"/api/games/{made[0]}")
        assert status == 410 and "no longer on this server" in answer["error"] and "without a request" in \
            answer["error"] and "Start a new game" in answer["error"], answer
        assert client("GET", f"/api/games/{mine}")[0] == 200 and client("GET", f"/api/games/{made[1]}")[0] == 200
        status, answer = client("GET", "/api/games/0123456789abcdef")
        assert status == 404 and "never started here" in answer["error"], answer
    finally:
        srv.should_exit = True


def test_the_503_names_when_to_try_again():
    srv, client = start_server(max_games=1, idle_s=30)
    try:
        _new(client)
        status, headers, answer, _, _ = _send(client, _head("POST", "/api/games", "Content-Length: 2\r\n"), b"{}")
    finally:
        srv.should_exit = True
    assert status == 503 and 1 <= int(headers["retry-after"]) <= 30 and "try again in" in answer["error"], answer


class _Game:
    def __init__(self, gid, over=False):
        self.id, self.over = gid, over

    def finished(self):
        return self.over


def test_the_store_drops_only_games_left_alone():
    now = [0.0]
    store = Store(2, idle_s=100, finished_idle_s=10, clock=lambda: now[0])
    store.add(_Game("a"))
    store.add(_Game("b", over=True))
    now[0] = 5
    with pytest.raises(PlayError) as refused:
        store.add(_Game("c"))
    assert refused.value.status == 503 and refused.value.headers["Retry-After"] == "5"  # b, finished, in 5 s
    now[0] = 11
    store.add(_Game("c"))  # b went: finished and untouched for 11 s
    assert store.get("a").id == "a" and len(store) == 2
    with pytest.raises(PlayError, match="dropped after 11 s without a request") as gone:
        store.get("b")
    assert gone.value.status == 410
    now[0] = 90
    store.get("c")
    now[0] = 105  # a: 94 s idle, c: 15 s; neither may go yet
    with pytest.raises(PlayError, match="try again in 6 s"):
        store.add(_Game("d"))
    now[0] = 111
    store.add(_Game("d"))
    assert store.get("c").id == "c" and store.get("d").id == "d"
    with pytest.raises(PlayError, match="no longer on this server"):
        store.get("a")

"""Each game's own words where a person reads them, in headless Chromium: a snooker nomination reads as a
nomination, and a three-cushion point as a point, on the play page (the status line and the Rulings list, once the
animation has reached the shot) and in the replay viewer (the live page's and the saved game's: the ruling under the
players).

Snooker: a position set on the server's game before the page loads (a red just potted: a colour is on and must be
nominated), the pink moved clear of the pack with the cue ball straight behind it on the line to the foot right
corner. The person aims at the pink, taps it (which nominates it) and shoots: the pink drops, is respotted, and
the ruling says "(nominated: the pink)", never a called pocket. Three-cushion: seed 1's hint scores a point with
the first shot, and a soft shot the other way then scores none ("a point", "no point", never "pots").
"""
from __future__ import annotations

import math
import time

import numpy as np

from billiards_env.play.browser import PagePerson
from billiards_env.rules.records import IN_HAND_NONE, PHASE_COLOUR

PINK = 20                 # snooker's ball numbers: 1..15 the reds, 16..21 yellow, green, brown, blue, pink, black
FOOT_RIGHT = 5            # Table.pockets order: the foot right corner
WAIT_S = 60.0
POLL = 0.02


def text(browser, element_id: str) -> str:
    return browser.execute_script("return document.getElementById(arguments[0]).textContent;", element_id)


def settled(browser, n_shots: int) -> None:
    """Wait until the page holds ``n_shots`` replay entries and shows the last one's end (live, not playing)."""
    end = time.monotonic() + WAIT_S
    while not browser.execute_script(
            "const V = window.billiardsReplay, c = V.current(); return V.nShots === arguments[0] && !c.playing && "
            "c.shot === V.nShots - 1 && c.t >= V.duration(c.shot);", n_shots):
        assert time.monotonic() < end, "the shot did not finish on the page"
        time.sleep(POLL)


def rulings(browser) -> list[str]:
    return browser.execute_script("return Array.from(document.querySelectorAll('#pl-log li')).map(function (li) "
                                  "{ return li.textContent; });")


def saved_rulings(server, browser, gid: str, tmp_path, shots) -> list[str]:
    """The saved game's page opened from a file: the viewer's ruling at the end of each of ``shots`` (the live
    page's entry numbers: the live page's entry 0 is the rack, which a saved page has as its ``base``)."""
    status, page = server.raw("GET", f"/api/games/{gid}/replay.html")
    assert status == 200
    path = tmp_path / f"{gid}.html"
    path.write_bytes(page)
    browser.get(path.as_uri())
    out = []
    for k in shots:
        browser.execute_script("const V = window.billiardsReplay, k = arguments[0] - 1 + V.base; "
                               "V.seek(k, V.duration(k));", k)
        out.append(text(browser, "ruling"))
    return out


def test_a_snooker_nomination_reads_as_a_nomination(server, browser, tmp_path):
    st, g = server("POST", "/api/games", {"game": "snooker", "opponent": "human", "seed": 3, "breaker": 0})
    assert st == 201, g
    s = server.app.state.store.get(g["id"])
    with s.lock:  # a red has just been potted: the shooter is on a colour, which must be nominated
        c = s.core
        pocket = c.pockets[FOOT_RIGHT, :2]
        pink = np.array([1.45, 3.0])
        u = (pocket - pink) / np.linalg.norm(pocket - pink)
        c.state.pos[0, PINK] = pink
        c.state.pos[0, 0] = pink - 0.45 * u  # straight behind the pink, on the line to the pocket
        c.game.phase[0], c.game.ball_in_hand[0], c.game.shots[0] = PHASE_COLOUR, IN_HAND_NONE, 2
        c._changed()
        s.start_pos, s.start_pocket = c.state.pos[0].copy(), c.state.pocket[0].copy()  # the rack the page draws
    browser.get(server.url + "/game/" + g["id"])
    person = PagePerson(browser)
    state = person.wait_turn()
    assert state["call_needed"] and not state["calls_pocket"] and PINK in state["targets"], state
    assert "nominated: the colour hit first" in text(browser, "pl-info"), text(browser, "pl-info")
    person.aim(math.atan2(*(np.array(state["pos"][PINK]) - state["pos"][0])[::-1]))  # dragged: at the pink
    assert browser.execute_script("return window.billiardsPlay.preview().ball;") == PINK
    person.click_at(person.px(*state["pos"][PINK]))  # a tap on the pink: nominated (the aim stays)
    assert browser.execute_script("return window.billiardsPlay.choice.ball;") == PINK
    info = text(browser, "pl-info")
    assert "nominated: the pink" in info and "tap a ball" not in info and "called" not in info, info
    assert "ball 20" not in info and state["ball_names"][PINK] == "the pink" and state["ball_names"][1] == "the red"
    browser.execute_script("window.billiardsPlay.opts.speed = 16;")
    person.set_speed(1.2, state["limits"])
    person.click("pl-shoot")
    settled(browser, 2)
    ruling = server("GET", f"/api/games/{g['id']}")[1]["shots"][-1]["info"]["game"]["ruling"]
    assert "(nominated: the pink)" in ruling and "pots the pink" in ruling, ruling
    status, listed = text(browser, "pl-status"), rulings(browser)
    for where in (status, listed[0]):
        assert "(nominated: the pink)" in where and "called" not in where and "pots the pink" in where, where
    assert text(browser, "ruling") == ruling  # the live page's viewer, under the players
    assert saved_rulings(server, browser, g["id"], tmp_path, [1]) == [ruling]


def test_a_three_cushion_point_reads_as_a_point(server, browser, tmp_path):
    st, g = server("POST", "/api/games", {"game": "three_cushion", "opponent": "human", "seed": 1, "breaker": 0})
    assert st == 201, g
    browser.get(server.url + "/game/" + g["id"])
    person = PagePerson(browser)
    person.wait_turn()
    browser.execute_script("window.billiardsPlay.opts.speed = 16;")
    assert person.wait_turn()["ball_names"] == ["the white", "the yellow", "the red"]
    person.hint()  # seed 1: the hint's shot scores
    person.click("pl-shoot")
    settled(browser, 2)
    state = person.wait_turn()
    assert state["points"] == [1, 0], state["points"]
    made = rulings(browser)[0]
    assert "a point" in made and "stays at the table" in made and "pots" not in made, made
    assert "a point" in text(browser, "pl-status"), text(browser, "pl-status")
    person.aim(math.radians(250.0))  # slow, along a clear path (test_play_preview's aim): one cushion at most
    person.set_speed(state["limits"]["speed_min"], state["limits"])
    person.click("pl-shoot")
    settled(browser, 3)
    state = person.wait_turn()
    assert state["points"] == [1, 0] and state["to_move"] == 1, state
    assert state["ball_names"] == ["the yellow", "the white", "the red"], state["ball_names"]  # slot 0: the mover's
    missed = rulings(browser)[0]
    assert "no point" in missed and "pots" not in missed, missed
    assert "no point" in text(browser, "ruling") and "points 1" in text(browser, "players")  # the live page's viewer
    saved = saved_rulings(server, browser, g["id"], tmp_path, [1, 2])
    assert "a point" in saved[0] and "no point" in saved[1] and not any("pots" in r for r in saved), saved
    players = text(browser, "players")
    assert "points 1" in players and "games won" not in players, players


def test_refusals_name_snooker_balls_by_colour():
    """The server's refusals a person reads name a snooker ball by colour ('overlaps the red', 'the red cannot be
    nominated'), as the pool games keep 'ball 3' (tests/play/test_server.py)."""
    import pytest

    from billiards_env.play.session import PlayError, Session, placement_problem

    s = Session("t", "snooker", ["human", "human"], 3)
    c = s.core
    m = c.table.marks
    spot = np.array([m.d_centre[0] - 0.1, m.d_centre[1] - 0.1])  # inside the D
    c.state.pos[0, 1] = spot  # a red moved into the D
    c._changed()
    assert placement_problem(c, spot) == "the cue ball there overlaps the red"
    c.game.phase[0], c.game.ball_in_hand[0], c.game.shots[0] = PHASE_COLOUR, IN_HAND_NONE, 2
    c._changed()
    with pytest.raises(PlayError, match="^the red cannot be nominated: after a red"):
        s._nomination(3, c.constraints())

"""The play page's aim preview as a help (issue 45, item 5), in headless Chromium: an object ball's line that
another ball blocks is drawn blocked, up to that ball; a cue ball that heads for a pocket is warned of; the last
shot's trails leave the table once the next shot is aimed (and come back when that shot is reviewed); after the
cue ball is placed with ball in hand, the aim points at what it pointed at before.

Positions are set on the server's own game (the session's ``GameCore`` state and the rack the page draws, before
the page loads), and the page's preview is read from ``window.billiardsPlay.preview()`` (what the overlay drew, in
metres). Where the preview says where the cue ball goes, it is compared with the simulator (``Equipment.simulate``
with ``record=True``: the cue ball's first event that touches anything), as ``test_play_preview.py`` does.
"""
from __future__ import annotations

import math
import time

import numpy as np
import pytest

from billiards_env.physics import constants as C
from billiards_env.physics.state import BallState
from billiards_env.physics.strike import strike_velocity
from billiards_env.play.browser import PagePerson
from tests.play.test_play_phone import PORTRAIT, phone  # noqa: F401  (the phone fixture)

SPEED = 2.0            # m/s: a centre-ball shot that goes straight (no spin) and reaches any pocket from mid-table
POINT_TOL_M = 0.25e-3  # m: the page's point against the simulator's (test_play_preview.CUSHION_TOL_M, its reasons)
CONTACT_TOL_M = 1e-9   # m: a ball-to-ball distance the page computes as 2R (float64 rounding is ~1e-16 m)
ANGLE_TOL = 1e-12      # rad: JS Math.atan2 and Python's math.atan2 of the same doubles agree to an ulp or two
SWEEP = 21             # aims across each pocket's mouth, from a jaw or rail on one side to one on the other
WAIT_S = 20.0          # s: the longest wait for the server's answer to a placement
POLL = 0.02

KIND = {"ball": C.EV_BALL_BALL, "cushion": C.EV_CUSHION, "tip": C.EV_JAW_TIP, "pocket": C.EV_POCKET}


def arranged(server, browser, spots: dict, touch: bool = False) -> tuple[str, PagePerson, dict]:
    """A new 9-ball game between two people at one screen, its balls put where ``spots`` says ({ball: (x, y)};
    every other object ball off the table), on the server's session before the page is loaded: (id, the person
    at the page, by mouse or by ``touch``, the state)."""
    st, g = server("POST", "/api/games", {"game": "nine_ball", "opponent": "human", "seed": 3, "breaker": 0})
    assert st == 201, g
    s = server.app.state.store.get(g["id"])
    with s.lock:
        c = s.core
        for i in range(1, c.n_balls):
            c.state.pocket[0, i] = 0
        for i, xy in spots.items():
            c.state.pos[0, i] = xy
            c.state.pocket[0, i] = -1
        c._changed()  # the rules' constraints (targets, ball in hand) of the new position
        s.start_pos, s.start_pocket = c.state.pos[0].copy(), c.state.pocket[0].copy()  # the rack the page draws
    browser.get(server.url + "/game/" + g["id"])
    person = PagePerson(browser, touch=touch)
    state = person.wait_turn()
    assert state["pos"][0] == list(spots[0]) and sum(state["on_table"]) == len(spots), state
    return g["id"], person, state


def first_touch(server, gid: str, phi: float) -> tuple[int, int, np.ndarray]:
    """The simulator's first event of the cue ball struck along ``phi`` (centre ball, SPEED, no noise) on game
    ``gid``'s table that touches anything: (its kind, the other ball / segment / tip / pocket, the cue ball's centre)."""
    core = server.app.state.store.get(gid).core
    state = BallState.from_positions(core.state.pos[0].copy(), pocket=core.state.pocket[:1].copy())
    struck = strike_velocity(state, phi, SPEED, 0.0, 0.0, params=core.params)
    log = core.equipment.simulate(struck, record=True).events[0]
    for k, kind, (i, j) in zip(range(len(log)), log.kind, log.balls):
        if kind in KIND.values() and (i == 0 or kind == C.EV_BALL_BALL and j == 0):
            s = 0 if i == 0 else 1
            return int(kind), int(i if j == 0 and kind == C.EV_BALL_BALL else j), log.states[k, s, :2].copy()
    raise AssertionError("the cue ball touched nothing")


def preview(browser, phi: float | None = None) -> dict:
    """The preview drawn (with ``phi``: of that aim, set on the page's controls and drawn)."""
    if phi is not None:
        browser.execute_script("window.billiardsPlay.choice.phi = arguments[0]; window.billiardsReplay.redraw();", phi)
    pv = browser.execute_script("return window.billiardsPlay.preview();")
    assert pv is not None, "no preview drawn"
    return pv


def text(browser, element_id: str) -> str:
    return browser.execute_script("return document.getElementById(arguments[0]).textContent;", element_id)


def towards(a, b) -> float:
    return math.atan2(b[1] - a[1], b[0] - a[0])


# --- a blocked object ball ------------------------------------------------------------------------------------

CUE, OBJECT, BLOCKER, OTHER = (0.635, 0.5), (0.635, 1.3), (0.635, 1.7), (0.2, 2.2)


@pytest.mark.parametrize("blocker", [BLOCKER, (0.935, 1.7), None], ids=["in-the-way", "moved-aside", "removed"])
def test_a_blocked_object_ball_line_stops_at_the_ball_in_the_way(server, browser, blocker):
    """The cue ball aimed (by mouse) straight at the 1, the 5 on the 1's line beyond it: the 1's line is drawn
    up to where it meets the 5 (the 1's centre 2R from the 5's) and the preview names the 5; with the 5 moved
    0.3 m aside, or off the table, the line is clear to the foot cushion."""
    spots = {0: CUE, 1: OBJECT, 9: OTHER} | ({} if blocker is None else {5: blocker})
    gid, person, st = arranged(server, browser, spots)
    R, L = st["limits"]["R"], st["limits"]["length"]
    person.aim(math.pi / 2)
    pv = preview(browser)
    assert pv["ball"] == 1, pv
    to = np.array(pv["objectTo"])
    if blocker == BLOCKER:
        assert pv["objectBlockedBy"] == 5, pv
        assert abs(math.dist(to, BLOCKER) - 2 * R) < CONTACT_TOL_M, (to, BLOCKER)
        assert OBJECT[1] < to[1] < BLOCKER[1], to
    else:
        assert pv["objectBlockedBy"] is None, pv
        assert abs(to[1] - (L - R)) < CONTACT_TOL_M and pv["objectPocket"] is None, to  # on the foot cushion
    assert pv["scratchPocket"] is None and text(browser, "pl-warn") == "", pv


# --- the cue ball into a pocket -------------------------------------------------------------------------------

def test_the_cue_ball_heading_for_a_pocket_is_warned_of(server, browser):
    """Aimed (by mouse) at the head left corner pocket with no ball in the way: the pocket is named under the
    controls and marked, and the path drawn ends where the simulator's cue ball drops into that pocket; aimed at a
    ball: no warning. Then aims swept across every pocket's mouth: the page's first thing met (a ball, a cushion, a
    jaw tip or a pocket, by index) is the simulator's, at the simulator's point, for every aim."""
    gid, person, st = arranged(server, browser, {0: (0.4, 0.5), 1: (1.0, 1.2)})
    pockets, names = st["pockets"], st["pocket_names"]
    person.aim(towards((0.4, 0.5), pockets[0]))
    pv = preview(browser)
    assert pv["ball"] == -1 and pv["scratchPocket"] == 0, pv
    assert text(browser, "pl-warn") == f"The cue ball heads for the {names[0]} pocket.", text(browser, "pl-warn")
    kind, where, sim = first_touch(server, gid, pv["phi"])
    assert (kind, where) == (C.EV_POCKET, 0), (C.EVENT_NAMES[kind], where)
    assert math.dist(pv["path"][-1], sim) < POINT_TOL_M, (pv["path"], sim)
    person.aim(towards((0.4, 0.5), (1.0, 1.2)))
    pv = preview(browser)
    assert pv["ball"] == 1 and pv["scratchPocket"] is None and text(browser, "pl-warn") == "", pv
    assert first_touch(server, gid, pv["phi"])[:2] == (C.EV_BALL_BALL, 1)

    # the sweep: from mid-table, across each pocket's capture circle and a ball's width either side of it
    gid, person, st = arranged(server, browser, {0: (0.635, 0.95), 1: (0.635, 2.0)})
    c, R = np.array(st["pos"][0]), st["limits"]["R"]
    seen = {k: set() for k in range(len(pockets))}
    for k, (px, py, r) in enumerate(pockets):
        mid, half = towards(c, (px, py)), math.asin(min(1.0, (r + 2 * R) / math.dist(c, (px, py))))
        for phi in np.linspace(mid - half, mid + half, SWEEP):
            pv = preview(browser, float(phi))
            kind, where, sim = first_touch(server, gid, float(phi))
            page = (KIND[pv["meets"][0]], pv["meets"][1])
            assert page == (kind, where), f"aim {math.degrees(phi):.4f} deg: page {pv['meets']}, simulator " \
                                          f"{C.EVENT_NAMES[kind]} {where}"
            if kind == C.EV_POCKET:
                assert pv["scratchPocket"] == where and len(pv["path"]) == 1, pv
            elif pv["scratchPocket"] is not None:  # off a jaw or cushion, the mirrored leg into a pocket
                q = pockets[pv["scratchPocket"]]
                assert len(pv["path"]) == 2 and abs(math.dist(pv["path"][1], q[:2]) - q[2]) < CONTACT_TOL_M, pv
            if kind != C.EV_BALL_BALL:
                assert math.dist(pv["path"][0], sim) < POINT_TOL_M, (pv["path"][0], sim)
            seen[k].add(kind)
    for k, kinds in seen.items():  # every mouth swept from outside it to inside it
        assert C.EV_POCKET in kinds and kinds & {C.EV_CUSHION, C.EV_JAW_TIP}, (names[k], kinds)


def test_a_bank_into_a_pocket_is_warned_of(server, browser):
    """Off the right cushion into the foot left corner pocket (the mirror path the preview draws): warned of, the
    path's second leg ending in that pocket; in three-cushion (no pockets) never."""
    gid, person, st = arranged(server, browser, {0: (0.635, 0.95), 1: (0.3, 0.5)})
    R, W, corner = st["limits"]["R"], st["limits"]["width"], st["pockets"][4]
    image = (2 * (W - R) - corner[0], corner[1])  # the pocket's mirror image in the right cushion's line (x = W - R)
    pv = preview(browser, towards((0.635, 0.95), image))
    assert pv["ball"] == -1 and pv["scratchPocket"] == 4 and len(pv["path"]) == 2, pv
    assert abs(pv["path"][0][0] - (W - R)) < CONTACT_TOL_M, pv["path"]  # off the right cushion
    assert abs(math.dist(pv["path"][1], corner[:2]) - corner[2]) < CONTACT_TOL_M  # into the capture circle
    assert text(browser, "pl-warn") == f"The cue ball heads for the {st['pocket_names'][4]} pocket."
    st3, g = server("POST", "/api/games", {"game": "three_cushion", "opponent": "human", "seed": 3})
    browser.get(server.url + "/game/" + g["id"])
    PagePerson(browser).wait_turn()
    for deg in range(0, 360, 15):
        pv = preview(browser, math.radians(deg))
        assert pv["scratchPocket"] is None and pv["meets"][0] in ("ball", "cushion"), pv
    assert text(browser, "pl-warn") == ""


def object_first_touch(server, gid: str, phi: float, ball: int) -> tuple[int, int, np.ndarray]:
    """After the cue ball's first contact (with ``ball``), the simulator's first event of ``ball`` that touches
    anything (as ``first_touch``): (its kind, the other ball / segment / tip / pocket, ``ball``'s centre)."""
    core = server.app.state.store.get(gid).core
    state = BallState.from_positions(core.state.pos[0].copy(), pocket=core.state.pocket[:1].copy())
    struck = strike_velocity(state, phi, SPEED, 0.0, 0.0, params=core.params)
    log = core.equipment.simulate(struck, record=True).events[0]
    hit = False
    for k, kind, (i, j) in zip(range(len(log)), log.kind, log.balls):
        if kind not in KIND.values():
            continue
        if not hit:
            assert kind == C.EV_BALL_BALL and {i, j} == {0, ball}, (C.EVENT_NAMES[kind], i, j)
            hit = True
        elif i == ball or kind == C.EV_BALL_BALL and j == ball:
            s = 0 if i == ball else 1
            return int(kind), int(i if j == ball and kind == C.EV_BALL_BALL else j), log.states[k, s, :2].copy()
    raise AssertionError(f"ball {ball} touched nothing after the cue ball")


def test_a_bank_of_the_object_ball_is_drawn(server, browser):
    """A cross-side bank: the 1 sent full ball (the aim at its centre) to the right cushion at the point whose
    mirrored leg runs into the left side pocket. The 1's line ends on the right cushion where the simulator's 1
    first meets it (within 0.25 mm: a full hit throws nothing), and its bank leg ends in the left side pocket's
    capture circle (the pocket ringed; the leg is geometry: the real rebound is bent by the cushion and the ball's
    roll). Then a bank off the foot cushion whose mirrored leg meets the 9: the leg ends with the 1's centre 2R from
    the 9's, and the 1's straight line is not blocked."""
    o = np.array([0.635, 0.8])
    gid, person, st = arranged(server, browser, {0: (0.3, 0.7), 1: tuple(o), 9: (0.2, 2.2)})
    L, pockets = st["limits"], st["pockets"]
    W, R = L["width"], L["R"]
    side = min(range(len(pockets)), key=lambda k: math.dist(pockets[k][:2], (0.0, L["length"] / 2)))
    q = pockets[side]
    image = np.array([2 * (W - R) - q[0], q[1]])  # the left side pocket's mirror image in the right cushion's line
    u = (image - o) / np.linalg.norm(image - o)
    gid, person, st = arranged(server, browser, {0: tuple(o - 0.4 * u), 1: tuple(o), 9: (0.2, 2.2)})
    pv = preview(browser, towards(st["pos"][0], st["pos"][1]))
    assert pv["ball"] == 1 and pv["objectBlockedBy"] is None and pv["objectPocket"] is None, pv
    assert len(pv["objectPath"]) == 2 and pv["objectBankPocket"] == side and pv["objectBankBall"] is None, pv
    assert abs(pv["objectTo"][0] - (W - R)) < CONTACT_TOL_M, pv["objectTo"]  # on the right cushion's line
    assert abs(math.dist(pv["objectPath"][1], q[:2]) - q[2]) < CONTACT_TOL_M, pv["objectPath"]
    kind, where, sim = object_first_touch(server, gid, pv["phi"], 1)
    assert kind == C.EV_CUSHION, C.EVENT_NAMES[kind]
    assert math.dist(pv["objectTo"], sim) < POINT_TOL_M, (pv["objectTo"], sim)

    o, u = np.array([0.4, 1.6]), np.array([1.0, 3.0]) / math.sqrt(10.0)
    foot = o + (L["length"] - R - o[1]) / u[1] * u  # where the 1 meets the foot cushion's line
    nine = foot + 0.5 * np.array([u[0], -u[1]])     # on the mirrored leg, 0.5 m from the cushion
    gid, person, st = arranged(server, browser, {0: tuple(o - 0.4 * u), 1: tuple(o), 9: tuple(nine)})
    pv = preview(browser, towards(st["pos"][0], st["pos"][1]))
    assert pv["ball"] == 1 and pv["objectBlockedBy"] is None and pv["objectBankBall"] == 9, pv
    assert math.dist(pv["objectTo"], foot) < CONTACT_TOL_M, (pv["objectTo"], foot)
    assert abs(math.dist(pv["objectPath"][1], nine) - 2 * R) < CONTACT_TOL_M, pv["objectPath"]
    assert pv["scratchPocket"] is None and text(browser, "pl-warn") == "", pv


# --- the default aim -------------------------------------------------------------------------------------------

@pytest.mark.parametrize("game", ["nine_ball", "eight_ball", "ten_ball", "snooker"])
def test_the_default_aim_meets_a_legal_ball(server, browser, game):
    """A new game's break, as the page first shows it: the aim goes to the foot spot (the rack's apex) when the
    cue ball's path there meets a legal ball first, and else to a legal ball it can reach: in snooker the pink
    stands on that spot, in front of the apex red, and the aim goes to the first red with a clear path."""
    st, g = server("POST", "/api/games", {"game": game, "opponent": "human", "seed": 3, "breaker": 0})
    browser.get(server.url + "/game/" + g["id"])
    st = PagePerson(browser).wait_turn()
    pv = preview(browser)
    assert st["break"] and pv["ball"] in st["targets"], (pv["ball"], st["targets"])
    foot = st["limits"]["foot_spot"]
    at_foot = abs(math.remainder(pv["phi"] - towards(st["pos"][0], foot), 2 * math.pi)) < ANGLE_TOL
    assert at_foot == (game != "snooker"), (game, pv["phi"], towards(st["pos"][0], foot))


# --- the last shot's trails -----------------------------------------------------------------------------------

def trails(browser) -> int:
    return browser.execute_script("return window.billiardsPlay.trailsShown();")


def test_the_last_shots_trails_leave_when_aiming_starts(server, browser, phone):  # noqa: F811
    """By touch on 390 x 844: after the break the person to move sees its trails under the preview until they
    aim (a fine-aim turn); then the trails are gone, under review of the break they are back, and back to live
    gone again. After the next shot, a drag on the table to aim clears them as well, and the break's end,
    reviewed from there, has its trails."""
    phone(PORTRAIT)
    st, g = server("POST", "/api/games", {"game": "nine_ball", "opponent": "human", "seed": 15})
    browser.get(server.url + "/game/" + g["id"])
    person = PagePerson(browser, touch=True)
    person.wait_turn()
    browser.execute_script("window.billiardsPlay.opts.cut = true; window.billiardsPlay.opts.speed = 16;")
    person.turn()  # the break
    st = person.wait_turn()
    assert st["turn"] == 1 and browser.execute_script("return window.billiardsReplay.current().shot;") == 1
    browser.execute_script("window.billiardsReplay.redraw();")
    assert trails(browser) >= 3, "the break's trails are drawn until the person aims"
    person.click("pl-aim-p2")
    assert trails(browser) == 0 and preview(browser)["phi"] is not None
    browser.execute_script("const V = window.billiardsReplay; V.seek(1, 0.6 * V.duration(1));")  # review the break
    assert trails(browser) >= 3 and not browser.execute_script("return window.billiardsPlay.ready();")
    person.click("pl-live")
    assert browser.execute_script("return window.billiardsPlay.ready();") and trails(browser) == 0
    person.turn()  # the second shot (a push-out: the cue ball rolls)
    st = person.wait_turn()
    assert st["turn"] == 2
    browser.execute_script("window.billiardsReplay.redraw();")
    assert trails(browser) >= 1, "the second shot's trails are drawn until the person aims"
    sent = browser.execute_script("return window.billiardsPlay.sent.length;")
    person.aim(preview(browser)["phi"] + 0.2)  # a drag on the table (near the aim: not on the drawn cue)
    assert trails(browser) == 0 and browser.execute_script("return window.billiardsPlay.sent.length;") == sent
    browser.execute_script("const V = window.billiardsReplay; V.seek(1, V.duration(1));")  # the break's end, reviewed
    assert trails(browser) >= 3 and "Reviewing Shot 1" in text(browser, "pl-status")


# --- the aim after a placement ----------------------------------------------------------------------------------

def placed(person, spot) -> list:
    """Drag the cue ball to ``spot`` (by touch) and wait for the server's answer; the cue ball's place."""
    n = person.js("return window.billiardsPlay.placements();")
    person.drag(person.px(*person.cue()), person.px(*spot))
    end = time.monotonic() + WAIT_S
    while person.js("return window.billiardsPlay.placements();") == n:
        assert time.monotonic() < end, "the placement was not answered"
        time.sleep(POLL)
    return person.js("return window.billiardsPlay.choice.placement;")


def test_a_placement_keeps_the_aim_on_its_ball(server, browser, phone):  # noqa: F811
    """By touch on 390 x 844, ball in hand after a scratch: aimed at a cut on the 5 (not the ball on), the cue
    ball dragged elsewhere: the aim points at the 5's centre from the new place (to ANGLE_TOL: the same atan2 of
    the same doubles); aimed at no ball, the cue ball dragged again: the aim points at the 1, the ball on."""
    phone(PORTRAIT)
    gid, person, st = arranged(server, browser, {0: (0.3, 0.3), 1: (0.3, 1.6), 5: (0.9, 1.4)}, touch=True)
    person.aim(towards((0.3, 0.3), st["pockets"][0]))  # the cue ball into the head left corner pocket: a scratch
    assert preview(browser)["scratchPocket"] == 0
    browser.execute_script("window.billiardsPlay.opts.cut = true; window.billiardsPlay.opts.speed = 16;")
    person.set_speed(1.5, st["limits"])
    person.click("pl-shoot")
    st = person.wait_turn()
    assert st["turn"] == 1 and st["in_hand_code"] == 1 and not st["break"] and st["targets"][0] == 1, st
    R, five, one = st["limits"]["R"], st["pos"][5], st["pos"][1]
    cut = (five[0] + R, five[1])  # a half-ball cut on the 5
    person.aim(towards(person.cue(), cut))
    pv = preview(browser)
    assert pv["ball"] == 5 and abs(pv["phi"] - towards(person.cue(), five)) > 1e-3, pv
    at = placed(person, (0.6, 0.5))
    phi = browser.execute_script("return window.billiardsPlay.choice.phi;")
    assert abs(phi - towards(at, five)) < ANGLE_TOL, (phi, towards(at, five))
    assert preview(browser)["ball"] == 5
    person.aim(0.0)  # at the right cushion: no ball on the way
    assert preview(browser)["ball"] == -1
    at = placed(person, (0.9, 0.6))
    phi = browser.execute_script("return window.billiardsPlay.choice.phi;")
    assert abs(phi - towards(at, one)) < ANGLE_TOL, (phi, towards(at, one))
    assert preview(browser)["ball"] == 1

"""Seeing the third dimension (issue 46, item 5): replays of shots with balls
in flight (``Effects(airborne=True)``) and balls that leave the table read
back bit for bit and evaluate as the simulator does; the raster renderer
and the HTML viewer draw a ball in flight larger, lifted over its shadow,
and a ball off the table on the rail where it came down (ringed when it fell
to the floor), distinct from a pocketed ball (not drawn).

The browser tests need Chromium and selenium (conftest.py), as in
test_replay.py.
"""
from __future__ import annotations

import io
import math

import numpy as np
import pytest

from billiards_env.physics import BallState, Effects, PhysicsParams, SimOptions, Table, simulate, strike_velocity
from billiards_env.physics import constants as C
from billiards_env.rendering import Replay, draw, save_replay_animation, save_replay_html
from billiards_env.rendering.replay import off_table_landing, segment_normals

AIR = Effects(airborne=True)
P = PhysicsParams()
TABLE = Table.pool()
POS_TOL = 1e-9       # Python evaluation vs the simulator (test_replay.py)
BROWSER_TOL = 1e-6   # the browser's port vs the simulator (test_replay.py)
PPM = 300


def _shot(pos, speed, theta_deg, phi=math.pi / 2, a=0.0, b=0.0):
    s = BallState.from_positions(np.array([pos], dtype=np.float64))
    s = BallState(s.pos, s.vel, s.omega, s.pocket, np.zeros((1, len(pos), 2)))
    s = strike_velocity(s, phi, speed, a, b, P, theta=math.radians(theta_deg))
    return s, simulate(s, TABLE, P, effects=AIR, record=True)


@pytest.fixture(scope="module")
def jump():
    """The cue ball jumped at 4 m/s, cue 30 degrees up, into a ball 0.3 m on
    (struck in flight, 5 cm up), a third ball further on."""
    s, r = _shot([[0.635, 0.6], [0.635, 0.9], [0.635, 1.5]], 4.0, 30)
    return s, r, Replay.from_sim(r, s, TABLE, P, AIR)


@pytest.fixture(scope="module")
def off():
    """Ball 0 driven over the foot cushion to the floor (6 m/s, 45 degrees),
    ball 1 at rest."""
    s, r = _shot([[0.635, 2.2], [0.3, 2.3]], 6.0, 45)
    return s, r, Replay.from_sim(r, s, TABLE, P, AIR)


def _round_trip(rep, res, tmp_path, log_read_back):
    path = rep.save(tmp_path / "shot.json")
    back = Replay.load(path)
    assert back.to_json() == rep.to_json() == path.read_text()
    log_read_back(back, res.events[0])
    for tt in np.concatenate([back.event_times(0), np.random.default_rng(0).uniform(0, back.duration(0), 40)]):
        np.testing.assert_array_equal(back.states_at(tt), rep.states_at(tt))
        for x, y in zip(back.table_view(tt), rep.table_view(tt)):
            np.testing.assert_array_equal(x, y)
    return back


# ---------------------------------------------------------------- replay --
def test_jump_shot_replay_round_trip_bit_for_bit(jump, tmp_path, log_read_back):
    s, r, rep = jump
    back = _round_trip(rep, r, tmp_path, log_read_back)
    flights = [row for row in back.shots[0]["events"] if row[4][0] == C.AIRBORNE]
    assert flights and all(len(row[4]) == 10 for row in flights)
    assert back.shots[0]["start"][0][0] == C.AIRBORNE  # struck into the slate: in the air at t = 0
    assert "off_table" not in back.shots[0]["info"]


def test_off_table_replay_round_trip_and_where_it_came_down(off, tmp_path, log_read_back):
    s, r, rep = off
    back = _round_trip(rep, r, tmp_path, log_read_back)
    (e,) = back.shots[0]["info"]["off_table"]
    assert e["ball"] == 0 and e["code"] == int(r.state.pocket[0, 0]) == C.OFF_FLOOR
    row = next(row for row in back.shots[0]["events"] if row[1] == C.EV_OFF_TABLE)
    assert e["t"] == row[0] and row[4][0] == C.POCKETED
    assert e["x"] == pytest.approx(0.635) and e["y"] > TABLE.length + 0.15  # beyond the rail, towards the floor
    assert back.shots[0]["info"]["pocketed"] == []  # off the table is not pocketed
    pos, pocket, h = back.table_view(back.duration(0))
    assert pocket.tolist() == [C.OFF_FLOOR, -1] and (pos[0] == (e["x"], e["y"])).all()
    pos, pocket, h = back.table_view(0.5 * e["t"])
    assert pocket[0] == -1 and h[0] > 0.0  # in flight before it left
    # the next entry starts with it still off the table: carried, from t = 0
    back.add_still(r.state.pos[0], r.state.pocket[0])
    assert back.shots[1]["info"]["off_table"] == [dict(e, t=0.0)]
    assert back.table_view(0.0, 1)[1][0] == C.OFF_FLOOR


def test_planar_replays_carry_no_off_table_entry():
    s = strike_velocity(BallState.from_positions(np.array([[0.635, 0.6], [0.635, 1.5]])), math.pi / 2, 3.0,
                        params=P)
    r = simulate(s, TABLE, P, record=True)
    rep = Replay.from_sim(r, s, TABLE, P)
    assert "off_table" not in rep.shots[0]["info"]
    assert all(rec[0] != C.AIRBORNE and len(rec) < 10 for rec in rep.shots[0]["start"])
    pos, pocket, h = rep.table_view(rep.duration(0))
    assert (h == 0).all() and (pocket == np.where(r.state.pocket[0] < 0, -1, r.state.pocket[0])).all()


def test_jump_positions_and_heights_equal_the_simulator_at_every_event(jump):
    """The simulator stopped after n events holds every ball at the n-th
    event's time, in flight too (x, y and the height h)."""
    s, r, rep = jump
    times = rep.event_times(0)
    for n in range(1, int(r.n_events[0]) + 1):
        cut = simulate(s, TABLE, P, effects=AIR, options=SimOptions(max_events=n))
        t = float(cut.time[0])
        assert t == times[n - 1]
        got = rep.states_at(t)
        on = cut.state.pocket[0] < 0
        assert np.abs(got[on, :2] - cut.state.pos[0][on]).max() < POS_TOL, f"after {n} events"
        assert np.abs(got[on, 8] - cut.state.air[0][on, 0]).max() < POS_TOL, f"height after {n} events"
    pos, pocket, h = rep.table_view(rep.duration(0))
    assert np.abs(pos - r.state.pos[0]).max() < POS_TOL and (h == 0).all()


def test_where_balls_come_down_agrees_with_the_simulator():
    """The replay's rail-or-floor rule (``off_table_landing``) against the
    simulator's pocket codes over shots sent off every side of the table,
    over cushions, jaw tips and pockets, at speeds and elevations that land
    on the rail and on the floor."""
    rng = np.random.default_rng(7)
    codes, seen = [], set()
    for _ in range(80):
        x, y = rng.uniform(0.2, TABLE.width - 0.2), rng.uniform(0.3, TABLE.length - 0.3)
        s, r = _shot([[x, y]], rng.uniform(2.5, 7.0), rng.uniform(35, 70), phi=rng.uniform(-math.pi, math.pi))
        rep = Replay.from_sim(r, s, TABLE, P, AIR)
        off = rep.shots[0]["info"].get("off_table", [])
        if int(r.state.pocket[0, 0]) >= C.OFF_TABLE:
            assert [e["code"] for e in off] == [int(r.state.pocket[0, 0])]
            codes.append(off[0]["code"])
            seen.add(next(row[3] for row in rep.shots[0]["events"] if row[1] == C.EV_OFF_TABLE) >= 0)
        else:
            assert off == []
    assert {C.OFF_RAIL, C.OFF_FLOOR} <= set(codes), codes
    print(f"\n{len(codes)} of 80 shots left the table: {codes.count(C.OFF_RAIL)} onto the rail, "
          f"{codes.count(C.OFF_FLOOR)} to the floor")


def test_off_table_landing_rule():
    """Over a cushion the outward speed counts, over a pocket all of it: the
    rail within RAIL_WIDTH, the floor beyond."""
    from billiards_env.physics.cushion.rail import RAIL_WIDTH

    p = P.as_array()
    normals = segment_normals(TABLE.segments)
    segs = TABLE.segments
    foot = int(np.flatnonzero((segs[:, 1] == TABLE.length) & (segs[:, 3] == TABLE.length))[0])  # the foot cushion
    y0 = TABLE.length - P.R
    # crossing at the nose's height, falling: drop_time 0 -> comes down where it is, on the rail
    code, x, y = off_table_landing([0.6, y0, 0, 1.0, 0, 0, 0, C.AIRBORNE, P.h_c, -0.1], foot, normals, p)
    assert (code, x, y) == (C.OFF_RAIL, 0.6, y0)
    # 0.3 m above the nose at 2 m/s outward: sqrt(0.6 / g) = 0.247 s, 0.49 m out: the floor
    code, x, y = off_table_landing([0.6, y0, 0, 2.0, 0, 0, 0, C.AIRBORNE, P.h_c + 0.3, 0.0], foot, normals, p)
    assert code == C.OFF_FLOOR and y == pytest.approx(y0 + 2.0 * math.sqrt(0.6 / P.g), rel=1e-12)
    # sliding along the cushion, barely outward: the rail, though it travels far
    code, *_ = off_table_landing([0.6, y0, 3.0, 0.05, 0, 0, 0, C.AIRBORNE, P.h_c + 0.3, 0.0], foot, normals, p)
    assert code == C.OFF_RAIL and 0.05 * math.sqrt(0.6 / P.g) - P.R <= RAIL_WIDTH
    code, *_ = off_table_landing([0.6, y0, 3.0, 0.05, 0, 0, 0, C.AIRBORNE, P.h_c + 0.3, 0.0], -1, normals, p)
    assert code == C.OFF_FLOOR  # over a pocket: all of its speed


# ---------------------------------------------------------------- raster --
def _pixels(img, colour):
    return int(np.sum(np.all(img == np.array(colour, dtype=np.uint8), axis=2)))


def test_raster_ball_in_flight_is_larger_lifted_and_casts_a_shadow():
    pos = np.array([[0.635, 1.0]])
    ground = draw.render_table(TABLE, P, pos, ppm=PPM)
    h = 0.06
    flying = draw.render_table(TABLE, P, pos, ppm=PPM, height=[h])
    white = draw.ball_color(0)
    n0, n1 = _pixels(ground, white), _pixels(flying, white)
    assert n1 / n0 == pytest.approx(draw.flight_scale(h) ** 2, rel=0.15), (n0, n1)
    assert draw.flight_scale(h) == 1 + h / draw.CAMERA_HEIGHT
    cx, cy = np.round(draw.world_to_pixel(TABLE, pos[0], PPM)).astype(int)
    assert tuple(ground[cy, cx]) == white
    assert tuple(flying[cy + int(0.6 * P.R * PPM), cx]) == draw.SHADOW_COLOR  # its shadow on the slate at (x, y)
    lift = int(round(draw.HEIGHT_LIFT * h * PPM))
    assert tuple(flying[cy - lift, cx]) == white  # the ball, lifted by its height
    assert _pixels(ground, draw.SHADOW_COLOR) == 0
    # a ball in flight is drawn over a ball on the slate it passes
    two = draw.render_table(TABLE, P, np.array([[0.635, 1.0], [0.635, 1.0 + h]]), ppm=PPM, height=[h, 0.0])
    assert tuple(two[cy - lift, cx]) == white


def test_raster_off_table_balls_on_the_rail_pocketed_not_drawn():
    R, L = P.R, TABLE.length
    pos = np.array([[0.4, L + 0.05], [0.9, L + 0.6], [0.635, 1.0]])  # came down on the rail, on the floor; pocketed
    img = draw.render_table(TABLE, P, pos, pocket=[C.OFF_RAIL, C.OFF_FLOOR, 0], ppm=PPM)
    spots = [draw.off_table_spot(TABLE, p, R) for p in pos[:2]]
    assert spots[0] == (0.4, L + 0.05)  # within the drawn rail: where it came down
    assert spots[1] == (0.9, L + draw.BORDER - R)  # beyond it: at the rail's outer edge, the side it went
    for i, sp in enumerate(spots):
        cx, cy = np.round(draw.world_to_pixel(TABLE, sp, PPM)).astype(int)
        assert tuple(img[cy, cx + int(0.78 * R * PPM)]) == draw.ball_color(i)  # beside the number disc
    cx, cy = np.round(draw.world_to_pixel(TABLE, spots[1], PPM)).astype(int)
    assert tuple(img[cy, cx - int(R * PPM) - 2]) == draw.FLOOR_RING_COLOR  # the floor's ring
    ring = np.all(img == np.array(draw.FLOOR_RING_COLOR, dtype=np.uint8), axis=2)
    rr, cc = np.nonzero(ring)
    assert np.hypot(rr - cy, cc - cx).max() < 1.6 * R * PPM  # only around the floor ball
    cx, cy = np.round(draw.world_to_pixel(TABLE, pos[2], PPM)).astype(int)
    assert tuple(img[cy, cx]) == draw.FELT_COLOR  # the pocketed ball is not drawn
    # a ball over the bed or the cushion is moved out onto the rail
    assert draw.off_table_spot(TABLE, (0.635, L - 0.01), R) == (0.635, L + R)


def test_raster_frames_of_replays(off, jump, tmp_path):
    """The replay's frames: the ball off the table at its rail spot, ringed;
    the jumped ball's shadow in flight; the GIF writes."""
    s, r, rep = off
    pos, pocket, h = rep.table_view(rep.duration(0))
    img = draw.render_table(TABLE, P, pos, pocket, ppm=PPM, height=h)
    sp = draw.off_table_spot(TABLE, pos[0], P.R)
    cx, cy = np.round(draw.world_to_pixel(TABLE, sp, PPM)).astype(int)
    assert tuple(img[cy, cx]) == draw.ball_color(0)
    assert _pixels(img, draw.FLOOR_RING_COLOR) > 0
    # the log's own evaluation (save_shot_animation, game frames) gives the same
    for t in (0.0, 0.05, rep.duration(0)):
        for x, y in zip(draw.balls_at(r.events[0], P, 2, t, AIR, TABLE), rep.table_view(t)):
            np.testing.assert_allclose(x, y, atol=POS_TOL)
    s, r, rep = jump
    pos, pocket, h = rep.table_view(0.05)
    assert h[0] > 0.02
    img = draw.render_table(TABLE, P, pos, pocket, ppm=PPM, height=h)
    assert _pixels(img, draw.SHADOW_COLOR) > 0
    out = save_replay_animation(tmp_path / "jump.gif", rep, ppm=60, fps=10)
    assert out.stat().st_size > 0


# --------------------------------------------------------------- browser --
def _page(rep, browser, tmp_path, name):
    browser.get(save_replay_html(rep, tmp_path / f"{name}.html").as_uri())
    assert browser.execute_script("return typeof window.billiardsReplay") == "object"


def test_browser_jump_shot_matches_the_simulator(jump, browser, tmp_path):
    """The viewer evolves the records in flight on their parabola as
    replay.evolve_state does: positions and heights at every event time
    against the simulator stopped there, and at random times against the
    Python replay."""
    s, r, rep = jump
    _page(rep, browser, tmp_path, "jump")
    js = "return window.billiardsReplay.positionsAt(arguments[0], arguments[1])"
    for n in range(1, int(r.n_events[0]) + 1):
        cut = simulate(s, TABLE, P, effects=AIR, options=SimOptions(max_events=n))
        t = float(cut.time[0])
        got = np.array(browser.execute_script(js, 0, t), dtype=object)
        on = cut.state.pocket[0] < 0
        assert np.abs(np.array(got[:, :2], dtype=float)[on] - cut.state.pos[0][on]).max() < BROWSER_TOL
        hs = [browser.execute_script("return window.billiardsReplay.state(0, arguments[0], arguments[1])[8]", i, t)
              for i in range(3)]
        assert np.abs(np.array(hs)[on] - cut.state.air[0][on, 0]).max() < BROWSER_TOL, f"after {n} events"
    for t in np.random.default_rng(3).uniform(0, 1.0, 25):
        for i in range(3):
            got = np.array(browser.execute_script("return window.billiardsReplay.state(0, arguments[0], arguments[1])",
                                                  i, float(t)))
            want = rep.ball_state_at(t, i)
            assert np.abs(got - want).max() < BROWSER_TOL, (t, i, got, want)


def test_browser_draws_the_ball_in_flight_and_its_shadow(jump, browser, tmp_path):
    from PIL import Image

    s, r, rep = jump
    _page(rep, browser, tmp_path, "jump")
    t = 0.05
    h = rep.ball_state_at(t, 0)[8]
    browser.execute_script("window.billiardsReplay.seek(0, arguments[0])", t)
    look = browser.execute_script("return window.billiardsReplay.look(0)")
    scale = browser.execute_script("return window.billiardsReplay.scale()")
    assert look["h"] == pytest.approx(h, abs=BROWSER_TOL)
    assert look["r"] == pytest.approx(P.R * scale * draw.flight_scale(h), rel=1e-9)
    assert look["shadow"][1] - look["y"] == pytest.approx(draw.HEIGHT_LIFT * h * scale, rel=1e-6)
    assert browser.execute_script("return window.billiardsReplay.look(1)")["shadow"] is None  # on the slate
    img = np.asarray(Image.open(io.BytesIO(browser.get_screenshot_as_png())).convert("RGB")).astype(int)
    sx, sy = look["shadow"]
    shade = img[int(round(sy + 0.7 * P.R * scale)), int(round(sx))]  # the shadow's far side, clear of the ball
    assert (shade < 0.6 * np.array(draw.FELT_COLOR) + 3).all(), shade
    assert np.abs(img[int(round(look["y"])), int(round(look["x"]))] - draw.ball_color(0)).max() <= 3


def test_browser_draws_the_off_table_ball_where_it_came_down(off, browser, tmp_path):
    from PIL import Image

    s, r, rep = off
    _page(rep, browser, tmp_path, "off")
    browser.execute_script("window.billiardsReplay.seek(0, arguments[0])", rep.duration(0))
    look = browser.execute_script("return window.billiardsReplay.look(0)")
    assert look["off"] == C.OFF_FLOOR
    border = browser.execute_script("return window.billiardsReplay.layout().border")
    (e,) = rep.shots[0]["info"]["off_table"]
    want = browser.execute_script("var q = window.billiardsReplay.toPx(arguments[0], arguments[1]), "
                                  "b = document.getElementById('table').getBoundingClientRect(); "
                                  "return [b.left + q[0], b.top + q[1]]",
                                  *draw.off_table_spot(TABLE, (e["x"], e["y"]), P.R, border))
    assert look["x"] == pytest.approx(want[0], abs=1e-6) and look["y"] == pytest.approx(want[1], abs=1e-6)
    img = np.asarray(Image.open(io.BytesIO(browser.get_screenshot_as_png())).convert("RGB")).astype(int)
    assert np.abs(img[int(round(look["y"])), int(round(look["x"]))] - draw.ball_color(0)).max() <= 3
    # the ring, on the table side (the far side is off the canvas): a pixel across its width in its colour
    w = max(2.0, 0.25 * look["r"])
    ring = img[int(round(look["y"])), int(look["x"] - look["r"] - w - 1):int(look["x"] - look["r"]) + 1]
    assert (np.abs(ring - draw.FLOOR_RING_COLOR).max(axis=1) <= 3).any(), ring
    words = browser.find_element("id", "info").text
    assert "off the table" in words and "(floor)" in words
    browser.execute_script("window.billiardsReplay.seek(0, arguments[0])", e["t"])
    assert "leaves the table over cushion" in browser.find_element("id", "event").text
    assert "to the floor" in browser.find_element("id", "event").text

"""Replays: the event log read back bit for bit, positions at any time equal
to the simulator's, env recording, the command-line script, and the HTML
viewer in a real (headless Chromium) browser.

The browser tests need Chromium, its driver and selenium (``apt-get install
-y chromium chromium-driver``; ``pip install selenium``; conftest.py). Without
them they are skipped, except under CI (environment variable ``CI`` set),
where a missing browser fails.
"""
from __future__ import annotations

import importlib.util
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401  (registers the env ids)
from billiards_env.physics import BallState, Effects, EventLog, PhysicsParams, SimOptions, Table, simulate, strike_velocity
from billiards_env.physics import constants as C
from billiards_env.physics.state import diamond_slots
from billiards_env.rendering import (RecordReplay, Replay, ball_color, ball_paths, positions_at, replay_html,
                                     save_replay_animation, save_replay_html)
from billiards_env.rendering import draw

ROOT = Path(__file__).resolve().parents[2]
# Python evaluation vs the simulator: the same closed forms in float64, so
# they differ by rounding only (~1e-15 m at table scale).
POS_TOL = 1e-9
# The browser's port of the motion law vs the simulator (JavaScript doubles:
# rounding only; 1e-6 m is far below a pixel).
BROWSER_TOL = 1e-6
# Screenshot colours: sRGB fills come back exactly; allow colour management a few units.
COLOR_TOL = 3


# ----------------------------------------------------------------- shots --
def _break(effects=None, cue_x=0.12, speed=8.0):
    """A 9-ball break on a 9 ft table: (struck state, result, table, params)."""
    table, params = Table.pool(9), PhysicsParams.standard()
    slots = diamond_slots(table, params.R)
    pos = np.zeros((10, 2))
    pos[1], pos[9] = slots[0], slots[4]
    pos[[2, 3, 4, 5, 6, 7, 8]] = slots[[1, 2, 3, 5, 6, 7, 8]]
    pos[0] = (table.width / 2 + cue_x, 0.25 * table.length)
    d = pos[1] - pos[0]
    start = strike_velocity(BallState.from_positions(pos), math.atan2(d[1], d[0]), speed, 0.05, -0.1, params)
    return start, simulate(start, table, params, record=True, effects=effects), table, params


def _cut_draw():
    """A 30 degree cut into a corner pocket with draw."""
    table, params = Table.pool(9), PhysicsParams.standard()
    corner = np.array([table.width, table.length])
    obj = corner - 0.3 * np.array([1.0, 1.0]) / math.sqrt(2.0)
    ghost = obj - 2 * params.R * (corner - obj) / np.linalg.norm(corner - obj)
    cue = ghost + 0.9 * np.array([math.cos(math.radians(200.0)), math.sin(math.radians(200.0))])
    d = ghost - cue
    start = strike_velocity(BallState.from_positions(np.array([cue, obj])), math.atan2(d[1], d[0]), 3.0, 0.0, -0.4,
                            params)
    return start, simulate(start, table, params, record=True), table, params


@pytest.fixture(scope="module")
def brk():
    start, res, table, params = _break()
    return start, res, table, params, Replay.from_sim(res, start, table, params)


def _closed_form(st, dt, params):
    """Independent numpy evaluation of a recorded state after dt: constant
    acceleration -mu g along the slip (sliding) or the velocity (rolling)."""
    x, y, vx, vy, wx, wy, _, ms = st[:8]  # the event log's states have 10 columns (h, vz: 0 on the slate)
    ax = ay = 0.0
    if ms == C.SLIDING:
        ux, uy = vx - params.R * wy, vy + params.R * wx
        n = math.hypot(ux, uy)
        ax, ay = -params.mu_s * params.g * ux / n, -params.mu_s * params.g * uy / n
    elif ms == C.ROLLING:
        n = math.hypot(vx, vy)
        ax, ay = -params.mu_r * params.g * vx / n, -params.mu_r * params.g * vy / n
    else:
        vx = vy = 0.0
    return np.array([x + vx * dt + 0.5 * ax * dt * dt, y + vy * dt + 0.5 * ay * dt * dt])


# -------------------------------------------------------- Python replay --
@pytest.mark.parametrize("effects", [None, Effects.minimal()], ids=["all effects", "minimal"])
def test_event_log_reads_back_bit_for_bit(effects, tmp_path, log_read_back):
    start, res, table, params = _break(effects)
    rep = Replay.from_sim(res, start, table, params, effects)
    path = rep.save(tmp_path / "break.json")
    back = Replay.load(path)
    log_read_back(back, res.events[0])
    data = json.loads(path.read_text())
    assert data["format"] == "billiards-replay" and data["version"] == 1
    assert data["n_balls"] == 10 and len(data["shots"]) == 1
    assert set(data["params"]) >= {"R", "g", "mu_s", "mu_r", "mu_sp"}
    assert set(data["effects"]) >= {"spin", "vertical_spin"}
    assert set(data["table"]) >= {"width", "length", "segments", "tips", "pockets", "outline"}


def test_positions_equal_the_simulator_at_every_event(brk):
    """The simulator stopped after n events holds every ball at the n-th event's time."""
    start, res, table, params, rep = brk
    n_total = int(res.n_events[0])
    times = rep.event_times(0)
    for n in sorted(set(np.linspace(1, n_total, 25).astype(int))):
        cut = simulate(start, table, params, options=SimOptions(max_events=n))
        t = float(cut.time[0])
        pos, on = rep.positions_at(t)
        sim_on = cut.state.pocket[0] < 0
        err = np.abs(pos[sim_on] - cut.state.pos[0][sim_on]).max()
        assert err < POS_TOL, f"after {n} events (t = {t}): {err:.3g} m"
        if not np.any(np.isclose(times[times > t], t, rtol=0, atol=1e-12)):  # no later event at the same instant
            np.testing.assert_array_equal(on, sim_on)
    pos, on = rep.positions_at(rep.duration(0))
    np.testing.assert_array_equal(on, res.state.pocket[0] < 0)
    assert np.abs(pos[on] - res.state.pos[0][on]).max() < POS_TOL


def test_positions_at_random_times_match_an_independent_evaluation(brk):
    start, res, table, params, rep = brk
    log = res.events[0]
    rng = np.random.default_rng(0)
    for t in rng.uniform(0.0, rep.duration(0), 60):
        pos, on = rep.positions_at(t)
        for i in range(rep.n_balls):
            rec = [(tr, st) for tr, st, (a, b), k in zip(log.time, log.states, log.balls, log.kind)
                   for st, who in ((st[0], a), (st[1], b if k == C.EV_BALL_BALL else -1)) if who == i and tr <= t]
            tr, st = rec[-1]
            assert on[i] == (st[7] != C.POCKETED)
            if on[i]:
                err = np.abs(pos[i] - _closed_form(st, t - tr, params)).max()
                assert err < POS_TOL, f"ball {i} at t = {t}: {err:.3g} m"
    # the raster renderer's positions are the same evaluation
    for t in rng.uniform(0.0, rep.duration(0), 5):
        p1, on1 = positions_at(log, params, rep.n_balls, t)
        p2, on2 = rep.positions_at(t)
        np.testing.assert_array_equal(on1, on2)
        np.testing.assert_array_equal(p1[on1], p2[on2])


def test_shot_info_and_size():
    start, res, table, params = _cut_draw()
    rep = Replay.from_sim(res, start, table, params, info={"shooter": 0, "ball_in_hand": False})
    info = rep.shots[0]["info"]
    assert info["speed"] == pytest.approx(3.0, abs=1e-12) and info["height"] == pytest.approx(-0.4, abs=1e-12)
    assert info["side"] == pytest.approx(0.0, abs=1e-12)
    assert info["first_contact"] == 1 and info["pocketed"] == [1] and info["shooter"] == 0
    assert info["first_contact"] == int(res.first_contact[0])
    size = lambda shot: len(json.dumps(shot, separators=(",", ":")))
    assert size(rep.shots[0]) < 2500  # a few KB per shot
    assert len(rep.to_json()) - size(rep.shots[0]) < 4000  # table, physics, effects: once per replay
    _, res_b, _, _ = _break()
    assert size(Replay.from_sim(res_b, None, table, params).shots[0]) < 20000  # the busiest shot


def test_multi_shot_replay_and_bad_input(tmp_path):
    start, res, table, params = _cut_draw()
    rep = Replay.from_sim(res, start, table, params)
    # the next shot from the resting table
    nxt = BallState.from_positions(res.state.pos, res.state.pocket)
    nxt = strike_velocity(nxt, 0.5, 1.0, params=params)
    res2 = simulate(nxt, table, params, record=True)
    rep.add_log(res2.events[0], duration=float(res2.time[0]))
    back = Replay.load(rep.save(tmp_path / "two.json"))
    assert len(back) == 2
    p0, on0 = back.positions_at(back.duration(0), 0)
    p1, on1 = back.positions_at(0.0, 1)
    np.testing.assert_array_equal(on0, on1)
    np.testing.assert_array_equal(p0[on0], p1[on1])
    with pytest.raises(ValueError, match="version"):
        Replay({**back.data, "version": 99})
    with pytest.raises(ValueError, match="record=True"):
        Replay.from_sim(simulate(start, table, params), start, table, params)


def _without_stops(rep: Replay) -> Replay:
    """The replay with its roll-stop records removed: balls whose last record is rolling."""
    data = json.loads(rep.to_json())
    for sh in data["shots"]:
        sh["events"] = [row for row in sh["events"] if row[1] != C.EV_ROLL_STOP]
    return Replay(data)


def test_evaluation_stops_at_the_motion_transition():
    """The closed form of a state ends at its transition: without the
    roll-stop records the balls still come to rest where they stopped."""
    start, res, table, params = _cut_draw()
    rep = _without_stops(Replay.from_sim(res, start, table, params))
    assert rep.shots[0]["events"][-1][4][0] == C.ROLLING
    for t in (rep.duration(0), 10 * rep.duration(0)):
        pos, on = rep.positions_at(t)
        np.testing.assert_array_equal(on, res.state.pocket[0] < 0)
        assert np.abs(pos[on] - res.state.pos[0][on]).max() < POS_TOL


def test_ball_paths_use_the_replay_motion(brk):
    start, res, table, params, rep = brk
    paths = ball_paths(EventLog(*rep.event_states(0)), params, rep.n_balls)
    for i, p in enumerate(ball_paths(res.events[0], params, rep.n_balls)):
        np.testing.assert_array_equal(p, paths[i])


# ----------------------------------------------------- envs and scripts --
def test_record_replay_wrapper(tmp_path):
    env = RecordReplay(gym.make("Billiards-RunOut-v1", render_mode="rgb_array", n_balls=2), tmp_path)
    obs, _ = env.reset(seed=4)
    u = env.unwrapped
    n_shots = 0
    while True:
        before = u.state.pos[0].copy()
        obs, r, term, trunc, info = env.step(np.array([0.0, 0.2, 0.0, -0.3], np.float32))
        n_shots += 1
        shot = env.replay.shots[-1] if env.replay is not None else Replay.load(tmp_path / "episode-0000.json").shots[-1]
        assert shot["info"]["first_contact"] == info["first_contact"]
        np.testing.assert_array_equal([rec[1:3] for rec in shot["start"]], before)
        if term or trunc:
            break
    env.close()
    rep = Replay.load(tmp_path / "episode-0000.json")
    assert len(rep) == n_shots and rep.data["meta"]["seed"] == 4
    pos, on = rep.positions_at(rep.duration(n_shots - 1), n_shots - 1)
    np.testing.assert_array_equal(on, u.state.pocket[0] < 0)
    assert np.abs(pos[on] - u.state.pos[0][on]).max() < POS_TOL
    page = (tmp_path / "episode-0000.html").read_text()
    assert "<script src" not in page and "http://" not in page and "https://" not in page  # self-contained
    with pytest.raises(ValueError, match="render_mode"):
        RecordReplay(gym.make("Billiards-PotOne-v1"), tmp_path)


def test_script_episode_to_html_json_gif(tmp_path):
    outs = [tmp_path / "e.html", tmp_path / "e.json", tmp_path / "e.gif"]
    cmd = [sys.executable, str(ROOT / "scripts" / "replay.py"), "--env", "Billiards-PotOne-v1", "--policy", "ghost",
           "--seed", "1", "--ppm", "60", "--fps", "5", "--speedup", "4"]
    for o in outs:
        cmd += ["--out", str(o)]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    assert all(o.stat().st_size > 0 for o in outs)
    rep = Replay.load(outs[1])
    assert rep.data["meta"]["policy"] == "ghost" and len(rep) == 1
    import imageio.v3 as iio
    frames = iio.imread(outs[2])
    assert frames.ndim == 4 and frames.shape[0] > 2
    # the same episode from the single env gives the same shot
    env = gym.make("Billiards-PotOne-v1", render_mode="rgb_array")
    env.reset(seed=1)
    np.testing.assert_array_equal([rec[1:3] for rec in rep.shots[0]["start"]], env.unwrapped.state.pos[0])


def test_mp4_needs_imageio_ffmpeg(tmp_path, monkeypatch, brk):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name in ("imageio_ffmpeg", "av") else real(name, *a))
    with pytest.raises(RuntimeError, match="imageio-ffmpeg"):
        save_replay_animation(tmp_path / "x.mp4", brk[4], ppm=20, fps=2)


def test_raster_draws_legible_numbers():
    """Numbers from NUMBER_MIN_RADIUS px: a digit's dark pixels on the white disc."""
    table, params = Table.pool(9), PhysicsParams.standard()
    pos = np.array([[0.2 + 0.07 * i, 1.0] for i in range(16)])
    ppm = 400
    img = draw.render_table(table, params, pos, ppm=ppm)
    for i in (1, 8, 12):
        cx, cy = draw.world_to_pixel(table, pos[i], ppm)
        box = img[int(cy) - 5:int(cy) + 6, int(cx) - 5:int(cx) + 6].reshape(-1, 3)
        assert (box == 255).all(axis=1).any() and (box == 0).all(axis=1).any(), f"ball {i}: no number drawn"
    small = draw.render_table(table, params, pos, ppm=100)  # too small for numbers: plain ball colours
    cx, cy = np.round(draw.world_to_pixel(table, pos[3], 100)).astype(int)
    assert tuple(small[cy, cx]) == ball_color(3)


# ------------------------------------------------------------- browser --
@pytest.fixture(scope="module")
def break_html(brk, tmp_path_factory):
    return save_replay_html(brk[4], tmp_path_factory.mktemp("html") / "break.html", title="break")


@pytest.fixture
def break_page(break_html, browser):
    """The browser showing the break (other tests load other pages)."""
    path = break_html
    browser.get(path.as_uri())
    assert browser.execute_script("return typeof window.billiardsReplay") == "object"
    return path


def test_browser_positions_match_simulator(brk, browser, break_page):
    start, res, table, params, rep = brk
    js = "return window.billiardsReplay.positionsAt(arguments[0], arguments[1])"
    n_total = int(res.n_events[0])
    for n in (1, 5, n_total // 3, n_total // 2, n_total - 1, n_total):
        cut = simulate(start, table, params, options=SimOptions(max_events=n))
        t = float(cut.time[0])
        got = np.array(browser.execute_script(js, 0, t), dtype=object)
        pos = np.array(got[:, :2], dtype=float)
        sim_on = cut.state.pocket[0] < 0
        assert np.abs(pos[sim_on] - cut.state.pos[0][sim_on]).max() < BROWSER_TOL, f"after {n} events"
    for t in np.random.default_rng(1).uniform(0, rep.duration(0), 20):
        browser.execute_script("window.billiardsReplay.seek(0, arguments[0])", float(t))
        got = browser.execute_script("return window.billiardsReplay.positions()")
        pos, on = rep.positions_at(t)
        np.testing.assert_array_equal([g[2] for g in got], on)
        err = np.abs(np.array([g[:2] for g in got])[on] - pos[on]).max()
        assert err < BROWSER_TOL, f"t = {t}: {err:.3g} m"


def test_browser_evaluation_stops_at_the_motion_transition(browser, tmp_path):
    start, res, table, params = _cut_draw()
    rep = _without_stops(Replay.from_sim(res, start, table, params))
    browser.get(save_replay_html(rep, tmp_path / "nostop.html").as_uri())
    got = browser.execute_script("return window.billiardsReplay.positionsAt(0, arguments[0])", rep.duration(0))
    on = res.state.pocket[0] < 0
    assert [g[2] for g in got] == on.tolist()
    assert np.abs(np.array([g[:2] for g in got])[on] - res.state.pos[0][on]).max() < BROWSER_TOL


def test_browser_screenshot_shows_balls_in_their_colours(brk, browser, break_page):
    from PIL import Image

    rep = brk[4]
    for t in (0.0, 0.25, rep.duration(0)):
        browser.execute_script("window.billiardsReplay.seek(0, arguments[0])", t)
        img = np.asarray(Image.open(io.BytesIO(browser.get_screenshot_as_png())).convert("RGB")).astype(int)
        assert len(np.unique(img.reshape(-1, 3)[::97], axis=0)) > 10, "blank screenshot"
        assert (np.abs(img - draw.FELT_COLOR).max(axis=2) == 0).mean() > 0.1, "no felt on the page"
        pos, on = rep.positions_at(t)
        for i in np.nonzero(on)[0]:
            x, y, r = browser.execute_script("return window.billiardsReplay.ballPixel(arguments[0])", int(i))
            # beside the number disc (radius 0.5 r), on the stripe band (|dy| < 0.65 r)
            px = img[int(round(y)), int(round(x + (0.78 * r if i > 0 else 0.0)))]
            assert np.abs(px - ball_color(int(i))).max() <= COLOR_TOL, f"t = {t}: ball {i} pixel {px}"


def test_browser_frame_times(browser, break_page):
    """Plays the break at 1x for 2.5 s; prints the requestAnimationFrame
    intervals and the draw cost per frame (median, 95th percentile)."""
    import time

    browser.execute_script("window.billiardsReplay.frameTimes.length = 0; window.billiardsReplay.drawTimes.length = 0;"
                           "window.billiardsReplay.seek(0, 0); window.billiardsReplay.play(1)")
    time.sleep(2.5)
    ft, dt = browser.execute_script("window.billiardsReplay.pause();"
                                    "return [window.billiardsReplay.frameTimes, window.billiardsReplay.drawTimes]")
    ft, dt = np.array(ft[1:]), np.array(dt)
    print(f"\nviewer, 9-ball break at 1x: {len(ft)} frames; rAF interval median {np.median(ft):.2f} ms, "
          f"p95 {np.percentile(ft, 95):.2f} ms; draw median {np.median(dt):.3f} ms, p95 {np.percentile(dt, 95):.3f} ms")
    assert len(ft) >= 30, "the viewer did not animate"
    assert np.median(dt) < 8.0, "drawing a frame takes too long for 60 frames per second"


def test_browser_controls_and_play_through(browser, tmp_path):
    """Next / previous event buttons, the speed menu, and play-through from one shot to the next."""
    import time

    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select

    start, res, table, params = _cut_draw()
    rep = Replay.from_sim(res, start, table, params)
    nxt = strike_velocity(BallState.from_positions(res.state.pos, res.state.pocket), 0.5, 0.8, params=params)
    res2 = simulate(nxt, table, params, record=True)
    rep.add_log(res2.events[0], duration=float(res2.time[0]))
    browser.get(save_replay_html(rep, tmp_path / "two.html").as_uri())
    marked = [row[0] for row in rep.shots[0]["events"] if row[1] in (C.EV_BALL_BALL, C.EV_CUSHION, C.EV_JAW_TIP,
                                                                     C.EV_POCKET)]
    cur = lambda: browser.execute_script("return window.billiardsReplay.current()")
    browser.find_element(By.ID, "next").click()
    assert cur()["t"] == marked[0]
    browser.find_element(By.ID, "next").click()
    assert cur()["t"] == marked[1]
    browser.find_element(By.ID, "prev").click()
    assert cur()["t"] == marked[0]
    Select(browser.find_element(By.ID, "speed")).select_by_visible_text("4x")
    browser.execute_script("window.billiardsReplay.seek(0, window.billiardsReplay.duration(0) - 0.05)")
    browser.find_element(By.ID, "play").click()
    deadline = time.time() + 5.0
    while cur()["shot"] == 0 and time.time() < deadline:
        time.sleep(0.1)
    state = cur()
    assert state["shot"] == 1 and state["playing"], state
    browser.execute_script("window.billiardsReplay.pause()")


def test_from_sim_takes_one_table_of_a_batch():
    start, res, table, params = _cut_draw()
    batch = BallState.stack([start, strike_velocity(start, 0.3, 2.0, 0.1, 0.2, params)])
    res2 = simulate(batch, table, params, record=True)
    one = Replay.from_sim(res2, batch, table, params, index=0)
    other = Replay.from_sim(res2, batch, table, params, index=1)
    assert one.shots[0] == Replay.from_sim(res, start, table, params).shots[0]
    assert other.shots[0]["info"]["speed"] == pytest.approx(2.0, abs=1e-12)
    assert other.shots[0]["info"]["side"] == pytest.approx(0.1, abs=1e-12)
    pos, on = other.positions_at(other.duration(0))
    np.testing.assert_array_equal(on, res2.state.pocket[1] < 0)
    assert np.abs(pos[on] - res2.state.pos[1][on]).max() < POS_TOL

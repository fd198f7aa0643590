"""Whole two-player games as replays: the recorder (no shot written twice
after a pass), the game envs' render mode and RecordReplay, the scripts
(replay.py for every registered two-player id, match.py --save-replays), and
the viewer page of a game in headless Chromium (rulings in words, links to
a moment, the phone layouts, a broken file, a saved page)."""
from __future__ import annotations

import io
import json
import re
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import billiards_env  # noqa: F401  (registers the env ids)
from billiards_env.bots import make_bot
from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.envs.games.play import bot_actions
from billiards_env.physics import BallState, PhysicsParams, SimOptions, Table, simulate, strike_velocity
from billiards_env.rendering import GameRecorder, RecordReplay, Replay, replay_html, save_replay_html
from billiards_env.studies.matches import play_pairing

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from replay import game_of  # noqa: E402  (scripts/replay.py)

POS_TOL = 1e-9       # Python evaluation vs the simulator: rounding only
BROWSER_TOL = 1e-6   # the browser's port of the motion law vs the simulator (JavaScript doubles)
MIN_BALL_PX = 8.0    # the ball radius a phone held upright must keep (CSS px)
RAW_CODE = re.compile(r"\b(ball in hand|shooter|foul|end|group|in_hand) \d\b|code \d")  # what words replace
TWO_PLAYER_IDS = sorted(i for i in gym.registry if i.startswith("Billiards-") and game_of(i))


def _scripted_game(seed=3, max_shots=12):
    """A seeded 9-ball game of two ghost bots on a recording core, in which
    every push-out allowed is declared and every pass allowed is taken:
    (core, recorder, [(log played, passed)] per core step)."""
    core = GameCore(GameConfig(game="nine_ball", noise="tournament", max_shots=max_shots), 1, record=True)
    core.streams.seed([0], [seed])
    core.reset_tables([0], [0])
    rec = GameRecorder(core, players=("ghost", "ghost"), meta={"seed": seed})
    bots = [make_bot("ghost", seed), make_bot("ghost", seed + 1)]
    steps = []
    while True:
        c = core.constraints()
        a = bot_actions(core, bots[int(c.shooter[0])], [0])
        if c.push_out_allowed[0] or c.may_pass[0]:
            a[:, 6] = 1.0
        before = core.last_events[0]
        out = core.step(a, [0])
        passed = bool(out["info"]["passed"][0])
        steps.append((before if passed else core.last_events[0], passed, core.state.pos[0].copy(),
                      core.state.pocket[0].copy()))
        if out["terminated"][0] or out["truncated"][0]:
            return core, rec, steps


@pytest.fixture(scope="module")
def scripted():
    return _scripted_game()


def test_recorder_writes_each_turn_once_a_pass_as_a_still(scripted):
    core, rec, steps = scripted
    games = rec.games(0)
    assert len(games) == 1
    rep = games[0]
    assert len(rep) == len(steps), "one entry per turn"
    passes = [k for k, s in enumerate(steps) if s[1]]
    assert passes, "the scripted game has a pass"
    for k in passes:
        # the hazard: after a pass the core still holds the previous shot's log
        assert steps[k][0] is steps[k - 1][0] and core is not None
        sh = rep.shots[k]
        assert sh["events"] == [] and sh["duration"] == 0.0 and sh["info"]["game"]["passed"]
        assert sh["info"]["game"]["declared"] == "pass"
        # the still entry holds the table as it stood
        np.testing.assert_array_equal([r[1:3] for r in sh["start"]], steps[k - 1][2])
    played = [k for k, s in enumerate(steps) if not s[1]]
    for a, b in zip(played, played[1:]):
        assert rep.shots[a]["events"] != rep.shots[b]["events"], f"shots {a} and {b} are the same shot"
    for k in played:  # each played shot is the log the core played, read back bit for bit
        t, kind, balls, states = rep.event_states(k)
        log = steps[k][0]
        np.testing.assert_array_equal(t, log.time)
        np.testing.assert_array_equal(states[:, 0], log.states[:, 0])
    # the end of the last played shot is the table the game ended on (no respot after the 9 went down legally)
    last = played[-1]
    pos, on = rep.positions_at(rep.duration(last), last)
    np.testing.assert_array_equal(on, core.state.pocket[0] < 0)
    assert np.abs(pos[on] - core.state.pos[0][on]).max() < POS_TOL
    with pytest.raises(ValueError, match="record=True"):
        GameRecorder(GameCore(GameConfig(), 1))


def test_game_entries_say_the_game_in_words(scripted):
    core, rec, steps = scripted
    rep = rec.games(0)[0]
    g = rep.data["game"]
    assert g["name"] == "nine_ball" and g["labels"] == ["Player 1", "Player 2"] and len(g["pocket_names"]) == 6
    assert g["start"]["break"] and g["start"]["ball_in_hand"] == "behind the head string"
    for k, sh in enumerate(rep.shots):
        gm = sh["info"]["game"]
        assert gm["ruling"].startswith(f"Player {gm['shooter'] + 1} ")
        assert not RAW_CODE.search(gm["ruling"]), gm["ruling"]
        for st in (gm["before"], gm["after"]):
            assert st["ball_in_hand"] in ("none", "anywhere", "behind the head string")
            assert len(st["fouls"]) == 2 and len(st["score"]) == 2
        if k:  # each turn starts where the last one left the game
            assert gm["before"] == rep.shots[k - 1]["info"]["game"]["after"]
        if not gm["legal"]:
            assert "foul (" in gm["ruling"] and gm["after"]["ball_in_hand"] != "none"
        if gm["before"]["ball_in_hand"] != "none" and not gm["passed"]:
            assert gm["placement"] == [r[1:3] for r in sh["start"]][0]
    assert "pushes out" in " ".join(sh["info"]["game"]["ruling"] for sh in rep.shots)
    final = rep.shots[-1]["info"]["game"]
    if final["game_over"]:
        assert final["after"]["score"][final["winner"]] == 1 and "wins" in final["ruling"]


def test_empty_replay_is_an_error_before_any_page(tmp_path, scripted):
    rep = Replay.for_table(scripted[0].table)
    with pytest.raises(ValueError, match="no shots"):
        save_replay_html(rep, tmp_path / "empty.html")
    assert not (tmp_path / "empty.html").exists()
    with pytest.raises(TypeError, match="Replay"):
        replay_html({"shots": []})


@pytest.mark.parametrize("env_id", TWO_PLAYER_IDS)
def test_game_env_renders(env_id):
    env = gym.make(env_id, render_mode="rgb_array")
    env.reset(seed=0)
    img = env.render()
    assert img.ndim == 3 and img.shape[2] == 3 and img.dtype == np.uint8 and img.std() > 0
    with pytest.raises(ValueError, match="render_mode"):
        type(env.unwrapped)(render_mode="ansi")


def test_two_player_ids_are_found_by_the_registry():
    assert {"Billiards-NineBall2P-v1", "Billiards-EightBall-v1"} <= set(TWO_PLAYER_IDS)
    assert game_of("Billiards-PotOne-v1") is None and game_of("No-Such-v0") is None


def test_record_replay_records_whole_games_of_a_game_env(tmp_path):
    env = RecordReplay(gym.make("Billiards-NineBall2P-v1", render_mode="rgb_array", opponent="ghost", max_shots=10),
                       tmp_path)
    env.reset(seed=1)
    core = env.unwrapped.core
    bot = make_bot("ghost", 7)
    n_steps = 0
    while True:
        obs, r, term, trunc, info = env.step(core.actions_of(bot.act(core.view([0])), [0])[0])
        n_steps += 1 + info["opponent_shots"]
        if term or trunc:
            break
    env.close()
    reps = sorted(tmp_path.glob("episode-*.json"))
    rep = Replay.load(reps[-1])
    assert len(rep) >= n_steps  # every shot of both players (and the opponent's before the agent's first)
    assert rep.data["game"]["players"] == ["agent", "ghost"]
    last = len(rep) - 1
    pos, on = rep.positions_at(rep.duration(last), last)
    np.testing.assert_array_equal(on, core.state.pocket[0] < 0)
    assert np.abs(pos[on] - core.state.pos[0][on]).max() < POS_TOL
    assert (tmp_path / reps[-1].with_suffix(".html").name).exists()
    with pytest.raises(ValueError, match="render_mode"):
        RecordReplay(gym.make("Billiards-EightBall-v1"), tmp_path)


@pytest.mark.parametrize("env_id", TWO_PLAYER_IDS)
def test_script_writes_a_whole_game_of_every_two_player_id(env_id, tmp_path):
    outs = [tmp_path / "g.html", tmp_path / "g.json"]
    policy = "carom8" if game_of(env_id) == "three_cushion" else "ghost"  # the ghost bot pots: no carom
    cmd = [sys.executable, str(ROOT / "scripts" / "replay.py"), "--env", env_id, "--policy", policy,
           "--opponent", "random", "--seed", "2", "--max-shots", "6", "--out", str(outs[0]), "--out", str(outs[1])]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    rep = Replay.load(outs[1])
    assert rep.data["game"]["name"] == game_of(env_id) and rep.data["meta"]["opponent"] == "random"
    played = [s for s in rep.shots if "speed" in s["info"]]  # a pass (snooker: the offender put back in) is no shot
    assert rep.data["game"]["start"]["break"] and 1 <= len(played) <= 6 + 1
    assert rep.shots[-1]["info"]["game"]["after"]["over"] or rep.shots[-1]["info"]["game"]["truncated"]
    assert "<script src" not in outs[0].read_text()


def test_match_saves_replays_without_changing_the_match(tmp_path):
    kw = dict(game="eight_ball", n_racks=2, seed=4, noise="tournament", max_shots=12)
    plain = play_pairing("random", "ghost", **kw)
    saved = play_pairing("random", "ghost", save_replays=3, **kw)
    np.testing.assert_array_equal(plain.winner, saved.winner)
    np.testing.assert_array_equal(plain.shots, saved.shots)
    assert plain.replays == [] and len(saved.replays) == 3
    for rep, k in zip(saved.replays, [0, 2, 1]):  # rack 1 each side breaking, then rack 2
        assert len(rep) == saved.shots[k] + sum(sh["info"]["game"]["passed"] for sh in rep.shots)
        assert rep.data["meta"]["rack"] == k % 2 and rep.data["game"]["players"] == ["random", "ghost"]
    cmd = [sys.executable, str(ROOT / "scripts" / "match.py"), "--policies", "random", "ghost", "--racks", "1",
           "--max-shots", "6", "--save-replays", "2", "--out", str(tmp_path)]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    pages = sorted((tmp_path / "replays" / "nine_ball_tournament").glob("*.html"))
    assert [p.name for p in pages] == ["random_v_ghost-00.html", "random_v_ghost-01.html"]
    bad = subprocess.run(cmd[:-2] + ["--save-replays", "5", "--out", str(tmp_path)], capture_output=True, text=True,
                         timeout=900, cwd=ROOT)
    assert bad.returncode == 2 and "--save-replays" in bad.stderr
    # an entrant whose name holds a dot keeps one file per game (it once lost the game number to with_suffix)
    import importlib.util
    import types
    spec = importlib.util.spec_from_file_location("match_script", ROOT / "scripts" / "match.py")
    match = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(match)
    match.write_replays(tmp_path / "dotted", [types.SimpleNamespace(a="lookahead-2026.12", b="ghost",
                                                                    replays=saved.replays[:2])])
    assert sorted(p.name for p in (tmp_path / "dotted").iterdir()) == [
        f"lookahead-2026.12_v_ghost-0{n}.{ext}" for n in (0, 1) for ext in ("html", "json")]


# ------------------------------------------------------------- browser --
@pytest.fixture(scope="module")
def game_page(scripted, tmp_path_factory):
    return save_replay_html(scripted[1].games(0)[0], tmp_path_factory.mktemp("game") / "game.html")


def _open(browser, path, hash_=""):
    browser.get(path.as_uri() + hash_)
    assert browser.execute_script("return typeof window.billiardsReplay") == "object"


def test_browser_shows_the_game_in_words(browser, game_page, scripted):
    from selenium.webdriver.common.by import By

    rep = scripted[1].games(0)[0]
    _open(browser, game_page)
    api = "window.billiardsReplay"
    for k, sh in enumerate(rep.shots):
        browser.execute_script(f"{api}.seek(arguments[0], {api}.duration(arguments[0]))", k)
        text = browser.find_element(By.TAG_NAME, "aside").text
        gm = sh["info"]["game"]
        assert gm["ruling"] in browser.find_element(By.ID, "ruling").text
        assert "fouls in a row" in text and "ball in hand" in text
        assert not RAW_CODE.search(text), text
        tray = browser.find_element(By.ID, "tray").text
        down = {i for i in range(1, rep.n_balls) if not rep.positions_at(rep.duration(k), k)[1][i]}
        assert {int(x) for x in re.findall(r"\b\d+\b", tray.replace("Player 1", "").replace("Player 2", ""))} == down
    k = next(k for k, sh in enumerate(rep.shots) if sh["info"]["game"]["before"]["push_out_allowed"])
    browser.execute_script(f"{api}.seek(arguments[0], 0)", k)
    assert "push out" in browser.find_element(By.ID, "gamestate").text


def test_browser_raw_action_and_metadata_behind_a_toggle(browser, game_page, scripted):
    """The panel tells a shot in words; the action vector as recorded and the page's metadata are behind a closed
    details toggle, and opened it shows them exactly (the shot's action, the replay's meta)."""
    import json

    from selenium.webdriver.common.by import By

    rep = scripted[1].games(0)[0]
    _open(browser, game_page)
    api = "window.billiardsReplay"
    k = 1
    browser.execute_script(f"{api}.seek(arguments[0], {api}.duration(arguments[0]))", k)
    box, raw = browser.find_element(By.ID, "rawbox"), browser.find_element(By.ID, "raw")
    assert box.get_attribute("open") is None and not raw.is_displayed()
    box.find_element(By.TAG_NAME, "summary").click()
    assert raw.is_displayed()
    shown = json.loads(raw.text)
    assert shown["action"] == pytest.approx(list(rep.shots[k]["info"]["action"]), abs=0), shown
    assert shown["meta"] == rep.data.get("meta", {}), shown
    box.find_element(By.TAG_NAME, "summary").click()  # closed again for the tests that read the panel's words


def test_browser_link_opens_at_that_moment(browser, tmp_path):
    """#shot=2&t=<time of the n-th event of shot 2>: the page opens there and
    its balls stand where the simulator stopped after n events."""
    table, params = Table.pool(9), PhysicsParams.standard()
    start = strike_velocity(BallState.from_positions(np.array([[0.6, 0.5], [0.7, 1.6], [0.3, 2.0]])), 1.45, 3.0,
                            0.0, -0.3, params)
    res = simulate(start, table, params, record=True)
    rep = Replay.from_sim(res, start, table, params)
    nxt = strike_velocity(BallState.from_positions(res.state.pos, res.state.pocket), 0.5, 2.5, 0.1, 0.2, params)
    res2 = simulate(nxt, table, params, record=True)
    rep.add_log(res2.events[0], duration=float(res2.time[0]))
    path = save_replay_html(rep, tmp_path / "two.html")
    for n in (3, int(res2.n_events[0]) // 2):
        cut = simulate(nxt, table, params, options=SimOptions(max_events=n))
        t = float(cut.time[0])
        _open(browser, path, f"#shot=2&t={t!r}")
        cur = browser.execute_script("return window.billiardsReplay.current()")
        assert cur["shot"] == 1 and cur["t"] == t
        got = browser.execute_script("return window.billiardsReplay.positions()")
        on = cut.state.pocket[0] < 0
        err = np.abs(np.array([g[:2] for g in got])[on] - cut.state.pos[0][on]).max()
        assert err < BROWSER_TOL, f"after {n} events: {err:.3g} m"
    # a seek writes the moment into the address; a bad link is said, not ignored
    from selenium.webdriver.support.ui import WebDriverWait

    browser.execute_script("window.billiardsReplay.seek(0, 0.25)")
    WebDriverWait(browser, 5).until(lambda d: d.current_url.endswith("#shot=1&t=0.25"))
    _open(browser, path, "#shot=9&t=1")
    assert "not one of shots 1 to 2" in browser.find_element("id", "notice").text


def test_browser_phone_layouts(browser, game_page, scripted):
    """Upright (390 x 844) the table turns portrait and every ball keeps at
    least 8 px of radius inside the window's width; sideways (844 x 390) it
    fills the width."""
    rep = scripted[1].games(0)[0]
    try:
        browser.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                                {"width": 390, "height": 844, "deviceScaleFactor": 3, "mobile": True})
        _open(browser, game_page)
        lay = browser.execute_script("return window.billiardsReplay.layout()")
        assert lay["portrait"] and lay["height"] > lay["width"]
        for k in (0, len(rep) - 1):
            browser.execute_script("window.billiardsReplay.seek(arguments[0], 0)", k)
            _, on = rep.positions_at(0.0, k)
            for i in np.nonzero(on)[0]:
                x, y, r = browser.execute_script("return window.billiardsReplay.ballPixel(arguments[0])", int(i))
                assert r >= MIN_BALL_PX, f"ball {i}: radius {r:.2f} px"
                assert r <= x <= 390 - r, f"ball {i} outside the window's width: x = {x:.1f}"
        browser.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                                {"width": 844, "height": 390, "deviceScaleFactor": 3, "mobile": True})
        _open(browser, game_page)
        lay = browser.execute_script("return window.billiardsReplay.layout()")
        assert not lay["portrait"] and lay["width"] >= 844 - 40, lay
    finally:
        browser.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})


def test_browser_broken_file_says_what_is_wrong(browser, game_page, tmp_path):
    page = game_page.read_text()
    data = re.search(r'<script type="application/json" id="replay-data">(.*?)</script>', page, re.S)
    cases = {"no shots": json.dumps({**json.loads(data.group(1)), "shots": []}),
             "not valid JSON": data.group(1)[:-40],
             "ball records at its start": json.dumps({**json.loads(data.group(1)), "n_balls": 3})}
    for k, (msg, text) in enumerate(cases.items()):
        path = tmp_path / f"broken{k}.html"
        path.write_text(page[:data.start(1)] + text + page[data.end(1):])
        browser.get(path.as_uri())
        err = browser.find_element("id", "error")
        assert err.is_displayed() and msg in err.text, err.text


def test_browser_saved_page_reopens_offline(browser, game_page, scripted, tmp_path):
    rep = scripted[1].games(0)[0]
    _open(browser, game_page)
    saved = tmp_path / "saved.html"
    saved.write_text(browser.execute_script("return window.billiardsReplay.pageHtml()"))
    text = saved.read_text()
    assert "<script src" not in text and "http://" not in text and "https://" not in text
    k = len(rep) - 1
    _open(browser, saved, f"#shot={k + 1}&t=0.5")
    got = browser.execute_script("return window.billiardsReplay.positions()")
    pos, on = rep.positions_at(0.5, k)
    assert [g[2] for g in got] == on.tolist()
    assert np.abs(np.array([g[:2] for g in got])[on] - pos[on]).max() < BROWSER_TOL
    from PIL import Image
    img = np.asarray(Image.open(io.BytesIO(browser.get_screenshot_as_png())).convert("RGB"))
    assert len(np.unique(img.reshape(-1, 3)[::97], axis=0)) > 10, "blank page"


def test_browser_phone_frame_times(browser, game_page):
    """Plays a game's break at 1x for 2.5 s on a phone held upright (390 x
    844, 3 device pixels per CSS px) and prints the requestAnimationFrame
    intervals and the draw cost per frame (median, 95th percentile)."""
    import time

    try:
        browser.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                                {"width": 390, "height": 844, "deviceScaleFactor": 3, "mobile": True})
        _open(browser, game_page)
        browser.execute_script("const b = window.billiardsReplay; b.seek(0, 0); b.frameTimes.length = 0;"
                               "b.drawTimes.length = 0; b.play(1)")
        time.sleep(2.5)
        ft, dt = browser.execute_script("const b = window.billiardsReplay; b.pause(); return [b.frameTimes, b.drawTimes]")
    finally:
        browser.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})
    ft, dt = np.array(ft[1:]), np.array(dt)
    print(f"\nviewer, a game's break at 1x on a 390x844 phone: {len(ft)} frames; rAF interval median "
          f"{np.median(ft):.2f} ms, p95 {np.percentile(ft, 95):.2f} ms; draw median {np.median(dt):.3f} ms, "
          f"p95 {np.percentile(dt, 95):.3f} ms")
    assert len(ft) >= 30, "the viewer did not animate"


@pytest.mark.parametrize("game,policy", [("snooker", "snooker"), ("three_cushion", "carom8"), ("ten_ball", "ghost"),
                                         ("eight_ball", "ghost")])
def test_game_states_show_points_and_calls_in_the_games_words(game, policy):
    """Games to a score show each player's points (not games won), and a
    call is worded for its game (snooker nominates a colour, 10-ball calls
    its ball and pocket)."""
    core = GameCore(GameConfig(game=game, noise="tournament", max_shots=14), 1, record=True)
    core.streams.seed([0], [5])
    core.reset_tables([0], [0])
    rec = GameRecorder(core)
    bots = [make_bot(policy, 1), make_bot(policy, 2)]
    for _ in range(14):
        out = core.step(bot_actions(core, bots[int(core.constraints().shooter[0])], [0]), [0])
        if out["terminated"][0] or out["truncated"][0]:
            break
    turns = [s["info"]["game"] for s in rec.games(0)[-1].shots]
    states = [t["after"] for t in turns]
    want = "points" if game in ("snooker", "three_cushion") else "games won"
    assert all(st["score_of"] == want for st in states)
    if want == "points":
        assert states[-1]["score"] == core.game.score[0].tolist()
    calls = {st["call"] for st in [t["before"] for t in turns] if st["call_needed"]}
    assert None not in calls and len(calls) <= 1
    if game in ("snooker", "ten_ball"):
        assert calls == {{"snooker": "nominate the colour", "ten_ball": "call the ball and its pocket"}[game]}


# ------------------------------------------- snooker and three-cushion in their own words --
def _bot_game(game, policy, seed=5, max_shots=14):
    core = GameCore(GameConfig(game=game, noise="tournament", max_shots=max_shots), 1, record=True)
    core.streams.seed([0], [seed])
    core.reset_tables([0], [0])
    rec = GameRecorder(core)
    bots = [make_bot(policy, 1), make_bot(policy, 2)]
    for _ in range(max_shots):
        out = core.step(bot_actions(core, bots[int(core.constraints().shooter[0])], [0]), [0])
        if out["terminated"][0] or out["truncated"][0]:
            break
    return core, rec.games(0)[-1]


@pytest.fixture(scope="module")
def named_pages(tmp_path_factory):
    """A snooker frame (snooker bots) and a three-cushion game (carom8), 14 shots each, and their pages."""
    out = {}
    for game, policy in (("snooker", "snooker"), ("three_cushion", "carom8")):
        core, rep = _bot_game(game, policy)
        out[game] = (core, rep, save_replay_html(rep, tmp_path_factory.mktemp(game) / f"{game}.html"))
    return out


NUMBERED = re.compile(r"\bball \d+")  # a ball by number: "ball 7" (lists of numbers: the rows' tests)
SNOOKER_NAMES = {"red", "yellow", "green", "brown", "blue", "pink", "black"}


def _rows(browser, table_id):
    return dict(browser.execute_script(
        "return Array.from(document.getElementById(arguments[0]).rows).map(function (r) "
        "{ return [r.cells[0].textContent, r.cells[1].textContent]; });", table_id))


def test_game_entry_names_the_balls_and_the_d(named_pages):
    core, rep, _ = named_pages["snooker"]
    g = rep.data["game"]
    assert g["ball_names"][0] == "cue ball" and g["ball_names"][1:16] == ["red"] * 15
    assert g["ball_names"][16:] == ["yellow", "green", "brown", "blue", "pink", "black"]
    m = core.table.marks
    assert g["d"] == [m.d_centre[0], m.d_centre[1], m.d_radius] and "pockets" not in g
    g3 = named_pages["three_cushion"][1].data["game"]
    assert g3["ball_names"] == ["white", "yellow", "red"] and g3["pockets"] is False and "d" not in g3
    for sh in named_pages["three_cushion"][1].shots:  # each state says its frame: slot 0 the player to move's ball
        for st in (sh["info"]["game"]["before"], sh["info"]["game"]["after"]):
            assert st["ball_ids"] == ([0, 1, 2] if st["to_move"] == 0 else [1, 0, 2]), st
    pool = _scripted_game(max_shots=2)[1].games(0)[0].data["game"]  # pool games: numbers, no new entries
    assert not {"ball_names", "pockets", "d"} & set(pool)


def test_browser_snooker_names_balls_by_colour_and_shades_the_d(browser, named_pages):
    core, rep, page = named_pages["snooker"]
    _open(browser, page)
    api = "window.billiardsReplay"
    seen = set()
    for k, sh in enumerate(rep.shots):
        browser.execute_script(f"{api}.seek(arguments[0], {api}.duration(arguments[0]))", k)
        aside = browser.find_element("tag name", "aside").text
        assert not NUMBERED.search(aside), (k, aside)
        gm, info, state = sh["info"]["game"], _rows(browser, "info"), _rows(browser, "gamestate")
        targets = state.get("legal targets", "none")
        assert not re.search(r"\d", targets), targets
        if len(gm["after"]["targets"]) > 1 and all(1 <= b <= 15 for b in gm["after"]["targets"]):
            assert targets == "reds", targets
        if gm.get("nominated"):
            assert info["nominated"] in SNOOKER_NAMES - {"red"}, info
            seen.add("nominated")
        if sh["info"]["pocketed"]:
            assert not re.search(r"\b\d+\b", info["pocketed"]), info["pocketed"]
            seen.add("pocketed")
        if gm["respotted"]:
            assert state["respotted"] in SNOOKER_NAMES, state
            seen.add("respotted")
        fc = sh["info"]["first_contact"]
        if fc > 0:
            assert info["first contact"] == ("a red" if fc <= 15 else f"the {rep.data['game']['ball_names'][fc]}")
    assert seen == {"nominated", "pocketed", "respotted"}, seen
    labels = browser.execute_script("return Array.from(document.querySelectorAll('#shot option')).map("
                                    "function (o) { return o.text; });")
    assert any("pots a red" in t for t in labels) and not any(re.search(r"pots \d", t) for t in labels), labels
    # the break: the cue ball in hand in the D, which is shaded (in baulk outside the D, and beyond it, is not)
    browser.execute_script(f"{api}.seek(0, 0)")
    assert "in the D" in _rows(browser, "gamestate")["ball in hand"]
    cx, cy, r = rep.data["game"]["d"]
    felt = browser.execute_script(
        "const V = window.billiardsReplay, c = document.getElementById('table'), x = c.getContext('2d'), "
        "k = c.width / c.getBoundingClientRect().width; return arguments[0].map(function (p) { const q = V.toPx(p[0], "
        "p[1]); return Array.from(x.getImageData(Math.round(q[0] * k), Math.round(q[1] * k), 1, 1).data); });",
        [[cx - 0.4 * r, cy - 0.5 * r], [0.2, cy - 0.3], [cx, cy + 1.0]])
    inside, baulk, beyond = (np.array(p[:3], dtype=float) for p in felt)
    assert np.abs(baulk - beyond).max() <= 2, (baulk, beyond)   # neither shaded
    assert (inside - baulk).min() >= 8, (inside, baulk)          # the D lighter


def test_browser_three_cushion_names_the_balls_and_rings_the_movers_targets(browser, named_pages):
    """Slot 0 is the cue ball of the player to move: after a shot that hands the table over, the next player's
    targets (the after state's slots) are the other two balls of the shot drawn, and the rings go on them, never on
    the next player's own cue ball."""
    _, rep, page = named_pages["three_cushion"]
    _open(browser, page)
    api = "window.billiardsReplay"
    handed = 0
    for k, sh in enumerate(rep.shots):
        gm, ids = sh["info"]["game"], sh["info"]["ball_ids"]
        browser.execute_script(f"{api}.seek(arguments[0], {api}.duration(arguments[0]))", k)
        after = gm["after"]
        if after["over"]:
            continue
        ringed = {ids[i] for i in browser.execute_script(f"return {api}.ringed()")}
        want = {after["ball_ids"][b] for b in after["targets"]}
        assert ringed == want and after["ball_ids"][0] not in ringed, (k, ringed, want)
        handed += gm["turn_over"]
        aside = browser.find_element("tag name", "aside").text
        assert not NUMBERED.search(aside) and "pocketed" not in aside, (k, aside)
        names = rep.data["game"]["ball_names"]
        assert _rows(browser, "gamestate")["legal targets"] == ", ".join(names[i] for i in sorted(
            want, key=lambda i: after["ball_ids"].index(i)))
        assert _rows(browser, "info")["cue ball"] == names[ids[0]]
        if k + 1 < len(rep.shots):  # the next shot's start rings the same balls
            browser.execute_script(f"{api}.seek(arguments[0], 0)", k + 1)
            nxt = rep.shots[k + 1]["info"]["ball_ids"]
            assert {nxt[i] for i in browser.execute_script(f"return {api}.ringed()")} == want
    assert handed >= 3

"""How quickly the play page answers, measured in headless Chromium against a
server on 127.0.0.1 (``scripts/play_latency.py``; docs/play.md).

- **click to first frame**: from the Shoot click's handler to the first frame
  of that shot's animation on screen (``requestAnimationFrame`` after the
  frame that drew it): the request, the server's simulation and ruling, the
  JSON, and the viewer taking the new entry;
- **bot reply**: from the page's request for the bot's turn to the first frame
  of its animation (the page starts it as soon as it arrives: ``opts.cut``),
  with the bot's own thinking time on the server beside it;
- **frames while animating a break** on a 390 x 844 phone screen (3 device px
  per CSS px): the ``requestAnimationFrame`` intervals and the draw cost.

A ``PagePerson`` plays 9-ball by mouse (the Hint's shot, dragged and clicked)
against each bot, game after game, until every bot has given ``shots``
replies and the person has taken ``shots`` shots.
"""
from __future__ import annotations

import csv
import json
import os
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

from ..rules import DEFAULT_GAME
from .browser import PagePerson

FPS_SECONDS = 2.5        # s of break animation timed at 1x
RUN_GAMES = 512          # the measuring server's store: a game per rack and bot (about 60 in a --docs run), none dropped
WARM_TURNS = 40         # untimed turns per bot before its timings (its kernels compiled; numba caches them on disk)
PHONE = {"width": 390, "height": 844, "deviceScaleFactor": 3, "mobile": True}


def chromium(width: int = 1400, height: int = 900):
    """A headless Chromium (Debian's ``chromium`` and ``chromium-driver``) and its profile directory."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    binary = shutil.which("chromium") or "/usr/bin/chromium"
    driver = shutil.which("chromedriver") or "/usr/bin/chromedriver"
    if not (os.path.exists(binary) and os.path.exists(driver)):
        raise RuntimeError("Chromium not found: apt-get install -y chromium chromium-driver")
    opts = webdriver.ChromeOptions()
    opts.binary_location = binary
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
                 f"--window-size={width},{height}", "--force-device-scale-factor=1"):
        opts.add_argument(flag)
    profile = tempfile.mkdtemp(prefix="play-chromium-")
    opts.add_argument(f"--user-data-dir={profile}")
    return webdriver.Chrome(service=Service(driver), options=opts), profile


def _new_game(client, bot: str, seed: int) -> str:
    status, g = client("POST", "/api/games", {"game": DEFAULT_GAME, "opponent": bot, "seed": seed})
    if status != 201:
        raise RuntimeError(f"could not start a game: {g}")
    return g["id"]


def warm(client, bot: str, turns: int = WARM_TURNS) -> None:
    """Play ``turns`` turns of ``bot`` against itself through the API (new racks as games end), so that the
    kernels of its rarer paths (safeties, kicks, ball in hand) are compiled before anything is timed."""
    gid, seed = None, 0
    for _ in range(turns):
        if gid is None:
            status, g = client("POST", "/api/games", {"game": DEFAULT_GAME, "players": [bot, bot], "seed": seed})
            seed += 1
            gid = g["id"]
        status, r = client("POST", f"/api/games/{gid}/bot")
        if status != 200 or r["state"]["over"]:
            gid = None


def measure_bot(driver, client, bot: str, shots: int, seed0: int = 100, progress=print) -> dict:
    """Timings (ms) of ``shots`` person shots and ``shots`` bot replies against ``bot``."""
    got = {"shot": [], "bot": [], "think": []}
    seed = seed0
    while len(got["shot"]) < shots or len(got["bot"]) < shots:
        driver.get(client.url + "/game/" + _new_game(client, bot, seed))
        driver.execute_script("window.billiardsPlay.opts.cut = true; window.billiardsPlay.opts.speed = 16;")
        person = PagePerson(driver, push_out=False)
        for _ in range(60):
            st = person.wait_turn()
            if st["over"] or len(got["shot"]) >= shots and len(got["bot"]) >= shots:
                break
            person.turn()
        person.wait_turn()
        for t in driver.execute_script("return window.billiardsPlay.timings;"):
            got[t["kind"]].append(t["ms"])
            if t["kind"] == "bot":
                got["think"].append(t["think_ms"])
        progress(f"  {bot}, game seed {seed}: {len(got['shot'])} shots, {len(got['bot'])} replies so far")
        seed += 1
    return got


def summary(values) -> dict:
    v = np.asarray(values, dtype=float)
    return {"n": int(len(v)), "p50": float(np.median(v)), "p95": float(np.percentile(v, 95)), "max": float(v.max())}


def phone_fps(driver, client, seconds: float = FPS_SECONDS) -> dict:
    """rAF intervals and draw times (ms) while a person's break animates at 1x on a 390 x 844 screen."""
    try:
        driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride", PHONE)
        driver.get(client.url + "/game/" + _new_game(client, "ghost", 1))
        person = PagePerson(driver, push_out=False)
        person.wait_turn()
        driver.execute_script("window.billiardsPlay.opts.speed = 1;")
        person.turn()
        end = time.monotonic() + 30
        while driver.execute_script("return window.billiardsReplay.current().shot;") < 1 and time.monotonic() < end:
            time.sleep(0.01)
        driver.execute_script("const b = window.billiardsReplay; b.frameTimes.length = 0; b.drawTimes.length = 0;")
        time.sleep(seconds)
        ft, dt, playing, lay = driver.execute_script(
            "const b = window.billiardsReplay; return [b.frameTimes.slice(1), b.drawTimes.slice(), b.current().playing,"
            " b.layout()];")
    finally:
        driver.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})
    ft, dt = np.asarray(ft), np.asarray(dt)
    return {"frames": int(len(ft)), "fps_median": float(1000.0 / np.median(ft)), "interval_p50": float(np.median(ft)),
            "interval_p95": float(np.percentile(ft, 95)), "draw_p50": float(np.median(dt)),
            "draw_p95": float(np.percentile(dt, 95)), "late_frames": float(np.mean(ft > 1000.0 / 60 * 1.5)),
            "still_playing": bool(playing), "portrait": bool(lay["portrait"]), "ball_px": float(lay["scale"] * 0.028575)}


def table_md(rows: list[dict], fps: dict | None, load: float | None = None) -> str:
    out = ["| bot | person's shot: click to first frame p50 / p95 (ms) | bot's reply: request to first frame p50 / p95 "
           "(ms) | bot thinking p50 / p95 (ms) | shots / replies |", "|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| `{r['bot']}` | {r['shot']['p50']:.1f} / {r['shot']['p95']:.1f} | {r['bot_reply']['p50']:.1f} / "
                   f"{r['bot_reply']['p95']:.1f} | {r['think']['p50']:.1f} / {r['think']['p95']:.1f} | "
                   f"{r['shot']['n']} / {r['bot_reply']['n']} |")
    if fps:
        out += ["", f"Break animating at 1x on a 390 x 844 screen (3 device px per CSS px, portrait, balls "
                    f"{fps['ball_px']:.1f} CSS px in radius): {fps['frames']} frames in {FPS_SECONDS} s, "
                    f"{fps['fps_median']:.1f} frames per second (median interval {fps['interval_p50']:.2f} ms, p95 "
                    f"{fps['interval_p95']:.2f} ms, {100 * fps['late_frames']:.1f}% of frames over 25 ms); drawing a "
                    f"frame {fps['draw_p50']:.2f} ms median, {fps['draw_p95']:.2f} ms p95."]
    if load is not None:
        out += ["", f"Load average of the machine during the run: {load:.1f} on {os.cpu_count()} cores."]
    return "\n".join(out)


def run(bots, shots: int, out: Path | None, docs: Path | None = None, fps: bool = True, progress=print) -> dict:
    from .server import serve, warm_up

    class Client:
        def __init__(self, url):
            self.url = url.rstrip("/")

        def __call__(self, method, path, body=None):
            import urllib.error
            import urllib.request
            req = urllib.request.Request(self.url + path, method=method, headers={"Content-Type": "application/json"},
                                         data=None if body is None else json.dumps(body).encode())
            try:
                with urllib.request.urlopen(req, timeout=300) as f:
                    return f.status, json.loads(f.read())
            except urllib.error.HTTPError as e:
                return e.code, json.loads(e.read())

    progress("compiling...")
    warm_up()
    server, url = serve(port=0, max_games=RUN_GAMES)
    client = Client(url)
    driver, profile = chromium()
    rows = []
    try:
        for bot in bots:
            progress(f"{bot}: warming up its kernels ({WARM_TURNS} turns of the bot against itself, not timed)")
            warm(client, bot)
            got = measure_bot(driver, client, bot, shots, progress=progress)
            rows.append({"bot": bot, "shot": summary(got["shot"]), "bot_reply": summary(got["bot"]),
                         "think": summary(got["think"])})
        phone = phone_fps(driver, client) if fps else None
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
        server.should_exit = True
    load = os.getloadavg()[1]  # the 5-minute average
    md = table_md(rows, phone, load)
    result = {"rows": rows, "fps": phone, "shots": shots, "cpus": os.cpu_count(), "load": load}
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "latency.json").write_text(json.dumps(result, indent=1))
        (out / "latency.md").write_text(md + "\n")
        with open(out / "latency.csv", "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["bot", "measure", "n", "p50_ms", "p95_ms", "max_ms"])
            for r in rows:
                for k in ("shot", "bot_reply", "think"):
                    w.writerow([r["bot"], k, r[k]["n"], f"{r[k]['p50']:.2f}", f"{r[k]['p95']:.2f}", f"{r[k]['max']:.2f}"])
    if docs is not None:
        text = docs.read_text()
        a, b = "<!-- latency:start -->", "<!-- latency:end -->"
        if a in text and b in text:
            docs.write_text(text[:text.index(a) + len(a)] + "\n" + md + "\n" + text[text.index(b):])
    return result

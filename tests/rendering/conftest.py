"""The headless Chromium the viewer's browser tests share (selenium with
Debian's ``chromium`` and ``chromium-driver``). Without them the browser
tests skip, except under CI (environment variable ``CI`` set), where a
missing browser fails."""
from __future__ import annotations

import importlib.util
import os
import shutil
import tempfile

import pytest


def _missing(msg: str):
    if os.environ.get("CI"):
        pytest.fail(msg + " (required under CI)")
    pytest.skip(msg)


def _find_browser(chromium: str | None = None, driver: str | None = None) -> tuple[str, str]:
    """Paths of Chromium and chromedriver; skips (fails under CI) when either, or selenium, is missing."""
    if importlib.util.find_spec("selenium") is None:
        _missing("selenium is not installed: pip install selenium (part of the 'test' extra)")
    chromium = chromium or shutil.which("chromium") or "/usr/bin/chromium"
    driver = driver or shutil.which("chromedriver") or "/usr/bin/chromedriver"
    if not (os.path.exists(chromium) and os.path.exists(driver)):
        _missing("Chromium not found: install it with apt-get install -y chromium chromium-driver")
    return chromium, driver


def _log_read_back(back, log, shot: int = 0) -> None:
    """A replay's shot ``shot`` read back (``Replay.event_states``) is the simulator's event log ``log``, bit for
    bit: times, kinds, balls, the first ball's state of every event and the second's of every ball-ball event."""
    import numpy as np

    from billiards_env.physics import constants as C
    t, kind, balls, states = back.event_states(shot)
    np.testing.assert_array_equal(t, log.time)
    np.testing.assert_array_equal(kind, log.kind)
    np.testing.assert_array_equal(balls, log.balls)
    np.testing.assert_array_equal(states[:, 0], log.states[:, 0])
    bb = log.kind == C.EV_BALL_BALL
    np.testing.assert_array_equal(states[bb, 1], log.states[bb, 1])


@pytest.fixture
def log_read_back():
    return _log_read_back


@pytest.fixture
def find_browser():
    return _find_browser


@pytest.fixture(scope="session")
def browser():
    """One headless Chromium, 1400 x 900 CSS px at device scale 1 (a test that emulates
    another screen clears its override when done)."""
    chromium, driver_bin = _find_browser()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--window-size=1400,900", "--force-device-scale-factor=1"):
        opts.add_argument(flag)
    profile = tempfile.mkdtemp(prefix="replay-chromium-")
    opts.add_argument(f"--user-data-dir={profile}")
    drv = webdriver.Chrome(service=Service(driver_bin), options=opts)
    yield drv
    drv.quit()
    shutil.rmtree(profile, ignore_errors=True)

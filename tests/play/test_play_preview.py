"""The play page's aim preview against the simulator: where the drawn cue-ball line first meets a cushion.

The page draws the cue ball's path on to the first cushion (the line of the ball's centre R from the cushion
noses) and mirrors it from there (three times in three-cushion). Here a person aims by mouse along a path with
no ball on it, the page's drawn first-cushion point is read (``window.billiardsPlay.preview()``: the points the
overlay drew, in metres) and compared with the simulator's: the same aim struck slowly, with no spin and no
noise, through the game's own equipment (``Equipment.simulate`` with ``record=True``), and the cue ball's
centre at its first ``EV_CUSHION`` event.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from billiards_env.envs.games import GameConfig, GameCore
from billiards_env.physics import constants as C
from billiards_env.physics.state import BallState
from billiards_env.physics.strike import strike_velocity
from billiards_env.play.browser import PagePerson

# The browser fixture's window is 1400 x 900 CSS px at device scale 1; there the 9-ball table is drawn at 374 px per
# metre (2.7 mm of table a pixel) and the carom table at 337 (3.0 mm a pixel): the test reads the scale and checks
# that a pixel is at most MAX_PX_M. The page computes the preview in metres (float64) on the same cushion line as
# the simulator (the ball's centre R from the nose) and only then turns it into pixels, so the two should agree far
# inside a pixel: the tolerance is under a tenth of a pixel here, 0.25 mm (measured on 2026-12-07: 2.5e-16 m, the
# two computations agree to rounding).
CUSHION_TOL_M = 0.25e-3
MAX_PX_M = 3.0e-3               # the tolerance's premise: a pixel is at most 3 mm of table at this window size
SPEED = 1.0                     # m/s: a slow shot that reaches the first cushion (rolling, on a straight line)

# (game, the game's own bot, seed, aims in degrees from +x along which the cue ball meets no ball and reaches
# a rail away from the pockets' jaws)
CASES = [("nine_ball", "ghost", 3, (200.0, 290.0, 160.0)),
         ("three_cushion", "carom", 3, (20.0, 250.0, 110.0))]


def first_cushion(core: GameCore, pos, on_table, phi: float) -> tuple[int, np.ndarray]:
    """The simulator's first event of the cue ball (ball 0) after the strike that touches anything (another
    ball, a cushion, a jaw, a pocket): (its kind, the cue ball's centre there)."""
    pocket = np.where(np.asarray(on_table), -1, 0)
    state = BallState.from_positions(np.asarray(pos, dtype=float), pocket=pocket[None])
    struck = strike_velocity(state, phi, SPEED, 0.0, 0.0, params=core.params)
    log = core.equipment.simulate(struck, record=True).events[0]
    for k, kind, (i, j) in zip(range(len(log)), log.kind, log.balls):
        touches = kind in (C.EV_BALL_BALL, C.EV_CUSHION, C.EV_JAW_TIP, C.EV_POCKET)
        if touches and (i == 0 or kind == C.EV_BALL_BALL and j == 0):
            s = 0 if i == 0 else 1
            return int(kind), log.states[k, s, :2].copy()
    raise AssertionError("the cue ball touched nothing")


@pytest.mark.parametrize("game,bot,seed,aims", CASES, ids=[c[0] for c in CASES])
def test_the_drawn_first_cushion_point_is_the_simulators(server, browser, game, bot, seed, aims):
    st, g = server("POST", "/api/games", {"game": game, "opponent": bot, "seed": seed, "breaker": 0, "noise": "none"})
    assert st == 201, g
    browser.get(server.url + "/game/" + g["id"])
    person = PagePerson(browser)
    state = person.wait_turn()
    assert state["human_to_move"] and not state["over"]
    px_per_m = browser.execute_script("return window.billiardsReplay.layout().scale;")
    assert 1.0 / px_per_m <= MAX_PX_M, f"a pixel is {1e3 / px_per_m:.2f} mm: the tolerance's reason no longer holds"
    core = GameCore(GameConfig(game=game, noise="none"), 1)
    lim = state["limits"]
    assert math.isclose(core.params.R, lim["R"]) and math.isclose(core.table.width, lim["width"])
    for deg in aims:
        person.aim(math.radians(deg))  # dragged by mouse: the page's aim is near deg, to the pixel
        pv = browser.execute_script("return window.billiardsPlay.preview();")
        phi = browser.execute_script("return window.billiardsPlay.choice.phi;")
        assert pv is not None and pv["phi"] == phi, "the preview drawn is of the aim chosen"
        assert pv["from"] == state["pos"][0], "from where the simulated cue ball starts"
        assert abs(math.remainder(phi - math.radians(deg), 2 * math.pi)) < math.radians(2), (deg, phi)
        assert pv["ball"] == -1, f"aim {deg} deg: the drawn path meets ball {pv['ball']}, not a cushion"
        legs, full = len(pv["path"]) - 1, (3 if game == "three_cushion" else 1)
        assert legs == full or legs < full and pv["pathBall"] > 0, "the first cushion, then the mirrored leg(s) to a ball"
        assert pv["scratchPocket"] is None, f"aim {deg} deg: the path is drawn into pocket {pv['scratchPocket']}"
        kind, sim = first_cushion(core, state["pos"], state["on_table"], phi)
        assert kind == C.EV_CUSHION, f"aim {deg} deg: the simulated cue ball first meets {C.EVENT_NAMES[kind]}"
        page = np.array(pv["path"][0])
        gap = float(np.hypot(*(page - sim)))
        assert gap <= CUSHION_TOL_M, (f"{game}, aim {math.degrees(phi):.3f} deg: the page's first cushion point "
                                      f"{page} is {gap * 1e3:.3f} mm ({gap * px_per_m:.2f} px) from the "
                                      f"simulator's {sim}")

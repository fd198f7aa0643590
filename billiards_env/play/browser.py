"""A person at the play page, by mouse events or by touch events only
(selenium's pointer actions in a headless Chromium: a mouse, or a finger's
touch pointer with ``touch=True``): what the browser tests and
``scripts/play_latency.py`` play with.

The person looks at the page as a player would: the state panel, the aim
line and the ``Hint`` button's suggestion (the ghost bot's shot, shown as
the aim line and the power on the bar), then drags the cue ball when it
is in hand, drags from the cue ball to aim, taps the spin diagram and the
power bar, taps a pocket to call it, the push-out or pass buttons, and
Shoot. The page's own hooks (``window.billiardsPlay``,
``window.billiardsReplay``) are read only to see where things are drawn
(and where on the bar a speed lies). ``scrolled`` counts the times the page
had to be scrolled to reach what the person touched.
"""
from __future__ import annotations

import math
import time

READY_TIMEOUT = 120.0   # s: the longest wait for the page to hand a person the table
POLL = 0.02             # s between looks at the page


class PagePerson:
    """Plays the open play page of ``driver`` (a selenium WebDriver).
    ``tip``: the (side, height) offset clicked on the cue-ball diagram;
    ``push_out``: declare a push-out whenever the rules offer one (the shot
    then rolls the cue ball softly); ``pass_back``: pass when offered."""

    def __init__(self, driver, tip=(0.0, -0.1), push_out: bool = True, pass_back: bool = False, touch: bool = False):
        self.d, self.tip, self.push_out, self.pass_back, self.touch = driver, tip, push_out, pass_back, touch
        self.done = {"placement": 0, "aim": 0, "tip": 0, "push_out": 0, "pass": 0, "pocket": 0, "speed": 0}
        self.scrolled = 0  # times the page had to be scrolled to reach what the person touched

    # --- looking at the page -------------------------------------------------------
    def js(self, script: str, *args):
        return self.d.execute_script(script, *args)

    def state(self) -> dict:
        return self.js("return window.billiardsPlay.state();")

    def wait_turn(self, timeout: float = READY_TIMEOUT) -> dict:
        """Wait until a person may shoot or the game is over; the state."""
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            r = self.js("const P = window.billiardsPlay, s = P && P.state();"
                        "return s ? {ready: P.ready(), busy: P.busy(), over: s.over} : null;")
            if r and (r["ready"] or r["over"] and not r["busy"]):
                return self.state()
            time.sleep(POLL)
        raise TimeoutError("the page did not hand the table to a person in time: " +
                           str(self.js("return document.getElementById('pl-status').textContent + ' / ' + "
                                       "document.getElementById('pl-msg').textContent;")))

    def px(self, x: float, y: float) -> tuple[int, int]:
        """Viewport CSS pixel of the table point (x, y) m (the page scrolled to show it, when it is off the screen: a
        corner pocket at the screen's top edge is touched where it is)."""
        if self.js("const q = window.billiardsReplay.toPx(arguments[0], arguments[1]),"
                   "b = document.getElementById('table').getBoundingClientRect(), v = b.top + q[1];"
                   "if (v < 1 || v > innerHeight - 1) { window.scrollBy(0, v - innerHeight / 2); return true; }"
                   "return false;", x, y):
            self.scrolled += 1
        u, v = self.js("const q = window.billiardsReplay.toPx(arguments[0], arguments[1]),"
                       "b = document.getElementById('table').getBoundingClientRect(); return [b.left + q[0], b.top + q[1]];",
                       x, y)
        return round(u), round(v)

    def centre(self, element_id: str) -> tuple[float, float, float, float]:
        """The element's box in the viewport (scrolled into view first)."""
        box = self.js("const e = document.getElementById(arguments[0]), r = e.getBoundingClientRect();"
                      "const off = r.top < 0 || r.bottom > innerHeight; if (off) e.scrollIntoView({block: 'center'});"
                      "const b = e.getBoundingClientRect();"
                      "return [b.left, b.top, b.width, b.height, off];", element_id)
        self.scrolled += bool(box[4])
        return tuple(box[:4])

    # --- the mouse, or a finger ---------------------------------------------------------
    def _actions(self):
        from selenium.webdriver.common.actions import interaction
        from selenium.webdriver.common.actions.action_builder import ActionBuilder
        from selenium.webdriver.common.actions.mouse_button import MouseButton
        from selenium.webdriver.common.actions.pointer_input import PointerInput
        if self.touch:  # touch events only: a finger's pointer (pointerType "touch"), no mouse
            return ActionBuilder(self.d, mouse=PointerInput(interaction.POINTER_TOUCH, "finger"), duration=0), MouseButton.LEFT
        return ActionBuilder(self.d, duration=0), MouseButton.LEFT

    def drag(self, a, b, steps: int = 4) -> None:
        ab, left = self._actions()
        ab.pointer_action.move_to_location(*a).pointer_down(left)
        for k in range(1, steps + 1):
            ab.pointer_action.move_to_location(round(a[0] + (b[0] - a[0]) * k / steps),
                                               round(a[1] + (b[1] - a[1]) * k / steps))
        ab.pointer_action.pointer_up(left)
        ab.perform()

    def click_at(self, p) -> None:
        ab, left = self._actions()
        ab.pointer_action.move_to_location(*p).pointer_down(left).pointer_up(left)
        ab.perform()

    def click(self, element_id: str) -> None:
        x, y, w, h = self.centre(element_id)
        self.click_at((round(x + w / 2), round(y + h / 2)))

    # --- a turn ---------------------------------------------------------------------------
    def hint(self) -> dict:
        """Click Hint and read the suggestion off the page (the aim line, the slider, the placed cue ball)."""
        before = self.js("return window.billiardsPlay.choice.phi;")
        self.js("document.getElementById('pl-msg').textContent = '';")
        self.click("pl-hint")
        end = time.monotonic() + 60
        while time.monotonic() < end:  # the page shows the hint's wait, then its shot on the controls
            if self.js("return !window.billiardsPlay.hinting() && "
                       "document.getElementById('pl-msg').textContent.indexOf('hint') >= 0;"):
                break
            time.sleep(POLL)
        c = self.js("const c = window.billiardsPlay.choice; return {phi: c.phi, placement: c.placement, pocket: c.pocket,"
                    "speed: c.speed};")
        c["changed"] = c["phi"] != before
        return c

    def cue(self):
        return self.js("const P = window.billiardsPlay; return P.choice.placement || P.state().pos[0];")

    def place(self, st: dict, spot) -> None:
        self.drag(self.px(*self.cue()), self.px(*spot))
        self.done["placement"] += 1
        time.sleep(0.05)
        for _ in range(200):  # the server's legal-placement answer
            if self.js("return window.billiardsPlay.choice.placement !== null;"):
                break
            time.sleep(POLL)

    def aim(self, phi: float) -> None:
        """Drag from the cue ball to the farthest point on the table along ``phi``."""
        st, c = self.state(), self.cue()
        L = st["limits"]
        dx, dy = math.cos(phi), math.sin(phi)
        reach = min(((L["width"] - L["R"] - c[0]) / dx if dx > 1e-12 else (L["R"] - c[0]) / dx if dx < -1e-12 else 9.0),
                    ((L["length"] - L["R"] - c[1]) / dy if dy > 1e-12 else (L["R"] - c[1]) / dy if dy < -1e-12 else 9.0))
        reach = max(reach, 2.5 * L["R"])
        # from the cue ball (with ball in hand, from just beside it: a press on it picks it up)
        start = (c[0] + 2.2 * L["R"] * dx, c[1] + 2.2 * L["R"] * dy) if st["in_hand_code"] else c
        self.drag(self.px(*start), self.px(c[0] + reach * dx, c[1] + reach * dy))
        self.done["aim"] += 1

    def set_tip(self, side: float, height: float) -> None:
        x, y, w, h = self.centre("pl-tip")
        r = self.js("return window.billiardsPlay.tipRadius;") * w / 88  # the diagram's ball radius (panel.html TIP_R)
        self.click_at((round(x + w / 2 + side * r), round(y + h / 2 - height * r)))
        self.done["tip"] += 1

    def set_speed(self, speed: float, lim: dict) -> None:
        x, y, w, h = self.centre("pl-power")
        f = self.js("return window.billiardsPlay.frac(arguments[0]);", speed)  # the bar's place of that speed
        self.click_at((round(x + min(max(f, 0.0), 1.0) * w), round(y + h / 2)))
        self.done["speed"] += 1

    def turn(self) -> dict:
        """Play one turn of the person to move; returns the state the turn started from."""
        st = self.state()
        if st["may_pass"] and self.pass_back:
            self.click("pl-pass")
            self.done["pass"] += 1
            return st
        h = self.hint()
        if st["in_hand_code"]:
            spot = h["placement"] or st["pos"][0]
            if st["break"]:
                spot = (0.42 * st["limits"]["width"], 0.8 * st["limits"]["head_string"])
            self.place(st, spot)
            if st["break"]:
                c = self.js("return window.billiardsPlay.choice.placement;")
                foot = st["limits"]["foot_spot"]
                h["phi"], h["speed"] = math.atan2(foot[1] - c[1], foot[0] - c[0]), st["limits"]["speed_max"] * 0.9
        if st["push_out_allowed"] and self.push_out:
            self.click("pl-push")
            self.done["push_out"] += 1
            h["speed"] = 0.8
        self.aim(h["phi"])
        self.set_tip(*self.tip)
        self.set_speed(h["speed"], st["limits"])
        if st["call_needed"] and h["pocket"] is not None:
            p = st["pockets"][h["pocket"]]
            self.click_at(self.px(p[0], p[1]))
            self.done["pocket"] += 1
        self.click("pl-shoot")
        return st

    def play_game(self, max_turns: int = 200) -> int:
        """Turns until the game is over; the number of turns this person played."""
        n = 0
        while n < max_turns:
            st = self.wait_turn()
            if st["over"]:
                return n
            self.turn()
            n += 1
        return n

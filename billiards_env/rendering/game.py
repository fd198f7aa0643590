"""Images of a two-player game's state and a whole game as an animation.

``render_game(core, k)`` draws table ``k`` of a ``GameCore`` with a status
panel under it: the player to move, ball in hand (and the head string when
it is behind it), the legal targets (ringed), the 8-ball groups, the
consecutive fouls and the last shot's ruling; ``shot_frames`` draws one
recorded shot of it as frames (``billiards_env.studies.game_animation`` plays
a whole game between two bots through it).
"""
from __future__ import annotations

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from ..rules import END_NAMES, FOUL_NAMES
from ..rules import records as R
from .game_words import GROUP_WORDS, IN_HAND_WORDS, ball_ids, call_words
from .draw import BORDER, PPM, Animation, ball_paths, balls_at, render_table, world_to_pixel

PANEL_LINES = 4
LINE_PX = 14             # pixel height of a status line
TARGET_RING = (255, 255, 0)
HEAD_STRING_COLOR = (200, 200, 200)
GROUP_NAMES = GROUP_WORDS
IN_HAND_NAMES = {code: "" if code == R.IN_HAND_NONE else "ball in hand" + ("" if w == "anywhere" else " " + w)
                 for code, w in IN_HAND_WORDS.items()}


def ruling_text(info: dict | None, k: int = 0) -> str:
    """One line saying what the last shot of table ``k`` was ruled (from a step's info)."""
    if info is None:
        return "new game"
    who = f"P{int(info['shooter'][k])}"
    if "replaced" in info and info["replaced"][k]:
        return f"{who} has the balls replaced"
    if info["passed"][k]:
        return f"{who} passes the shot back"
    if info["game_over"][k]:
        return f"{who}: {END_NAMES[int(info['end'][k])]}; P{int(info['winner'][k])} wins"
    if not info["legal"][k]:
        return f"{who}: foul ({FOUL_NAMES[int(info['foul'][k])]})"
    what = "push-out" if info["push_out"][k] else ("legal, keeps the table" if not info["turn_over"][k] else "legal")
    return f"{who}: {what}"


def status_lines(core, k: int, info: dict | None = None) -> list[str]:
    g, c = core.game, core.constraints()
    shooter = int(c.shooter[k])
    first = f"{core.config.game.replace('_', '-')}: " + ("game over" if c.over[k] else f"P{shooter} to move")
    extras = [IN_HAND_NAMES[int(c.ball_in_hand[k])]]
    if c.push_out_allowed[k]:
        extras.append("push-out allowed")
    if c.may_pass[k]:
        extras.append("may pass the shot back")
    if c.call_needed[k]:
        extras.append(call_words(core.config.game))
    groups = (f"groups: P0 {GROUP_NAMES[int(g.group[k, 0])]}, P1 {GROUP_NAMES[int(g.group[k, 1])]}; "
              if core.rules.groups else "")
    if core.rules.to_points:  # games to a score (snooker, three-cushion): the scores
        groups = f"score: P0 {int(g.score[k, 0])}, P1 {int(g.score[k, 1])}; "
    return [first + (" - " + ", ".join(e for e in extras if e) if any(extras) else ""),
            f"{groups}fouls in a row: P0 {int(g.fouls[k, 0])}, P1 {int(g.fouls[k, 1])}; shot {int(g.shots[k])}",
            "last: " + ruling_text(info, k), ""]


def render_game(core, k: int = 0, info: dict | None = None, pos=None, on=None, paths=None,
                ppm: float = PPM, pocket=None, height=None) -> np.ndarray:
    """RGB image of table ``k`` (balls at ``pos``/``on``, default the core's
    state; or ``pocket`` codes as ``render_table`` takes them, and ``height``
    above the slate of balls in flight) with the legal targets ringed, the
    head string drawn when the ball in hand is behind it, and the status
    panel (``info``: the last step's info, for the ruling line)."""
    s, c, t = core.state, core.constraints(), core.table
    if pocket is None:  # the state's own codes draw its off-table balls on the rail
        pocket = s.pocket[k] if on is None else np.where(on, -1, 0)
    pocket = np.asarray(pocket)
    on = pocket < 0
    pos = s.pos[k] if pos is None else pos
    # balls drawn in their owners' colours (three-cushion); during a shot's frames, the shot's shooter's
    shooter = int(info["shooter"][k]) if pos is not None and info is not None else None
    img = render_table(t, core.params, pos, pocket, paths=paths, ppm=ppm, ids=ball_ids(core, k, shooter),
                       height=height)
    H, W, _ = img.shape
    canvas = Image.new("RGB", (W, H + PANEL_LINES * LINE_PX + 4), (20, 20, 20))
    canvas.paste(Image.fromarray(img), (0, 0))
    d = ImageDraw.Draw(canvas)
    rp = core.params.R * ppm + 2
    for b in np.nonzero(c.targets[k] & on)[0]:
        cx, cy = world_to_pixel(t, pos[b], ppm, BORDER)
        d.ellipse([cx - rp, cy - rp, cx + rp, cy + rp], outline=TARGET_RING, width=2)
    if c.ball_in_hand[k] == R.IN_HAND_KITCHEN:
        from ..rules.placement import HEAD_STRING
        a, b = world_to_pixel(t, [(0.0, HEAD_STRING * t.length), (t.width, HEAD_STRING * t.length)], ppm, BORDER)
        d.line([tuple(a), tuple(b)], fill=HEAD_STRING_COLOR, width=1)
    font = ImageFont.load_default()
    for i, line in enumerate(status_lines(core, k, info)):
        d.text((4, H + 2 + i * LINE_PX), line, fill=(235, 235, 235), font=font)
    return np.asarray(canvas, dtype=np.uint8).copy()


def shot_frames(core, start_pos, start_on, log, info, anim: Animation):
    """Frames of one recorded shot: balls the log never mentions stay where they were."""
    fps, speedup, max_seconds, ppm = anim.fps, anim.speedup, anim.max_seconds, anim.ppm
    B = core.n_balls
    t_end = float(log.time[-1]) if len(log) else 0.0
    n = int(min(t_end / speedup, max_seconds) * fps) + 1
    paths = ball_paths(log, core.params, B, effects=core.effects)
    moved = np.array([len(x) > 0 for x in paths])
    frames = []
    for tt in np.minimum(np.arange(n) * speedup / fps, t_end):
        p, pk, h = balls_at(log, core.params, B, tt, core.effects, core.table)
        p = np.where(moved[:, None], p, start_pos)
        pk = np.where(moved, pk, np.where(start_on, -1, 0))
        frames.append(render_game(core, 0, info, p, paths=paths, ppm=ppm, pocket=pk, height=np.where(moved, h, 0.0)))
    return frames


GAME_ANIMATION = Animation(fps=10, speedup=2.0, max_seconds=8.0, hold=5)  # a game: short shots, brisk

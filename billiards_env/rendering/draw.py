"""Draw a pool table as an RGB uint8 image with Pillow (balls numbered and
striped); reconstruct ball paths from a simulator event log with the
simulator's own motion kernel (``replay.evolve_state``); write GIF / MP4
animations of shots and replays.

Image frame: the table's x axis runs left to right, its y axis bottom to
top; a ``border`` (m) of rail surrounds the playing surface; ``ppm`` pixels
per metre. ``world_to_pixel`` gives the pixel (column, row) of a table point.

The third dimension (``Effects(airborne=True)``). A ball in flight, its
lowest point h above the slate, casts a shadow on the slate at its (x, y)
(a disc of radius R in ``SHADOW_COLOR``, under every ball) and is drawn above
it, lifted up the image by h (``HEIGHT_LIFT``: the plan to scale with heights
standing straight up the page, as a military projection draws them) and
larger by the factor 1 + h / ``CAMERA_HEIGHT`` (a camera looking down sees a
ball closer to it larger: a pinhole at height H above the ball's centre
scales it by H / (H - h), whose first order this is; linear, so a ball thrown
a metre up grows in proportion instead of without bound). Balls in flight are
drawn after the balls on the slate, lowest first. A ball that left the table
(``pocket`` >= ``OFF_TABLE``) is drawn where it came down, moved onto the
drawn rail (``off_table_spot``): plain on the rail top (``OFF_RAIL``), ringed
in ``FLOOR_RING_COLOR`` when it fell to the floor (``OFF_FLOOR``), at the
rail's outer edge on the side it went; pocketed balls are not drawn.
"""
from __future__ import annotations

import dataclasses

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from ..physics import constants as C
from ..physics.effects import Effects
from .replay import evolve_state, off_table_of, segment_normals

FELT_COLOR = (35, 100, 155)
RAIL_COLOR = (95, 55, 30)
CUSHION_COLOR = (20, 70, 110)
POCKET_COLOR = (10, 10, 10)
BALL_COLORS = {
    0: (255, 255, 255), 1: (250, 200, 0), 2: (0, 50, 210), 3: (220, 20, 20), 4: (110, 40, 150),
    5: (255, 120, 0), 6: (0, 150, 60), 7: (130, 20, 30), 8: (20, 20, 20),
}
# Balls of other equipment (``Table.style``): carom's white and yellow cue
# balls and the red, drawn without numbers.
# Snooker: the white, 15 reds (balls 1..15), then yellow, green, brown, blue, pink, black (16..21).
SNOOKER_COLORS = ((255, 255, 255),) + ((200, 20, 20),) * 15 + (
    (250, 215, 0), (0, 130, 60), (120, 70, 30), (0, 70, 200), (250, 130, 170), (15, 15, 15))
STYLE_BALL_COLORS = {"carom": {0: (255, 255, 255), 1: (250, 200, 0), 2: (200, 20, 20)},
                     "snooker": dict(enumerate(SNOOKER_COLORS))}
DIAMOND_COLOR = (232, 220, 192)
BORDER = 0.08  # m of rail drawn around the playing surface
# Default pixels per metre: a ball is 17 px across, its number legible.
PPM = 300
# Ball numbers: drawn from this ball radius (px) up (smaller balls have no
# room for them), straight on the ball up to NUMBER_DISC_RADIUS, on a white
# disc of NUMBER_DISC_FRACTION R from there. Digits are a 3 x 5 pixel font
# scaled by whole pixels, so they stay sharp at any size.
NUMBER_MIN_RADIUS = 5.0
NUMBER_DISC_RADIUS = 8.0
NUMBER_DISC_FRACTION = 0.6
STRIPE_ANGLE = 40.5  # degrees: the band of a striped ball spans |dy| < sin(40.5 deg) R = 0.65 R
# Balls in flight (module docstring). A camera this high (m) above a ball
# draws it 11% larger when it jumps one ball height (5.7 cm): 2 px at PPM. A
# camera that frames the whole table (2.2 m up with a 60 degree lens) would
# draw it 2.6% larger, under half a pixel: the size cue would be lost.
CAMERA_HEIGHT = 0.5
HEIGHT_LIFT = 1.0  # m up the image per m of height
SHADOW_COLOR = tuple(int(0.45 * c) for c in FELT_COLOR)  # the felt in the ball's shadow
FLOOR_RING_COLOR = (230, 60, 60)  # around a ball that fell to the floor
_DIGITS = ("111101101101111", "010110010010111", "111001111100111", "111001111001111", "101101111001001",
           "111100111001111", "111100111101111", "111001010010010", "111101111101111", "111101111001111")


MARK_COLOR = (225, 225, 225)


def draw_marks(d, table, ppm: float, border: float) -> None:
    """A snooker table's baulk line, D and colour spots (nothing on other tables)."""
    m = getattr(table, "marks", None)
    if m is None:
        return
    P = lambda xy: [tuple(p) for p in world_to_pixel(table, xy, ppm, border)]
    w = max(1, int(ppm * 0.003))
    d.line(P([(0.0, m.baulk), (table.width, m.baulk)]), fill=MARK_COLOR, width=w)
    (cx, cy), r = m.d_centre, m.d_radius
    a = np.linspace(np.pi, 2 * np.pi, 49)
    d.line(P(np.stack([cx + r * np.cos(a), cy + r * np.sin(a)], axis=1)), fill=MARK_COLOR, width=w)
    sr = max(1.0, 0.004 * ppm)
    for x, y in m.spots:
        c = world_to_pixel(table, (x, y), ppm, border)
        d.ellipse([c[0] - sr, c[1] - sr, c[0] + sr, c[1] + sr], fill=MARK_COLOR)


def ball_color(i: int, style: str = "pool") -> tuple:
    """Colour of ball i: cue white, 1-8 solids, 9-15 stripes of 1-7's
    colours; on a table of another ``style`` its own (STYLE_BALL_COLORS)."""
    if style in STYLE_BALL_COLORS:
        return STYLE_BALL_COLORS[style][i]
    return BALL_COLORS[i] if i <= 8 else BALL_COLORS[(i - 9) % 7 + 1]


def diamonds(table, border: float = BORDER) -> np.ndarray:
    """Centres [N, 2] of the sights on the rails (halfway across the drawn
    rail): eighths of the length on the long rails, quarters of the width on
    the short ones, as the replay viewer draws them."""
    hb = border / 2
    pts = [(x, table.length * k / 8) for k in range(1, 8) if k != 4 for x in (-hb, table.width + hb)]
    pts += [(table.width * k / 4, y) for k in range(1, 4) for y in (-hb, table.length + hb)]
    return np.array(pts)


def image_size(table, ppm: float = PPM, border: float = BORDER) -> tuple[int, int]:
    """(height, width) in pixels."""
    return int(round((table.length + 2 * border) * ppm)), int(round((table.width + 2 * border) * ppm))


def world_to_pixel(table, xy, ppm: float = PPM, border: float = BORDER) -> np.ndarray:
    """Table coordinates [..., 2] (m) -> pixel (column, row) [..., 2] as floats."""
    xy = np.asarray(xy, dtype=np.float64)
    col = (xy[..., 0] + border) * ppm
    row = (table.length - xy[..., 1] + border) * ppm
    return np.stack([col, row], axis=-1)


def _records(log, n_balls: int):
    """Per ball: list of (time, state[8]) after each event involving it."""
    rec = [[] for _ in range(n_balls)]
    for t, kind, ij, st in zip(log.time, log.kind, log.balls, log.states):
        rec[ij[0]].append((t, st[0]))
        if kind == C.EV_BALL_BALL and ij[1] >= 0:
            rec[ij[1]].append((t, st[1]))
    return rec


def _advance(st: np.ndarray, dt, params, effects=None) -> np.ndarray:
    """Positions [K, 2] of a ball in recorded state ``st`` after times ``dt [K]``,
    by the simulator's own motion law (``replay.evolve_state``)."""
    p = params.as_array()
    eff = (effects or Effects()).normalized()
    dt = np.atleast_1d(np.asarray(dt, dtype=np.float64))
    return np.array([evolve_state(st, d, p, eff.vertical_spin, eff.spin)[:2] for d in dt]).reshape(-1, 2)


def ball_paths(log, params, n_balls: int, samples: int = 24, effects=None) -> list[np.ndarray]:
    """Path [K, 2] of every ball over a recorded shot (``simulate(..., record=True)``)."""
    out = []
    for rec in _records(log, n_balls):
        pts = []
        for n, (t, st) in enumerate(rec):
            pts.append(st[None, :2])
            if st[7] in (C.SLIDING, C.ROLLING) and n + 1 < len(rec):
                t1 = rec[n + 1][0]
                pts.append(_advance(st, np.linspace(0.0, t1 - t, samples)[1:-1], params, effects))
        out.append(np.concatenate(pts) if pts else np.zeros((0, 2)))
    return out


def _last_record(rec, t: float):
    """A ball's last (time, state) record at or before ``t`` (None: none yet)."""
    last = None
    for tr, st in rec:
        if tr > t:
            break
        last = (tr, st)
    return last


def positions_at(log, params, n_balls: int, t: float, effects=None):
    """(pos [B, 2], on_table [B]) of every ball at time ``t`` of a recorded shot."""
    pos = np.zeros((n_balls, 2))
    on = np.zeros(n_balls, dtype=bool)
    for i, rec in enumerate(_records(log, n_balls)):
        last = _last_record(rec, t)
        if last is None:
            continue
        tr, st = last
        if st[7] == C.POCKETED:
            continue
        pos[i] = _advance(st, t - tr, params, effects)[0]
        on[i] = True
    return pos, on


def flight_scale(h) -> float:
    """How much larger a ball whose lowest point is ``h`` m above the slate
    is drawn: 1 + h / CAMERA_HEIGHT (module docstring)."""
    return 1.0 + max(float(h), 0.0) / CAMERA_HEIGHT


def off_table_spot(table, xy, R: float, border: float = BORDER) -> tuple[float, float]:
    """Where a ball off the table is drawn (table coordinates): the point
    where it came down (``Replay.table_view``), moved onto the drawn rail:
    out of the cushion box [0, W] x [0, L] widened by R to its nearest
    side, then at least R inside the drawn rail's outer edge (which wins
    where the rail is drawn narrower than 2R)."""
    x, y = float(xy[0]), float(xy[1])
    W, L = table.width, table.length
    if -R < x < W + R and -R < y < L + R:
        k = int(np.argmin([x + R, W + R - x, y + R, L + R - y]))
        x, y = ((-R, y), (W + R, y), (x, -R), (x, L + R))[k]
    return min(max(x, R - border), W + border - R), min(max(y, R - border), L + border - R)


def balls_at(log, params, n_balls: int, t: float, effects=None, table=None):
    """The balls at time ``t`` of a recorded shot as the renderers draw them:
    (pos [B, 2], pocket [B], h [B]), as ``Replay.table_view`` gives them for
    a replay. With ``table`` (the one simulated on) a ball that left the
    table is at ``OFF_RAIL`` / ``OFF_FLOOR`` where it came down; without it,
    or a ball in a pocket, ``pocket`` is the pocket (0 where the log does not
    say) and the ball is not drawn. A ball the log never mentions: pocket 0."""
    eff = (effects or Effects()).normalized()
    p = params.as_array()
    pos, h = np.zeros((n_balls, 2)), np.zeros(n_balls)
    pocket = np.zeros(n_balls, dtype=np.int64)
    for i, rec in enumerate(_records(log, n_balls)):
        last = _last_record(rec, t)
        if last is None:
            continue
        s = evolve_state(last[1], t - last[0], p, eff.vertical_spin, eff.spin)
        pos[i] = s[:2]
        if s[7] != C.POCKETED:
            pocket[i] = -1
            h[i] = s[8] if len(s) > 8 else 0.0
    for n in range(len(log)):
        if log.time[n] <= t and log.kind[n] == C.EV_POCKET:
            pocket[int(log.balls[n, 0])] = int(log.balls[n, 1])
    if table is not None and np.any(np.asarray(log.kind) == C.EV_OFF_TABLE):
        normals = segment_normals(table.geometry(eff.pockets)[0])
        for e in off_table_of(log.time, log.kind, log.balls, log.states, normals, p, eff.vertical_spin, eff.spin):
            if e["t"] <= t:
                pocket[e["ball"]], pos[e["ball"]] = e["code"], (e["x"], e["y"])
    return pos, pocket, h


def render_table(table, params, pos, pocket=None, paths=None, ppm: float = PPM,
                 border: float = BORDER, ids=None, height=None) -> np.ndarray:
    """RGB uint8 image [H, W, 3] (see ``image_size``) of the table with its
    cushions, pockets and the balls at ``pos [B, 2]``: those with
    ``0 <= pocket < OFF_TABLE`` (pocketed) are not drawn, those off the
    table (``pocket >= OFF_TABLE``, ``pos`` where they came down) on the rail
    (``off_table_spot``); ``height`` [B]: the height of each ball's lowest
    point above the slate (m; > 0 in flight: drawn lifted and larger over
    its shadow, module docstring); ``paths`` (list of [K, 2]) are drawn
    under the balls in each ball's colour; ``ids`` [B]: the ball in each
    slot, whose colour it is drawn in (default: slot i is ball i)."""
    H, W = image_size(table, ppm, border)
    img = Image.new("RGB", (W, H), RAIL_COLOR)
    d = ImageDraw.Draw(img)
    P = lambda xy: [tuple(p) for p in world_to_pixel(table, xy, ppm, border)]
    has_pk = table.has_pockets
    d.polygon(P(table.outline(has_pk)), fill=FELT_COLOR)
    R = params.R
    for x, y, r in table.pockets:
        c, rr = world_to_pixel(table, (x, y), ppm, border), (r + R) * ppm
        d.ellipse([c[0] - rr, c[1] - rr, c[0] + rr, c[1] + rr], fill=POCKET_COLOR)
    for x0, y0, x1, y1 in table.segments:
        d.line(P([(x0, y0), (x1, y1)]), fill=CUSHION_COLOR, width=max(1, int(ppm * 0.01)))
    draw_marks(d, table, ppm, border)
    style = getattr(table, "style", "pool")
    if style == "carom":  # the sights carom players aim by, and the three spots
        for c in world_to_pixel(table, diamonds(table, border), ppm, border):
            rd = max(1.0, 0.006 * ppm)
            d.ellipse([c[0] - rd, c[1] - rd, c[0] + rd, c[1] + rd], fill=DIAMOND_COLOR)
        for fy in (0.25, 0.5, 0.75):
            c, rd = world_to_pixel(table, (table.width / 2, fy * table.length), ppm, border), max(1.0, 0.004 * ppm)
            d.ellipse([c[0] - rd, c[1] - rd, c[0] + rd, c[1] + rd], fill=DIAMOND_COLOR)
    numbered = style not in STYLE_BALL_COLORS
    pos = np.asarray(pos, dtype=np.float64)
    pocket = np.full(len(pos), -1) if pocket is None else np.asarray(pocket)
    if paths is not None:
        for i in reversed(range(len(paths))):  # cue-ball path on top
            pth = paths[i]
            if len(pth) > 1:
                d.line(P(pth), fill=ball_color(i if ids is None else ids[i], style), width=max(1, int(ppm * 0.006)))
    rp = R * ppm
    h = np.zeros(len(pos)) if height is None else np.maximum(np.asarray(height, dtype=np.float64), 0.0)
    flying = [i for i in np.argsort(h, kind="stable") if pocket[i] < 0 and h[i] > 0.0]
    for i in flying:  # shadows on the slate, under every ball
        cx, cy = world_to_pixel(table, pos[i], ppm, border)
        d.ellipse([cx - rp, cy - rp, cx + rp, cy + rp], fill=SHADOW_COLOR)
    colour = lambda i: ball_color(i if ids is None else ids[i], style)
    for i in range(len(pos)):
        if pocket[i] >= C.OFF_TABLE:
            cx, cy = world_to_pixel(table, off_table_spot(table, pos[i], R, border), ppm, border)
            if pocket[i] == C.OFF_FLOOR:
                w = max(2, int(round(0.25 * rp)))
                d.ellipse([cx - rp - w, cy - rp - w, cx + rp + w, cy + rp + w], outline=FLOOR_RING_COLOR, width=w)
            _draw_ball(d, i, cx, cy, rp, colour(i), numbered)
        elif pocket[i] < 0 and h[i] <= 0.0:
            cx, cy = world_to_pixel(table, pos[i], ppm, border)
            _draw_ball(d, i, cx, cy, rp, colour(i), numbered)
    for i in flying:  # lowest first, lifted by their height
        cx, cy = world_to_pixel(table, pos[i], ppm, border)
        _draw_ball(d, i, cx, cy - HEIGHT_LIFT * h[i] * ppm, rp * flight_scale(h[i]), colour(i), numbered)
    return np.asarray(img, dtype=np.uint8).copy()


def _draw_ball(d, i: int, cx: float, cy: float, rp: float, col: tuple, numbered: bool) -> None:
    """Ball ``i`` centred at pixel (cx, cy), radius ``rp`` px."""
    box = [cx - rp, cy - rp, cx + rp, cy + rp]
    d.ellipse(box, fill=col, outline=(0, 0, 0))
    if i >= 9 and numbered:  # stripe: white caps above and below a coloured band of 1.3 R
        d.chord(box, 180 + STRIPE_ANGLE, 360 - STRIPE_ANGLE, fill=(255, 255, 255))
        d.chord(box, STRIPE_ANGLE, 180 - STRIPE_ANGLE, fill=(255, 255, 255))
    if i > 0 and numbered and rp >= NUMBER_MIN_RADIUS:
        _draw_number(d, i, cx, cy, rp, col)


def _draw_number(d, i: int, cx: float, cy: float, rp: float, col: tuple) -> None:
    """Ball number ``i`` centred at pixel (cx, cy) of a ball of radius ``rp`` px."""
    s = max(1, int(rp / 5.5))  # font pixel size: "15" fits the disc
    text = str(i)
    w, h = (4 * len(text) - 1) * s, 5 * s
    if rp >= NUMBER_DISC_RADIUS:
        dr = NUMBER_DISC_FRACTION * rp
        d.ellipse([cx - dr, cy - dr, cx + dr, cy + dr], fill=(255, 255, 255))
        ink = (0, 0, 0)
    else:  # no room for a disc: dark digits on light balls, light on dark
        ink = (0, 0, 0) if i >= 9 or sum(col) > 380 else (255, 255, 255)
    x0, y0 = int(round(cx - w / 2)), int(round(cy - h / 2))
    for k, ch in enumerate(text):
        bits = _DIGITS[int(ch)]
        for n, bit in enumerate(bits):
            if bit == "1":
                x = x0 + (4 * k + n % 3) * s
                y = y0 + (n // 3) * s
                d.rectangle([x, y, x + s - 1, y + s - 1], fill=ink)


def write_animation(path, frames, fps: int) -> Path:
    """Write frames [N, H, W, 3] as an animated GIF (``.gif``) or an MP4
    (``.mp4``, needs the imageio-ffmpeg package). Returns the path."""
    import importlib.util

    import imageio.v3 as iio

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".gif":
        iio.imwrite(path, frames, duration=1000.0 / fps, loop=0)
    elif suffix == ".mp4":
        if importlib.util.find_spec("imageio_ffmpeg") is None and importlib.util.find_spec("av") is None:
            raise RuntimeError("writing MP4 needs imageio-ffmpeg (pip install imageio-ffmpeg) or PyAV; "
                               "or save the animation as .gif")
        iio.imwrite(path, frames, fps=fps)
    else:
        raise ValueError(f"animation path must end in .gif or .mp4, got {path.name!r}")
    return path


def _check_suffix(path) -> Path:
    path = Path(path)
    if path.suffix.lower() not in (".gif", ".mp4"):
        raise ValueError(f"animation path must end in .gif or .mp4, got {path.name!r}")
    return path


@dataclasses.dataclass(frozen=True)
class Animation:
    """How an animation is drawn: ``fps`` frames per second of video,
    ``ppm`` pixels per metre, ``speedup`` (> 1 plays faster than real
    time), at most ``max_seconds`` of video per shot, ``paths`` (draw each
    ball's path), ``hold`` (frames of the resting table after a shot, where
    an animation holds)."""

    fps: int = 30
    ppm: float = PPM
    speedup: float = 1.0
    max_seconds: float = 30.0
    paths: bool = True
    hold: int = 5


def save_shot_animation(path, table, params, log, n_balls: int, anim: Animation = Animation(), effects=None) -> Path:
    """Write a recorded shot (an ``EventLog`` from ``simulate(..., record=True)``)
    as an animated GIF (``.gif``) or MP4 (``.mp4``, needs imageio-ffmpeg),
    drawn as ``anim`` says. Returns the path."""
    fps, ppm, speedup, max_seconds, paths = anim.fps, anim.ppm, anim.speedup, anim.max_seconds, anim.paths
    path = _check_suffix(path)
    t_end = float(log.time[-1]) if len(log) else 0.0
    n_frames = int(min(t_end / speedup, max_seconds) * fps) + 2
    times = np.minimum(np.arange(n_frames) * speedup / fps, t_end)
    full = ball_paths(log, params, n_balls, effects=effects) if paths else None
    frames = []
    for t in times:
        pos, pocket, h = balls_at(log, params, n_balls, t, effects, table)
        frames.append(render_table(table, params, pos, pocket, paths=full, ppm=ppm, height=h))
    return write_animation(path, np.stack(frames), fps)


def save_replay_animation(path, replay, shots=None, fps: int = 30, ppm: float = PPM, speedup: float = 1.0,
                          max_seconds: float = 60.0, paths: bool = True, hold: float = 0.5) -> Path:
    """Write the shots (default: all) of a ``Replay`` one after another as a
    GIF or MP4, holding each shot's last frame ``hold`` seconds of video.
    The balls come from ``Replay.table_view``. Returns the path."""
    from ..physics.simulate import EventLog

    path = _check_suffix(path)
    table, params = replay.table_object(), replay.params
    frames = []
    for k in range(len(replay)) if shots is None else shots:
        t_end = replay.duration(k)
        n = int(min(t_end / speedup, max_seconds) * fps) + 2
        times = np.concatenate([np.minimum(np.arange(n) * speedup / fps, t_end), np.full(int(hold * fps), t_end)])
        full = ball_paths(EventLog(*replay.event_states(k)), params, replay.n_balls, effects=replay.effects) \
            if paths else None
        for t in times:
            pos, pocket, h = replay.table_view(t, k)
            frames.append(render_table(table, params, pos, pocket, paths=full, ppm=ppm, height=h))
    if not frames:
        raise ValueError("the replay has no shots to animate")
    return write_animation(path, np.stack(frames), fps)

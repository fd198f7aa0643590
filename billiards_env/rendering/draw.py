"""Draw a pool table as an RGB uint8 image with Pillow; reconstruct ball
paths from a simulator event log with the closed-form felt motion.

Image frame: the table's x axis runs left to right, its y axis bottom to
top; a ``border`` (m) of rail surrounds the playing surface; ``ppm`` pixels
per metre. ``world_to_pixel`` gives the pixel (column, row) of a table point.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw

from ..physics import constants as C

FELT_COLOR = (35, 100, 155)
RAIL_COLOR = (95, 55, 30)
CUSHION_COLOR = (20, 70, 110)
POCKET_COLOR = (10, 10, 10)
BALL_COLORS = {
    0: (255, 255, 255), 1: (250, 200, 0), 2: (0, 50, 210), 3: (220, 20, 20), 4: (110, 40, 150),
    5: (255, 120, 0), 6: (0, 150, 60), 7: (130, 20, 30), 8: (20, 20, 20),
}
BORDER = 0.08  # m of rail drawn around the playing surface


def ball_color(i: int) -> tuple:
    """Colour of ball i: cue white, 1-8 solids, 9-15 stripes of 1-7's colours."""
    return BALL_COLORS[i] if i <= 8 else BALL_COLORS[(i - 9) % 7 + 1]


def image_size(table, ppm: float = 200, border: float = BORDER) -> tuple[int, int]:
    """(height, width) in pixels."""
    return int(round((table.length + 2 * border) * ppm)), int(round((table.width + 2 * border) * ppm))


def world_to_pixel(table, xy, ppm: float = 200, border: float = BORDER) -> np.ndarray:
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


def _advance(st: np.ndarray, dt, params) -> np.ndarray:
    """Positions [K, 2] of a ball in recorded state ``st`` after times ``dt [K]``
    (closed-form constant-acceleration motion of its current motion state)."""
    x, y, vx, vy, wx, wy, _, ms = st
    ax = ay = 0.0
    if ms == C.SLIDING:
        ux, uy = vx - params.R * wy, vy + params.R * wx
        n = np.hypot(ux, uy)
        if n > 0:
            ax, ay = -params.mu_s * params.g * ux / n, -params.mu_s * params.g * uy / n
    elif ms == C.ROLLING:
        n = np.hypot(vx, vy)
        if n > 0:
            ax, ay = -params.mu_r * params.g * vx / n, -params.mu_r * params.g * vy / n
    else:
        vx = vy = 0.0
    dt = np.asarray(dt, dtype=np.float64)
    return np.stack([x + vx * dt + 0.5 * ax * dt ** 2, y + vy * dt + 0.5 * ay * dt ** 2], axis=-1)


def ball_paths(log, params, n_balls: int, samples: int = 24) -> list[np.ndarray]:
    """Path [K, 2] of every ball over a recorded shot (``simulate(..., record=True)``)."""
    out = []
    for rec in _records(log, n_balls):
        pts = []
        for n, (t, st) in enumerate(rec):
            pts.append(st[None, :2])
            if st[7] in (C.SLIDING, C.ROLLING) and n + 1 < len(rec):
                t1 = rec[n + 1][0]
                pts.append(_advance(st, np.linspace(0.0, t1 - t, samples)[1:-1], params))
        out.append(np.concatenate(pts) if pts else np.zeros((0, 2)))
    return out


def positions_at(log, params, n_balls: int, t: float):
    """(pos [B, 2], on_table [B]) of every ball at time ``t`` of a recorded shot."""
    pos = np.zeros((n_balls, 2))
    on = np.zeros(n_balls, dtype=bool)
    for i, rec in enumerate(_records(log, n_balls)):
        last = None
        for tr, st in rec:
            if tr <= t:
                last = (tr, st)
            else:
                break
        if last is None:
            continue
        tr, st = last
        if st[7] == C.POCKETED:
            continue
        pos[i] = _advance(st, t - tr, params)
        on[i] = True
    return pos, on


def render_table(table, params, pos, pocket=None, paths=None, ppm: float = 200,
                 border: float = BORDER) -> np.ndarray:
    """RGB uint8 image [H, W, 3] (see ``image_size``) of the table with its
    cushions, pockets and the balls at ``pos [B, 2]`` (those with
    ``pocket >= 0`` are not drawn); ``paths`` (list of [K, 2]) are drawn
    under the balls in each ball's colour."""
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
    pos = np.asarray(pos, dtype=np.float64)
    pocket = np.full(len(pos), -1) if pocket is None else np.asarray(pocket)
    if paths is not None:
        for i in reversed(range(len(paths))):  # cue-ball path on top
            pth = paths[i]
            if len(pth) > 1:
                d.line(P(pth), fill=ball_color(i), width=max(1, int(ppm * 0.006)))
    rp = R * ppm
    for i in range(len(pos)):
        if pocket[i] >= 0:
            continue
        cx, cy = world_to_pixel(table, pos[i], ppm, border)
        box = [cx - rp, cy - rp, cx + rp, cy + rp]
        col = ball_color(i)
        d.ellipse(box, fill=col, outline=(0, 0, 0))
        if i >= 9:  # stripe: white caps above and below a coloured band
            d.chord(box, 210, 330, fill=(255, 255, 255))
            d.chord(box, 30, 150, fill=(255, 255, 255))
    return np.asarray(img, dtype=np.uint8).copy()


def save_shot_animation(path, table, params, log, n_balls: int, fps: int = 30, ppm: float = 150,
                        speedup: float = 1.0, max_seconds: float = 30.0, paths: bool = True) -> Path:
    """Write a recorded shot (an ``EventLog`` from ``simulate(..., record=True)``)
    as an animated GIF (``.gif``) or MP4 (``.mp4``, needs imageio-ffmpeg or
    PyAV). Frames are ``fps`` per second of video; ``speedup`` > 1 plays faster.
    Returns the path."""
    import imageio.v3 as iio

    path = Path(path)
    t_end = float(log.time[-1]) if len(log) else 0.0
    n_frames = int(min(t_end / speedup, max_seconds) * fps) + 2
    times = np.minimum(np.arange(n_frames) * speedup / fps, t_end)
    full = ball_paths(log, params, n_balls) if paths else None
    frames = []
    for t in times:
        pos, on = positions_at(log, params, n_balls, t)
        frames.append(render_table(table, params, pos, np.where(on, -1, 0), paths=full, ppm=ppm))
    frames = np.stack(frames)
    suffix = path.suffix.lower()
    if suffix == ".gif":
        iio.imwrite(path, frames, duration=1000.0 / fps, loop=0)
    elif suffix == ".mp4":
        try:
            iio.imwrite(path, frames, fps=fps)
        except Exception as exc:  # no video backend installed
            raise RuntimeError(f"writing MP4 needs imageio-ffmpeg or PyAV ({exc}); save as .gif instead") from exc
    else:
        raise ValueError(f"animation path must end in .gif or .mp4, got {path.name!r}")
    return path

"""Table geometry: cushion segments, jaw tips and pocket capture circles.

Frame: origin at a corner of the playing surface, x across the width, y
along the length, z up. Cushion segments are the lines the ball's *centre*
must stay R away from (the cushion noses). Pool tables have six pockets; each
corner pocket mouth is cut at 45 degrees with jaws at 142 degrees to the rail,
each side pocket with jaws at 104 degrees (WPA equipment specifications). A
ball whose centre enters a pocket's capture circle is pocketed.

The 12 ft snooker table (``Table.snooker``) is built the same way from its
own ``PocketSpec``: playing area 3569 x 1778 mm between the cushion noses
(WPBSA Official Rules, Section 1 Equipment), the pocket mouths and jaws of
pooltool's snooker table (``pooltool/objects/table/collection.py``,
``SNOOKER_GENERIC``: corner mouth 83 mm, middle 75 mm, pocket angle 0,
i.e. jaws running straight into the pocket, jaw depths 36 mm and 24 mm),
and its markings (``SnookerMarks``: baulk line, D, the six colour spots,
WPBSA Section 1). pooltool rounds the snooker jaws (radii 91 and 64 mm);
here they stay straight segments with a sharp tip (docs/rules.md says so).
The carom match table (``Table.carom()``) has no pockets: its playing
surface between the cushion noses is 2.84 x 1.42 m (UMB, "Rules of the
Game of Three-Cushion", the equipment article: 2.84 m x 1.42 m, +-5 mm; a
cushion nose 37 mm +-1 mm above the bed, which ``PhysicsParams.carom()``
holds as ``h_c``). pooltool's ``BilliardTableSpecs`` is a pocketless box of
the same kind (its default is a 10 ft table, not the match size).

``Table.style`` names the equipment the renderers draw ("pool", "carom", "snooker"):
the balls' colours and the table's markings; the physics never reads it.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

# WPA: playing surface of a 9 ft table 100 x 50 in; 8 ft 88 x 44; 7 ft 78 x 39.
_POOL_SIZES = {9: (1.27, 2.54), 8: (1.1176, 2.2352), 7: (0.9906, 1.9812)}
CORNER_MOUTH = 0.116     # m, corner pocket mouth (4.5-4.625 in, WPA)
SIDE_MOUTH = 0.132       # m, side pocket mouth (5-5.125 in, WPA)
CORNER_JAW_ANGLE = 142.0  # degrees between rail nose and jaw face
SIDE_JAW_ANGLE = 104.0
CORNER_JAW_LENGTH = 0.05  # m
SIDE_JAW_LENGTH = 0.04
CAPTURE_DEPTH = 0.004  # m a ball centre must pass the mouth line to drop
# 12 ft snooker (WPBSA Section 1: 11 ft 8.5 in x 5 ft 10 in between the cushion noses).
SNOOKER_SIZE = (1.778, 3.569)
SNOOKER_BAULK = 0.737     # m, the baulk line from the bottom cushion's face (29 in, WPBSA)
SNOOKER_D_RADIUS = 0.292  # m, the D's radius about the baulk line's middle (11.5 in, WPBSA)
SNOOKER_BLACK = 0.324     # m, the black spot from the top cushion's face (12.75 in, WPBSA)
# A jaw segment or tip belongs to a pocket's neighbourhood if it lies within
# this of the pocket's centre (m): a pool pocket's jaws reach ~0.11 m from
# it, and every rail between two pockets is longer than twice this, so rails
# stay outside every neighbourhood.
POCKET_GROUP_RADIUS = 0.2
# UMB match carom table: playing surface between the cushion noses (m).
CAROM_SIZE = (1.42, 2.84)


@dataclasses.dataclass(frozen=True)
class PocketSpec:
    """A six-pocket table's mouths and jaws: mouth widths (m, between the jaw
    tips), each jaw's angle to the rail nose (degrees; 180 would continue the
    rail) and length (m), and the middle pocket's capture circle (its centre
    outside the rail line and its radius, m)."""

    corner_mouth: float = CORNER_MOUTH
    side_mouth: float = SIDE_MOUTH
    corner_jaw_angle: float = CORNER_JAW_ANGLE
    side_jaw_angle: float = SIDE_JAW_ANGLE
    corner_jaw_length: float = CORNER_JAW_LENGTH
    side_jaw_length: float = SIDE_JAW_LENGTH
    side_capture_centre: float = 0.06
    side_capture_radius: float = 0.06 - CAPTURE_DEPTH


POOL_POCKETS = PocketSpec()
# pooltool SNOOKER_GENERIC: corner_pocket_width 0.083, side_pocket_width 0.075, pocket angles 0 (a corner jaw
# then meets the rail at 135 degrees, a middle jaw at 90), corner_pocket_depth 0.036, side 0.95 in. The middle
# capture circle keeps pool's proportions to the mouth (centre 0.06 / 0.066 and radius 0.056 / 0.066 of the
# half mouth), so it spans the throat a few mm past the rail line as on the pool table.
SNOOKER_POCKETS = PocketSpec(corner_mouth=0.083, side_mouth=0.075, corner_jaw_angle=135.0, side_jaw_angle=90.0,
                             corner_jaw_length=0.036, side_jaw_length=0.95 * 0.0254,
                             side_capture_centre=0.0375 * 0.06 / 0.066, side_capture_radius=0.0375 * 0.056 / 0.066)


@dataclasses.dataclass(frozen=True)
class SnookerMarks:
    """A snooker table's markings (m, table frame: y = 0 the baulk cushion):
    ``baulk`` the baulk line's y, ``d_centre`` (x, y) and ``d_radius`` of the
    D (the half circle on the baulk side of the line), ``spots [6, 2]`` the
    colour spots yellow, green, brown, blue, pink, black (values 2..7).
    Yellow is at the D's right end seen from the baulk end, green at its left."""

    baulk: float
    d_centre: tuple
    d_radius: float
    spots: np.ndarray

    @classmethod
    def wpbsa(cls, width: float, length: float) -> "SnookerMarks":
        cx = width / 2
        spots = np.array([(cx + SNOOKER_D_RADIUS, SNOOKER_BAULK), (cx - SNOOKER_D_RADIUS, SNOOKER_BAULK),
                          (cx, SNOOKER_BAULK), (cx, length / 2), (cx, 0.75 * length), (cx, length - SNOOKER_BLACK)])
        return cls(SNOOKER_BAULK, (cx, SNOOKER_BAULK), SNOOKER_D_RADIUS, spots)

    def in_d(self, x, y, tol: float = 0.0):
        """Whether points lie in the D (on its line or arc counts, ``tol`` m inside)."""
        cx, cy = self.d_centre
        return (np.asarray(y) <= cy - tol) & (np.hypot(np.asarray(x) - cx, np.asarray(y) - cy) <= self.d_radius - tol)


@dataclasses.dataclass(frozen=True)
class PocketGroups:
    """The boundary elements split for the event solver's broad phase.

    ``rails [N]`` segments tested for every moving ball; ``free_tips [M]``
    tips near no pocket (also always tested); per pocket k, ``near [K, 4]``
    the box (x_lo, x_hi, y_lo, y_hi) holding its capture circle and the jaw
    segments ``gsegs [K, G]`` and tips ``gtips [K, G]`` of its neighbourhood
    (index lists padded with -1): they are tested only for a path whose box
    reaches that neighbourhood.
    """

    rails: np.ndarray
    free_tips: np.ndarray
    near: np.ndarray
    gsegs: np.ndarray
    gtips: np.ndarray


def pocket_groups(segs: np.ndarray, tips: np.ndarray, pockets: np.ndarray) -> PocketGroups:
    """Assign every jaw segment (both ends within POCKET_GROUP_RADIUS of one
    pocket centre) and tip to its nearest pocket; the rest are always tested."""
    K = len(pockets)
    seg_group = np.full(len(segs), -1)
    tip_group = np.full(len(tips), -1)
    for s, (x0, y0, x1, y1) in enumerate(segs):
        for k, (cx, cy, _) in enumerate(pockets):
            if max(math.hypot(x0 - cx, y0 - cy), math.hypot(x1 - cx, y1 - cy)) < POCKET_GROUP_RADIUS:
                seg_group[s] = k
    for v, (x, y) in enumerate(tips):
        d = [math.hypot(x - cx, y - cy) for cx, cy, _ in pockets]
        if K and min(d) < POCKET_GROUP_RADIUS:
            tip_group[v] = int(np.argmin(d))
    G = max([1] + [int(np.sum(seg_group == k)) for k in range(K)] + [int(np.sum(tip_group == k)) for k in range(K)])
    near = np.zeros((K, 4))
    gsegs = np.full((K, G), -1, dtype=np.int64)
    gtips = np.full((K, G), -1, dtype=np.int64)
    for k, (cx, cy, r) in enumerate(pockets):
        xs = [cx - r, cx + r] + list(segs[seg_group == k][:, [0, 2]].ravel()) + list(tips[tip_group == k][:, 0])
        ys = [cy - r, cy + r] + list(segs[seg_group == k][:, [1, 3]].ravel()) + list(tips[tip_group == k][:, 1])
        near[k] = (min(xs), max(xs), min(ys), max(ys))
        members = np.flatnonzero(seg_group == k)
        gsegs[k, :len(members)] = members
        members = np.flatnonzero(tip_group == k)
        gtips[k, :len(members)] = members
    return PocketGroups(np.flatnonzero(seg_group < 0).astype(np.int64), np.flatnonzero(tip_group < 0).astype(np.int64),
                        near, gsegs, gtips)


@dataclasses.dataclass(frozen=True, eq=False)
class Table:
    """Playing surface of ``width`` x ``length`` with its cushions and pockets.

    ``segments [S, 4]`` cushion noses (x0, y0, x1, y1), each with its unit
    normal ``normals [S, 2]`` pointing into the table; ``tips [V, 2]`` jaw tips
    (vertices a ball can strike); ``pockets [P, 3]`` capture circles (x, y, r).
    ``box_segments`` is the closed box used when pockets are switched off.
    ``style`` the equipment the renderers draw (module docstring).
    """

    width: float
    length: float
    segments: np.ndarray
    normals: np.ndarray
    tips: np.ndarray
    pockets: np.ndarray
    name: str = "custom"
    style: str = "pool"
    marks: "SnookerMarks | None" = None  # a snooker table's baulk line, D and spots (None on other tables)

    @property
    def box_segments(self) -> np.ndarray:
        w, l = self.width, self.length
        return np.array([[0, 0, w, 0], [w, 0, w, l], [w, l, 0, l], [0, l, 0, 0]], dtype=np.float64)

    @property
    def box_normals(self) -> np.ndarray:
        return np.array([[0, 1], [-1, 0], [0, -1], [1, 0]], dtype=np.float64)

    @property
    def has_pockets(self) -> bool:
        return len(self.pockets) > 0

    def geometry(self, pockets: bool):
        """Arrays the kernels read: (segments, normals, tips, pockets)."""
        if pockets and self.has_pockets:
            return self.segments, self.normals, self.tips, self.pockets
        return self.box_segments, self.box_normals, np.zeros((0, 2)), np.zeros((0, 3))

    def groups(self, pockets: bool) -> PocketGroups:
        """``pocket_groups`` of ``geometry(pockets)``, computed once per table."""
        cache = self.__dict__.setdefault("_groups", {})
        if pockets not in cache:
            segs, _, tips, pk = self.geometry(pockets)
            cache[pockets] = pocket_groups(np.asarray(segs, dtype=np.float64), np.asarray(tips, dtype=np.float64),
                                           np.asarray(pk, dtype=np.float64))
        return cache[pockets]

    @classmethod
    def pocketless(cls, width: float = 1.27, length: float = 2.54) -> "Table":
        """A closed rectangular box (carom-style scenes and tests)."""
        if not (math.isfinite(width) and math.isfinite(length) and width > 0 and length > 0):
            raise ValueError(f"table size must be finite and positive, got {width} x {length}")
        t = cls(width, length, np.zeros((0, 4)), np.zeros((0, 2)), np.zeros((0, 2)), np.zeros((0, 3)),
                name=f"pocketless {width:g}x{length:g}")
        object.__setattr__(t, "segments", t.box_segments)
        object.__setattr__(t, "normals", t.box_normals)
        return t

    @classmethod
    def carom(cls) -> "Table":
        """The UMB match carom table: 2.84 x 1.42 m between the cushion
        noses, no pockets (module docstring). Use it with
        ``PhysicsParams.carom()`` (carom balls, cloth and cushion height)."""
        t = cls.pocketless(*CAROM_SIZE)
        object.__setattr__(t, "name", "carom match")
        object.__setattr__(t, "style", "carom")
        return t

    @classmethod
    def pool(cls, size_ft: int = 9) -> "Table":
        """A pool table of 7, 8 or 9 ft with six pockets."""
        if size_ft not in _POOL_SIZES:
            raise ValueError(f"size_ft must be one of {sorted(_POOL_SIZES)}, got {size_ft!r}")
        w, l = _POOL_SIZES[size_ft]
        return cls._six_pockets(w, l, POOL_POCKETS, f"pool {size_ft} ft")

    @classmethod
    def snooker(cls) -> "Table":
        """The 12 ft snooker table (see the module docstring), with its ``marks``."""
        w, l = SNOOKER_SIZE
        t = cls._six_pockets(w, l, SNOOKER_POCKETS, "snooker 12 ft")
        object.__setattr__(t, "marks", SnookerMarks.wpbsa(w, l))
        object.__setattr__(t, "style", "snooker")
        return t

    @classmethod
    def _six_pockets(cls, w: float, l: float, spec: PocketSpec, name: str) -> "Table":
        sc = spec.corner_mouth / math.sqrt(2.0)  # rail end distance from the corner
        ss = spec.side_mouth / 2.0
        # Rails as (start, end) along the nose, walked counter-clockwise, each
        # ending at a pocket mouth: (corner|side, point, direction along rail).
        rails = [
            ((sc, 0.0), (w - sc, 0.0)),            # bottom
            ((w, sc), (w, l / 2 - ss)),             # right, lower half
            ((w, l / 2 + ss), (w, l - sc)),         # right, upper half
            ((w - sc, l), (sc, l)),                 # top
            ((0.0, l - sc), (0.0, l / 2 + ss)),     # left, upper half
            ((0.0, l / 2 - ss), (0.0, sc)),         # left, lower half
        ]
        segs, norms, tips = [], [], []
        for (x0, y0), (x1, y1) in rails:
            d = np.array([x1 - x0, y1 - y0]); d /= np.linalg.norm(d)
            n = np.array([-d[1], d[0]])  # left of a counter-clockwise walk = into the table
            segs.append((x0, y0, x1, y1)); norms.append(n)
            for (px, py), away in (((x0, y0), d), ((x1, y1), -d)):
                # the jaw leaves the rail end, turning outward (-n) by the jaw angle
                at_side = (abs(px) < 1e-12 or abs(px - w) < 1e-12) and abs(py - l / 2) < l / 4
                ang = math.radians(spec.side_jaw_angle if at_side else spec.corner_jaw_angle)
                length = spec.side_jaw_length if at_side else spec.corner_jaw_length
                # unit vector at angle `ang` from `away`, on the outside of the rail
                jd = math.cos(ang) * away + math.sin(ang) * (-n)
                qx, qy = px + length * jd[0], py + length * jd[1]
                # jaw face as a segment whose table-side normal faces the pocket's throat
                jn = np.array([-jd[1], jd[0]])
                if np.dot(jn, away) > 0:
                    jn = -jn
                segs.append((px, py, qx, qy)); norms.append(jn)
                tips.append((px, py))
        # Capture circles: a ball drops once its centre is a few mm past the
        # mouth line (corner) or the rail line (side); each circle also spans
        # the whole throat between the jaws, so no ball can pass behind them.
        rc = sc / math.sqrt(2.0) - CAPTURE_DEPTH
        side_c, side_r = spec.side_capture_centre, spec.side_capture_radius
        pockets = [(0.0, 0.0, rc), (w, 0.0, rc), (-side_c, l / 2, side_r),
                   (w + side_c, l / 2, side_r), (0.0, l, rc), (w, l, rc)]
        return cls(w, l, np.array(segs, dtype=np.float64), np.array(norms, dtype=np.float64),
                   np.array(tips, dtype=np.float64), np.array(pockets, dtype=np.float64), name=name)

    def outline(self, pockets: bool = True) -> np.ndarray:
        """Polygon [N, 2] of the region ball centres may occupy, before the
        R clearance: rails, with each pocket's jaws leading into its throat."""
        segs, _, _, pk = self.geometry(pockets)
        if len(pk) == 0:
            return segs[:, :2].copy()
        pts = []
        # layout from pool(): rail, jaw at its start, jaw at its end
        for r in range(0, len(segs), 3):
            rail, jaw0, jaw1 = segs[r], segs[r + 1], segs[r + 2]
            pts += [jaw0[2:], rail[:2], rail[2:], jaw1[2:]]
        return np.array(pts)

    def contains(self, pos: np.ndarray, R: float, tol: float, pockets: bool = True) -> np.ndarray:
        """True where a ball centre at ``pos [N, 2]`` lies legally on the table:
        inside the outline, at least R - tol from every cushion nose and jaw
        tip, and outside every pocket's capture circle."""
        pos = np.asarray(pos, dtype=np.float64).reshape(-1, 2)
        x, y = pos[:, 0], pos[:, 1]
        # Fast path: every cushion nose and jaw lies on or outside the playing
        # rectangle, so a centre at least R inside it is clear of all of them;
        # only the pocket capture circles remain to check.
        inner = (x >= R) & (x <= self.width - R) & (y >= R) & (y <= self.length - R)
        if inner.all():
            ok = np.ones(len(pos), dtype=bool)
            for cx, cy, r in self.geometry(pockets)[3]:
                ok &= (x - cx) ** 2 + (y - cy) ** 2 > r * r
            return ok
        poly = self.outline(pockets)
        inside = np.zeros(len(pos), dtype=bool)
        for k in range(len(poly)):  # even-odd ray casting
            (x0, y0), (x1, y1) = poly[k - 1], poly[k]
            crosses = (y0 > y) != (y1 > y)
            with np.errstate(divide="ignore", invalid="ignore"):
                xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
            inside ^= crosses & (x < xc)
        segs, _, tips, pk = self.geometry(pockets)
        for x0, y0, x1, y1 in segs:
            d = np.array([x1 - x0, y1 - y0]); L2 = d @ d
            lam = np.clip(((pos - [x0, y0]) @ d) / L2, 0.0, 1.0)
            near = np.array([x0, y0]) + lam[:, None] * d
            inside &= np.linalg.norm(pos - near, axis=1) >= R - tol
        for cx, cy, r in pk:
            inside &= np.hypot(x - cx, y - cy) > r
        return inside

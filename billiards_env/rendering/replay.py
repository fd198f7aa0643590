"""Exact replays of simulated shots and episodes, as compact JSON.

A replay holds the table geometry, the physics parameters, the effect flags
and a list of shots. Each shot holds every ball's state at its start and,
for every event of the event solver, the new state of each ball the event
changed. Between two records of a ball its motion is the felt's closed form
(``billiards_env.physics.motion``): a position quadratic in time, so any
instant is evaluated exactly from the ball's last record, by the simulator's
own motion kernel (``evolve_state``, the one call into it).

A ball record is packed by its motion state, dropping what the state
defines (velocity 0 at rest; spin locked to the velocity when rolling, or 0
for point masses; no spin at rest or in a pocket):

=================  ===========================================
STATIONARY (0)     ``[0, x, y]``
SPINNING (1)       ``[1, x, y, wz]``
SLIDING (2)        ``[2, x, y, vx, vy, wx, wy, wz]``
ROLLING (3)        ``[3, x, y, vx, vy, wz]``
POCKETED (4)       ``[4, x, y]`` (where the ball dropped, or left the table)
AIRBORNE (5)       ``[5, x, y, vx, vy, wx, wy, wz, h, vz]`` (in flight)
=================  ===========================================

A ball in flight (``Effects(airborne=True)``) follows its parabola between
records (``airborne.fly``), with h the height of its lowest point above the
slate and vz its vertical velocity; every other record has h = vz = 0.

A ball that leaves the table (an ``EV_OFF_TABLE`` event: it passed over a
cushion, a jaw tip or a pocket) is recorded POCKETED where it crossed, as a
pocketed ball is where it dropped; the event log does not say where it came
down, so ``off_table_landing`` works it out from the ball's flight by the
rail model's rule (``physics.cushion.rail.landing_code``): on the rail top
(``OFF_RAIL``) if it descends to the cushion nose's height within
``RAIL_WIDTH`` beyond the cushion, else on the floor (``OFF_FLOOR``). The
shot's ``info["off_table"]`` lists these balls (ball, code, the time it
left, where it came down), and carries them into the next shot while they
stay off the table, for the renderers (``draw.render_table`` and the
viewer draw them on the rail, distinct from pocketed balls).

Numbers are written with the shortest decimal that reads back as the same
float64, so unpacking gives the event log's states bit for bit. The format,
field by field, is documented in docs/replay.md.

Event logs of the step solver load too, but its motion between events is
straight lines with per-step friction, so ``positions_at`` only approximates
such a shot between its records.
"""
from __future__ import annotations

import bisect
import dataclasses
import json
import math
from pathlib import Path

import numpy as np

from ..physics import constants as C
from ..physics.airborne import drop_time, rise
from ..physics.cushion.rail import RAIL_WIDTH
from ..physics.effects import Effects
from ..physics.motion import evolve, transition_time
from ..physics.params import PhysicsParams
from ..physics.table import Table

FORMAT = "billiards-replay"
VERSION = 1
_RECORD_LEN = {C.STATIONARY: 3, C.SPINNING: 4, C.SLIDING: 8, C.ROLLING: 6, C.POCKETED: 3, C.AIRBORNE: 10}
COLUMNS = 10  # a ball's state: x, y, vx, vy, wx, wy, wz, motion state, h, vz (simulate.EventLog.states)
_INFO_KEYS = ("first_contact", "foul", "scratch", "success", "reward", "shooter", "ball_in_hand", "legal_target",
              "action")


def evolve_state(state, dt: float, p: np.ndarray, zspin_on: bool, spin_on: bool) -> np.ndarray:
    """State [10] (x, y, vx, vy, wx, wy, wz, motion state, h, vz) of a ball
    ``dt`` seconds after ``state``, by the simulator's motion kernels; ``dt``
    is clamped at the ball's next motion transition (in flight: its
    landing), where the closed form of its state ends. ``p``:
    ``PhysicsParams.as_array()``. The only place the rendering package calls
    the physics kernels."""
    s = np.asarray(state, dtype=np.float64)
    if int(s[7]) == C.AIRBORNE:
        g = float(p[C.P_G])
        dt = min(float(dt), drop_time(float(s[8]), float(s[9]), g))
        out = s.copy()
        out[0] += s[2] * dt; out[1] += s[3] * dt
        h, out[9] = rise(float(s[8]), float(s[9]), dt, g)
        out[8] = max(h, 0.0)
        return out
    pos = s[None, None, 0:2].copy()
    vel = s[None, None, 2:4].copy()
    om = s[None, None, 4:7].copy()
    st = np.array([[int(s[7])]], dtype=np.int64)
    dt = min(float(dt), transition_time(vel, om, st, 0, 0, p))
    evolve(pos, vel, om, st, 0, 0, dt, p, bool(zspin_on), bool(spin_on))
    return np.array([pos[0, 0, 0], pos[0, 0, 1], vel[0, 0, 0], vel[0, 0, 1],
                     om[0, 0, 0], om[0, 0, 1], om[0, 0, 2], st[0, 0], 0.0, 0.0], dtype=np.float64)


def segment_normals(segments) -> np.ndarray:
    """Unit normals [S, 2] of cushion segments [S, 4] (up to sign: the
    replay keeps the segments, not the kernels' normals)."""
    segs = np.asarray(segments, dtype=np.float64).reshape(-1, 4)
    d = segs[:, 2:] - segs[:, :2]
    return np.stack([-d[:, 1], d[:, 0]], axis=1) / np.hypot(d[:, 0], d[:, 1])[:, None]


def off_table_landing(flight, b: int, normals, p: np.ndarray) -> tuple[int, float, float]:
    """Where a ball in flight that passes over boundary ``b`` (an
    ``EV_OFF_TABLE`` event's index: a cushion segment, -2 - tip for a jaw
    tip, -1 over a pocket) comes down: (``OFF_RAIL`` or ``OFF_FLOOR``, x, y).
    ``flight`` [10]: its state as it crosses; (x, y) where it descends to
    the cushion nose's height, on the rail top or over the floor. The rule
    of ``physics.cushion.rail.landing_code``: on the rail if it gets there
    within ``RAIL_WIDTH`` beyond the cushion line, its outward speed being
    its speed across cushion ``b`` (over a tip or a pocket: all of its
    horizontal speed); ``normals``: ``segment_normals`` of the table's
    segments (their sign does not matter)."""
    s = np.asarray(flight, dtype=np.float64)
    R, g, hc = float(p[C.P_R]), float(p[C.P_G]), float(p[C.P_H_C])
    vx, vy = float(s[2]), float(s[3])
    td = drop_time(max(float(s[8]) - hc, 0.0), float(s[9]), g)
    if b >= 0:
        out = abs(vx * float(normals[b, 0]) + vy * float(normals[b, 1]))
    else:
        out = math.sqrt(vx * vx + vy * vy)
    code = C.OFF_RAIL if out * td - R <= RAIL_WIDTH else C.OFF_FLOOR
    return code, float(s[0]) + vx * td, float(s[1]) + vy * td


def off_table_of(time, kind, balls, states, normals, p: np.ndarray, zspin_on: bool, spin_on: bool) -> list:
    """The balls an event log (its arrays: time [N], kind [N], balls [N, 2],
    states [N, 2, 10]) sends off the table, in order:
    ``{"ball", "code", "t", "x", "y"}`` (``off_table_landing``)."""
    last, out = {}, []
    for n in range(len(time)):
        k, i = int(kind[n]), int(balls[n, 0])
        if k == C.EV_OFF_TABLE and i in last:
            t0, s0 = last[i]
            fl = evolve_state(s0, float(time[n]) - t0, p, zspin_on, spin_on)
            fl[0], fl[1] = states[n, 0, 0], states[n, 0, 1]  # where it crossed, as the log has it
            code, x, y = off_table_landing(fl, int(balls[n, 1]), normals, p)
            out.append({"ball": i, "code": code, "t": float(time[n]), "x": x, "y": y})
        last[i] = (float(time[n]), states[n, 0])
        if k == C.EV_BALL_BALL:
            last[int(balls[n, 1])] = (float(time[n]), states[n, 1])
    return out


# ------------------------------------------------------------- records --
def pack_state(s) -> list:
    """One ball's state [10] (or the planar [8]) -> its record (see the
    module docstring)."""
    x, y, vx, vy, wx, wy, wz, ms = (float(v) for v in s[:8])
    ms = int(ms)
    if ms == C.AIRBORNE:
        return [ms, x, y, vx, vy, wx, wy, wz, float(s[8]), float(s[9])]
    if ms == C.SLIDING:
        return [ms, x, y, vx, vy, wx, wy, wz]
    if ms == C.ROLLING:
        return [ms, x, y, vx, vy, wz]
    if ms == C.SPINNING:
        return [ms, x, y, wz]
    if ms in (C.STATIONARY, C.POCKETED):
        return [ms, x, y]
    raise ValueError(f"unknown motion state {ms}")


def unpack_state(rec, R: float, spin_on: bool = True) -> np.ndarray:
    """A record -> the ball's state [10] (inverse of ``pack_state``)."""
    ms = int(rec[0])
    if len(rec) != _RECORD_LEN.get(ms, -1):
        raise ValueError(f"ball record {rec!r}: a state-{ms} record has {_RECORD_LEN.get(ms)} entries")
    out = np.zeros(COLUMNS)
    out[0], out[1], out[7] = rec[1], rec[2], ms
    if ms == C.AIRBORNE:
        out[2:7] = rec[3:8]
        out[8:10] = rec[8:10]
    elif ms == C.SLIDING:
        out[2:7] = rec[3:8]
    elif ms == C.ROLLING:
        vx, vy = float(rec[3]), float(rec[4])
        out[2], out[3], out[6] = vx, vy, rec[5]
        if spin_on:  # the rolling constraint, written as the kernels write it
            out[4] = -vy / R
            out[5] = vx / R
    elif ms == C.SPINNING:
        out[6] = rec[3]
    return out


def _shot_from_log(log, duration: float | None, truncated: bool, info: dict) -> dict:
    n_start = 0
    while n_start < len(log) and log.kind[n_start] == C.EV_START:
        n_start += 1
    if n_start == 0:
        raise ValueError("the event log has no start records (simulate(..., record=True) writes one per ball)")
    start = [None] * n_start
    for n in range(n_start):
        start[int(log.balls[n, 0])] = pack_state(log.states[n, 0])
    events = []
    for n in range(n_start, len(log)):
        kind = int(log.kind[n])
        i, j = int(log.balls[n, 0]), int(log.balls[n, 1])
        row = [float(log.time[n]), kind, i, j, pack_state(log.states[n, 0])]
        if kind == C.EV_BALL_BALL:
            row.append(pack_state(log.states[n, 1]))
        events.append(row)
    t_end = float(log.time[-1]) if duration is None else float(duration)
    return {"info": info, "duration": t_end, "truncated": bool(truncated), "start": start, "events": events}


def _derived_info(log) -> dict:
    """Cue-ball strike, first contact and pocketed balls read from an event log."""
    info = {}
    first = -1
    pocketed, pockets = [], []
    for n in range(len(log)):
        k = int(log.kind[n])
        i, j = int(log.balls[n, 0]), int(log.balls[n, 1])
        if k == C.EV_BALL_BALL and first < 0 and (i == 0 or j == 0):
            first = j if i == 0 else i
        if k == C.EV_POCKET:
            pocketed.append(i); pockets.append(j)
    info["first_contact"] = first
    info["pocketed"] = pocketed
    info["pockets"] = pockets
    return info


def _strike_info(vel, omega, R: float) -> dict:
    """Aim (rad), speed (m/s) and tip offsets (a side, b height; units of R)
    of a struck cue ball, inverting physics.strike's omega = 5 v / (2R) (a z + b (z x d))."""
    vx, vy = float(vel[0]), float(vel[1])
    speed = math.hypot(vx, vy)
    if speed == 0.0:
        return {"aim": 0.0, "speed": 0.0, "side": 0.0, "height": 0.0}
    dx, dy = vx / speed, vy / speed
    k = 2.5 * speed / R
    return {"aim": math.atan2(vy, vx), "speed": speed, "side": float(omega[2]) / k,
            "height": (float(omega[0]) * -dy + float(omega[1]) * dx) / k}


def _jsonable(v):
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if isinstance(v, dict):
        return {str(k): _jsonable(x) for k, x in v.items()}
    return v


# -------------------------------------------------------------- replay --
class Replay:
    """A list of shots on one table. Build with ``from_sim`` (a
    ``simulate(..., record=True)`` result) or ``for_table`` + ``add_log``
    (env episodes: see ``record_env_shot`` and ``RecordReplay``); write with
    ``save`` / ``to_json``, read with ``load`` / ``from_dict``;
    ``positions_at(t, shot)`` evaluates the balls at any time."""

    def __init__(self, data: dict):
        if data.get("format") != FORMAT:
            raise ValueError(f"not a billiards replay (format {data.get('format')!r}, expected {FORMAT!r})")
        if data.get("version") != VERSION:
            raise ValueError(f"replay version {data.get('version')!r} is not supported (this reader: {VERSION})")
        self.data = data
        self.params = PhysicsParams(**data["params"])
        self.effects = Effects(**data["effects"]).normalized()
        self._p = self.params.as_array()
        self._tracks = [None] * len(data["shots"])
        self._segment_normals = None

    # --- construction -----------------------------------------------------
    @classmethod
    def for_table(cls, table: Table, params: PhysicsParams | None = None, effects: Effects | None = None,
                  n_balls: int | None = None, meta: dict | None = None) -> "Replay":
        """An empty replay (no shots yet) of ``table`` with these physics."""
        params = params or PhysicsParams.standard()
        effects = effects or Effects()
        segs, _, tips, pockets = table.geometry(effects.pockets)
        geo = {"name": table.name, "style": table.style, "width": table.width, "length": table.length,
               "segments": segs.tolist(), "tips": tips.tolist(), "pockets": pockets.tolist(),
               "outline": table.outline(effects.pockets).tolist()}
        if table.marks is not None:  # snooker: the markings for the viewer
            m = table.marks
            geo["marks"] = {"baulk": m.baulk, "d_centre": list(m.d_centre), "d_radius": m.d_radius,
                            "spots": m.spots.tolist()}
        return cls({"format": FORMAT, "version": VERSION, "meta": _jsonable(meta or {}), "n_balls": n_balls,
                    "table": geo, "params": params.to_dict(), "effects": effects.to_dict(), "shots": []})

    @classmethod
    def from_sim(cls, result, start_state=None, table: Table | None = None, params: PhysicsParams | None = None,
                 effects: Effects | None = None, index: int = 0, info: dict | None = None,
                 meta: dict | None = None) -> "Replay":
        """One table (``index``) of a ``simulate(..., record=True)`` result as
        a one-shot replay. ``start_state``: the struck state passed to
        ``simulate`` (gives the strike's aim, speed and tip offsets; without
        it they are read from the log's start records). ``info``: extra shot
        information (shooter, ball_in_hand, fouls, ...)."""
        if table is None:
            raise ValueError("from_sim needs the table the shot was simulated on")
        if result.events is None:
            raise ValueError("the result has no event log: simulate with record=True")
        log = result.events[index]
        rep = cls.for_table(table, params, effects, n_balls=int(result.state.n_balls), meta=meta)
        start = None
        if start_state is not None:
            start = (start_state.vel[index, 0], start_state.omega[index, 0])
        rep.add_log(log, info=info, duration=float(result.time[index]), truncated=bool(result.truncated[index]),
                    strike=start)
        return rep

    def add_log(self, log, info: dict | None = None, duration: float | None = None, truncated: bool = False,
                strike=None) -> dict:
        """Append a shot from its ``EventLog``; returns the shot's dict.
        ``strike``: (velocity [2], omega [3]) of the struck cue ball, else
        read from the log's start record of ball 0."""
        if self.data["n_balls"] is None:
            self.data["n_balls"] = int(np.sum(log.kind == C.EV_START))
        shot_info = _derived_info(log)
        if strike is None:
            n0 = int(np.nonzero((log.kind == C.EV_START) & (log.balls[:, 0] == 0))[0][0])
            strike = (log.states[n0, 0, 2:4], log.states[n0, 0, 4:7])
        shot_info.update(_strike_info(strike[0], strike[1], self.params.R))
        shot_info.update({k: v for k, v in (info or {}).items() if v is not None})
        shot = _shot_from_log(log, duration, truncated, _jsonable(shot_info))
        if len(shot["start"]) != self.n_balls:
            raise ValueError(f"the log has {len(shot['start'])} balls, the replay {self.n_balls}")
        off = self._still_off(shot["start"])
        if np.any(log.kind == C.EV_OFF_TABLE):
            off += off_table_of(log.time, log.kind, log.balls, log.states, self._normals(), self._p,
                                self.effects.vertical_spin, self.effects.spin)
        if off:  # only where a ball left the table: planar replays are unchanged
            shot["info"]["off_table"] = off
        self.data["shots"].append(shot)
        self._tracks.append(None)
        return shot

    def add_still(self, pos, pocket, info: dict | None = None) -> dict:
        """Append a turn in which no ball moved (a pass: the shot handed
        back): every ball at rest where it lies (``pos`` [B, 2], ``pocket``
        [B], -1 on the table), no events, duration 0; returns the entry."""
        pos, pocket = np.asarray(pos, dtype=np.float64), np.asarray(pocket)
        if self.data["n_balls"] is None:
            self.data["n_balls"] = len(pos)
        if len(pos) != self.n_balls:
            raise ValueError(f"the table has {len(pos)} balls, the replay {self.n_balls}")
        start = [[C.POCKETED if pocket[i] >= 0 else C.STATIONARY, float(pos[i, 0]), float(pos[i, 1])]
                 for i in range(len(pos))]
        shot = {"info": _jsonable(dict(info or {})), "duration": 0.0, "truncated": False, "start": start,
                "events": []}
        off = self._still_off(start)
        if off:
            shot["info"]["off_table"] = off
        self.data["shots"].append(shot)
        self._tracks.append(None)
        return shot

    def _normals(self) -> np.ndarray:
        if self._segment_normals is None:
            self._segment_normals = segment_normals(self.table["segments"])
        return self._segment_normals

    def _still_off(self, start) -> list:
        """The previous shot's off-table balls that start this one still off
        the table (their record pocketed), from time 0."""
        if not self.shots:
            return []
        prev = (self.shots[-1].get("info") or {}).get("off_table", [])
        return [dict(e, t=0.0) for e in prev if int(start[e["ball"]][0]) == C.POCKETED]

    # --- access -----------------------------------------------------------
    @property
    def n_balls(self) -> int:
        return int(self.data["n_balls"])

    @property
    def shots(self) -> list:
        return self.data["shots"]

    @property
    def table(self) -> dict:
        return self.data["table"]

    def duration(self, shot: int = 0) -> float:
        return float(self.shots[shot]["duration"])

    def event_times(self, shot: int = 0) -> np.ndarray:
        return np.array([row[0] for row in self.shots[shot]["events"]])

    def _track(self, shot: int):
        """Per ball: (record times [K], states [K, 10]) of a shot."""
        if self._tracks[shot] is None:
            sh, R, spin = self.shots[shot], self.params.R, self.effects.spin
            times = [[0.0] for _ in range(self.n_balls)]
            states = [[unpack_state(rec, R, spin)] for rec in sh["start"]]
            for row in sh["events"]:
                t, kind, i = row[0], row[1], row[2]
                times[i].append(t); states[i].append(unpack_state(row[4], R, spin))
                if kind == C.EV_BALL_BALL:
                    j = row[3]
                    times[j].append(t); states[j].append(unpack_state(row[5], R, spin))
            self._tracks[shot] = [(np.array(tt), np.array(ss)) for tt, ss in zip(times, states)]
        return self._tracks[shot]

    def ball_state_at(self, t: float, ball: int, shot: int = 0) -> np.ndarray:
        """State [10] of one ball at time ``t`` (s from the shot's start;
        clamped to [0, duration])."""
        times, states = self._track(shot)[ball]
        t = min(max(float(t), 0.0), self.duration(shot))
        k = bisect.bisect_right(times, t) - 1
        dt = t - times[k]
        if k + 1 < len(times):  # the motion law holds only until the ball's next record
            dt = min(dt, times[k + 1] - times[k])
        return evolve_state(states[k], dt, self._p, self.effects.vertical_spin, self.effects.spin)

    def states_at(self, t: float, shot: int = 0) -> np.ndarray:
        """Every ball's state [B, 10] at time ``t`` of a shot."""
        return np.stack([self.ball_state_at(t, i, shot) for i in range(self.n_balls)])

    def positions_at(self, t: float, shot: int = 0):
        """(pos [B, 2], on_table [B]) at time ``t`` of a shot."""
        s = self.states_at(t, shot)
        return s[:, :2].copy(), s[:, 7] != C.POCKETED

    def table_view(self, t: float, shot: int = 0):
        """The balls at time ``t`` of a shot as the renderers draw them: (pos
        [B, 2], pocket [B], h [B]). ``pocket`` as ``BallState.pocket``: -1 on
        the table (in flight too, h > 0 the height of its lowest point above
        the slate), ``OFF_RAIL`` / ``OFF_FLOOR`` for a ball off the table (pos:
        where it came down, ``off_table_landing``), else the pocket the shot
        put it in (0 where the replay does not say: pocketed before the shot)."""
        s = self.states_at(t, shot)
        pos, h = s[:, :2].copy(), s[:, 8].copy()
        pocket = np.where(s[:, 7] == C.POCKETED, 0, -1)
        info = self.shots[shot].get("info") or {}
        for b, k in zip(info.get("pocketed", []), info.get("pockets", [])):
            if pocket[b] >= 0:
                pocket[b] = k
        t = min(max(float(t), 0.0), self.duration(shot))
        for e in info.get("off_table", []):
            b = e["ball"]
            if e["t"] <= t and pocket[b] >= 0:
                pocket[b], pos[b] = e["code"], (e["x"], e["y"])
        return pos, pocket, h

    def event_states(self, shot: int = 0):
        """The shot's event log read back: (time [N], kind [N], balls [N, 2],
        states [N, 2, 10]), as ``simulate(..., record=True)`` wrote it."""
        sh, R, spin = self.shots[shot], self.params.R, self.effects.spin
        B = self.n_balls
        n = B + len(sh["events"])
        time, kind = np.zeros(n), np.zeros(n, dtype=np.int64)
        balls, states = np.zeros((n, 2), dtype=np.int64), np.zeros((n, 2, COLUMNS))
        for i, rec in enumerate(sh["start"]):
            balls[i] = (i, -1)
            states[i, 0] = unpack_state(rec, R, spin)
        for m, row in enumerate(sh["events"], start=B):
            time[m], kind[m], balls[m] = row[0], row[1], (row[2], row[3])
            states[m, 0] = unpack_state(row[4], R, spin)
            if row[1] == C.EV_BALL_BALL:
                states[m, 1] = unpack_state(row[5], R, spin)
        return time, kind, balls, states

    def table_object(self) -> Table:
        """The replay's geometry as a ``Table`` (for the raster renderer)."""
        g = self.table
        segs = np.array(g["segments"], dtype=np.float64).reshape(-1, 4)
        d = segs[:, 2:] - segs[:, :2]
        n = np.stack([-d[:, 1], d[:, 0]], axis=1) / np.hypot(d[:, 0], d[:, 1])[:, None]
        marks = None
        if "marks" in g:
            from ..physics.table import SnookerMarks
            mk = g["marks"]
            marks = SnookerMarks(mk["baulk"], tuple(mk["d_centre"]), mk["d_radius"], np.array(mk["spots"], dtype=np.float64))
        return Table(g["width"], g["length"], segs, n, np.array(g["tips"], dtype=np.float64).reshape(-1, 2),
                     np.array(g["pockets"], dtype=np.float64).reshape(-1, 3), name=g.get("name", "custom"),
                     style=g.get("style", "pool"), marks=marks)

    # --- files ------------------------------------------------------------
    def to_dict(self) -> dict:
        return self.data

    def to_json(self) -> str:
        return json.dumps(self.data, separators=(",", ":"), allow_nan=False)

    def save(self, path) -> Path:
        path = Path(path)
        path.write_text(self.to_json())
        return path

    @classmethod
    def from_dict(cls, data: dict) -> "Replay":
        return cls(data)

    @classmethod
    def load(cls, path) -> "Replay":
        return cls(json.loads(Path(path).read_text()))

    def __len__(self):
        return len(self.shots)


def record_env_shot(replay: Replay, env, info: dict | None = None, reward: float | None = None, action=None,
                    index: int = 0) -> dict:
    """Append the shot an env just played (its ``last_events``; the env needs
    a ``render_mode`` to keep them) to ``replay``. ``index``: the table of a
    vector env. ``info``/``reward``/``action``: that step's outputs."""
    logs = env.unwrapped.last_events if hasattr(env, "unwrapped") else env.last_events
    log = logs[index] if isinstance(logs, list) else logs
    if log is None:
        raise RuntimeError("the env kept no event log: create it with a render_mode (e.g. render_mode='rgb_array') "
                           "so it records each shot's events")
    vector = isinstance(logs, list)  # a vector env: info entries are arrays over its tables
    extra = {}
    for k in _INFO_KEYS:
        if info is not None and k in info:
            extra[k] = _jsonable(np.asarray(info[k])[index] if vector else info[k])
    if reward is not None:
        extra["reward"] = float(np.asarray(reward)[index] if vector else reward)
    if action is not None:
        a = np.asarray(action, dtype=np.float64)
        extra["action"] = (a[index] if vector else a).tolist()
    truncated = bool(np.asarray(info["sim_truncated"])[index] if vector else info["sim_truncated"]) \
        if info is not None and "sim_truncated" in info else False
    return replay.add_log(log, info=extra, truncated=truncated)


def replay_for_env(env, meta: dict | None = None) -> Replay:
    """An empty replay on an env's table and physics."""
    u = env.unwrapped if hasattr(env, "unwrapped") else env
    n = u.state.n_balls if u.state is not None else None
    return Replay.for_table(u.table, u.params, u.effects, n_balls=n, meta=meta)

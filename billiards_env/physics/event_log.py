"""Event recording into the preallocated ``LogBuffers`` (both solvers);
``simulate`` turns the buffers into ``EventLog`` objects."""
from . import constants as C
from ._jit import njit


@njit
def record(log, balls, e, t, kind, i, j):
    """Append event ``kind`` at time t of ball i (and ball j of a ball-ball
    event; else j is a cushion, tip or pocket index, or -1) to table e's log,
    with the involved balls' states after it: (x, y, vx, vy, wx, wy, wz,
    motion state, h, vz), the last two (height above the slate, vertical
    velocity) zero but in a kernel of balls in flight."""
    n = log.n[e]
    if n >= log.t.shape[1]:
        log.n[e] = n + 1  # counts overflow; the wrapper reports it
        return
    pos, vel, om, st = balls.pos, balls.vel, balls.om, balls.st
    rec = log.state
    log.t[e, n] = t
    log.kind[e, n] = kind
    log.ij[e, n, 0] = i
    log.ij[e, n, 1] = j
    for s in range(2):
        b = i if s == 0 else j
        # only ball-ball events name a second ball
        if b < 0 or (s == 1 and kind != C.EV_BALL_BALL):
            continue
        rec[e, n, s, 0] = pos[e, b, 0]; rec[e, n, s, 1] = pos[e, b, 1]
        rec[e, n, s, 2] = vel[e, b, 0]; rec[e, n, s, 3] = vel[e, b, 1]
        rec[e, n, s, 4] = om[e, b, 0]; rec[e, n, s, 5] = om[e, b, 1]
        rec[e, n, s, 6] = om[e, b, 2]; rec[e, n, s, 7] = st[e, b]
        if balls.air.shape[0] > 0:
            rec[e, n, s, 8] = balls.air[e, b, 0]; rec[e, n, s, 9] = balls.air[e, b, 1]
    log.n[e] = n + 1


@njit
def record_start(log, balls, e):
    """Every ball's initial state, as start events at t = 0."""
    if log.on:
        for i in range(balls.pos.shape[1]):
            record(log, balls, e, 0.0, C.EV_START, i, -1)

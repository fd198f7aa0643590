"""Diagnostics the checking kernel variants (simulate(..., diagnostics=True))
write per table into ``Outputs.diag``: [0] largest energy gain (J) of an
impact or of the total between events, [1] largest momentum error of a
ball-ball impact (kg m/s), [2] smallest gap between balls (m), [3] largest
excursion off the table (m)."""
import math

from . import constants as C
from ._jit import njit
from .airborne import flight_energy
from .motion import energy


@njit
def start(balls, geo, e, p, diag):
    """Reset table e's diagnostics and check its initial state; returns its
    total energy."""
    diag[e, 0] = 0.0; diag[e, 1] = 0.0; diag[e, 2] = math.inf; diag[e, 3] = 0.0
    check_geometry(balls, geo, e, p, diag)
    return total_energy(balls, e, p)


@njit
def check_geometry(balls, geo, e, p, diag):
    """Smallest pair gap (diag[e, 2]) and worst excursion off the table
    (diag[e, 3]) of table e now; balls in flight (a kernel with
    ``Balls.air``) are apart in 3D, and a ball below the slate is an
    excursion by its depth."""
    pos, st, pockets = balls.pos, balls.st, geo.pockets
    air_on = balls.air.shape[0] > 0
    width, length = geo.width, geo.length
    R = p[C.P_R]
    B = pos.shape[1]
    for i in range(B):
        if st[e, i] == C.POCKETED:
            continue
        for j in range(i + 1, B):
            if st[e, j] == C.POCKETED:
                continue
            d = math.hypot(pos[e, i, 0] - pos[e, j, 0], pos[e, i, 1] - pos[e, j, 1])
            if air_on:
                d = math.hypot(d, balls.air[e, i, 0] - balls.air[e, j, 0])
            gap = d - 2.0 * R
            if gap < diag[e, 2]:
                diag[e, 2] = gap
        x, y = pos[e, i, 0], pos[e, i, 1]
        out = max(R - x, x - (width - R), R - y, y - (length - R), 0.0)
        if air_on and -balls.air[e, i, 0] > diag[e, 3]:
            diag[e, 3] = -balls.air[e, i, 0]
        if out > C.OFF_TABLE_TOL:
            near = False
            for k in range(pockets.shape[0]):
                if math.hypot(x - pockets[k, 0], y - pockets[k, 1]) < C.POCKET_REGION:
                    near = True
            if not near and out > diag[e, 3]:
                diag[e, 3] = out


@njit
def total_energy(balls, e, p):
    """Kinetic plus rotational energy of every ball of table e (J)."""
    en = 0.0
    air_on = balls.air.shape[0] > 0
    for i in range(balls.vel.shape[1]):
        en += energy(balls.vel, balls.om, balls.st, e, i, p)
        if air_on and balls.st[e, i] != C.POCKETED:
            en += flight_energy(balls, e, i, p)
    return en


@njit
def energy_step(balls, e, p, diag, en_prev):
    """Total energy may never rise from one event (or step) to the next:
    record a rise in diag[e, 0]; returns the energy now."""
    en = total_energy(balls, e, p)
    diag[e, 0] = max(diag[e, 0], en - en_prev)
    return en

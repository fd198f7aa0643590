"""Named structures the kernels take (numba namedtuples of arrays).

``simulate`` builds them by name; a kernel or helper takes a few of them
instead of dozens of arrays in an order two files must agree on. Fields are
per table ``e`` of the batch (first axis E) and ball ``i`` (axis B).
"""
from collections import namedtuple

import numpy as np

from . import constants as C
from ._jit import njit_alloc

# pos [E, B, 2], vel [E, B, 2], om [E, B, 3], st [E, B] motion state
# (constants.STATIONARY ...), pocket [E, B] pocket index or -1 (or an
# off-table code, constants.OFF_TABLE); air [E, B, 2] the height of each
# ball's lowest point above the slate (m) and its vertical velocity (m/s),
# read only by the kernels of Effects(airborne) (the others get an empty
# [0, 0, 2] array: they never index it)
Balls = namedtuple("Balls", "pos vel om st pocket air")
# segs [S, 4] cushion segments (x0, y0, x1, y1), norms [S, 2] their unit
# normals into the table, tips [T, 2] jaw tips, pockets [K, 3] (x, y, r);
# width, length of the bed (m); the broad phase's split of them
# (table.PocketGroups): rails, free_tips, near, gsegs, gtips
Geometry = namedtuple("Geometry", "segs norms tips pockets width length rails free_tips near gsegs gtips")
# Event solver scratch: per ball the absolute time of its next transition
# (tt) and boundary event (tb, of kind bkind with boundary index bidx), per
# pair the contact time (tpair [E, B, B]), per ball its acceleration and swept
# box (paths [E, B, 6], detection.sweep_path), and the time its state in
# ``Balls`` refers to (tlast [E, B]: balls are evolved lazily, only when an
# event involves them)
EventScratch = namedtuple("EventScratch", "tt tb bkind bidx tpair paths tlast")
# Per table: simulated time, events, first ball the cue ball touched (-1),
# cushion hits per ball [E, B] (all, and those after the cue ball's first
# contact), truncated flag, diagnostics [E, 4] (simulate.SimResult.diagnostics),
# the cue ball's contacts in order (order [E, K, 2]: event kind, ball or
# boundary index; norder [E] how many there were, K or more; written only by
# a kernel compiled with the contact order on, SimOptions.contacts)
Outputs = namedtuple("Outputs", "time nev first cush cush_after trunc diag")
OrderedOutputs = namedtuple("OrderedOutputs", Outputs._fields + ("order", "norder"))
# Event log buffers: on (record at all), n [E] events so far, t [E, N],
# kind [E, N], ij [E, N, 2], state [E, N, 2, 10] (simulate.EventLog)
LogBuffers = namedtuple("LogBuffers", "on n t kind ij state")
# One table's scratch for a set of simultaneous ball-ball impacts: pair ids
# (i, j), approach speeds (w), distinct balls and two state copies (saved,
# swapped) for the two resolution orders (impacts.resolve_impact_set)
ImpactScratch = namedtuple("ImpactScratch", "i j w balls saved swapped")
# One worker's scratch, reused for each table of its chunk (event solver):
# imp its ImpactScratch, stuck [B] a flag per ball (the balls of the events
# at the current instant), todo [B] the balls whose events to recompute
ChunkScratch = namedtuple("ChunkScratch", "imp stuck todo")
# A ball's motion coefficients within one motion state, built inside the
# detection kernels: its path is r(t) = (x, y) + (vx, vy) t + (ax, ay) t^2 / 2
Motion = namedtuple("Motion", "x y vx vy ax ay")


@njit_alloc
def impact_scratch():
    """Fresh ``ImpactScratch`` for one table."""
    return ImpactScratch(np.empty(C.MAX_SIMULTANEOUS, dtype=np.int64), np.empty(C.MAX_SIMULTANEOUS, dtype=np.int64),
                         np.empty(C.MAX_SIMULTANEOUS), np.empty(2 * C.MAX_SIMULTANEOUS, dtype=np.int64),
                         np.empty((2 * C.MAX_SIMULTANEOUS, 6)), np.empty((2 * C.MAX_SIMULTANEOUS, 6)))

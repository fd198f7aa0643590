"""Named tolerances and index constants shared by the kernels.

Every tolerance carries a one-line reason. Units are SI throughout.
"""

# --- tolerances -----------------------------------------------------------
# Balls closer than 2R - OVERLAP_TOL at input are rejected: 1 nm is far below
# any physical placement error yet far above float64 rounding at table scale
# (about 1e-16 * 2.54 m).
OVERLAP_TOL = 1e-9
# A contact gap below CONTACT_TOL (m) counts as touching: it is a few hundred
# ulps of a table coordinate, so rounding cannot open or close a contact.
CONTACT_TOL = 1e-12
# Speeds (m/s) and spins (rad/s) below these are zero: 1e-12 m/s moves a ball
# one picometre in a second, far below anything a trajectory can resolve.
SPEED_EPS = 1e-12
SPIN_EPS = 1e-10
# Relative accelerations (m/s^2) below ACCEL_EPS are rounding: the felt's
# accelerations are 0.1 - 2 m/s^2, so two balls of one merged chain differ
# by ~1e-16 m/s^2, which must not count as pressing them together.
ACCEL_EPS = 1e-12
# Impacts slower than ZENO_SPEED (m/s) are treated as resting contacts
# (restitution 0, sliding ended at once). Without this a ball pushed by its own
# felt friction into a neighbour or a cushion bounces ever faster and smaller,
# an infinite (Zeno) sequence of events; 10 um/s changes no outcome.
ZENO_SPEED = 1e-5
# Simulated events per table before the solver gives up and flags the table
# as truncated (never silently): a 15-ball break takes a few hundred.
MAX_EVENTS = 20_000
# Inelastic collapse: a slow ball wedged between a ball and a cushion can be
# struck back and forth at one instant forever (each impact pushes it into
# the other contact). After ZENO_EVENTS events without time advancing, the
# balls of those events slower than ZENO_FREEZE_SPEED (speed of the contact
# point with the cloth, |v| + R|w_xy|, m/s) stop translating and rolling
# (spin about the vertical axis, which drives no contact, is kept): the felt
# would stop such a ball within (1e-3)^2 / (2 mu_r g) ~ 5 um, and stopping it
# only removes energy. If the same instant still does not end, each further
# ZENO_EVENTS events double the speed limit (a ball with strong side spin
# sliding along a jaw into a neighbour stalled one at 3 mm/s), so the
# collapse ends after at most ~log2(max speed / 1e-3) rounds.
ZENO_EVENTS = 100
ZENO_FREEZE_SPEED = 1e-3
# Fixed steps per table before the step solver flags truncation (600 s of
# simulated time at dt = 1e-5 would be 6e7 steps: far beyond any shot).
MAX_STEPS = 100_000_000
# Ball-ball impacts closer in time than this are one simultaneous impact:
# 1e-12 s is a femtometre of travel at 1 m/s.
SIMULTANEOUS_TIME = 1e-12
# At most this many ball-ball impacts are resolved as one simultaneous set.
MAX_SIMULTANEOUS = 4
# Diagnostics and invariants: a ball counts as off the table if it is outside
# the rails by more than OFF_TABLE_TOL (m; as OVERLAP_TOL, far above rounding
# at table scale) and not within POCKET_REGION (m) of a pocket centre (a
# ball dropping into a pocket crosses the rail line).
OFF_TABLE_TOL = 1e-9
POCKET_REGION = 0.15
# Root polishing: bisection/Newton stops when the bracket is below this (s);
# 1e-15 s at 10 m/s is 1e-14 m.
ROOT_TIME_TOL = 1e-15

# --- motion states --------------------------------------------------------
STATIONARY = 0
SPINNING = 1   # no translation, spin about the vertical axis only
SLIDING = 2
ROLLING = 3
POCKETED = 4     # off the slate for good: in a pocket, or off the table (``pocket`` tells which)
AIRBORNE = 5     # in flight above the slate (Effects(airborne)): height and vertical velocity in ``Balls.air``

# --- where a ball went (BallState.pocket) ---------------------------------
# -1: on the table; 0 .. K-1: in pocket k; OFF_TABLE and above: it left the
# table over a cushion (Effects(airborne) only). Codes, not pockets: they
# never index the table's pocket arrays, and ``pocket >= 0`` still means
# "no longer in play" everywhere.
ON_TABLE = -1
OFF_TABLE = 100
OFF_RAIL = 100   # came down on the rail top, beyond the cushion: off the table
OFF_FLOOR = 101  # cleared the rail and fell to the floor

# --- event kinds (event log) ----------------------------------------------
EV_START = 0
EV_BALL_BALL = 1
EV_CUSHION = 2      # linear cushion segment
EV_JAW_TIP = 3      # cushion vertex at a pocket jaw
EV_POCKET = 4
EV_SLIDE_ROLL = 5
EV_ROLL_STOP = 6
EV_SPIN_STOP = 7
EV_SLATE = 8        # an airborne ball meets the slate (a bounce, or it settles)
EV_OFF_TABLE = 9    # an airborne ball passes over a cushion's nose and leaves the table
EVENT_NAMES = ("start", "ball-ball", "cushion", "jaw-tip", "pocket",
               "slide-roll", "roll-stop", "spin-stop", "slate", "off-table")

# --- parameter vector layout (PhysicsParams.as_array) -----------------------
P_M, P_R, P_G, P_MU_S, P_MU_R, P_MU_SP, P_MU_B, P_E_B, P_E_C, P_F_C, P_H_C, P_KT_KN = range(12)
N_PARAMS = 12

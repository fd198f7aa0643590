"""First-contact times of the event detector (roots.first_entry) against
closed forms, including the touching cases the fuzzers found."""
import math

import pytest

from billiards_env.physics import constants as C
from billiards_env.physics.roots import first_entry

R2 = 2 * 0.028575                       # centre distance at contact (m)
F_TOL = 2.0 * R2 * C.CONTACT_TOL        # the pair detector's tolerance on f


def test_apart_pair_meets_at_the_quadratic_root():
    # head-on at 1 m/s from 0.1 m apart: gap^2 - (2R)^2 with d(t) = d0 - t
    d0 = R2 + 0.1
    t = first_entry(0.0, 0.0, 1.0, -2.0 * d0, d0 * d0 - R2 * R2, 10.0, F_TOL, -math.inf)
    assert t == pytest.approx(0.1, rel=1e-12)


def test_touching_and_closing_is_a_contact_now():
    assert first_entry(0.0, 0.0, 1.0, -1e-3, 0.0, 1.0, F_TOL, -math.inf) == 0.0


def test_touching_opening_by_rounding_and_pressed_is_held_closed():
    """A pair left by a resting contact: approach zero but for rounding
    (c1 a hair above zero) and pressed together by the felt (c2 < 0)."""
    assert first_entry(3.8, 1e-15, -0.22, 3e-19, -3e-17, 1.0, F_TOL, -math.inf) == 0.0


def test_touching_balls_turning_into_each_other_meet_again():
    """Fuzz case (closed box, two rolling balls sliding past each other):
    f = c0 + c1 t + c2 t^2 + c3 t^3 + c4 t^4 with c0 a rounding below zero
    and c1 ~ 0. f rises by less than its rounding offset before the cubic
    term turns it down, so f never crosses zero from above; the contact is
    where f returns to its current level, the root of c2 + c3 t + c4 t^2."""
    c4, c3, c2, c1, c0 = 0.004623110560532232, -0.005176870124363874, 1.3202041249278651e-08, \
        3.1014890485974055e-19, -3.382710778154774e-17
    expected = 2 * c2 / (-c3 + math.sqrt(c3 * c3 - 4 * c4 * c2))  # smaller root, cancellation-free
    t = first_entry(c4, c3, c2, c1, c0, 1.0, F_TOL, -math.inf)
    assert t == pytest.approx(expected, rel=1e-6)


def test_touching_and_moving_together_never_meet():
    """Equal motion but for rounding: no contact (it would repeat every
    few nanoseconds)."""
    assert first_entry(0.0, 0.0, 6e-26, 7e-21, 0.0, 1.0, F_TOL, -math.inf) == math.inf
    assert first_entry(0.0, 0.0, -1e-14, 7e-21, 0.0, 1.0, F_TOL, -math.inf) == math.inf

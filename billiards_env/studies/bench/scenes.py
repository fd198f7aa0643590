"""The benchmark's named scenes: ``SCENES[name](n, P, T, rng)`` is a struck
batch of ``n`` tables drawn from ``rng`` (builders in ``studies.scenes``;
the same draws in the same order on every commit, so the figures compare)."""
from __future__ import annotations

from .. import scenes as _s


def _nine_break(n, P, T, rng):
    return _s.straight_break(T, P, n, rng, layout="nine")


def _fifteen_break(n, P, T, rng):
    return _s.straight_break(T, P, n, rng, layout="eight")


def _two_ball_cut(n, P, T, rng):
    return _s.half_ball_cut(T, P, n, rng)


def _one_ball_two_cushions(n, P, T, rng):
    return _s.one_ball_two_cushions(T, P, n, rng)


SCENES = {
    "9-ball break (8 m/s)": _nine_break,
    "15-ball break (8 m/s)": _fifteen_break,
    "two-ball cut (2 m/s, top+side)": _two_ball_cut,
    "one ball, top spin, two cushions": _one_ball_two_cushions,
}


def chosen_scenes(opts, names=tuple(SCENES)) -> list[str]:
    """The scenes among ``names`` that ``opts`` (a ``RunOptions``) keeps."""
    return [n for n in names if opts.keeps(n)]

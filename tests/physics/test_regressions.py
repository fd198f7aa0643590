"""Replay every saved failing case in tests/regressions/ (one JSON file per
case, written by the fuzzers or by hand from a bug found): the invariants
must hold now."""
import pathlib

import pytest

from billiards_env.physics import Effects, Models

from billiards_env.testing import load_case, run_checked

# tests/regressions/, shared with scripts/fuzz.py (its default --regressions)
REGRESSIONS = pathlib.Path(__file__).resolve().parents[1] / "regressions"

CASES = sorted(REGRESSIONS.glob("*.json"))


def test_regression_cases_exist():
    assert CASES, "tests/regressions/ should hold the cases found so far"


@pytest.mark.parametrize("path", CASES, ids=[p.stem for p in CASES])
def test_regression_case(path):
    c, state, table, params = load_case(path)
    run_checked(state, table, params, c["solver"], dt=c.get("dt") or 1e-3,
                effects=Effects.from_dict(c.get("effects")), models=Models.from_dict(c.get("models")))

"""Property-based fuzzing (hypothesis) of random racks, shots and presets on
both solvers: the invariants of billiards_env.testing hold for every shot.
A failing shot is written to tests/regressions/ (replayed by
test_regressions.py) before the test fails."""
import pathlib

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

from billiards_env.physics import Effects, Models
from billiards_env.physics.models import REGISTRIES
from billiards_env.testing import LAYOUTS, case_dict, random_batch, run_batch, save_case
from billiards_env.testing.fuzzing import SNOOKER_LAYOUTS

# tests/regressions/, shared with scripts/fuzz.py (its default --regressions)
REGRESSIONS = pathlib.Path(__file__).resolve().parents[1] / "regressions"

SETTINGS = settings(max_examples=12, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.parametrize("solver", ["event", "step"])
@SETTINGS
@given(seed=st.integers(0, 2**32 - 1), layout=st.sampled_from(LAYOUTS),
       preset=st.sampled_from(["standard", "seed"]))
def test_random_shots_keep_invariants(solver, seed, layout, preset):
    rng = np.random.default_rng(seed)
    _check_batch(*random_batch(rng, 8, layout, preset), solver, Effects.all())


@pytest.mark.parametrize("effects", sorted(Effects.each_off()))
@settings(SETTINGS, max_examples=4)
@given(seed=st.integers(0, 2**32 - 1), layout=st.sampled_from(LAYOUTS))
def test_random_shots_keep_invariants_under_every_effect_set(effects, seed, layout):
    """Every kernel variant keeps the invariants, not only the default one
    (event solver; each set with one effect off, and the minimal set)."""
    eff = Effects.each_off()[effects]
    rng = np.random.default_rng(seed)
    _check_batch(*random_batch(rng, 8, layout, "standard", pockets=eff.pockets), "event", eff)


# every non-default model alone, all effects on: the kernels
# test_models.py checks, so no new compile
NEW_MODELS = {name: Models(**{field: name}) for field, registry in REGISTRIES.items()
              for name in sorted(registry) if name != getattr(Models(), field)}


@pytest.mark.parametrize("model", sorted(NEW_MODELS))
@settings(SETTINGS, max_examples=4)
@given(seed=st.integers(0, 2**32 - 1), layout=st.sampled_from(LAYOUTS),
       preset=st.sampled_from(["standard", "seed"]))
def test_random_shots_keep_invariants_with_every_model(model, seed, layout, preset):
    """Each registered model other than the defaults keeps the invariants
    (event solver, all effects; 4 batches of 8 shots)."""
    rng = np.random.default_rng(seed)
    _check_batch(*random_batch(rng, 8, layout, preset), "event", Effects.all(), NEW_MODELS[model])


@pytest.mark.parametrize("solver", ["event", "step"])
@settings(SETTINGS, max_examples=6)
@given(seed=st.integers(0, 2**32 - 1), layout=st.sampled_from(SNOOKER_LAYOUTS))
def test_random_shots_on_the_snooker_table_keep_invariants(solver, seed, layout):
    """The 12 ft snooker table with snooker balls: the frozen 22-ball opening, random balls, balls in the jaws."""
    rng = np.random.default_rng(seed)
    _check_batch(*random_batch(rng, 8, layout, "snooker", table_name="snooker"), solver, Effects.all(),
                 table_name="snooker")


def _check_batch(state, table, params, solver, effects, models=None, table_name="pool9"):
    """Simulate, save every failing table as a regression case, and fail."""
    _, viol = run_batch(state, table, params, solver, effects=effects, models=models)
    bad = [e for e, v in enumerate(viol) if v]
    for e in bad:
        save_case(case_dict(state, e, params, solver, 1e-3, viol[e], effects, models, table_name), REGRESSIONS,
                  tag="hyp")
    assert not bad, {e: viol[e] for e in bad}

"""Model registry: every registered model is selectable and simulates
clean shots where it acts (all effects on; the default models under every
effect set); with its own effect off it shares the frictionless kernel;
unknown names fail clearly; a new friction law plugs in by one registry
entry."""
import numpy as np
import pytest

from billiards_env.physics import Effects, Models, simulate
from billiards_env.physics import ball_ball, cushion
from billiards_env.physics._jit import njit
from billiards_env.physics.kernels import make_kernel
from billiards_env.physics.models import REGISTRIES
from billiards_env.testing import random_batch, run_checked

# the default models and every other registered model alone (one kernel
# variant each; the cross product of models would add kernels, not checks
# of a model's own code)
CHOICES = [Models()] + [Models(**{field: name}) for field, registry in REGISTRIES.items()
                        for name in sorted(registry) if name != getattr(Models(), field)]
EFFECTS = Effects.each_off()
# the effect under which each interaction's model acts (off: frictionless)
OWN_EFFECT = {"ball_ball_friction": "ball_friction", "cushion": "cushion_friction"}


def _shots(n, seed, layout="nine", pockets=True):
    return random_batch(np.random.default_rng(seed), n, layout, "standard", pockets=pockets)


def test_defaults_are_todays_models():
    assert Models() == Models(ball_ball_friction="constant", cushion="han2005")
    assert Models.from_dict(None) == Models() == Models.from_dict(Models().to_dict())
    assert Models().key() == ("constant", "han2005")


@pytest.mark.parametrize("field", sorted(REGISTRIES))
def test_every_registered_model_is_selectable(field):
    for name in REGISTRIES[field]:
        m = Models.from_dict({field: name})
        assert getattr(m, field) == name and m.to_dict()[field] == name
        assert hasattr(REGISTRIES[field][name], "friction_coefficient" if field == "ball_ball_friction" else "resolve")


def test_unknown_model_name_is_rejected_with_the_choices():
    with pytest.raises(ValueError, match=r"unknown cushion model 'nope'; registered: \['han2005'"):
        Models(cushion="nope")
    with pytest.raises(ValueError, match="unknown ball_ball_friction model 'x'"):
        Models.from_dict({"ball_ball_friction": "x"})


def test_unknown_interaction_is_rejected_with_the_known_ones():
    with pytest.raises(ValueError, match=r"unknown model interactions \['cushions'\]; known: \['ball_ball_friction', 'cushion'\]"):
        Models.from_dict({"cushions": "han2005"})


def test_simulate_takes_models_or_their_dict(params, pool):
    s, table, p = _shots(2, 0)
    a = simulate(s, table, p, models=Models())
    b = simulate(s, table, p, models={"cushion": "han2005"})
    assert np.array_equal(a.state.pos, b.state.pos)
    with pytest.raises(TypeError, match="models must be a Models or a dict"):
        simulate(s, table, p, models="han2005")


def test_switched_off_effects_share_a_kernel_whatever_the_model():
    # no cushion friction: the cushion is a plain reflection for every model
    eff = Effects(cushion_friction=False)
    assert Models().resolved(eff) == ("coulomb/constant", "reflection")
    assert Models().resolved(Effects(spin=False)) == ("frictionless", "reflection")
    assert make_kernel("event", Effects.minimal(), Models()) is make_kernel("event", Effects.minimal(), Models())


def test_a_model_with_its_effect_off_shares_the_frictionless_kernel():
    """Where a model does not act its choice compiles nothing new: every
    registered model, with its own effect off (alone or with spin off),
    gets the default models' kernel."""
    for field, registry in REGISTRIES.items():
        for eff in (Effects(**{OWN_EFFECT[field]: False}), Effects(spin=False), Effects.minimal()):
            for name in registry:
                for kind in ("event", "step"):
                    assert make_kernel(kind, eff, Models(**{field: name}), True) is make_kernel(kind, eff, Models(), True)


CHECKED = [(m, "all") for m in CHOICES] + [(Models(), name) for name in sorted(EFFECTS) if name != "all"]


@pytest.mark.parametrize("models, name", CHECKED, ids=[f"{name}-{'-'.join(m.key())}" for m, name in CHECKED])
def test_every_model_runs_clean_shots_where_it_acts(models, name):
    eff = EFFECTS[name]
    for seed, layout in enumerate(("nine", "random")):
        s, table, p = _shots(8, seed, layout, eff.pockets)
        res = run_checked(s, table, p, "event", effects=eff, models=models)
        assert np.isfinite(res.state.pos).all() and (res.n_events > 0).all()


@pytest.mark.parametrize("models", CHOICES, ids=lambda m: "-".join(m.key()))
def test_every_model_runs_clean_shots_on_the_step_solver(models):
    s, table, p = _shots(8, 7)
    res = run_checked(s, table, p, "step", dt=1e-3, models=models)
    assert np.isfinite(res.state.pos).all()


@njit
def _no_friction(slip_speed, p):
    return 0.0


def test_a_new_friction_law_plugs_in_by_one_registry_entry(monkeypatch):
    """Coulomb friction with mu = 0 is the frictionless model: same shots,
    same final states, through a law registered at run time."""
    monkeypatch.setitem(ball_ball.FRICTION_LAWS, "zero", type("law", (), {"friction_coefficient": _no_friction}))
    s, table, p = _shots(16, 3)
    zero = simulate(s, table, p, models=Models(ball_ball_friction="zero"))
    frictionless = simulate(s, table, p, effects=Effects(ball_friction=False))
    default = simulate(s, table, p)
    np.testing.assert_array_equal(zero.state.pos, frictionless.state.pos)
    assert not np.array_equal(zero.state.pos, default.state.pos)


def test_cushion_models_share_one_interface(params):
    """Every cushion model takes and returns world-frame scalars: a head-on
    impact without spin sends the ball straight back (the reflection at
    exactly e_c times its speed) without sideways velocity or vertical-axis
    spin."""
    p = params.as_array()
    for resolve in [m.resolve for m in cushion.MODELS.values()] + [cushion.reflection.resolve]:
        vx, vy, wx, wy, wz = resolve(0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.5, p)
        assert vy == pytest.approx(0.5, rel=1e-12) if resolve is cushion.reflection.resolve else vy > 0.0
        assert abs(vx) < 1e-12 and wz == 0.0

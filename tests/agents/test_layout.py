"""The agents package's layout: light package imports, and the two old module
paths RLlib checkpoints written before the regrouping pickle (``agents/__init__.py``)."""
from __future__ import annotations

import pickle
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_package_imports_load_neither_torch_nor_ray():
    code = ("import sys; import agents, agents.interface, agents.sb3, agents.rllib, agents.evaluation; "
            "import agents.evaluation.entrants, agents.rllib.backend, agents.rllib.policy, agents.config; "
            "heavy = [m for m in ('torch', 'ray', 'stable_baselines3') if m in sys.modules]; "
            "assert not heavy, heavy")
    subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True)


def test_old_rllib_paths_unpickle_as_the_new_modules():
    import agents.rllib.backend as backend

    # what a pre-regrouping RLlib checkpoint's class_and_ctor_args.pkl holds: a class by its old module path
    old = pickle.loads(b"cagents.rllib_backend\nEpisodeFlagTotals\n.")
    assert old is backend.EpisodeFlagTotals
    assert sys.modules["agents.rllib_backend"] is backend
    assert backend.__spec__.name == "agents.rllib.backend"


def test_old_sampling_path_is_the_new_module():
    pytest.importorskip("ray.rllib")
    import agents.rllib.sampling as sampling

    assert pickle.loads(b"cagents.rllib_sampling\nMeanStdFilter\n.") is sampling.MeanStdFilter


@pytest.mark.parametrize("old", ["agents.training", "agents.sb3_vec_env", "agents.evaluation.evaluate",
                                 "agents.game_policies", "agents.baselines"])
def test_other_old_paths_are_gone(old):
    """Only the pickled RLlib paths have aliases: a stale import elsewhere fails."""
    import importlib

    with pytest.raises(ImportError):
        importlib.import_module(old)

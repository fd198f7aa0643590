"""Learned agents for the billiards tasks: training, evaluation, tuning (in
the repository, not in the wheel; scripts and pytest put the checkout on
``sys.path``).

- ``agents.interface``: the agent's side of the env, shared by both training
  backends and the evaluation: the ghost-ball features and action modes
  (``features``), the shot menu of ``action_mode: choice`` (``choice``), the
  one-player view of the two-player games (``game_view``);
- ``agents.sb3``: stable-baselines3: the ``VecEnv`` adapter over the native
  vector env (``vec_env``), training (``training``), checkpoints and resuming
  (``checkpoints``), a saved model as a policy (``policy``);
- ``agents.rllib``: Ray RLlib training (``backend``, ``sampling``), its
  saved policy (``policy``), the benchmark's rllib section (``bench``) and
  evaluation spread over a Ray cluster (``evaluation``);
- ``agents.evaluation``: the seeded evaluation harness (``harness``),
  policies by name (``policies``), trained models as match entrants
  (``entrants``);
- ``agents.config`` (the typed training config), ``agents.plotting``
  (learning curves, figures), ``agents.tuning`` (Optuna search),
  ``agents.benchmark`` (the agents' benchmark table).

Nothing is imported here: ``import agents`` loads neither torch nor ray.

Saved runs and the module paths in them: stable-baselines3 runs name no
``agents`` module (``model.zip`` holds the learning-rate schedule pickled by
value, ``vecnormalize.pkl`` SB3's own classes, checkpoints plain arrays and
JSON), so they load as they are. RLlib checkpoints do: their
``class_and_ctor_args.pkl`` files (read by RLlib's own
``Algorithm.from_checkpoint`` and the components' ``from_checkpoint``, not by
``RLlibPolicy.load`` or resuming, which rebuild from ``config.yaml``) name
``agents.rllib_sampling.MeanStdFilter`` and
``agents.rllib_backend.EpisodeFlagTotals`` when written before the
regrouping. ``OLD_MODULES`` keeps those two old paths importable as aliases
of the new modules (the same module objects), resolved only when something
imports an old path (unpickling such a file).
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys

# old module path (pickled in RLlib checkpoints written before the regrouping) -> its module now
OLD_MODULES = {
    "agents.rllib_backend": "agents.rllib.backend",
    "agents.rllib_sampling": "agents.rllib.sampling",
}


class _OldModuleAlias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports an old path of ``OLD_MODULES`` as the module that replaced it."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname in OLD_MODULES:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        return None  # a placeholder; exec_module swaps in the real module

    def exec_module(self, module):
        sys.modules[module.__name__] = importlib.import_module(OLD_MODULES[module.__name__])


if not any(isinstance(f, _OldModuleAlias) for f in sys.meta_path):
    sys.meta_path.append(_OldModuleAlias())

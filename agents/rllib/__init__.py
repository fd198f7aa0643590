"""The Ray side: training with Ray RLlib's PPO and evaluation on a Ray cluster.

- ``backend``: the RLlib training backend (``scripts/train.py --backend rllib``);
- ``sampling``: cheaper sampling inside the EnvRunners (lean observation filter, GC tuning);
- ``policy``: ``RLlibPolicy``, a trained RLlib run as a policy of the evaluation harness;
- ``evaluation``: the evaluation harness's batches and the search baseline's
  chunks as Ray tasks (``scripts/evaluate.py --backend ray``);
- ``bench``: the ``rllib`` section of ``scripts/benchmark.py``.

Imports nothing here: ray loads with the submodules that need it, when they
need it (``backend`` and ``policy`` import it inside their functions)."""

"""Evaluating policies and trained models, and entering them in matches.

- ``harness``: the seeded evaluation (``evaluate``, ``evaluate_policies``),
  results, tables and charts (``scripts/evaluate.py``);
- ``policies``: policies by name (the library's baselines, the lookahead,
  saved models) for the harness;
- ``entrants``: saved models as entrants of the two-player games beside the
  library's bots (``scripts/match.py``).
- ``benchmark``: the benchmark's scoring command (``python -m
  agents.evaluation.benchmark score``: a policy under ``billiards_env.benchmark``'s
  protocol, through the harness; docs/benchmark.md).

Imports nothing here (``entrants`` stays free of stable-baselines3 and torch
until a model is loaded)."""

"""The throughput benchmark behind ``scripts/benchmark.py`` (its command line:
``cli``), one job per module:

- ``options``: the run's options (``RunOptions``), the sections' names, the checkout;
- ``scenes``: the named, seeded shot sets (built by ``studies.scenes``);
- ``timing``: medians of repeated calls, the env layer's simulator clock;
- ``sections``: the measurements (solver, effects, models, env, cold, games; rllib is
  ``agents/rllib/bench.py``, above the library: scripts/benchmark.py plugs it in);
- ``report``: Markdown tables, the CSV history and its plot (history.png);
- ``trees``: git revisions, temporary worktrees, numba cache sharing;
- ``against``: this tree against another revision, a worker process per run.
"""


def main(argv=None):
    """``scripts/benchmark.py``'s command line (see ``cli``)."""
    from .cli import main as run
    return run(argv)

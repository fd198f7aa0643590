"""Simulator and environment throughput, and how it compares across commits:
the command line of ``billiards_env.studies.bench`` (``--help`` for its
usage; the logic is in that package's modules).

Imported (scripts/cpu_bench.py, scripts/compile_profile.py), it gives the
benchmark's ``SCENES`` and ``COLD_START_CODE``.
"""
from __future__ import annotations

import sys
from pathlib import Path

if __name__ == "__main__":
    # this checkout first: its billiards_env, and agents/ (the rllib and games sections)
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from billiards_env.studies.bench import main
    from billiards_env.studies.bench.sections import plug_in

    def _rllib_rows(opts):
        from agents.rllib.bench import rllib_rows
        return rllib_rows(opts)

    def _rllib_markdown(rows):
        from agents.rllib.bench import rllib_markdown
        return rllib_markdown(rows)

    plug_in("rllib", _rllib_rows, _rllib_markdown)
    main()
else:
    from billiards_env.studies.bench.scenes import SCENES  # noqa: F401
    from billiards_env.studies.bench.sections import COLD_START_CODE  # noqa: F401

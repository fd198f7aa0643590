"""Simulator and environment throughput, and how it compares across commits:
the command line of ``billiards_env.studies.bench`` (``--help`` for its
usage; the logic is in that package's modules).

``SCENES`` and ``COLD_START_CODE`` are importable from here too
(scripts/cpu_bench.py, scripts/compile_profile.py).
"""
from __future__ import annotations

import sys
from pathlib import Path

from billiards_env.studies.bench.scenes import SCENES  # noqa: F401
from billiards_env.studies.bench.sections import COLD_START_CODE  # noqa: F401

if __name__ == "__main__":
    # this checkout first: its billiards_env, and agents/ (the rllib and games sections)
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from billiards_env.studies.bench import main
    main()

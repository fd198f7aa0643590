"""Where a script writes when it is given no ``--out``: a new folder of its
own, ``runs/<script>/<timestamp>/`` under the checkout (``/runs/`` is
git-ignored), never the committed ``results/``. A command that regenerates a
committed table names its folder: ``--out results/...``."""
from __future__ import annotations

import datetime
from pathlib import Path

RUNS = "runs"  # the checkout's git-ignored folder of runs (.gitignore: /runs/)
MAX_PER_SECOND = 1000  # runs of one script started in the same second, each its own folder (far more than happen)


def run_folder(root: Path, script: str) -> Path:
    """A new, empty folder ``root/runs/<script>/<YYYYmmdd-HHMMSS>`` (with
    ``-2``, ``-3``, ... when a run of the same second has it), created."""
    stamp = datetime.datetime.now().strftime("%Y%m%d-%H%M%S")
    parent = Path(root) / RUNS / script
    parent.mkdir(parents=True, exist_ok=True)
    for k in range(1, MAX_PER_SECOND + 1):
        path = parent / (stamp if k == 1 else f"{stamp}-{k}")
        try:
            path.mkdir()
            return path
        except FileExistsError:
            continue
    raise RuntimeError(f"no free run folder for {stamp} in {parent}")

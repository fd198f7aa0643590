import importlib.util
import os
from pathlib import Path

import numpy as np
import pytest

from billiards_env.physics import Effects, PhysicsParams, Table, random_placement, simulate, strike_velocity

MAX_WORKERS = 8  # `pytest -n auto`: at most this many workers (each compiles the kernel variants its tests use)


def pytest_xdist_auto_num_workers(config):
    """pytest-xdist's worker count for ``-n auto``: one per CPU, at most ``MAX_WORKERS``."""
    return max(1, min(os.cpu_count() or 1, MAX_WORKERS))


@pytest.fixture(scope="session", autouse=True)
def _compiled_kernels():
    """Compile (or load from the disk cache) the kernel variants the tests
    use, so that per-shot wall-time bounds measure simulation, not compilation."""
    P = PhysicsParams.standard()
    T = Table.pool(9)
    s = strike_velocity(random_placement(T, P, 2, seed=0), 0.3, 0.5, params=P)
    for eff in (None, Effects.minimal()):
        simulate(s, T, P, solver="event", effects=eff, diagnostics=True)
        simulate(s, T, P, solver="step", dt=1e-3, effects=eff, diagnostics=True)


@pytest.fixture(scope="session")
def params():
    return PhysicsParams.standard()


@pytest.fixture(scope="session")
def pool():
    return Table.pool(9)


@pytest.fixture(scope="session")
def big_box():
    """A pocketless 20 m x 20 m table: no cushion within reach of a test shot."""
    return Table.pocketless(20.0, 20.0)


@pytest.fixture(scope="session")
def load_script():
    """``load_script(name)``: the module of ``scripts/<name>.py``, loaded from its file (scripts/ is not a
    package), for tests that call a script's functions or its ``main`` in this process."""
    root = Path(__file__).resolve().parents[1] / "scripts"

    def load(name: str):
        spec = importlib.util.spec_from_file_location(name, root / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        return mod
    return load

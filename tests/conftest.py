import contextlib
import importlib.util
import logging
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from billiards_env.physics import Effects, PhysicsParams, Table, random_placement, simulate, strike_velocity

MAX_WORKERS = 8  # `pytest -n auto`: at most this many workers (each compiles the kernel variants its tests use)


def pytest_xdist_auto_num_workers(config):
    """pytest-xdist's worker count for ``-n auto``: one per CPU, at most ``MAX_WORKERS``."""
    return max(1, min(os.cpu_count() or 1, MAX_WORKERS))


COLD_CACHE_NOTE = ("billiards_env: the simulator's kernels compile on first use (20-160 s each) and are cached on "
                   "disk: on a cold cache the first tests take several minutes")


def pytest_sessionstart(session):
    """One line before anything runs (in the main process, with -q and -n too): a cold numba cache
    otherwise keeps the suite silent for its first minutes."""
    if not hasattr(session.config, "workerinput"):  # not an xdist worker
        reporter = session.config.pluginmanager.get_plugin("terminalreporter")
        if reporter is not None:
            reporter.write_line(COLD_CACHE_NOTE)


@contextlib.contextmanager
def _compile_messages_shown(config):
    """The kernels' compile messages (logger ``billiards_env.physics.compile``) on the terminal as they
    happen, past pytest's capture (shown with -n 0; xdist workers' output is not)."""
    capture = config.pluginmanager.get_plugin("capturemanager")
    log = logging.getLogger("billiards_env.physics.compile")
    with capture.global_and_fixture_disabled() if capture else contextlib.nullcontext():
        handler = logging.StreamHandler(sys.stderr)  # the real stderr while capture is off
        log.addHandler(handler)
        try:
            yield
        finally:
            log.removeHandler(handler)


@pytest.fixture(scope="session", autouse=True)
def _compiled_kernels(request):
    """Compile (or load from the disk cache) the kernel variants the tests
    use, so that per-shot wall-time bounds measure simulation, not compilation."""
    P = PhysicsParams.standard()
    T = Table.pool(9)
    s = strike_velocity(random_placement(T, P, 2, seed=0), 0.3, 0.5, params=P)
    with _compile_messages_shown(request.config):
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

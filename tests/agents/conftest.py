"""Shared by the tests of agents/: the Ray requirement."""
from __future__ import annotations

import importlib
import os

import pytest


@pytest.fixture(scope="session")
def ray_module():
    """``ray`` with ``ray.rllib`` and ``ray.cluster_utils``, or the test skips
    (saying how to install it); under CI (``CI`` set) it fails instead, since
    CI installs the ``ray`` extra."""
    try:
        ray = importlib.import_module("ray")
        importlib.import_module("ray.rllib")
        importlib.import_module("ray.cluster_utils")
    except ImportError:
        msg = "ray[rllib] is not installed (pip install -e '.[ray]')"
        if os.environ.get("CI"):
            pytest.fail(msg + " (required under CI)")
        pytest.skip(msg)
    return ray

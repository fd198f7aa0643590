"""Every registered id plays as its recorded fingerprint says (billiards_env/testing/fingerprints.py).

A failure here means an id's behaviour changed under the same version: bump the id's version, record what
changed in docs/versions.md, and regenerate tests/envs/env_fingerprints.json with
``python -m billiards_env.testing.fingerprints --write``."""
from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.error import DeprecatedEnv

from billiards_env.testing import fingerprints as F

RECORDED = F.load()
IDS = F.registered_ids()


def test_every_registered_id_is_recorded():
    assert sorted(RECORDED["ids"]) == sorted(IDS), (
        "the fingerprints file and the registered ids differ: a new id needs its fingerprint "
        "(python -m billiards_env.testing.fingerprints --write); a removed id, its entry removed")
    assert RECORDED["precision"] == F.PRECISION and RECORDED["seed"] == F.SEED
    assert (RECORDED["single_steps"], RECORDED["vec_envs"], RECORDED["vec_steps"]) == (
        F.SINGLE_STEPS, F.VEC_ENVS, F.VEC_STEPS), "the fingerprints were taken with other settings: regenerate"


@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("kind", ["single", "vector"])
def test_fingerprint(env_id, kind):
    got = F.fingerprint_single(env_id) if kind == "single" else F.fingerprint_vector(env_id)
    want = RECORDED["ids"].get(env_id, {}).get(kind)
    assert got == want, f"{env_id} ({kind} entry point): {F.CHANGED}"


def test_hash_ignores_ulps_and_sees_changes():
    def h(x):
        hh = F._Hasher()
        hh.add("x", np.asarray(x))
        return hh.hexdigest()

    x = np.array([0.123456789, -2.5e-3, 1.0, 0.0])
    assert h(x) == h(x * (1 + 4e-16)) == h(x + 1e-12)     # ulp-level differences between CPUs
    assert h(x) != h(x + 2e-6)                            # a change of behaviour
    assert h(np.float32(0.5)) == h(np.float64(0.5))       # the dtype's width is not behaviour
    assert h(np.array([np.nan])) != h(np.array([0.0]))


@pytest.mark.parametrize("env_id", IDS)
def test_older_versions_are_deprecated_naming_the_current_id(env_id):
    """Every older version (-v0; -v1 of an id now at -v2) played other behaviour (docs/versions.md): making it
    fails with Gymnasium's DeprecatedEnv, which names the current id; it never silently gives the current one."""
    stem, version = env_id.rsplit("-v", 1)
    assert int(version) >= 1
    for old in (f"{stem}-v{k}" for k in range(int(version))):
        for make in (lambda: gym.make(old),
                     lambda: gym.make_vec(old, num_envs=2, vectorization_mode="vector_entry_point"),
                     lambda: gym.make(f"billiards_env:{old}")):
            with pytest.raises(DeprecatedEnv, match=f"`{env_id}`"):
                make()

"""SB3's per-env infos as a view of the vector info (agents.sb3.infos)."""
from __future__ import annotations

import pickle

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

import gymnasium as gym  # noqa: E402

import billiards_env  # noqa: E402,F401
from agents.sb3.infos import VecInfos  # noqa: E402


def _eager(info: dict, n: int, j: int) -> dict:
    """Row ``j`` as a plain dict, key by key (the oracle: what SB3's per-env dicts hold)."""
    row = {}
    for key, value in info.items():
        if key.startswith("_"):
            continue
        mask = info.get("_" + key)
        if mask is not None and not mask[j]:
            continue
        if isinstance(value, dict):
            row[key] = _eager(value, n, j)
        elif isinstance(value, np.ndarray) and value.ndim >= 1 and len(value) == n:
            row[key] = value[j].tolist()
        else:
            row[key] = value
    return row


def _game_info(n: int = 16, steps: int = 3) -> dict:
    env = gym.make_vec("Billiards-NineBall2P-v1", num_envs=n, vectorization_mode="vector_entry_point",
                       autoreset_mode="same_step", opponent="ghost")
    env.reset(seed=3)
    env.action_space.seed(3)
    for _ in range(steps):
        *_, info = env.step(env.action_space.sample())
    env.close()
    return info


def test_rows_equal_the_per_env_dicts_of_a_game_step():
    info, n = _game_info(), 16
    infos = VecInfos(info, n)
    assert len(infos) == n and len(info) > 20
    for j, row in enumerate(infos):
        want = _eager(info, n, j)
        assert row == want and dict(row) == want and set(row) == set(want) and len(row) == len(want)
        assert infos[j] == want and infos[j - n] == want
        for key in want:
            assert key in row and row.get(key) == want[key] and row[key] == want[key]
    assert infos[2:5] == [infos[2], infos[3], infos[4]]
    with pytest.raises(IndexError):
        infos[n]


def test_masks_absent_keys_and_broadcast_values():
    info = {"a": np.array([1, 2, 3]), "_a": np.array([True, False, True]),
            "terms": {"x": np.array([0.5, 0.6, 0.7])}, "scalar": 4, "short": np.array([9, 9])}
    infos = VecInfos(info, 3)
    assert set(infos[1]) == {"terms", "scalar", "short"} and set(infos[0]) == {"a", "terms", "scalar", "short"}
    assert "a" not in infos[1] and infos[1].get("a", "none") == "none" and infos[2]["a"] == 3
    with pytest.raises(KeyError):
        infos[1]["a"]
    assert infos[0]["scalar"] == 4 and infos[0]["short"] is info["short"]
    assert infos[0]["terms"] == {"x": 0.5}


def test_writes_and_deletions_stay_in_the_row_and_leave_the_arrays_alone():
    info = {"a": np.arange(4), "b": np.arange(4) * 2, "terms": {"x": np.arange(4) * 0.5}}
    infos = VecInfos(info, 4)
    row = infos[2]
    row["terminal_observation"] = np.zeros(3)
    assert infos[2] is row and infos[2] is infos[2]
    assert infos[2]["terminal_observation"].shape == (3,) and "terminal_observation" not in infos[1]
    assert infos[2]["a"] == 2 and infos[2]["terms"] == {"x": 1.0} and dict(infos[2]["terms"]) == {"x": 1.0}
    assert row == {"a": 2, "b": 4, "terms": {"x": 1.0}, "terminal_observation": row["terminal_observation"]}
    infos[1]["terms"]["x"] = 9.0              # a write into a nested info of an unwritten row stays too
    assert infos[1]["terms"]["x"] == 9.0 and infos[0]["terms"]["x"] == 0.0
    del row["a"]
    assert "a" not in infos[2] and "a" in infos[1] and set(infos[2]) == {"b", "terms", "terminal_observation"}
    with pytest.raises(KeyError):
        del row["a"]
    row["a"] = "back"
    assert infos[2]["a"] == "back" and len(infos[2]) == 4
    infos[3] = {"b": 1}
    assert infos[3] == {"b": 1} and list(infos)[3] == {"b": 1}
    assert info["a"][2] == 2 and info["terms"]["x"][1] == 0.5  # the arrays are not written to


def test_concat_pickle_and_column_follow_env_order():
    rng = np.random.default_rng(0)
    parts_info = [{"to_move": rng.integers(0, 2, 5), "shooter": rng.integers(0, 2, 5)} for _ in range(2)]
    parts = [VecInfos(p, 5) for p in parts_info]
    parts[1][0]["TimeLimit.truncated"] = False  # a written row moves with its part
    whole = VecInfos.concat([pickle.loads(pickle.dumps(p)) for p in parts])
    assert len(whole) == 10
    flat = [_eager(p, 5, j) for p in parts_info for j in range(5)]
    flat[5]["TimeLimit.truncated"] = False
    assert list(whole) == flat
    np.testing.assert_array_equal(whole.column("to_move"), np.concatenate([p["to_move"] for p in parts_info]))
    whole[7]["shooter"] = 7
    assert whole.column("shooter")[7] == 7 and parts_info[1]["shooter"][2] != 7
    with pytest.raises(KeyError):
        whole.column("missing")
    masked = VecInfos({"a": np.arange(3), "_a": np.array([True, False, True])}, 3)
    with pytest.raises(KeyError):
        masked.column("a")

"""A bot written against the documented API only (docs/bots.md's own example,
not a library module) plays a match through scripts/match.py and a game
through PettingZoo's AEC env; bad bots are refused with a clear error."""
import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def doc_bot_source() -> str:
    text = (ROOT / "docs" / "bots.md").read_text()
    section = text.split("## A bot from scratch", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


@pytest.fixture()
def bot_dir(tmp_path, monkeypatch):
    (tmp_path / "my_bots.py").write_text(doc_bot_source())
    monkeypatch.syspath_prepend(str(tmp_path))
    sys.modules.pop("my_bots", None)
    return tmp_path


def test_the_documented_bot_is_short():
    assert len(doc_bot_source().strip().splitlines()) < 50


def test_user_bot_enters_a_match_through_the_script(bot_dir):
    out = subprocess.run([sys.executable, str(ROOT / "scripts" / "match.py"), "--game", "nine_ball", "--policies",
                          "my_bots:planner", "ghost", "--racks", "3", "--noise", "tournament", "--max-shots", "40",
                          "--out", str(bot_dir / "out")], capture_output=True, text=True, timeout=600, cwd=bot_dir)
    assert out.returncode == 0, out.stderr[-3000:]
    doc = json.loads((bot_dir / "out" / "nine_ball_tournament.json").read_text())
    (pairing,) = doc["pairings"]
    assert pairing["a"] == "my_bots:planner" and pairing["games"] == 6
    assert {r["name"] for r in doc["ratings"]} == {"my_bots:planner", "ghost"}


def test_user_bot_plays_through_the_aec_env(bot_dir):
    from billiards_env.envs.games.aec import EightBallAECEnv
    from my_bots import Planner
    aec = EightBallAECEnv(max_shots=30)
    aec.reset(seed=0)
    bots = {agent: Planner(seed=i, k=8) for i, agent in enumerate(aec.possible_agents)}
    shots = 0
    for agent in aec.agent_iter():
        obs, reward, terminated, truncated, info = aec.last()
        if terminated or truncated:
            aec.step(None)
            continue
        view = aec.bot_view()
        assert view.n == 1 and view.to_move[0] == aec.possible_agents.index(agent)
        assert not view.pos.flags.writeable  # the view is read-only
        aec.step(aec.bot_action(bots[agent].act(view)))
        shots += 1
    assert 1 <= shots <= 30


def test_user_bot_as_the_versus_opponent(bot_dir):
    import gymnasium as gym

    import billiards_env  # noqa: F401
    from my_bots import Planner
    env = gym.make_vec("Billiards-NineBall2P-v1", num_envs=4, vectorization_mode="vector_entry_point",
                       opponent=Planner(seed=1, k=4))
    env.reset(seed=0)
    for _ in range(3):
        env.step(np.zeros((4, 8), dtype=np.float32))
    env2 = gym.make("Billiards-NineBall2P-v1", opponent="my_bots:planner")
    env2.reset(seed=0)
    env2.step(np.zeros(8, dtype=np.float32))


def test_bad_bots_are_named():
    import gymnasium as gym

    import billiards_env  # noqa: F401
    from billiards_env.bots import make_bot
    with pytest.raises(ValueError, match="opponent must be a bot name"):
        gym.make("Billiards-NineBall2P-v1", opponent=42)
    with pytest.raises(ValueError, match="cannot import module 'no_such_bots'"):
        make_bot("no_such_bots:x")
    with pytest.raises(ValueError, match="unknown bot 'gost'"):
        make_bot("gost")


def test_a_bad_plan_is_refused_before_the_shot():
    from billiards_env.bots import ShotPlan
    from billiards_env.envs.games import GameConfig, GameCore
    from billiards_env.physics.strike import Shots
    core = GameCore(GameConfig(game="nine_ball"), 2)
    core.reset_tables([0, 1], [0, 0])
    before = core.state.pos.copy()
    with pytest.raises(ValueError, match="miscue disc"):
        core.actions_of(ShotPlan.of(Shots(0.0, 2.0, 0.6, 0.0), placement=np.full((2, 2), np.nan)), [0, 1])
    with pytest.raises(ValueError, match="speed must lie in"):
        core.actions_of(ShotPlan.of(Shots(0.0, -1.0, 0.0, 0.0), placement=np.full((2, 2), np.nan)), [0, 1])
    assert np.array_equal(core.state.pos, before)

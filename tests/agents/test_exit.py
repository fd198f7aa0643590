"""Expert Iteration (agents.exit): the quick mode of its command, a resumed run against an uninterrupted one, the
torch network against its numpy export, the search's policy target, the config, and shipping without torch."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from agents.exit import QUICK, ExItConfig
from agents.exit.fit import Stop
from agents.exit.loop import load_state, run_exit, ship
from billiards_env.bots.learned import proposal_net as PN
from billiards_env.bots.planner import proposals as PR
from billiards_env.rules import DEFAULT_GAME

ROOT = Path(__file__).resolve().parents[2]
QUIET = lambda s: None  # noqa: E731


def quick() -> ExItConfig:
    return ExItConfig(game=DEFAULT_GAME).replace(**QUICK)


def test_quick_command_runs_rounds_and_the_distillation(tmp_path):
    run = tmp_path / "q"
    res = subprocess.run([sys.executable, "scripts/expert_iteration.py", "--quick", "--run", str(run)], cwd=ROOT,
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr[-3000:]
    state = json.loads((run / "exit.json").read_text())
    assert state["round"] == 2 and [s["stem"] for s in state["snapshots"]] == ["round_001", "round_002"]
    assert state["fast"] is not None and state["decisions"] > 0
    assert len(list((run / "data").rglob("job_*.npz"))) == 2
    for stem in ("round_001", "round_002", "fast"):
        net, card = PN.load(run / "snapshots" / stem)
        assert card["game"] == DEFAULT_GAME and net.turns > 0
    res = subprocess.run([sys.executable, "scripts/expert_iteration.py", "--quick", "--run", str(run)], cwd=ROOT,
                         capture_output=True, text=True, timeout=600)
    assert res.returncode != 0 and "--resume" in res.stderr          # a finished run is not overwritten


def test_a_resumed_run_ends_with_the_networks_of_an_uninterrupted_one(tmp_path):
    """Stopped in round 1's fit after its first epoch, then in the distillation, and resumed each time: the
    same snapshots (weight hashes), the same student and the same decision count as a run that went through; a
    run resumed past its config's rounds distils its student again."""
    cfg = quick()
    whole = run_exit(tmp_path / "whole", cfg, log=QUIET)
    with pytest.raises(Stop):
        run_exit(tmp_path / "parts", cfg, log=QUIET, stop={"round": 1, "epoch": 1})
    assert load_state(tmp_path / "parts")["round"] == 1
    with pytest.raises(Stop):
        run_exit(tmp_path / "parts", resume=True, log=QUIET, stop={"distill": 1})
    parts = run_exit(tmp_path / "parts", resume=True, log=QUIET)
    assert [s["sha256"] for s in parts["snapshots"]] == [s["sha256"] for s in whole["snapshots"]]
    assert parts["fast"]["sha256"] == whole["fast"]["sha256"] and parts["decisions"] == whole["decisions"]
    with pytest.raises(FileExistsError, match="--resume"):
        run_exit(tmp_path / "whole", cfg, log=QUIET)
    more = run_exit(tmp_path / "whole", resume=True, rounds=3, log=QUIET)     # past the config: distilled again
    assert more["round"] == 3 and more["fast"]["round"] == 3 and more["fast"]["sha256"] != whole["fast"]["sha256"]


def test_the_numpy_network_computes_the_torch_networks_function():
    torch = pytest.importorskip("torch")
    from agents.exit.model import TorchProposalNet
    rng = np.random.default_rng(0)
    G, F, T, V, S = 11, PN.F, 3, 4, 7
    g, x = rng.normal(size=(5, G)).astype(np.float32), rng.normal(size=(5, S, F)).astype(np.float32)
    stats = (g.mean(0), g.std(0) + 0.5, x.reshape(-1, F).mean(0), x.reshape(-1, F).std(0) + 0.5)
    torch.manual_seed(0)
    m = TorchProposalNet(G, F, T, V, ((8,), (9, 6), (5,)), stats)
    with torch.no_grad():
        for p in m.parameters():
            p.copy_(torch.randn_like(p) * 0.3)      # the heads start at zero: give them weights
        out_t, z = m(torch.as_tensor(g), torch.as_tensor(x))
    net = m.to_numpy()
    out, v = net.forward(g, x)
    np.testing.assert_allclose(out, out_t.numpy(), rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(v, torch.sigmoid(z).numpy(), rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(net.value(g), v, rtol=1e-6)
    back = TorchProposalNet.from_numpy(net).to_numpy()
    for a, b in zip(net.arrays().values(), back.arrays().values()):
        np.testing.assert_array_equal(a, b)


def test_the_policy_target_favours_the_candidate_the_search_found_better():
    """Two candidates of equal prior on one table, sampled alike, the first with the higher mean: the completed-Q
    target gives it more mass; target and rest sum to 1; with ``visits`` the target is the sample shares."""
    c = dict(safe=np.zeros(3, bool))
    res = PR.SearchResult(c=c, li=np.zeros(3, np.int64), v0=np.array([0.6, 0.5, 0.4]), est=np.array([0.6, 0.5, 0.4]),
                          mean=np.array([0.8, 0.3, np.nan]), count=np.array([24, 24, 0]),
                          logp=np.log(np.array([0.3, 0.3, 0.3])), rest_logp=np.log(np.array([0.1])),
                          best=np.array([0]), value=np.array([0.8]))
    y, rest = PR.targets(res, PR.SearchBudget())
    assert y[0] > y[1] and y[0] > y[2] and abs(y.sum() + rest[0] - 1) < 1e-9
    y, rest = PR.targets(res, PR.SearchBudget(target="visits"))
    np.testing.assert_allclose(y, [0.5, 0.5, 0.0])
    assert rest[0] == 0


def test_config_round_trips_and_names_bad_keys(tmp_path):
    cfg = ExItConfig.load(ROOT / "configs" / f"exit_{DEFAULT_GAME}.yaml")
    assert ExItConfig.from_dict(cfg.to_dict()) == cfg and cfg.threads == 1
    assert isinstance(cfg.play, PR.SearchBudget) and cfg.expert.explore and not cfg.play.explore
    with pytest.raises(ValueError, match="unknown Expert Iteration config keys"):
        ExItConfig.from_dict(dict(rounds=2, epochz=3))
    with pytest.raises(ValueError, match="unknown net keys"):
        ExItConfig.from_dict(dict(net=dict(hidden=[3])))
    with pytest.raises(ValueError, match="Expert Iteration trains"):
        ExItConfig(game="three_cushion")


# plays a shipped card's fast player and search by name-free construction (root=) twice from one seed in a process
# where importing torch fails; prints both runs' winners and shot counts
NO_TORCH = r'''
import sys, importlib.abc, json
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] == "torch":
            raise ImportError(f"blocked: {name}")
sys.meta_path.insert(0, Block())
from billiards_env.bots.learned.proposal_bot import FAST, SEARCH, CARD, ProposalPlayer
from billiards_env.studies.matches import play_pairing
out = {}
for name, budget in ((FAST, None), (SEARCH, CARD)):
    runs = [play_pairing(ProposalPlayer(name, seed=3, root=%r, budget=budget), "ghost", %r, n_racks=2, seed=11,
                         noise="tournament", max_shots=30) for _ in range(2)]
    out[name] = [[r.winner.tolist(), r.shots.tolist()] for r in runs]
assert "torch" not in sys.modules
print(json.dumps(out))
'''


def test_shipped_networks_play_without_torch_identically_twice(tmp_path):
    run_exit(tmp_path / "run", quick(), log=QUIET)
    stems = ship(tmp_path / "run", root=tmp_path / "cards", log=QUIET)
    assert [s.name for s in stems] == ["exit-search", "exit-fast"]
    card = json.loads(stems[1].with_suffix(".json").read_text())
    assert len(card["break"]) == 4 and card["training"]["rounds"] == 2 and card["budget"] is None
    with np.load(stems[1].with_suffix(".npz"), allow_pickle=False) as z:
        assert all(z[k].dtype == np.float32 for k in z.files)
    res = subprocess.run([sys.executable, "-c", NO_TORCH % (str(tmp_path / "cards"), DEFAULT_GAME)], cwd=ROOT,
                         capture_output=True, text=True, timeout=600,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert res.returncode == 0, res.stderr[-3000:]
    out = json.loads(res.stdout.strip().splitlines()[-1])
    for name, (first, second) in out.items():
        assert first == second, name
        assert sum(first[1]) > 4, name

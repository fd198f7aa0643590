"""scripts/tune.py in quick mode: a study in a temporary SQLite file, resumed."""
import json
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("optuna")
ROOT = Path(__file__).resolve().parents[2]


def _run(tmp_path, trials):
    cmd = [sys.executable, str(ROOT / "scripts" / "tune.py"), "--quick", "--trials", str(trials),
           "--run-dir", str(tmp_path / "study")]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads((tmp_path / "study" / "study_summary.json").read_text())


@pytest.mark.slow  # several training runs in subprocesses: about a minute
def test_quick_study_runs_and_resumes(tmp_path):
    import optuna

    first = _run(tmp_path, 2)
    assert first["finished_trials"] == 2 and first["finished_before_this_run"] == 0
    assert (tmp_path / "study" / "study.db").exists()
    # the same study resumed in-process (no second interpreter start-up), one trial more
    from agents.tuning import Trials, tune
    fixed = ("n_envs=64", "policy.net_arch=[16]", "ppo.n_steps=8", "ppo.batch_size=256")
    second = tune("Billiards-PotOne-v1", "ppo", 3, tmp_path / "study",
                  trials=Trials(steps=2048, n_evals=2, eval_episodes=50, fixed=fixed, startup_trials=2))
    assert second["finished_before_this_run"] == 2 and second["finished_trials"] == 3
    study = optuna.load_study(study_name=second["study"], storage=second["storage"])
    assert len(study.trials) == 3
    assert all(0.0 <= t.value <= 1.0 for t in study.trials if t.value is not None)
    # every trial evaluated on held seeds at its intermediate points
    assert all(t.intermediate_values for t in study.trials)
    best = second["best"]
    assert (tmp_path / "study" / "best_overrides.yaml").read_text().count("- ") == len(best["overrides"])
    # a study over another config's block: its trials keep that block's env options
    direct = tune("Billiards-PotOne-v1", "ppo", 1, tmp_path / "direct",
                  trials=Trials(steps=2048, n_evals=2, eval_episodes=50, fixed=fixed, startup_trials=1),
                  config=ROOT / "configs" / "ppo_direct.yaml")
    assert direct["finished_trials"] == 1
    import yaml
    trial_cfg = yaml.safe_load((tmp_path / "direct" / "trials" / "0000" / "config.yaml").read_text())
    assert trial_cfg["action_mode"] == "direct" and trial_cfg["env_kwargs"]["aim"] == "impact"

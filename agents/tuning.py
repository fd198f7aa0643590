"""Hyper-parameter search with Optuna (what ``scripts/tune.py`` runs).

One trial = one training run (``agents.sb3.training.train``) with hyper-
parameters drawn by the TPE sampler over the search space of its algorithm
(``SPACES``), given as dotted overrides of the env's block in
``configs/<algo>.yaml``. During the run the policy is evaluated on held seeds
(``HeldOutEvaluation``) ``n_evals`` times; each evaluation is reported to
the study, and the median pruner stops trials below the median of earlier
trials at the same step. A trial's value is its last held-seed success rate.

The study lives in an Optuna storage: by default an SQLite file in the run
directory (nothing to set up), or any database URL Optuna accepts
(``postgresql://...``, ``mysql://...``) so many processes or machines can
work on one study. Studies resume: ``n_trials`` is the number of finished
(complete or pruned) trials wanted, and a rerun with the same storage and
study name only runs the missing ones.
"""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from .config import load_config

# hyper-parameter -> (kind, choices or (low, high)); kind: cat | log | float | int
SPACES = {
    "ppo": {
        "n_envs": ("cat", [256, 512, 1024]),
        "ppo.n_steps": ("cat", [2, 4, 8]),
        "ppo.batch_size": ("cat", [512, 1024, 2048]),
        "ppo.n_epochs": ("int", (2, 10)),
        "ppo.learning_rate": ("log", (1e-4, 3e-3)),
        "lr_schedule": ("cat", ["constant", "linear"]),
        "policy.net_arch": ("cat", ["[64, 64]", "[128, 128]", "[256, 256]"]),
        "policy.log_std_init": ("float", (-2.5, -1.0)),
    },
    "sac": {
        "sac.learning_rate": ("log", (1e-4, 3e-3)),
        "sac.batch_size": ("cat", [256, 512, 1024]),
        "sac.gradient_steps": ("int", (1, 8)),
        "sac.tau": ("log", (0.002, 0.05)),
        "policy.net_arch": ("cat", ["[64, 64]", "[256, 256]"]),
    },
}


def sample_overrides(trial, algo: str, fixed: tuple = ()) -> list[str]:
    """Dotted overrides for one trial (keys of ``fixed`` overrides are not sampled)."""
    fixed_keys = {f.split("=", 1)[0] for f in fixed}
    out, lr_key, schedule = [], None, "constant"
    for key, (kind, rng) in SPACES[algo].items():
        if key in fixed_keys:
            continue
        if kind == "cat":
            v = trial.suggest_categorical(key, rng)
        elif kind == "log":
            v = trial.suggest_float(key, *rng, log=True)
        elif kind == "float":
            v = trial.suggest_float(key, *rng)
        else:
            v = trial.suggest_int(key, *rng)
        if key == "lr_schedule":
            schedule = v
            continue
        if key.endswith("learning_rate"):
            lr_key = key
        out.append(f"{key}={v}")
    if schedule == "linear" and lr_key is not None:
        out = [f"{lr_key}=lin_{o.split('=', 1)[1]}" if o.startswith(lr_key + "=") else o for o in out]
    return out + list(fixed)


def create_study(storage: str, study_name: str, seed: int = 0, startup_trials: int = 5, warmup_evals: int = 1):
    """A maximising study with the TPE sampler and the median pruner, created
    or loaded from ``storage``."""
    import optuna

    return optuna.create_study(
        study_name=study_name, storage=storage, direction="maximize", load_if_exists=True,
        sampler=optuna.samplers.TPESampler(seed=seed, n_startup_trials=startup_trials),
        pruner=optuna.pruners.MedianPruner(n_startup_trials=startup_trials, n_warmup_steps=warmup_evals))


def finished_trials(study) -> list:
    import optuna
    done = (optuna.trial.TrialState.COMPLETE, optuna.trial.TrialState.PRUNED)
    return [t for t in study.trials if t.state in done]


def objective_fn(env_id: str, algo: str, run_dir: Path, steps: int, n_evals: int, eval_episodes: int,
                 fixed: tuple = (), config_path=None):
    import optuna

    from .sb3.training import train

    def objective(trial) -> float:
        over = sample_overrides(trial, algo, fixed)
        base = [f"train.total_timesteps={steps}", f"train.eval_every={max(steps // n_evals, 1)}",
                f"train.eval_every_episodes={eval_episodes}", "train.eval_episodes=0",
                "train.progress_bar=false", "train.tensorboard=false", "train.checkpoint_every=0"]
        cfg = load_config(config_path, env_id, base + over, algo=algo)
        trial.set_user_attr("overrides", over)
        n_reports = [0]

        def report(row) -> bool:
            if row["timesteps"] == 0:
                return True
            trial.report(row["success_rate"], n_reports[0])
            n_reports[0] += 1
            return not trial.should_prune()

        summary = train(cfg, run_dir / "trials" / f"{trial.number:04d}", "tune", report=report)
        held = summary["held_out"]
        trial.set_user_attr("train_s", summary["train_wall_s"])
        trial.set_user_attr("timesteps", summary["timesteps"])
        if summary["timesteps"] < steps and trial.should_prune():
            raise optuna.TrialPruned()
        return float(held["held_success"])

    return objective


@dataclasses.dataclass(frozen=True)
class Trials:
    """How each trial of a study runs: ``steps`` env steps, ``n_evals``
    held-seed evaluations of ``eval_episodes`` tables (the pruner's
    intermediate values), the sampler's ``seed`` and ``startup_trials``
    (random trials before TPE), and ``fixed`` dotted overrides every trial keeps."""

    steps: int = 200_000
    n_evals: int = 5
    eval_episodes: int = 1000
    seed: int = 0
    fixed: tuple = ()
    startup_trials: int = 5


def tune(env_id: str, algo: str, n_trials: int, run_dir, storage: str | None = None, study_name: str | None = None,
         trials: Trials = Trials(), config=None) -> dict:
    """Run the study until it has ``n_trials`` finished trials (each as
    ``trials`` says), each starting from the env's block in ``config``
    (default ``configs/<algo>.yaml``); write ``study_summary.json``,
    ``best_overrides.yaml`` and ``importance.png`` (when at least two trials
    completed) into ``run_dir``."""
    import optuna

    steps, n_evals, eval_episodes, seed, fixed, startup_trials = (trials.steps, trials.n_evals, trials.eval_episodes,
                                                                  trials.seed, trials.fixed, trials.startup_trials)
    run_dir = Path(run_dir)
    run_dir.mkdir(parents=True, exist_ok=True)
    storage = storage or f"sqlite:///{(run_dir / 'study.db').resolve()}"
    study_name = study_name or f"{algo}_{env_id}"
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    study = create_study(storage, study_name, seed, startup_trials)
    before = len(finished_trials(study))
    missing = max(n_trials - before, 0)
    if missing:
        study.optimize(objective_fn(env_id, algo, run_dir, steps, n_evals, eval_episodes, tuple(fixed), config),
                       n_trials=missing)
    return write_summary(study, run_dir, storage, resumed_with=before)


def write_summary(study, run_dir: Path, storage: str, resumed_with: int = 0) -> dict:
    import optuna

    done = finished_trials(study)
    complete = [t for t in done if t.state == optuna.trial.TrialState.COMPLETE]
    summary = dict(study=study.study_name, storage=storage, finished_trials=len(done),
                   complete=len(complete), pruned=len(done) - len(complete),
                   finished_before_this_run=resumed_with)
    if complete:
        best = study.best_trial
        summary["best"] = dict(number=best.number, value=best.value, params=best.params,
                               overrides=best.user_attrs.get("overrides"), train_s=best.user_attrs.get("train_s"))
        (run_dir / "best_overrides.yaml").write_text(
            "# best trial's overrides (python scripts/train.py --set KEY=VALUE ...)\n"
            + "".join(f"- {o}\n" for o in best.user_attrs.get("overrides", [])))
    if len(complete) >= 2:
        try:
            imp = optuna.importance.get_param_importances(study)
        except (RuntimeError, ValueError, ImportError) as exc:  # e.g. a parameter with one value only
            summary["importance_error"] = str(exc)
        else:
            summary["importance"] = imp
            plot_importance(imp, run_dir / "importance.png", study.study_name)
    (run_dir / "study_summary.json").write_text(json.dumps(summary, indent=2, default=float))
    return summary


def plot_importance(imp: dict, out, title: str) -> None:
    from .plotting import pyplot, save_figure

    plt = pyplot()

    names = list(imp)[::-1]
    fig, ax = plt.subplots(figsize=(6, 0.4 * len(names) + 1.2))
    ax.barh(names, [imp[n] for n in names])
    ax.set_xlabel("importance (Optuna's default evaluator)")
    ax.set_title(title)
    save_figure(fig, out)


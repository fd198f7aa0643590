"""The league that trains ``value-lookahead``: generations of games, a value network fitted to them, frozen.

Generation g (``run_generation``):

1. The learner is ``lookahead`` searching with the newest snapshot's value (``value@<run>/snapshots/gen_<g>``;
   at generation 0, before any snapshot, plain ``lookahead``). It plays one job of ``racks`` racks (each
   twice, each side breaking once) against every opponent of the league, at every noise level of
   ``noises``: the built-in bots of ``opponents`` and the frozen snapshots of earlier generations (the newest
   ``max_snapshots`` of them), so it cannot just learn to exploit one.
2. Every decision of both sides but the breaks is recorded: the table seen by its shooter and whether that
   shooter won (``agents.league.games``), and for the searching sides the value their search gave
   the chosen shot. The samples go to ``<run>/data/gen_<g>.npz``. A sample's target is its shooter's result,
   or, where the shooter searched, ``(1 - search_weight) result + search_weight search value`` (the search's
   one-shot backup of the current value: lower variance than the result alone).
3. A value network is fitted (``agents.league.fit``) to the newest ``window`` generations' samples, each
   also mirrored across the table's long axis, starting from the previous snapshot's weights, and frozen as
   ``<run>/snapshots/gen_<g+1>.npz`` / ``.json``.

The league's state is ``<run>/league.json``: the config, the generation reached, the snapshots (paths, SHA-256
of their weights, fit reports), the games played per pairing and noise, the rack seeds used, the RNG state
(numpy's PCG64 state, which seeds every job and fit) and the wall time. It is written after each generation, so
a stopped run resumes (``resume=True``) from the last finished generation and ends where an uninterrupted run
ends. Job seeds count up from ``seed_base`` (racks ``seed * 1_000_003 + k``): evaluations at ``scripts/match.py
--seed`` below it play racks the league never saw.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import time
from pathlib import Path

import numpy as np
import yaml

from billiards_env.rules.games import GAMES as GAME_SPECS
from billiards_env.bots.learned.value import VALUE_DIR, load_value, mirror_features, n_balls_of

from ..evaluation.distributed import MatchJob
from .games import SNAPSHOT, play_league_jobs
from .fit import FitConfig, fit_value

STATE = "league.json"
STATE_VERSION = 1
GAMES = tuple(name for name in GAME_SPECS if not GAME_SPECS[name].own_bots)  # the pool games (the lookahead's)
GAME_ID = 100_000   # a sample's game id: job seed * GAME_ID + its table in the job (jobs have fewer tables)


@dataclasses.dataclass(frozen=True)
class LeagueConfig:
    game: str = "nine_ball"
    generations: int = 4
    racks: int = 8                      # racks per job (each played twice)
    opponents: tuple = ("ghost", "search64", "lookahead")
    max_snapshots: int = 2              # frozen snapshots in the league besides the learner's own
    noises: tuple = ("tournament", "variable")
    max_shots: int = 120
    window: int = 3                     # generations of samples each fit uses
    search_weight: float = 0.0          # the search value's weight in a searching shooter's target
    ball_eases: bool = False            # the network also sees every ball's own ease (bots.learned.value)
    seed: int = 0                       # the league's RNG
    seed_base: int = 1000               # the first job's rack seed
    fit: FitConfig = FitConfig()

    def __post_init__(self):
        if self.game not in GAMES:
            raise ValueError(f"the league trains {GAMES}, got game {self.game!r}")
        if self.generations < 1 or self.racks < 1 or self.window < 1:
            raise ValueError("generations, racks and window must be at least 1")

    @classmethod
    def from_dict(cls, d: dict) -> "LeagueConfig":
        d = dict(d)
        names = {f.name for f in dataclasses.fields(cls)}
        bad = sorted(set(d) - names)
        if bad:
            raise ValueError(f"unknown league config keys {bad}; known: {sorted(names)}")
        fit = d.pop("fit", {}) or {}
        fnames = {f.name for f in dataclasses.fields(FitConfig)}
        if set(fit) - fnames:
            raise ValueError(f"unknown fit keys {sorted(set(fit) - fnames)}; known: {sorted(fnames)}")
        if "hidden" in fit:
            fit["hidden"] = tuple(fit["hidden"])
        for k in ("opponents", "noises"):
            if k in d:
                d[k] = tuple(d[k])
        return cls(**d, fit=FitConfig(**fit))

    @classmethod
    def load(cls, path, **overrides) -> "LeagueConfig":
        d = yaml.safe_load(Path(path).read_text()) or {}
        d.update({k: v for k, v in overrides.items() if v is not None})
        return cls.from_dict(d)

    def to_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["fit"]["hidden"] = list(self.fit.hidden)
        d["opponents"], d["noises"] = list(self.opponents), list(self.noises)
        return d


def weights_hash(stem) -> str:
    """SHA-256 of a snapshot's arrays (names and bytes, in name order)."""
    h = hashlib.sha256()
    with np.load(Path(stem).with_suffix(".npz"), allow_pickle=False) as z:
        for k in sorted(z.files):
            h.update(k.encode())
            h.update(np.ascontiguousarray(z[k]).tobytes())
    return h.hexdigest()


def new_state(cfg: LeagueConfig) -> dict:
    rng = np.random.Generator(np.random.PCG64(cfg.seed))
    return dict(version=STATE_VERSION, config=cfg.to_dict(), generation=0, snapshots=[], games={}, seeds=[],
                next_seed=cfg.seed_base, rng=rng.bit_generator.state, seconds=0.0, history=[])


def _json_safe(o):
    if isinstance(o, dict):
        return {k: _json_safe(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_json_safe(v) for v in o]
    if isinstance(o, np.integer):
        return int(o)
    return o


def save_state(run: Path, state: dict) -> None:
    tmp = run / (STATE + ".tmp")
    tmp.write_text(json.dumps(_json_safe(state), indent=1) + "\n")
    tmp.replace(run / STATE)


def load_state(run: Path) -> dict:
    path = run / STATE
    if not path.exists():
        raise FileNotFoundError(f"no league state at {path}; start the run without --resume")
    state = json.loads(path.read_text())
    if state.get("version") != STATE_VERSION:
        raise ValueError(f"{path}: league state version {state.get('version')}, this code reads {STATE_VERSION}")
    return state


def learner_spec(run: Path, state: dict) -> str:
    return SNAPSHOT + str(run / state["snapshots"][-1]["stem"]) if state["snapshots"] else "lookahead"


def league_jobs(run: Path, cfg: LeagueConfig, state: dict) -> list[MatchJob]:
    """Generation ``state['generation']``'s jobs (module docstring, step 1); takes their seeds."""
    learner = learner_spec(run, state)
    frozen = [SNAPSHOT + str(run / s["stem"]) for s in state["snapshots"][:-1]][-cfg.max_snapshots:]
    jobs = []
    for opp in (*cfg.opponents, *frozen):
        if opp == learner:
            continue
        for noise in cfg.noises:
            jobs.append(MatchJob(learner, opp, cfg.game, cfg.racks, state["next_seed"], noise, cfg.max_shots))
            state["seeds"].append(state["next_seed"])
            state["next_seed"] += 1
    return jobs


def label(spec: str, run: Path) -> str:
    """A pairing's entrant as the state names it: a snapshot by its stem, a bot by its name."""
    return spec[len(SNAPSHOT):].replace(str(run) + "/", "") if spec.startswith(SNAPSHOT) else spec


def run_generation(run: Path, cfg: LeagueConfig, state: dict, address=None, log=print) -> None:
    t0 = time.perf_counter()
    g = state["generation"]
    rng = np.random.Generator(np.random.PCG64(0))
    rng.bit_generator.state = state["rng"]
    jobs = league_jobs(run, cfg, state)
    log(f"generation {g}: {len(jobs)} jobs of {cfg.racks} racks (x2), learner {label(jobs[0].a, run) if jobs else '-'}")

    def progress(i, r):
        j = r.job
        log(f"  [{i + 1}/{len(jobs)}] vs {label(j.b, run)} ({j.noise}, seed {j.seed}): learner "
            f"{r.score_a:.1f}/{len(r.winner)}, {0 if r.samples is None else len(r.samples.y)} samples")

    results = play_league_jobs(jobs, address=address, progress=progress,
                               chunk_progress=lambda n, total: log(f"  {n}/{total} jobs played "
                                                                   f"({time.perf_counter() - t0:.0f} s)"))
    xs, ys, gs, ss, bs, summary = [], [], [], [], [], []
    for r in results:
        j = r.job
        key = f"{label(j.a, run)} | {label(j.b, run)} | {j.noise}"
        c = state["games"].setdefault(key, dict(games=0, a_score=0.0))
        c["games"] += len(r.winner)
        c["a_score"] += r.score_a
        summary.append(dict(pairing=key, games=len(r.winner), a_score=r.score_a, seed=j.seed))
        if r.samples is not None:
            xs.append(r.samples.x)
            ys.append(r.samples.y)
            gs.append(j.seed * GAME_ID + r.samples.table)
            ss.append(r.samples.search)
            bs.append(r.samples.balls)
    data = run / "data"
    data.mkdir(parents=True, exist_ok=True)
    np.savez(data / f"gen_{g:03d}.npz", x=np.concatenate(xs), y=np.concatenate(ys), game=np.concatenate(gs),
             search=np.concatenate(ss), balls=np.concatenate(bs))
    # the fit: the newest `window` generations, mirrored
    parts = [np.load(data / f"gen_{k:03d}.npz", allow_pickle=False) for k in range(max(0, g + 1 - cfg.window), g + 1)]
    x = np.concatenate([p["x"] for p in parts])
    y = np.concatenate([p["y"] for p in parts])
    game = np.concatenate([p["game"] for p in parts])
    sv = np.concatenate([p["search"] if "search" in p.files else np.full(len(p["y"]), np.nan) for p in parts])
    if cfg.ball_eases:
        if any("balls" not in p.files for p in parts):
            raise ValueError(f"{data}: samples recorded without the balls' eases cannot fit a ball_eases network")
        x = np.concatenate([x, np.concatenate([p["balls"] for p in parts])], axis=1)
    w = cfg.search_weight
    y = np.where(np.isnan(sv), y, (1 - w) * y + w * np.nan_to_num(sv))
    B = n_balls_of(x.shape[1], cfg.ball_eases)
    x, y, game = np.concatenate([x, mirror_features(x, B)]), np.concatenate([y, y]), np.concatenate([game, game])
    init = load_value(run / state["snapshots"][-1]["stem"])[0] if state["snapshots"] else None
    tf = time.perf_counter()
    net, rep = fit_value(x, y, cfg.fit, rng, init=init, groups=game, ball_eases=cfg.ball_eases)
    rep["fit_seconds"] = time.perf_counter() - tf
    stem = f"snapshots/gen_{g + 1:03d}"
    net.save(run / stem, dict(game=cfg.game, version=f"league-gen{g + 1}", generation=g + 1, fit=rep,
                              trained_on=[s["pairing"] for s in summary]))
    state["snapshots"].append(dict(stem=stem, generation=g + 1, sha256=weights_hash(run / stem), fit=rep))
    state["rng"] = rng.bit_generator.state
    state["generation"] = g + 1
    secs = time.perf_counter() - t0
    state["seconds"] += secs
    state["history"].append(dict(generation=g, jobs=summary, seconds=secs))
    save_state(run, state)
    log(f"generation {g} done in {secs:.0f} s: {rep['samples']} samples (mirrored); held-out games' log loss "
        f"{rep.get('val_log_loss', float('nan')):.4f} (epoch {rep['best_epoch']}), the starting value's "
        f"{rep.get('val_log_loss_start', float('nan')):.4f}, a constant's "
        f"{rep.get('val_log_loss_constant', float('nan')):.4f}; froze {stem}")


def run_league(run, cfg: LeagueConfig | None = None, resume: bool = False, generations: int | None = None,
               address=None, log=print) -> dict:
    """Train (or resume, from ``<run>/league.json``) until ``generations`` (default: the config's) are done;
    returns the state."""
    run = Path(run)
    if resume:
        state = load_state(run)
        cfg = LeagueConfig.from_dict(state["config"])
        log(f"resuming {run} at generation {state['generation']}")
    else:
        if cfg is None:
            raise ValueError("a new league needs a config")
        if (run / STATE).exists():
            raise FileExistsError(f"{run / STATE} exists: pass --resume to continue it, or choose another --run")
        run.mkdir(parents=True, exist_ok=True)
        state = new_state(cfg)
        save_state(run, state)
    target = generations or cfg.generations
    while state["generation"] < target:
        run_generation(run, cfg, state, address=address, log=log)
    return state


def ship(run, root=VALUE_DIR, generation: int | None = None) -> Path:
    """Copy a snapshot (default the newest) to the package's shipped values, ``<root>/<game>.npz`` / ``.json``,
    its card extended with the league's budget (generations, games, wall time)."""
    run = Path(run)
    state = load_state(run)
    snaps = state["snapshots"]
    snap = snaps[-1] if generation is None else next(s for s in snaps if s["generation"] == generation)
    net, doc = load_value(run / snap["stem"])
    cfg = state["config"]
    doc.update(league=dict(config=cfg, generations=state["generation"], wall_seconds=state["seconds"],
                           games=sum(c["games"] for c in state["games"].values()), seeds=state["seeds"]))
    for k in ("format", "format_version", "in_dim", "hidden", "ball_eases"):
        doc.pop(k)
    Path(root).mkdir(parents=True, exist_ok=True)
    net.save(Path(root) / cfg["game"], doc)
    return Path(root) / cfg["game"]


__all__ = ["LeagueConfig", "run_league", "ship", "weights_hash", "load_state"]

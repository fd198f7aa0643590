"""Expert Iteration's rounds, the distillation of the fast player, and shipping both (docs/expert_iteration.md).

Round r (``run_round``):

1. **Self-play** (``selfplay.play_round``): the expert plays ``jobs`` jobs of ``racks`` racks against itself. In
   round 0 the expert is the search over the hand prior with the ``expert0`` budget (the first fit imitates it);
   in round r > 0 the search over snapshot r's proposals with the ``expert`` budget (Gumbel-top-k candidates,
   the leaves partly valued by the network). Every decision's record keeps the search's allocation.
2. **Fit** (``fit.fit``): the network is fitted to the newest ``window`` rounds' records, from snapshot r's
   weights, and frozen as ``<run>/snapshots/round_<r + 1>.npz`` / ``.json``.

After the last round, **distillation**: the student (``distill`` sizes) learns the last ``distill_window`` rounds'
searches with ``distill_hard`` of each target moved to the shot the search played, from the last snapshot's
weights where the sizes match, and is frozen as ``<run>/snapshots/fast``; a run resumed past the config's rounds
(``--rounds``) distils again from its newest rounds. ``ship`` copies the last snapshot and
the student into the package as ``exit-search`` and ``exit-fast`` of the game, with the break strike a
break search found for the game (``bots.planner.breaks``) and the training's figures in their cards.

The run's state is ``<run>/exit.json`` (config, rounds done, snapshots with the SHA-256 of their weights, the
history, wall seconds), written after each round. Every seed derives from the config (job seeds from
``seed_base``, round and job; a fit's from ``seed``, round and epoch), so a stopped run resumes where it stopped
(the shards already written, the fit's last checkpoint) and ends with the networks an uninterrupted run ends with.
"""
from __future__ import annotations

import hashlib
import json
import time
from pathlib import Path

import numpy as np

from billiards_env.bots.learned import proposal_net as PN
from billiards_env.bots.learned.proposal_bot import CARD_DIR, FAST, SEARCH

from ..evaluation.distributed import MatchJob, play_jobs
from .config import ExItConfig
from .fit import fit, targets
from .selfplay import Data, entrant, play_round, shard_path, spec

STATE = "exit.json"
STATE_VERSION = 1
DISTILL_KEY = 1_000_000        # the distillation's fit key (rounds' fits use their round number)
BREAK_RACKS = 32               # breaking racks the shipped break strike is searched on (champion's RACKS)


def weights_hash(stem) -> str:
    """SHA-256 of a network's arrays (names and bytes, in name order)."""
    h = hashlib.sha256()
    with np.load(Path(stem).with_suffix(".npz"), allow_pickle=False) as z:
        for k in sorted(z.files):
            h.update(k.encode())
            h.update(np.ascontiguousarray(z[k]).tobytes())
    return h.hexdigest()


def save_state(run: Path, state: dict) -> None:
    tmp = run / (STATE + ".tmp")
    tmp.write_text(json.dumps(state, indent=1) + "\n")
    tmp.replace(run / STATE)


def load_state(run: Path) -> dict:
    path = Path(run) / STATE
    if not path.exists():
        raise FileNotFoundError(f"no Expert Iteration state at {path}; start the run without --resume")
    state = json.loads(path.read_text())
    if state.get("version") != STATE_VERSION:
        raise ValueError(f"{path}: state version {state.get('version')}, this code reads {STATE_VERSION}")
    return state


def _snapshot(run: Path, state: dict):
    return state["snapshots"][-1]["stem"] if state["snapshots"] else None


def run_round(run: Path, cfg: ExItConfig, state: dict, address=None, log=print, stop_after=None,
              workers: int | None = None) -> None:
    r = state["round"]
    t0 = time.perf_counter()
    snap = _snapshot(run, state)
    log(f"round {r}: self-play by the search over {'the hand prior' if snap is None else snap}")
    play_round(run, cfg, r, snap, address, log, workers)
    t1 = time.perf_counter()
    paths = [shard_path(run, k, j) for k in range(max(0, r + 1 - cfg.window), r + 1) for j in range(cfg.jobs)]
    data = Data.load(paths, cfg.net.max_samples)
    init = PN.load(run / "snapshots" / snap)[0] if snap else None
    log(f"round {r}: fitting on {data.n} decisions of rounds {max(0, r + 1 - cfg.window)}..{r}")
    net, rep = fit(data, cfg.net, targets(data, cfg.value_mix), (cfg.seed, r), run / "fit" / f"round_{r:03d}",
                   init=init, log=log, stop_after=stop_after)
    stem = f"round_{r + 1:03d}"
    net.save(run / "snapshots" / stem, dict(game=cfg.game, version=f"exit-round{r + 1}", round=r + 1, fit=rep))
    t2 = time.perf_counter()
    new = Data.load([shard_path(run, r, j) for j in range(cfg.jobs)]).n
    entry = dict(round=r, decisions=new, play_seconds=round(t1 - t0, 1), fit_seconds=round(t2 - t1, 1),
                 fit=rep["epochs"][-1] if rep["epochs"] else {})
    if cfg.eval_racks:
        entry["eval"] = evaluate(run, cfg, stem, address, workers)
        log(f"round {r}: {stem}'s search against {cfg.eval_opponent}: {entry['eval']['score']:.3f} of "
            f"{entry['eval']['games']} games")
    state["snapshots"].append(dict(stem=stem, round=r + 1, sha256=weights_hash(run / "snapshots" / stem)))
    state["history"].append(entry)
    state["decisions"] += new
    state["seconds"] += time.perf_counter() - t0
    state["round"] = r + 1
    save_state(run, state)
    log(f"round {r} done: {new} decisions in {t1 - t0:.0f} s of self-play, fit {t2 - t1:.0f} s; froze {stem}")


def distill(run: Path, cfg: ExItConfig, state: dict, log=print, stop_after=None) -> None:
    t0 = time.perf_counter()
    last = state["round"]
    paths = [shard_path(run, k, j) for k in range(max(0, last - cfg.distill_window), last) for j in range(cfg.jobs)]
    data = Data.load(paths, cfg.distill.max_samples)
    teacher = PN.load(run / "snapshots" / _snapshot(run, state))[0]
    log(f"distilling: {data.n} decisions of the last {cfg.distill_window} rounds, {cfg.distill_hard} of each target "
        "on the played shot")
    net, rep = fit(data, cfg.distill, targets(data, cfg.value_mix, cfg.distill_hard), (cfg.seed, DISTILL_KEY + last),
                   run / "fit" / f"distill_{last:03d}", init=teacher, log=log, stop_after=stop_after)
    net.save(run / "snapshots" / "fast", dict(game=cfg.game, version=f"exit-fast-round{last}", round=last, fit=rep))
    state["fast"] = dict(stem="fast", round=last, sha256=weights_hash(run / "snapshots" / "fast"))
    state["seconds"] += time.perf_counter() - t0
    save_state(run, state)
    log(f"distilled in {time.perf_counter() - t0:.0f} s: snapshots/fast")


def run_exit(run, cfg: ExItConfig | None = None, resume: bool = False, rounds: int | None = None, address=None,
             log=print, stop: dict | None = None, workers: int | None = None) -> dict:
    """Train (or resume, from ``<run>/exit.json``) until ``rounds`` (default the config's) are done, then distil;
    returns the state. ``stop``: ``{"round": r, "epoch": e}`` stops round r's fit after epoch e (``{"distill":
    e}``: the distillation's), as a kill would (tests). ``workers``: the CPUs of a local Ray instance (``address``
    ``local``; default all cores)."""
    run = Path(run)
    if resume:
        state = load_state(run)
        cfg = ExItConfig.from_dict(state["config"])
        log(f"resuming {run} at round {state['round']}")
    else:
        if cfg is None:
            raise ValueError("a new Expert Iteration run needs a config")
        if (run / STATE).exists():
            raise FileExistsError(f"{run / STATE} exists: pass --resume to continue it, or choose another --run")
        run.mkdir(parents=True, exist_ok=True)
        state = dict(version=STATE_VERSION, config=cfg.to_dict(), round=0, snapshots=[], history=[], decisions=0,
                     seconds=0.0, fast=None)
        save_state(run, state)
    import torch
    torch.set_num_threads(cfg.threads)
    stop = stop or {}
    target = rounds or cfg.rounds
    while state["round"] < target:
        r = state["round"]
        run_round(run, cfg, state, address, log, stop.get("epoch") if stop.get("round") == r else None, workers)
    if state["round"] >= cfg.rounds and (state.get("fast") or {}).get("round") != state["round"]:
        distill(run, cfg, state, log, stop.get("distill"))
    return state


def evaluate(run: Path, cfg: ExItConfig, stem: str, address=None, workers: int | None = None) -> dict:
    """The search over snapshot ``stem`` (the ``play`` budget) against ``eval_opponent``: score of its games."""
    import functools
    job = MatchJob(spec(run, stem, "play"), cfg.eval_opponent, cfg.game, cfg.eval_racks, cfg.eval_seed, cfg.noise,
                   cfg.max_shots, cfg.chunk_racks)
    games = play_jobs([job], address, bot_factory=functools.partial(entrant, config=cfg.to_dict()), num_cpus=workers)
    w = np.array([g.winner for g in games.values()])
    return dict(games=int(len(w)), score=float((w == 0).mean() + 0.5 * (w < 0).mean()), seed=cfg.eval_seed)


def ship(run, root=CARD_DIR, log=print, play: dict | None = None) -> list:
    """Copy the run's last snapshot and its student into ``<root>/<game>/`` as ``exit-search`` and
    ``exit-fast`` (module docstring); returns the stems written. ``play``: changes to the config's ``play`` budget,
    the search's at decision time (its card's)."""
    run = Path(run)
    state = load_state(run)
    if state.get("fast") is None:
        raise ValueError(f"{run}: the run has not finished (rounds done: {state['round']}, no distilled network); "
                         "resume it first")
    cfg = ExItConfig.from_dict(state["config"])
    strike = break_strike(cfg)
    log(f"break strike for {cfg.game}: {np.round(strike, 4).tolist()}")
    training = dict(run=run.name, rounds=state["round"], decisions=state["decisions"],
                    wall_seconds=round(state["seconds"], 1), config=state["config"],
                    snapshots=state["snapshots"], history=state["history"])
    out = []
    for name, stem in ((SEARCH, _snapshot(run, state)), (FAST, "fast")):
        net, doc = PN.load(run / "snapshots" / stem)
        card = dict(name=name, game=cfg.game, version=doc.get("version"), source=stem, training=training,
                    fit=doc.get("fit"),
                    budget=dict(state["config"]["play"], **(play or {})) if name == SEARCH else None,
                    **{"break": [float(v) for v in strike]})
        net.save(Path(root) / cfg.game / name, card)
        out.append(Path(root) / cfg.game / name)
    from billiards_env.bots.learned.proposal_bot import shipped
    shipped.cache_clear()
    return out


def break_strike(cfg: ExItConfig) -> np.ndarray:
    """The break strike champion's break search finds for the game on ``BREAK_RACKS`` breaking racks."""
    from billiards_env.bots.learned.proposal_bot import ProposalPlayer
    from billiards_env.envs.games import GameConfig, GameCore

    core = GameCore(GameConfig(game=cfg.game, noise=cfg.noise), BREAK_RACKS)
    core.streams.seed(np.arange(BREAK_RACKS), cfg.eval_seed * 1_000_003 + np.arange(BREAK_RACKS))
    core.reset_tables(np.arange(BREAK_RACKS), np.zeros(BREAK_RACKS, dtype=np.int64))
    player = ProposalPlayer(seed=cfg.seed, nets={cfg.game: (None, {})})
    view = core.view(np.arange(BREAK_RACKS))
    return player.breaks.strike(player, view, np.arange(BREAK_RACKS))

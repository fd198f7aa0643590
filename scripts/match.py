#!/usr/bin/env python
"""Seeded matches between bots (and trained models), with win rates and ratings.

    python scripts/match.py --game nine_ball --policies random ghost ghost-safety --racks 100
    python scripts/match.py --policies my_bots:planner ghost search64 --racks 50   # a bot of your own
    python scripts/match.py --game eight_ball --noise high --racks 50 --out results/matches
    python scripts/match.py --game ten_ball --policies ghost ghost-safety search64 --racks 100
    python scripts/match.py --summary --out results/matches   # every game and noise level there in one table
    python scripts/match.py --policies ghost search64 --racks 20 --save-replays 4   # + 4 whole games per pairing
    python scripts/match.py --protocol championship --policies lookahead search64 ghost-safety --racks 100
    python scripts/match.py --policies ghost ghost-safety search64 --racks 100 --address local --chunk-racks 25

Every pairing plays ``--racks`` racks twice (each side breaks once on each
rack). Writes into ``--out`` (default: a new run folder,
``runs/match/<timestamp>/``, git-ignored; the committed tables of
``results/`` are rewritten only when ``--out results/...`` names them)
``<out>/<game>_<noise>.json``, ``.md`` and ``.png`` (ratings
with 95% intervals); with ``--save-replays N``, the first N games of every
pairing (rack 1 with each side breaking, rack 2, ...) as replay pages and
JSON in ``<out>/replays/<game>_<noise>/``. An entrant is a built-in bot (``random``, ``ghost``,
``ghost-safety``, ``search<K>``), ``module:factory`` (a bot of your own,
docs/bots.md; the module is looked up on PYTHONPATH and in the current
directory) or the path of a saved model. Noise levels: ``tournament``, ``high`` (5x), ``variable``
(a factor uniform in [0, 5] per game), ``none``.

Every protocol reports each entrant's compute per shot (wall and CPU
milliseconds per decided shot, measured where the games are played).

``--protocol championship``: 8-ball under the 2011 computer pool
championship's conditions (``studies.championship``): the tournament at
each of the noise levels ``tournament`` (1x), ``high`` (5x) and
``variable``, alternating breaks on the same racks, and every entrant's
compute per shot; writes ``<out>/eight_ball_<noise>.*`` and
``<out>/championship.md`` / ``.json``.
``--quick``: 2 racks, games cut at 20 shots (a smoke run).

``--address``: the pairings' racks played as Ray tasks, in chunks of
``--chunk-racks`` racks (``agents.evaluation.distributed``; ``local``
starts Ray on this machine, ``auto`` or ``HOST:PORT`` joins a cluster;
docs/distributed.md). Without it every chunk plays in this process. The
results depend on the chunks, not on where they ran: the same with and
without ``--address``; without ``--chunk-racks`` a pairing is one chunk.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(1, str(Path.cwd()))  # module:factory bots in the current directory

from agents.evaluation import distributed  # noqa: E402
from agents.evaluation.entrants import bot_factory  # noqa: E402
from billiards_env.envs.games import GAMES  # noqa: E402
from billiards_env.envs.games.core import BREAK_NINE  # noqa: E402
from billiards_env.envs.games.setup import RACKS  # noqa: E402
from billiards_env.rendering import save_replay_html  # noqa: E402
from billiards_env.studies import match_report  # noqa: E402
from billiards_env.studies.run_folder import run_folder  # noqa: E402
from billiards_env.studies.championship import GAME as CHAMPIONSHIP_GAME  # noqa: E402
from billiards_env.studies.championship import TimedBot, championship, compute_table, per_shot  # noqa: E402


def write_replays(folder: Path, results) -> None:
    """Each pairing's recorded games as ``<a>_v_<b>-NN.html`` and ``.json``."""
    for r in results:
        for n, rep in enumerate(r.replays):
            folder.mkdir(parents=True, exist_ok=True)
            # appended, not Path.with_suffix: an entrant's name may hold a dot (lookahead-2026.12)
            stem = f"{_safe(r.a)}_v_{_safe(r.b)}-{n:02d}"
            rep.save(folder / f"{stem}.json")
            save_replay_html(rep, folder / f"{stem}.html")
            print(f"wrote {folder / stem}.html ({len(rep)} shots)")


def timed_bot(spec, seed):
    """An entrant whose decisions are timed (``studies.championship.TimedBot``): compute per shot in every protocol,
    measured where the games are played (here or on a Ray worker)."""
    return TimedBot(bot_factory(spec, seed), spec if isinstance(spec, str) else type(spec).__name__, {})


def bot_clocks(job, bots, result) -> list:
    """After each chunk, where it ran: every timed bot's (name, [shots decided, wall seconds, CPU seconds])."""
    return [(b.name, list(b.clock[b.name])) for b in bots]


def _progress(done: int, total: int) -> None:
    if total > 1:
        print(f"chunks played: {done}/{total}", file=sys.stderr, flush=True)


def _safe(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-." else "-" for c in Path(name).name)


class _Pairing:
    """A pairing's recorded summary (a ``<game>_<noise>.json``'s ``pairings`` entry) where the report wants a
    result: ``summary()`` returns it."""

    def __init__(self, summary: dict):
        self._summary = summary

    def summary(self) -> dict:
        return self._summary


COMPUTE_NOTE = ("\n## Compute per shot\n\nEach entrant's decisions (breaks included), timed where the games were "
                "played: shots decided, wall ms per shot and, in brackets, CPU ms per shot (the process's, numba's "
                "threads included).\n\n")


def match_markdown(doc: dict) -> str:
    """The Markdown of one ``<game>_<noise>.json`` (a match's, the ladder's or a league's tournament): every
    pairing and the ratings (``studies.match_report.markdown``), and the compute per shot when the standard
    protocol timed it (the championship's levels report theirs in ``championship.md``)."""
    md = match_report.markdown(f"{doc['game']} matches, noise `{doc['noise']}`", doc["command"],
                               [_Pairing(p) for p in doc["pairings"]], doc["ratings"], doc["seconds"])
    if "compute" in doc and doc.get("protocol") != "championship":
        md += COMPUTE_NOTE + compute_table([dict(noise=doc["noise"], compute=doc["compute"])]) + "\n"
    return md


def championship_markdown(doc: dict) -> str:
    """``championship.md`` from ``championship.json``: the compute per shot at every level, then each level's
    tournament (its title one level down)."""
    parts = [f"# The championship protocol: {CHAMPIONSHIP_GAME}, {doc['racks']} racks per pairing and level\n",
             f"`{doc['command']}`\n",
             "Compute per shot: milliseconds of wall clock in each entrant's decisions (its previews included), over the "
             "shots it played, and in brackets the process's CPU time in them (every thread's), which a loaded "
             "machine does not inflate; the tables of a pairing are decided in batches, so this is the batched "
             "cost.\n",
             compute_table(doc["levels"]) + "\n"]
    for lv in doc["levels"]:
        parts.append("#" + match_markdown(dict(lv, game=CHAMPIONSHIP_GAME, command=doc["command"],
                                               protocol="championship")))
    return "\n".join(parts)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--game", choices=list(GAMES), default=None, help="default nine_ball (championship: eight_ball)")
    ap.add_argument("--protocol", choices=("standard", "championship"), default="standard",
                    help="championship: 8-ball at tournament, high (5x) and variable noise, with compute per shot")
    ap.add_argument("--quick", action="store_true", help="2 racks, games cut at 20 shots")
    ap.add_argument("--policies", nargs="+", default=["random", "ghost"],
                    help="entrants: random, ghost, ghost-safety, search<K>, module:factory, or paths of saved models")
    ap.add_argument("--racks", type=int, default=100, help="racks per pairing (each played twice)")
    ap.add_argument("--noise", choices=match_report.NOISES, default="tournament")
    ap.add_argument("--rack", choices=RACKS, default="realistic",
                    help="realistic: seeded gaps and offsets between the balls; perfect: every ball frozen")
    ap.add_argument("--break-nine", choices=BREAK_NINE, default="wins", help="9-ball: the 9 on the break wins or is spotted")
    ap.add_argument("--airborne", action="store_true",
                    help="balls fly (effects={'airborne': True}, docs/physics.md): the bots may elevate the cue")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-shots", type=int, default=200)
    ap.add_argument("--out", type=Path, default=None,
                    help="folder of the tables (default: a new runs/match/<timestamp>/; results/... only when named)")
    ap.add_argument("--save-replays", type=int, default=0, metavar="N",
                    help="write the first N games of every pairing as replays (HTML and JSON)")
    ap.add_argument("--summary", action="store_true",
                    help="only write <out>/summary.md from the JSON files there (needs --out)")
    ap.add_argument("--address", default=None,
                    help="play on Ray: local (a Ray instance here), auto or HOST:PORT (a cluster); default: this process")
    ap.add_argument("--chunk-racks", type=int, default=None, metavar="N",
                    help="racks played together (one Ray task each); default: all racks of a pairing")
    args = ap.parse_args(argv)
    if args.quick:
        args.racks, args.max_shots = 2, 20
    champ = args.protocol == "championship"
    if champ and args.game not in (None, CHAMPIONSHIP_GAME):
        ap.error(f"--protocol championship plays {CHAMPIONSHIP_GAME}, got --game {args.game}")
    args.game = args.game or (CHAMPIONSHIP_GAME if champ else "nine_ball")
    config = dict(rack=args.rack, **({"break_nine": args.break_nine} if args.break_nine != "wins" else {}),
                  **({"effects": {"airborne": True}} if args.airborne else {}))
    if args.summary:
        if args.out is None:
            ap.error("--summary reads the JSON files of a folder of matches: name it, e.g. --out results/matches")
        md = match_report.summary(args.out)
        (args.out / "summary.md").write_text(md)
        print(md)
        return 0
    if len(set(args.policies)) < 2:
        ap.error("need at least two different policies")
    if args.chunk_racks is not None and args.chunk_racks < 1:
        ap.error(f"--chunk-racks must be a positive integer, got {args.chunk_racks}")
    if champ and args.airborne:
        ap.error("--airborne applies to the standard protocol (the championship is the planar 8-ball of the ladder)")
    if champ and (args.address or args.chunk_racks):
        ap.error("--address and --chunk-racks apply to the standard protocol (the championship times each entrant's "
                 "compute per shot in this process)")
    if not 0 <= args.save_replays <= 2 * args.racks:
        ap.error(f"--save-replays must be between 0 and 2 x --racks ({2 * args.racks}), got {args.save_replays}")
    t0 = time.perf_counter()
    for spec in args.policies:  # a bad entrant fails before any game is played
        bot_factory(spec, args.seed)
    if args.out is None:
        args.out = run_folder(ROOT, "match")
        print(f"writing to {args.out} (--out names another folder)", file=sys.stderr, flush=True)
    command = " ".join(["python", "scripts/match.py"] + (argv if argv is not None else sys.argv[1:]))
    if champ:
        return run_championship(args, command)
    clocks: dict = {}

    def add_clock(chunk, entries):
        for name, (shots, wall, cpu) in entries:
            c = clocks.setdefault(name, [0, 0.0, 0.0])
            c[0], c[1], c[2] = c[0] + shots, c[1] + wall, c[2] + cpu

    results, table = distributed.tournament(args.policies, args.game, args.racks, args.seed, args.noise, args.address,
                                            args.chunk_racks, args.max_shots, config, save_replays=args.save_replays,
                                            progress=_progress, bot_factory=timed_bot, extra=bot_clocks,
                                            on_extra=add_clock)
    seconds = time.perf_counter() - t0
    write_replays(args.out / "replays" / f"{args.game}_{args.noise}", results)
    compute = {name: per_shot(c) for name, c in sorted(clocks.items())}
    doc = dict(command=command, game=args.game, **config, noise=args.noise, racks=args.racks, seed=args.seed, seconds=seconds,
               pairings=[r.summary() for r in results], ratings=table, compute=compute)
    stem = args.out / f"{args.game}_{args.noise}"
    match_report.write(stem, doc, results, table)
    md = match_markdown(json.loads(stem.with_suffix(".json").read_text()))  # what scripts/regenerate.py renders
    stem.with_suffix(".md").write_text(md)
    print(md)
    return 0


def run_championship(args, command: str) -> int:
    """The championship protocol (module docstring): one tournament per noise level, compute per shot."""
    if args.break_nine != "wins":
        raise SystemExit("--break-nine is a 9-ball option; the championship plays 8-ball")
    levels = championship(args.policies, args.racks, args.seed, max_shots=args.max_shots, bot_factory=bot_factory,
                          rack=args.rack,
                          progress=lambda lv: print(f"noise {lv} ...", file=sys.stderr, flush=True))
    for lv in levels:
        doc = dict(command=command, protocol="championship", game=CHAMPIONSHIP_GAME, noise=lv["noise"], rack=args.rack,
                   racks=args.racks, seed=args.seed, seconds=lv["seconds"],
                   pairings=[r.summary() for r in lv["results"]], ratings=lv["ratings"], compute=lv["compute"])
        match_report.write(args.out / f"{CHAMPIONSHIP_GAME}_{lv['noise']}", doc, lv["results"], lv["ratings"])
    doc = dict(command=command, racks=args.racks, seed=args.seed,
               levels=[dict(noise=lv["noise"], compute=lv["compute"], ratings=lv["ratings"], seconds=lv["seconds"],
                            pairings=[r.summary() for r in lv["results"]]) for lv in levels])
    (args.out / "championship.json").write_text(json.dumps(doc, indent=2) + "\n")
    text = championship_markdown(json.loads(json.dumps(doc)))  # as scripts/regenerate.py renders it from the JSON
    (args.out / "championship.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

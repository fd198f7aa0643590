#!/usr/bin/env python
"""Seeded matches between bots (and trained models), with win rates and ratings.

    python scripts/match.py --game nine_ball --policies random ghost ghost-safety --racks 100
    python scripts/match.py --policies my_bots:planner ghost search64 --racks 50   # a bot of your own
    python scripts/match.py --game eight_ball --noise high --racks 50 --out results/matches
    python scripts/match.py --summary    # every game and noise level of results/matches in one table

Every pairing plays ``--racks`` racks twice (each side breaks once on each
rack). Writes ``<out>/<game>_<noise>.json``, ``.md`` and ``.png`` (ratings
with 95% intervals). An entrant is a built-in bot (``random``, ``ghost``,
``ghost-safety``, ``search<K>``), ``module:factory`` (a bot of your own,
docs/bots.md; the module is looked up on PYTHONPATH and in the current
directory) or the path of a saved model. Noise levels: ``tournament``, ``high`` (5x), ``variable``
(a factor uniform in [0, 5] per game), ``none``.
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

from agents.game_policies import bot_factory  # noqa: E402
from billiards_env.studies.matches import tournament  # noqa: E402

NOISES = ["none", "tournament", "high", "variable"]


def markdown(args, results, table, seconds) -> str:
    lines = [f"# {args.game} matches, noise `{args.noise}`", "",
             f"`python scripts/match.py --game {args.game} --noise {args.noise} --racks {args.racks} "
             f"--seed {args.seed} --policies {' '.join(args.policies)}` ({seconds:.0f} s)", "",
             "| a | b | games | a wins | b wins | draws | a win rate [95% CI] | a breaking / not | shots per game |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        s = r.summary()
        lines.append(f"| {s['a']} | {s['b']} | {s['games']} | {s['a_wins']} | {s['b_wins']} | {s['draws']} | "
                     f"{s['a_win_rate']:.3f} [{s['ci95'][0]:.3f}, {s['ci95'][1]:.3f}] | "
                     f"{s['a_win_rate_breaking']:.3f} / {s['a_win_rate_not_breaking']:.3f} | {s['mean_shots']:.1f} |")
    lines += ["", "Bradley-Terry ratings (Elo scale, mean 0; 95% bootstrap intervals):", "",
              "| entrant | rating | 95% interval |", "|---|---|---|"]
    for t in table:
        lines.append(f"| {t['name']} | {t['elo']:.0f} | [{t['ci95'][0]:.0f}, {t['ci95'][1]:.0f}] |")
    return "\n".join(lines) + "\n"


def plot(table, path: Path, title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5, 0.5 + 0.45 * len(table)))
    names = [t["name"] for t in table][::-1]
    elo = [t["elo"] for t in table][::-1]
    err = [[t["elo"] - t["ci95"][0] for t in table][::-1], [t["ci95"][1] - t["elo"] for t in table][::-1]]
    ax.errorbar(elo, range(len(names)), xerr=err, fmt="o", capsize=4)
    ax.set_yticks(range(len(names)), names)
    ax.set_xlabel("rating (Elo scale, 95% interval)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def summary(out: Path) -> str:
    """One Markdown table of every ``<game>_<noise>.json`` in ``out``: each
    entrant's rating [95% interval], and the best entrant's win rate against random."""
    docs = [json.loads(p.read_text()) for p in sorted(out.glob("*_*.json"))]
    if not docs:
        return "no match results\n"
    names = sorted({r["name"] for d in docs for r in d["ratings"]})
    lines = ["| game | noise | " + " | ".join(names) + " | seconds |", "|---|---|" + "---|" * (len(names) + 1)]
    for d in sorted(docs, key=lambda d: (d["game"], NOISES.index(d["noise"]))):
        r = {x["name"]: x for x in d["ratings"]}
        cells = [f"{r[n]['elo']:.0f} [{r[n]['ci95'][0]:.0f}, {r[n]['ci95'][1]:.0f}]" if n in r else "" for n in names]
        lines.append(f"| {d['game']} | {d['noise']} | " + " | ".join(cells) + f" | {d['seconds']:.0f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--game", choices=["nine_ball", "eight_ball"], default="nine_ball")
    ap.add_argument("--policies", nargs="+", default=["random", "ghost"],
                    help="entrants: random, ghost, ghost-safety, search<K>, module:factory, or paths of saved models")
    ap.add_argument("--racks", type=int, default=100, help="racks per pairing (each played twice)")
    ap.add_argument("--noise", choices=NOISES, default="tournament")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-shots", type=int, default=200)
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "matches")
    ap.add_argument("--summary", action="store_true", help="only write <out>/summary.md from the JSON files there")
    args = ap.parse_args(argv)
    if args.summary:
        md = summary(args.out)
        (args.out / "summary.md").write_text(md)
        print(md)
        return 0
    if len(set(args.policies)) < 2:
        ap.error("need at least two different policies")
    t0 = time.perf_counter()
    for spec in args.policies:  # a bad entrant fails before any game is played
        bot_factory(spec, args.seed)
    results, table = tournament(args.policies, args.game, args.racks, args.seed, args.noise, max_shots=args.max_shots,
                                bot_factory=bot_factory)
    seconds = time.perf_counter() - t0
    args.out.mkdir(parents=True, exist_ok=True)
    stem = args.out / f"{args.game}_{args.noise}"
    doc = dict(command=" ".join(["python", "scripts/match.py"] + (argv if argv is not None else sys.argv[1:])),
               game=args.game, noise=args.noise, racks=args.racks, seed=args.seed, seconds=seconds,
               pairings=[r.summary() for r in results], ratings=table)
    stem.with_suffix(".json").write_text(json.dumps(doc, indent=2) + "\n")
    md = markdown(args, results, table, seconds)
    stem.with_suffix(".md").write_text(md)
    plot(table, stem.with_suffix(".png"), f"{args.game}, noise {args.noise}")
    print(md)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

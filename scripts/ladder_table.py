#!/usr/bin/env python
"""The ladder's cross table: the shipped learned agents against the built-in bots.

    python scripts/ladder_table.py                        # every game and noise level, 20 racks per pairing
    python scripts/ladder_table.py --racks 50 --noise tournament high
    python scripts/ladder_table.py --quick --out /tmp/ladder   # smoke test: ladder-1 v ghost, 2 racks, no noise
    python scripts/ladder_table.py --games eight_ball --noise high &   # one part per process, then
    python scripts/ladder_table.py --collect                           # the CSV, summary and docs of every part
    python scripts/ladder_table.py --racks 50 --address local --chunk-racks 10   # the matches as Ray tasks

For each game with a shipped ladder (9-ball, 8-ball) and noise level (``none``, ``tournament``,
``high``, ``variable``) every pairing of the game's ladder agents
(``billiards_env.bots.learned.ladder``) and ``--bots`` (default ``ghost``,
``ghost-safety``, ``search64``, ``lookahead``, ``lookahead-2026.12``, ``value-lookahead``, ``champion``,
``champion-fast`` and ``exit-search``, each where it has a player for the game) plays ``--racks`` paired racks
(each rack twice, each side breaking once; ``studies.matches``), and
Bradley-Terry ratings with 95% bootstrap intervals are fitted. Writes
``<out>/<game>_<noise>.json/.md/.png`` (every pairing and the ratings),
``<out>/ratings.csv``, ``<out>/pairings.csv``, ``<out>/summary.md`` (one
table of every rating) and ``<out>/ladder.md`` (the agents' cards and the
summary); with the default ``--out`` the summary also goes into
``docs/ladder.md`` between its markers. ``--collect`` plays nothing: it
writes the CSV, summary and docs from the ``<game>_<noise>.json`` already
in ``--out`` (parts played by separate processes). ``--address`` plays the
matches as Ray tasks (``local``: Ray on this machine; ``auto`` or
``HOST:PORT``: a cluster), in chunks of ``--chunk-racks`` racks
(``agents.evaluation.distributed``, docs/distributed.md); the results are
the same as without it for the same chunks.
"""
from __future__ import annotations

import argparse
import csv
import io
import json
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from agents.evaluation.distributed import tournament  # noqa: E402
from billiards_env.bots.learned import ladder as L  # noqa: E402
from billiards_env.studies import match_report  # noqa: E402

from billiards_env.rules import GAMES as REGISTRY  # noqa: E402
GAMES = tuple(g for g in REGISTRY if L.ladder_names(g))  # the games with a shipped ladder
BOTS = ("ghost", "ghost-safety", "search64", "lookahead", "lookahead-2026.12", "value-lookahead", "champion",
        "champion-fast", "exit-search")
DOC = ROOT / "docs" / "ladder.md"
BEGIN, END = "<!-- ladder-table:begin -->", "<!-- ladder-table:end -->"


def plays(bot: str, game: str) -> bool:
    """Whether the built-in bot ``bot`` can play ``game`` (the play server's test, ``bot_problem``: a network or a
    measured player shipped for the game, bots written for other games refused)."""
    from billiards_env.play.app import bot_problem
    return bot_problem(bot, game) is None


def cards_table(games) -> str:
    lines = ["| game | agent | version | training steps | training wall (s) | trained against | checked positions |",
             "|---|---|---|---|---|---|---|"]
    for g in games:
        for n in L.ladder_names(g):
            c = L.card(g, n)
            lines.append(f"| {g} | {n} | {c['version']} | {c['training_steps']:,} | {c['training_wall_s']:.0f} | "
                         f"{c['trained_against']} | {c['checked_positions']} |")
    return "\n".join(lines) + "\n"


def csv_texts(docs: list) -> dict:
    """``ratings.csv`` and ``pairings.csv`` of the tournaments ``docs``, as text (the csv module's line ends)."""
    ratings, pairings = io.StringIO(newline=""), io.StringIO(newline="")
    w = csv.writer(ratings)
    w.writerow(["game", "noise", "entrant", "elo", "ci95_lo", "ci95_hi"])
    for d in docs:
        for r in d["ratings"]:
            w.writerow([d["game"], d["noise"], r["name"], f"{r['elo']:.1f}", f"{r['ci95'][0]:.1f}",
                        f"{r['ci95'][1]:.1f}"])
    w = csv.writer(pairings)
    w.writerow(["game", "noise", "a", "b", "games", "a_wins", "b_wins", "draws", "a_win_rate", "ci95_lo",
                "ci95_hi", "mean_shots"])
    for d in docs:
        for p in d["pairings"]:
            w.writerow([d["game"], d["noise"], p["a"], p["b"], p["games"], p["a_wins"], p["b_wins"], p["draws"],
                        f"{p['a_win_rate']:.3f}", f"{p['ci95'][0]:.3f}", f"{p['ci95'][1]:.3f}",
                        f"{p['mean_shots']:.1f}"])
    return {"ratings.csv": ratings.getvalue(), "pairings.csv": pairings.getvalue()}


def collect_command(docs: list) -> str:
    """The command quoted in ladder.md: the one that played every part, or the parts' and ``--collect``."""
    parts = sorted({d["command"] for d in docs})
    return (parts[0] if len(parts) == 1 else
            f"python scripts/ladder_table.py --racks {docs[0]['racks']}` (played as {len(parts)} processes, one per "
            f"game and noise level, then `python scripts/ladder_table.py --collect")


def collected(out: Path, docs: list, command: str, doc_text: str | None = None) -> dict:
    """Every file the tables of ``docs`` (the ``<game>_<noise>.json`` of ``out``) make, by path, as text:
    the CSVs, ``summary.md``, ``ladder.md`` and, given ``doc_text`` (docs/ladder.md), that page with the table
    between its markers. What ``--collect`` writes and scripts/regenerate.py renders."""
    games = [g for g in GAMES if any(d["game"] == g for d in docs)]
    files = {out / name: text for name, text in csv_texts(docs).items()}
    summary = match_report.summary(out)
    files[out / "summary.md"] = summary
    body = (f"`{command}`: {docs[0]['racks']} racks per pairing, each played twice (each side breaks once), seed "
            f"{docs[0]['seed']}.\n\nThe agents:\n\n{cards_table(games)}\nBradley-Terry ratings (Elo scale, mean 0 "
            f"per game and noise level; 95% bootstrap intervals over games):\n\n{summary}")
    files[out / "ladder.md"] = "# The ladder's cross table\n\n" + body
    if doc_text is not None:
        a, b = doc_text.index(BEGIN) + len(BEGIN), doc_text.index(END)
        files[DOC] = doc_text[:a] + "\n" + body + doc_text[b:]
    return files


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--games", nargs="+", choices=GAMES, default=list(GAMES))
    ap.add_argument("--noise", nargs="+", choices=match_report.NOISES, default=list(match_report.NOISES))
    ap.add_argument("--bots", nargs="+", default=list(BOTS), help="the built-in bots beside the ladder")
    ap.add_argument("--racks", type=int, default=20, help="racks per pairing (each played twice)")
    ap.add_argument("--seed", type=int, default=2026, help="match seed (not a training seed)")
    ap.add_argument("--max-shots", type=int, default=200)
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "ladder")
    ap.add_argument("--quick", action="store_true", help="ladder-1 v ghost, 2 racks, no noise (the test's run)")
    ap.add_argument("--collect", action="store_true", help="play nothing: tables and docs from the JSON in --out")
    ap.add_argument("--address", default=None,
                    help="play on Ray: local (a Ray instance here), auto or HOST:PORT (a cluster); default: this process")
    ap.add_argument("--chunk-racks", type=int, default=None, metavar="N",
                    help="racks played together (one Ray task each); default: all racks of a pairing")
    args = ap.parse_args(argv)
    if args.chunk_racks is not None and args.chunk_racks < 1:
        ap.error(f"--chunk-racks must be a positive integer, got {args.chunk_racks}")
    if args.quick:
        args.bots, args.racks, args.noise = ["ghost"], 2, ["none"]
    command = " ".join(["python", "scripts/ladder_table.py"] + (argv if argv is not None else sys.argv[1:]))
    docs = []
    for game in [] if args.collect else args.games:
        rungs = L.ladder_names(game)[:1] if args.quick else L.ladder_names(game)
        if not rungs:
            raise SystemExit(f"no ladder agents shipped for {game} (scripts/export_ladder.py writes them)")
        names = rungs + [b for b in args.bots if plays(b, game)]
        for noise in args.noise:
            t0 = time.perf_counter()
            results, table = tournament(names, game, args.racks, args.seed, noise, args.address, args.chunk_racks,
                                        args.max_shots)
            doc = dict(command=command, game=game, noise=noise, racks=args.racks, seed=args.seed,
                       seconds=time.perf_counter() - t0, pairings=[r.summary() for r in results], ratings=table)
            match_report.write(args.out / f"{game}_{noise}", doc, results, table)
            print(f"{game} {noise}: " + ", ".join(f"{t['name']} {t['elo']:.0f}" for t in table)
                  + f" ({doc['seconds']:.0f} s)", flush=True)
            docs.append(doc)
    if args.collect:
        docs = [json.loads(p.read_text()) for p in sorted(args.out.glob("*_*.json"))]
        if not docs:
            raise SystemExit(f"no <game>_<noise>.json in {args.out} to collect")
        command = collect_command(docs)
    to_docs = args.out.resolve() == (ROOT / "results" / "ladder").resolve() and DOC.exists()
    files = collected(args.out, docs, command, DOC.read_text() if to_docs else None)
    for path, text in files.items():
        path.write_text(text, newline="" if path.suffix == ".csv" else None)
    summary = files[args.out / "summary.md"]
    print(summary)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Reports of a tournament (``studies.matches``): the Markdown table of every
pairing and the ratings, the ratings plot, and one summary table over every
game and noise level written to a folder."""
from __future__ import annotations

import json
from pathlib import Path

from ..physics.noise import NOISE_LEVELS

NOISES = tuple(NOISE_LEVELS)  # the games' noise levels, in order (physics.noise.NOISE_LEVELS)


def markdown(title: str, command: str, results: list, table: list, seconds: float) -> str:
    """Every pairing's record and win rate [95% CI], then the ratings."""
    lines = [f"# {title}", "", f"`{command}` ({seconds:.0f} s)", "",
             "| a | b | games | a wins | b wins | draws | a win rate [95% CI] | a breaking / not | shots per game |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        s = r.summary()
        lines.append(f"| {s['a']} | {s['b']} | {s['games']} | {s['a_wins']} | {s['b_wins']} | {s['draws']} | "
                     f"{s['a_win_rate']:.3f} [{s['ci95'][0]:.3f}, {s['ci95'][1]:.3f}] | "
                     f"{s['a_win_rate_breaking']:.3f} / {s['a_win_rate_not_breaking']:.3f} | {s['mean_shots']:.1f} |")
    per = [r.summary() for r in results]
    if per and "a_points_per_inning" in per[0]:  # games to a score (three-cushion)
        lines += ["", "Points per inning (all of a side's points over all its innings):", "",
                  "| a | b | a points / inning | b points / inning |", "|---|---|---|---|"]
        lines += [f"| {s['a']} | {s['b']} | {s['a_points_per_inning']:.3f} | {s['b_points_per_inning']:.3f} |"
                  for s in per]
    lines += ["", "Bradley-Terry ratings (Elo scale, mean 0; 95% bootstrap intervals):", "",
              "| entrant | rating | 95% interval |", "|---|---|---|"]
    for t in table:
        lines.append(f"| {t['name']} | {t['elo']:.0f} | [{t['ci95'][0]:.0f}, {t['ci95'][1]:.0f}] |")
    return "\n".join(lines) + "\n"


def plot(table: list, path: Path, title: str) -> None:
    """The ratings with their 95% intervals (needs the ``plot`` extra)."""
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
    entrant's rating [95% interval] per game and noise level."""
    docs = [json.loads(p.read_text()) for p in sorted(Path(out).glob("*_*.json"))]
    if not docs:
        return "no match results\n"
    names = sorted({r["name"] for d in docs for r in d["ratings"]})
    lines = ["| game | noise | " + " | ".join(names) + " | seconds |", "|---|---|" + "---|" * (len(names) + 1)]
    for d in sorted(docs, key=lambda d: (d["game"], NOISES.index(d["noise"]))):
        r = {x["name"]: x for x in d["ratings"]}
        cells = [f"{r[n]['elo']:.0f} [{r[n]['ci95'][0]:.0f}, {r[n]['ci95'][1]:.0f}]" if n in r else "" for n in names]
        lines.append(f"| {d['game']} | {d['noise']} | " + " | ".join(cells) + f" | {d['seconds']:.0f} |")
    return "\n".join(lines) + "\n"


def write(stem: Path, doc: dict, results: list, table: list) -> str:
    """``<stem>.json``, ``.md`` and ``.png`` of a tournament; returns the Markdown."""
    stem.parent.mkdir(parents=True, exist_ok=True)
    stem.with_suffix(".json").write_text(json.dumps(doc, indent=2) + "\n")
    md = markdown(f"{doc['game']} matches, noise `{doc['noise']}`", doc["command"], results, table, doc["seconds"])
    stem.with_suffix(".md").write_text(md)
    plot(table, stem.with_suffix(".png"), f"{doc['game']}, noise {doc['noise']}")
    return md

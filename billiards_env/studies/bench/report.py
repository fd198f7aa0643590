"""What a run leaves: the Markdown tables (one file per section, joined in
benchmark.md; against.md for --against), benchmark.csv (every run's rows,
with the revision) and history.png (the headline figures over time)."""
from __future__ import annotations

import csv
import datetime
from pathlib import Path

import numba

from .options import ROOT, SECTION_NAMES

# the columns that name a row (the same row in two trees or two rounds)
ROW_KEY = ("section", "scene", "solver", "effects", "batch", "autoreset", "note")


def _solver_table(rows: list[dict], nt: int) -> list[str]:
    lines = ["| scene | solver | events/shot | shots/s, 1 thread | "
             f"shots/s, {nt} threads | single-table latency (ms) |", "|---|---|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['solver']} | {r['events_per_shot']:.1f} | {r['shots_per_s_1t']:,.0f} | "
                     f"{r[f'shots_per_s_{nt}t']:,.0f} | {r['latency_ms']:.3f} |")
    return lines + [""]


def _effects_table(rows: list[dict], nt: int) -> list[str]:
    lines = ["| scene | solver | effects | events/shot | simulated s/shot | µs per event or step | "
             f"shots/s, 1 thread | shots/s, {nt} threads | single-shot latency (ms) | speed-up vs all |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['solver']} | {r['effects']} | {r['events_per_shot']:.1f} | "
                     f"{r['sim_seconds_per_shot']:.2f} | {r['us_per_unit']:.2f} | {r['shots_per_s_1t']:,.0f} | "
                     f"{r[f'shots_per_s_{nt}t']:,.0f} | {r['latency_ms']:.3f} | {r['speedup_vs_all']:.2f}x |")
    return lines + [""]


def _impact_table(rows: list[dict]) -> list[str]:
    """The models section's per-impact cost (``impacts.impact_rows``)."""
    lines = ["| cushion model | impacts | µs per impact | vs the baseline |", "|---|---:|---:|---:|"]
    for r in rows:
        ratio = f"{r['vs_baseline']:.2f}x" if r.get("vs_baseline") else "-"
        lines.append(f"| {r['effects']} | {r['batch']} | {r['us_per_impact']:.3f} | {ratio} |")
    return lines + [""]


def _env_table(rows: list[dict]) -> list[str]:
    lines = ["| task | tables | autoreset | env steps/s | time in simulator | env overhead |",
             "|---|---:|---|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['scene']} | {r['batch']} | {r['autoreset']} | {r['env_steps_per_s']:,.0f} | "
                     f"{100 * r['sim_share']:.0f}% | {r['env_overhead_pct']:.0f}% |")
    return lines + [""]


def _cold_table(rows: list[dict]) -> list[str]:
    return ["| start | seconds |", "|---|---:|"] + [f"| {r['note']} | {r['seconds']:.2f} |" for r in rows]


def markdown(rows: list[dict]) -> str:
    """The tables of every section present in ``rows``, in a fixed order."""
    lines = []
    nt = numba.config.NUMBA_NUM_THREADS
    part = {k: [r for r in rows if r["section"] == k] for k in SECTION_NAMES.values()}
    if part["solver"]:
        lines += _solver_table(part["solver"], nt)
    impacts = [r for r in part["models"] if "us_per_impact" in r]
    if impacts:
        lines += _impact_table(impacts)
    for k in ("effects", "models", "airborne"):
        rest = [r for r in part[k] if "us_per_impact" not in r]
        if rest:
            lines += _effects_table(rest, nt)
    if part["env"]:
        lines += _env_table(part["env"])
    if part["rllib"]:  # the RLlib backend's section (agents/rllib/bench.py, plugged in by scripts/benchmark.py)
        from .sections import PLUGGED
        lines += PLUGGED["rllib"][1](part["rllib"])
    if part["cold start"]:
        lines += _cold_table(part["cold start"])
    return "\n".join(lines)


def write_tables(out_dir: Path, rows: list[dict], sections) -> Path:
    """One Markdown file per section of ``sections`` (so a partial run, --only,
    replaces only its own), and benchmark.md joining the latest of every
    section; returns benchmark.md's path."""
    for section in sections:
        part = markdown([r for r in rows if r["section"] == SECTION_NAMES[section]])
        (out_dir / f"{section}.md").write_text(part.rstrip("\n") + "\n")
    parts = [(out_dir / f"{k}.md").read_text() for k in SECTION_NAMES if (out_dir / f"{k}.md").exists()]
    path = out_dir / "benchmark.md"
    path.write_text("\n".join(parts))
    return path


# ------------------------------------------------------------------ CSV --
def append_csv(csv_path: Path, rows: list[dict]) -> None:
    """Append ``rows`` to the CSV; when they bring new columns the file is
    rewritten with the union of the columns, so the history stays in one file."""
    old_rows, old_keys = [], []
    if csv_path.exists():
        with csv_path.open(newline="") as f:
            reader = csv.DictReader(f)
            old_keys = list(reader.fieldnames or [])
            old_rows = list(reader)
    keys = sorted(set(old_keys) | {k for r in rows for k in r})
    if old_keys and set(keys) == set(old_keys):
        with csv_path.open("a", newline="") as f:
            csv.DictWriter(f, fieldnames=old_keys).writerows(rows)
        return
    with csv_path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(old_rows + rows)


# -------------------------------------------------------------- history --
# the figures history.png follows: (section, scene, solver, batch, autoreset, column, label)
HEADLINES = (
    ("solver", "9-ball break (8 m/s)", "event", "1024", "", "shots_per_s_1t", "9-ball breaks/s, 1 thread"),
    ("solver", "two-ball cut (2 m/s, top+side)", "event", "1024", "", "shots_per_s_1t",
     "two-ball cut shots/s, 1 thread"),
    ("env", "Billiards-PotOne-v1", "event", "1024", "same_step", "env_steps_per_s", "PotOne env steps/s, 1024 tables"),
    ("env", "Billiards-NineBall-v1", "event", "1024", "same_step", "env_steps_per_s",
     "NineBall env steps/s, 1024 tables"),
)


def history_rows(out_dir: Path) -> list[dict]:
    """Every full-size row of benchmark.csv and of the files older versions of
    this script set aside when the columns changed (benchmark.<stamp>.csv),
    without --quick runs and without the rows of --against comparisons."""
    rows, seen = [], set()
    for path in sorted(out_dir.glob("benchmark*.csv")):
        with path.open(newline="") as f:
            for r in csv.DictReader(f):
                key = (r.get("timestamp"), r.get("section"), r.get("scene"), r.get("solver"), r.get("effects"),
                       r.get("batch"), r.get("autoreset"), r.get("note"))
                if key in seen or r.get("quick") == "True" or r.get("compared_with"):
                    continue
                seen.add(key)
                rows.append(r)
    return rows


def _headline_points(rows: list[dict], headline: tuple) -> list[tuple]:
    section, scene, solver, batch, mode, col, _ = headline
    return sorted((datetime.datetime.fromisoformat(r["timestamp"]), float(r[col])) for r in rows
                  if r["section"] == section and r["scene"] == scene and r["solver"] == solver
                  and r["batch"] == batch and r.get("autoreset", "") == mode and r.get(col))


def plot_history(out_dir: Path) -> Path | None:
    """history.png: each headline figure against the date of its run
    (matplotlib: the ``plot`` extra); None when there is nothing to plot."""
    rows = history_rows(out_dir)
    if not rows:
        return None
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.5), sharex=True)
    for ax, headline in zip(axes.flat, HEADLINES):
        pts = _headline_points(rows, headline)
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-")
            ax.annotate(f"{pts[-1][1]:,.0f}", pts[-1], textcoords="offset points", xytext=(-10, 6), fontsize=8)
        ax.set_title(headline[-1], fontsize=10)
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
    fig.autofmt_xdate()
    where = out_dir.resolve()
    where = where.relative_to(ROOT) if where.is_relative_to(ROOT) else where
    fig.suptitle(f"Benchmark history ({where}/benchmark.csv, full runs)")
    fig.tight_layout()
    path = out_dir / "history.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


# -------------------------------------------------------------- against --
# per section: the figures compared, as (column, label)
COMPARED = {
    "solver": (("shots_per_s_1t", "shots/s, 1 thread"), ("latency_ms", "single-table latency (ms)")),
    "effects": (("shots_per_s_1t", "shots/s, 1 thread"), ("latency_ms", "single-shot latency (ms)")),
    "models": (("shots_per_s_1t", "shots/s, 1 thread"), ("latency_ms", "single-shot latency (ms)")),
    "env": (("env_steps_per_s", "env steps/s"),),
    "cold": (("seconds", "seconds"),),
}


def _figure(x) -> str:
    return "-" if not x else f"{x:,.0f}" if x >= 100 else f"{x:.4g}"


def _against_section(section: str, new: list[dict], old: dict, revs: tuple[str, str]) -> list[str]:
    """against.md's table of one section (``old``: the other tree's rows by ROW_KEY)."""
    figures = COMPARED[section]
    rs = [r for r in new if r["section"] == SECTION_NAMES[section]]
    if not rs:
        return []
    new_rev, old_rev = revs
    head = "| scene | solver | effects | tables | " + " | ".join(
        f"{lab}, {old_rev} | {lab}, {new_rev} | ratio" for _, lab in figures) + " |"
    lines = [f"## {SECTION_NAMES[section]}", "", head, "|---|---|---|---:|" + "---:|---:|---:|" * len(figures)]
    for r in rs:
        o = old.get(tuple(r.get(k) for k in ROW_KEY))
        cells = []
        for col, _ in figures:
            a, b = (o or {}).get(col), r.get(col)
            cells += [_figure(a), _figure(b), f"{b / a:.3f}" if a and b else "-"]
        kind = r.get("autoreset") or r.get("note") or r["effects"]
        lines.append(f"| {r['scene']} | {r['solver']} | {kind} | {r['batch']} | " + " | ".join(cells) + " |")
    return lines + [""]


def against_markdown(rows: list[dict], rev_spec: str) -> str:
    """against.md: per compared section, both trees' medians and their ratio."""
    new = [r for r in rows if r["tree"] == "new"]
    old = {tuple(r.get(k) for k in ROW_KEY): r for r in rows if r["tree"] == "old"}
    if not new:
        return ""
    new_rev, old_rev = new[0]["revision"], new[0]["compared_with"]
    lines = [f"# This tree ({new_rev}) against {rev_spec} ({old_rev})", "",
             f"Medians over {new[0]['rounds']} interleaved rounds (each a fresh process per tree and section, "
             "the same seeds); ratio = this tree / the other. Higher is better for rates, lower for latencies "
             "and seconds.", ""]
    for section in COMPARED:
        lines += _against_section(section, new, old, (new_rev, old_rev))
    return "\n".join(lines)

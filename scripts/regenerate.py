#!/usr/bin/env python
"""Regenerate every committed generated file that is derived from committed data, or check that it is current.

    python scripts/regenerate.py                 # rewrite every derived table from its committed source
    python scripts/regenerate.py --check         # render into a temporary folder; exit 1 naming each stale file
    python scripts/regenerate.py --list          # the inventory: every generated file, its generator, its kind
    python scripts/regenerate.py --only 'results/breaks/*'   # only the files matching a pattern (repeatable)

The committed generated files are of three kinds (``--list`` prints each file with its kind):

- **derived**: rendered from other committed files without running anything (a ``<game>_<noise>.md`` from its
  JSON, the ladder's CSVs and summary, ``results/benchmark/benchmark.md`` from the section tables, the generated
  blocks of docs/ladder.md, docs/agents_benchmark.md and docs/play.md, docs/environments.md from the task
  registry). This command rewrites them; ``--check`` fails when one differs from what its source gives, which
  the test suite runs (tests/test_generated.py), so CI keeps them current.
- **plot**: a PNG drawn from committed data. Listed, not checked (its bytes depend on the matplotlib and
  FreeType versions); its generator redraws it.
- **measured**: the data itself (a match's JSON, a benchmark CSV, a fuzz record, a trained agent's scores, a
  replay page): it needs a simulation or a training run, so it is never re-run here. ``--list`` prints the
  command that re-measures it where the file or its folder records one.

The renderers are the generators' own functions, imported (``scripts/match.py``'s ``match_markdown``,
``scripts/ladder_table.py``'s ``collected``, ...), so a table written by a run and the same table rendered here
are one function's output.
"""
from __future__ import annotations

import argparse
import dataclasses
import difflib
import fnmatch
import importlib.util
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Callable

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

CHEAP, PLOT, MEASURED = "derived", "plot", "measured"


@dataclasses.dataclass
class Entry:
    """One generated file: ``path`` (relative to the repository), its ``kind``, the ``command`` that
    regenerates it (derived, plot) or re-measures it (measured; "" when nothing records one), and for a derived
    file ``render(root) -> text`` from the committed sources under ``root`` and those ``sources``."""

    path: str
    kind: str
    command: str
    render: Callable[[Path], str] | None = None
    sources: tuple = ()


# ------------------------------------------------------------------ the generators, imported --
_SCRIPTS: dict = {}


def script(name: str):
    """A module of scripts/ by name (they are entry points, not a package)."""
    if name not in _SCRIPTS:
        spec = importlib.util.spec_from_file_location(f"_regenerate_{name}", ROOT / "scripts" / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod  # before it runs: its dataclasses look their module up there
        spec.loader.exec_module(mod)
        _SCRIPTS[name] = mod
    return _SCRIPTS[name]


def _json(path: Path):
    return json.loads(path.read_text())


def _is_tournament(doc) -> bool:
    return isinstance(doc, dict) and {"pairings", "ratings", "game", "noise", "command"} <= set(doc)


def _backtick_command(text: str) -> str:
    """The first `python ...` quoted in a page: the command a measured table records."""
    m = re.search(r"`(python [^`]+)`", text)
    return m.group(1) if m else ""


# --------------------------------------------------------------------------- the derived files --
def _tournaments(root: Path, files: list) -> list:
    """``<stem>.md`` of every ``<stem>.json`` tournament (matches, the ladder, the leagues, the championship's
    levels): ``scripts/match.py``'s ``match_markdown``."""
    out = []
    for rel in files:
        if not rel.endswith(".json") or rel[:-5] + ".md" not in files:
            continue
        try:
            doc = _json(root / rel)
        except ValueError:
            continue
        if not _is_tournament(doc):
            continue
        md = rel[:-5] + ".md"
        out.append(Entry(md, CHEAP, f"python scripts/regenerate.py (from {Path(rel).name}: scripts/match.py "
                         "match_markdown)",
                         lambda r, rel=rel: script("match").match_markdown(_json(r / rel)), (rel,)))
        if rel[:-5] + ".png" in files:
            out.append(Entry(rel[:-5] + ".png", PLOT, f"{doc['command']} (studies.match_report.plot)"))
        out.append(Entry(rel, MEASURED, doc["command"]))
    return out


def _championships(root: Path, files: list) -> list:
    out = []
    for rel in files:
        if Path(rel).name == "championship.json" and rel[:-5] + ".md" in files:
            doc = _json(root / rel)
            out.append(Entry(rel[:-5] + ".md", CHEAP, "python scripts/regenerate.py (scripts/match.py "
                             "championship_markdown)", lambda r, rel=rel: script("match").championship_markdown(
                                 _json(r / rel)), (rel,)))
            out.append(Entry(rel, MEASURED, doc["command"]))
    return out


def _summaries(root: Path, files: list) -> list:
    """``results/matches/summary.md`` (``scripts/match.py --summary --out results/matches``)."""
    out = []
    for folder in ("results/matches",):
        rel = f"{folder}/summary.md"
        if rel in files:
            from billiards_env.studies import match_report
            out.append(Entry(rel, CHEAP, f"python scripts/match.py --summary --out {folder}",
                             lambda r, folder=folder: match_report.summary(r / folder),
                             tuple(f for f in files if f.startswith(folder + "/") and f.count("/") == 2
                                   and f.endswith(".json"))))
    return out


def _ladder(root: Path, files: list) -> list:
    """``scripts/ladder_table.py --collect``: the CSVs, summary.md, ladder.md and docs/ladder.md's table."""
    folder = "results/ladder"
    jsons = tuple(f for f in files if f.startswith(folder + "/") and f.count("/") == 2 and f.endswith(".json"))
    if not jsons:
        return []

    def render_all(r: Path) -> dict:
        lt = script("ladder_table")
        docs = [_json(r / f) for f in sorted(jsons)]
        page = r / "docs" / "ladder.md"
        made = lt.collected(r / folder, docs, lt.collect_command(docs), page.read_text() if page.exists() else None)
        return {("docs/ladder.md" if p == lt.DOC else str(p.relative_to(r))): text for p, text in made.items()}

    cache: dict = {}

    def one(name):
        def render(r: Path) -> str:
            key = str(r)
            if key not in cache:
                cache[key] = render_all(r)
            return cache[key][name]
        return render

    names = [f"{folder}/{n}" for n in ("ratings.csv", "pairings.csv", "summary.md", "ladder.md")] + ["docs/ladder.md"]
    return [Entry(n, CHEAP, "python scripts/ladder_table.py --collect", one(n), jsons) for n in names if n in files]


def _breaks(root: Path, files: list) -> list:
    out = []
    for rel in files:
        if rel.startswith("results/breaks/") and rel.endswith(".json") and rel[:-5] + ".md" in files:
            doc = _json(root / rel)
            out.append(Entry(rel[:-5] + ".md", CHEAP, "python scripts/regenerate.py (scripts/break_stats.py "
                             "markdown)", lambda r, rel=rel: script("break_stats").markdown(_json(r / rel)), (rel,)))
            out.append(Entry(rel, MEASURED, doc["command"]))
    return out


def _budgets(root: Path, files: list) -> list:
    """``budgets_<game>_<noise>.md`` of scripts/lookahead_cost.py; the seed, which the JSON rows lack, is read
    from the committed page's command (0 when it names none)."""
    out = []
    for rel in files:
        m = re.fullmatch(r"(.*/)?budgets_(nine_ball|eight_ball|ten_ball)_(\w+)\.json", rel)
        if not m or rel[:-5] + ".md" not in files:
            continue
        md = rel[:-5] + ".md"
        command = _backtick_command((root / md).read_text())

        def render(r, rel=rel, md=md, game=m.group(2), noise=m.group(3)):
            seed = re.search(r"--seed (\d+)", (r / md).read_text()) if (r / md).exists() else None
            return script("lookahead_cost").budgets_markdown(game, noise, int(seed.group(1)) if seed else 0,
                                                            _json(r / rel))
        out.append(Entry(md, CHEAP, "python scripts/regenerate.py (scripts/lookahead_cost.py budgets_markdown)",
                         render, (rel,)))
        out.append(Entry(rel, MEASURED, command))
    return out


def _bench_join(root: Path, files: list) -> list:
    """``benchmark.md`` of a benchmark folder: its section tables joined in the sections' order
    (``studies.bench.report.write_tables`` with no new rows)."""
    from billiards_env.studies.bench.options import SECTION_NAMES
    out = []
    for folder in ("results/benchmark", "results/distributed"):
        if f"{folder}/benchmark.md" not in files:
            continue
        sections = tuple(f"{folder}/{k}.md" for k in SECTION_NAMES if f"{folder}/{k}.md" in files)

        def render(r, sections=sections):
            from billiards_env.studies.bench.report import write_tables
            with tempfile.TemporaryDirectory() as tmp:
                for s in sections:
                    shutil.copy(r / s, Path(tmp) / Path(s).name)
                return write_tables(Path(tmp), [], []).read_text()
        out.append(Entry(f"{folder}/benchmark.md", CHEAP, f"python scripts/benchmark.py --out {folder} --only "
                         "<section> (joins the sections' tables; studies.bench.report.write_tables)", render, sections))
        for s in sections:
            name = Path(s).stem
            out.append(Entry(s, MEASURED, f"python scripts/benchmark.py --out {folder} --only {name}"))
    return out


def _latency(root: Path, files: list) -> list:
    """results/play/latency.{md,csv} and docs/play.md's table from latency.json (``billiards_env.play.latency``)."""
    src = "results/play/latency.json"
    if src not in files:
        return []

    def table(r: Path) -> str:
        from unittest import mock

        from billiards_env.play import latency
        doc = _json(r / src)
        with mock.patch.object(latency.os, "cpu_count", return_value=doc["cpus"]):  # the measuring machine's
            return latency.table_md(doc["rows"], doc["fps"], doc["load"])

    def csv_text(r: Path) -> str:
        import csv
        import io
        buf = io.StringIO(newline="")
        w = csv.writer(buf)
        w.writerow(["bot", "measure", "n", "p50_ms", "p95_ms", "max_ms"])
        for row in _json(r / src)["rows"]:
            for k in ("shot", "bot_reply", "think"):
                w.writerow([row["bot"], k, row[k]["n"], f"{row[k]['p50']:.2f}", f"{row[k]['p95']:.2f}",
                            f"{row[k]['max']:.2f}"])
        return buf.getvalue()

    def page(r: Path) -> str:
        text = (r / "docs" / "play.md").read_text()
        a, b = "<!-- latency:start -->", "<!-- latency:end -->"
        return text[:text.index(a) + len(a)] + "\n" + table(r) + "\n" + text[text.index(b):]

    cmd = "python scripts/play_latency.py --docs"
    out = [Entry("results/play/latency.md", CHEAP, f"{cmd} (from latency.json: play.latency.table_md)",
                 lambda r: table(r) + "\n", (src,)),
           Entry("results/play/latency.csv", CHEAP, f"{cmd} (from latency.json)", csv_text, (src,)),
           Entry(src, MEASURED, cmd)]
    if "docs/play.md" in files and "<!-- latency:start -->" in (root / "docs" / "play.md").read_text():
        out.append(Entry("docs/play.md", CHEAP, f"{cmd} (its table from results/play/latency.json)", page, (src,)))
    return [e for e in out if e.path in files]


def _agents_benchmark(root: Path, files: list) -> list:
    src, page = "results/agents/benchmark/benchmark.json", "docs/agents_benchmark.md"
    if src not in files or page not in files:
        return []

    def render(r: Path) -> str:
        from agents.benchmark import markdown_table
        out = r / "results" / "agents" / "benchmark"
        return script("benchmark_agents").doc_with_table((r / page).read_text(),
                                                         markdown_table(_json(r / src), out))
    return [Entry(page, CHEAP, "python scripts/benchmark_agents.py --table-only", render, (src,)),
            Entry(src, MEASURED, "python scripts/benchmark_agents.py --all")]


def _env_docs(root: Path, files: list) -> list:
    if "docs/environments.md" not in files:
        return []
    return [Entry("docs/environments.md", CHEAP, "python scripts/make_env_docs.py",
                  lambda r: script("make_env_docs").render(),
                  ("billiards_env/envs/tasks", "billiards_env/envs/billiards.py", "scripts/make_env_docs.py"))]


def _reference_agents(root: Path, files: list) -> list:
    """The reference agents' table (``agents.evaluation.reference``): ``table.md`` from the units' results files
    (and the reference bots' rows in billiards_env/benchmark/reference.json); the units themselves are measured."""
    folder = "results/suite/agents"
    page = f"{folder}/table.md"
    if page not in files:
        return []

    def render(r: Path) -> str:
        from agents.evaluation.reference import collect, table_text
        return table_text(collect(r / folder))
    cmd = f"python -m agents.evaluation.reference --jobs 2 --out {folder}"
    units = [f for f in files if f.startswith(folder + "/") and f.endswith(".json") and "/seed" in f]
    out = [Entry(page, CHEAP, f"{cmd} (its table: agents.evaluation.reference.table_text)", render, tuple(units))]
    out += [Entry(f, MEASURED, cmd) for f in units]
    out += [Entry(f, PLOT, cmd) for f in files if f.startswith(folder + "/") and f.endswith(".png")]
    out += [Entry(f, MEASURED, cmd) for f in files if f == f"{folder}/aggregate.json"]
    return out


DERIVED = (_tournaments, _championships, _summaries, _ladder, _breaks, _budgets, _bench_join, _latency,
           _agents_benchmark, _env_docs, _reference_agents)

# Measured files by folder (first match wins): the command that re-measures them, when the file records none.
MEASURED_BY_FOLDER = (
    ("results/accuracy/cushion_models.*", "python scripts/cushion_curves.py"),
    ("results/accuracy/models.*", "python scripts/accuracy_vs_time.py --models"),
    ("results/accuracy/*", "python scripts/accuracy_vs_time.py"),
    ("results/benchmark/benchmark*.csv", "python scripts/benchmark.py --out results/benchmark"),
    ("results/benchmark/history.png", "python scripts/benchmark.py --history --out results/benchmark"),
    ("results/benchmark/against*.md", "python scripts/benchmark.py --against <REV> --out results/benchmark"),
    ("results/benchmark/games.md", "python scripts/benchmark.py --out results/benchmark --only games"),
    ("results/benchmark/snooker.md", "python scripts/benchmark.py --out results/benchmark --only snooker"),
    ("results/distributed/history.png", "python scripts/benchmark.py --history --out results/distributed"),
    ("results/distributed/benchmark.csv", "python scripts/benchmark.py --out results/distributed --only rllib"),
    ("results/distributed/match_throughput.json", "python scripts/match_throughput.py"),
    ("results/fuzz/*", "python scripts/fuzz.py (its options are in the record)"),
    ("results/agents/benchmark/*", "python scripts/benchmark_agents.py --all"),
    ("results/agents/tuning*", "python scripts/tune.py (docs/tuning.md)"),
    ("results/agents/nineball_shot_stats.json", "python scripts/shot_stats.py"),
    ("results/agents/learning_curve.png", "python scripts/plot_learning_curve.py"),
    ("results/agents/*", "python scripts/evaluate.py (docs/agents.md)"),
    ("results/suite/reference/*/results.png", "python -m agents.evaluation.benchmark score (the command in "
                                              "results.json)"),
    ("results/ladder/*", "python scripts/ladder_table.py"),
    ("results/league/*", "python scripts/league.py / scripts/match.py (docs/league.md)"),
    ("docs/gallery/*", "python scripts/replay.py (the commands in docs/replay.md)"),
)
EXTRA_MEASURED = {  # committed generated files outside results/ and docs/gallery
    "tests/envs/env_fingerprints.json": "python -m billiards_env.testing.fingerprints --write",
    "billiards_env/benchmark/reference.json": "python -m agents.evaluation.benchmark score --policy <bot> --task "
                                              "all --reference (and python -m agents.evaluation.reference "
                                              "--reference): rows merged run by run",
}


def committed(root: Path) -> list:
    """The files the inventory covers: git's files under results/ and docs/ (all of them, when ``root`` is not
    a checkout: a copy in the tests), plus the generated files elsewhere."""
    try:
        out = subprocess.run(["git", "ls-files", "results", "docs"], cwd=root, capture_output=True, text=True,
                             check=True).stdout.split()
    except (subprocess.CalledProcessError, FileNotFoundError):
        out = []
    if not out or not (root / ".git").exists():
        out = [str(p.relative_to(root)) for d in ("results", "docs") if (root / d).exists()
               for p in (root / d).rglob("*") if p.is_file()]
    return sorted(set(out) | {f for f in EXTRA_MEASURED if (root / f).exists()})


def inventory(root: Path = ROOT) -> list:
    """Every generated file under ``root``: the derived ones, then every other committed file of results/ (and
    docs/gallery, the measured extras) as measured (or plot), each with its command where one is known."""
    files = committed(root)
    entries: dict = {}
    for find in DERIVED:
        for e in find(root, files):
            if e.path not in entries or entries[e.path].kind != CHEAP:
                entries[e.path] = e
    for rel in files:
        if rel in entries or not (rel.startswith("results/") or rel.startswith("docs/gallery/")
                                  or rel in EXTRA_MEASURED):
            continue
        kind = PLOT if rel.endswith(".png") else MEASURED
        entries[rel] = Entry(rel, kind, _measured_command(root, rel))
    return sorted(entries.values(), key=lambda e: e.path)


def _measured_command(root: Path, rel: str) -> str:
    if rel in EXTRA_MEASURED:
        return EXTRA_MEASURED[rel]
    path = root / rel
    for folder in path.parents:  # a training run's record: its command.txt
        if folder == root or folder == root / "results":
            break
        if (folder / "command.txt").exists():
            return (folder / "command.txt").read_text().strip().splitlines()[0]
    for sibling in (path.with_suffix(".json"), path.with_suffix(".md"), path):
        if not sibling.exists() or sibling.stat().st_size > 2_000_000:
            continue
        if sibling.suffix == ".json":
            try:
                doc = _json(sibling)
            except ValueError:
                continue
            if isinstance(doc, dict) and isinstance(doc.get("command"), str):
                return doc["command"]
        elif sibling.suffix == ".md":
            cmd = _backtick_command(sibling.read_text()[:3000])
            if cmd:
                return cmd
    for pattern, cmd in MEASURED_BY_FOLDER:
        if fnmatch.fnmatch(rel, pattern):
            return cmd
    return ""


# ------------------------------------------------------------------------------- the actions --
def select(entries: list, only) -> list:
    return [e for e in entries if not only or any(fnmatch.fnmatch(e.path, p) for p in only)]


def render_into(entries: list, root: Path, dest: Path) -> list:
    """Render every derived entry from the sources under ``root`` into ``dest`` (same relative paths); returns
    [(entry, error)] of the renders that failed."""
    failed = []
    for e in entries:
        if e.kind != CHEAP:
            continue
        try:
            text = e.render(root)
        except Exception as exc:  # a source the renderer cannot read: reported, not fatal to the others
            failed.append((e, f"{type(exc).__name__}: {exc}"))
            continue
        out = dest / e.path
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text, newline="")
    return failed


def check(root: Path = ROOT, only=(), verbose: bool = True) -> list:
    """Render every derived file into a temporary folder and compare it with the committed one; returns the
    stale entries as [(entry, why)] (empty: every derived file is current)."""
    entries = [e for e in select(inventory(root), only) if e.kind == CHEAP]
    stale = []
    with tempfile.TemporaryDirectory(prefix="regenerate-") as tmp:
        failed = render_into(entries, root, Path(tmp))
        stale += [(e, f"its generator failed: {err}") for e, err in failed]
        bad = {e.path for e, _ in failed}
        for e in entries:
            if e.path in bad:
                continue
            new, old = (Path(tmp) / e.path).read_bytes(), (root / e.path).read_bytes()
            if new != old:
                diff = difflib.unified_diff(old.decode(errors="replace").splitlines(),
                                            new.decode(errors="replace").splitlines(),
                                            f"{e.path} (committed)", f"{e.path} (regenerated)", lineterm="", n=1)
                stale.append((e, "\n".join(list(diff)[:12])))
    if verbose:
        for e, why in stale:
            print(f"STALE {e.path}\n  fix: {e.command}\n" + "".join(f"  | {line}\n" for line in why.splitlines()))
        print(f"{len(entries) - len(stale)} of {len(entries)} derived files current" +
              (f"; {len(stale)} stale: python scripts/regenerate.py rewrites them" if stale else ""))
    return stale


def regenerate(root: Path = ROOT, only=()) -> list:
    """Rewrite every derived file (matching ``only``) from its sources; returns the paths that changed."""
    entries = [e for e in select(inventory(root), only) if e.kind == CHEAP]
    changed = []
    with tempfile.TemporaryDirectory(prefix="regenerate-") as tmp:
        failed = render_into(entries, root, Path(tmp))
        for e, err in failed:
            print(f"FAILED {e.path}: {err}", file=sys.stderr)
        bad = {e.path for e, _ in failed}
        for e in entries:
            if e.path in bad:
                continue
            new = (Path(tmp) / e.path).read_bytes()
            if not (root / e.path).exists() or (root / e.path).read_bytes() != new:
                (root / e.path).write_bytes(new)
                changed.append(e.path)
                print(f"rewrote {e.path}")
    print(f"{len(changed)} of {len(entries)} derived files rewritten")
    return changed if not failed else changed + [None]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--check", action="store_true", help="fail (exit 1) naming each stale derived file")
    mode.add_argument("--list", action="store_true", help="print the inventory: file, kind, command")
    ap.add_argument("--only", action="append", default=[], metavar="GLOB", help="only the files matching GLOB")
    ap.add_argument("--kind", choices=(CHEAP, PLOT, MEASURED), default=None, help="--list: only this kind")
    ap.add_argument("--root", type=Path, default=ROOT, help="the tree to check or rewrite (default: this checkout)")
    a = ap.parse_args(argv)
    if a.list:
        entries = [e for e in select(inventory(a.root), a.only) if a.kind in (None, e.kind)]
        for e in entries:
            print(f"{e.path}\t{e.kind}\t{e.command or '-'}")
        counts = {k: sum(e.kind == k for e in entries) for k in (CHEAP, PLOT, MEASURED)}
        print(f"{len(entries)} files: " + ", ".join(f"{n} {k}" for k, n in counts.items()), file=sys.stderr)
        return 0
    if a.check:
        return 1 if check(a.root, a.only) else 0
    return 1 if None in regenerate(a.root, a.only) else 0


if __name__ == "__main__":
    sys.exit(main())

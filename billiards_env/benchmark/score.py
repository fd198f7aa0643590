"""Normalized scores, the reference rows, and the results files of the benchmark.

``normalized_score(task, score)``: ``(score - baseline) / (reference - baseline)`` with both anchors the mean
over runs of the ``REFERENCE`` rows of the task's ``baseline`` (``random``) and ``reference`` bot, measured
under the protocol (``reference.json`` beside this module, written by the scoring command:
``python -m agents.evaluation.benchmark score --policy <bot> --task all --reference``).

A results file (``results.json`` of a scoring run; docs/benchmark.md) holds::

    {"schema": "billiards_env.benchmark/1", "protocol": 1, "quick": false,
     "policy": "ghost", "algorithm": "ghost", "budget": null,           # env steps trained (null: a bot)
     "command": "...", "commit": "...", "created": "2026-12-07T05:00:00+00:00",
     "tasks": {"Billiards-PotOne-v1": {
         "runs": [{"run": 0, "eval_seed": 900000, "episodes": 500, "score": 0.71, "ci95": [0.67, 0.75],
                   "mean_reward": 0.79, "wall_time_s": 1.5}, ...],
         "score": 0.70, "normalized": [0.78, ...]}}}

``REFERENCE`` rows (``Row``: task, algorithm, budget, per-run scores) come from the same files.
"""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np

from .protocol import PROTOCOL, Protocol

SCHEMA = "billiards_env.benchmark/1"
REFERENCE_FILE = Path(__file__).with_name("reference.json")


@dataclasses.dataclass(frozen=True)
class Row:
    """A reference row: ``algorithm`` (a bot's name, or an agent's algorithm) on ``task`` (an env id), trained
    ``budget`` env steps (None: a bot), its score per run."""

    task: str
    algorithm: str
    budget: int | None
    scores: tuple

    @property
    def mean(self) -> float:
        return float(np.mean(self.scores))


def load_reference(path=REFERENCE_FILE) -> tuple:
    """The rows of a reference file (a results file's rows; empty when there is none)."""
    path = Path(path)
    if not path.exists():
        return ()
    doc = json.loads(path.read_text())
    return tuple(Row(r["task"], r["algorithm"], r["budget"], tuple(r["scores"])) for r in doc["rows"])


REFERENCE = load_reference()


def rows_of(results: dict) -> list:
    """The rows of a results document (one per task)."""
    return [Row(task, results["algorithm"], results.get("budget"), tuple(r["score"] for r in t["runs"]))
            for task, t in results["tasks"].items()]


def anchors(task: str, reference=None, protocol: Protocol = PROTOCOL) -> tuple:
    """(score of the baseline, score of the reference bot) of ``task``: the means of their rows."""
    t = protocol.task(task)
    rows = REFERENCE if reference is None else reference

    def one(name):
        found = [r for r in rows if r.task == t.env_id and r.algorithm == name]
        if not found:
            raise ValueError(f"no reference row of {name!r} on {t.env_id}: measure it with the scoring command "
                             f"(docs/benchmark.md, 'Reference rows')")
        return found[0].mean

    lo, hi = one(t.baseline), one(t.reference)
    if not hi > lo:
        raise ValueError(f"{t.env_id}: the reference {t.reference} ({hi:.3f}) does not beat {t.baseline} ({lo:.3f})")
    return lo, hi


def normalized_score(task: str, score, reference=None, protocol: Protocol = PROTOCOL):
    """``score`` on ``task`` (an id or short name) normalized: 0 = the ``random`` policy's score,
    1 = the task's reference bot's (``protocol.Task.reference``), both from ``REFERENCE``."""
    lo, hi = anchors(task, reference, protocol)
    return (np.asarray(score, dtype=np.float64) - lo) / (hi - lo) if np.ndim(score) else (float(score) - lo) / (hi - lo)


def check_results(doc: dict) -> dict:
    """``doc`` if it is a results document of this schema (ValueError naming what is wrong otherwise)."""
    if not isinstance(doc, dict) or doc.get("schema") != SCHEMA:
        raise ValueError(f"not a benchmark results file (schema {SCHEMA!r} expected)")
    version = doc.get("protocol")
    if not isinstance(version, int) or not 1 <= version <= PROTOCOL.version:
        raise ValueError(f"results of protocol {version!r}; this is protocol {PROTOCOL.version}")
    for key in ("policy", "algorithm", "tasks"):
        if key not in doc:
            raise ValueError(f"results file without {key!r}")
    for task, t in doc["tasks"].items():
        spec = PROTOCOL.task(task)
        if version < spec.since:
            raise ValueError(f"{task}: scored under protocol {version}; its evaluation changed in protocol "
                             f"{spec.since}: score it again")
        if doc.get("budget") is not None and version < PROTOCOL.budgets_since:
            raise ValueError(f"{task}: a trained agent's row of protocol {version}, whose budgets differ from "
                             f"protocol {PROTOCOL.version}'s: train it again at this protocol's budget")
        if not t.get("runs") or any("score" not in r for r in t["runs"]):
            raise ValueError(f"{task}: no runs with a score")
    return doc


def load_results(path) -> dict:
    return check_results(json.loads(Path(path).read_text()))


def write_reference(docs, path=REFERENCE_FILE) -> Path:
    """Write the rows of results documents (full protocol, not quick) as the reference file."""
    rows = []
    for doc in docs:
        check_results(doc)
        if doc.get("quick"):
            raise ValueError("quick results are no reference")
        rows += [dataclasses.asdict(r) | {"scores": list(r.scores)} for r in rows_of(doc)]
    rows.sort(key=lambda r: ([t.env_id for t in PROTOCOL.tasks].index(r["task"]), r["algorithm"]))
    doc = {"about": "The benchmark's reference rows (billiards_env/benchmark/score.py), measured with the scoring "
                    f"command under protocol {PROTOCOL.version} (bots' rows from the protocol their task's evaluation "
                    f"dates from, Task.since); see docs/benchmark.md", "protocol": PROTOCOL.version, "rows": rows}
    Path(path).write_text(json.dumps(doc, indent=1) + "\n")
    return Path(path)

#!/usr/bin/env python
"""Regenerate the agents' benchmark table (docs/agents_benchmark.md).

    python scripts/benchmark_agents.py                       # every configured task x algo, config budgets
    python scripts/benchmark_agents.py --all                 # ... and the other configs of the table (hours)
    python scripts/benchmark_agents.py --steps 100000 --task Billiards-RunOut-v1 --algo ppo
    python scripts/benchmark_agents.py --quick --out /tmp/bench   # smoke test (tiny runs, 20 episodes)
    python scripts/benchmark_agents.py --config configs/ppo_direct.yaml --task Billiards-PotOne-v1 --algo ppo
    python scripts/benchmark_agents.py --from-run runs/ppo_nineball --config configs/ppo_nineball.yaml

Trains PPO and SAC on every task that has a block in configs/<algo>.yaml,
records a held-seed learning curve, evaluates each final model on
--episodes held tables without noise and with tournament noise, and writes
<out>/benchmark.json, <out>/learning_curves.png and the Markdown table
(between the markers of --doc; in quick mode into <out>/benchmark.md).
A run replaces the row of its (task, algo) in <out>/benchmark.json and keeps
the others, so the table can be filled one invocation at a time. Runs
shorter than the config's budget are labelled as such in the table.
--from-run adds the row of a run already trained with scripts/train.py
(with train.eval_every > 0 for its curve) instead of training one.
"""
from __future__ import annotations

import argparse
import json
import shlex
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

BEGIN, END = "<!-- benchmark table: begin -->", "<!-- benchmark table: end -->"
QUICK = ("n_envs=16", "policy.net_arch=[16]", "ppo.n_steps=16", "ppo.batch_size=64", "ppo.n_epochs=1",
         "sac.learning_starts=64", "sac.batch_size=64", "sac.gradient_steps=1", "sac.buffer_size=4096")


def doc_with_table(text: str | None, table_md: str) -> str:
    """The page ``text`` (None: a new one) with ``table_md`` between the markers (appended when it has none):
    what the command writes to --doc and scripts/regenerate.py renders from <out>/benchmark.json."""
    table = f"{BEGIN}\n{table_md}\n{END}"
    text = text if text is not None else f"# Agents' benchmark\n\n{BEGIN}\n{END}\n"
    if BEGIN in text and END in text:
        return text[:text.index(BEGIN)] + table + text[text.index(END) + len(END):]
    return text + "\n" + table + "\n"


def main(argv=None) -> int:
    from agents.benchmark import (ALGOS, TABLE_CONFIGS, TASKS, Budget, markdown_table, plot_curves, row_from_run,
                                  run_benchmark, store_row, table_configs)

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--task", action="append", default=None, help=f"env id (repeatable; default {', '.join(TASKS)})")
    ap.add_argument("--algo", action="append", default=None, choices=ALGOS)
    ap.add_argument("--steps", type=int, default=None, help="training budget per run (default: the config's)")
    ap.add_argument("--episodes", type=int, default=1000, help="held evaluation tables per noise setting")
    ap.add_argument("--curve-points", type=int, default=10)
    ap.add_argument("--curve-episodes", type=int, default=1000)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="override for every run")
    ap.add_argument("--config", default=None,
                    help="YAML of the runs (default configs/<algo>.yaml); its rows sit beside the default's")
    ap.add_argument("--all", action="store_true",
                    help=f"the default configs and every other config of the table ({', '.join(TABLE_CONFIGS)}): "
                         "every row, at the configs' budgets")
    ap.add_argument("--out", default=str(ROOT / "results" / "agents" / "benchmark"))
    ap.add_argument("--doc", default=str(ROOT / "docs" / "agents_benchmark.md"))
    ap.add_argument("--quick", action="store_true", help="tiny runs (1,024 steps, 20 episodes) for the tests")
    ap.add_argument("--table-only", action="store_true", help="rewrite the table and plot from <out>/benchmark.json")
    ap.add_argument("--from-run", default=None, metavar="RUN_DIR",
                    help="add the row of a run trained with scripts/train.py (label it with --config)")
    a = ap.parse_args(argv)
    extra = tuple(a.set)
    if a.quick:
        a.steps, a.episodes, a.curve_points, a.curve_episodes = 1024, 20, 2, 20
        extra = QUICK + extra
    out = Path(a.out)
    command = "python " + " ".join(shlex.quote(x) for x in [sys.argv[0]] + list(argv if argv is not None else sys.argv[1:]))
    if a.table_only:
        rows = json.loads((out / "benchmark.json").read_text())
    elif a.from_run:
        out.mkdir(parents=True, exist_ok=True)
        rows = store_row(out, row_from_run(a.from_run, out, a.episodes, command, a.config))
    else:
        if a.all and a.config:
            ap.error("--all runs every config of the table; leave out --config")
        budget = Budget(a.steps, a.episodes, a.curve_points, a.curve_episodes, tuple(extra))
        rows = run_benchmark(out, a.task or TASKS, a.algo or ALGOS, budget, command, a.config,
                             table_configs() if a.all else None)
    plot_curves(rows, out / "learning_curves.png")
    doc = out / "benchmark.md" if a.quick else Path(a.doc)
    doc.write_text(doc_with_table(doc.read_text() if doc.exists() else None, markdown_table(rows, out)))
    print(markdown_table(rows, out))
    print(f"\nwrote {doc}, {out / 'benchmark.json'}, {out / 'learning_curves.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

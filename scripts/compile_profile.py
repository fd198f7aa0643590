"""Where the cold start's compile time goes: runs "import + first 9-ball
break" (``COLD_START_CODE`` of ``scripts/benchmark.py``) in this process
with an empty numba cache and prints, per compiled function, how often it
was compiled and the process CPU seconds of its compilations, inclusive
(with the functions it compiled on the way) and exclusive (its own type
inference, lowering and LLVM optimisation); and how many times numba
inlined each ``inline="always"`` helper into a caller at the IR level
(every inlined copy is type-inferred and optimised again with its caller).

    PYTHONPATH=. python scripts/compile_profile.py
"""
from __future__ import annotations

import argparse
import collections
import os
import sys
import tempfile
import time
from pathlib import Path


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--top", type=int, default=25, help="rows of the table (largest exclusive time first)")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as cache:
        os.environ["NUMBA_CACHE_DIR"] = cache  # before numba is imported: an empty cache
        return profile(args.top)


def profile(top: int) -> int:
    t_start = time.process_time()
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from benchmark import COLD_START_CODE  # the scene is defined once, there (it imports numba, compiles nothing)
    from numba.core import event
    from numba.core.inline_closurecall import InlineWorker

    inlined = collections.Counter()
    inline_function = InlineWorker.inline_function

    def counting_inline(self, caller_ir, block, i, function, *a, **k):
        inlined[(function.__qualname__, caller_ir.func_id.func_qualname)] += 1
        return inline_function(self, caller_ir, block, i, function, *a, **k)

    InlineWorker.inline_function = counting_inline

    calls = collections.Counter()
    inclusive = collections.Counter()
    exclusive = collections.Counter()
    stack = []  # [name, start CPU time, CPU time of nested compilations]

    class CpuListener(event.Listener):
        def on_start(self, ev):
            stack.append([ev.data["dispatcher"].py_func.__qualname__, time.process_time(), 0.0])

        def on_end(self, ev):
            name, t0, nested = stack.pop()
            dt = time.process_time() - t0
            calls[name] += 1
            inclusive[name] += dt
            exclusive[name] += dt - nested
            if stack:
                stack[-1][2] += dt

    llvm = [0.0, 0.0]  # CPU seconds holding numba's LLVM lock (optimising, emitting machine code), start

    class LlvmListener(event.Listener):
        def on_start(self, ev):
            llvm[1] = time.process_time()

        def on_end(self, ev):
            llvm[0] += time.process_time() - llvm[1]

    with event.install_listener("numba:compile", CpuListener()), \
            event.install_listener("numba:llvm_lock", LlvmListener()):
        print("wall time of the scene (s): ", end="")
        exec(COLD_START_CODE, {})  # (prints its wall time)
    total = time.process_time() - t_start
    print(f"process CPU: {total:.2f} s; "
          f"in numba compilations: {sum(exclusive.values()):.2f} s, of which in LLVM {llvm[0]:.2f} s; "
          f"{sum(calls.values())} compilations of {len(calls)} functions\n")
    print("| function | compilations | CPU s, inclusive | CPU s, exclusive |\n|---|---:|---:|---:|")
    for name, ex in exclusive.most_common(top):
        print(f"| `{name}` | {calls[name]} | {inclusive[name]:.2f} | {ex:.2f} |")
    print("\n| inlined helper | into | copies |\n|---|---|---:|")
    for (callee, caller), n in sorted(inlined.items()):
        print(f"| `{callee}` | `{caller}` | {n} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

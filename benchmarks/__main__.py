"""``make bench``: run every benchmark of the project, each in its own process, then one table.

A benchmark run after others in one process would inherit what they left on the heap: every
``gc.collect()`` it makes between two measurements traverses that too (about 20 ms after the
AADL syntax benchmark alone), and the allocator starts from another state. So each module runs
as ``python -m benchmarks.bench_NAME`` in a process of its own, prints its own table as it goes,
and hands its rows back as JSON in the file named by ``$ROSAADL_BENCH_ROWS``
(``benchmarks.harness``); the table at the end gathers the headline rows of every module:
measure, ours, wall, reference (the floor or the other tool), ratio, goal and whether it is met.

``python -m benchmarks NAME ...`` runs only the named ones (``aaxl2`` or ``bench_aaxl2``);
``--all`` puts the detail rows (per corpus file, say) in the final table too.
"""

from __future__ import annotations

import os
import pkgutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.harness import ROWS_ENV, Row, format_table, read_rows


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    every_row = "--all" in args
    only = {a for a in args if a != "--all"}
    folder = Path(__file__).resolve().parent
    names = sorted(m.name for m in pkgutil.iter_modules([str(folder)]) if m.name.startswith("bench_"))
    status = 0
    rows: list[Row] = []
    failed: list[str] = []
    with tempfile.TemporaryDirectory(prefix="rosaadl-bench-") as scratch:
        for name in names:
            if only and name not in only and name.removeprefix("bench_") not in only:
                continue
            print(f"\n=== {name} ===", flush=True)
            target = Path(scratch) / f"{name}.json"
            environment = {**os.environ, ROWS_ENV: str(target)}
            start = time.perf_counter()
            command = [sys.executable, "-m", f"benchmarks.{name}"]
            code = subprocess.run(command, cwd=folder.parent, env=environment).returncode
            status = status or code
            print(f"--- {name}: {time.perf_counter() - start:.1f} s", flush=True)
            found = read_rows(target)
            if not found:
                failed.append(f"{name} reported no rows (exit status {code})")
            rows.extend(r for r in found if every_row or not r.detail)
    print("\n=== every benchmark (CPU time; ratio = ours / reference) ===")
    print(format_table(rows, modules=True))
    for line in failed:
        print(line)
    missed = [r for r in rows if r.verdict == "MISSED"]
    if missed:
        print(f"{len(missed)} goal(s) missed: " + "; ".join(f"{r.module}: {r.measure}" for r in missed))
    return status or (1 if failed else 0)


if __name__ == "__main__":
    raise SystemExit(main())

"""``make bench``: run every benchmark of the project, one after the other, each in its own process.

A benchmark run after others in one process would inherit what they left on the heap: every
``gc.collect()`` it makes between two measurements traverses that too (about 20 ms after the
AADL syntax benchmark alone), and the allocator starts from another state. ``python -m
benchmarks NAME ...`` runs only the named ones (``aaxl2`` or ``bench_aaxl2``).
"""

from __future__ import annotations

import pkgutil
import subprocess
import sys
import time
from pathlib import Path


def main() -> int:
    folder = Path(__file__).resolve().parent
    names = sorted(m.name for m in pkgutil.iter_modules([str(folder)]) if m.name.startswith("bench_"))
    only = set(sys.argv[1:])
    status = 0
    for name in names:
        if only and name not in only and name.removeprefix("bench_") not in only:
            continue
        print(f"\n=== {name} ===", flush=True)
        start = time.perf_counter()
        code = subprocess.run([sys.executable, "-m", f"benchmarks.{name}"], cwd=folder.parent).returncode
        status = status or code
        print(f"--- {name}: {time.perf_counter() - start:.1f} s", flush=True)
    return status


if __name__ == "__main__":
    raise SystemExit(main())

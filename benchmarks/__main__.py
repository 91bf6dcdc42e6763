"""``make bench``: run every benchmark of the project, one after the other, in one process tree."""

from __future__ import annotations

import importlib
import pkgutil
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
        module = importlib.import_module(f"benchmarks.{name}")
        code = module.main([]) or 0
        status = status or code
        print(f"--- {name}: {time.perf_counter() - start:.1f} s", flush=True)
    return status


if __name__ == "__main__":
    raise SystemExit(main())

"""Throughput of the AADL text reader (the package ``importers/aadl_text/``), next to the parser alone.

Side by side, in MB/s of AADL text (wall clock, and CPU time of this process, which is what
counts on a shared machine), on every ``.aadl``/``.aadl2`` file of the real-world corpus
(``$ROSAADL_CORPUS`` or ``../shared/corpus``) and on the generated package of
``bench_aadl_syntax`` (10 000 components: threads with ports, flows and properties in processes
with connections and contained property associations):

  * ``parse``: ``aadl_syntax.parse`` alone, the floor of the reader;
  * ``read_string``: parse and build the model (``rosaadl.importers.aadl_text.read_string``);
  * ``read_files``: the file read from disk, the component library added and every name, unit
    and enumeration literal checked across all units (generated package only: the corpus is
    many separate projects).

Usage: ``python benchmarks/bench_aadl_reader.py [--repeat N] [--components N]``.
Target of the issue: the reader reads >= 1 MB/s.
"""

from __future__ import annotations

import argparse
import gc
import logging
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

__all__ = ["main"]

try:
    from benchmarks.bench_aadl_syntax import corpus_texts, generated_package
except ImportError:  # run as a script from the benchmarks folder
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_aadl_syntax import corpus_texts, generated_package  # type: ignore[no-redef]


def best_time(action: Callable[[], object], repeat: int) -> tuple[float, float]:
    """The best wall-clock and the best CPU time of ``repeat`` runs.

    The models of earlier runs are collected before each run, outside the measure: pyecore
    objects live in reference cycles, so only the garbage collector frees them."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        gc.collect()
        start, start_cpu = time.perf_counter(), time.process_time()
        action()
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    return wall, cpu


def row(label: str, what: str, size: int, wall: float, cpu: float) -> str:
    rates = f"{size / wall / 1e6:8.2f} {size / cpu / 1e6:9.2f}"
    return f"{label:<10} {what:<12} {size / 1e6:7.2f} MB {wall:8.3f} s {rates}"


def main(argv: list[str] | None = None) -> int:
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--repeat", type=int, default=3, help="runs per measurement; the best is shown")
    options.add_argument("--components", type=int, default=10_000, help="size of the generated package")
    args = options.parse_args(argv)

    from rosaadl.importers import aadl_syntax, aadl_text

    logging.getLogger("rosaadl").setLevel(logging.ERROR)  # tool-generated corpus files warn
    aadl_syntax.parse("package Warm_Up public end Warm_Up;")  # grammar tables, once per process
    aadl_text.read_string("package Warm_Up public system S end S; end Warm_Up;")
    print(f"{'input':<10} {'stage':<12} {'size':>10} {'time':>10} {'MB/s':>8} {'MB/s CPU':>9}")

    corpus = corpus_texts()
    if corpus:
        size = sum(len(data) for _, data in corpus)
        wall, cpu = best_time(lambda: [aadl_syntax.parse(data, name) for name, data in corpus], args.repeat)
        print(row("corpus", "parse", size, wall, cpu))
        wall, cpu = best_time(
            lambda: [aadl_text.read_string(data, name) for name, data in corpus], args.repeat
        )
        print(row("corpus", "read_string", size, wall, cpu))
        print(f"           ({len(corpus)} files)")
    else:
        print("corpus: not found (set ROSAADL_CORPUS); skipped")

    text = generated_package(args.components).encode("utf-8")
    size = len(text)
    label = f"gen {args.components // 1000}k" if args.components >= 1000 else f"gen {args.components}"
    wall, cpu = best_time(lambda: aadl_syntax.parse(text, "<generated>"), args.repeat)
    print(row(label, "parse", size, wall, cpu))
    wall, cpu = best_time(lambda: aadl_text.read_string(text, "<generated>"), args.repeat)
    print(row(label, "read_string", size, wall, cpu))
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "generated.aadl"
        path.write_bytes(text)
        wall, cpu = best_time(lambda: aadl_text.read_files([path]), args.repeat)
        print(row(label, "read_files", size, wall, cpu))
    print("(read_files: with the component library, names, units and literals checked)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""AADL text writer benchmark: throughput (MB/s of text produced) on a generated package.

The package holds N thread types (default 10 000), each with three features (one with a property
block) and three property associations (a number with unit, an enumeration literal, a range), and
one system implementation with a subcomponent and a connection per thread
(``benchmarks.generators.declarative.thread_types_package``). Side by side in one run:

  * ``walk``: visiting every object once through the reflective model API (``model.walk``),
    for scale: the writer reads the same objects through their typed attributes;
  * ``write_unit``: the writer, text in memory;
  * ``write_model``: the writer plus the atomic file write;
  * ``parse``: reading the produced text back with the AADL grammar (``aadl_syntax.parse``).

Usage: ``python -m benchmarks.bench_aadl_writer [--components N] [--repeat R]``.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from benchmarks.generators.declarative import thread_types_package
from benchmarks.harness import Report, best_of

__all__ = ["main"]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--components", type=int, default=10_000)
    parser.add_argument("--repeat", type=int, default=3, help="runs per phase; the best is shown")
    args = parser.parse_args(argv)

    from rosaadl import model
    from rosaadl.exporters.aadl_text import write_model, write_unit
    from rosaadl.importers.aadl_syntax import parse

    built = best_of(lambda: thread_types_package(args.components), 1)
    ws = built.result
    pkg = ws.units[0]
    objects = sum(1 for _ in model.walk(ws))

    walk = best_of(lambda: sum(1 for _ in model.walk(ws)), args.repeat)
    write = best_of(lambda: write_unit(pkg), args.repeat)
    text = write.result
    size_mb = len(text.encode("utf-8")) / 1e6
    with tempfile.TemporaryDirectory(prefix="rosaadl-bench-") as tmp:
        files = best_of(lambda: write_model(ws, Path(tmp)), args.repeat)
    parsed = best_of(lambda: parse(text, "bench.aadl"), 1)

    report = Report("aadl_writer")
    what = f"{args.components} thread types, {objects} objects"
    report.time(f"build the model, {what}", built, detail=True)
    report.time(f"walk, {what}", walk, note=f"{size_mb / walk.cpu:.2f} MB/s")
    lines = text.count("\n")
    for phase, timing in (("write_unit", write), ("write_model", files), ("parse the text back", parsed)):
        report.time(
            f"{phase}, {size_mb:.2f} MB, {lines} lines",
            timing,
            walk,
            against="walk",
            note=f"{size_mb / timing.cpu:.2f} MB/s",
        )
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

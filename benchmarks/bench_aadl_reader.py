"""Throughput of the AADL text reader (the package ``importers/aadl_text/``), next to the parser alone.

Side by side, in MB/s of AADL text (CPU time of this process, which is what counts on a shared
machine; the wall-clock rate in the note), on every ``.aadl``/``.aadl2`` file of the real-world
corpus (``$ROSAADL_CORPUS`` or ``../shared/corpus``) and on the generated package of
``bench_aadl_syntax`` (``benchmarks.generators.aadl_text.aadl_package_text``, 10 000
components: threads with ports, flows and properties in processes with connections and
contained property associations):

  * ``parse``: ``aadl_syntax.parse`` alone, the floor of the reader;
  * ``read_string``: parse and build the model (``rosaadl.importers.aadl_text.read_string``);
  * ``read_files``: the file read from disk, the component library added and every name, unit
    and enumeration literal checked across all units (generated package only: the corpus is
    many separate projects).

Usage: ``python -m benchmarks.bench_aadl_reader [--repeat N] [--components N]``.
Target of the issue: the reader reads >= 1 MB/s.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

from benchmarks.generators.aadl_text import aadl_package_text
from benchmarks.generators.corpus import aadl_texts
from benchmarks.harness import Goal, Report, best_of

__all__ = ["main"]

READ_GOAL = Goal(1.0, at_most=False)


def main(argv: list[str] | None = None) -> int:
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--repeat", type=int, default=3, help="runs per measurement; the best is shown")
    options.add_argument("--components", type=int, default=10_000, help="size of the generated package")
    args = options.parse_args(argv)

    from rosaadl.importers import aadl_syntax, aadl_text

    logging.getLogger("rosaadl").setLevel(logging.ERROR)  # tool-generated corpus files warn
    aadl_syntax.parse("package Warm_Up public end Warm_Up;")  # grammar tables, once per process
    aadl_text.read_string("package Warm_Up public system S end S; end Warm_Up;")
    report = Report("aadl_reader")

    corpus = aadl_texts()
    if corpus:
        size = sum(len(data) for _, data in corpus) / 1e6
        parse = best_of(lambda: [aadl_syntax.parse(data, name) for name, data in corpus], args.repeat)
        read = best_of(lambda: [aadl_text.read_string(data, name) for name, data in corpus], args.repeat)
        what = f"{len(corpus)} files, {size:.2f} MB"
        report.rate("corpus: parse", parse, size, note=what, detail=True)
        report.rate("corpus: read_string", read, size, parse, against="parse", goal=READ_GOAL, note=what)
    else:
        print("corpus: not found (set ROSAADL_CORPUS); skipped")

    text = aadl_package_text(args.components).encode("utf-8")
    size = len(text) / 1e6
    label = f"gen {args.components // 1000}k" if args.components >= 1000 else f"gen {args.components}"
    parse = best_of(lambda: aadl_syntax.parse(text, "<generated>"), args.repeat)
    read = best_of(lambda: aadl_text.read_string(text, "<generated>"), args.repeat)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "generated.aadl"
        path.write_bytes(text)
        files = best_of(lambda: aadl_text.read_files([path]), args.repeat)
    what = f"{size:.2f} MB"
    report.rate(f"{label}: parse", parse, size, note=what, detail=True)
    report.rate(f"{label}: read_string", read, size, parse, against="parse", goal=READ_GOAL, note=what)
    report.rate(
        f"{label}: read_files",
        files,
        size,
        parse,
        against="parse",
        goal=READ_GOAL,
        note=f"{what}, with the component library, names, units and literals checked",
    )
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

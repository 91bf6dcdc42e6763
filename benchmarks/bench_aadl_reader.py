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

And the peak memory of reading a file (``read_files``, without the library and checks), per
byte of the file: for the generated package, and for a file of corpus shape (the corpus's
packages and property sets copied under new names, ``renamed_copies_text``, ``--copies-mb``
MB).  The bound of the issue is 10x the file, met by the file of corpus shape (about 9x: the
model about 6.5x, the text the rest, held as 2 bytes per character once one is not ASCII).  The
generated package has 20 bytes of text per model object, and a pyecore object with its
dictionary takes about 220 bytes (11x such text) before any value: its goal is the figure
reached, about 23x (was 44x; README, "Known limits").

Usage: ``python -m benchmarks.bench_aadl_reader [--repeat N] [--components N] [--copies-mb M]``.
Target of the issue: the reader reads >= 1 MB/s.
"""

from __future__ import annotations

import argparse
import logging
import subprocess
import sys
import tempfile
from pathlib import Path

from benchmarks.generators.aadl_text import aadl_package_text, renamed_copies_text
from benchmarks.generators.corpus import aadl_texts
from benchmarks.harness import Goal, Report, best_of

__all__ = ["main", "read_peak_per_byte"]

ROOT = Path(__file__).resolve().parents[1]

READ_GOAL = Goal(1.0, at_most=False)
MEMORY_GOAL = Goal(10.0, says="issue: a 20 MB file in <= 10x its size")
DENSE_MEMORY_GOAL = Goal(25.0, says="20 bytes of text per object; a pyecore object is 11x that")


_READ_IN_CHILD = """
import gc, logging, sys
from benchmarks.harness import reset_peak, status_kib
from rosaadl.errors import RosaadlError
from rosaadl.importers.aadl_text import read_files, read_string
logging.getLogger("rosaadl").setLevel(logging.CRITICAL)
read_string("package W public system S end S; end W;", "w.aadl")  # the grammar tables, once
gc.collect()
before = reset_peak()
try:
    model = read_files([sys.argv[1]], include_library=False, check=sys.argv[2] == "check", lenient=True)
except RosaadlError:  # names the checks did not find: they ran all the same
    if sys.argv[2] != "check":
        raise
print("GROWN", (status_kib("VmHWM:") - before) * 1024)
"""


def read_peak_per_byte(path: Path, *, check: bool = False) -> float:
    """The peak memory of reading the AADL file ``path`` into a model (``read_files`` without the
    library; with ``check``, also resolving its names and checking its values, errors or not),
    in a fresh process (memory freed before in this one would be reused and hide part of it),
    per byte of the file."""
    done = subprocess.run(
        [sys.executable, "-c", _READ_IN_CHILD, str(path), "check" if check else "read"],
        capture_output=True,
        text=True,
        timeout=600,
        check=False,
        cwd=ROOT,
    )
    if done.returncode != 0:
        raise RuntimeError(f"reading {path} failed:\n{done.stderr}")
    grown = next(int(line.split()[1]) for line in done.stdout.splitlines() if line.startswith("GROWN "))
    return grown / path.stat().st_size


def _memory_row(report: Report, label: str, ratio: float, size: int, note: str, goal: Goal) -> None:
    """A row of the peak memory of a read per byte of the file read (``ratio``)."""
    peak = ratio * size / 2**20
    report.add(f"{label}: read peak / file size", ratio, "", goal=goal, peak_mib=peak, note=note)


def main(argv: list[str] | None = None) -> int:
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--repeat", type=int, default=3, help="runs per measurement; the best is shown")
    options.add_argument("--components", type=int, default=10_000, help="size of the generated package")
    options.add_argument(
        "--copies-mb", type=float, default=20.0, help="size of the file of corpus shape (MB)"
    )
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
        memory = [
            (
                label,
                read_peak_per_byte(path),
                len(text),
                "20 bytes of text per model object",
                DENSE_MEMORY_GOAL,
            )
        ]
        if corpus:
            copies = Path(folder) / "copies.aadl"
            texts = (data.decode("utf-8-sig") for _, data in corpus)
            copies.write_text(renamed_copies_text(texts, int(args.copies_mb * 1e6)), encoding="utf-8")
            copied = copies.stat().st_size
            memory.append(
                (
                    "corpus copies",
                    read_peak_per_byte(copies),
                    copied,
                    "the corpus's units under new names",
                    MEMORY_GOAL,
                )
            )
            memory.append(
                (
                    "corpus copies, checked",
                    read_peak_per_byte(copies, check=True),
                    copied,
                    "the same, names resolved and values checked",
                    MEMORY_GOAL,
                )
            )
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
    for name, ratio, bytes_read, what_read, goal in memory:
        _memory_row(report, name, ratio, bytes_read, f"{bytes_read / 1e6:.2f} MB, {what_read}", goal)
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

"""Throughput of the AADL concrete-syntax parser (``importers/aadl_syntax.py``).

Prints MB/s of ``parse`` on every ``.aadl``/``.aadl2`` file of the real-world corpus
(``$ROSAADL_CORPUS`` or ``../shared/corpus``) and on a generated package of 10 000 components
(``benchmarks.generators.aadl_text.aadl_package_text``), plus the one-off cost of compiling the
grammar with and without lark's on-disk table cache.

    python -m benchmarks.bench_aadl_syntax [--repeat N] [--components N]

Target: the whole AADL reader (parse + model building) must read >= 1 MB/s on a 2-core
machine, so ``parse`` alone should stay well above 2 MB/s.
"""

from __future__ import annotations

import argparse
import os
import tempfile

from benchmarks.generators.aadl_text import aadl_package_text
from benchmarks.generators.corpus import aadl_texts
from benchmarks.harness import Goal, Report, best_of

__all__ = ["main"]

PARSE_GOAL = Goal(2.0, at_most=False, says="well above")


def _compile(aadl_syntax, cache: str) -> None:
    os.environ["ROSAADL_CACHE_DIR"] = cache
    aadl_syntax._reader.cache_clear()
    aadl_syntax._reader()


def main(argv: list[str] | None = None) -> int:
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--repeat", type=int, default=5, help="runs per measurement; the best is shown")
    options.add_argument("--components", type=int, default=10_000, help="size of the generated package")
    args = options.parse_args(argv)

    from rosaadl.importers import aadl_syntax

    report = Report("aadl_syntax")
    with tempfile.TemporaryDirectory() as cache:
        compiled = best_of(lambda: _compile(aadl_syntax, ""), 1)
        _compile(aadl_syntax, cache)  # writes the cache file
        cached = best_of(lambda: _compile(aadl_syntax, cache), 1)
    report.time("grammar: compile", compiled)
    report.time("grammar: load from the table cache", cached, compiled, against="compiled")

    corpus = aadl_texts()
    if corpus:
        size = sum(len(data) for _, data in corpus)

        def parse_corpus() -> None:
            for name, data in corpus:
                aadl_syntax.parse(data, name)

        timing = best_of(parse_corpus, args.repeat)
        report.rate(
            "parse: corpus",
            timing,
            size / 1e6,
            goal=PARSE_GOAL,
            note=f"{len(corpus)} files, {size / 1e6:.2f} MB",
        )
    else:
        print("corpus: not found (set ROSAADL_CORPUS); skipped")

    text = aadl_package_text(args.components).encode("utf-8")
    timing = best_of(lambda: aadl_syntax.parse(text, "<generated>"), args.repeat)
    report.rate(
        f"parse: generated, {args.components} components",
        timing,
        len(text) / 1e6,
        goal=PARSE_GOAL,
        note=f"{len(text) / 1e6:.2f} MB",
    )
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

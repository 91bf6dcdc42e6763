"""Instantiation benchmark: a generated system of P processes × T threads (default 100 × 100).

Every thread has an in and an out event data port typed by a data type with ``Data_Size``,
``Dispatch_Protocol``, ``Period`` and ``Compute_Execution_Time``; the threads of a process form a
chain of port connections, the processes form a chain too (one semantic connection per process
boundary), and every process is bound to the processor by a contained ``applies to`` association,
which its threads inherit.  The property sets are the few definitions the model uses, written
out (``benchmarks.generators.declarative.chained_system``) so that the benchmark measures
instantiation only.

Side by side in one run, for a tenth of the size and the full size: building the declarative
model, instantiating it (CPU and wall time), the objects made, against the floor of 10 s
for 10 000 threads (scaled for the smaller size).  Usage: ``python -m benchmarks.bench_instantiate
[--processes P] [--threads T]``.
"""

from __future__ import annotations

import argparse
import logging

from benchmarks.generators.declarative import chained_system
from benchmarks.harness import Goal, Report, best_of

__all__ = ["main"]

FLOOR_SECONDS = 10.0
FLOOR_THREADS = 10_000


def _measure(report: Report, processes: int, threads: int) -> None:
    from rosaadl.transforms.instantiate import Instantiator

    built = best_of(lambda: chained_system(processes, threads), 1)
    ws = built.result

    def instantiate() -> Instantiator:
        instantiator = Instantiator(ws)
        instantiator.run("bench::top.impl")
        return instantiator

    timing = best_of(instantiate, 1)
    made = timing.result.factory.made
    objects = sum(made.values()) + 1
    counts = (
        f"{made.get('ComponentInstance', 0) + 1} components, {made.get('FeatureInstance', 0)} features, "
        f"{made.get('ConnectionInstance', 0)} connections, "
        f"{made.get('PropertyAssociation', 0)} property associations"
    )
    size = processes * threads
    report.time(f"build the declarative model, {size} threads", built, detail=True)
    report.time(
        f"instantiate {size} threads",
        timing,
        goal=Goal(FLOOR_SECONDS * size / FLOOR_THREADS),
        note=f"{objects} objects: {counts}",
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_instantiate", description=__doc__.splitlines()[0])
    parser.add_argument("--processes", type=int, default=100)
    parser.add_argument("--threads", type=int, default=100, help="threads per process")
    args = parser.parse_args(argv)
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    report = Report("instantiate")
    for processes in (max(1, args.processes // 10), args.processes):
        _measure(report, processes, args.threads)
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

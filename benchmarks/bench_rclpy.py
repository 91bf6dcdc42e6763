"""Code generation benchmark: a ROS 2 workspace for a system of N nodes (default 1 000).

The instance is built directly with the model API, as the instantiator makes them
(``benchmarks.generators.instances.ros_ring``): N processes of N distinct classifiers spread
over 20 software packages, each with a periodic publisher thread and a sporadic subscriber
thread (``Period``, ``Deadline``, ``Compute_Execution_Time``, ``Priority``, ``Queue_Size``,
standard and custom message types), a ring of port connections between the nodes (one semantic
connection per pair, with its connection references) and one processor per 8 nodes.

Side by side: building the instance, the first generation (every file written), a regeneration
of the unchanged model (nothing written), and a regeneration after renaming a thread in every
tenth node (the trace moves the blocks), against the floor of 10 s for 1 000 nodes.
Usage: ``python -m benchmarks.bench_rclpy [--nodes N] [--output DIR]``.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

from benchmarks.generators.instances import ros_ring
from benchmarks.harness import Goal, Report, best_of
from rosaadl import model

__all__ = ["main"]

FLOOR_SECONDS = 10.0
FLOOR_NODES = 1000


def _rename_trace(root, nodes: int):
    """Rename the receiver thread of every tenth node; the trace that says so."""
    from rosaadl.transforms import trace as tracing

    trace = tracing.new_trace("rename")
    for process in root.componentInstances[:nodes:10]:
        thread = process.componentInstances[1]
        old = tracing.element_key(thread)
        thread.name = thread.subcomponent = "listener"
        link = model.new("trace.TraceLink", rule="rename")
        link.sources.append(model.new("trace.TraceElement", path=old))
        link.targets.append(model.new("trace.TraceElement", path=tracing.element_key(thread)))
        trace.links.append(link)
    return trace


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_rclpy", description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=FLOOR_NODES)
    parser.add_argument(
        "--output", type=Path, default=None, help="folder to generate into (default: a temporary one)"
    )
    args = parser.parse_args(argv)
    logging.getLogger("rosaadl").setLevel(logging.ERROR)

    from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace

    options = GenerationOptions(year=2024)
    built = best_of(lambda: ros_ring(args.nodes), 1)
    root = built.result

    with tempfile.TemporaryDirectory(prefix="bench_rclpy_") as scratch:
        out = args.output or Path(scratch) / "src"
        first = best_of(lambda: generate_workspace(root, out, options=options), 1)
        second = best_of(lambda: generate_workspace(root, out, options=options), 1)
        trace = _rename_trace(root, args.nodes)
        third = best_of(lambda: generate_workspace(root, out, options=options, trace=trace), 1)

    report = Report("rclpy")
    report.time("build instance", built, note=f"{args.nodes} nodes, {2 * args.nodes} threads", detail=True)
    report.time(
        f"generate {args.nodes} nodes",
        first,
        goal=Goal(FLOOR_SECONDS * args.nodes / FLOOR_NODES),
        note=f"{len(first.result.written)} files written",
    )
    report.time("regenerate, unchanged", second, note=f"{len(second.result.written)} files written")
    report.time(
        "regenerate, renames",
        third,
        note=f"{len(third.result.written)} files written, {len(third.result.moved)} blocks moved",
    )
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

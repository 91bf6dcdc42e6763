"""Instrumentation benchmark: what the generated nodes' tracer (parameter ``rosaadl.trace``) costs
per dispatch, off and on, and per message (stamped on publish, read on receipt).

The tracer and the carrier functions are those of a generated node (the tracking example's
``usb_cam``), called as the generated callbacks call them: off, a dispatch tests
``self.tracer`` twice; on, it calls ``begin()`` and ``end()`` (a line held, the held lines
appended to the file every 4096). A message is a ``sensor_msgs/Image`` of 921 600 bytes (its
header carries the sequence number and time) and a ``geometry_msgs/Point`` (its x and y). Goal:
under 20 µs per dispatch (the issue's); each figure is the CPU time per call, the best of the
rounds. Needs the ROS 2 runtime (``make ros``); without it, the module says so and exits 0.
Usage: ``python -m benchmarks.bench_trace [--calls N] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import array
import ast
import os
import struct
import sys
import tempfile
import threading
import time
import types
from pathlib import Path

from benchmarks.harness import Goal, Report, best_of

__all__ = ["main"]

GOAL_US = 20.0


def _tracer_code(folder: Path) -> types.SimpleNamespace:
    """``Tracer``, ``carry`` and ``carried`` of the generated usb_cam node of the tracking example
    (its module imports the example's interface package, which is not built here: the tracer's
    code is taken from it as generated)."""
    from rosaadl.exporters.rclpy import generate_workspace
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    library = Path(__file__).resolve().parent.parent / "library" / "systems"
    generate_workspace(instantiate(read_files([library]), "sys_tracking::tracking.impl"), folder / "src")
    tree = ast.parse((folder / "src" / "usb_cam" / "usb_cam" / "usb_cam.py").read_text())
    wanted = {"Tracer", "_doubles", "carry", "carried"}
    body = [n for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef)) and n.name in wanted]
    namespace = {"array": array, "os": os, "struct": struct, "threading": threading, "time": time}
    exec(compile(ast.Module(body=body, type_ignores=[]), "usb_cam.py", "exec"), namespace)  # noqa: S102
    return types.SimpleNamespace(**{name: namespace[name] for name in wanted})


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_trace", description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=20_000)
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args(argv)
    report = Report("trace")
    try:
        from geometry_msgs.msg import Point
        from sensor_msgs.msg import Image
    except ImportError:
        print("bench_trace: no ROS 2 runtime in this Python (make ros); nothing measured", file=sys.stderr)
        return report.finish()
    calls = args.calls
    with tempfile.TemporaryDirectory() as scratch:
        module = _tracer_code(Path(scratch))
        tracer = module.Tracer("/bench", scratch, [("pub", "image_broadcaster")], [])
        off = types.SimpleNamespace(tracer=None)
        on = types.SimpleNamespace(tracer=tracer)

        def dispatches(node):
            def run():
                for _ in range(calls):
                    started = time.monotonic()
                    if node.tracer:
                        node.tracer.begin()
                    if node.tracer:
                        node.tracer.end("pub", started)

            return run

        def bare():
            for _ in range(calls):
                time.monotonic()

        floor = best_of(bare, args.rounds)
        timing_off = best_of(dispatches(off), args.rounds)
        timing_on = best_of(dispatches(on), args.rounds)
        per = lambda timing: max(0.0, (timing.cpu - floor.cpu) / calls * 1e6)  # noqa: E731 - µs per call
        report.add(
            "dispatch, tracer off (µs per dispatch)", per(timing_off), "us", note="two attribute tests"
        )
        report.add(
            "dispatch, tracer on (µs per dispatch)",
            per(timing_on),
            "us",
            goal=Goal(GOAL_US, says="< 20 µs per dispatch"),
            note="begin() + end(), file writes included",
        )
        image = Image()
        image.data = array.array("B", bytes(921_600))
        point = Point()
        for name, message, topic in (("Image 921 600 B", image, "/image"), ("Point", point, "/point")):
            publisher = types.SimpleNamespace(topic_name=topic)

            def messages(message=message, publisher=publisher, topic=topic):
                for _ in range(calls):
                    tracer.stamp(publisher, message)
                    tracer.received(topic, message)

            timing = best_of(messages, args.rounds)
            report.add(
                f"message {name}, stamped and read (µs per message)",
                timing.cpu / calls * 1e6,
                "us",
                note="stamp() on publish + received() on receipt",
            )
        tracer.flush()
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

"""The topic monitor of a run: an rclpy node counting the messages of every topic of the model.

It runs as a process of its own (``python -m rosaadl.workflow.run.monitor SPEC OUT``), in the
run's ROS environment, so that rosaadl itself never loads ROS 2. ``SPEC`` is a JSON list of the
topics (``name``, ``type``, ``reliable``); the monitor subscribes to each with ``raw=True`` (the
serialized CDR bytes, not deserialized: what is counted is what travels), writes ``OUT.ready``
once its subscriptions exist, and on SIGINT or SIGTERM writes ``OUT``: per topic the messages
seen, the times of the first and last one, and the serialized bytes (total, smallest, largest).

:func:`topic_counts` is the measured rate: ``(messages - 1) / (last - first)``, the rate of the
stream once it flows (start-up and discovery do not count against it).
"""

from __future__ import annotations

import importlib
import json
import os
import signal
import sys
import time
from pathlib import Path

__all__ = ["READY_SUFFIX", "monitor_command", "topic_counts", "main"]

READY_SUFFIX = ".ready"
_DEPTH = 50


def monitor_command(spec: Path, out: Path) -> list[str]:
    """The command line of the monitor process."""
    return [sys.executable, "-m", "rosaadl.workflow.run.monitor", str(spec), str(out)]


def topic_counts(entry: dict) -> tuple[int, float | None, float | None]:
    """(messages, rate in Hz, mean serialized bytes per message) of one topic of the output."""
    messages = int(entry.get("messages", 0))
    first, last = entry.get("first"), entry.get("last")
    rate = None
    if messages > 1 and isinstance(first, float) and isinstance(last, float) and last > first:
        rate = round((messages - 1) / (last - first), 3)
    size = round(entry.get("bytes", 0) / messages, 1) if messages else None
    return messages, rate, size


def _message_class(type_name: str):
    package, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), name)


def main(argv: list[str] | None = None) -> int:
    """Subscribe, count until SIGINT/SIGTERM, write the counts (see the module docstring)."""
    import rclpy
    from rclpy.qos import QoSHistoryPolicy, QoSProfile, QoSReliabilityPolicy
    from rclpy.signals import SignalHandlerOptions

    spec_path, out_path = (Path(a) for a in (argv if argv is not None else sys.argv[1:]))
    topics = json.loads(spec_path.read_text(encoding="utf-8"))
    stop = []
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stop.append(True))
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = rclpy.create_node("rosaadl_run_monitor")
    counts: dict[str, dict] = {}

    def counter(entry: dict):
        def on_message(data: bytes) -> None:
            now = time.monotonic()
            size = len(data)
            if entry["messages"] == 0:
                entry["first"] = now
                entry["min_bytes"] = size
            entry["messages"] += 1
            entry["last"] = now
            entry["bytes"] += size
            entry["min_bytes"] = min(entry["min_bytes"], size)
            entry["max_bytes"] = max(entry["max_bytes"], size)

        return on_message

    for topic in topics:
        entry = {"messages": 0, "bytes": 0, "min_bytes": None, "max_bytes": 0, "error": None}
        counts[topic["name"]] = entry
        try:
            cls = _message_class(topic["type"])
        except (ImportError, AttributeError, ValueError) as exc:
            entry["error"] = f"message type {topic['type']} cannot be loaded: {exc}"
            continue
        qos = QoSProfile(
            history=QoSHistoryPolicy.KEEP_LAST,
            depth=_DEPTH,
            reliability=(
                QoSReliabilityPolicy.RELIABLE
                if topic.get("reliable", True)
                else QoSReliabilityPolicy.BEST_EFFORT
            ),
        )
        node.create_subscription(cls, topic["name"], counter(entry), qos, raw=True)
    Path(str(out_path) + READY_SUFFIX).write_text("ready\n", encoding="utf-8")
    try:
        while not stop:
            rclpy.spin_once(node, timeout_sec=0.05)
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
        temporary = out_path.with_name(out_path.name + f".{os.getpid()}.tmp")
        temporary.write_text(json.dumps(counts, indent=1), encoding="utf-8")
        os.replace(temporary, out_path)
    return 0


if __name__ == "__main__":
    sys.exit(main())

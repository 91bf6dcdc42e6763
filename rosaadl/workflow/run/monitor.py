"""The topic monitor of a run: an rclpy node counting the messages of every topic of the model.

It runs as a process of its own (``python .../monitor.py SPEC OUT``: this file alone, so that it
loads nothing of rosaadl), in the run's ROS environment, so that rosaadl itself never loads ROS 2.
``SPEC`` is ``{"topics": [{"name", "type", "reliable"}], "nodes": [full names]}``; the monitor subscribes to
each topic with ``raw=True`` (the serialized CDR bytes, not deserialized: what is counted is what
travels), writes ``OUT.ready`` once its subscriptions exist, keeps ``OUT.up`` (the nodes of the
model in the ROS graph now) up to date, and on SIGINT or SIGTERM writes ``OUT``: per topic
the messages seen, the times of the first and last one, and the serialized bytes (total, smallest,
largest), and the nodes seen.

:func:`topic_counts` is the measured rate: ``(messages - 1) / (last - first)``, the rate of the
stream once it flows (start-up and discovery do not count against it).
"""

from __future__ import annotations

import importlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

__all__ = [
    "MONITOR_NODE",
    "READY_SUFFIX",
    "UP_SUFFIX",
    "monitor_command",
    "start_monitor",
    "stop_monitor",
    "topic_counts",
    "nodes_up",
    "main",
]

#: The monitor's ROS node: hidden (a leading ``_``), so that ``ros2 node list`` and
#: ``rosaadl import ros2-graph`` of a running application show the application's nodes only.
MONITOR_NODE = "_rosaadl_run_monitor"
READY_SUFFIX = ".ready"
UP_SUFFIX = ".up"
_DEPTH = 50
_GRAPH_SECONDS = 0.2
_READY_SECONDS = 60.0
_STOP_SECONDS = 10.0


def monitor_command(spec: Path, out: Path, cpus: list[int] | tuple[int, ...] = ()) -> list[str]:
    """The command line of the monitor process (``cpus``: the CPUs it keeps to, all when none)."""
    pinned = [",".join(str(cpu) for cpu in cpus)] if cpus else []
    return [sys.executable, str(Path(__file__).resolve()), str(spec), str(out), *pinned]


def topic_counts(entry: dict) -> tuple[int, float | None, float | None]:
    """(messages, rate in Hz, mean serialized bytes per message) of one topic of the output."""
    messages = int(entry.get("messages", 0))
    first, last = entry.get("first"), entry.get("last")
    rate = None
    if messages > 1 and isinstance(first, float) and isinstance(last, float) and last > first:
        rate = round((messages - 1) / (last - first), 3)
    size = round(entry.get("bytes", 0) / messages, 1) if messages else None
    return messages, rate, size


def nodes_up(out: Path) -> set[str]:
    """The nodes of the model the monitor writing ``out`` sees in the ROS graph now."""
    try:
        return set(json.loads(Path(str(out) + UP_SUFFIX).read_text(encoding="utf-8")))
    except (OSError, ValueError, TypeError):
        return set()


def _write(path: Path, data: object) -> None:
    temporary = path.with_name(path.name + f".{os.getpid()}.tmp")
    temporary.write_text(json.dumps(data, indent=1), encoding="utf-8")
    os.replace(temporary, path)


def start_monitor(
    topics: list,
    nodes: list[str],
    counts_file: Path,
    env: dict[str, str],
    cwd: Path,
    cpus: list[int] | tuple[int, ...] = (),
) -> subprocess.Popen:
    """Start the monitor of ``topics`` (:class:`~rosaadl.workflow.run.plan.TopicPlan`) and
    ``nodes`` (full names), writing into ``counts_file``, on ``cpus`` (all when none: see
    :func:`~rosaadl.workflow.run.cores.quietest_cpus`); return once it listens (a
    :class:`RunError` when it does not come up)."""
    from rosaadl.workflow.run.environment import tail
    from rosaadl.workflow.run.plan import RunError

    logs = counts_file.parent
    spec = logs / "monitor-topics.json"
    spec.write_text(
        json.dumps(
            {
                "topics": [{"name": t.name, "type": t.type, "reliable": t.reliable} for t in topics],
                "nodes": nodes,
            },
            indent=1,
        ),
        encoding="utf-8",
    )
    ready = Path(str(counts_file) + READY_SUFFIX)
    for stale in (ready, counts_file, Path(str(counts_file) + UP_SUFFIX)):
        stale.unlink(missing_ok=True)
    log = logs / "monitor.log"
    with open(log, "wb") as out:
        monitor = subprocess.Popen(
            monitor_command(spec, counts_file, cpus),
            cwd=cwd,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    deadline = time.monotonic() + _READY_SECONDS
    try:
        while not ready.exists():
            if monitor.poll() is not None or time.monotonic() > deadline:
                raise RunError(f"the topic monitor did not start:\n{tail(log)}", file=str(log))
            time.sleep(0.02)
    except BaseException:  # an interrupt too: no monitor is left behind
        if monitor.poll() is None:
            monitor.kill()
            monitor.wait()
        raise
    return monitor


def stop_monitor(monitor: subprocess.Popen) -> None:
    """SIGINT to the monitor (it writes its counts), SIGKILL when it does not end."""
    if monitor.poll() is None:
        monitor.send_signal(signal.SIGINT)
        try:
            monitor.wait(timeout=_STOP_SECONDS)
        except subprocess.TimeoutExpired:
            monitor.kill()
            monitor.wait()


def _message_class(type_name: str):
    package, kind, name = type_name.split("/")
    return getattr(importlib.import_module(f"{package}.{kind}"), name)


def main(argv: list[str] | None = None) -> int:
    """Subscribe, count until SIGINT/SIGTERM, write the counts (see the module docstring)."""
    import rclpy
    from rclpy.qos import QoSHistoryPolicy, QoSProfile, QoSReliabilityPolicy
    from rclpy.signals import SignalHandlerOptions

    args = argv if argv is not None else sys.argv[1:]
    spec_path, out_path = Path(args[0]), Path(args[1])
    if len(args) > 2 and hasattr(os, "sched_setaffinity"):
        # before rclpy starts its threads, which keep the affinity they start with
        os.sched_setaffinity(0, {int(cpu) for cpu in args[2].split(",")})
    spec = json.loads(spec_path.read_text(encoding="utf-8"))
    topics, expected = spec["topics"], set(spec["nodes"])
    stop = []
    for signum in (signal.SIGINT, signal.SIGTERM):
        signal.signal(signum, lambda *_: stop.append(True))
    rclpy.init(signal_handler_options=SignalHandlerOptions.NO)
    node = rclpy.create_node(MONITOR_NODE)
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
    first_seen: dict[str, float] = {}
    present: set[str] = set()
    up_path = Path(str(out_path) + UP_SUFFIX)
    _write(up_path, [])
    Path(str(out_path) + READY_SUFFIX).write_text("ready\n", encoding="utf-8")
    looked = 0.0
    try:
        while not stop:
            rclpy.spin_once(node, timeout_sec=0.05)
            if time.monotonic() - looked > _GRAPH_SECONDS:
                looked = time.monotonic()
                graph = {f"{ns.rstrip('/')}/{name}" for name, ns in node.get_node_names_and_namespaces()}
                now = graph & expected
                if now != present:
                    present = now
                    for name in now:
                        first_seen.setdefault(name, looked)
                    _write(up_path, sorted(now))
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
        _write(out_path, {"topics": counts, "nodes": first_seen})
    return 0


if __name__ == "__main__":
    # run as a file: its folder (plan.py, session.py, ...) must not shadow modules ROS 2 imports
    _here = Path(__file__).resolve().parent
    sys.path[:] = [p for p in sys.path if not p or Path(p).resolve() != _here]
    sys.exit(main())

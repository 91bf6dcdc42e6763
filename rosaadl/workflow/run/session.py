"""One run of a generated application: generate, build, start, watch, stop, and what was seen.

:func:`prepare_run` generates the workspace of a model into a run folder (``RUN_DIR/src``, as
``rosaadl generate rclpy`` does: user code is kept across regenerations) and saves its run plan;
:func:`run_application` builds it with colcon, starts the topic monitor and then every node as
the deployment's launch file describes, lets them run, stops them (SIGINT, then SIGTERM and
SIGKILL after a grace period) and compares what flowed with the model.

The run folder holds ``src`` (the packages), ``build``/``install``/``log`` (colcon's),
``build.log``, ``rosaadl-run.json`` (the run plan) and ``run/`` (each node's output, the
monitor's output and counts).

A run is *ok* when every node started, ran to the stop and exited 0 on SIGINT, every message
type could be loaded, and, with ``emulate``, every topic some node of the model publishes on
carried at least one message. A measured rate more than :data:`RATE_TOLERANCE` away from the
modelled one, a node that needed SIGTERM or SIGKILL, a core of the model that does not exist
here or a real-time priority that cannot be set are warnings.
"""

from __future__ import annotations

import json
import signal
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, Location
from rosaadl.exporters.rclpy import GenerationOptions, GenerationResult, generate_workspace
from rosaadl.workflow.run.cores import machine, node_prefix
from rosaadl.workflow.run.environment import colcon_build, require_ros, run_environment, tail
from rosaadl.workflow.run.monitor import READY_SUFFIX, monitor_command, topic_counts
from rosaadl.workflow.run.plan import RunError, RunPlan, TopicPlan, run_plan, save_plan
from rosaadl.workflow.run.processes import GRACE_SECONDS, NodeProcess, node_command, start_node, stop_nodes

__all__ = [
    "RATE_TOLERANCE",
    "EMULATE_PARAMETER",
    "RUN_LOGS",
    "RunOptions",
    "NodeResult",
    "TopicResult",
    "RunResult",
    "prepare_run",
    "run_application",
]

#: Relative difference between a measured and a modelled rate beyond which a warning is given.
RATE_TOLERANCE = 0.10
#: The node parameter switching the generated workload twin on.
EMULATE_PARAMETER = "rosaadl.emulate"
#: The folder of the run folder holding the nodes' and the monitor's output.
RUN_LOGS = "run"
_MONITOR_READY_SECONDS = 60.0
_MONITOR_STOP_SECONDS = 10.0


@dataclass(frozen=True)
class RunOptions:
    """How long and how to run."""

    duration: float
    emulate: bool = False
    realtime: bool = True  # apply the model's real-time scheduling (chrt) where permitted
    build: bool = True
    startup: float = 3.0  # seconds a node has to come up (part of ``duration``)
    grace: float = GRACE_SECONDS


@dataclass
class NodeResult:
    name: str
    started: bool
    exit_code: int | None
    stopped_by: str
    command: list[str]
    log: str


@dataclass
class TopicResult:
    name: str
    type: str
    messages: int
    rate_hz: float | None
    model_rate_hz: float | None
    bytes_per_message: float | None
    model_bytes: int | None


@dataclass
class RunResult:
    """What a run saw."""

    folder: Path
    duration: float
    nodes: list[NodeResult] = field(default_factory=list)
    topics: list[TopicResult] = field(default_factory=list)
    errors: list[Diagnostic] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.errors

    def data(self) -> dict:
        """The verb's JSON fields (besides ``ok``, ``errors`` and ``warnings``)."""
        return {
            "run_folder": str(self.folder),
            "duration_s": self.duration,
            "nodes": [
                {
                    "name": n.name,
                    "started": n.started,
                    "exit_code": n.exit_code,
                    "stopped_by": n.stopped_by or None,
                    "log": n.log,
                }
                for n in self.nodes
            ],
            "topics": [
                {
                    "name": t.name,
                    "type": t.type,
                    "messages": t.messages,
                    "rate_hz": t.rate_hz,
                    "model_rate_hz": t.model_rate_hz,
                    "bytes_per_message": t.bytes_per_message,
                    "model_bytes": t.model_bytes,
                }
                for t in self.topics
            ],
        }


def prepare_run(
    instance: EObject,
    folder: Path,
    *,
    rosmod_trace: EObject | None = None,
    options: GenerationOptions | None = None,
) -> tuple[RunPlan, GenerationResult]:
    """Generate the workspace of ``instance`` into ``folder/src`` and save its run plan."""
    result = generate_workspace(instance, folder / "src", rosmod_trace=rosmod_trace, options=options)
    plan = run_plan(result.plan)
    save_plan(plan, folder)
    return plan, result


def _diagnostic(severity: str, message: str, path: str | None = None, file: str | None = None) -> Diagnostic:
    return Diagnostic(severity, message, Location(file=file, path=path))


def _exit_code(code: int | None) -> int | None:
    """A process's exit code as a shell gives it (128 + N when signal N ended it)."""
    return 128 - code if code is not None and code < 0 else code


def run_application(
    folder: Path,
    plan: RunPlan,
    options: RunOptions,
    progress: Callable[[str], None] = lambda _: None,
) -> RunResult:
    """Build, start, watch and stop the application of ``folder`` (see the module docstring).

    A missing ROS 2 runtime, a failed build or a monitor that cannot start is a :class:`RunError`;
    what the nodes and topics did is in the result. An interrupt (``KeyboardInterrupt`` or the
    CLI's own) stops every node before it goes on.
    """
    require_ros()
    result = RunResult(folder=folder, duration=options.duration)
    if options.build:
        progress(f"building {folder / 'src'} with colcon")
        began = time.monotonic()
        install = colcon_build(folder)
        progress(f"built in {time.monotonic() - began:.1f} s")
    else:
        install = folder / "install"
    env = run_environment(install)
    logs = folder / RUN_LOGS
    logs.mkdir(exist_ok=True)
    here = machine(realtime=options.realtime)
    monitor: subprocess.Popen | None = None
    processes: list[NodeProcess] = []
    counts_file = logs / "monitor.json"
    try:
        monitor = _start_monitor(plan.topics, logs, counts_file, env, folder)
        extra = [(EMULATE_PARAMETER, True)] if options.emulate else []
        for node in plan.nodes:
            prefix, warnings = node_prefix(node, here)
            result.warnings.extend(_diagnostic("warning", w, node.path) for w in warnings)
            command = node_command(node, install, prefix, extra)
            processes.append(start_node(node, command, env, logs, folder))
            progress(f"started {node.full_name}" + (f" ({' '.join(prefix)})" if prefix else ""))
        _run_for(processes, options, progress)
        _stop_monitor(monitor)
        progress(f"stopping {len(processes)} node(s)")
        stop_nodes(processes, grace=options.grace)
    finally:
        if monitor is not None and monitor.poll() is None:
            _stop_monitor(monitor)
        stop_nodes([p for p in processes if p.running()], grace=options.grace)
    _node_results(result, processes)
    _topic_results(result, plan.topics, counts_file, options)
    return result


def _start_monitor(
    topics: list[TopicPlan], logs: Path, counts_file: Path, env: dict[str, str], cwd: Path
) -> subprocess.Popen:
    spec = logs / "monitor-topics.json"
    spec.write_text(
        json.dumps([{"name": t.name, "type": t.type, "reliable": t.reliable} for t in topics], indent=1),
        encoding="utf-8",
    )
    ready = Path(str(counts_file) + READY_SUFFIX)
    for stale in (ready, counts_file):
        stale.unlink(missing_ok=True)
    log = logs / "monitor.log"
    with open(log, "wb") as out:
        monitor = subprocess.Popen(
            monitor_command(spec, counts_file),
            cwd=cwd,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    deadline = time.monotonic() + _MONITOR_READY_SECONDS
    while not ready.exists():
        if monitor.poll() is not None or time.monotonic() > deadline:
            if monitor.poll() is None:
                monitor.kill()
                monitor.wait()
            raise RunError(f"the topic monitor did not start:\n{tail(log)}", file=str(log))
        time.sleep(0.02)
    return monitor


def _stop_monitor(monitor: subprocess.Popen) -> None:
    if monitor.poll() is None:
        monitor.send_signal(signal.SIGINT)
        try:
            monitor.wait(timeout=_MONITOR_STOP_SECONDS)
        except subprocess.TimeoutExpired:
            monitor.kill()
            monitor.wait()


def _run_for(processes: list[NodeProcess], options: RunOptions, progress: Callable[[str], None]) -> None:
    """Let the nodes run ``options.duration`` seconds; a node running after ``startup`` seconds
    has started (one that ended before is recorded as it ended)."""
    began = time.monotonic()
    startup = min(options.startup, options.duration)
    while time.monotonic() - began < startup and all(p.running() for p in processes):
        time.sleep(0.02)
    for process in processes:
        process.started = process.running()
    progress(f"running {options.duration:g} s" + (" with the workload twin" if options.emulate else ""))
    while time.monotonic() - began < options.duration:
        time.sleep(0.05)


def _node_results(result: RunResult, processes: list[NodeProcess]) -> None:
    for process in processes:
        node = process.node
        code = _exit_code(process.exit_code)
        result.nodes.append(
            NodeResult(
                name=node.full_name,
                started=process.started,
                exit_code=code,
                stopped_by=process.stopped_by,
                command=process.command,
                log=str(process.log),
            )
        )
        result.warnings.extend(_diagnostic("warning", w, node.path) for w in process.warnings)
        if not process.started:
            result.errors.append(
                _diagnostic(
                    "error",
                    f"node {node.full_name} did not start: it exited with code {code}:\n{tail(process.log)}",
                    node.path,
                    str(process.log),
                )
            )
        elif process.stopped_by == "":
            result.errors.append(
                _diagnostic(
                    "error",
                    f"node {node.full_name} ended during the run with code {code}:\n{tail(process.log)}",
                    node.path,
                    str(process.log),
                )
            )
        elif code != 0:
            result.errors.append(
                _diagnostic(
                    "error",
                    f"node {node.full_name} exited with code {code} when stopped:\n{tail(process.log)}",
                    node.path,
                    str(process.log),
                )
            )


def _topic_results(
    result: RunResult, topics: list[TopicPlan], counts_file: Path, options: RunOptions
) -> None:
    try:
        counts = json.loads(counts_file.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        counts = {}
        result.errors.append(
            _diagnostic(
                "error", "the topic monitor wrote no counts", file=str(counts_file.parent / "monitor.log")
            )
        )
    for topic in topics:
        entry = counts.get(topic.name, {})
        messages, rate, size = topic_counts(entry)
        result.topics.append(
            TopicResult(
                name=topic.name,
                type=topic.type,
                messages=messages,
                rate_hz=rate,
                model_rate_hz=topic.model_rate_hz,
                bytes_per_message=size,
                model_bytes=topic.model_bytes,
            )
        )
        where = f"topic {topic.name}"
        if entry.get("error"):
            result.errors.append(_diagnostic("error", f"{where}: {entry['error']}"))
            continue
        if not topic.publishers:
            result.warnings.append(
                _diagnostic(
                    "warning", f"{where}: no node of the model publishes on it (an input from outside)"
                )
            )
            continue
        if messages == 0:
            if options.emulate:
                result.errors.append(
                    _diagnostic(
                        "error",
                        f"{where}: no message in {options.duration:g} s (published by "
                        f"{', '.join(topic.publishers)})",
                    )
                )
            continue
        if options.emulate and topic.model_rate_hz and rate is not None:
            off = abs(rate - topic.model_rate_hz) / topic.model_rate_hz
            if off > RATE_TOLERANCE:
                result.warnings.append(
                    _diagnostic(
                        "warning",
                        f"{where}: {rate:g} Hz measured, {topic.model_rate_hz:g} Hz modelled ({off:.0%} off)",
                    )
                )

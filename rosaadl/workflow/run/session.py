"""One run of a generated application: generate, build, start, watch, stop, and what was seen.

:func:`prepare_run` generates the workspace of a model into a run folder (``RUN_DIR/src``, as
``rosaadl generate rclpy`` does: user code is kept across regenerations) and saves its run plan;
:func:`run_application` builds it with colcon, starts the topic monitor and then every node as
the deployment's launch file describes, lets them run, stops them (SIGINT, then SIGTERM and
SIGKILL after a grace period) and compares what flowed with the model.

The run folder holds ``src`` (the packages), ``build``/``install``/``log`` (colcon's),
``build.log``, ``rosaadl-run.json`` (the run plan) and ``run/`` (each node's output, the
monitor's output and counts).

The nodes talk on the run's ROS domain (``ROS_DOMAIN_ID``, see
:mod:`~rosaadl.workflow.run.environment`), on this host only: a progress line names it before the
nodes start (``ROS domain N``), and the report gives it (``ros_domain_id``), so that a tool can
join the running graph (``ros2 topic list``, ``rosaadl import ros2-graph --domain-id N``) with
``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST``.

A run is *ok* when every node started, ran to the stop and exited 0 on SIGINT, every message
type could be loaded, and, with ``emulate``, every topic some node of the model publishes on
carried at least one message. A measured rate more than :data:`RATE_TOLERANCE` away from the
modelled one, a node that needed SIGTERM or SIGKILL, a core of the model that does not exist
here or a real-time priority that cannot be set are warnings.
"""

from __future__ import annotations

import json
import subprocess
import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, Location
from rosaadl.exporters.rclpy import GenerationOptions, GenerationResult, generate_workspace
from rosaadl.workflow.run.cores import Machine, machine, node_prefix, quietest_cpus, shared_cpus
from rosaadl.workflow.run.environment import colcon_build, require_ros, run_environment, tail
from rosaadl.workflow.run.measure import ChainPlan, chain_plans
from rosaadl.workflow.run.measured_window import MeasuredWindow, whole_periods
from rosaadl.workflow.run.monitor import nodes_up, start_monitor, stop_monitor, topic_counts
from rosaadl.workflow.run.period_scale import auto_period_scale, predicted_cpu_loads, scaled_plan
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
    "expects_messages",
    "prepare_run",
    "run_application",
]

#: Relative difference between a measured and a modelled rate beyond which a warning is given.
RATE_TOLERANCE = 0.10
#: The node parameter switching the generated workload twin on.
EMULATE_PARAMETER = "rosaadl.emulate"
#: The folder of the run folder holding the nodes' and the monitor's output.
RUN_LOGS = "run"


@dataclass(frozen=True)
class RunOptions:
    """How long and how to run."""

    duration: float
    emulate: bool = False
    realtime: bool = True  # apply the model's real-time scheduling (chrt) where permitted
    build: bool = True
    startup: float = 60.0  # seconds the nodes have to come up in the ROS graph (before ``duration``)
    grace: float = GRACE_SECONDS
    measure: bool = False  # trace the nodes and write measurements.json (see .measure)
    warm_up: float = 0.0  # seconds run once the nodes are up, before ``duration`` (not measured)
    chains: tuple = ()  # the model's flows as ChainPlan, measured with ``measure``
    root: str | None = None  # the model's root, written into measurements.json
    period_scale: float | None = 1.0  # every period × this (None: auto), see .period_scale


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
    domain_id: int | None = None  # the ROS_DOMAIN_ID the nodes talk on
    nodes: list[NodeResult] = field(default_factory=list)
    topics: list[TopicResult] = field(default_factory=list)
    errors: list[Diagnostic] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)
    measurements: Path | None = None
    period_scale: float = 1.0  # the factor the nodes' periods were multiplied by

    @property
    def ok(self) -> bool:
        return not self.errors

    def data(self) -> dict:
        """The verb's JSON fields (besides ``ok``, ``errors`` and ``warnings``)."""
        return {
            "run_folder": str(self.folder),
            "duration_s": self.duration,
            "ros_domain_id": self.domain_id,
            "period_scale": self.period_scale,
            **({"measurements": str(self.measurements)} if self.measurements else {}),
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
    """Generate the workspace of ``instance`` into ``folder/src`` and save its run plan, with the
    model's chains (:func:`model_chains`) so that any run of the folder can measure them."""
    result = generate_workspace(instance, folder / "src", rosmod_trace=rosmod_trace, options=options)
    plan = run_plan(result.plan)
    chains = model_chains(instance, plan)
    plan.chains = [{"name": c.name, "topics": [list(hop) for hop in c.topics]} for c in chains]
    save_plan(plan, folder)
    return plan, result


def model_chains(instance: EObject, plan: RunPlan) -> list[ChainPlan]:
    """The model's end-to-end flows (the latency analysis's asynchronous chains) as topic chains
    between the plan's nodes."""
    from rosaadl.analysis import run_analyses

    latency = run_analyses(instance, "latency").result("latency")
    flows = (
        [] if latency is None else [(c.name, list(c.threads)) for c in latency.chains if c.mode == "async"]
    )
    return chain_plans(plan.nodes, plan.topics, flows)


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
    folder = Path(folder).absolute()  # the nodes and the monitor run in folders of their own
    result = RunResult(folder=folder, duration=options.duration)
    if options.build:
        progress(f"building {folder / 'src'} with colcon")
        began = time.monotonic()
        install = colcon_build(folder)
        progress(f"built in {time.monotonic() - began:.1f} s")
    else:
        install = folder / "install"
        if not (install / "lib").is_dir():
            raise RunError("the run folder has not been built: run it without --no-build", file=str(folder))
    env = run_environment(install)
    result.domain_id = _domain_id(env)
    progress(f"ROS domain {env['ROS_DOMAIN_ID']} ({env.get('ROS_AUTOMATIC_DISCOVERY_RANGE', 'any host')})")
    logs = folder / RUN_LOGS
    logs.mkdir(exist_ok=True)
    here = machine(realtime=options.realtime)
    plan = _scaled(plan, here, options, result, progress)
    if options.measure and (window_s := whole_periods(options.duration, plan.nodes)) != options.duration:
        progress(f"measuring {window_s:g} s ({options.duration:g} s to whole periods of the longest timer)")
        options = replace(options, duration=window_s)
        result.duration = window_s
    monitor: subprocess.Popen | None = None
    window: MeasuredWindow | None = None
    processes: list[NodeProcess] = []
    counts_file = logs / "monitor.json"
    try:
        quiet = quietest_cpus(plan.nodes, here, predicted_cpu_loads(plan.nodes, here))
        names = [n.full_name for n in plan.nodes]
        monitor = start_monitor(plan.topics, names, counts_file, env, folder, quiet)
        extra = [(EMULATE_PARAMETER, True)] if options.emulate else []
        window = MeasuredWindow(folder, processes) if options.measure else None
        if window is not None:
            extra += window.parameters()
        shared = shared_cpus(plan.nodes, here)
        for node in plan.nodes:
            prefix, warnings = node_prefix(node, here, shared)
            result.warnings.extend(_diagnostic("warning", w, node.path) for w in warnings)
            command = node_command(node, install, prefix, extra)
            processes.append(start_node(node, command, env, logs, folder))
            progress(f"started {node.full_name}" + (f" ({' '.join(prefix)})" if prefix else ""))
        _run_for(processes, counts_file, options, progress, None if window is None else window.begin)
        if window is not None:
            window.end()
        stop_monitor(monitor)
        progress(f"stopping {len(processes)} node(s)")
        stop_nodes(processes, grace=options.grace)
    finally:
        if window is not None:
            window.stop_gauges()
        if monitor is not None and monitor.poll() is None:
            stop_monitor(monitor)
        stop_nodes([p for p in processes if p.running()], grace=options.grace)
    counts = _counts(result, counts_file)
    for process in processes:
        process.started = process.node.full_name in counts.get("nodes", {})
    _node_results(result, processes, options)
    _topic_results(result, plan.topics, counts.get("topics", {}), options)
    if window is not None:
        result.measurements = window.write(plan, result, options)
        progress(f"wrote {result.measurements}")
    return result


def _scaled(
    plan: RunPlan, here: Machine, options: RunOptions, result: RunResult, progress: Callable[[str], None]
) -> RunPlan:
    """The plan with its periods scaled as ``options`` says (``auto``: from the model's loads)."""
    scale = options.period_scale
    if scale is None:
        loads = predicted_cpu_loads(plan.nodes, here)
        scale = auto_period_scale(plan.nodes, here)
        busiest = max(loads, key=lambda cpu: loads[cpu], default=None)
        if busiest is not None:
            progress(
                f"period scale {scale:g} (auto): the busiest CPU, {busiest}, has a predicted load of "
                f"{loads[busiest]:.1f} %, scaled {loads[busiest] / scale:.1f} %"
            )
    elif scale != 1:
        progress(f"period scale {scale:g}: every period of the nodes × {scale:g}")
    result.period_scale = scale
    return scaled_plan(plan, scale)


def _domain_id(env: dict[str, str]) -> int | None:
    """The run's ``ROS_DOMAIN_ID`` as a number (None when the caller's environment set no number)."""
    try:
        return int(env.get("ROS_DOMAIN_ID", ""))
    except ValueError:
        return None


def _counts(result: RunResult, counts_file: Path) -> dict:
    try:
        counts = json.loads(counts_file.read_text(encoding="utf-8"))
        if isinstance(counts, dict):
            return counts
    except (OSError, ValueError):
        pass
    result.errors.append(
        _diagnostic(
            "error", "the topic monitor wrote no counts", file=str(counts_file.parent / "monitor.log")
        )
    )
    return {}


def _run_for(
    processes: list[NodeProcess],
    counts_file: Path,
    options: RunOptions,
    progress: Callable[[str], None],
    on_start: Callable[[], None] | None = None,
) -> None:
    """Wait until every node is up in the ROS graph (at most ``options.startup`` seconds, less
    when a node ends), then let them run ``options.duration`` seconds."""
    names = {p.node.full_name for p in processes}
    deadline = time.monotonic() + options.startup
    began = time.monotonic()
    while time.monotonic() < deadline and all(p.running() for p in processes):
        if names <= nodes_up(counts_file):
            break
        time.sleep(0.05)
    up = nodes_up(counts_file)
    missing = sorted(names - up)
    progress(
        f"{len(names & up)} of {len(names)} node(s) up in {time.monotonic() - began:.1f} s"
        + (f" (not: {', '.join(missing)})" if missing else "")
    )
    if options.warm_up > 0:
        progress(f"warming up {options.warm_up:g} s")
        _wait(options.warm_up)
    progress(f"running {options.duration:g} s" + (" with the workload twin" if options.emulate else ""))
    if on_start is not None:
        on_start()
    _wait(options.duration)


def _wait(seconds: float) -> None:
    """Wait ``seconds`` (the nodes run meanwhile)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        time.sleep(0.05)


def _node_results(result: RunResult, processes: list[NodeProcess], options: RunOptions) -> None:
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
            how = (
                f"it exited with code {code}"
                if process.stopped_by == ""
                else f"it did not come up in the ROS graph within {options.startup:g} s"
            )
            result.errors.append(
                _diagnostic(
                    "error",
                    f"node {node.full_name} did not start: {how}:\n{tail(process.log)}",
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


def expects_messages(model_rate_hz: float | None, duration: float) -> bool:
    """Whether the workload twin sends a message on a topic of modelled rate ``model_rate_hz`` within
    ``duration`` seconds.  A ROS 2 timer first fires one period after it is made, so a thread whose
    period is longer than the run sends nothing in it (ROSMOD's long-running operations, a timer
    of minutes).  A topic with no modelled rate gets nothing from the twin: no timer of the model
    dispatches its publishers (a ROSMOD component with no timer publishing from a subscriber
    callback fed from outside or from a cycle, a component with publishers only), and only user
    code would publish on it."""
    return model_rate_hz is not None and model_rate_hz * duration >= 1.0


def _topic_results(result: RunResult, topics: list[TopicPlan], counts: dict, options: RunOptions) -> None:
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
            if options.emulate and expects_messages(topic.model_rate_hz, options.duration):
                result.errors.append(
                    _diagnostic(
                        "error",
                        f"{where}: no message in {options.duration:g} s (published by "
                        f"{', '.join(topic.publishers)})",
                    )
                )
            elif options.emulate and topic.model_rate_hz:
                result.warnings.append(
                    _diagnostic(
                        "warning",
                        f"{where}: no message in {options.duration:g} s, none expected: its modelled "
                        f"rate of {topic.model_rate_hz:g} Hz gives its first message after "
                        f"{1 / topic.model_rate_hz:.3g} s (a longer --duration measures it)",
                    )
                )
            elif options.emulate:
                result.warnings.append(
                    _diagnostic(
                        "warning",
                        f"{where}: no message in {options.duration:g} s, none expected: no timer of "
                        "the model dispatches its publishers (only messages from outside the model or "
                        "from a cycle of topics, or calls nobody in the model makes), so the workload "
                        "twin sends nothing on it",
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

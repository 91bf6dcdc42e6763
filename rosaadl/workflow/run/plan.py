"""What a run of a generated application starts and watches, from the generator's own plan.

The nodes are those of the deployment's launch file (:func:`rosaadl.exporters.rclpy.plan_workspace`
decides both, from :mod:`rosaadl.exporters.rclpy.deployment`): the same package and executable,
node name, namespace, parameters, remappings, CPU affinity and real-time scheduling. The topics
are the ones the nodes' ports use, each resolved as ROS 2 resolves it (a remapped name is the
launch file's target; a relative one is put under the node's namespace; ``~/`` under the node).

The *modelled rate* of a topic is the sum of the dispatch rates of the threads publishing on it
(each dispatch of a thread publishes once on every port the generated workload twin sends from
it: its own out ports, and those of its thread group or process it is the sender of, see
:mod:`rosaadl.exporters.rclpy.twin`):
a thread on a periodic timer (``Periodic``, ``Timed``, ``Hybrid``) is dispatched ``1 / period``
times a second (its ``<thread>.period`` parameter), plus once per message on each in port that
dispatches it (``Sporadic``, ``Aperiodic``, and the event ports of ``Timed``/``Hybrid``), plus
once per call of each service it provides: the twin's dispatches call the services their thread
requires (its own required subprogram accesses and those of the component it sends for, one
unanswered call per client at most), so a server thread is dispatched as often as the threads
calling it are (a ROSMOD component with no timer, publishing from its service callbacks). The
rates are propagated along the topics and service calls until they settle; a rate that depends on
a timer thread with no period or on a cycle is unknown (``None``), and so is one no dispatch of the
model gives (a service nobody in the model calls). A topic no node of the model publishes on is an
input from outside the model: its rate is unknown.

The plan is saved in the run folder (:data:`PLAN_FILE`), so that a run folder can be run again
(after editing the user code of its packages) without the model.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from rosaadl.errors import RosaadlError
from rosaadl.exporters.rclpy import WorkspacePlan
from rosaadl.exporters.rclpy.deployment import NodeInstance
from rosaadl.fileio import atomic_write_text, loads_bounded
from rosaadl.workflow.run.profiles import model_profile

__all__ = [
    "PLAN_FILE",
    "PLAN_VERSION",
    "NodeLaunch",
    "TopicPlan",
    "RunPlan",
    "RunError",
    "resolve_name",
    "run_plan",
    "save_plan",
    "load_plan",
]

#: The run plan kept in a run folder (beside ``src``).
PLAN_FILE = "rosaadl-run.json"
PLAN_VERSION = 1
_SETTLE_PASSES = 64


class RunError(RosaadlError):
    """The application could not be built, started or watched."""

    stage = "run"


@dataclass
class NodeLaunch:
    """One node as the deployment's launch file starts it."""

    name: str
    namespace: str
    package: str
    executable: str
    path: str  # the AADL process instance
    parameters: list[tuple[str, object]] = field(default_factory=list)
    remappings: list[tuple[str, str]] = field(default_factory=list)
    cpus: list[int] | None = None
    policy: str = ""  # SCHED_FIFO | SCHED_RR | "" (as the launch prefix writes it)
    priority: int | None = None
    profile: list[str] | None = None  # [board, core] of the PDM it is in the model (see .profiles)
    #: the threads (idents) dispatched by a periodic timer: the release their trace records is
    #: the timer's due time (see :mod:`.measure`); None: a plan written before it was kept
    timers: list[str] | None = None

    @property
    def full_name(self) -> str:
        return f"{self.namespace.rstrip('/')}/{self.name}"

    def timer_periods(self) -> dict[str, float]:
        """The period in seconds (``<thread>.period``, > 0) of each thread its timers dispatch."""
        periods = dict(self.parameters)
        return {
            thread: float(period)
            for thread in self.timers or ()
            if isinstance(period := periods.get(f"{thread}.period"), (int, float))
            and not isinstance(period, bool)
            and period > 0
        }


@dataclass
class TopicPlan:
    """One ROS topic of the model."""

    name: str
    type: str  # package/msg/Name
    publishers: list[str] = field(default_factory=list)  # node full names
    subscribers: list[str] = field(default_factory=list)
    reliable: bool = True
    model_rate_hz: float | None = None
    model_bytes: int | None = None  # Data_Size of the publishing port


@dataclass
class RunPlan:
    """Nodes and topics of one application."""

    app: str
    model: str  # the root system instance it came from
    nodes: list[NodeLaunch] = field(default_factory=list)
    topics: list[TopicPlan] = field(default_factory=list)
    #: the model's end-to-end flows as topic chains between the nodes, measured by ``--measure``:
    #: ``{"name", "topics": [[topic, publishing node, subscribing node], ...]}``
    chains: list[dict] = field(default_factory=list)

    def as_json(self) -> dict:
        return {"version": PLAN_VERSION, **asdict(self)}


def resolve_name(local: str, namespace: str, node: str) -> str:
    """The full name ROS 2 gives the topic name ``local`` of node ``node`` in ``namespace``."""
    base = namespace.rstrip("/")
    if local.startswith("/"):
        return local
    if local.startswith("~"):
        return f"{base}/{node}/{local[1:].lstrip('/')}".rstrip("/")
    return f"{base}/{local}"


def _parameter(node: NodeInstance, name: str) -> object:
    return next((value for key, value in node.parameters if key == name), None)


def _frequency(node: NodeInstance, thread_ident: str) -> float | None:
    period = _parameter(node, f"{thread_ident}.period")
    if isinstance(period, (int, float)) and not isinstance(period, bool) and period > 0:
        return 1.0 / float(period)
    return None


def _listed(pair: tuple[str, str] | None) -> list[str] | None:
    return None if pair is None else list(pair)


def run_plan(plan: WorkspacePlan) -> RunPlan:
    """The run plan of a generated workspace (see the module docstring)."""
    result = RunPlan(app=plan.app, model=plan.root.classifier or plan.root.name or plan.app)
    topics: dict[str, TopicPlan] = {}
    # (topic, node, thread) triples: who publishes what, and which topics dispatch which thread
    out_ends: list[tuple[str, NodeInstance, str]] = []
    triggers: dict[tuple[int, str], list[str]] = {}
    # (service, node, thread): who calls what; thread -> the services it serves
    calls: list[tuple[str, NodeInstance, str]] = []
    served: dict[tuple[int, str], list[str]] = {}
    for node in plan.nodes:
        result.nodes.append(
            NodeLaunch(
                name=node.node_name,
                namespace=node.namespace,
                package=node.cls.package,
                executable=node.cls.executable,
                path=node.path,
                parameters=list(node.parameters),
                remappings=list(node.remappings),
                cpus=list(node.cpus) if node.cpus else None,
                policy=node.policy if node.priority is not None else "",
                priority=node.priority,
                profile=_listed(model_profile(plan.root, node.path)),
                timers=[t.ident for t in node.cls.threads if t.dispatches and t.timer == "periodic"],
            )
        )
        full = result.nodes[-1].full_name
        remapped = dict(node.remappings)
        for thread in node.cls.threads:
            for port in thread.ports:
                name = resolve_name(remapped.get(port.local, port.local), node.namespace, node.node_name)
                topic = topics.setdefault(name, TopicPlan(name=name, type=port.msg.full_name))
                if port.direction == "out":
                    topic.reliable = topic.reliable and port.qos.reliability == "RELIABLE"
                    if full not in topic.publishers:
                        topic.publishers.append(full)
                    if port.data_size is not None:
                        topic.model_bytes = max(topic.model_bytes or 0, port.data_size)
                else:
                    if full not in topic.subscribers:
                        topic.subscribers.append(full)
                    if port.triggers and thread.dispatches:
                        triggers.setdefault((id(node), thread.ident), []).append(name)
            if thread.dispatches:  # what its emulated dispatch publishes (its ports, its group's)
                for port in thread.twin_outputs:
                    name = resolve_name(remapped.get(port.local, port.local), node.namespace, node.node_name)
                    out_ends.append((name, node, thread.ident))
                for srv in thread.twin_calls:  # and the services it calls
                    name = resolve_name(remapped.get(srv.local, srv.local), node.namespace, node.node_name)
                    calls.append((name, node, thread.ident))
                for srv in thread.servers:
                    name = resolve_name(remapped.get(srv.local, srv.local), node.namespace, node.node_name)
                    served.setdefault((id(node), thread.ident), []).append(name)
    rates = _settled_rates(plan, topics, out_ends, triggers, (calls, served))
    for name, topic in topics.items():
        topic.model_rate_hz = rates.get(name)
    result.topics = sorted(topics.values(), key=lambda t: t.name)
    return result


def _settled_rates(
    plan: WorkspacePlan,
    topics: dict[str, TopicPlan],
    out_ends: list[tuple[str, NodeInstance, str]],
    triggers: dict[tuple[int, str], list[str]],
    services: tuple[list[tuple[str, NodeInstance, str]], dict[tuple[int, str], list[str]]],
) -> dict[str, float | None]:
    """Topic rates propagated through the dispatching in ports and the service calls (``services``:
    the (service, node, thread) calls and, per thread, the services it serves) until they no
    longer change."""
    threads = {(id(n), t.ident): (n, t) for n in plan.nodes for t in n.cls.threads if t.dispatches}
    rates: dict[str, float | None] = {name: None for name in topics}
    published = {name for name, _, _ in out_ends}
    calls, served = services
    callers: dict[str, list[tuple[int, str]]] = {}
    for name, node, thread_ident in calls:
        callers.setdefault(name, []).append((id(node), thread_ident))
    previous: dict[tuple[int, str], float | None] = {ident: None for ident in threads}
    for _ in range(_SETTLE_PASSES):
        thread_rates: dict[tuple[int, str], float | None] = {}
        for ident, (node, thread) in threads.items():
            rate: float | None = 0.0
            if thread.timer == "periodic":
                rate = _frequency(node, thread.ident)
            for name in triggers.get(ident, []):
                incoming = rates.get(name) if name in published else 0.0
                rate = None if rate is None or incoming is None else rate + incoming
            for name in served.get(ident, []):
                for caller in callers.get(name, []):
                    incoming = previous.get(caller)
                    rate = None if rate is None or incoming is None else rate + incoming
            thread_rates[ident] = rate
        new: dict[str, float | None] = {name: (0.0 if name in published else None) for name in topics}
        for name, node, thread_ident in out_ends:
            rate = thread_rates.get((id(node), thread_ident))
            current = new[name]
            new[name] = None if rate is None or current is None else current + rate
        if new == rates and thread_rates == previous:
            break
        rates, previous = new, thread_rates
    else:  # a cycle that never settles: its rates are not known
        return {name: None for name in topics}
    return {name: (round(rate, 6) if rate else None) for name, rate in rates.items()}


def save_plan(plan: RunPlan, folder: Path) -> Path:
    """Write ``plan`` into the run folder (atomically)."""
    path = folder / PLAN_FILE
    atomic_write_text(path, json.dumps(plan.as_json(), indent=2) + "\n")
    return path


def load_plan(folder: Path) -> RunPlan:
    """The run plan of a run folder; a located :class:`RunError` when it is missing or wrong."""
    path = folder / PLAN_FILE
    if not path.is_file():
        raise RunError(
            f"no {PLAN_FILE} here: not a folder made by `rosaadl run` (give the model to run instead)",
            file=str(folder),
        )
    try:
        data = loads_bounded(path.read_text(encoding="utf-8"))
        if data.get("version") != PLAN_VERSION:
            raise ValueError(f"version {data.get('version')!r}, expected {PLAN_VERSION}")
        nodes = [
            NodeLaunch(
                **{
                    **item,
                    "parameters": [tuple(p) for p in item["parameters"]],
                    "remappings": [tuple(r) for r in item["remappings"]],
                }
            )
            for item in data["nodes"]
        ]
        topics = [TopicPlan(**item) for item in data["topics"]]
        chains = [
            {"name": str(c["name"]), "topics": [[str(part) for part in hop] for hop in c["topics"]]}
            for c in data.get("chains", [])  # a plan written before chains were kept has none
        ]
        return RunPlan(
            app=str(data["app"]), model=str(data["model"]), nodes=nodes, topics=topics, chains=chains
        )
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        raise RunError(
            f"unreadable run plan ({exc}); run the model again to rewrite it", file=str(path)
        ) from exc

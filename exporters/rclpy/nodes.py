"""What each ROS node of a generated workspace contains, read from the AADL instance.

One node class per AADL process classifier (processes of the same classifier and structure share
their class; each process instance is one node in the launch files).  Inside a node:

* each AADL thread is a callback group: a ``MutuallyExclusiveCallbackGroup`` of its own, shared
  by the threads that access the same protected data component (ROSMOD's callback queue of a
  component, ``Concurrency_Control_Protocol`` set), or one ``ReentrantCallbackGroup`` for a
  thread array (its elements run the same callbacks concurrently);
* dispatch: ``Periodic`` → ``create_timer`` with the ``Period``; ``Sporadic``/``Aperiodic`` →
  one subscription per in event (data) port (in data ports when it has no event port), one
  service per provided subprogram access; ``Timed``/``Hybrid`` → both; ``Background`` → a
  one-shot timer at start-up; in ports that do not dispatch their thread feed a bounded queue
  the thread reads when it runs;
* out ports → ``create_publisher``; required subprogram access → ``create_client`` (and a
  helper that calls it with ``call_async``); Queue_Size (or ``ROS_Properties::QoS_Depth``) →
  QoS depth, event ports KEEP_LAST/RELIABLE, data ports depth 1;
* parameters ``<thread>.period``, ``<thread>.deadline`` (seconds) and ``<thread>.priority``;
  each dispatching callback logs a deadline overrun;
* the workload twin (:mod:`~rosaadl.exporters.rclpy.twin`): ``Compute_Execution_Time`` bounds of
  each thread (parameters ``<thread>.cet_min``/``cet_max``) and the ``Data_Size`` of each out port.

A process with no thread is one implicit thread named after the node, so that its ports still
have their constructs.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, Location
from rosaadl.exporters.rclpy import naming
from rosaadl.exporters.rclpy.instances import enum_name, key, prop
from rosaadl.exporters.rclpy.messages import InterfaceType, MessageCatalog
from rosaadl.exporters.rclpy.preservation import fit_marker
from rosaadl.exporters.rclpy.topics import Topology
from rosaadl.exporters.rclpy.twin import assign_twin_outputs
from rosaadl.properties import Range
from rosaadl.units import Quantity

__all__ = [
    "QoS",
    "PortPlan",
    "ServicePlan",
    "GroupPlan",
    "ThreadPlan",
    "NodeClass",
    "NodeBuilder",
    "seconds",
    "cet_bounds",
    "size_bytes",
    "quantity_text",
    "threads_of",
]

log = logging.getLogger(__name__)

#: Fixed marker and method names of a node module, which model names must not take.
_RESERVED_MEMBERS = frozenset(
    {
        "imports",
        "init",
        "members",
        "main",
        "check_deadline",
        "node",
        "period_of",
        "cet_of",
        "emulate",
        "emulating",
        "payload",
        "twin",
        "twin_publishing",
        "twin_calls",
        "twin_call",
        "twin_waiting",
        "tracer",
        "take_priority",
        "scheduling",
        "started_scheduling",
        "warned",
        "warn_once",
        "release_of",
        "start_timers",
    }
)

_PORT_CATEGORIES = frozenset({"dataPort", "eventPort", "eventDataPort"})
_ACCESS_CATEGORIES = frozenset({"subprogramAccess", "subprogramGroupAccess"})
_UNPROTECTED = frozenset({"", "none_specified", "nonespecified", "none"})


@dataclass(frozen=True)
class QoS:
    """A QoS profile as the generated code writes it."""

    depth: int = 1
    history: str = "KEEP_LAST"
    reliability: str = "RELIABLE"
    durability: str = "VOLATILE"


@dataclass
class PortPlan:
    """An AADL port of a thread and its rclpy construct."""

    name: str
    ident: str
    direction: str  # "in" | "out"
    category: str
    msg: InterfaceType
    local: str  # topic name in the node's code (remapped by the launch files)
    qos: QoS
    key: str
    rel_path: tuple[str, ...]
    triggers: bool = False
    msg_class: str = ""
    attr: str = ""
    callback: str = ""
    queue_attr: str = ""
    marker: str = ""
    data_size: int | None = None  # Data_Size in bytes (the workload twin's payload)


@dataclass
class ServicePlan:
    """A subprogram access of a thread: a service (provides) or a client (requires)."""

    name: str
    ident: str
    role: str  # "server" | "client"
    srv: InterfaceType
    local: str
    key: str
    rel_path: tuple[str, ...]
    srv_class: str = ""
    attr: str = ""
    callback: str = ""
    call_method: str = ""
    marker: str = ""


@dataclass
class GroupPlan:
    """A callback group."""

    attr: str
    kind: str  # "MutuallyExclusiveCallbackGroup" | "ReentrantCallbackGroup"
    members: list[str] = field(default_factory=list)
    reason: str = ""


@dataclass
class ThreadPlan:
    """An AADL thread (or thread array) of a node and its constructs."""

    name: str  # dotted path below the process
    ident: str
    dispatch: str
    key: str
    rel_path: tuple[str, ...]
    size: int = 1
    period: float | None = None
    deadline: float | None = None
    priority: int | None = None
    offset: float | None = None  # Dispatch_Offset in seconds: a timer's releases from its period's grid
    period_text: str = ""
    deadline_text: str = ""
    cet_text: str = ""
    offset_text: str = ""
    cet: tuple[float, float] | None = None  # Compute_Execution_Time bounds in seconds
    policy: str = ""
    group: GroupPlan | None = None
    ports: list[PortPlan] = field(default_factory=list)
    services: list[ServicePlan] = field(default_factory=list)
    timer: str | None = None  # "periodic" | "oneshot" | None
    dormant: bool = False  # a periodic timer of Period 0: made cancelled, for the user code to start
    timer_attr: str = ""
    callback: str = ""
    marker: str = ""
    implicit: bool = False
    container: bool = False  # a thread group's (or the process's) own ports, no thread of its own
    dispatch_inferred: bool = False
    twin_outputs: list[PortPlan] = field(default_factory=list)  # what its emulated dispatch publishes
    twin_calls: list[ServicePlan] = field(default_factory=list)  # the services its emulated dispatch calls

    @property
    def sched_policy(self) -> str:
        """The policy its priority runs with, as the generated code writes it: ``os.SCHED_FIFO``
        or ``os.SCHED_RR`` when the thread's POSIX_Scheduling_Policy says so, else ``None``: the
        policy the node was started with (the launch prefix's ``chrt``, from the process)."""
        policy = self.policy.lower()
        return {"sched_fifo": "os.SCHED_FIFO", "sched_rr": "os.SCHED_RR"}.get(policy, "None")

    @property
    def dispatches(self) -> bool:
        """Whether the thread has callbacks of its own (a timer, triggering ports or services)."""
        triggered = [p for p in self.inputs if p.triggers]
        return not self.container and bool(self.timer or self.servers or triggered)

    @property
    def inputs(self) -> list[PortPlan]:
        return [p for p in self.ports if p.direction == "in"]

    @property
    def outputs(self) -> list[PortPlan]:
        return [p for p in self.ports if p.direction == "out"]

    @property
    def servers(self) -> list[ServicePlan]:
        return [s for s in self.services if s.role == "server"]

    @property
    def clients(self) -> list[ServicePlan]:
        return [s for s in self.services if s.role == "client"]

    def summary(self) -> str:
        """``Sporadic, Period 33333 us, Deadline 33333 us, Compute_Execution_Time 37000 us .. 37000 us``."""
        if self.container:
            return "ports that none of its threads handles (connected there), used by its threads"
        parts = [self.dispatch or "dispatch not set"]
        if self.size > 1:
            parts.append(f"{self.size} threads")
        if self.period_text:
            parts.append(f"Period {self.period_text}")
        if self.deadline_text:
            parts.append(f"Deadline {self.deadline_text}")
        if self.offset_text:
            parts.append(f"Dispatch_Offset {self.offset_text}")
        if self.cet_text:
            parts.append(f"Compute_Execution_Time {self.cet_text}")
        if self.priority is not None:
            parts.append(f"Priority {self.priority}")
        return ", ".join(parts)


@dataclass
class NodeClass:
    """One generated module and ``Node`` subclass."""

    package: str
    module: str
    class_name: str
    executable: str
    node_name: str
    classifier: str
    key: str
    threads: list[ThreadPlan] = field(default_factory=list)
    groups: list[GroupPlan] = field(default_factory=list)
    thread_count: int = 1
    imports: list[tuple[str, list[str]]] = field(default_factory=list)  # (module, names); [] = import
    interfaces: list[InterfaceType] = field(default_factory=list)
    uses_queue: bool = False
    instances: list[EObject] = field(default_factory=list)
    signature: tuple = ()

    @property
    def ports(self) -> list[PortPlan]:
        return [p for t in self.threads for p in t.ports]

    @property
    def services(self) -> list[ServicePlan]:
        return [s for t in self.threads for s in t.services]

    @property
    def group_kinds(self) -> list[str]:
        return sorted({g.kind for g in self.groups})

    def marker(self, suffix: str, indent: int = 8) -> str:
        """The name of a block of this module (``<module>.<suffix>``), fitted to its line."""
        return fit_marker(f"{self.module}.{suffix}", indent)


#: Seconds per unit of AADL_Project::Time_Units, as divisors or multipliers of the value (exact
#: for the common literals; other literals go through :meth:`Quantity.to`).
_TIME_DIVISORS = {"ps": 10**12, "ns": 10**9, "us": 10**6, "ms": 10**3, "sec": 1}
_TIME_MULTIPLIERS = {"min": 60, "hr": 3600}


def seconds(value: object) -> float | None:
    """A time property value in seconds (the upper bound of a range), None when not a time."""
    if isinstance(value, Range):
        value = value.maximum
    if isinstance(value, Quantity):
        unit = (value.unit or "").lower()
        if unit in _TIME_DIVISORS and isinstance(value.value, (int, float)):
            return value.value / _TIME_DIVISORS[unit]
        if unit in _TIME_MULTIPLIERS and isinstance(value.value, (int, float)):
            return float(value.value * _TIME_MULTIPLIERS[unit])
        try:
            converted = value.to("sec")
        except Exception:  # noqa: BLE001 - not a time unit: not usable as a period
            return None
        return float(converted)
    return None


def cet_bounds(value: object) -> tuple[float, float] | None:
    """``Compute_Execution_Time`` as (lower, upper) bound in seconds (a single time: both), None
    when it is not a time."""
    if isinstance(value, Range):
        low, high = seconds(value.minimum), seconds(value.maximum)
        if low is None or high is None:
            return None
        return (min(low, high), max(low, high))
    one = seconds(value)
    return None if one is None else (one, one)


def size_bytes(value: object) -> int | None:
    """A ``Size`` property value (``Data_Size``) in bytes, None when it is not a size."""
    if isinstance(value, Range):
        value = value.maximum
    if not isinstance(value, Quantity) or isinstance(value.value, bool):
        return None
    try:
        converted = value.to("Bytes")
    except Exception:  # noqa: BLE001 - not a size unit
        return None
    return max(0, round(converted)) if isinstance(converted, (int, float)) else None


def quantity_text(value: object) -> str:
    """A property value as the model writes it (``33333 us``, ``2 ms .. 3 ms``)."""
    if value is None:
        return ""
    if isinstance(value, Range):
        return f"{quantity_text(value.minimum)} .. {quantity_text(value.maximum)}"
    if isinstance(value, Quantity):
        number = value.value
        if isinstance(number, float) and number.is_integer():
            number = int(number)
        return f"{number} {value.unit}" if value.unit else str(number)
    return " ".join(str(value).split())


def threads_of(component: EObject) -> list[EObject]:
    """Thread instances below a component (through thread groups), in declaration order."""
    found: list[EObject] = []
    stack = list(reversed(list(component.componentInstances)))
    while stack:
        child = stack.pop()
        category = enum_name(child.category)
        if category == "thread":
            found.append(child)
        elif category == "threadGroup":
            stack.extend(reversed(list(child.componentInstances)))
    return found


def _containers(process: EObject) -> list[EObject]:
    """The process and the thread groups below it, in declaration order."""
    found = [process]
    stack = list(reversed(list(process.componentInstances)))
    while stack:
        child = stack.pop()
        if enum_name(child.category) == "threadGroup":
            found.append(child)
            stack.extend(reversed(list(child.componentInstances)))
    return found


def _relative_path(obj: EObject, process: EObject) -> tuple[str, ...]:
    parts: list[str] = []
    current = obj
    while current is not None and current is not process:
        parts.append(current.name or "")
        current = current.eContainer()
    return tuple(reversed(parts))


def _int(value: object) -> int | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, int):
        return value
    if isinstance(value, float) and value.is_integer():
        return int(value)
    if isinstance(value, Quantity) and isinstance(value.value, int):
        return value.value
    return None


def _features(component: EObject) -> list[EObject]:
    """Feature instances of a component, feature groups expanded."""
    found: list[EObject] = []
    stack = list(reversed(list(component.featureInstances)))
    while stack:
        feature = stack.pop()
        if enum_name(feature.category) == "featureGroup":
            stack.extend(reversed(list(feature.featureInstances)))
        else:
            found.append(feature)
    return found


class NodeBuilder:
    """Builds the :class:`NodeClass` plans of the processes of one system instance."""

    def __init__(self, root: EObject, catalog: MessageCatalog, topology: Topology) -> None:
        self.root = root
        self.catalog = catalog
        self.topology = topology
        self.diagnostics: list[Diagnostic] = []

    def _warn(self, message: str, obj: EObject | None = None) -> None:
        path = model.instance_path(obj) if obj is not None else None
        self.diagnostics.append(Diagnostic("warning", message, Location(path=path)))
        log.warning("%s%s", f"{path}: " if path else "", message)

    def _own_end(self, feature: EObject) -> bool:
        """A feature of a process or thread group that gets a publisher, subscription, server or
        client of its own: the end of a connection instance, or a port of the component itself
        that nothing reaches (a ROSMOD component's publisher that no subscriber of the
        deployment reads still publishes); not one that only passes a thread's port through."""
        if self.topology.is_end(feature):
            return True
        return not self.topology.reached(feature) and not self.catalog.connected_inside(feature)

    # ------------------------------------------------------------------ node classes

    def signature(self, process: EObject) -> tuple:
        """What makes two processes of one classifier need different classes."""
        items = []
        for thread in threads_of(process) or [process]:
            ports = tuple(
                (
                    f.name,
                    enum_name(f.category),
                    enum_name(f.direction),
                    enum_name(f.access),
                    f.classifier or "",
                )
                for f in _features(thread)
            )
            items.append((_relative_path(thread, process), _dispatch_of(thread), ports))
        for container in _containers(process):
            ends = tuple(f.name for f in _features(container) if self._own_end(f))
            if ends:
                items.append((_relative_path(container, process), "container", ends))
        return tuple(items)

    def build(
        self,
        process: EObject,
        *,
        package: str,
        module: str,
        class_name: str,
        node_name: str,
        executable: str,
        signature: tuple | None = None,
    ) -> NodeClass:
        """The plan of the class of ``process`` (the first instance of its classifier)."""
        cls = NodeClass(
            package=package,
            module=module,
            class_name=class_name,
            executable=executable,
            node_name=node_name,
            classifier=process.classifier or "",
            key=key(process),
            instances=[process],
            signature=signature if signature is not None else self.signature(process),
        )
        members = naming.NameTable(_RESERVED_MEMBERS)
        threads = threads_of(process)
        count = len(threads)
        seen: dict[tuple[str, ...], ThreadPlan] = {}
        for thread in threads:
            rel = _relative_path(thread, process)
            plan = seen.get(rel)
            if plan is not None:  # another element of a thread array
                plan.size += 1
                continue
            plan = self._thread(cls, thread, process, rel, members)
            seen[rel] = plan
            cls.threads.append(plan)
        if not threads:
            count = 1
            plan = self._thread(cls, process, process, (), members, implicit=True)
            cls.threads.append(plan)
        else:
            for container in _containers(process):
                ends = [
                    f
                    for f in _features(container)
                    if enum_name(f.category) in _PORT_CATEGORIES | _ACCESS_CATEGORIES and self._own_end(f)
                ]
                if ends:
                    rel = _relative_path(container, process)
                    cls.threads.append(self._thread(cls, container, process, rel, members, features=ends))
        cls.thread_count = max(1, count)
        self._groups(cls, process, threads)
        assign_twin_outputs(cls)
        self._finish(cls)
        return cls

    def _thread(
        self,
        cls: NodeClass,
        thread: EObject,
        process: EObject,
        rel: tuple[str, ...],
        members: naming.NameTable,
        *,
        implicit: bool = False,
        features: list[EObject] | None = None,
    ) -> ThreadPlan:
        container = features is not None
        dotted = ".".join(rel) if rel else cls.node_name
        ident = members.unique(naming.identifier("_".join(rel) if rel else cls.module, fallback="thread"))
        period_value = None if container else prop(thread, "Period")
        deadline_value = None if container else prop(thread, "Deadline")
        if seconds(deadline_value) is None:  # AADL's default Deadline is the Period
            deadline_value = period_value
        offset_value = None if container else prop(thread, "Dispatch_Offset")
        dispatch = "" if container else _dispatch_of(thread)
        plan = ThreadPlan(
            name=dotted,
            ident=ident,
            dispatch=dispatch,
            key=key(thread),
            rel_path=rel,
            period=seconds(period_value),
            deadline=seconds(deadline_value),
            priority=None if container else _int(prop(thread, "Priority")),
            offset=seconds(offset_value),
            offset_text=quantity_text(offset_value) if seconds(offset_value) else "",
            period_text=quantity_text(period_value) if seconds(period_value) is not None else "",
            deadline_text=quantity_text(deadline_value) if seconds(deadline_value) is not None else "",
            cet_text="" if container else quantity_text(prop(thread, "Compute_Execution_Time")),
            cet=None if container else cet_bounds(prop(thread, "Compute_Execution_Time")),
            policy="" if container else enum_name(prop(thread, "POSIX_Scheduling_Policy")),
            implicit=implicit,
            container=container,
        )
        if container:
            plan.key = f"{plan.key}#ports"
        plan.callback = f"on_{ident}"
        plan.marker = cls.marker(ident)
        plan.timer_attr = f"timer_{ident}"
        names = naming.NameTable()
        for feature in features if container else _features(thread):
            category = enum_name(feature.category)
            if category in _PORT_CATEGORIES:
                self._port(cls, plan, feature, process, names, members)
            elif category in _ACCESS_CATEGORIES:
                self._access(cls, plan, feature, process, names, members)
        if container:
            for port in plan.inputs:
                port.triggers = True
        else:
            self._dispatch(plan, thread)
        return plan

    def _local_name(self, plan: ThreadPlan, feature: EObject, process: EObject, port_ident: str) -> str:
        """The topic or service name the node's code uses for a feature (see ``topics``)."""
        outer = self.topology.outer_feature(feature, process)
        if outer is not feature or plan.implicit or plan.container:
            owner = outer.eContainer()
            path = []
            while owner is not None and owner is not process:
                path.append(naming.topic_token(owner.name or ""))
                owner = owner.eContainer()
            return "/".join([*reversed(path), naming.topic_token(outer.name or "")])
        return f"{plan.ident}/{port_ident}"

    def _port(self, cls, plan, feature, process, names, members) -> None:
        direction = enum_name(feature.direction) or "in"
        category = enum_name(feature.category)
        ident = names.unique(naming.identifier(feature.name or "", fallback="port"))
        typed = (
            feature if feature.classifier or category == "eventPort" else self.topology.typed_peer(feature)
        )
        msg = self.catalog.for_port(typed or feature)
        directions = ["in", "out"] if direction == "inOut" else [direction]
        for index, one in enumerate(directions):
            port_ident = ident if index == 0 else names.unique(f"{ident}_out")
            base = members.unique(naming.shorten(f"{plan.ident}_{port_ident}"))
            port = PortPlan(
                name=feature.name or "",
                ident=port_ident,
                direction=one,
                category=category,
                msg=msg,
                local=self._local_name(plan, feature, process, port_ident),
                qos=self._qos(feature, category),
                key=key(feature),
                rel_path=(*plan.rel_path, feature.name or ""),
                data_size=size_bytes(prop(feature, "Data_Size")),
            )
            if one == "out":
                port.attr = f"pub_{base}"
            else:
                port.attr = f"sub_{base}"
                port.callback = f"on_{base}"
                port.queue_attr = f"inbox_{base}"
                port.marker = cls.marker(f"{plan.ident}.{port_ident}")
            plan.ports.append(port)

    def _access(self, cls, plan, feature, process, names, members) -> None:
        access = enum_name(feature.access) or "requires"
        ident = names.unique(naming.identifier(feature.name or "", fallback="service"))
        base = members.unique(naming.shorten(f"{plan.ident}_{ident}"))
        local_name = self._local_name(plan, feature, process, ident)
        typed = feature if feature.classifier else self.topology.typed_peer(feature)
        service = ServicePlan(
            name=feature.name or "",
            ident=ident,
            role="server" if access == "provides" else "client",
            srv=self.catalog.for_access(typed or feature),
            local=local_name,
            key=key(feature),
            rel_path=(*plan.rel_path, feature.name or ""),
        )
        if service.role == "server":
            service.attr = f"srv_{base}"
            service.callback = f"on_{base}"
            service.marker = cls.marker(f"{plan.ident}.{ident}")
        else:
            service.attr = f"cli_{base}"
            service.call_method = f"call_{base}"
            service.callback = f"on_{base}_response"
            service.marker = cls.marker(f"{plan.ident}.{ident}.response")
        plan.services.append(service)

    def _qos(self, feature: EObject, category: str) -> QoS:
        depth = _int(prop(feature, "QoS_Depth"))
        if depth is None:
            depth = _int(prop(feature, "Queue_Size"))
        if category == "dataPort":
            depth = 1
        if depth is None or depth < 1:
            depth = 1
        history = enum_name(prop(feature, "QoS_History")).upper() or "KEEP_LAST"
        reliability = enum_name(prop(feature, "QoS_Reliability")).upper() or "RELIABLE"
        durability = enum_name(prop(feature, "QoS_Durability")).upper() or "VOLATILE"
        if history not in ("KEEP_LAST", "KEEP_ALL"):
            history = "KEEP_LAST"
        if reliability not in ("RELIABLE", "BEST_EFFORT"):
            reliability = "RELIABLE"
        if durability not in ("VOLATILE", "TRANSIENT_LOCAL"):
            durability = "VOLATILE"
        return QoS(depth=depth, history=history, reliability=reliability, durability=durability)

    def _dispatch(self, plan: ThreadPlan, thread: EObject) -> None:
        dispatch = plan.dispatch
        inputs = plan.inputs
        events = [p for p in inputs if p.category != "dataPort"]
        if not dispatch:
            if events or plan.servers:
                dispatch = "Sporadic"
            elif plan.period is not None:
                dispatch = "Periodic"
            else:
                dispatch = "Background"
            plan.dispatch = dispatch
            plan.dispatch_inferred = True
        low = dispatch.lower()
        if low == "periodic":
            plan.timer = "periodic"
        elif low in ("timed", "hybrid"):
            plan.timer = "periodic"
            for port in events:
                port.triggers = True
        elif low in ("sporadic", "aperiodic"):
            triggers = events or inputs
            for port in triggers:
                port.triggers = True
            if not triggers and not plan.servers:
                if plan.period is not None:
                    plan.timer = "periodic"
                    self._warn(
                        f"{dispatch} thread {plan.name!r} has no in port nor provided service to dispatch "
                        "it; it runs every Period (its minimum inter-arrival time)",
                        thread,
                    )
                else:
                    self._warn(
                        f"{dispatch} thread {plan.name!r} has no in port, no provided service and no Period: "
                        "nothing dispatches it",
                        thread,
                    )
        elif low == "background":
            plan.timer = "oneshot"
        else:
            self._warn(
                f"thread {plan.name!r}: unknown Dispatch_Protocol {dispatch!r}; run as Background", thread
            )
            plan.timer = "oneshot"
        if plan.timer == "periodic" and plan.period is None:
            self._warn(
                f"thread {plan.name!r} runs on a timer but has no Period: the node needs the parameter "
                f"{plan.ident}.period at start-up",
                thread,
            )
        elif plan.timer == "periodic" and plan.period <= 0:
            # ROSMOD's timer of period 0 (the textual `timer` project's sporadic_timer): a timer the
            # component's own code starts; a timer of period 0 would refuse to start the node.
            self._warn(
                f"thread {plan.name!r} has Period {plan.period_text or '0'}: its timer is made "
                "cancelled (its user code may start it), nothing in the model dispatches it",
                thread,
            )
            plan.dormant = True

    # ------------------------------------------------------------------ callback groups

    def _groups(self, cls: NodeClass, process: EObject, threads: list[EObject]) -> None:
        by_rel = {t.rel_path: t for t in cls.threads}
        parent: dict[str, str] = {t.ident: t.ident for t in cls.threads}
        reasons: dict[str, str] = {}

        def find(x: str) -> str:
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        owners: dict[int, tuple[str, EObject]] = {}
        shared_names: dict[str, str] = {}
        for thread in threads:
            plan = by_rel.get(_relative_path(thread, process))
            if plan is None or plan.size > 1:
                continue
            for data in self.topology.shared_data(thread):
                protocol = enum_name(prop(data, "Concurrency_Control_Protocol")).lower()
                if protocol in _UNPROTECTED:
                    continue
                first = owners.get(id(data))
                if first is None:
                    owners[id(data)] = (plan.ident, data)
                    continue
                a, b = find(first[0]), find(plan.ident)
                if a != b:
                    parent[b] = a
                protocol_name = enum_name(prop(data, "Concurrency_Control_Protocol"))
                reasons[a] = f"Its threads share {data.name} ({protocol_name})"
                shared_names[a] = naming.identifier("_".join(_relative_path(data, process)), fallback="data")
        for plan in cls.threads:
            if not plan.container:
                continue
            inside = [
                t
                for t in cls.threads
                if not t.container and t.rel_path[: len(plan.rel_path)] == plan.rel_path
            ]
            roots = {find(t.ident) for t in inside}
            if len(roots) == 1 and all(t.size == 1 for t in inside):
                parent[plan.ident] = roots.pop()
        groups: dict[str, GroupPlan] = {}
        group_names = naming.NameTable({f"cbg_{t.ident}" for t in cls.threads})
        for plan in cls.threads:
            root = find(plan.ident)
            group = groups.get(root)
            if group is None:
                if plan.size > 1:
                    group = GroupPlan(
                        attr=f"cbg_{plan.ident}",
                        kind="ReentrantCallbackGroup",
                        reason=f"A thread array of {plan.size}: its callbacks may run concurrently",
                    )
                else:
                    members = [t for t in cls.threads if find(t.ident) == root]
                    real = [t for t in members if not t.container]
                    if len(real) <= 1:
                        attr = f"cbg_{(real or members)[0].ident}"
                    else:
                        attr = group_names.unique(f"cbg_{shared_names.get(root, root)}")
                    group = GroupPlan(
                        attr=attr,
                        kind="MutuallyExclusiveCallbackGroup",
                        reason=reasons.get(root, "") if len(real) > 1 else "",
                    )
                groups[root] = group
                cls.groups.append(group)
            group.members.append(plan.name)
            plan.group = group

    # ------------------------------------------------------------------ imports

    def _finish(self, cls: NodeClass) -> None:
        interfaces: list[InterfaceType] = []
        for port in cls.ports:
            if port.msg not in interfaces:
                interfaces.append(port.msg)
        for service in cls.services:
            if service.srv not in interfaces:
                interfaces.append(service.srv)
        interfaces.sort()
        cls.interfaces = interfaces
        fixed = {
            cls.class_name,
            "Node",
            "MultiThreadedExecutor",
            "ExternalShutdownException",
            "MutuallyExclusiveCallbackGroup",
            "ReentrantCallbackGroup",
            "QoSProfile",
            "QoSHistoryPolicy",
            "QoSReliabilityPolicy",
            "QoSDurabilityPolicy",
            "rclpy",
            "array",
            "os",
            "random",
            "sys",
            "threading",
            "force_exit",
            "wait_loop_at_normal_priority",
            "restore_scheduling",
            "time",
            "deque",
            "main",
            "THREAD_COUNT",
            "_rclpy",
        }
        counts: dict[str, int] = {}
        for itype in interfaces:
            counts[itype.name] = counts.get(itype.name, 0) + 1
        aliases: dict[InterfaceType, str] = {}
        for itype in interfaces:
            name = itype.name
            if counts[name] > 1 or name in fixed:
                name = naming.camel(itype.package) + itype.name
                if itype.kind == "srv":
                    name += "Srv"
            aliases[itype] = name
        for port in cls.ports:
            port.msg_class = aliases[port.msg]
        for service in cls.services:
            service.srv_class = aliases[service.srv]
        cls.uses_queue = any(p.direction == "in" and not p.triggers for p in cls.ports)
        by_module: dict[str, list[str]] = {}
        for itype in interfaces:
            alias = aliases[itype]
            text = itype.name if alias == itype.name else f"{itype.name} as {alias}"
            by_module.setdefault(itype.module, []).append(text)
        imports: list[tuple[str, list[str]]] = [
            (module, sorted(names, key=str.lower)) for module, names in by_module.items()
        ]
        imports.append(("rclpy", []))
        imports.append(("rclpy.callback_groups", cls.group_kinds))
        imports.append(("rclpy.executors", ["ExternalShutdownException", "MultiThreadedExecutor"]))
        imports.append(("rclpy.impl.implementation_singleton", ["rclpy_implementation as _rclpy"]))
        imports.append(("rclpy.node", ["Node"]))
        if cls.ports:
            imports.append(
                (
                    "rclpy.qos",
                    ["QoSDurabilityPolicy", "QoSHistoryPolicy", "QoSProfile", "QoSReliabilityPolicy"],
                )
            )
        imports.sort(key=lambda item: (item[0].lower(), bool(item[1])))
        cls.imports = imports


def _dispatch_of(thread: EObject) -> str:
    value = prop(thread, "Dispatch_Protocol")
    return enum_name(value) if value is not None else ""

"""Deployment of the nodes: node names, bindings, scheduling, parameters and remappings.

Each process instance is one node of the launch files:

* its name is ``ROS_Properties::Node_Name`` or the instance name (``cam_2`` for ``cam[2]``),
  unique within its namespace (``ROS_Properties::Namespace``);
* ``Actual_Processor_Binding`` (of the process, else the union of its threads') gives the cores
  it may run on, written as ``taskset -c <cpus>`` in the launch ``prefix``.  A core's CPU number
  is ``Cheddar_Properties::Core_Id`` when set, otherwise its position from 0, in the instance's
  order (OSATE's: by category, declaration order within one), among the innermost processors of
  its *host*: the nearest enclosing multi-core
  ``processor``, or system carrying ``Hardware_Properties::Architecture`` (a chip, as the
  library models SoCs).  A processor with no such host is a host of its own (a ROSMOD host)
  and gets no affinity, only its scheduling.  A binding to a virtual processor follows that
  virtual processor's own binding; a binding to a system or a multi-core processor means all of
  its cores;
* ``POSIX_Scheduling_Policy`` ``SCHED_FIFO``/``SCHED_RR`` with ``Priority`` (of the process,
  else the highest of its threads') is written as ``chrt -f <priority>`` / ``chrt -r``; a
  ``Priority`` with no policy on the process means ``SCHED_FIFO``; ``SCHED_OTHER(S)`` means no
  real-time scheduling.  Linux real-time priorities are 1..99; other values are clamped;
* the parameters of each thread (period, deadline, priority, and the bounds of its
  ``Compute_Execution_Time`` when it has one) and the remapping of each local
  topic or service name to the topic its connections give.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, Location
from rosaadl.exporters.rclpy import naming
from rosaadl.exporters.rclpy.instances import enum_name, key, prop
from rosaadl.exporters.rclpy.nodes import NodeClass, ThreadPlan, cet_bounds, seconds, threads_of
from rosaadl.exporters.rclpy.topics import Group, normalize_ros_name
from rosaadl.properties import Reference

__all__ = [
    "HostPlan",
    "NodeInstance",
    "node_name_of",
    "namespace_of",
    "bound_processors",
    "host_of",
    "cpu_number",
    "scheduling_of",
    "launch_prefix",
    "Deployment",
    "find_feature",
]

log = logging.getLogger(__name__)

_RT_POLICIES = {"sched_fifo": "-f", "sched_rr": "-r"}
_NON_RT = frozenset({"sched_other", "sched_others", "sched_batch", "sched_idle"})


@dataclass
class HostPlan:
    """A machine of the deployment: a launch file of its own."""

    ident: str
    name: str
    path: str
    key: str
    nodes: list[NodeInstance] = field(default_factory=list)


@dataclass
class NodeInstance:
    """A process instance as a node of the launch files."""

    process: EObject
    path: str
    key: str
    cls: NodeClass
    node_name: str
    namespace: str
    ident: str
    parameters: list[tuple[str, object]] = field(default_factory=list)
    remappings: list[tuple[str, str]] = field(default_factory=list)
    cpus: list[int] | None = None
    host: HostPlan | None = None
    policy: str = ""
    priority: int | None = None
    prefix: str = ""
    bound_to: list[str] = field(default_factory=list)


def node_name_of(process: EObject) -> str:
    """The ROS node name of a process instance (not yet made unique)."""
    value = prop(process, "Node_Name")
    base = value if isinstance(value, str) and value.strip() else process.name or ""
    name = naming.node_name(base)
    index = [i for i in (process.index or ()) if i]
    if index:
        name += "_" + "_".join(str(i) for i in index)
    return name


def namespace_of(process: EObject) -> str:
    value = prop(process, "Namespace")
    if not isinstance(value, str) or not value.strip():
        return ""
    name = normalize_ros_name(value if value.startswith("/") else "/" + value, allow_private=False)
    return name or ""


def _leaf_processors(component: EObject) -> list[EObject]:
    """The innermost processors of ``component`` (itself when it is a processor without cores),
    in the instance's order."""
    found: list[EObject] = []

    def visit(current: EObject) -> bool:
        below = False
        for child in current.componentInstances:
            below = visit(child) or below
        if enum_name(current.category) == "processor":
            if not below:
                found.append(current)
            return True
        return below

    visit(component)
    return found


def bound_processors(target: EObject, seen: set[int] | None = None) -> list[EObject]:
    """The innermost processors a binding target stands for."""
    seen = seen if seen is not None else set()
    if id(target) in seen or not model.is_a(target, "ComponentInstance"):
        return []
    seen.add(id(target))
    category = enum_name(target.category)
    if category == "virtualProcessor":
        found: list[EObject] = []
        for item in _as_list(prop(target, "Actual_Processor_Binding")):
            if model.is_a(item, "ComponentInstance"):
                found.extend(bound_processors(item, seen))
        return found
    if category in ("processor", "system", "abstract"):
        return _leaf_processors(target)
    return []


def _as_list(value: object) -> list:
    if value is None:
        return []
    return list(value) if isinstance(value, list) else [value]


def host_of(processor: EObject) -> EObject:
    """The host of a core (see the module docstring); the processor itself when it has none."""
    current = processor.eContainer()
    while current is not None and model.is_a(current, "ComponentInstance"):
        category = enum_name(current.category)
        if category == "processor":
            return current
        if category == "system" and prop(current, "Architecture") is not None:
            return current
        current = current.eContainer()
    return processor


def cpu_number(processor: EObject) -> int | None:
    """The Linux CPU number of a core, None when it is a host of its own."""
    core_id = prop(processor, "Core_Id")
    if isinstance(core_id, int) and not isinstance(core_id, bool):
        return core_id
    if isinstance(core_id, str) and core_id.strip().isdigit():
        return int(core_id.strip())
    host = host_of(processor)
    if host is processor:
        return None
    cores = _leaf_processors(host)
    for position, core in enumerate(cores):
        if core is processor:
            return position
    return None


def scheduling_of(process: EObject) -> tuple[str, int | None]:
    """(policy, priority) of a process: see the module docstring."""
    policy = enum_name(prop(process, "POSIX_Scheduling_Policy")).lower()
    priority = prop(process, "Priority")
    priority = priority if isinstance(priority, int) and not isinstance(priority, bool) else None
    if priority is not None and not policy:
        policy = "sched_fifo"
    if priority is None:
        thread_priorities = []
        thread_policies = set()
        for thread in threads_of(process):
            value = prop(thread, "Priority")
            thread_policy = enum_name(prop(thread, "POSIX_Scheduling_Policy")).lower()
            if isinstance(value, int) and not isinstance(value, bool) and thread_policy in _RT_POLICIES:
                thread_priorities.append(value)
                thread_policies.add(thread_policy)
        if thread_priorities and not policy:
            priority = max(thread_priorities)
            policy = sorted(thread_policies)[0]
    if policy in _RT_POLICIES:
        return policy.upper(), priority
    return (policy.upper() if policy else ""), None


def launch_prefix(cpus: list[int] | None, policy: str, priority: int | None) -> str:
    """``taskset -c 0,2 chrt -f 50`` (empty when nothing is to be applied)."""
    parts: list[str] = []
    if cpus:
        parts.append("taskset -c " + ",".join(str(c) for c in sorted(set(cpus))))
    flag = _RT_POLICIES.get(policy.lower())
    if flag and priority is not None:
        parts.append(f"chrt {flag} {priority}")
    return " ".join(parts)


class Deployment:
    """Node instances and hosts of one system instance."""

    def __init__(self, root: EObject) -> None:
        self.root = root
        self.diagnostics: list[Diagnostic] = []
        self.hosts: list[HostPlan] = []
        self._hosts: dict[int, HostPlan] = {}
        self._host_names = naming.NameTable()

    def _warn(self, message: str, obj: EObject | None = None) -> None:
        path = model.instance_path(obj) if obj is not None else None
        self.diagnostics.append(Diagnostic("warning", message, Location(path=path)))
        log.warning("%s%s", f"{path}: " if path else "", message)

    def node_names(self, processes: list[EObject]) -> dict[int, tuple[str, str]]:
        """``id(process) -> (namespace, unique node name)``."""
        tables: dict[str, naming.NameTable] = {}
        result: dict[int, tuple[str, str]] = {}
        for process in processes:
            namespace = namespace_of(process)
            table = tables.setdefault(namespace, naming.NameTable())
            name = table.unique(node_name_of(process))
            result[id(process)] = (namespace, name)
        return result

    def instance(
        self,
        process: EObject,
        cls: NodeClass,
        names: tuple[str, str],
        ident: str,
        topics: dict[int, Group],
        services: dict[int, Group],
    ) -> NodeInstance:
        namespace, node_name = names
        node = NodeInstance(
            process=process,
            path=model.instance_path(process),
            key=key(process),
            cls=cls,
            node_name=node_name,
            namespace=namespace,
            ident=ident,
        )
        self._bindings(node)
        node.policy, node.priority = scheduling_of(process)
        if node.priority is not None and not 1 <= node.priority <= 99:
            clamped = min(99, max(1, node.priority))
            self._warn(f"priority {node.priority} is outside Linux's 1..99; {clamped} is used", process)
            node.priority = clamped
        node.prefix = launch_prefix(node.cpus, node.policy, node.priority)
        self._parameters(node)
        self._remappings(node, topics, services)
        return node

    def _bindings(self, node: NodeInstance) -> None:
        process = node.process
        targets = [t for t in _as_list(prop(process, "Actual_Processor_Binding"))]
        if not targets:
            for thread in threads_of(process):
                for target in _as_list(prop(thread, "Actual_Processor_Binding")):
                    if all(target is not t for t in targets):
                        targets.append(target)
        processors: list[EObject] = []
        for target in targets:
            if isinstance(target, Reference):
                self._warn(f"binding to {target.path!r} does not resolve to an instance; ignored", process)
                continue
            for proc in bound_processors(target):
                if all(proc is not p for p in processors):
                    processors.append(proc)
        if not processors:
            return
        node.bound_to = [model.instance_path(p) for p in processors]
        hosts = []
        for proc in processors:
            host = host_of(proc)
            if all(host is not h for h in hosts):
                hosts.append(host)
        if len(hosts) > 1:
            self._warn(
                f"bound to processors of {len(hosts)} hosts "
                f"({', '.join(model.instance_path(h) for h in hosts)}); it is launched on the first",
                process,
            )
        host = hosts[0]
        cpus = [cpu_number(p) for p in processors if host_of(p) is host]
        node.cpus = sorted({c for c in cpus if c is not None}) or None
        node.host = self._host(host)
        node.host.nodes.append(node)

    def _host(self, host: EObject) -> HostPlan:
        plan = self._hosts.get(id(host))
        if plan is None:
            path = model.instance_path(host)
            relative = path.split(".", 1)[1] if "." in path else path
            plan = HostPlan(
                ident=self._host_names.unique(naming.module_name(relative, fallback="host")),
                name=host.name or "",
                path=path,
                key=key(host),
            )
            self._hosts[id(host)] = plan
            self.hosts.append(plan)
        return plan

    def _parameters(self, node: NodeInstance) -> None:
        for plan in [t for t in node.cls.threads if not t.container]:
            thread = _find_thread(node.process, plan)
            period = seconds(prop(thread, "Period")) if thread is not None else None
            deadline = seconds(prop(thread, "Deadline")) if thread is not None else None
            if deadline is None:  # AADL's default Deadline is the Period
                deadline = period
            priority = prop(thread, "Priority") if thread is not None else None
            node.parameters.append((f"{plan.ident}.period", float(period or 0.0)))
            node.parameters.append((f"{plan.ident}.deadline", float(deadline or 0.0)))
            node.parameters.append(
                (
                    f"{plan.ident}.priority",
                    priority if isinstance(priority, int) and not isinstance(priority, bool) else 0,
                )
            )
            offset = seconds(prop(thread, "Dispatch_Offset")) if thread is not None else None
            if offset and plan.timer == "periodic":  # releases at k * Period + Dispatch_Offset
                node.parameters.append((f"{plan.ident}.offset", float(offset)))
            cet = cet_bounds(prop(thread, "Compute_Execution_Time")) if thread is not None else None
            if cet is not None:  # the workload twin's CPU time per dispatch (parameter rosaadl.emulate)
                node.parameters.append((f"{plan.ident}.cet_min", cet[0]))
                node.parameters.append((f"{plan.ident}.cet_max", cet[1]))

    def _remappings(self, node: NodeInstance, topics: dict[int, Group], services: dict[int, Group]) -> None:
        chosen: dict[str, str] = {}
        for thread in node.cls.threads:
            for element, table in [(p, topics) for p in thread.ports] + [
                (s, services) for s in thread.services
            ]:
                feature = find_feature(node.process, element.rel_path)
                if feature is None:
                    continue
                group = table.get(id(feature))
                if group is None or group.name is None:
                    continue
                local = element.local
                if local in chosen:
                    if chosen[local] != group.name:
                        self._warn(
                            f"{local!r} is connected to {chosen[local]!r} and to {group.name!r}; "
                            f"it is remapped to {chosen[local]!r}",
                            feature,
                        )
                    continue
                chosen[local] = group.name
        node.remappings = [(local, name) for local, name in chosen.items() if local != name]


def _find_thread(process: EObject, plan: ThreadPlan) -> EObject | None:
    if plan.implicit:
        return process
    current = process
    for name in plan.rel_path:
        current = next((c for c in current.componentInstances if c.name == name), None)
        if current is None:
            return None
    return current


def find_feature(process: EObject, rel_path: tuple[str, ...]) -> EObject | None:
    current = process
    for name in rel_path[:-1]:
        current = next((c for c in current.componentInstances if c.name == name), None)
        if current is None:
            return None
    stack = list(current.featureInstances)
    while stack:
        feature = stack.pop(0)
        if feature.name == rel_path[-1] and enum_name(feature.category) != "featureGroup":
            return feature
        stack.extend(feature.featureInstances)
    return None

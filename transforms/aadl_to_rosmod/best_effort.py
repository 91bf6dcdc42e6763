"""Best effort: AADL models not made by rosaadl into a ROSMOD project, as rules of
:data:`BEST_EFFORT` on their instances.

Each root system implementation is instantiated; it gives a hardware model and a deployment
named after its type. Its processors are hosts; each process is a node (on the host of the
processor it, or its cores' cluster, is bound to); each thread in a process is a component
instance of a component made from the thread's classifier (``Type`` for ``Type.impl``,
``Type_<impl>`` for other implementations, in a package named after the AADL package), once per
classifier: its ports from the thread's features (``out``/``in`` ports publishers/subscribers,
``requires``/``provides`` subprogram access clients/servers, typed by
``ROS_Properties::Message_Type`` on the feature or its data classifier, else by an empty
message named after the classifier), a timer when the thread is periodic, else the thread's
deadline and priority on its callbacks. Every element that has no ROSMOD counterpart is a
warning located by its instance path.

The walk visits, per root: the system, the components outside processes (in document order;
what a device or a memory holds is not visited), then each process followed by what it holds
that is not a thread and by its threads, then the root's connections. The rules keep that
order for names made unique and for the warnings; the instances are taken out of the model
once visited.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Sequence

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, Location, RosaadlError, TransformationError
from rosaadl.properties import own_property
from rosaadl.transforms import rosmod_to_aadl as fwd
from rosaadl.transforms.engine import Context, Transformation

from .reading import (
    ClassifierIndex,
    Report,
    add,
    enum_name,
    new,
    qualify,
    quantity_seconds,
    set_given,
    unique,
    words,
)

__all__ = ["BEST_EFFORT", "BestEffortState", "top_level_systems"]

#: the rules of the best-effort conversion
BEST_EFFORT = Transformation("aadl2rosmod_best_effort")

_t = BEST_EFFORT

_PORTS = ("eventDataPort", "dataPort", "eventPort")
_OUTSIDE_NODES = ("processor", "system", "virtualProcessor", "virtualBus")  # visited, and what they hold


def top_level_systems(
    model: EObject, units: Iterable[EObject] | None = None, *, library: Iterable[EObject] = ()
) -> list[str]:
    """Qualified names of the system implementations of ``units`` (default: the model's units
    that are not in ``library``, the units of rosaadl's component library) that no classifier
    of the model uses as a subcomponent or extends: the roots a best-effort conversion
    instantiates."""
    used: set[str] = set()
    for unit in model.units:
        if not _model.is_a(unit, "AadlPackage"):
            continue
        for classifier in unit.classifiers:
            if classifier.extended:
                used.add(qualify(classifier.extended, unit).lower())
            if _model.is_a(classifier, "ComponentImplementation"):
                for sub in classifier.subcomponents:
                    if sub.classifier:
                        used.add(qualify(sub.classifier, unit).lower())
    skipped = {id(unit) for unit in library}
    chosen = list(units) if units is not None else [u for u in model.units if id(u) not in skipped]
    roots = []
    for unit in chosen:
        if not _model.is_a(unit, "AadlPackage"):
            continue
        for classifier in unit.classifiers:
            if (
                not _model.is_a(classifier, "ComponentImplementation")
                or enum_name(classifier.category) != "system"
            ):
                continue
            name = f"{unit.name}::{classifier.name}"
            if name.lower() not in used:
                roots.append(name)
    return roots


class BestEffortState:
    """What the rules of one run share (``ctx.options['state']``): the roots, the project being
    made, the packages, components and message types made so far, and the names taken."""

    def __init__(self, model: EObject, roots: Sequence[str], report: Report) -> None:
        self.model = model
        self.roots = list(roots)
        self.report = report
        self.index = ClassifierIndex(model)
        self.project: EObject | None = None
        self.packages: dict[str, EObject] = {}
        self.components: dict[str, EObject] = {}  # thread classifier (lower case) → Component
        self.messages: dict[str, str] = {}  # data classifier (lower case) → "pkg/Type"
        self.root_name: dict[int, str] = {}  # system instance → the root it instantiates
        self.used_systems: set[str] = set()
        self.taken: dict[tuple[str, int], set[str]] = {}  # (kind, holder) → names taken in it
        self._members: dict[int, tuple[list[EObject], list[EObject]]] = {}

    # -- the walk
    def walk(self, model: EObject) -> Iterator[EObject]:
        """The elements the rules see, in the order of the module documentation."""
        from rosaadl.transforms.instantiate import instantiate

        yield model
        for root in self.roots:
            diagnostics: list[Diagnostic] = []
            try:
                instance = instantiate(model, root, diagnostics=diagnostics, strict=False)
            except RosaadlError as exc:
                raise TransformationError(
                    f"cannot instantiate {root} to convert it: {exc.message}", exc.location
                ) from None
            self.root_name[id(instance)] = root
            try:
                yield from self._instance(instance)
            finally:
                if instance in model.instances:
                    model.instances.remove(instance)

    def _instance(self, instance: EObject) -> Iterator[EObject]:
        yield instance
        processes: list[EObject] = []
        stack = list(reversed(list(instance.componentInstances)))
        while stack:  # document order; what is inside processes is the nodes' business
            child = stack.pop()
            if enum_name(child.category) == "process":
                processes.append(child)
                continue
            yield child
            if enum_name(child.category) in _OUTSIDE_NODES:
                stack.extend(reversed(list(child.componentInstances)))
        for process in processes:
            yield process
            threads, others = self.members(process)
            yield from others
            yield from threads
        stack = [instance]
        while stack:
            current = stack.pop()
            yield from current.connectionInstances
            stack.extend(current.componentInstances)

    def members(self, process: EObject) -> tuple[list[EObject], list[EObject]]:
        """The threads a process holds (through thread groups), and what else it holds that is
        not data (each a warning)."""
        found = self._members.get(id(process))
        if found is None:
            threads: list[EObject] = []
            others: list[EObject] = []
            stack = list(reversed(list(process.componentInstances)))
            while stack:
                current = stack.pop()
                category = enum_name(current.category)
                if category == "thread":
                    threads.append(current)
                elif category == "threadGroup":
                    stack.extend(reversed(list(current.componentInstances)))
                elif category != "data":
                    others.append(current)
            found = self._members[id(process)] = (threads, others)
        return found

    # -- what the rules share
    def names(self, kind: str, holder: EObject) -> set[str]:
        return self.taken.setdefault((kind, id(holder)), set())

    def warn(self, message: str, element: EObject | None) -> None:
        path = _model.instance_path(element) if element is not None else None
        self.report.warn(message, Location(path=path))

    def package(self, name: str) -> EObject:
        found = self.packages.get(name)
        if found is None:
            found = self.packages[name] = new("Package", name=name)
            self.project.software.packages.append(found)
        return found

    def message_type(self, feature: EObject) -> str | None:
        """``pkg/Type`` of a feature's data: its ``Message_Type``, or its classifier's (through
        implementations and ``extends``), else an empty message made for the classifier."""
        given = own_property(feature, fwd.MESSAGE_TYPE)
        if isinstance(given, str):
            return given
        classifier = feature.classifier
        if not classifier:
            return None
        key = classifier.lower()
        if key in self.messages:
            return self.messages[key]
        target = self.index.classifiers.get(key)
        found = None
        seen = 0
        while target is not None and found is None and seen < 50:
            seen += 1
            found = own_property(target, fwd.MESSAGE_TYPE) or own_property(target, fwd.SERVICE_TYPE)
            unit = self.index.unit_of.get(id(target))
            if found is None and _model.is_a(target, "ComponentImplementation") and unit is not None:
                target = self.index.find(target.type, target) if target.type else None
            elif found is None and target.extended and unit is not None:
                target = self.index.find(target.extended, unit)
            else:
                break
        if not isinstance(found, str):
            pkg_name, _, local = classifier.rpartition("::")
            package = self.package(fwd.aadl_identifier(pkg_name or "messages"))
            msg_name = fwd.aadl_identifier(local.replace(".", "_"))
            if enum_name(feature.category) == "subprogramAccess":
                if not any(s.name == msg_name for s in package.services):
                    package.services.append(new("Service", name=msg_name, definition="---\n"))
            elif not any(m.name == msg_name for m in package.messages):
                package.messages.append(new("Message", name=msg_name, definition=""))
                self.report.warn(
                    f"data type {classifier} has no ROS_Properties::Message_Type: made an empty message "
                    f"{package.name}/{msg_name}",
                    Location(path=classifier),
                )
            found = f"{package.name}/{msg_name}"
        self.messages[key] = found
        return found


def state(ctx: Context) -> BestEffortState:
    return ctx.options["state"]


def _node_of(component: EObject) -> EObject | None:
    """The process instance that holds ``component``, if any."""
    current = component.eContainer()
    while current is not None and _model.is_a(current, "ComponentInstance"):
        if enum_name(current.category) == "process":
            return current
        current = current.eContainer()
    return None


def _system_of(component: EObject) -> EObject:
    current = component
    while not _model.is_a(current, "SystemInstance"):
        current = current.eContainer()
    return current


def _category(*names: str, in_node: bool):
    return lambda ctx, c: enum_name(c.category) in names and (_node_of(c) is not None) == in_node


def _not_category(*names: str, in_node: bool):
    return lambda ctx, c: enum_name(c.category) not in names and (_node_of(c) is not None) == in_node


# --------------------------------------------------------------------------- project and platform


@_t.rule("AadlModel", name="project")
def _project(ctx: Context, model: EObject) -> EObject:
    st = state(ctx)
    if not st.roots:
        st.report.warn(
            "no root system implementation to convert: the model has no top-level system "
            "implementation outside the library (name one with roots=)",
            Location(),
        )
    st.project = new("Project", name=model.name or "project", formatVersion="0.3")
    st.project.software = new("Software", name="software")
    return st.project


@_t.rule("SystemInstance", name="system")
def _system(ctx: Context, instance: EObject) -> tuple[EObject, EObject]:
    """The hardware model and the deployment of one root, named after its type."""
    st = state(ctx)
    root = st.root_name[id(instance)]
    type_name = root.rpartition("::")[2].partition(".")[0]
    base = type_name if type_name not in st.used_systems else root.replace("::", "_").replace(".", "_")
    st.used_systems.add(base)
    system = new("System", name=base)
    deployment = new("Deployment", name=base, systemName=base, system=system)
    st.project.systems.append(system)
    st.project.deployments.append(deployment)
    return system, deployment


@_system.bind
def _system_bind(ctx: Context, instance: EObject, system: EObject, deployment: EObject) -> None:
    components = _model.component_instances(instance, include_root=False)
    add(system, "hosts", ctx.resolve_all(components, "host"))
    add(deployment, "nodes", ctx.resolve_all(components, "node"))


@_t.rule("ComponentInstance", name="host", when=_category("processor", in_node=False))
def _host(ctx: Context, processor: EObject) -> EObject:
    taken = state(ctx).names("host", _system_of(processor))
    host = new("Host", name=unique(processor.name, _model.instance_path(processor), taken))
    arch = own_property(processor, fwd.ARCHITECTURE)
    if isinstance(arch, str):
        host.architecture = arch
    return host


@_t.rule(
    "ComponentInstance",
    name="unmapped_component",
    when=_not_category(*_OUTSIDE_NODES, "process", in_node=False),
)
def _unmapped_component(ctx: Context, component: EObject) -> None:
    state(ctx).warn(
        f"{words(enum_name(component.category))} {component.name} has no ROSMOD counterpart; skipped",
        component,
    )


# --------------------------------------------------------------------------- nodes


@_t.rule("ComponentInstance", name="node", when=_category("process", in_node=False))
def _node(ctx: Context, process: EObject) -> EObject:
    st = state(ctx)
    taken = st.names("node", _system_of(process))
    node = new("Node", name=unique(process.name, _model.instance_path(process), taken))
    priority = own_property(process, fwd.PRIORITY)
    if isinstance(priority, int) and not isinstance(priority, bool):
        node.priority = priority
    binding = own_property(process, fwd.PROCESSOR_BINDING)
    targets = binding if isinstance(binding, list) else [binding] if binding is not None else []
    host = None
    for target in targets:
        current = target if isinstance(target, EObject) else None
        while current is not None and host is None:  # the processor, or the one a core is in
            host = next(iter(ctx.resolve(current, "host")), None)
            current = current.eContainer()
        if host is not None:
            break
    if host is not None:
        node.host = host
        node.hostRef = f"{ctx.resolve(_system_of(process), 'system')[0].name}/{host.name}"
    elif targets:
        st.warn(f"process {process.name} is bound to something that is not a processor", process)
    return node


@_node.bind
def _node_bind(ctx: Context, process: EObject, node: EObject) -> None:
    threads, _ = state(ctx).members(process)
    add(node, "componentInstances", ctx.resolve_all(threads, "thread"))


@_t.rule(
    "ComponentInstance",
    name="unmapped_in_node",
    when=_not_category("thread", "threadGroup", "data", in_node=True),
)
def _unmapped_in_node(ctx: Context, component: EObject) -> None:
    category = enum_name(component.category)
    state(ctx).warn(f"{category} {component.name} in a node has no ROSMOD counterpart; skipped", component)


# --------------------------------------------------------------------------- threads


@_t.rule("ComponentInstance", name="thread", when=_category("thread", in_node=True))
def _thread(ctx: Context, thread: EObject) -> EObject:
    """A component instance of the component made from the thread's classifier."""
    st = state(ctx)
    key = (thread.classifier or "").lower()
    comp = st.components.get(key) if key else None
    if comp is None:
        comp = ctx.lazy(_component, thread)
    process = _node_of(thread)
    relative = _model.instance_path(thread)[len(_model.instance_path(process)) + 1 :]
    return new(
        "ComponentInstance",
        name=unique(thread.name, relative, st.names("instance", process)),
        component=comp,
        componentRef=f"{comp.eContainer().name}/{comp.name}",
    )


@_t.rule("ComponentInstance", name="component", lazy=True)
def _component(ctx: Context, thread: EObject) -> tuple[EObject, ...]:
    """The component of a thread's classifier (made from the first thread of it): its ports,
    and a timer when the thread is periodic."""
    st = state(ctx)
    classifier = thread.classifier or ""
    pkg_name, _, local = classifier.rpartition("::")
    type_name, _, impl_name = local.partition(".")
    if not type_name:
        pkg_name, type_name = "threads", thread.name
    name = type_name if impl_name in ("", "impl") else f"{type_name}_{impl_name}"
    package = st.package(fwd.aadl_identifier(pkg_name or "threads"))
    comp = new(
        "Component",
        name=unique(name, f"{name}_{len(package.components)}", {c.name for c in package.components}),
        datatype="Base",
    )
    package.components.append(comp)
    if classifier:
        st.components[classifier.lower()] = comp
    subscribers = []
    for feature in thread.featureInstances:
        port = ctx.lazy(_port, feature)
        if port is None:
            continue
        comp.ports.append(port)
        if _model.is_a(port, "rosmod.Subscriber", "rosmod.Server"):
            subscribers.append(port)
    dispatch = own_property(thread, "Dispatch_Protocol")
    dispatch_name = str(dispatch).lower() if dispatch is not None else ""
    priority = own_property(thread, fwd.PRIORITY)
    priority = priority if isinstance(priority, int) and not isinstance(priority, bool) else None
    deadline = quantity_seconds(own_property(thread, fwd.DEADLINE))
    if dispatch_name == "periodic":
        timer = new(
            "Timer",
            name=f"{thread.name}_timer",
            period=quantity_seconds(own_property(thread, fwd.PERIOD)),
            priority=priority,
            deadline=deadline,
        )
        comp.timers.append(timer)
        return comp, timer
    if dispatch_name in ("sporadic", "aperiodic") and subscribers:
        for port in subscribers:
            set_given(port, priority=priority, deadline=deadline)
    else:
        what = f"dispatch protocol {dispatch}" if dispatch is not None else "no dispatch protocol"
        st.warn(
            f"thread {thread.name} has {what}: neither a timer nor a callback; its component has no "
            "callback for it",
            thread,
        )
    return (comp,)


@_t.rule("FeatureInstance", name="port", lazy=True)
def _port(ctx: Context, feature: EObject) -> EObject | None:
    """A publisher or subscriber for an ``out`` or ``in`` port, a client or server for a
    required or provided subprogram access; None (and a warning) for other features."""
    st = state(ctx)
    thread = feature.eContainer()
    category = enum_name(feature.category)
    name = feature.name
    if category in _PORTS:
        direction = enum_name(feature.direction)
        if direction not in ("in", "out"):
            st.warn(f"port {name} is 'in out': ROSMOD ports publish or subscribe; skipped", feature)
            return None
        type_name = st.message_type(feature)
        cls = "Publisher" if direction == "out" else "Subscriber"
    elif category == "subprogramAccess":
        type_name = st.message_type(feature)
        cls = "Client" if enum_name(feature.access) == "requires" else "Server"
    else:
        if category != "dataAccess":  # the callback queue and shared data are not ports
            st.warn(f"{category} {name} is not a ROSMOD port; skipped", feature)
        return None
    if type_name is None:
        st.warn(f"port {name} of {thread.name} has no data type: its ROSMOD type is left empty", feature)
    return new(cls, name=name, type=type_name)


# --------------------------------------------------------------------------- connections


def _joins_features(ctx: Context, conn: EObject) -> bool:
    return (
        enum_name(conn.kind) == "portConnection"
        and _model.is_a(conn.source, "FeatureInstance")
        and _model.is_a(conn.destination, "FeatureInstance")
    )


@_t.rule("ConnectionInstance", name="connection", when=_joins_features)
def _connection(ctx: Context, conn: EObject) -> None:
    """No target: ROSMOD joins publishers and subscribers by message type; a connection that
    this matching would not make is a warning."""
    st = state(ctx)
    source, destination = conn.source, conn.destination
    owners = (source.eContainer(), destination.eContainer())
    if any(enum_name(getattr(owner, "category", "")) != "thread" for owner in owners):
        st.warn(
            f"connection {conn.name} does not join two threads (ROSMOD topics join publishers and "
            "subscribers of nodes); not kept",
            conn,
        )
        return
    if st.message_type(source) != st.message_type(destination):
        st.warn(
            f"connection {conn.name} joins ports of different types; ROSMOD matches topics by message "
            "type, so it is not kept",
            conn,
        )

"""The convention's rules on the software: a software package gives a ROSMOD package; its
``data`` types with a ``Message_Type`` give messages (their fields parsed from ``Definition``),
its subprograms with a ``Service_Type`` services; a thread group gives a component whose ports
are the group's features (in feature order) and whose timers are the threads of its
implementation that serve no port; a thread connected to a port is that port's callback
(priority, deadline, operation).
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import RosaadlError
from rosaadl.importers import ros_msg
from rosaadl.properties import own_property
from rosaadl.transforms import rosmod_to_aadl as fwd
from rosaadl.transforms.engine import Context

from .convention import COMPONENT, COMPONENT_IMPL, CONVENTION, holder_role, placed, state, unit_kind
from .reading import add, enum_name, integer, new, scheduling_scheme, seconds, set_given, settings, text

__all__ = ["port_class"]

_t = CONVENTION

_PORTS = ("eventDataPort", "dataPort", "eventPort")


def port_class(feature: EObject) -> str | None:
    """The ROSMOD port class of a thread group feature (Publisher, Subscriber, Client, Server)."""
    category = enum_name(feature.category)
    if category in _PORTS and enum_name(feature.direction) in ("in", "out"):
        return "Publisher" if enum_name(feature.direction) == "out" else "Subscriber"
    if category == "subprogramAccess":
        return "Client" if enum_name(feature.access) == "requires" else "Server"
    return None


def _in_software(ctx: Context, classifier: EObject) -> bool:
    return state(ctx).kind.get(id(classifier.eContainer())) == "software"


def _software(ctx: Context, classifier: EObject) -> str | None:
    """The rules' key on classifiers: the category of a classifier of a software package."""
    return placed(ctx, classifier)[1] if _in_software(ctx, classifier) else None


def _port_class(ctx: Context, feature: EObject) -> str | None:
    """:func:`port_class`, read once per feature."""
    cache = state(ctx).cache
    key = ("port", id(feature))
    if key not in cache:
        cache[key] = port_class(feature)
    return cache[key]


# --------------------------------------------------------------------------- packages


@_t.rule("AadlPackage", name="package", where=(unit_kind, "software"))
def _package(ctx: Context, unit: EObject) -> EObject:
    package = new("Package", name=state(ctx).name(unit))
    package.properties.extend(settings(unit))
    return package


@_package.bind
def _package_bind(ctx: Context, unit: EObject, package: EObject) -> None:
    classifiers = list(unit.classifiers)
    add(package, "messages", ctx.resolve_all(classifiers, "message"))
    add(package, "services", ctx.resolve_all(classifiers, "service"))
    add(package, "components", ctx.resolve_all(state(ctx).thread_groups(unit), "component"))


def _package_name(ctx: Context, classifier: EObject) -> str:
    """The ROSMOD name of the package of a classifier (made before it: the walk visits the
    package first)."""
    return ctx.resolve(classifier.eContainer(), "package")[0].name


def _interface_type(ctx: Context, classifier: EObject, class_name: str) -> EObject:
    """A message or service named after a classifier, with its fields parsed from ``Definition``
    (a warning when it does not parse)."""
    st = state(ctx)
    made = new(class_name, name=st.name(classifier), definition=text(classifier, fwd.DEFINITION))
    if made.definition:
        package = _package_name(ctx, classifier)
        try:
            if class_name == "Message":
                spec = ros_msg.parse_msg(made.definition, name=made.name, package=package)
                made.fields.extend(ros_msg.fields_to_model(spec.fields))
            else:
                spec = ros_msg.parse_srv(made.definition, name=made.name, package=package)
                made.requestFields.extend(ros_msg.fields_to_model(spec.request.fields))
                made.responseFields.extend(ros_msg.fields_to_model(spec.response.fields))
        except RosaadlError as exc:
            what = class_name.lower()
            st.warn(f"{what} {made.name}: its definition does not parse ({exc.message})", classifier)
    return made


@_t.rule(
    "ComponentType",
    name="message",
    where=(_software, "data"),
    when=lambda ctx, c: text(c, fwd.MESSAGE_TYPE) is not None,
)
def _message(ctx: Context, classifier: EObject) -> EObject:
    return _interface_type(ctx, classifier, "Message")


@_t.rule(
    "ComponentType",
    name="service",
    where=(_software, "subprogram"),
    when=lambda ctx, c: text(c, fwd.SERVICE_TYPE) is not None,
)
def _service(ctx: Context, classifier: EObject) -> EObject:
    return _interface_type(ctx, classifier, "Service")


@_t.rule(
    "ComponentType",
    name="unmapped_classifier",
    when=lambda ctx, c: _software(ctx, c) not in (None, "data", "subprogram", "threadGroup", "thread"),
)
def _unmapped_classifier(ctx: Context, classifier: EObject) -> None:
    state(ctx).warn(
        f"{enum_name(classifier.category)} {classifier.name} has no ROSMOD counterpart in a software package",
        classifier,
    )


# --------------------------------------------------------------------------- components


@_t.rule("ComponentType", name="component", where=(_software, "threadGroup"))
def _component(ctx: Context, ctype: EObject) -> EObject:
    st = state(ctx)
    comp = new(
        "Component",
        name=st.name(ctype),
        datatype=text(ctype, fwd.DATATYPE),
        schedulingScheme=scheduling_scheme(ctype),
    )
    comp.properties.extend(settings(ctype))
    if st.implementation[id(ctype)] is None:
        st.warn(f"thread group {ctype.name} has no implementation: no timers or callbacks", ctype)
    return comp


@_component.bind
def _component_bind(ctx: Context, ctype: EObject, comp: EObject) -> None:
    add(comp, "ports", ctx.resolve_all(ctype.features, "port"))
    impl = state(ctx).implementation[id(ctype)]
    if impl is not None:
        add(comp, "timers", ctx.resolve_all(impl.subcomponents, "timer"))


def _port_type(ctx: Context, feature: EObject) -> str | None:
    given = text(feature, fwd.MESSAGE_TYPE)
    if given is not None:
        return given
    st = state(ctx)
    target = st.index.find(feature.classifier, feature.eContainer())
    if target is None:
        if feature.classifier:
            st.warn(f"feature {feature.name}: classifier {feature.classifier} does not resolve", feature)
        return None
    for prop in (fwd.MESSAGE_TYPE, fwd.SERVICE_TYPE):
        found = text(target, prop)
        if found is not None:
            return found
    unit = st.index.unit_of.get(id(target))
    return f"{unit.name}/{target.name}" if unit is not None else target.name


@_t.rule(
    "Feature",
    name="port",
    where=(holder_role, COMPONENT),
    when=lambda ctx, f: _port_class(ctx, f) is not None,
)
def _port(ctx: Context, feature: EObject) -> EObject:
    cls = _port_class(ctx, feature)
    port = new(cls, name=state(ctx).name(feature), type=_port_type(ctx, feature))
    if cls == "Publisher":
        latching = own_property(feature, fwd.LATCHING)
        if isinstance(latching, bool):
            port.latching = latching
    return port


@_t.rule(
    "Feature",
    name="not_a_port",
    where=(holder_role, COMPONENT),
    when=lambda ctx, f: _port_class(ctx, f) is None,
)
def _not_a_port(ctx: Context, feature: EObject) -> None:
    owner = feature.eContainer()
    state(ctx).warn(f"feature {feature.name} of {owner.name} is not a ROSMOD port; skipped", feature)


# --------------------------------------------------------------------------- timers and callbacks


def _served(ctx: Context, impl: EObject) -> dict[str, EObject]:
    """Thread name (lower case) → the port feature of the thread group it serves: connected from
    an in port, or to a server's provided access."""
    st = state(ctx)
    key = ("served", id(impl))
    found = st.cache.get(key)
    if found is not None:
        return found
    ports: dict[str, EObject] = {}
    for feature in st.component_of[id(impl)].features:
        if _port_class(ctx, feature) is not None:
            ports[feature.name.lower()] = feature
    served: dict[str, EObject] = {}
    for conn in impl.connections:
        source, destination = conn.source or "", conn.destination or ""
        kind = enum_name(conn.kind)
        if kind == "portConnection" and "." not in source and "." in destination:
            port = ports.get(source.lower())
            if port is not None:
                served[destination.partition(".")[0].lower()] = port
        elif kind == "accessConnection" and "." in source and "." not in destination:
            port = ports.get(destination.lower())
            if port is not None and _port_class(ctx, port) == "Server":
                served[source.partition(".")[0].lower()] = port
    st.cache[key] = served
    return served


def _serves(ctx: Context, sub: EObject) -> EObject | None:
    """The port feature a thread of a component's implementation serves (None: a timer), read
    once per thread."""
    cache = state(ctx).cache
    key = ("serves", id(sub))
    if key not in cache:
        cache[key] = _served(ctx, sub.eContainer()).get(sub.name.lower())
    return cache[key]


@_t.rule(
    "Subcomponent",
    name="timer",
    where=(placed, (COMPONENT_IMPL, "thread")),
    when=lambda ctx, s: _serves(ctx, s) is None,
)
def _timer(ctx: Context, sub: EObject) -> EObject:
    return new(
        "Timer",
        name=state(ctx).name(sub),
        period=seconds(sub, fwd.PERIOD, fwd.PERIOD_SECONDS),
        priority=integer(sub, fwd.PRIORITY),
        deadline=seconds(sub, fwd.DEADLINE, fwd.DEADLINE_SECONDS),
        operation=text(sub, fwd.OPERATION),
    )


@_t.rule(
    "Subcomponent",
    name="callback",
    where=(placed, (COMPONENT_IMPL, "thread")),
    when=lambda ctx, s: _serves(ctx, s) is not None,
)
def _callback(ctx: Context, sub: EObject) -> list[EObject]:
    """The port the thread serves (made before it: the walk visits features first) gets the
    thread's priority, deadline and operation."""
    ports = ctx.resolve(_serves(ctx, sub), "port")
    for port in ports:
        set_given(
            port,
            priority=integer(sub, fwd.PRIORITY),
            deadline=seconds(sub, fwd.DEADLINE, fwd.DEADLINE_SECONDS),
            operation=text(sub, fwd.OPERATION),
        )
    return ports

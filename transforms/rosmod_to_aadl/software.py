"""The ROSMOD → AADL rules of the software: packages, messages, services, components and their
timers and ports.

One AADL package per ROSMOD package (``Unit_Kind => Software``). A message is a ``data`` type
with ``ROS_Properties::Message_Type``, its ``.msg`` text and ``Data_Size`` when every message of
the type has the same size; a service is a ``subprogram`` with an ``in parameter`` request and an
``out parameter`` response. A component is a ``thread group`` type (its ports as features:
publisher → ``out event data port``, subscriber → ``in event data port``, client → ``requires
subprogram access``, server → ``provides subprogram access``) and implementation holding one
``thread`` per timer (periodic) and per subscriber or server callback (sporadic), all connected
to the component's callback queue (a ``data`` subcomponent of ``ros::callback_queue``: one
executor per component instance). The package holds one generated callback thread type per kind
it needs, extending the library's.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import TransformationError
from rosaadl.importers import ros_msg
from rosaadl.transforms.engine import Context, source_location
from rosaadl.transforms.rosmod_to_aadl.plan import split_ros_type
from rosaadl.transforms.rosmod_to_aadl.rules import (
    TRANSFORMATION,
    State,
    name_if_changed,
    set_time,
    state,
    unit_header,
)
from rosaadl.transforms.rosmod_to_aadl.values import given
from rosaadl.transforms.rosmod_to_aadl.vocabulary import (
    CALLBACK_THREADS,
    DATA_SIZE,
    DATATYPE,
    DEADLINE,
    DEADLINE_SECONDS,
    DEFINITION,
    LATCHING,
    MESSAGE_TYPE,
    OPERATION,
    PERIOD,
    PERIOD_SECONDS,
    PRIORITY,
    QUEUE_ACCESS,
    QUEUE_CLASSIFIER,
    SCHEDULING_SCHEME,
    SERVER_ACCESS,
    SERVICE_TYPE,
    SUBSCRIBER_PORT,
)

__all__: list[str] = []  # its rules are declared on TRANSFORMATION


@TRANSFORMATION.rule("rosmod.Package", name="package")
def _package(ctx: Context, src: EObject) -> EObject:
    st = state(ctx)
    pkg = unit_header(st, src, "Software")
    st.factory.settings(pkg, src.properties)
    return pkg


@_package.bind
def _package_bind(ctx: Context, src: EObject, pkg: EObject) -> None:
    st = state(ctx)
    f = st.factory
    classifiers: list[EObject] = []
    for msg in src.messages:
        classifiers.extend(ctx.resolve(msg))
    for srv in src.services:
        classifiers.extend(ctx.resolve(srv))
    for kind in ("timer", "subscriber", "server"):
        name = st.plan.callback_types.get((id(src), kind))
        if name is None:
            continue
        base = CALLBACK_THREADS[kind][1]
        thread = f.ctype("thread", name, extended=base)
        queue = f.feature(QUEUE_ACCESS, "data access", access="requires", classifier=QUEUE_CLASSIFIER)
        f.add(thread, "features", queue)
        classifiers.append(thread)
        classifiers.append(f.cimpl("thread", name, extended=f"{base}.impl"))
    for comp in src.components:
        classifiers.extend(t for t in ctx.resolve(comp) if not model.is_a(t, "Subcomponent"))
    f.add(pkg, "classifiers", *classifiers)


def _sizes(st: State) -> dict[str, list[ros_msg.FieldSpec]]:
    if not st.sizes and st.project.software is not None:
        for package in st.project.software.packages:
            for msg in package.messages:
                st.sizes.setdefault(
                    f"{package.name}/{msg.name}", [ros_msg.field_from_model(x) for x in msg.fields]
                )
    return st.sizes


def _data_size(st: State, fields: list[ros_msg.FieldSpec], own: str | None) -> int | None:
    spec = ros_msg.MessageSpec(
        name=own.rpartition("/")[2] if own else None,
        package=own.rpartition("/")[0] if own else None,
        fields=tuple(fields),
    )
    return ros_msg.data_size(spec, _sizes(st).get)


@TRANSFORMATION.rule("rosmod.Message", name="message")
def _message(ctx: Context, src: EObject) -> EObject:
    st = state(ctx)
    f = st.factory
    package = src.eContainer()
    name = st.plan.names[id(src)]
    data = f.ctype("data", name)
    name_if_changed(f, data, name, src.name)
    full = f"{package.name}/{src.name}"
    size = _data_size(st, [ros_msg.field_from_model(x) for x in src.fields], full)
    if size is not None:
        f.pa(data, DATA_SIZE, f.integer(size, "Bytes"))
    f.pa(data, MESSAGE_TYPE, f.string(full))
    f.text(data, DEFINITION, src.definition)
    return data


@TRANSFORMATION.rule("rosmod.Service", name="service")
def _service(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    package = src.eContainer()
    name = st.plan.names[id(src)]
    pkg_unit = st.plan.units[id(package)]
    subprogram = f.ctype("subprogram", name)
    out: list[EObject] = []
    for role, direction, fields in (
        ("request", "in", src.requestFields),
        ("response", "out", src.responseFields),
    ):
        data_name = st.plan.extra[(id(src), role)]
        data = f.ctype("data", data_name)
        size = _data_size(st, [ros_msg.field_from_model(x) for x in fields], None)
        if size is not None:
            f.pa(data, DATA_SIZE, f.integer(size, "Bytes"))
        out.append(data)
        f.add(
            subprogram,
            "features",
            f.feature(role, "parameter", direction=direction, classifier=f"{pkg_unit}::{data_name}"),
        )
    name_if_changed(f, subprogram, name, src.name)
    f.pa(subprogram, SERVICE_TYPE, f.string(f"{package.name}/{src.name}"))
    f.text(subprogram, DEFINITION, src.definition)
    return (*out, subprogram)


@TRANSFORMATION.rule("rosmod.Component", name="component")
def _component(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    f = st.factory
    name = st.plan.names[id(src)]
    group = f.ctype("thread group", name)
    name_if_changed(f, group, name, src.name)
    f.text(group, DATATYPE, src.datatype)
    if src.eIsSet("schedulingScheme"):
        f.pa(group, SCHEDULING_SCHEME, f.named(src.schedulingScheme.name))
    f.settings(group, src.properties)
    impl = f.cimpl("thread group", name)
    queue_name = st.plan.extra.get((id(src), "queue"))
    if queue_name is None:
        return group, impl
    queue = f.sub(queue_name, "data", QUEUE_CLASSIFIER)
    return group, impl, queue


@_component.bind
def _component_bind(ctx: Context, src: EObject, group: EObject, impl: EObject, *queue: EObject) -> None:
    st = state(ctx)
    f = st.factory
    features: list[EObject] = []
    threads: list[EObject] = list(queue)
    connections: list[EObject] = []
    for port in src.ports:
        features.extend(t for t in ctx.resolve(port) if model.is_a(t, "Feature"))
    for element in (
        *src.timers,
        *(p for p in src.ports if model.is_a(p, "rosmod.Subscriber", "rosmod.Server")),
    ):
        for target in ctx.resolve(element):
            if model.is_a(target, "Subcomponent"):
                threads.append(target)
            elif model.is_a(target, "Connection"):
                connections.append(target)
    f.add(group, "features", *features)
    f.add(impl, "subcomponents", *threads)
    f.add(impl, "connections", *connections)


def _callback_thread(ctx: Context, src: EObject, kind: str, thread_name: str) -> tuple[EObject, EObject]:
    """The thread subcomponent of a timer or callback, and its connection to the callback queue."""
    st = state(ctx)
    f = st.factory
    comp = src.eContainer()
    package = comp.eContainer()
    unit = st.plan.units[id(package)]
    type_name = st.plan.callback_types[(id(package), kind)]
    thread = f.sub(thread_name, "thread", f"{unit}::{type_name}.impl")
    if kind == "timer":
        set_time(ctx, f, thread, PERIOD, PERIOD_SECONDS, given(src, "period"), src)
    set_time(ctx, f, thread, DEADLINE, DEADLINE_SECONDS, given(src, "deadline"), src)
    if given(src, "priority") is not None:
        f.pa(thread, PRIORITY, f.integer(src.priority))
    f.text(thread, OPERATION, src.operation)
    queue = st.plan.extra[(id(comp), "queue")]
    link = f.conn(
        st.plan.extra[(id(src), "queue_conn")], "access", queue, f"{thread_name}.{QUEUE_ACCESS}", "data"
    )
    return thread, link


@TRANSFORMATION.rule("rosmod.Timer", name="timer")
def _timer(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    name = st.plan.names[id(src)]
    thread, queue = _callback_thread(ctx, src, "timer", name)
    name_if_changed(st.factory, thread, name, src.name)
    return thread, queue


def _port_classifier(ctx: Context, src: EObject, kind: str) -> str | None:
    """The AADL classifier of a port's ROS type; a located error for an unknown project type."""
    st = state(ctx)
    parts = split_ros_type(src.type)
    if parts is None:
        if src.type:
            ctx.warn(f"{src.eClass.name.lower()} {src.name!r}: type {src.type!r} is not 'package/Type'", src)
        return None
    pkg_name, type_name = parts
    own, other, what, other_what = (
        (st.plan.messages, st.plan.services, "message", "service")
        if kind == "message"
        else (st.plan.services, st.plan.messages, "service", "message")
    )
    found = own.get(src.type)
    if found is not None:
        return f"{found[0]}::{found[1]}"
    iface = st.plan.interfaces.get(pkg_name)
    if iface is not None:
        table = iface.messages if kind == "message" else iface.services
        if src.type in table:
            return f"{iface.unit}::{table[src.type]}"
    if src.type in other:
        raise TransformationError(
            f"{src.eClass.name.lower()} {src.name!r} needs a {what} type, but {src.type!r} is a {other_what}",
            source_location(src),
        )
    raise TransformationError(
        f"unknown {what} type {src.type!r} of {src.eClass.name.lower()} {src.name!r}: package "
        f"{pkg_name!r} defines no {what} {type_name!r}",
        source_location(src),
    )


def _port_feature(ctx: Context, src: EObject) -> EObject:
    st = state(ctx)
    f = st.factory
    message = model.is_a(src, "rosmod.Publisher", "rosmod.Subscriber")
    classifier = _port_classifier(ctx, src, "message" if message else "service")
    name = st.plan.names[id(src)]
    if message:
        direction = "out" if model.is_a(src, "rosmod.Publisher") else "in"
        feature = f.feature(name, "event data port", direction=direction, classifier=classifier)
    else:
        access = "requires" if model.is_a(src, "rosmod.Client") else "provides"
        feature = f.feature(name, "subprogram access", access=access, classifier=classifier)
    name_if_changed(f, feature, name, src.name)
    if src.type and classifier is None:
        f.pa(feature, MESSAGE_TYPE, f.string(src.type))
    if model.is_a(src, "rosmod.Publisher") and given(src, "latching") is not None:
        f.pa(feature, LATCHING, f.boolean(src.latching))
    return feature


@TRANSFORMATION.rule("rosmod.Publisher", name="publisher")
def _publisher(ctx: Context, src: EObject) -> EObject:
    return _port_feature(ctx, src)


@TRANSFORMATION.rule("rosmod.Client", name="client")
def _client(ctx: Context, src: EObject) -> EObject:
    return _port_feature(ctx, src)


@TRANSFORMATION.rule("rosmod.Subscriber", name="subscriber")
def _subscriber(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    feature = _port_feature(ctx, src)
    thread_name = st.plan.extra[(id(src), "thread")]
    thread, queue = _callback_thread(ctx, src, "subscriber", thread_name)
    call = st.factory.conn(
        st.plan.extra[(id(src), "callback_conn")], "port", feature.name, f"{thread_name}.{SUBSCRIBER_PORT}"
    )
    return feature, thread, call, queue


@TRANSFORMATION.rule("rosmod.Server", name="server")
def _server(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = state(ctx)
    feature = _port_feature(ctx, src)
    thread_name = st.plan.extra[(id(src), "thread")]
    thread, queue = _callback_thread(ctx, src, "server", thread_name)
    call = st.factory.conn(
        st.plan.extra[(id(src), "callback_conn")],
        "access",
        f"{thread_name}.{SERVER_ACCESS}",
        feature.name,
        "subprogram",
    )
    return feature, thread, call, queue

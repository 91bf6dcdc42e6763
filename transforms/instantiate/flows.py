"""Flows: flow specification instances and end-to-end flow instances.

Each component gets the flow specifications of its classifier (source, sink or path, with their
feature instance ends). An end-to-end flow of an implementation becomes the list of instance
objects it goes through: subcomponents, the flow specifications of the subcomponents (through
their flow implementations, as deep as they go), for each run of declared connections the
semantic connection instance that goes through them, and for a data or subprogram access feature
the component it gives access to (with the connection instances to it and back from it).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl.resolution import split_path

from .declared import declared_connections
from .mirrors import ComponentMirror, ConnectionRecord, FeatureMirror, enum_name

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["end_to_end_flows", "flow_specifications"]


def flow_specifications(st: Instantiator, ci: ComponentMirror) -> None:
    """The flow specification instances of a component (after its features)."""
    factory = st.factory
    specs = []
    for spec in st.resolver.flow_specifications(ci.node.classifier):
        kind = spec.kind
        fsi = factory.new("FlowSpecificationInstance", name=spec.name, kind=kind)
        src = _flow_end(ci, spec.inEnd)
        dst = _flow_end(ci, spec.outEnd)
        if enum_name(kind) in ("path", "sink") and src is not None:
            factory.set(fsi, "source", src.obj)
        if enum_name(kind) in ("path", "source") and dst is not None:
            factory.set(fsi, "destination", dst.obj)
        specs.append(fsi)
        ci.flow_specs[(spec.name or "").lower()] = fsi
    factory.extend(ci.obj, "flowSpecifications", specs)


def _flow_end(ci: ComponentMirror, text: str | None) -> FeatureMirror | None:
    segments = split_path(text or "")
    if not segments:
        return None
    fi = ci.feature(segments[0].key)
    for segment in segments[1:]:
        if fi is None:
            return None
        fi = fi.child(segment.key)
    return fi


def end_to_end_flows(st: Instantiator) -> None:
    """The end-to-end flow instances of every component (after the connection instances)."""
    factory = st.factory
    for ci in st.components:
        impl = ci.node.impl
        if impl is None:
            continue
        for flow in st.resolver.end_to_end_flows(impl):
            elements = _flow_elements(st, ci, flow, set())
            instance = factory.new("EndToEndFlowInstance", name=flow.name, flow=flow.name)
            unique = []
            previous = None
            for element in elements:
                if element is not previous and not any(element is e for e in unique):
                    unique.append(element)
                previous = element
            factory.extend(instance, "flowElements", unique)
            factory.extend(ci.obj, "endToEndFlows", [instance])


def _flow_elements(st: Instantiator, ci: ComponentMirror, flow: EObject, seen: set[int]) -> list[EObject]:
    """The instance objects end-to-end flow ``flow`` of ``ci`` goes through."""
    if id(flow) in seen:
        return []
    seen = seen | {id(flow)}
    texts = list(st.resolver.effective_attribute(flow, "elements") or [])
    return _resolve_flow_connections(st, _pieces(st, ci, texts, seen, end_to_end=True))


def _flow_spec_elements(st: Instantiator, ci: ComponentMirror, spec_name: str, seen: set[int]) -> list[Any]:
    """What a flow through subcomponent ``ci`` by its flow specification ``spec_name`` goes
    through: the elements of its flow implementation, else the flow specification instance."""
    impl = ci.node.impl
    flow_impl = None
    if impl is not None:
        flow_impl = next(
            (f for f in st.resolver.flow_implementations(impl) if (f.name or "").lower() == spec_name),
            None,
        )
    if flow_impl is None:
        spec = ci.flow_specs.get(spec_name)
        return [spec if spec is not None else ci.obj]
    return _pieces(st, ci, flow_impl.elements, seen, end_to_end=False)


def _pieces(
    st: Instantiator, ci: ComponentMirror, texts: list[str], seen: set[int], *, end_to_end: bool
) -> list:
    """The elements named by ``texts`` in ``ci`` (an end-to-end flow's, else a flow
    implementation's): ``sub.spec`` through a subcomponent, a subcomponent's instance object,
    ``("conn", declaration, ci)`` for a declared connection (resolved later),
    ``("access", feature)`` for a data or subprogram access feature of ``ci`` the flow goes
    through (also resolved later) and, in an end-to-end flow, the elements of another
    end-to-end flow it names."""
    pieces: list[Any] = []
    last = len(texts) - 1
    for position, text in enumerate(texts):
        segments = [s.key for s in split_path(text)]
        if not segments:
            continue
        if len(segments) >= 2:
            child = ci.child(segments[0])
            if child is not None:
                pieces.extend(_flow_spec_elements(st, child, segments[1], seen))
                continue
            if not end_to_end or ci.feature(segments[0]) is not None:
                continue
        name = segments[0]
        conn = next((c for c in declared_connections(st, ci) if c.name.lower() == name), None)
        if conn is not None:
            pieces.append(("conn", conn.decl, ci))
            continue
        child = ci.child(name)
        if child is not None:
            pieces.append(child.obj)
            continue
        feature = ci.feature(name)
        interior = end_to_end or 0 < position < last  # a flow implementation's ends are its own
        if interior and feature is not None and feature.category in ("dataAccess", "subprogramAccess"):
            pieces.append(("access", feature))
            continue
        if end_to_end:
            other = next(
                (f for f in st.resolver.end_to_end_flows(ci.node.impl) if (f.name or "").lower() == name),
                None,
            )
            if other is not None:
                pieces.extend(_flow_elements(st, ci, other, seen))
    return pieces


def _resolve_flow_connections(st: Instantiator, pieces: list[Any]) -> list[Any]:
    """Replace each run of declared connections of a flow by the semantic connection instance
    that goes through all of them (the first one that does, else the one that goes through
    the most of them).

    A data or subprogram access feature between two runs (OSATE's ``processAccess`` of
    ``CreateEndToEndFlowsSwitch``) stands for the component it gives access to: the run before
    it becomes the connection instance through that run that ends at a data or subprogram
    component, followed by that component's instance; the run after it starts with the
    declarations that connection instance crosses after the run's last one (in reverse: the
    way back to the accessor goes through them again) before the flow's next connections.
    """
    result: list[Any] = []
    run: list[tuple[int, int]] = []
    carried: list[tuple[int, int]] = []  # hops an access hands on, if a connection follows

    for piece in pieces:
        if isinstance(piece, tuple) and piece[0] == "conn":
            _, decl, context = piece
            run.extend(carried)
            carried = []
            run.append((id(decl), id(context)))
            continue
        carried = []
        if isinstance(piece, tuple):  # ("access", feature): needs a run that reaches it
            if not run:
                continue
            record = _best_record(st, run, _reaches_shared_component)
            run_ends = set(run)
            run.clear()
            if record is None:
                continue
            result.extend([record.obj, record.dst.obj])
            hops = _hops(record)
            last = max((i for i, hop in enumerate(hops) if hop in run_ends), default=len(hops) - 1)
            carried = list(reversed(hops[last + 1 :]))
            continue
        if run:
            record = _best_record(st, run, None)
            if record is not None:
                result.append(record.obj)
            run.clear()
        result.append(piece)
    if run:
        record = _best_record(st, run, None)
        if record is not None:
            result.append(record.obj)
    return result


def _hops(record: ConnectionRecord) -> list[tuple[int, int]]:
    """The (declaration, context) identities of the hops of a connection instance."""
    return list(zip((id(d) for d in record.decls), (id(c) for c in record.contexts), strict=False))


def _reaches_shared_component(record: ConnectionRecord) -> bool:
    """Whether a connection instance ends at a data or subprogram component (the component an
    access feature stands for in an end-to-end flow)."""
    return isinstance(record.dst, ComponentMirror) and record.dst.category in ("data", "subprogram")


def _best_record(
    st: Instantiator, wanted: list[tuple[int, int]], accept: Callable[[ConnectionRecord], bool] | None
) -> ConnectionRecord | None:
    """The connection instance (among those ``accept`` takes) through all the hops ``wanted``,
    the first one that is, else the first one through the most of them."""
    best = None
    best_score = 0
    for container in st.components:
        for record in container.connections:
            if accept is not None and not accept(record):
                continue
            through = set(_hops(record))
            score = sum(1 for item in wanted if item in through)
            if score > best_score:
                best, best_score = record, score
                if score == len(wanted):
                    return best
    return best

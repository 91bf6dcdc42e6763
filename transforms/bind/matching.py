"""The ROSMOD side of a binding: the component instances of a deployment, each matched with its
entry of the bindings file, its library node, the PDM for its core, and its ports.

A ROSMOD node's component instance is bound by the entry ``<node>/<instance>`` (or ``<node>``
when the node holds one instance); its library node has one platform-dependent implementation
(PDM) per core type, and the core chooses it (:func:`choose_pdm`); its publishers and
subscribers go to the library ports the entry maps them to, else to the one library port of the
same direction whose data type has the message's name (:func:`map_ports`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.transforms.bind.bindings_file import DeploymentSpec, NodeSpec, fail
from rosaadl.transforms.bind.library import Catalogue, Core, LibraryNode, classifier_named, literal

__all__ = ["InstanceBinding", "choose_pdm", "instance_bindings", "map_ports"]


@dataclass
class InstanceBinding:
    """A ROSMOD component instance in a deployment, with its binding (filled in step by step)."""

    node: EObject
    inst: EObject
    key: str
    spec: NodeSpec
    process: str = ""
    library: LibraryNode | None = None
    pdm: EObject | None = None
    core: Core | None = None
    port_map: dict[str, str | None] = field(default_factory=dict)  # ROSMOD port → library port


def _message_name(type_name: str | None) -> str:
    return (type_name or "").rpartition("/")[2].lower()


def _classifier_type_name(classifier: str | None) -> str:
    return (classifier or "").rpartition("::")[2].partition(".")[0].lower()


def instance_bindings(deployment: EObject, spec: DeploymentSpec) -> list[InstanceBinding]:
    """The component instances of a deployment, each with its entry of the bindings file."""
    used: set[str] = set()
    out = []
    for node in deployment.nodes:
        several = len(node.componentInstances) > 1
        for inst in node.componentInstances:
            keys = [f"{node.name}/{inst.name}"] + ([] if several else [node.name])
            key = next((k for k in keys if k in spec.nodes), None)
            if key is None:
                wanted = " or ".join(repr(k) for k in reversed(keys))
                raise fail(
                    spec.where["nodes"],
                    f"no binding for ROSMOD node {node.name!r} (component instance {inst.name!r} of "
                    f"{getattr(inst.component, 'name', '?')!r}); add a member {wanted}",
                )
            if inst.component is None:
                raise fail(spec.nodes[key].where[""], f"component instance {inst.name!r} has no component")
            used.add(key)
            out.append(InstanceBinding(node, inst, key, spec.nodes[key]))
    for key, entry in spec.nodes.items():
        if key not in used:
            known = ", ".join(sorted({n.name for n in deployment.nodes})) or "none"
            raise fail(
                entry.where[""],
                f"deployment {deployment.name!r} has no ROSMOD node {key!r} (it has: {known})",
            )
    return out


def choose_pdm(item: InstanceBinding, catalogue: Catalogue, cores: dict[str, Core]) -> None:
    """The library node, its PDM and the core of a component instance, as its entry says."""
    spec = item.spec
    library = catalogue.node(spec.library)
    if library is None:
        raise fail(
            spec.where["library"],
            f"{spec.library!r} is not a process type or implementation of the library (expected a node such "
            "as 'nd_usb_cam::usb_cam_nd')",
        )
    core = cores.get(spec.core.lower())
    if core is None:
        shown = ", ".join(c.path for c in list(cores.values())[:12])
        raise fail(spec.where["core"], f"the robot has no core {spec.core!r} (its cores: {shown})")
    available = (
        ", ".join(f"{impl.name.partition('.')[2]} ({ref})" for impl, ref in library.pdms)
        or "no platform-dependent implementation"
    )
    named = classifier_named(catalogue.model, spec.library)
    if named is not None and _model.is_a(named, "ComponentImplementation"):
        reference = catalogue.reference(named)
        if reference is not None and reference not in core.types:
            raise fail(
                spec.where["core"],
                f"{_model.qualified_name(named)} was measured on {reference}, but core {core.path} is a "
                f"{core.kind}; bind it to such a core or name the node type {library.qualified}",
            )
        pdm = named
    else:
        matches = [impl for impl, ref in library.pdms if ref in core.types]
        if not matches:
            raise fail(
                spec.where["core"],
                f"{library.qualified} has no platform-dependent implementation for core {core.path} "
                f"({core.kind}); it has: {available}",
            )
        if len(matches) > 1:
            names = ", ".join(_model.qualified_name(m) for m in matches)
            raise fail(
                spec.where["library"],
                f"{library.qualified} has several implementations for {core.kind} ({names}); name one",
            )
        pdm = matches[0]
    item.library, item.pdm, item.core = library, pdm, core


def map_ports(item: InstanceBinding) -> None:
    """ROSMOD publishers/subscribers → library ports: as the bindings file says, else the one
    port of the same direction whose data type has the message's name."""
    assert item.library is not None
    spec = item.spec
    component = item.inst.component
    ports = {p.name: p for p in component.ports if _model.is_a(p, "rosmod.Publisher", "rosmod.Subscriber")}
    for name in spec.ports:
        if name not in ports:
            known = ", ".join(sorted(ports)) or "none"
            raise fail(
                spec.where[f"ports.{name}"],
                f"component {component.name!r} has no publisher or subscriber {name!r} (it has: {known})",
            )
    for name, port in ports.items():
        direction = "out" if _model.is_a(port, "rosmod.Publisher") else "in"
        if name in spec.ports:
            target = spec.ports[name]
            if target is None:
                item.port_map[name] = None
                continue
            feature = item.library.ports.get(target.lower())
            if feature is None or literal(feature.direction) != direction:
                candidates = [
                    f.name for f in item.library.ports.values() if literal(f.direction) == direction
                ]
                raise fail(
                    spec.where[f"ports.{name}"],
                    f"{item.library.qualified} has no {direction} port {target!r} (its {direction} ports: "
                    f"{', '.join(candidates) or 'none'})",
                )
            item.port_map[name] = feature.name
            continue
        message = _message_name(port.type)
        if not message:  # an untyped port carries no topic ROSMOD could match
            item.port_map[name] = None
            continue
        candidates = [
            f
            for f in item.library.ports.values()
            if literal(f.direction) == direction and _classifier_type_name(f.classifier) == message
        ]
        if len(candidates) != 1:
            listed = ", ".join(
                f"{f.name}: {f.classifier or 'no type'}"
                for f in item.library.ports.values()
                if literal(f.direction) == direction
            )
            what = "no" if not candidates else "several"
            raise fail(
                spec.where[""],
                f"ROSMOD {port.eClass.name.lower()} {name!r} <{port.type}> of {component.name!r}: "
                f"{item.library.qualified} has {what} {direction} port of a data type named "
                f"{_message_name(port.type) or '?'!r} ({direction} ports: {listed or 'none'}); "
                'map it in "ports"',
            )
        item.port_map[name] = candidates[0].name

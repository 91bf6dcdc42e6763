"""The ``Deployments`` and ``Experiments`` of a WebGME ROSMOD project → ``rosmod.Deployment`` objects.

A deployment holds containers of nodes; containers are kept as ``Container:<name>`` deployment
properties and as the ``container`` property of their nodes. A deployed component is a
``ComponentInstance`` of the software component it derives from (its ``componentRef`` is
``<package>/<component>``), with its effective scheduling scheme, its ``Logging*`` attributes
as ``logging`` entries, and the values it overrides (on itself or on the timers and ports it
inherits) as properties ``<attribute>`` / ``<child>.<attribute>``. Experiments are kept as
``Experiment:<name>`` deployment properties; when every experiment of a deployment uses the
same system, that system becomes the deployment's ``system``. WebGME nodes are not bound to
hosts (experiments map them at run time), so ``Node.host`` is unset.
"""

from __future__ import annotations

import json
import os

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import NameResolutionError
from rosaadl.importers.rosmod_webgme.mapping import SKIPPED_KINDS, Mapper, text
from rosaadl.importers.rosmod_webgme.tree import Node

__all__ = ["deployment", "resolve"]

_LOGGING_KEYS = ("EnableLogging", "LoggingUnit")


def _is_logging_key(key: str) -> bool:
    return key.startswith("Logging") or key in _LOGGING_KEYS


def deployment(m: Mapper, node: Node) -> EObject:
    """A ``Deployment``: the nodes of its containers."""
    deployment = model.new("rosmod.Deployment", name=node.name, sourceFile=os.path.basename(m.filename))
    m.by_path[node.path] = deployment
    for container in m.children(node):
        if container.meta_type != "Container":
            m.unknown(node, container, deployment.properties)
            continue
        deployment.properties.append(m.prop(f"Container:{container.name}", m.opaque_attrs(container)))
        for child in m.children(container):
            if child.meta_type == "Node":
                deployment.nodes.append(_node(m, child, container))
            elif child.meta_type not in SKIPPED_KINDS:
                deployment.properties.append(m.prop(f"{child.meta_type}:{child.name}", m.opaque(child)))
    m.warn_duplicates(node, deployment.nodes, "node", f"deployment {node.name!r}")
    return deployment


def _node(m: Mapper, node: Node, container: Node) -> EObject:
    item = model.new(
        "rosmod.Node",
        name=node.name,
        priority=m.integer(node, "Priority"),
        arguments=text(node.attribute("Arguments")) or None,
    )
    item.properties.append(m.prop("container", container.name))
    for key, value in node.project_attributes().items():
        if key not in ("Priority", "Arguments"):
            item.properties.append(m.prop(key, value))
    for child in m.children(node):
        if child.meta_type == "Component":
            item.componentInstances.append(_instance(m, child))
        elif child.meta_type not in SKIPPED_KINDS:
            item.properties.append(m.prop(f"{child.meta_type}:{child.name}", m.opaque(child)))
    return item


def _software_component(node: Node) -> Node | None:
    """The component of a software package that a deployed component derives from."""
    for layer in list(node.bases())[1:]:
        if layer.is_meta():
            return None
        if (
            layer.meta_type == "Component"
            and layer.parent is not None
            and layer.parent.meta_type == "Package"
        ):
            return layer
    return None


def _instance(m: Mapper, node: Node) -> EObject:
    inst = model.new("rosmod.ComponentInstance", name=node.name)
    definition = _software_component(node)
    if definition is None:
        m.error(
            node,
            f"component {node.name!r} is not an instance of a software component",
            NameResolutionError,
        )
    else:
        inst.componentRef = f"{definition.parent.name}/{definition.name}"
        m.pending_components.append((inst, definition, node))
    m.scheme(node, inst, node.attribute("SchedulingScheme"))
    for key in node.attribute_names():
        if _is_logging_key(key):
            inst.logging.append(m.prop(key, node.attribute(key)))
    base = node.base
    for key in node.own_attribute_names():
        if key in ("name", "SchedulingScheme") or _is_logging_key(key):
            continue
        value = node.data["atr"][key]
        if base is None or base.attribute(key) != value:
            inst.properties.append(m.prop(key, value))
    _overrides(m, node, inst, "")
    return inst


def _overrides(m: Mapper, node: Node, inst: EObject, prefix: str) -> None:
    """Values an instance sets on the timers/ports it inherits (and children it adds)."""
    base = node.base
    base_relids = set(base.relids()) if base is not None else set()
    for child in m.children(node):
        label = f"{prefix}{child.name}"
        if child.relid not in base_relids:
            m.warn(
                child,
                f"{child.meta_type} {child.name!r} exists only in this instance; kept as a property",
            )
            inst.properties.append(m.prop(f"{child.meta_type}:{label}", m.opaque(child)))
            continue
        child_base = child.base
        for key in child.own_attribute_names():
            value = child.data["atr"][key]
            if child_base is None or child_base.attribute(key) != value:
                inst.properties.append(m.prop(f"{label}.{key}", value))
        _overrides(m, child, inst, f"{label}.")


def resolve(m: Mapper, project: EObject) -> None:
    """Once the whole project is mapped: each instance's component, and the experiments."""
    for inst, definition, node in m.pending_components:
        comp = m.by_path.get(definition.path)
        if comp is None:
            m.error(
                node,
                f"component {inst.componentRef!r} is not part of this project's software",
                NameResolutionError,
            )
        else:
            inst.component = comp
    m.pending_components = []
    systems_of: dict[str, set[str]] = {}
    for _folder, exp in m.experiments:
        dep_node = exp.pointer("Deployment")
        sys_node = exp.pointer("System")
        deployment = m.by_path.get(dep_node.path) if dep_node is not None else None
        system = m.by_path.get(sys_node.path) if sys_node is not None else None
        value = {"System": system.name if system is not None else None}
        value.update({k: text(v) for k, v in exp.project_attributes().items()})
        if deployment is None:
            project.properties.append(m.prop(f"Experiment:{exp.name}", json.dumps(value, sort_keys=True)))
            continue
        deployment.properties.append(m.prop(f"Experiment:{exp.name}", json.dumps(value, sort_keys=True)))
        systems_of.setdefault(deployment.name + "\x00" + dep_node.path, set()).add(
            sys_node.path if system is not None else ""
        )
    for key, paths in systems_of.items():
        dep_path = key.split("\x00", 1)[1]
        deployment = m.by_path[dep_path]
        if len(paths) == 1 and "" not in paths:
            system = m.by_path[next(iter(paths))]
            deployment.system = system
            deployment.systemName = system.name
    m.experiments = []

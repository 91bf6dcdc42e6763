"""The instance walk of an export: which roots a file holds, and the EMF path of every object.

A file holds the system instance and, when feature instances refer to them (``type``), the
further ``ComponentInstance`` roots of its model (:func:`extra_roots`). :func:`assign_paths`
gives every instance object its EMF path (``/``, ``//@componentInstance.1/@featureInstance.0``;
``/0``, ``/0/@…`` when the document holds several roots), counted per containment list in
the order EMF writes the lists (:func:`containments`), and checks on the way that components,
features, modes and flows are named by AADL identifiers.
"""

from __future__ import annotations

from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import ExportError, Location
from rosaadl.importers.aaxl2.xmi import TAG_FEATURE
from rosaadl.model import instance_path, is_a, walk

from .emf_text import items_of, value_of
from .state import Writer
from .vocabulary import FILE_STEM_RE, ID_RE

__all__ = ["extra_roots", "assign_paths", "containments"]

# the instance objects that must be named by an AADL identifier
CHECKED_CLASSES = (
    "ComponentInstance",
    "FeatureInstance",
    "ModeInstance",
    "FlowSpecificationInstance",
    "EndToEndFlowInstance",
)
# (element tag, feature) of a component instance's containment lists, in EMF's feature order
_COMPONENT_LISTS = tuple(
    (tag, TAG_FEATURE[tag])
    for tag in (
        "featureInstance",
        "componentInstance",
        "modeInstance",
        "modeTransitionInstance",
        "flowSpecification",
        "endToEndFlow",
        "connectionInstance",
    )
)


def extra_roots(w: Writer) -> list[EObject]:
    """Further ComponentInstance roots of the model that feature instances refer to (``type``)."""
    if w.model is None or not len(w.model.componentInstances):
        return []
    available = {id(r) for r in w.model.componentInstances}
    wanted: dict[int, EObject] = {}
    pending = [w.system]
    while pending:
        for obj in walk(pending.pop()):
            target = obj.type if is_a(obj, "FeatureInstance") else None
            if target is None:
                continue
            while target.eContainer() is not None and is_a(target.eContainer(), "InstanceObject"):
                target = target.eContainer()
            if id(target) in available and id(target) not in wanted:
                wanted[id(target)] = target
                pending.append(target)
    return [r for r in w.model.componentInstances if id(r) in wanted]


def assign_paths(w: Writer) -> None:
    """EMF paths of every instance object: ``/`` and ``//@a.1/@b.0`` (``/0``, ``/0/@a.1`` with
    several roots); component, feature, mode and flow instances must be named by AADL
    identifiers (a located :class:`ExportError` otherwise)."""
    system_name = value_of(w.system, "name") or ""
    if not FILE_STEM_RE.match(system_name):
        raise ExportError(
            f"the system instance is named {system_name!r}: expected letters, digits and underscores "
            "(OSATE names it Type_impl_Instance)",
            Location(path=system_name or None),
        )
    multi = len(w.roots) > 1
    for number, root in enumerate(w.roots):
        head = f"/{number}" if multi else "/"
        w.paths[id(root)] = head
        stack = [(root, head)]
        while stack:
            obj, path = stack.pop()
            for tag, items in containments(obj):
                for position, child in enumerate(items):
                    child_path = f"{path}/@{tag}.{position}"
                    w.paths[id(child)] = child_path
                    if _walk_of(child)[1]:
                        name = value_of(child, "name") or ""
                        if not ID_RE.match(name):
                            shown = repr(name) if name else "no name"
                            raise ExportError(
                                f"a {child.eClass.name} has {shown}: an AADL identifier is letters, "
                                "digits and single underscores, starting with a letter",
                                Location(path=f"{instance_path(obj)}.{name}"),
                            )
                    stack.append((child, child_path))
    for som in items_of(w.system, "systemOperationModes"):
        w.som_by_name.setdefault((value_of(som, "name") or "").lower(), som)


def containments(obj: EObject) -> list[tuple[str, Any]]:
    """(element tag, items) of the lists of an instance object that hold instance objects."""
    return [(tag, items_of(obj, feature)) for tag, feature in _walk_of(obj)[0]]


# what the walk needs of each class of instance object, looked up once per class: the walk
# visits every instance object, and model.is_a's call for each (1-4 per object) cost 2-3 % of
# exporting the generated 50 000-object model
_WALK: dict[Any, tuple[tuple[tuple[str, str], ...], bool]] = {}


def _walk_of(obj: EObject) -> tuple[tuple[tuple[str, str], ...], bool]:
    """((tag, feature) of the lists holding instance objects, whether it must be named by an
    AADL identifier) for the class of ``obj``."""
    found = _WALK.get(obj.eClass)
    if found is None:
        if is_a(obj, "ComponentInstance"):
            lists = _COMPONENT_LISTS
            if is_a(obj, "SystemInstance"):
                lists += (("systemOperationMode", "systemOperationModes"),)
        elif is_a(obj, "FeatureInstance"):
            lists = (("featureInstance", "featureInstances"),)
        else:
            lists = ()
        found = _WALK[obj.eClass] = (lists, is_a(obj, *CHECKED_CLASSES))
    return found

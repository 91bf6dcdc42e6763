"""AADL's visibility rules: which declaration a name denotes, seen from a unit.

* classifiers (:func:`find_classifier`): the unit's own package, fully qualified names
  (``P::T``, ``P::T.impl``; private classifiers only from their own package), package aliases and
  classifier aliases of ``renames`` declarations, and ``renames P::all``;
* properties, property types and constants (:func:`find_set_member`): ``Set::Name`` qualified, or
  unqualified through the unit itself, the predeclared property sets (``Period`` is
  ``Timing_Properties::Period``), then the property sets the unit names in its ``with`` clauses.

These are plain functions of a :class:`~.index.UnitIndex`; the
:class:`~rosaadl.resolution.Resolver` caches their answers.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.model import is_a

from .index import UnitIndex, visible_packages
from .names import enum_name, lower, split_name, strip_all

__all__ = [
    "PREDECLARED_PROPERTY_SETS",
    "find_classifier",
    "find_set_member",
    "missing_property_set",
    "package_alias",
]

#: The property sets of SAE AS5506C whose properties may be named without qualification.
PREDECLARED_PROPERTY_SETS: tuple[str, ...] = (
    "Deployment_Properties",
    "Thread_Properties",
    "Timing_Properties",
    "Communication_Properties",
    "Memory_Properties",
    "Programming_Properties",
    "Modeling_Properties",
    "AADL_Project",
)


def package_alias(index: UnitIndex, unit: EObject, qualifier: str) -> EObject | None:
    """The package a ``renames package`` alias ``qualifier`` of ``unit`` stands for, if any."""
    wanted = qualifier.lower()
    for ren in getattr(unit, "renamings", ()) or ():
        if enum_name(ren.kind) == "package" and lower(ren.name) == wanted:
            return index.unit(strip_all(ren.target))
    return None


def find_classifier(
    index: UnitIndex, name: str, unit: EObject | None, seen: set[tuple[int, str]] | None = None
) -> EObject | None:
    """The classifier ``name`` denotes from ``unit`` (a package, or None for qualified names
    only), or None. ``seen`` guards against renames that loop."""
    seen = set() if seen is None else seen
    qualifier, local = split_name(name)
    marker = (id(unit), f"{qualifier}::{local}".lower())
    if marker in seen:
        return None
    seen.add(marker)
    wanted = local.lower()
    if qualifier is not None:
        target = package_alias(index, unit, qualifier) if unit is not None else None
        if target is None:
            target = index.unit(qualifier)
        if target is None or not is_a(target, "AadlPackage"):
            return None
        found = index.classifiers(target).get(wanted)
        if found is not None and target is not unit and enum_name(found.visibility) == "private":
            return None
        return found
    if unit is None or not is_a(unit, "AadlPackage"):
        return None
    found = index.classifiers(unit).get(wanted)
    if found is not None:
        return found
    # classifier aliases: "X renames thread P::T;" and "renames thread P::T;"
    type_part, dot, impl_part = wanted.partition(".")
    for ren in getattr(unit, "renamings", ()) or ():
        kind = enum_name(ren.kind)
        if kind in ("classifier", "featureGroupType"):
            target = ren.target or ""
            alias = lower(ren.name) or split_name(target)[1].lower()
            if alias == wanted:
                return find_classifier(index, target, unit, seen)
            if dot and alias == type_part:
                # an implementation of an aliased type: T.impl where T renames P::T
                return find_classifier(index, f"{target}.{impl_part}", unit, seen)
    for ren in getattr(unit, "renamings", ()) or ():
        if enum_name(ren.kind) == "all":
            target_unit = index.unit(strip_all(ren.target))
            if target_unit is not None and is_a(target_unit, "AadlPackage"):
                found = index.classifiers(target_unit).get(wanted)
                if found is not None and enum_name(found.visibility) != "private":
                    return found
    return None


def find_set_member(index: UnitIndex, kind: str, name: str, unit: EObject | None) -> EObject | None:
    """The ``property``, ``type`` or ``constant`` (``kind``) ``name`` denotes from ``unit``."""
    qualifier, local = split_name(name)
    wanted = local.lower()
    if qualifier is not None:
        members = index.set_members(index.unit(qualifier))
        return members[kind].get(wanted) if members is not None else None
    candidates: list[dict[str, dict[str, EObject]]] = []
    if unit is not None:
        own = index.set_members(unit)
        if own is not None:
            candidates.append(own)
    for set_name in PREDECLARED_PROPERTY_SETS:
        members = index.set_members(index.unit(set_name))
        if members is not None:
            candidates.append(members)
    if unit is not None:
        for with_name in visible_packages(unit):
            members = index.set_members(index.unit(with_name))
            if members is not None:
                candidates.append(members)
    for members in candidates:
        found = members[kind].get(wanted)
        if found is not None:
            return found
    return None


def missing_property_set(index: UnitIndex, name: str | None) -> str | None:
    """The qualifier of ``name`` when it names a property set that is not loaded, else None."""
    qualifier, _ = split_name(name or "")
    if qualifier is None:
        return None
    return qualifier if index.unit(qualifier) is None else None

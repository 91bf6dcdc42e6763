"""The component library as a catalog: what it holds and what one component is.

* :func:`read_library` reads the library of rosaadl with any AADL files or folders given, resolved;
* :func:`list_packages` summarises every package and property set of such a model: its kind, its
  file and its components (name, category, type or implementation, what it extends);
* :func:`describe` says what one named thing is: a package or property set, a classifier
  ``Pkg::T`` / ``Pkg::T.impl``, or an unqualified name searched across every package. A classifier
  is described by its category, ``extends`` chain, implementations (of a type), features (ports
  with direction and data type), subcomponents, connections, flows and property associations
  (values as AADL text with units, :func:`rosaadl.property_text.format_value`, and where each
  comes from). Unknown and ambiguous names raise :class:`ComponentNotFound` with the candidates.

``rosaadl library list`` and ``rosaadl library show`` print these; see ``docs/library.md``.
"""

from __future__ import annotations

import difflib
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, NameResolutionError
from rosaadl.exporters.aadl_text.lexical import literal
from rosaadl.importers.aadl_text import read_files
from rosaadl.model import is_a
from rosaadl.property_text import format_value
from rosaadl.resolution import Resolver, feature_category_word, split_name

__all__ = [
    "ComponentNotFound",
    "ComponentSummary",
    "PackageSummary",
    "library_root",
    "display_file",
    "read_library",
    "list_packages",
    "find_named",
    "describe",
]


def library_root() -> Path:
    """The folder of the component library shipped with rosaadl."""
    return Path(str(resources.files("rosaadl.library")))


def display_file(source: str | None, root: Path | None = None) -> tuple[str | None, bool]:
    """``(file, in_library)``: a library file relative to the library folder (``nodes/x.aadl``),
    any other file as it was given."""
    if not source:
        return None, False
    base = (root or library_root()).resolve()
    try:
        relative = Path(source).resolve().relative_to(base)
    except (ValueError, OSError):
        return source, False
    return relative.as_posix(), True


@checked
def read_library(
    inputs: Iterable[str | os.PathLike[str]] = (), *, warnings: list[Diagnostic] | None = None
) -> EObject:
    """The component library with the AADL files and folders ``inputs``, read and resolved."""
    return read_files(list(inputs), include_library=True, warnings=warnings)


def _qname(resolver: Resolver, element: EObject | None) -> str | None:
    return resolver.qualified_name(element) if element is not None else None


# --------------------------------------------------------------------------- list


@dataclass(frozen=True)
class ComponentSummary:
    """One classifier of a package: name, category, ``type`` or ``implementation``, extends."""

    name: str
    category: str
    kind: str
    extends: str | None

    def as_dict(self) -> dict[str, Any]:
        return {"name": self.name, "category": self.category, "kind": self.kind, "extends": self.extends}

    def __str__(self) -> str:
        words = self.category if self.kind == "type" else f"{self.category} {self.kind}"
        text = f"{words} {self.name}"
        return f"{text} extends {self.extends}" if self.extends else text


@dataclass(frozen=True)
class PackageSummary:
    """A package (with its components) or a property set (with its property names)."""

    name: str
    kind: str  # "package" | "property set"
    file: str | None
    library: bool
    components: tuple[ComponentSummary, ...] = ()
    properties: tuple[str, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        data: dict[str, Any] = {
            "name": self.name,
            "kind": self.kind,
            "file": self.file,
            "library": self.library,
            "components": [c.as_dict() for c in self.components],
        }
        if self.kind == "property set":
            data["properties"] = list(self.properties)
        return data


def _summary(resolver: Resolver, classifier: EObject) -> ComponentSummary:
    if is_a(classifier, "FeatureGroupType"):
        category, kind = "feature group", "type"
    else:
        category = literal(classifier.category)
        kind = "implementation" if is_a(classifier, "ComponentImplementation") else "type"
    extends = None
    if classifier.extended:
        parent = resolver.classifier(classifier.extended, classifier)
        extends = _qname(resolver, parent) if parent is not None else classifier.extended
    return ComponentSummary(classifier.name or "", category, kind, extends)


@checked
def list_packages(workspace: EObject, resolver: Resolver | None = None) -> list[PackageSummary]:
    """Every package and property set of ``workspace``, sorted by name, with its components."""
    resolver = resolver or Resolver(workspace)
    root = library_root()
    out = []
    for unit in sorted(workspace.units, key=lambda u: ((u.name or "").lower(), u.name or "")):
        file, in_library = display_file(unit.sourceFile, root)
        if is_a(unit, "PropertySet"):
            names = tuple(p.name for p in unit.ownedProperties)
            out.append(PackageSummary(unit.name, "property set", file, in_library, (), names))
        else:
            components = tuple(_summary(resolver, c) for c in unit.classifiers)
            out.append(PackageSummary(unit.name, "package", file, in_library, components))
    return out


# --------------------------------------------------------------------------- show


class ComponentNotFound(NameResolutionError):
    """A name given to :func:`describe` names nothing, or several things (``candidates``)."""

    def __init__(self, message: str, candidates: Sequence[str] = (), **kwargs: Any) -> None:
        self.candidates = list(candidates)
        super().__init__(message, **kwargs)

    def as_dict(self) -> dict[str, object]:
        return {**super().as_dict(), "candidates": self.candidates}


def find_named(workspace: EObject, name: str) -> tuple[list[EObject], list[EObject]]:
    """``(units, classifiers)`` called ``name``: a package or property set, ``Pkg::T[.impl]``, or
    an unqualified classifier name searched in every package (case-insensitive, as AADL)."""
    text = "".join((name or "").split())
    wanted = text.lower()
    units = [u for u in workspace.units if (u.name or "").lower() == wanted]
    classifiers: list[EObject] = []
    qualifier, local = split_name(text)
    for unit in workspace.units:
        if not is_a(unit, "AadlPackage"):
            continue
        if qualifier is not None and (unit.name or "").lower() != qualifier.lower():
            continue
        classifiers.extend(c for c in unit.classifiers if (c.name or "").lower() == local.lower())
    return units, classifiers


def _all_names(workspace: EObject) -> list[str]:
    names = []
    for unit in workspace.units:
        names.append(unit.name)
        if is_a(unit, "AadlPackage"):
            names.extend(f"{unit.name}::{c.name}" for c in unit.classifiers)
    return names


def _close(workspace: EObject, name: str, limit: int = 8) -> list[str]:
    names = _all_names(workspace)
    lowered: dict[str, str] = {}
    for qualified in names:
        lowered.setdefault(qualified.lower(), qualified)
        local = qualified.rpartition("::")[2].lower()
        lowered.setdefault(local, qualified)
    wanted = "".join((name or "").split()).lower()
    hits = difflib.get_close_matches(wanted, list(lowered), n=limit * 2, cutoff=0.6)
    contains = [key for key in lowered if wanted and wanted in key and key not in hits]
    out: list[str] = []
    for key in [*hits, *sorted(contains)]:
        qualified = lowered[key]
        if qualified not in out:
            out.append(qualified)
    return out[:limit]


@checked
def describe(workspace: EObject, name: str, resolver: Resolver | None = None) -> dict[str, Any]:
    """What ``name`` is, as a JSON-ready dictionary (``"what"``: ``package``, ``property set`` or
    ``classifier``). A package or property set of that name wins over unqualified classifiers
    of the same name (listed under ``see_also``). Raises :class:`ComponentNotFound`."""
    resolver = resolver or Resolver(workspace)
    units, classifiers = find_named(workspace, name)
    if units:
        unit = units[0]
        info = _describe_unit(resolver, unit)
        if classifiers:
            info["see_also"] = [resolver.qualified_name(c) for c in classifiers]
        return info
    if len(classifiers) == 1:
        return _describe_classifier(workspace, resolver, classifiers[0])
    if classifiers:
        candidates = sorted(resolver.qualified_name(c) for c in classifiers)
        raise ComponentNotFound(
            f"{name!r} is ambiguous: it names {len(candidates)} classifiers ({', '.join(candidates)}); "
            "give the package too (Pkg::Name)",
            candidates,
        )
    candidates = _close(workspace, name)
    hint = f"; did you mean {', '.join(candidates)}?" if candidates else ""
    raise ComponentNotFound(
        f"{name!r} is not a package, property set or classifier of the library or the inputs{hint}",
        candidates,
    )


def _where(unit: EObject, element: EObject) -> dict[str, Any]:
    file, in_library = display_file(unit.sourceFile)
    return {"file": file, "line": getattr(element, "line", None) or None, "library": in_library}


def _describe_unit(resolver: Resolver, unit: EObject) -> dict[str, Any]:
    info: dict[str, Any] = {
        "what": "property set" if is_a(unit, "PropertySet") else "package",
        "name": unit.name,
        **_where(unit, unit),
        "withs": list(unit.withs),
    }
    if is_a(unit, "PropertySet"):
        info["properties"] = [
            {
                "name": prop.name,
                "type": _type_text(prop.type, prop.ownedType),
                "applies_to": list(prop.appliesTo),
                "inherit": bool(prop.inherit),
                "default": format_value(prop.defaultValue) if prop.defaultValue is not None else None,
            }
            for prop in unit.ownedProperties
        ]
        info["types"] = [
            {"name": ptype.name, "type": _type_text(None, ptype)} for ptype in unit.ownedPropertyTypes
        ]
        info["constants"] = [
            {"name": const.name, "value": format_value(const.value) if const.value is not None else None}
            for const in unit.ownedPropertyConstants
        ]
        return info
    info["renames"] = [
        {
            "name": ren.name,
            "kind": literal(ren.category)
            if literal(ren.kind) == "classifier" and ren.category
            else literal(ren.kind),
            "target": ren.target,
        }
        for ren in unit.renamings
    ]
    info["components"] = [_summary(resolver, c).as_dict() for c in unit.classifiers]
    return info


def _type_text(name: str | None, owned: EObject | None) -> str | None:
    if name:
        return name
    if owned is None:
        return None
    kind = owned.eClass.name
    if kind == "EnumerationType":
        return "enumeration (" + ", ".join(lit.name for lit in owned.ownedLiterals) + ")"
    if kind == "UnitsType":
        return "units (" + ", ".join(lit.name for lit in owned.ownedLiterals) + ")"
    if kind in ("AadlInteger", "AadlReal"):
        word = "aadlinteger" if kind == "AadlInteger" else "aadlreal"
        units = getattr(owned, "unitsType", None) or (
            _type_text(None, owned.ownedUnitsType) if getattr(owned, "ownedUnitsType", None) else None
        )
        return f"{word} units {units}" if units else word
    if kind == "ListType":
        return f"list of {_type_text(owned.elementType, owned.ownedElementType)}"
    if kind == "RangeType":
        return f"range of {_type_text(owned.numberType, owned.ownedNumberType)}"
    if kind in ("ReferenceType", "ClassifierType"):
        word = "reference" if kind == "ReferenceType" else "classifier"
        cats = list(owned.categories)
        return f"{word} ({', '.join(cats)})" if cats else word
    if kind == "RecordType":
        return "record (" + ", ".join(f.name for f in owned.ownedFields) + ")"
    return {"AadlString": "aadlstring", "AadlBoolean": "aadlboolean"}.get(kind, kind)


def _implementations_of(workspace: EObject, resolver: Resolver, ctype: EObject) -> list[str]:
    out = []
    for unit in workspace.units:
        if not is_a(unit, "AadlPackage"):
            continue
        for classifier in unit.classifiers:
            if (
                is_a(classifier, "ComponentImplementation")
                and resolver.implementation_type(classifier) is ctype
            ):
                out.append(resolver.qualified_name(classifier))
    return out


def _extended_by(workspace: EObject, resolver: Resolver, target: EObject) -> list[str]:
    out = []
    for unit in workspace.units:
        if not is_a(unit, "AadlPackage"):
            continue
        for classifier in unit.classifiers:
            if classifier.extended and resolver.classifier(classifier.extended, classifier) is target:
                out.append(resolver.qualified_name(classifier))
    return out


def _member_classifier(resolver: Resolver, member: EObject, resolved: EObject | None) -> str | None:
    if resolved is not None:
        return resolver.qualified_name(resolved)
    for element in resolver.refinement_chain(member):
        if element.classifier:
            return element.classifier
    return None


def _describe_classifier(workspace: EObject, resolver: Resolver, classifier: EObject) -> dict[str, Any]:
    unit = resolver.unit_of(classifier)
    summary = _summary(resolver, classifier)
    chain = resolver.extends_chain(classifier)
    info: dict[str, Any] = {
        "what": "classifier",
        "name": resolver.qualified_name(classifier),
        "package": unit.name if unit is not None else None,
        "category": summary.category,
        "kind": summary.kind,
        **(_where(unit, classifier) if unit is not None else {}),
        "extends": [resolver.qualified_name(c) for c in chain[1:]],
    }
    if chain and chain[-1].extended:
        info["extends"].append(chain[-1].extended + " (not found)")
    ctype = None
    if is_a(classifier, "ComponentImplementation"):
        ctype = resolver.implementation_type(classifier)
        info["type"] = _qname(resolver, ctype) or classifier.type or classifier.name.partition(".")[0]
        info["type_extends"] = (
            [resolver.qualified_name(c) for c in resolver.extends_chain(ctype)[1:]] if ctype else []
        )
    elif is_a(classifier, "ComponentType"):
        info["implementations"] = _implementations_of(workspace, resolver, classifier)
    info["extended_by"] = _extended_by(workspace, resolver, classifier)

    features = []
    for feature in resolver.features(classifier):
        category = feature.category.name if feature.category is not None else ""
        entry: dict[str, Any] = {"name": feature.name, "category": feature_category_word(feature.category)}
        if category in ("dataPort", "eventPort", "eventDataPort", "parameter", "abstractFeature"):
            entry["direction"] = literal(
                resolver.effective_attribute(feature, "direction") or feature.direction
            )
        elif category.endswith("Access"):
            entry["access"] = literal(feature.access)
        entry["classifier"] = _member_classifier(resolver, feature, resolver.feature_classifier(feature))
        entry["refined"] = bool(feature.refined)
        entry["from"] = _qname(resolver, feature.eContainer())
        features.append(entry)
    info["features"] = features

    if is_a(classifier, "ComponentImplementation"):
        info["subcomponents"] = [
            {
                "name": sub.name,
                "category": literal(sub.category),
                "classifier": _member_classifier(resolver, sub, resolver.subcomponent_classifier(sub)),
                "array": list(sub.arrayDimensions),
                "refined": bool(sub.refined),
                "from": _qname(resolver, sub.eContainer()),
            }
            for sub in resolver.subcomponents(classifier)
        ]
        connections = []
        for conn in resolver.connections(classifier):
            source, destination = resolver.connection_ends(conn)
            connections.append(
                {
                    "name": conn.name,
                    "kind": literal(resolver.effective_attribute(conn, "kind") or conn.kind),
                    "source": source,
                    "destination": destination,
                    "bidirectional": bool(resolver.effective_attribute(conn, "bidirectional")),
                    "refined": bool(conn.refined),
                    "from": _qname(resolver, conn.eContainer()),
                }
            )
        info["connections"] = connections
    if not is_a(classifier, "FeatureGroupType"):
        info["flows"] = [
            {
                "name": flow.name,
                "kind": literal(flow.kind),
                "in": flow.inEnd or None,
                "out": flow.outEnd or None,
            }
            for flow in resolver.flow_specifications(classifier)
        ]
        info["modes"] = [mode.name for mode in resolver.modes(classifier)]
    info["properties"] = _effective_associations(resolver, classifier, ctype)
    return info


def _effective_associations(
    resolver: Resolver, classifier: EObject, ctype: EObject | None
) -> list[dict[str, Any]]:
    """The property associations a classifier sees, nearest first: its own, then those of the
    classifiers it extends, then (implementations) its type's; one per property and target."""
    holders = list(resolver.extends_chain(classifier))
    if ctype is not None:
        holders.extend(resolver.extends_chain(ctype))
    seen: set[tuple[str, tuple[str, ...]]] = set()
    out = []
    for holder in holders:
        for pa in holder.ownedPropertyAssociations:
            prop = resolver.association_property(pa)
            display = (
                resolver.qualified_name(prop) if prop is not None else "".join((pa.property or "").split())
            )
            targets = tuple("".join(t.split()) for t in pa.appliesTo)
            key = (display.lower(), tuple(t.lower() for t in targets))
            if key in seen:
                continue
            seen.add(key)
            entry: dict[str, Any] = {"property": display}
            values = [mv for mv in pa.ownedValues if mv.value is not None]
            if len(values) == 1 and not values[0].inModes:
                entry["value"] = format_value(values[0].value)
                entry.update(_json_value(values[0].value))
            else:
                entry["value"] = ", ".join(
                    format_value(mv.value) + (f" in modes ({', '.join(mv.inModes)})" if mv.inModes else "")
                    for mv in values
                )
            entry["applies_to"] = list(targets)
            if pa.append:
                entry["append"] = True
            if pa.constant:
                entry["constant"] = True
            entry["from"] = resolver.qualified_name(holder)
            out.append(entry)
    return out


def _json_value(expr: EObject) -> dict[str, Any]:
    """The number and unit of a number or range value, for JSON."""
    if is_a(expr, "IntegerValue", "RealValue"):
        return {"number": expr.value, "unit": expr.unit or None}
    if is_a(expr, "RangeValue") and expr.minimum is not None and expr.maximum is not None:
        return {"minimum": _json_value(expr.minimum), "maximum": _json_value(expr.maximum)}
    return {}

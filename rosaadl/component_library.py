"""The component library as data: what it holds, what one component is, and new profiles.

* :func:`list_packages` summarises every package and property set of a model read with
  :func:`read_library` (the library of rosaadl, plus any AADL files given): its kind, its file and
  its components (name, category, type or implementation, what it extends).
* :func:`describe` says what one named thing is: a package or property set, a classifier
  ``Pkg::T`` / ``Pkg::T.impl``, or an unqualified name searched across every package. A classifier
  is described by its category, ``extends`` chain, implementations (of a type), features (ports
  with direction and data type), subcomponents, connections, flows and property associations
  (values with units, and where each comes from). Unknown and ambiguous names raise
  :class:`ComponentNotFound` with the candidates.
* :func:`add_profiles` turns a CSV file of measurements (:data:`COLUMNS`) into platform-dependent
  implementations (PDM) of library nodes, in the style of the library's own node packages::

      process implementation usb_cam_nd.le376_atom extends nd_usb_cam::usb_cam_nd.impl
        subcomponents
          image_broadcaster: refined to thread imagePublisher.le376_atom;
        properties
          SEI::MIPSBudget => 500.0 MIPS;
          ROS_Profiling::Raw_MIPS => 310.0 MIPS;
          ROS_Profiling::IPC => 0.62;
          Reference_Processor => classifier (Atom_D510::Atom_core);
      end usb_cam_nd.le376_atom;

      thread implementation imagePublisher.le376_atom extends nd_usb_cam::imagePublisher.impl
        properties
          Compute_Execution_Time => 6100 us .. 6100 us;
      end imagePublisher.le376_atom;

  one package ``<node package>_profiles`` per node package, which names the node's types with
  ``renames`` (an implementation is declared in the package of its type or of an alias of it).
  Every problem of the file is reported at once, located at its line and column
  (:class:`MeasurementError`); the packages are written only when the whole file is good, after
  they have been read back, resolved, instantiated and checked to carry the measured values.

See ``docs/library.md`` for the CSV columns and the profiling workflow.
"""

from __future__ import annotations

import csv
import difflib
import io
import logging
import os
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from decimal import ROUND_HALF_EVEN, ROUND_HALF_UP, Decimal, InvalidOperation
from importlib import resources
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import (
    Diagnostic,
    ExportError,
    Location,
    NameResolutionError,
    ParseError,
    RosaadlError,
)
from rosaadl.resolution import Resolver, feature_category_word, split_name

__all__ = [
    "COLUMNS",
    "OPTIONAL_COLUMNS",
    "PROFILE_SUFFIX",
    "ComponentNotFound",
    "ComponentSummary",
    "PackageSummary",
    "MeasurementError",
    "Measurement",
    "ProfiledImplementation",
    "ProfileResult",
    "library_root",
    "display_file",
    "read_library",
    "list_packages",
    "find_named",
    "describe",
    "format_value",
    "parse_measurements",
    "build_profiles",
    "add_profiles",
]

log = logging.getLogger(__name__)

#: The columns a measurements file must have (its header line names them, in any order).
COLUMNS: tuple[str, ...] = (
    "node",
    "thread",
    "board",
    "core",
    "period_us",
    "cet_us",
    "mips_raw",
    "ipc",
    "data_size_bytes",
)
#: Columns a measurements file may have: ``processor``, the classifier of the core measured on.
OPTIONAL_COLUMNS: tuple[str, ...] = ("processor",)
#: The profiles of the nodes of package ``P`` go to package ``P`` + this suffix.
PROFILE_SUFFIX = "_profiles"

# limits that keep a hostile file from exhausting memory or overflowing the model's 64-bit integers
MAX_FILE_BYTES = 16 * 1024 * 1024
MAX_ROWS = 100_000
_MAX_TIME_NS = 10**18  # about 31 years
_MAX_MIPS = Decimal(10) ** 9
_MAX_IPC = Decimal(1000)
_MIN_IPC = Decimal("0.000001")
_MAX_SIZE = 2**53

_IDENTIFIER = re.compile(r"[A-Za-z](?:_?[A-Za-z0-9])*\Z")
_PART = re.compile(r"[A-Za-z0-9](?:_?[A-Za-z0-9])*\Z")
_CLASSIFIER = re.compile(
    r"[A-Za-z](?:_?[A-Za-z0-9])*(?:::[A-Za-z](?:_?[A-Za-z0-9])*)+(?:\.[A-Za-z](?:_?[A-Za-z0-9])*)?\Z"
)
_NODE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z][A-Za-z0-9_]*)*\Z")
_CENT = Decimal("0.01")
_DATA_PORTS = ("dataPort", "eventDataPort")


# =========================================================================== shared helpers


def _word(value: object) -> str:
    """The AADL spelling of an enumeration value (``thread group``, ``in out``, ``event data port``)."""
    literal = getattr(value, "literal", None)
    if literal:
        return str(literal)
    name = getattr(value, "name", None)
    return str(name) if name is not None else str(value)


def _is(obj: object, *names: str) -> bool:
    if not isinstance(obj, EObject):
        return False
    eclass = obj.eClass
    return eclass.name in names or any(sup.name in names for sup in eclass.eAllSuperTypes())


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


def read_library(
    inputs: Iterable[str | os.PathLike[str]] = (), *, warnings: list[Diagnostic] | None = None
) -> EObject:
    """The component library with the AADL files and folders ``inputs``, read and resolved."""
    from rosaadl.importers.aadl_text import read_files

    return read_files(list(inputs), include_library=True, warnings=warnings)


def _qname(resolver: Resolver, element: EObject | None) -> str | None:
    return resolver.qualified_name(element) if element is not None else None


# =========================================================================== list


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
    if _is(classifier, "FeatureGroupType"):
        category, kind = "feature group", "type"
    else:
        category = _word(classifier.category)
        kind = "implementation" if _is(classifier, "ComponentImplementation") else "type"
    extends = None
    if classifier.extended:
        parent = resolver.classifier(classifier.extended, classifier)
        extends = _qname(resolver, parent) if parent is not None else classifier.extended
    return ComponentSummary(classifier.name or "", category, kind, extends)


def list_packages(workspace: EObject, resolver: Resolver | None = None) -> list[PackageSummary]:
    """Every package and property set of ``workspace``, sorted by name, with its components."""
    resolver = resolver or Resolver(workspace)
    root = library_root()
    out = []
    for unit in sorted(workspace.units, key=lambda u: ((u.name or "").lower(), u.name or "")):
        file, in_library = display_file(unit.sourceFile, root)
        if _is(unit, "PropertySet"):
            names = tuple(p.name for p in unit.ownedProperties)
            out.append(PackageSummary(unit.name, "property set", file, in_library, (), names))
        else:
            components = tuple(_summary(resolver, c) for c in unit.classifiers)
            out.append(PackageSummary(unit.name, "package", file, in_library, components))
    return out


# =========================================================================== show


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
        if not _is(unit, "AadlPackage"):
            continue
        if qualifier is not None and (unit.name or "").lower() != qualifier.lower():
            continue
        classifiers.extend(c for c in unit.classifiers if (c.name or "").lower() == local.lower())
    return units, classifiers


def _all_names(workspace: EObject) -> list[str]:
    names = []
    for unit in workspace.units:
        names.append(unit.name)
        if _is(unit, "AadlPackage"):
            names.extend(f"{unit.name}::{c.name}" for c in unit.classifiers)
    return names


def _close(workspace: EObject, name: str, limit: int = 8) -> list[str]:
    names = _all_names(workspace)
    lowered: dict[str, str] = {}
    for qualified in names:
        lowered.setdefault(qualified.lower(), qualified)
        local = qualified.rpartition("::")[2].lower()
        lowered.setdefault(local, qualified)
    wanted = "".join(name.split()).lower()
    hits = difflib.get_close_matches(wanted, list(lowered), n=limit * 2, cutoff=0.6)
    contains = [key for key in lowered if wanted and wanted in key and key not in hits]
    out: list[str] = []
    for key in [*hits, *sorted(contains)]:
        qualified = lowered[key]
        if qualified not in out:
            out.append(qualified)
    return out[:limit]


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
        "what": "property set" if _is(unit, "PropertySet") else "package",
        "name": unit.name,
        **_where(unit, unit),
        "withs": list(unit.withs),
    }
    if _is(unit, "PropertySet"):
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
            "kind": _word(ren.category)
            if _word(ren.kind) == "classifier" and ren.category
            else _word(ren.kind),
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
        if not _is(unit, "AadlPackage"):
            continue
        for classifier in unit.classifiers:
            if (
                _is(classifier, "ComponentImplementation")
                and resolver.implementation_type(classifier) is ctype
            ):
                out.append(resolver.qualified_name(classifier))
    return out


def _extended_by(workspace: EObject, resolver: Resolver, target: EObject) -> list[str]:
    out = []
    for unit in workspace.units:
        if not _is(unit, "AadlPackage"):
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
    if _is(classifier, "ComponentImplementation"):
        ctype = resolver.implementation_type(classifier)
        info["type"] = _qname(resolver, ctype) or classifier.type or classifier.name.partition(".")[0]
        info["type_extends"] = (
            [resolver.qualified_name(c) for c in resolver.extends_chain(ctype)[1:]] if ctype else []
        )
    elif _is(classifier, "ComponentType"):
        info["implementations"] = _implementations_of(workspace, resolver, classifier)
    info["extended_by"] = _extended_by(workspace, resolver, classifier)

    features = []
    for feature in resolver.features(classifier):
        category = feature.category.name if feature.category is not None else ""
        entry: dict[str, Any] = {"name": feature.name, "category": feature_category_word(feature.category)}
        if category in ("dataPort", "eventPort", "eventDataPort", "parameter", "abstractFeature"):
            entry["direction"] = _word(
                resolver.effective_attribute(feature, "direction") or feature.direction
            )
        elif category.endswith("Access"):
            entry["access"] = _word(feature.access)
        entry["classifier"] = _member_classifier(resolver, feature, resolver.feature_classifier(feature))
        entry["refined"] = bool(feature.refined)
        entry["from"] = _qname(resolver, feature.eContainer())
        features.append(entry)
    info["features"] = features

    if _is(classifier, "ComponentImplementation"):
        info["subcomponents"] = [
            {
                "name": sub.name,
                "category": _word(sub.category),
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
                    "kind": _word(resolver.effective_attribute(conn, "kind") or conn.kind),
                    "source": source,
                    "destination": destination,
                    "bidirectional": bool(resolver.effective_attribute(conn, "bidirectional")),
                    "refined": bool(conn.refined),
                    "from": _qname(resolver, conn.eContainer()),
                }
            )
        info["connections"] = connections
    if not _is(classifier, "FeatureGroupType"):
        info["flows"] = [
            {
                "name": flow.name,
                "kind": _word(flow.kind),
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
    kind = expr.eClass.name
    if kind in ("IntegerValue", "RealValue"):
        return {"number": expr.value, "unit": expr.unit or None}
    if kind == "RangeValue" and expr.minimum is not None and expr.maximum is not None:
        return {"minimum": _json_value(expr.minimum), "maximum": _json_value(expr.maximum)}
    return {}


def format_value(expr: EObject | None) -> str:
    """A property value as AADL text (``33333 us``, ``2319 us .. 2319 us``, ``classifier (P::T)``)."""
    from rosaadl.exporters.aadl_text import format_real

    if expr is None:
        return ""
    kind = expr.eClass.name
    if kind == "IntegerValue":
        return f"{expr.value} {expr.unit}" if expr.unit else str(expr.value)
    if kind == "RealValue":
        text = format_real(expr.value)
        return f"{text} {expr.unit}" if expr.unit else text
    if kind == "RangeValue":
        text = f"{format_value(expr.minimum)} .. {format_value(expr.maximum)}"
        return f"{text} delta {format_value(expr.delta)}" if expr.delta is not None else text
    if kind == "BooleanValue":
        return "true" if expr.value else "false"
    if kind == "StringValue":
        return '"' + (expr.value or "").replace('"', '""') + '"'
    if kind == "NamedValue":
        return expr.name or ""
    if kind == "ReferenceValue":
        return f"reference ({expr.path})"
    if kind == "ClassifierValue":
        return f"classifier ({expr.classifier})"
    if kind == "InstanceReferenceValue":
        target = expr.referencedInstanceObject
        return f"reference ({_model.instance_path(target) if target is not None else '?'})"
    if kind == "ListValue":
        return "(" + ", ".join(format_value(item) for item in expr.ownedItems) + ")"
    if kind == "RecordValue":
        return "[" + " ".join(f"{f.name} => {format_value(f.value)};" for f in expr.ownedFields) + "]"
    if kind == "ComputedValue":
        return f"compute ({expr.function})"
    if kind == "OperationValue":
        operands = [format_value(o) for o in expr.ownedOperands]
        if len(operands) == 1:
            sign = expr.operator in ("-", "+")
            return f"{expr.operator}{operands[0]}" if sign else f"{expr.operator} {operands[0]}"
        return f" {expr.operator} ".join(operands)
    return kind


# =========================================================================== measurements


class MeasurementError(ParseError):
    """A measurements file is malformed or does not match the library; located at file:line
    (and the column's position), naming the row and the column. The error raised for a whole file
    lists every problem in ``errors``."""

    stage = "profile"

    def __init__(self, message: str, location: Location | None = None, **kwargs: Any) -> None:
        self.errors: list[RosaadlError] = []
        super().__init__(message, location, **kwargs)


@dataclass(frozen=True)
class Measurement:
    """One good row of a measurements file. Times are in nanoseconds (exact), MIPS and IPC as
    written; ``columns`` maps each column name to its 1-based position."""

    file: str
    row: int
    line: int
    node: str
    thread: str
    board: str
    core: str
    period_ns: int
    cet_ns: int
    mips_raw: Decimal
    ipc: Decimal
    data_size: int | None
    processor: str | None
    columns: tuple[tuple[str, int], ...] = ()

    @property
    def pdm(self) -> str:
        """The implementation name of the PDM: ``<board>_<core>``."""
        return f"{self.board}_{self.core}"

    @property
    def mips_budget(self) -> Decimal:
        """``mips_raw / ipc`` rounded half up to 2 decimals, as the paper's Table 2 gives it."""
        return (self.mips_raw / self.ipc).quantize(_CENT, rounding=ROUND_HALF_UP)

    def where(self, column: str | None = None) -> Location:
        position = dict(self.columns).get(column) if column else None
        return Location(file=self.file, line=self.line, column=position)

    def error(self, column: str | None, message: str) -> MeasurementError:
        """An error at this row; ``column`` names one column (or several, comma-separated)."""
        if column:
            what = f"row {self.row}, {'columns' if ',' in column else 'column'} {column}"
        else:
            what = f"row {self.row}"
        return MeasurementError(f"{what}: {message}", self.where(column))


def _lines(text: str) -> Iterator[str]:
    """The physical lines of ``text`` (terminators kept), comment lines (``#`` first) emptied."""
    for line in io.StringIO(text, newline=""):
        yield "\n" if line.startswith("#") else line


def _number(text: str) -> Decimal | None:
    try:
        value = Decimal(text)
    except (InvalidOperation, ValueError):
        return None
    return value if value.is_finite() else None


def _describe_cell(text: str) -> str:
    shown = text if len(text) <= 40 else text[:37] + "..."
    return repr(shown)


def parse_measurements(
    data: str | bytes, filename: str = "<measurements>", *, max_rows: int = MAX_ROWS
) -> tuple[list[Measurement], list[MeasurementError], list[Diagnostic]]:
    """Read a measurements file: ``(good rows, errors, warnings)``. Every row is checked; a row
    with any error gives no :class:`Measurement`. See :data:`COLUMNS` and ``docs/library.md``."""
    errors: list[MeasurementError] = []
    warnings: list[Diagnostic] = []

    def fail(message: str, line: int | None = None, column: int | None = None) -> None:
        errors.append(MeasurementError(message, Location(file=filename, line=line, column=column)))

    if isinstance(data, (bytes, bytearray, memoryview)):
        raw = bytes(data)
        if len(raw) > MAX_FILE_BYTES:
            fail(f"the file is larger than {MAX_FILE_BYTES} bytes, the limit for a measurements file")
            return [], errors, warnings
        try:
            text = raw.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            fail(f"not UTF-8 text ({exc.reason}); expected a CSV file", raw[: exc.start].count(b"\n") + 1)
            return [], errors, warnings
    else:
        text = data[1:] if data.startswith("\ufeff") else data
        if len(text) > MAX_FILE_BYTES:
            fail(f"the text is {len(text)} characters; measurements files are limited to {MAX_FILE_BYTES}")
            return [], errors, warnings
    if "\x00" in text:
        fail("the file contains a NUL byte; expected CSV text", text[: text.index("\x00")].count("\n") + 1)
        return [], errors, warnings
    if not text.strip():
        fail(f"the file is empty; expected a header line naming the columns {', '.join(COLUMNS)}", 1)
        return [], errors, warnings

    reader = csv.reader(_lines(text), strict=True, skipinitialspace=True)
    header: dict[str, int] | None = None
    header_line = 1
    rows: list[Measurement] = []
    previous_end = 0
    row_number = 0
    try:
        for record in reader:
            start = previous_end + 1
            previous_end = reader.line_num
            cells = [cell.strip() for cell in record]
            if not any(cells):
                continue  # blank lines, comments and rows of empty cells
            if header is None:
                header_line = start
                header = _read_header(cells, filename, start, errors, warnings)
                continue
            row_number += 1
            if row_number > max_rows:
                fail(f"more than {max_rows} rows; split the measurements into several files", start)
                break
            measurement = _read_row(cells, header, filename, row_number, start, errors)
            if measurement is not None:
                rows.append(measurement)
    except csv.Error as exc:
        fail(f"malformed CSV: {exc}", reader.line_num or 1)
    if header is None and not errors:
        fail(f"the file holds no header line; expected one naming the columns {', '.join(COLUMNS)}", 1)
    elif header is not None and row_number == 0 and not errors:
        fail("the file has a header but no measurement rows", header_line)
    return rows, errors, warnings


def _read_header(
    cells: list[str], filename: str, line: int, errors: list[MeasurementError], warnings: list[Diagnostic]
) -> dict[str, int]:
    header: dict[str, int] = {}
    for position, cell in enumerate(cells, start=1):
        name = cell.lower()
        where = Location(file=filename, line=line, column=position)
        if not name:
            errors.append(MeasurementError(f"header: column {position} has no name", where))
        elif name in header:
            errors.append(
                MeasurementError(
                    f"header: column {name} is named twice (columns {header[name]} and {position})", where
                )
            )
        else:
            header[name] = position
            if name not in COLUMNS and name not in OPTIONAL_COLUMNS:
                warnings.append(
                    Diagnostic(
                        "warning",
                        f"header: column {cell!r} is not a measurement column and is ignored "
                        f"(columns: {', '.join(COLUMNS + OPTIONAL_COLUMNS)})",
                        where,
                    )
                )
    for name in COLUMNS:
        if name not in header:
            errors.append(
                MeasurementError(
                    f"header: missing column {name} (the header must name {', '.join(COLUMNS)})",
                    Location(file=filename, line=line),
                )
            )
    return header


def _read_row(
    cells: list[str],
    header: dict[str, int],
    filename: str,
    row: int,
    line: int,
    errors: list[MeasurementError],
) -> Measurement | None:
    before = len(errors)

    def fail(column: str | None, message: str, position: int | None = None) -> None:
        if position is None and column is not None:
            position = header.get(column)
        what = f"row {row}, column {column}" if column else f"row {row}"
        errors.append(
            MeasurementError(f"{what}: {message}", Location(file=filename, line=line, column=position))
        )

    width = max(header.values(), default=0)
    if len(cells) > width:
        fail(None, f"the row has {len(cells)} fields, the header names {width} columns", width + 1)
    short = [c for c in COLUMNS if c in header and header[c] > len(cells) and c != "data_size_bytes"]
    if short:
        fail(
            short[0],
            f"the row has {len(cells)} fields, the header names {width} columns: no value for "
            + ", ".join(short),
        )

    def cell(column: str) -> str | None:
        position = header.get(column)
        if position is None:
            return None  # a missing column, reported once with the header
        if position > len(cells):
            # a missing required value is reported above; optional ones may be left off the end
            return None if column in short else ""
        return cells[position - 1]

    def name(column: str, pattern: re.Pattern[str], what: str) -> str | None:
        value = cell(column)
        if value is None:
            return None
        if not value:
            fail(column, f"empty; expected {what}")
            return None
        if len(value) > 200 or not pattern.match(value):
            fail(column, f"{_describe_cell(value)} is not {what}")
            return None
        return value

    def time_ns(column: str, what: str) -> int | None:
        value = cell(column)
        if value is None:
            return None
        number = _number(value)
        if number is None:
            fail(column, f"{_describe_cell(value) if value else 'empty'}: expected a number of microseconds")
            return None
        if number <= 0:
            fail(column, f"{value} us: {what} must be positive")
            return None
        if number > Decimal(_MAX_TIME_NS) / 1000:
            fail(column, f"{value} us is out of range (at most {_MAX_TIME_NS // 1000} us)")
            return None
        ns = int((number * 1000).quantize(Decimal(1), rounding=ROUND_HALF_EVEN))
        if ns <= 0:
            fail(column, f"{value} us is below a nanosecond: {what} must be positive")
            return None
        return ns

    def positive(column: str, what: str, limit: Decimal) -> Decimal | None:
        value = cell(column)
        if value is None:
            return None
        number = _number(value)
        if number is None:
            fail(column, f"{_describe_cell(value) if value else 'empty'}: expected a number ({what})")
            return None
        if number == 0 and column == "ipc":
            fail(column, "the IPC is zero: MIPSBudget = mips_raw / ipc is undefined")
            return None
        if number <= 0:
            fail(column, f"{value}: {what} must be positive")
            return None
        if number > limit:
            fail(column, f"{value} is out of range (at most {limit})")
            return None
        if column == "ipc" and number < _MIN_IPC:
            fail(column, f"{value} is out of range (at least {_MIN_IPC})")
            return None
        return number

    node = name(
        "node", _NODE_NAME, "a node (its package nd_x, its process x_nd, Pkg::x_nd or its ROS node name)"
    )
    thread = name(
        "thread", _IDENTIFIER, "a thread (the name of a thread of the node's PIM, or its thread type)"
    )
    board = name(
        "board", _IDENTIFIER, "a board name (letters, digits and single underscores, starting with a letter)"
    )
    core = name("core", _PART, "a core name (letters, digits and single underscores)")
    if board is not None and core is not None and not _IDENTIFIER.match(f"{board}_{core}"):
        fail("core", f"{board}_{core} is not an AADL identifier")
    period = time_ns("period_us", "a period")
    cet = time_ns("cet_us", "a compute execution time")
    mips = positive("mips_raw", "the raw MIPS rate", _MAX_MIPS)
    ipc = positive("ipc", "the instructions per cycle", _MAX_IPC)
    size: int | None = None
    raw_size = cell("data_size_bytes")
    if raw_size:
        number = _number(raw_size)
        if number is not None and number > _MAX_SIZE:
            fail("data_size_bytes", f"{raw_size} is out of range (at most {_MAX_SIZE})")
        elif number is None or number != number.to_integral_value():
            fail(
                "data_size_bytes",
                f"{_describe_cell(raw_size)}: expected a whole number of bytes (or nothing)",
            )
        elif number < 0:
            fail("data_size_bytes", f"{raw_size}: a data size cannot be negative")
        else:
            size = int(number)
    processor = None
    raw_processor = cell("processor") if "processor" in header else None
    if raw_processor:
        if len(raw_processor) > 200 or not _CLASSIFIER.match(raw_processor):
            fail("processor", f"{_describe_cell(raw_processor)} is not a classifier name (Pkg::Core)")
        else:
            processor = raw_processor
    if len(errors) > before or None in (node, thread, board, core, period, cet, mips, ipc):
        return None
    columns = tuple(sorted(header.items(), key=lambda item: item[1]))
    return Measurement(
        filename, row, line, node, thread, board, core, period, cet, mips, ipc, size, processor, columns
    )


# =========================================================================== profiles


@dataclass
class ProfiledImplementation:
    """One PDM made from the measurements: the process implementation and its thread ones."""

    node: str  # the node's process type, qualified
    process: str  # the new process implementation, qualified
    threads: list[str]  # the new thread implementations, qualified
    rows: list[int]
    mips_budget: float
    reference_processor: str | None

    def as_dict(self) -> dict[str, Any]:
        return {
            "node": self.node,
            "process": self.process,
            "threads": list(self.threads),
            "rows": list(self.rows),
            "mips_budget": self.mips_budget,
            "reference_processor": self.reference_processor,
        }


@dataclass
class ProfileResult:
    """What :func:`build_profiles` / :func:`add_profiles` made: texts by file name, the PDMs."""

    texts: dict[str, str] = field(default_factory=dict)
    packages: list[str] = field(default_factory=list)
    implementations: list[ProfiledImplementation] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)

    def as_dict(self) -> dict[str, Any]:
        return {
            "files": [str(path) for path in self.files],
            "packages": list(self.packages),
            "implementations": [impl.as_dict() for impl in self.implementations],
        }


@dataclass
class _Node:
    """A node of the model: its process type, package and PIM (``T.impl``), and the PIM's threads
    as instantiated (values as analyses see them)."""

    ctype: EObject
    package: EObject
    pim: EObject
    threads: dict[str, EObject]  # lower-case subcomponent name -> subcomponent
    instances: dict[str, EObject]  # lower-case subcomponent name -> thread instance


@dataclass
class _Row:
    m: Measurement
    node: _Node
    sub: EObject
    thread_classifier: EObject  # what the PIM subcomponent is (an implementation or a type)
    thread_type: EObject
    port: str | None = None  # the data port data_size_bytes belongs to


@dataclass(frozen=True)
class _Expected:
    """What one row puts into a PDM, checked on the instance of the PDM before writing."""

    m: Measurement
    thread: str  # the thread subcomponent
    port: str | None


def _fail_all(errors: Sequence[RosaadlError], what: str = "problems") -> MeasurementError:
    """One error for a whole file: every problem, in file and line order, in ``errors``."""
    errors = sorted(
        errors,
        key=lambda e: (e.location.file or "", e.location.line or 0, e.location.column or 0),
    )
    first = errors[0]
    if len(errors) == 1 and isinstance(first, MeasurementError):
        first.errors = [first]
        return first
    listing = "\n".join(f"  {e}" for e in errors)
    exc = MeasurementError(f"{first.message}\n{len(errors)} {what}:\n{listing}", first.location)
    exc.errors = list(errors)
    return exc


class _Builder:
    """Resolves measurements against a model and builds the profile packages."""

    def __init__(self, workspace: EObject) -> None:
        from rosaadl.lookup import PropertyLookup

        self.model = workspace
        self.resolver = Resolver(workspace)
        self.lookup = PropertyLookup(workspace, self.resolver)
        self.errors: list[RosaadlError] = []
        self.warnings: list[Diagnostic] = []
        self._nodes: dict[int, _Node | None] = {}
        self._named: dict[str, tuple[list[EObject], str]] = {}
        self._node_failures: dict[int, str] = {}
        self._processes = [
            c
            for u in workspace.units
            if _is(u, "AadlPackage")
            for c in u.classifiers
            if _is(c, "ComponentType") and _word(c.category) == "process"
        ]

    # ------------------------------------------------------------------ nodes and threads

    def process_types(self, value: str) -> tuple[list[EObject], str]:
        """Process types ``value`` may name, and how it named them (cached)."""
        known = self._named.get(value)
        if known is None:
            known = self._named[value] = self._find_process_types(value)
        return known

    def _find_process_types(self, value: str) -> tuple[list[EObject], str]:
        resolver = self.resolver
        if "::" in value:
            found = resolver.classifier(value)
            if found is not None and _is(found, "ComponentType") and _word(found.category) == "process":
                return [found], "classifier"
            return [], "classifier"
        unit = resolver.unit(value)
        if unit is not None and _is(unit, "AadlPackage"):
            types = [c for c in self._processes if resolver.unit_of(c) is unit]
            with_pim = [c for c in types if self._pim(c) is not None]
            return (with_pim or types), "package"
        wanted = value.lower()
        named = [c for c in self._processes if (c.name or "").lower() == wanted]
        if named:
            return named, "process type"
        by_ros_name = []
        for ctype in self._processes:
            ros_name = self.lookup.python_value(ctype, "ROS_Properties::Node_Name")
            if isinstance(ros_name, str) and ros_name == value:
                by_ros_name.append(ctype)
        return by_ros_name, "ROS node name"

    def _pim(self, ctype: EObject) -> EObject | None:
        found = self.resolver.classifier(f"{ctype.name}.impl", ctype)
        return found if found is not None and _is(found, "ComponentImplementation") else None

    def node(self, m: Measurement) -> _Node | None:
        types, how = self.process_types(m.node)
        if not types:
            names = sorted(
                {self.resolver.qualified_name(c) for c in self._processes if self._pim(c) is not None},
                key=str.lower,
            )
            close = difflib.get_close_matches(m.node.lower(), [n.lower() for n in names], n=5, cutoff=0.5)
            shown = [n for n in names if n.lower() in close]
            shown += [n for n in names if n not in shown][: max(0, 12 - len(shown))]
            self.errors.append(
                m.error(
                    "node",
                    f"unknown node {m.node!r}: not a node of the library or of the inputs "
                    f"(nodes: {', '.join(shown)}{', ...' if len(shown) < len(names) else ''})",
                )
            )
            return None
        if len(types) > 1:
            names = sorted(self.resolver.qualified_name(c) for c in types)
            self.errors.append(
                m.error(
                    "node",
                    f"{m.node!r} ({how}) names several nodes: {', '.join(names)}; "
                    "write the node as Pkg::process_type",
                )
            )
            return None
        ctype = types[0]
        key = id(ctype)
        if key in self._nodes:
            known = self._nodes[key]
            if known is None:
                self.errors.append(m.error("node", self._node_failures[key]))
            return known
        pim = self._pim(ctype)
        qualified = self.resolver.qualified_name(ctype)
        if pim is None:
            message = (
                f"node {qualified} has no platform-independent implementation {ctype.name}.impl "
                "for a PDM to extend"
            )
            return self._node_failed(key, m, message)
        try:
            node = self._instantiate_pim(ctype, pim)
        except RosaadlError as exc:
            return self._node_failed(
                key, m, f"the PIM {self.resolver.qualified_name(pim)} does not instantiate: {exc}"
            )
        self._nodes[key] = node
        return node

    def _node_failed(self, key: int, m: Measurement, message: str) -> None:
        self._nodes[key] = None
        self._node_failures[key] = message
        self.errors.append(m.error("node", message))
        return None

    def _instantiate_pim(self, ctype: EObject, pim: EObject) -> _Node:
        from rosaadl.transforms.instantiate import instantiate

        threads = {
            (sub.name or "").lower(): sub
            for sub in self.resolver.subcomponents(pim)
            if _word(sub.category) == "thread"
        }
        notes: list[Diagnostic] = []
        instance = instantiate(
            self.model, self.resolver.qualified_name(pim), resolver=self.resolver, diagnostics=notes
        )
        try:
            instances = {}
            for child in instance.componentInstances:
                key = (child.name or "").lower()
                if key in threads and key not in instances:
                    instances[key] = child
        finally:
            self.model.instances.remove(instance)
        unit = self.resolver.unit_of(ctype)
        return _Node(ctype, unit, pim, threads, instances)

    def thread(self, m: Measurement, node: _Node) -> _Row | None:
        resolver = self.resolver
        sub = node.threads.get(m.thread.lower())
        if sub is None:
            matches = []
            for candidate in node.threads.values():
                classifier = resolver.subcomponent_classifier(candidate)
                ctype = resolver.component_type(classifier)
                if ctype is not None and (ctype.name or "").lower() == m.thread.lower():
                    matches.append(candidate)
            if len(matches) > 1:
                names = ", ".join(s.name for s in matches)
                self.errors.append(
                    m.error(
                        "thread",
                        f"{m.thread!r} is the type of several threads of "
                        f"{resolver.qualified_name(node.pim)} ({names}); name the thread",
                    )
                )
                return None
            sub = matches[0] if matches else None
        if sub is None:
            names = ", ".join(s.name for s in node.threads.values()) or "none"
            self.errors.append(
                m.error(
                    "thread",
                    f"unknown thread {m.thread!r}: {resolver.qualified_name(node.pim)} "
                    f"has the threads {names}",
                )
            )
            return None
        classifier = resolver.subcomponent_classifier(sub)
        ctype = resolver.component_type(classifier)
        if classifier is None or ctype is None:
            self.errors.append(
                m.error(
                    "thread",
                    f"thread {sub.name} of {resolver.qualified_name(node.pim)} has no "
                    "thread classifier that a PDM could extend",
                )
            )
            return None
        return _Row(m, node, sub, classifier, ctype)

    # ------------------------------------------------------------------ reference processors

    def _processor(self, m: Measurement) -> EObject | None:
        found = self.resolver.classifier(m.processor)
        if (
            found is None
            or not _is(found, "ComponentClassifier")
            or _word(found.category)
            not in (
                "processor",
                "virtual processor",
            )
        ):
            what = (
                "not found"
                if found is None
                else f"a {_word(getattr(found, 'category', ''))}, not a processor"
            )
            self.errors.append(m.error("processor", f"{m.processor}: {what} in the library or the inputs"))
            return None
        return found

    def _known_processor(self, pdm: str) -> tuple[EObject | None, list[str]]:
        """The Reference_Processor the model's process PDMs named ``*.<pdm>`` agree on."""
        found: dict[str, EObject] = {}
        suffix = "." + pdm.lower()
        for unit in self.model.units:
            if not _is(unit, "AadlPackage"):
                continue
            for impl in unit.classifiers:
                if not _is(impl, "ComponentImplementation") or not (impl.name or "").lower().endswith(suffix):
                    continue
                if _word(impl.category) != "process":
                    continue
                for pa in impl.ownedPropertyAssociations:
                    prop = self.resolver.association_property(pa)
                    if prop is None or (prop.name or "").lower() != "reference_processor" or pa.appliesTo:
                        continue
                    for mv in pa.ownedValues:
                        value = mv.value
                        if value is not None and value.eClass.name == "ClassifierValue":
                            target = self.resolver.classifier(value.classifier, impl)
                            if target is not None:
                                found.setdefault(self.resolver.qualified_name(target), target)
        if len(found) == 1:
            return next(iter(found.values())), []
        return None, sorted(found)

    # ------------------------------------------------------------------ building

    def build(
        self, measurements: Sequence[Measurement], existing: dict[str, EObject]
    ) -> tuple[list[EObject], list[ProfiledImplementation], dict[str, list[_Expected]]]:
        rows = []
        for m in measurements:
            node = self.node(m)
            if node is None:
                continue
            row = self.thread(m, node)
            if row is not None:
                rows.append(row)
        self._check_duplicates(rows)
        by_node: dict[int, list[_Row]] = {}
        for row in rows:
            by_node.setdefault(id(row.node.ctype), []).append(row)
        units = []
        implementations: list[ProfiledImplementation] = []
        rows_of: dict[str, list[_Expected]] = {}
        for group in sorted(
            by_node.values(), key=lambda g: self.resolver.qualified_name(g[0].node.ctype).lower()
        ):
            unit = self._package(group, existing, implementations, rows_of)
            if unit is not None:
                units.append(unit)
        return units, implementations, rows_of

    def _check_duplicates(self, rows: list[_Row]) -> None:
        seen: dict[tuple[int, str, str], Measurement] = {}
        for row in rows:
            key = (id(row.node.ctype), (row.sub.name or "").lower(), row.m.pdm.lower())
            first = seen.get(key)
            if first is None:
                seen[key] = row.m
                continue
            self.errors.append(
                row.m.error(
                    "node, thread, board, core",
                    f"duplicate measurement of thread {row.sub.name} of "
                    f"{self.resolver.qualified_name(row.node.ctype)} on {row.m.pdm}: "
                    f"row {first.row} (line {first.line}) already gives it",
                )
            )

    def _package(
        self,
        group: list[_Row],
        existing: dict[str, EObject],
        implementations: list[ProfiledImplementation],
        rows_of: dict[str, list[_Expected]],
    ) -> EObject | None:
        resolver = self.resolver
        node = group[0].node
        ctype = node.ctype
        package_name = f"{node.package.name}{PROFILE_SUFFIX}"
        if resolver.unit(package_name) is not None and package_name.lower() not in existing:
            other = resolver.unit(package_name)
            self.errors.append(
                group[0].m.error(
                    "node",
                    f"the profiles of {resolver.qualified_name(ctype)} go to package {package_name}, "
                    f"but the library or the inputs already hold a unit of that name ({other.sourceFile})",
                )
            )
            return None
        before = len(self.errors)
        withs: list[str] = [node.package.name]
        aliases: dict[str, tuple[str, str]] = {}  # lower alias -> (alias, target)

        def alias_for(target_type: EObject, m: Measurement, column: str) -> str | None:
            alias = target_type.name
            target = resolver.qualified_name(target_type)
            known = aliases.get(alias.lower())
            if known is not None and known[1].lower() != target.lower():
                self.errors.append(
                    m.error(
                        column,
                        f"{target} and {known[1]} have the same name {alias}; one package of "
                        "profiles cannot name both",
                    )
                )
                return None
            aliases[alias.lower()] = (alias, target)
            owner = resolver.unit_of(target_type)
            if owner is not None and owner.name not in withs:
                withs.append(owner.name)
            return alias

        node_alias = alias_for(ctype, group[0].m, "node")
        by_pdm: dict[str, list[_Row]] = {}
        for row in group:
            by_pdm.setdefault(row.m.pdm.lower(), []).append(row)
        classifiers: list[EObject] = []
        made: list[ProfiledImplementation] = []
        for key in sorted(by_pdm):
            pdm_rows = by_pdm[key]
            result = self._pdm(node, node_alias, pdm_rows, alias_for, withs)
            if result is not None:
                impls, summary = result
                classifiers.extend(impls)
                made.append(summary)
                rows_of[summary.process.lower()] = [_Expected(r.m, r.sub.name, r.port) for r in pdm_rows]
        if len(self.errors) > before:
            return None
        unit = _model.new(
            "AadlPackage",
            name=package_name,
            withs=withs,
            renamings=[
                _model.new(
                    "Renaming",
                    name=alias,
                    kind="classifier",
                    target=target,
                    category=_word(resolver.classifier(target).category),
                )
                for alias, target in aliases.values()
            ],
        )
        old = existing.get(package_name.lower())
        if old is not None:
            classifiers = self._merge(unit, old, classifiers, set(by_pdm))
        unit.classifiers.extend(sorted(classifiers, key=_pdm_order))
        implementations.extend(made)
        return unit

    def _merge(self, unit: EObject, old: EObject, new: list[EObject], pdms: set[str]) -> list[EObject]:
        """Keep what an earlier profiles package held, except the PDMs measured again; the
        classifiers of the new package."""
        made = {(c.name or "").lower(): c for c in new}
        kept = []
        for classifier in list(old.classifiers):
            name = (classifier.name or "").lower()
            if name in made or name.rpartition(".")[2] in pdms:
                replacement = made.get(name)
                if replacement is None or _signature(replacement) != _signature(classifier):
                    self.warnings.append(
                        Diagnostic(
                            "warning",
                            f"{old.name}::{classifier.name} of the earlier profiles is replaced by the "
                            "new measurements",
                            Location(file=old.sourceFile or None, line=classifier.line or None),
                        )
                    )
                continue
            kept.append(classifier)
        for with_name in old.withs:
            if with_name.lower() not in {w.lower() for w in unit.withs}:
                unit.withs.append(with_name)
        known = {(r.name or "").lower() for r in unit.renamings}
        for ren in list(old.renamings):
            if (ren.name or "").lower() not in known:
                unit.renamings.append(ren)
        return [*kept, *new]

    def _pdm(self, node: _Node, node_alias, rows: list[_Row], alias_for, withs: list[str]):
        resolver = self.resolver
        first = rows[0].m
        pdm = first.pdm
        before = len(self.errors)
        for row in rows[1:]:
            for column, a, b in (("mips_raw", first.mips_raw, row.m.mips_raw), ("ipc", first.ipc, row.m.ipc)):
                if a != b:
                    self.errors.append(
                        row.m.error(
                            column,
                            f"{b} differs from row {first.row} ({a}): the {column} of "
                            f"{resolver.qualified_name(node.ctype)} on {pdm} is one measurement of "
                            "the whole node",
                        )
                    )
        processors = {r.m.processor.lower(): r.m for r in rows if r.m.processor}
        if len(processors) > 1:
            later = list(processors.values())[1]
            self.errors.append(
                later.error("processor", f"{later.processor} differs from another row of {pdm}")
            )
        reference = None
        if processors:
            reference = self._processor(next(iter(processors.values())))
        else:
            reference, candidates = self._known_processor(pdm)
            if reference is None:
                reason = (
                    f"the library's {pdm} PDMs name several ({', '.join(candidates)})"
                    if candidates
                    else f"no PDM of the library or the inputs is named {pdm}"
                )
                self.warnings.append(
                    Diagnostic(
                        "warning",
                        f"row {first.row}: no Reference_Processor for "
                        f"{resolver.qualified_name(node.ctype)}.{pdm}: {reason}; "
                        "give the core's classifier in a processor column",
                        first.where("board"),
                    )
                )
        existing = resolver.classifier(f"{node.ctype.name}.{pdm}", node.ctype)
        if existing is not None:
            self.warnings.append(
                Diagnostic(
                    "warning",
                    f"row {first.row}: {resolver.qualified_name(existing)} already exists; the new PDM is a "
                    f"separate implementation in {node.package.name}{PROFILE_SUFFIX}",
                    first.where("board"),
                )
            )
        # thread PDMs, one per thread type
        threads: dict[str, tuple[EObject, _Row]] = {}
        refinements = []
        order = {key: index for index, key in enumerate(node.threads)}
        for row in sorted(rows, key=lambda r: order.get((r.sub.name or "").lower(), 0)):
            alias = alias_for(row.thread_type, row.m, "thread")
            if alias is None:
                continue
            impl = self._thread_pdm(row, alias, pdm)
            if impl is None:
                continue
            key = (impl.name or "").lower()
            shared = threads.get(key)
            if shared is not None:
                if _signature(shared[0]) != _signature(impl):
                    self.errors.append(
                        row.m.error(
                            "thread",
                            f"threads {shared[1].sub.name} and {row.sub.name} share the type "
                            f"{alias}, so they share the PDM {impl.name}; their measurements must agree "
                            f"(row {shared[1].m.row} differs)",
                        )
                    )
                    continue
            else:
                threads[key] = (impl, row)
            refinements.append(
                _model.new(
                    "Subcomponent", name=row.sub.name, category="thread", classifier=impl.name, refined=True
                )
            )
        if len(self.errors) > before or node_alias is None:
            return None
        budget = first.mips_budget
        properties = [
            _association("SEI::MIPSBudget", _real(budget, "MIPS")),
            _association("ROS_Profiling::Raw_MIPS", _real(first.mips_raw, "MIPS")),
            _association("ROS_Profiling::IPC", _real(first.ipc, None)),
        ]
        for name in ("SEI", "ROS_Profiling"):
            if name not in withs:
                withs.append(name)
        reference_name = None
        if reference is not None:
            reference_name = resolver.qualified_name(reference)
            properties.append(
                _association("Reference_Processor", _model.new("ClassifierValue", classifier=reference_name))
            )
            owner = resolver.unit_of(reference)
            if owner is not None and owner.name not in withs:
                withs.append(owner.name)
        process = _model.new(
            "ComponentImplementation",
            name=f"{node_alias}.{pdm}",
            type=node_alias,
            category="process",
            extended=resolver.qualified_name(node.pim),
            subcomponents=refinements,
            ownedPropertyAssociations=properties,
        )
        package = f"{node.package.name}{PROFILE_SUFFIX}"
        summary = ProfiledImplementation(
            node=resolver.qualified_name(node.ctype),
            process=f"{package}::{process.name}",
            threads=[f"{package}::{impl.name}" for impl, _ in threads.values()],
            rows=[r.m.row for r in rows],
            mips_budget=float(budget),
            reference_processor=reference_name,
        )
        return [process, *(impl for impl, _ in threads.values())], summary

    def _thread_pdm(self, row: _Row, alias: str, pdm: str) -> EObject | None:
        resolver = self.resolver
        m = row.m
        instance = row.node.instances.get((row.sub.name or "").lower())
        properties = [_association("Compute_Execution_Time", _time_range(m.cet_ns))]
        pim_period = _ns(_instance_value(instance, "Period"))
        if pim_period != m.period_ns:
            properties.append(_association("Period", _time(m.period_ns)))
            if pim_period is not None:
                self.warnings.append(
                    Diagnostic(
                        "warning",
                        f"row {m.row}, column period_us: {_us_text(m.period_ns)} differs from the Period "
                        f"of {row.sub.name} in the PIM ({_us_text(pim_period)}); the PDM thread sets its "
                        "own Period",
                        m.where("period_us"),
                    )
                )
        if m.data_size is not None:
            port = self._data_port(row, instance)
            if port is None:
                return None
            size = _instance_value(port, "Data_Size")
            current = _bytes(size)
            row.port = port.name
            if current != m.data_size:
                properties.append(
                    _association(
                        "Data_Size",
                        _model.new("IntegerValue", value=m.data_size, unit="Bytes"),
                        applies_to=[port.name],
                    )
                )
        extended = None
        if _is(row.thread_classifier, "ComponentImplementation"):
            extended = resolver.qualified_name(row.thread_classifier)
        return _model.new(
            "ComponentImplementation",
            name=f"{alias}.{pdm}",
            type=alias,
            category="thread",
            extended=extended,
            ownedPropertyAssociations=properties,
        )

    def _data_port(self, row: _Row, instance: EObject | None) -> EObject | None:
        ports = [
            fi
            for fi in (instance.featureInstances if instance is not None else ())
            if fi.category is not None and fi.category.name in _DATA_PORTS
        ]
        outgoing = [p for p in ports if _word(p.direction) in ("out", "in out")]
        incoming = [p for p in ports if _word(p.direction) == "in"]
        candidates = outgoing or incoming
        if len(candidates) == 1:
            return candidates[0]
        names = ", ".join(p.name for p in candidates) or "none"
        self.errors.append(
            row.m.error(
                "data_size_bytes",
                f"thread {row.sub.name} has {len(candidates)} {'outgoing' if outgoing else 'incoming'} data "
                f"ports ({names}); the data size must belong to exactly one (leave the cell empty)",
            )
        )
        return None


def _signature(impl: EObject) -> tuple:
    """What a classifier says, for comparing two of them (names, extends, members, values)."""
    return (
        (impl.name or "").lower(),
        (impl.extended or "").lower(),
        tuple(
            ((sub.name or "").lower(), (sub.classifier or "").lower())
            for sub in getattr(impl, "subcomponents", ())
        ),
        tuple(
            (
                (pa.property or "").lower(),
                tuple(t.lower() for t in pa.appliesTo),
                tuple(format_value(mv.value) for mv in pa.ownedValues),
            )
            for pa in impl.ownedPropertyAssociations
        ),
    )


def _pdm_order(classifier: EObject) -> tuple[str, int, str]:
    """Profiles grouped by board and core, the process implementation before its threads."""
    name = (classifier.name or "").lower()
    category = _word(getattr(classifier, "category", "")) if _is(classifier, "ComponentClassifier") else ""
    return (name.rpartition(".")[2], 0 if category == "process" else 1, name)


def _instance_value(obj: EObject | None, name: str) -> Any:
    from rosaadl.properties import property_value

    return property_value(obj, name) if obj is not None else None


def _ns(value: Any) -> int | None:
    from rosaadl.errors import ModelError
    from rosaadl.units import Quantity

    if not isinstance(value, Quantity):
        return None
    try:
        converted = value.to("ns")
    except ModelError:
        return None
    return int(converted) if float(converted).is_integer() else None


def _bytes(value: Any) -> int | None:
    from rosaadl.errors import ModelError
    from rosaadl.units import Quantity

    if not isinstance(value, Quantity):
        return None
    try:
        converted = value.to("Bytes")
    except ModelError:
        return None
    return int(converted) if float(converted).is_integer() else None


def _us_text(ns: int) -> str:
    return f"{ns // 1000} us" if ns % 1000 == 0 else f"{Decimal(ns) / 1000} us"


def _time(ns: int) -> EObject:
    if ns % 1000 == 0:
        return _model.new("IntegerValue", value=ns // 1000, unit="us")
    return _model.new("IntegerValue", value=ns, unit="ns")


def _time_range(ns: int) -> EObject:
    return _model.new("RangeValue", minimum=_time(ns), maximum=_time(ns))


def _real(value: Decimal, unit: str | None) -> EObject:
    return _model.new("RealValue", value=float(value), unit=unit)


def _association(prop: str, value: EObject, applies_to: Sequence[str] = ()) -> EObject:
    return _model.new(
        "PropertyAssociation",
        property=prop,
        appliesTo=list(applies_to),
        ownedValues=[_model.new("ModalPropertyValue", value=value)],
    )


def build_profiles(
    workspace: EObject,
    measurements: Sequence[Measurement],
    *,
    existing: dict[str, EObject] | None = None,
) -> tuple[list[EObject], list[ProfiledImplementation], list[RosaadlError], list[Diagnostic]]:
    """The profile packages for ``measurements`` resolved against ``workspace``:
    ``(packages, implementations, errors, warnings)``; no package when there are errors.

    ``existing`` maps lower-case package names to profile packages of an earlier run: what they
    hold is kept, except the PDMs (``*.<board>_<core>``) measured again.
    """
    builder = _Builder(workspace)
    units, implementations, _ = builder.build(measurements, existing or {})
    if builder.errors:
        return [], [], builder.errors, builder.warnings
    return units, implementations, [], builder.warnings


def _header_comment(unit: EObject, source_name: str, merged: bool) -> str:
    nodes = unit.name.removesuffix(PROFILE_SUFFIX)
    source = f"{source_name} and earlier measurements" if merged else source_name
    return (
        f"-- {unit.name}: platform-dependent implementations (PDM) of the nodes\n"
        f"-- of {nodes}, made by `rosaadl library add-profile` from {source}.\n"
        "-- Each PDM extends the node's PIM; its threads carry the measured\n"
        "-- Compute_Execution_Time, the process its SEI::MIPSBudget (= Raw_MIPS / IPC).\n\n"
    )


def _existing_outputs(
    workspace: EObject, out_dir: Path, names: Iterable[str]
) -> tuple[dict[str, EObject], list[RosaadlError]]:
    """Profile packages already written in ``out_dir`` (read from there) or given as inputs."""
    from rosaadl.exporters.aadl_text import unit_file_name
    from rosaadl.importers.aadl_text import read_string

    found: dict[str, EObject] = {}
    errors: list[RosaadlError] = []
    for name in names:
        unit = _model.find_unit(workspace, name)
        if unit is not None:
            found[name.lower()] = unit
            continue
        probe = _model.new("AadlPackage", name=name)
        target = out_dir / unit_file_name(probe)
        if not target.is_file():
            continue
        try:
            scratch = read_string(target.read_bytes(), str(target))
        except RosaadlError as exc:
            errors.append(exc)
            continue
        except OSError as exc:
            errors.append(ParseError(f"cannot read the file: {exc.strerror or exc}", file=str(target)))
            continue
        units = list(scratch.units)
        if len(units) != 1 or (units[0].name or "").lower() != name.lower():
            held = ", ".join(u.name for u in units) or "nothing"
            errors.append(
                ExportError(
                    f"would replace {target.name}, which holds {held}, not package {name}",
                    file=str(target),
                )
            )
            continue
        found[name.lower()] = units[0]
    return found, errors


def add_profiles(
    measurements: str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    *,
    inputs: Iterable[str | os.PathLike[str]] = (),
    warnings: list[Diagnostic] | None = None,
) -> ProfileResult:
    """Turn a measurements CSV into profile packages written into ``out_dir``.

    ``inputs`` are AADL files or folders read with the library (nodes that are not in the
    library). Raises :class:`MeasurementError` listing every problem of the file (nothing is
    written then); reader errors of the inputs propagate as they are.
    """
    from rosaadl.exporters.aadl_text import write_units

    csv_path = Path(measurements)
    target_dir = Path(out_dir)
    try:
        with csv_path.open("rb") as handle:  # no more than the limit is read, whatever the file
            data = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ParseError(f"cannot read the measurements: {exc.strerror or exc}", file=str(csv_path)) from None
    rows, errors, notes = parse_measurements(data, str(csv_path))
    if target_dir.exists() and not target_dir.is_dir():
        errors.append(MeasurementError("the output exists and is not a folder", file=str(target_dir)))
    notes_all: list[Diagnostic] = list(notes)
    read_notes: list[Diagnostic] = []
    workspace = read_library(inputs, warnings=read_notes)
    notes_all.extend(read_notes)
    builder = _Builder(workspace)
    units: list[EObject] = []
    implementations: list[ProfiledImplementation] = []
    rows_of: dict[str, list[_Expected]] = {}
    existing: dict[str, EObject] = {}
    if rows:
        # which packages the rows go to, to find earlier profiles in the output folder
        names = []
        for m in rows:
            types, _ = builder.process_types(m.node)
            if len(types) == 1:
                unit = builder.resolver.unit_of(types[0])
                names.append(f"{unit.name}{PROFILE_SUFFIX}")
        existing, problems = _existing_outputs(workspace, target_dir, sorted(set(names), key=str.lower))
        errors.extend(problems)  # type: ignore[arg-type]
        units, implementations, rows_of = builder.build(rows, existing)
        errors.extend(builder.errors)  # type: ignore[arg-type]
        notes_all.extend(builder.warnings)
    if errors:
        if warnings is not None:
            warnings.extend(notes_all)
        raise _fail_all(errors)
    merged = {name.lower() for name in existing}
    texts = {
        name: _header_comment(unit, csv_path.name, unit.name.lower() in merged) + text
        for (name, text), unit in zip(write_units(units).items(), units, strict=True)
    }
    targets = {name: _safe_target(target_dir, name) for name in texts}
    _verify(workspace, units, texts, targets, implementations, rows_of, notes_all)
    from rosaadl import fileio

    written = []
    for name, text in texts.items():
        try:
            fileio.atomic_write_text(targets[name], text)
        except OSError as exc:
            raise ExportError(
                f"cannot write the file: {exc.strerror or exc}", file=str(targets[name])
            ) from None
        written.append(targets[name])
    log.info("wrote %d profile package(s) to %s", len(written), target_dir)
    if warnings is not None:
        warnings.extend(notes_all)
    return ProfileResult(texts, [u.name for u in units], implementations, notes_all, written)


def _safe_target(out_dir: Path, name: str) -> Path:
    from rosaadl import fileio

    return fileio.safe_join(out_dir, name)


def _verify(
    workspace: EObject,
    units: list[EObject],
    texts: dict[str, str],
    targets: dict[str, Path],
    implementations: list[ProfiledImplementation],
    rows_of: dict[str, list[_Expected]],
    notes: list[Diagnostic],
) -> None:
    """Read the texts back into the workspace, resolve, instantiate each new PDM and check that it
    carries the measured values; any difference is an error and nothing is written."""
    from rosaadl.importers.aadl_text import read_string
    from rosaadl.transforms.instantiate import instantiate

    for unit in units:
        old = _model.find_unit(workspace, unit.name)
        if old is not None:
            workspace.units.remove(old)
    for name, text in texts.items():
        read_string(text, str(targets[name]), model=workspace)
    resolver = Resolver(workspace)
    problems = [d for d in resolver.check() if d.severity == "error"]
    if problems:
        listing = "\n".join(f"  {d}" for d in problems)
        raise ExportError(f"the profile packages do not resolve (a defect of rosaadl):\n{listing}")
    errors: list[RosaadlError] = []
    for impl in implementations:
        diagnostics: list[Diagnostic] = []
        instance = instantiate(workspace, impl.process, resolver=resolver, diagnostics=diagnostics)
        try:
            notes.extend(d for d in diagnostics if d.severity == "warning")
            errors.extend(_check_values(instance, impl, rows_of.get(impl.process.lower(), [])))
        finally:
            workspace.instances.remove(instance)
    if errors:
        raise _fail_all(errors)


def _check_values(
    instance: EObject, impl: ProfiledImplementation, expected: list[_Expected]
) -> list[RosaadlError]:
    """Differences between what the rows say and what the instance of the new PDM carries."""
    from rosaadl.properties import Range
    from rosaadl.units import Quantity

    errors: list[RosaadlError] = []
    if not expected:
        return errors
    budget = _instance_value(instance, "SEI::MIPSBudget")
    if not isinstance(budget, Quantity) or abs(float(budget.to("MIPS")) - impl.mips_budget) > 1e-9:
        errors.append(
            expected[0].m.error(
                "mips_raw",
                f"{impl.process} does not carry SEI::MIPSBudget => {impl.mips_budget} MIPS (it has {budget})",
            )
        )
    for item in expected:
        m = item.m
        thread = next(
            (c for c in instance.componentInstances if (c.name or "").lower() == item.thread.lower()), None
        )
        if thread is None:
            errors.append(m.error("thread", f"{impl.process} has no thread {item.thread}"))
            continue
        overridden = "; a contained property association of the PIM overrides it"
        cet = _instance_value(thread, "Compute_Execution_Time")
        if not isinstance(cet, Range) or _ns(cet.minimum) != m.cet_ns or _ns(cet.maximum) != m.cet_ns:
            errors.append(
                m.error(
                    "cet_us",
                    f"thread {thread.name} of {impl.process} does not carry Compute_Execution_Time => "
                    f"{_us_text(m.cet_ns)} .. {_us_text(m.cet_ns)} (it has {cet}){overridden}",
                )
            )
        period = _instance_value(thread, "Period")
        if _ns(period) != m.period_ns:
            errors.append(
                m.error(
                    "period_us",
                    f"thread {thread.name} of {impl.process} has the Period {period}, "
                    f"not {_us_text(m.period_ns)}{overridden}",
                )
            )
        if item.port is not None and m.data_size is not None:
            port = next(
                (f for f in thread.featureInstances if (f.name or "").lower() == item.port.lower()), None
            )
            size = _instance_value(port, "Data_Size")
            if _bytes(size) != m.data_size:
                errors.append(
                    m.error(
                        "data_size_bytes",
                        f"port {item.port} of thread {thread.name} of {impl.process} has the Data_Size "
                        f"{size}, not {m.data_size} Bytes{overridden}",
                    )
                )
    return errors

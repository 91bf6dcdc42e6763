"""AADL v2 text (SAE AS5506C) into the declarative AADL model (``metamodels/aadl.ecore``).

:func:`read_string` reads the packages and property sets of one text into an ``AadlModel``;
:func:`read_files` reads files and folders (``.aadl``/``.aadl2``, folders searched recursively in
sorted order) together with the component library of this project (``library_files``), then
checks names, units and enumeration literals across all of them.

The text is parsed by :mod:`rosaadl.importers.aadl_syntax` (a deterministic LALR(1) grammar);
this module walks the tree once and builds the model objects with
:class:`rosaadl.bulk.FastFactory` (no pyecore notifications or per-value checks: the values are
typed by construction).  What the text says is kept: names and references exactly
as written (``Timing_Properties::Period``, ``ros_data::Image.rgb``, ``a.b[2].c``), every value
form, ``line``/``column`` on every element and ``sourceFile`` on every unit.  Only comments and
layout are lost.  Constructs that the metamodel keeps as text:

* prototypes: a ``Prototype`` with ``text`` = what follows ``name:`` (and ``refined to``), e.g.
  ``"data Base_Types::Integer"``; prototypes are kept but not interpreted (a warning says so);
* prototype bindings: their source text in parentheses, ``"(p => data D)"``;
* array element implementations: ``"A.impl"`` or ``"A.impl (p => data D)"``;
* array dimensions: ``"3"``, ``"Pkg::Size"`` or ``""`` for ``[]``;
* annex subclauses and libraries: ``text`` is exactly what lies between ``{**`` and ``**}``
  (``None`` for ``annex X none;``);
* mode references in ``in modes``: ``"m"`` or ``"m => n"``; connection ends and triggers
  ``processor.x`` / ``self.x`` as written; ``applies to (all)`` is ``["all"]``.

Values: integers (based ``16#FF#``, exponents ``1e3``, underscores) become Python ints and must
fit the metamodel's 64-bit ``ELong``; reals become floats; strings are unescaped (``""`` and
``\\"`` are ``"``); ``-X`` on a named constant is an ``OperationValue`` ``-``, as are ``not``,
``and`` and ``or``.

Errors are located (file:line:column): syntax errors and literals out of range
(:class:`AadlSyntaxError`); the legality rules the grammar leaves to the builder
(:class:`ValidationError`, every one found in the text in one error: which subcomponent and
feature categories a component category may hold, as AS5506C's containment rules say
(:data:`SUBCOMPONENTS_ALLOWED`, :data:`FEATURES_ALLOWED`), which connection kinds, calls and
flows it may have, an implementation of another category than its type, ``end`` names, unit
conversions); and, in :func:`read_files`, the names, units and enumeration literals that do not
resolve (:class:`NameResolutionError`, every one in one error).  A name declared twice in one
namespace is a warning (real, tool-generated models have them; look-ups find the first).
"""

from __future__ import annotations

import bisect
import functools
import logging
import math
import os
import re
from collections.abc import Callable, Iterable, Sequence
from importlib import resources
from pathlib import Path
from typing import Any

from lark import Token, Tree
from pyecore.ecore import EObject

from rosaadl import metamodels
from rosaadl.bulk import FastBuilder, FastFactory, FeatureSlot, gc_paused
from rosaadl.errors import (
    AadlSyntaxError,
    Diagnostic,
    Location,
    ModelError,
    NameResolutionError,
    ParseError,
    RosaadlError,
    ValidationError,
)
from rosaadl.importers.aadl_syntax import parse

__all__ = [
    "read_string",
    "read_files",
    "library_files",
    "AADL_SUFFIXES",
    "FEATURES_ALLOWED",
    "SUBCOMPONENTS_ALLOWED",
    "CONNECTIONS_ALLOWED",
    "CALLS_ALLOWED",
]

log = logging.getLogger(__name__)

#: File name suffixes searched for in folders (compared case-insensitively).
AADL_SUFFIXES: tuple[str, ...] = (".aadl", ".aadl2")

#: How deeply values and property types may nest (lists of lists, records, boolean terms).
_MAX_NESTING = 64

_ELONG_MIN = -(2**63)
_ELONG_MAX = 2**63 - 1

# --------------------------------------------------------------------------- legality tables
# SAE AS5506C sections 4-7, as OSATE's grammar states them: which feature kinds a component type
# of each category may declare, which subcomponent categories and which connection kinds an
# implementation may hold.  Virtual bus access goes wherever bus access does.

_PORTS = frozenset({"dataPort", "eventPort", "eventDataPort"})
_BUS_ACCESS = frozenset({"busAccess", "virtualBusAccess"})
_COMMON_FEATURES = frozenset({"featureGroup", "abstractFeature"})
_CALLABLE = frozenset({"subprogramAccess", "subprogramGroupAccess"})
_SOFTWARE_FEATURES = _PORTS | _COMMON_FEATURES | _CALLABLE | {"dataAccess"}
_PLATFORM_FEATURES = _PORTS | _COMMON_FEATURES | _CALLABLE | _BUS_ACCESS

FEATURES_ALLOWED: dict[str, frozenset[str]] = {
    "abstract": _SOFTWARE_FEATURES | _BUS_ACCESS,
    "system": _SOFTWARE_FEATURES | _BUS_ACCESS,
    "process": _SOFTWARE_FEATURES,
    "thread group": _SOFTWARE_FEATURES,
    "thread": _SOFTWARE_FEATURES,
    "subprogram": (_SOFTWARE_FEATURES - {"dataPort"}) | {"parameter"},
    "subprogram group": _COMMON_FEATURES | _CALLABLE,
    "data": _COMMON_FEATURES | _CALLABLE | {"dataAccess"},
    "processor": _PLATFORM_FEATURES,
    "virtual processor": _PLATFORM_FEATURES,
    "device": _PLATFORM_FEATURES,
    "memory": _PORTS | _COMMON_FEATURES | _BUS_ACCESS,
    "bus": _PORTS | _COMMON_FEATURES | _BUS_ACCESS,
    "virtual bus": _PORTS | _COMMON_FEATURES,
}

_ALL_CATEGORIES = frozenset(
    {
        "abstract",
        "bus",
        "data",
        "device",
        "memory",
        "process",
        "processor",
        "subprogram",
        "subprogram group",
        "system",
        "thread",
        "thread group",
        "virtual bus",
        "virtual processor",
    }
)
_SOFTWARE_PARTS = frozenset({"data", "subprogram", "subprogram group", "abstract"})

SUBCOMPONENTS_ALLOWED: dict[str, frozenset[str]] = {
    "abstract": _ALL_CATEGORIES,
    "system": _ALL_CATEGORIES - {"thread", "thread group"},
    "process": _SOFTWARE_PARTS | {"thread", "thread group"},
    "thread group": _SOFTWARE_PARTS | {"thread", "thread group"},
    "thread": _SOFTWARE_PARTS,
    "subprogram": frozenset({"data", "subprogram", "abstract"}),
    "subprogram group": _SOFTWARE_PARTS,
    "data": frozenset({"data", "subprogram", "abstract"}),
    "processor": frozenset({"memory", "bus", "virtual bus", "virtual processor", "abstract"}),
    "virtual processor": frozenset({"virtual processor", "virtual bus", "abstract"}),
    "device": frozenset({"data", "bus", "virtual bus", "abstract"}),
    "memory": frozenset({"memory", "bus", "abstract"}),
    "bus": frozenset({"virtual bus", "abstract"}),
    "virtual bus": frozenset({"virtual bus", "abstract"}),
}

_STRUCTURAL_CONNECTIONS = frozenset({"access", "feature group", "feature"})
CONNECTIONS_ALLOWED: dict[str, frozenset[str]] = {
    "abstract": _STRUCTURAL_CONNECTIONS | {"port", "parameter"},
    "thread": _STRUCTURAL_CONNECTIONS | {"port", "parameter"},
    "subprogram": _STRUCTURAL_CONNECTIONS | {"port", "parameter"},
    "system": _STRUCTURAL_CONNECTIONS | {"port"},
    "process": _STRUCTURAL_CONNECTIONS | {"port"},
    "thread group": _STRUCTURAL_CONNECTIONS | {"port"},
    "processor": _STRUCTURAL_CONNECTIONS | {"port"},
    "virtual processor": _STRUCTURAL_CONNECTIONS | {"port"},
    "device": _STRUCTURAL_CONNECTIONS | {"port"},
    "subprogram group": _STRUCTURAL_CONNECTIONS,
    "memory": _STRUCTURAL_CONNECTIONS,
    "data": _STRUCTURAL_CONNECTIONS,
    "bus": frozenset(),
    "virtual bus": frozenset(),
}

#: Implementations with subprogram call sequences.
CALLS_ALLOWED = frozenset({"abstract", "thread", "subprogram"})
#: Types without flow specifications and implementations without flows.
_NO_FLOW_SPECS = frozenset({"memory", "bus", "virtual bus"})
_NO_FLOW_IMPLS = frozenset({"subprogram group", "memory", "bus", "virtual bus"})
#: Types without modes.
_NO_TYPE_MODES = frozenset({"subprogram group"})

_FEATURE_NODES = {
    "data_port": "data port",
    "event_port": "event port",
    "event_data_port": "event data port",
    "parameter": "parameter",
    "feature_group": "feature group",
    "abstract_feature": "feature",
    "data_access": "data access",
    "bus_access": "bus access",
    "virtual_bus_access": "virtual bus access",
    "subprogram_access": "subprogram access",
    "subprogram_group_access": "subprogram group access",
}
#: features whose direction may be left out: then they are "in out" (unless they refine one)
_UNDIRECTED_NODES = frozenset({"feature_group", "abstract_feature"})
_CONNECTION_NODES = {
    "port_connection": "port",
    "access_connection": "access",
    "feature_group_connection": "feature group",
    "feature_connection": "feature",
    "parameter_connection": "parameter",
}
_FLOW_KIND_NODES = {
    "flow_source_spec": "source",
    "flow_sink_spec": "sink",
    "flow_path_spec": "path",
    "flow_source_impl": "source",
    "flow_sink_impl": "sink",
    "flow_path_impl": "path",
}

# --------------------------------------------------------------------------- lexical helpers

_TRIVIA = re.compile(r"(?:\s+|--[^\n]*)*")
# the next character that matters when looking for the end of an opaque piece of text
_INTERESTING = re.compile(r'"(?:[^"\\]|\\.|"")*"|\{\*\*.*?\*\*\}|--[^\n]*|[()\[\]{};]', re.S)
_COMMENT_OR_STRING = re.compile(r'"(?:[^"\\]|\\.|"")*"|--[^\n]*')
_ESCAPE = re.compile(r'\\(u[0-9a-fA-F]{4}|.)|""', re.S)
_ESCAPES = {"b": "\b", "t": "\t", "n": "\n", "f": "\f", "r": "\r", '"': '"', "'": "'", "\\": "\\"}
_INTEGER_PARTS = re.compile(r"([0-9_]+)(?:#([0-9a-fA-F_]+)#)?(?:[eE]\+?([0-9]+))?\Z")


def _shown(text: str, limit: int = 40) -> str:
    """A literal as shown in a message (long ones shortened)."""
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _parse_integer(literal: str) -> int:
    """The value of an INTEGER token; ValueError (with a message) when malformed or huge."""
    shown = _shown(literal)
    match = _INTEGER_PARTS.match(literal)
    if match is None:  # the grammar's INTEGER terminal makes this impossible
        raise ValueError(f"malformed integer literal {shown!r}")
    digits, based, exponent = match.groups()
    digits = digits.replace("_", "")
    if based is not None:
        base = int(digits) if len(digits) < 4 else 0
        if not 2 <= base <= 16:
            raise ValueError(f"the base of {shown} must be 2 .. 16")
        text = based.replace("_", "")
        if any(int(c, 16) >= base for c in text):
            raise ValueError(f"{shown} has digits that are not base-{base} digits")
    else:
        base, text = 10, digits
    text = text.lstrip("0") or "0"
    too_big = f"integer {shown} does not fit in 64 bits (AADL integers are -2**63 .. 2**63-1)"
    if len(text) > 64:  # more digits than a 64-bit number has in any base
        raise ValueError(too_big)
    mantissa = int(text, base)
    if exponent is None or mantissa == 0:
        return mantissa
    exponent = exponent.lstrip("0") or "0"
    if len(exponent) > 3 or int(exponent) * math.log2(base) > 64:  # checked before computing it
        raise ValueError(too_big)
    return mantissa * base ** int(exponent)


def _unescape(token: str) -> str:
    """The value of a STRING token: quotes removed, ``""`` and backslash escapes replaced."""
    inner = token[1:-1]
    if "\\" not in inner and '""' not in inner:
        return inner

    def replace(match: re.Match[str]) -> str:
        escape = match.group(1)
        if escape is None:
            return '"'
        if len(escape) == 5:
            code = int(escape[1:], 16)
            return match.group() if 0xD800 <= code <= 0xDFFF else chr(code)  # no lone surrogates
        return _ESCAPES.get(escape, "\\" + escape)

    return _ESCAPE.sub(replace, inner)


def _normalise(text: str) -> str:
    """Source text without comments, white space runs as one space."""
    if "--" in text:
        text = _COMMENT_OR_STRING.sub(lambda m: m.group() if m.group().startswith('"') else " ", text)
    return " ".join(text.split())


def _find_end(text: str, pos: int, depth: int, stop: str) -> int:
    """The position of the ``stop`` character (``;`` or a closing bracket) that ends the
    construct starting at ``pos``, ``depth`` brackets deep; strings, annex texts and
    comments are stepped over.  ``len(text)`` when there is none."""
    search = _INTERESTING.search
    while True:
        match = search(text, pos)
        if match is None:
            return len(text)
        char = match.group()
        pos = match.end()
        if len(char) != 1:
            continue  # string, annex text or comment
        if char in "([{":
            depth += 1
        elif char in ")]}":
            depth -= 1
            if depth == 0 and stop == ")":
                return match.start()
        elif char == ";" and depth == 0 and stop == ";":
            return match.start()


# --------------------------------------------------------------------------- the builder


@functools.cache
def _class_setters(class_name: str) -> tuple[type, dict[str, tuple[FeatureSlot, Any]]]:
    """The pyecore class of a metamodel class, and each single-valued feature's slot and setter
    (metamodel metadata, looked up once per process)."""
    eclass = metamodels.load().eclass(class_name)
    setters: dict[str, tuple[FeatureSlot, Any]] = {}
    for feature in eclass.eAllStructuralFeatures():
        if not feature.many:
            slot = FeatureSlot(feature)
            setters[feature.name] = (
                slot,
                FastFactory.set_child if slot.containment else FastFactory.set_value,
            )
    return eclass.python_class, setters


@functools.cache
def _list_slot(eclass: Any, name: str) -> FeatureSlot:
    feature = eclass.findEStructuralFeature(name)
    if feature is None or not feature.many:
        raise ModelError(f"{eclass.name} has no list feature {name!r}")
    return FeatureSlot(feature)


def _make(class_name: str, /, **values: Any) -> EObject:
    """A new object with single-valued features set: :class:`rosaadl.bulk.FastFactory` with the
    slots looked up once (the builder passes typed values: enum literals, ints, strs, ...)."""
    cls, setters = _class_setters(class_name)
    obj = FastFactory.new(cls)
    for name, value in values.items():
        if value is not None:
            slot, setter = setters[name]
            setter(obj, slot, value)
    return obj


@functools.cache
def _maker(class_name: str, *names: str) -> Callable[..., EObject]:
    """``_maker("IntegerValue", "value", "line")(3, 12)``: :func:`_make` with the features
    given by position, for the objects the builder makes most often."""
    cls, setters = _class_setters(class_name)
    pairs = tuple(setters[name] for name in names)
    new = FastFactory.new

    def make(*values: Any) -> EObject:
        obj = new(cls)
        for (slot, setter), value in zip(pairs, values, strict=True):
            if value is not None:
                setter(obj, slot, value)
        return obj

    return make


def _add(owner: EObject, name: str, *items: Any) -> None:
    """Append to a many-valued feature of an object made by :func:`_make` (nothing: no change)."""
    if not items:
        return
    slot = _list_slot(owner.eClass, name)
    existing = owner.__dict__.get(name)
    if existing is None:
        FastFactory.set_many(owner, slot, list(items))
    else:
        FastFactory.extend(owner, slot, existing, items)


class _Literals:
    """The enumeration literals the builder uses, by their AADL spelling or tree node name."""

    def __init__(self) -> None:
        literal = FastBuilder().literal
        self.categories = {c: literal("ComponentCategory", c) for c in _ALL_CATEGORIES}
        self.feature_categories = {n: literal("FeatureCategory", w) for n, w in _FEATURE_NODES.items()}
        self.feature_names = {n: self.feature_categories[n].name for n in _FEATURE_NODES}
        self.directions = {d: literal("DirectionType", d) for d in ("in", "out", "in out")}
        self.access = {a: literal("AccessType", a) for a in ("provides", "requires")}
        self.connection_kinds = {n: literal("ConnectionKind", k) for n, k in _CONNECTION_NODES.items()}
        self.flow_kinds = {n: literal("FlowKind", k) for n, k in _FLOW_KIND_NODES.items()}
        self.visibility = {v: literal("Visibility", v) for v in ("public", "private")}
        self.rename_kinds = {
            k: literal("RenameKind", k) for k in ("classifier", "package", "feature group", "all")
        }


@functools.cache
def _literals() -> _Literals:
    return _Literals()


class _Builder:
    """Builds the model units of one parsed text; collects located errors and warnings."""

    def __init__(self, text: str, filename: str) -> None:
        self.text = text
        self.filename = filename
        self.make = _make
        self.add = _add
        # the most frequent objects, made with their features by position
        self.new_association = _maker(
            "PropertyAssociation", "property", "append", "constant", "line", "column"
        )
        self.new_modal = _maker("ModalPropertyValue", "value", "line", "column")
        self.new_integer = _maker("IntegerValue", "value", "unit", "line", "column")
        self.new_real = _maker("RealValue", "value", "unit", "line", "column")
        self.new_named = _maker("NamedValue", "name", "line", "column")
        self.new_feature = _maker(
            "Feature",
            "name",
            "category",
            "direction",
            "access",
            "refined",
            "inverse",
            "classifier",
            "line",
            "column",
        )
        self.errors: list[Diagnostic] = []
        self.warnings: list[Diagnostic] = []
        self.newlines: list[int] | None = None  # positions of the line breaks, when needed
        # per package: classifier names, component types, implementations (for the checks)
        self.unit_names: dict[str, int] = {}
        self.types: dict[str, Tree] = {}
        self.implementations: list[Tree] = []
        literals = _literals()
        self.categories = literals.categories
        self.feature_categories = literals.feature_categories
        self.feature_names = literals.feature_names
        self.directions = literals.directions
        self.access = literals.access
        self.connection_kinds = literals.connection_kinds
        self.flow_kinds = literals.flow_kinds
        self.visibility = literals.visibility
        self.rename_kinds = literals.rename_kinds
        self.values = {
            "integer_value": self.integer_value,
            "real_value": self.real_value,
            "named_value": self.named_value,
            "signed_constant": self.signed_constant,
            "boolean_value": self.boolean_value,
            "string_value": self.string_value,
            "list_value": self.list_value,
            "record_value": self.record_value,
            "reference_value": self.reference_value,
            "classifier_value": self.classifier_value,
            "computed_value": self.computed_value,
            "or_value": self.operation_value,
            "and_value": self.operation_value,
            "not_value": self.operation_value,
            "range_value": self.range_value,
        }

    # ----------------------------------------------------------------- diagnostics

    def error(self, message: str, line: int | None, column: int | None) -> None:
        self.errors.append(Diagnostic("error", message, Location(self.filename, line, column)))

    def warning(self, message: str, line: int | None, column: int | None) -> None:
        self.warnings.append(Diagnostic("warning", message, Location(self.filename, line, column)))

    def fatal(self, message: str, where: Any) -> AadlSyntaxError:
        line, column = _position(where)
        return AadlSyntaxError(message, file=self.filename, line=line, column=column)

    # ----------------------------------------------------------------- units

    def specification(self, tree: Tree) -> list[EObject]:
        units = []
        for node in tree.children:
            if node.data == "package":
                units.append(self.package(node))
            else:
                units.append(self.property_set(node))
        return units

    def check_end(self, name: str, end: str, what: str, where: Any) -> None:
        if name.lower() != end.lower():
            line, column = _position(where)
            self.error(f"{what} {name} ends with 'end {end}': expected 'end {name}'", line, column)

    def package(self, node: Tree) -> EObject:
        qname, public, private, properties, end = node.children
        name = "::".join(qname.children)
        first = qname.children[0]
        self.check_end(name, "::".join(end.children), "package", end.children[0])
        pkg = self.make(
            "AadlPackage", name=name, line=first.line, column=first.column, sourceFile=self.filename
        )
        self.unit_names: dict[str, int] = {}
        self.types: dict[str, Tree] = {}
        self.implementations: list[Tree] = []
        for section, visibility in ((public, "public"), (private, "private")):
            if section is not None:
                self.package_section(pkg, section, visibility)
        if properties is not None:
            self.add(pkg, "ownedPropertyAssociations", *self.associations(properties.children))
        self.check_implementation_categories()
        return pkg

    def package_section(self, pkg: EObject, section: Tree, visibility: str) -> None:
        withs: list[str] = []
        classifiers = []
        renamings = []
        annexes = []
        vis = self.visibility[visibility]
        for item in section.children:
            kind = item.data
            if kind == "component_type":
                classifiers.append(self.component_type(item, vis))
                self.declare(self.unit_names, item.children[1], "classifier")
                self.types.setdefault(item.children[1].lower(), item)
            elif kind == "component_implementation":
                classifiers.append(self.component_implementation(item, vis))
                type_name, impl_name = item.children[1].children
                self.declare(self.unit_names, type_name, "classifier", f"{type_name}.{impl_name}")
                self.implementations.append(item)
            elif kind == "with_clause":
                withs.extend("::".join(q.children) for q in item.children)
            elif kind == "feature_group_type":
                classifiers.append(self.feature_group_type(item, vis))
                self.declare(self.unit_names, item.children[0], "classifier")
            elif kind == "annex_library":
                annexes.append(self.annex_library(item, visibility))
            else:
                renamings.append(self.renaming(item, visibility))
        if withs:
            self.add(pkg, "withs" if visibility == "public" else "privateWiths", *withs)
        if classifiers:
            self.add(pkg, "classifiers", *classifiers)
        if renamings:
            self.add(pkg, "renamings", *renamings)
        if annexes:
            self.add(pkg, "annexLibraries", *annexes)

    def declare(self, names: dict[str, int], name: Token | None, what: str, text: str | None = None) -> None:
        """Record a name of a namespace; a second declaration of it is reported.

        AADL forbids it (OSATE reports an error), but real models generated by tools have such
        duplicates: both are kept, name look-ups find the first, and a warning says so."""
        if name is None:
            return
        text = text or name
        key = text.lower()
        previous = names.get(key)
        if previous is None:
            names[key] = name.line
            return
        self.warning(
            f"{what} {text} is declared twice (first at line {previous}); names refer to the first",
            name.line,
            name.column,
        )

    def renaming(self, node: Tree, visibility: str) -> EObject:
        kind = node.data
        children = node.children
        vis = self.visibility[visibility]
        if kind == "package_rename":
            alias, target = children
            return self.make(
                "Renaming",
                name=str(alias),
                kind=self.rename_kinds["package"],
                visibility=vis,
                target="::".join(target.children),
                line=alias.line,
                column=alias.column,
            )
        if kind == "package_rename_all":
            first = children[0]
            return self.make(
                "Renaming",
                kind=self.rename_kinds["all"],
                visibility=vis,
                target="::".join(children),
                line=first.line,
                column=first.column,
            )
        if kind == "feature_group_type_rename":
            alias, target = children
            where = alias if alias is not None else target.children[0]
            return self.make(
                "Renaming",
                name=str(alias) if alias is not None else None,
                kind=self.rename_kinds["feature group"],
                visibility=vis,
                target=_classifier_ref(target),
                line=where.line,
                column=where.column,
            )
        alias, category, target = children  # component_type_rename
        where = alias if alias is not None else category.children[0]
        return self.make(
            "Renaming",
            name=str(alias) if alias is not None else None,
            kind=self.rename_kinds["classifier"],
            visibility=vis,
            category=self.categories[_words(category)],
            target=_classifier_ref(target),
            line=where.line,
            column=where.column,
        )

    # ----------------------------------------------------------------- classifiers

    def component_type(self, node: Tree, visibility: Any) -> EObject:
        children = node.children
        category_node, name, extends, bindings = children[:4]
        category = _words(category_node)
        self.check_end(name, children[-1], f"{category} type", children[-1])
        sections = children[4:-1]
        ctype = self.make(
            "ComponentType",
            name=str(name),
            category=self.categories[category],
            requiresModes=True if any(s.data == "requires_modes" for s in sections) else None,
            visibility=visibility,
            extended=_classifier_ref(extends.children[0]) if extends is not None else None,
            prototypeBindings=self.bindings_text(bindings) if bindings is not None else None,
            line=name.line,
            column=name.column,
        )
        members: dict[str, int] = {}
        for section in sections:
            kind = section.data
            if kind == "features":
                features = self.features(section, category, members)
                self.add(ctype, "features", *features)
            elif kind == "properties":
                self.add(ctype, "ownedPropertyAssociations", *self.associations(section.children))
            elif kind == "flow_specs":
                if category in _NO_FLOW_SPECS and section.children:
                    self.not_allowed(f"a {category} type cannot have flow specifications", section)
                self.add(ctype, "flowSpecifications", *self.flow_specs(section, members))
            elif kind == "modes" or kind == "requires_modes":
                if category in _NO_TYPE_MODES and section.children:
                    self.not_allowed(f"a {category} type cannot have modes", section)
                self.modes(ctype, section, members)
            elif kind == "prototypes":
                self.add(ctype, "prototypes", *self.prototypes(section, members))
            else:  # annex_subclause
                self.add(ctype, "annexSubclauses", self.annex_subclause(section))
        return ctype

    def component_implementation(self, node: Tree, visibility: Any) -> EObject:
        children = node.children
        category_node, impl_name, extends, bindings = children[:4]
        category = _words(category_node)
        type_token, impl_token = impl_name.children
        name = f"{type_token}.{impl_token}"
        end_type, end_impl = children[-1].children
        self.check_end(name, f"{end_type}.{end_impl}", f"{category} implementation", end_type)
        impl = self.make(
            "ComponentImplementation",
            name=name,
            type=str(type_token),
            category=self.categories[category],
            visibility=visibility,
            extended=_classifier_ref(extends.children[0]) if extends is not None else None,
            prototypeBindings=self.bindings_text(bindings) if bindings is not None else None,
            line=type_token.line,
            column=type_token.column,
        )
        members: dict[str, int] = {}
        for section in children[4:-1]:
            kind = section.data
            if kind == "subcomponents":
                self.add(impl, "subcomponents", *self.subcomponents(section, category, members))
            elif kind == "connections":
                self.add(impl, "connections", *self.connections(section, category, members))
            elif kind == "properties":
                self.add(impl, "ownedPropertyAssociations", *self.associations(section.children))
            elif kind == "flow_impls":
                if category in _NO_FLOW_IMPLS and section.children:
                    self.not_allowed(f"a {category} implementation cannot have flows", section)
                self.flow_impls(impl, section, members)
            elif kind == "calls":
                if category not in CALLS_ALLOWED and section.children:
                    self.not_allowed(
                        f"a {category} implementation cannot have subprogram calls "
                        "(only thread, subprogram and abstract implementations can)",
                        section,
                    )
                self.add(impl, "callSequences", *self.call_sequences(section, members))
            elif kind == "modes":
                self.modes(impl, section, members)
            elif kind == "prototypes":
                self.add(impl, "prototypes", *self.prototypes(section, members))
            else:  # annex_subclause
                self.add(impl, "annexSubclauses", self.annex_subclause(section))
        return impl

    def feature_group_type(self, node: Tree, visibility: Any) -> EObject:
        children = node.children
        name, extends, bindings = children[:3]
        self.check_end(name, children[-1], "feature group type", children[-1])
        sections = children[3:-1]
        inverse = next((s.children[0] for s in sections if s.data == "inverse_of"), None)
        fgt = self.make(
            "FeatureGroupType",
            name=str(name),
            inverseOf=_classifier_ref(inverse) if inverse is not None else None,
            visibility=visibility,
            extended=_classifier_ref(extends.children[0]) if extends is not None else None,
            prototypeBindings=self.bindings_text(bindings) if bindings is not None else None,
            line=name.line,
            column=name.column,
        )
        members: dict[str, int] = {}
        for section in sections:
            kind = section.data
            if kind == "features":
                self.add(fgt, "features", *self.features(section, None, members))
            elif kind == "inverse_of":
                pass  # set above
            elif kind == "properties":
                self.add(fgt, "ownedPropertyAssociations", *self.associations(section.children))
            elif kind == "prototypes":
                self.add(fgt, "prototypes", *self.prototypes(section, members))
            else:  # annex_subclause
                self.add(fgt, "annexSubclauses", self.annex_subclause(section))
        return fgt

    def not_allowed(self, message: str, where: Any) -> None:
        line, column = _position(where)
        self.error(message, line, column)

    def check_implementation_categories(self) -> None:
        """An implementation has the category of its type (when the type is in this package)."""
        for impl in self.implementations:
            type_name, impl_name = impl.children[1].children
            ctype = self.types.get(type_name.lower())
            if ctype is None:
                continue
            impl_category = _words(impl.children[0])
            type_category = _words(ctype.children[0])
            if impl_category != type_category:
                self.error(
                    f"{impl_category} implementation {type_name}.{impl_name} implements {type_category} "
                    f"type {ctype.children[1]}: the categories must be the same",
                    type_name.line,
                    type_name.column,
                )

    # ----------------------------------------------------------------- prototypes

    def prototypes(self, section: Tree, members: dict[str, int]) -> list[EObject]:
        out = []
        for node in section.children:
            name, refined = node.children[:2]
            start = self.after(name.end_pos, ":", "refined", "to")
            stop = _find_end(self.text, start, 0, ";")
            proto = self.make(
                "Prototype",
                name=str(name),
                refined=True if refined is not None else None,
                text=_normalise(self.text[start:stop]),
                line=name.line,
                column=name.column,
            )
            self.declare(members, name, "prototype")
            out.append(proto)
        if out:
            first = section.children[0].children[0]
            self.warning(
                "prototypes are kept as text but not interpreted: bindings are not applied "
                "when the model is instantiated",
                first.line,
                first.column,
            )
        return out

    def bindings_text(self, node: Tree) -> str:
        """``(p => data T, ...)`` as written (comments and line breaks dropped)."""
        first = node.children[0].children[0]
        stop = _find_end(self.text, first.start_pos, 1, ")")
        return "(" + _normalise(self.text[first.start_pos : stop]) + ")"

    # ----------------------------------------------------------------- features

    def features(self, section: Tree, category: str | None, members: dict[str, int]) -> list[EObject]:
        out = []
        allowed = FEATURES_ALLOWED.get(category) if category is not None else None
        new_feature = self.new_feature
        for node in section.children:
            kind = node.data
            children = node.children
            name = children[0]
            if kind == "feature_group":
                _, refined, direction, inverse, classifier, array, block = children
            else:
                _, refined, direction, classifier, array, block = children
                inverse = None
            in_out = access = None
            if direction is not None:
                word = _words(direction)
                if direction.data == "access_kind":
                    access = self.access[word]
                else:
                    in_out = self.directions[word]
            elif refined is None and kind in _UNDIRECTED_NODES:
                in_out = self.directions["in out"]  # no direction is both ways (OSATE's reading)
            feature = new_feature(
                str(name),
                self.feature_categories[kind],
                in_out,
                access,
                True if refined is not None else None,
                True if inverse is not None else None,
                _feature_classifier(classifier) if classifier is not None else None,
                name.line,
                name.column,
            )
            if array is not None:
                self.add(feature, "arrayDimensions", _array_size(array))
            if block is not None:
                self.add(feature, "ownedPropertyAssociations", *self.associations(block.children))
            if allowed is not None and self.feature_names[kind] not in allowed:
                self.error(
                    f"a {category} cannot have {_FEATURE_NODES[kind]} features ({name})",
                    name.line,
                    name.column,
                )
            self.declare(members, name, "feature")
            out.append(feature)
        return out

    # ----------------------------------------------------------------- implementations

    def subcomponents(self, section: Tree, category: str, members: dict[str, int]) -> list[EObject]:
        out = []
        allowed = SUBCOMPONENTS_ALLOWED[category]
        make = self.make
        add = self.add
        for node in section.children:
            name, refined, cat_node, classifier, bindings, dims, elements, block, in_modes = node.children
            sub_category = _words(cat_node)
            sub = make(
                "Subcomponent",
                name=str(name),
                category=self.categories[sub_category],
                refined=True if refined is not None else None,
                classifier=_classifier_ref(classifier) if classifier is not None else None,
                prototypeBindings=self.bindings_text(bindings) if bindings is not None else None,
                line=name.line,
                column=name.column,
            )
            if dims is not None:
                add(sub, "arrayDimensions", *[_array_size(d) for d in dims.children])
            if elements is not None:
                add(sub, "arrayElementBindings", *[self.element_implementation(e) for e in elements.children])
            if block is not None:
                add(sub, "ownedPropertyAssociations", *self.associations(block.children))
            if in_modes is not None:
                add(sub, "inModes", *_mode_refs(in_modes))
            if sub_category not in allowed:
                self.error(
                    f"a {category} implementation cannot contain {sub_category} subcomponents ({name}); "
                    f"it can contain: {', '.join(sorted(allowed))}",
                    name.line,
                    name.column,
                )
            self.declare(members, name, "subcomponent")
            out.append(sub)
        return out

    def element_implementation(self, node: Tree) -> str:
        ref, bindings = node.children
        text = _classifier_ref(ref)
        return f"{text} {self.bindings_text(bindings)}" if bindings is not None else text

    def call_sequences(self, section: Tree, members: dict[str, int]) -> list[EObject]:
        out = []
        for node in section.children:
            children = node.children
            name = children[0]
            block, in_modes = children[-2:]
            seq = self.make("CallSequence", name=str(name), line=name.line, column=name.column)
            self.declare(members, name, "call sequence")
            calls = []
            for call_node in children[1:-2]:
                call_name, called, call_block = call_node.children
                if called.data == "processor_subprogram":
                    called_text = f"processor.{called.children[0]}"
                else:
                    called_text = _classifier_ref(called)
                call = self.make(
                    "SubprogramCall",
                    name=str(call_name),
                    called=called_text,
                    line=call_name.line,
                    column=call_name.column,
                )
                if call_block is not None:
                    self.add(call, "ownedPropertyAssociations", *self.associations(call_block.children))
                self.declare(members, call_name, "subprogram call")
                calls.append(call)
            self.add(seq, "calls", *calls)
            if block is not None:
                self.add(seq, "ownedPropertyAssociations", *self.associations(block.children))
            if in_modes is not None:
                self.add(seq, "inModes", *_mode_refs(in_modes))
            out.append(seq)
        return out

    def connections(self, section: Tree, category: str, members: dict[str, int]) -> list[EObject]:
        out = []
        allowed = CONNECTIONS_ALLOWED[category]
        make = self.make
        for node in section.children:
            kind = node.data
            children = node.children
            name = children[0]
            refined = children[1]
            values: dict[str, Any] = {}
            if kind == "port_connection" or kind == "access_connection":
                qualifier = children[2]
                source, direction, destination, block, in_modes = children[3:]
                if qualifier is not None:
                    words = _words(qualifier)
                    if kind == "access_connection":
                        values["accessCategory"] = self.categories[words]
                    elif words != "port":
                        line, column = _position(qualifier)
                        self.warning(
                            f"'{words}' connections are AADL v1 syntax: read as a port connection",
                            line,
                            column,
                        )
            else:
                source, direction, destination, block, in_modes = children[2:]
            line, column = _position(name if name is not None else node)
            connection = make(
                "Connection",
                name=str(name) if name is not None else None,
                kind=self.connection_kinds[kind],
                refined=True if refined is not None else None,
                source=_end(source) if source is not None else None,
                destination=_end(destination) if destination is not None else None,
                bidirectional=True if direction is not None and direction.children[0] == "<->" else None,
                line=line,
                column=column,
                **values,
            )
            if block is not None:
                self.add(connection, "ownedPropertyAssociations", *self.associations(block.children))
            if in_modes is not None:
                self.add(connection, "inModes", *_mode_refs(in_modes))
            word = _CONNECTION_NODES[kind]
            if word not in allowed:
                self.error(
                    f"a {category} implementation cannot have {word} connections"
                    + (f" ({name})" if name is not None else ""),
                    line,
                    column,
                )
            if source is None and refined is None:
                self.error("a connection needs a source and a destination", line, column)
            self.declare(members, name, "connection")
            out.append(connection)
        return out

    # ----------------------------------------------------------------- flows

    def flow_specs(self, section: Tree, members: dict[str, int]) -> list[EObject]:
        out = []
        for node in section.children:
            kind = node.data
            children = node.children
            name, refined = children[:2]
            block, in_modes = children[-2:]
            ends: dict[str, Any] = {}
            if kind == "flow_path_spec":
                if children[2] is not None:
                    ends["inEnd"] = _path(children[2])
                    ends["outEnd"] = _path(children[3])
            elif children[2] is not None:
                ends["outEnd" if kind == "flow_source_spec" else "inEnd"] = _path(children[2])
            if not ends and refined is None:
                self.error(f"flow {name} needs its end feature", name.line, name.column)
            flow = self.make(
                "FlowSpecification",
                name=str(name),
                kind=self.flow_kinds[kind],
                refined=True if refined is not None else None,
                line=name.line,
                column=name.column,
                **ends,
            )
            if block is not None:
                self.add(flow, "ownedPropertyAssociations", *self.associations(block.children))
            if in_modes is not None:
                self.add(flow, "inModes", *_mode_refs(in_modes))
            self.declare(members, name, "flow")
            out.append(flow)
        return out

    def flow_impls(self, impl: EObject, section: Tree, members: dict[str, int]) -> None:
        flows = []
        end_to_end = []
        for node in section.children:
            kind = node.data
            children = node.children
            name = children[0]
            block, in_modes = children[-2:]
            if kind == "end_to_end_flow":
                refined, segments = children[1:3]
                flow = self.make(
                    "EndToEndFlow",
                    name=str(name),
                    refined=True if refined is not None else None,
                    line=name.line,
                    column=name.column,
                )
                if segments is None and refined is None:
                    self.error(f"end-to-end flow {name} needs its flow elements", name.line, name.column)
                self.declare(members, name, "flow")
                end_to_end.append(flow)
            else:
                segments = children[1]
                flow = self.make(
                    "FlowImplementation",
                    name=str(name),
                    kind=self.flow_kinds[kind],
                    line=name.line,
                    column=name.column,
                )
                self.declare(members, name, "flow")
                flows.append(flow)
            if segments is not None:
                self.add(flow, "elements", *[_path(p) for p in segments.children])
            if block is not None:
                self.add(flow, "ownedPropertyAssociations", *self.associations(block.children))
            if in_modes is not None:
                self.add(flow, "inModes", *_mode_refs(in_modes))
        if flows:
            self.add(impl, "flowImplementations", *flows)
        if end_to_end:
            self.add(impl, "endToEndFlows", *end_to_end)

    # ----------------------------------------------------------------- modes

    def modes(self, classifier: EObject, section: Tree, members: dict[str, int]) -> None:
        modes = []
        transitions = []
        for node in section.children:
            children = node.children
            if node.data == "mode":
                name, initial, block = children
                mode = self.make(
                    "Mode",
                    name=str(name),
                    initial=True if initial is not None else None,
                    line=name.line,
                    column=name.column,
                )
                self.declare(members, name, "mode")
                modes.append(mode)
            else:
                name, source, triggers, destination, block = children
                where = name if name is not None else source
                mode = self.make(
                    "ModeTransition",
                    name=str(name) if name is not None else None,
                    source=str(source),
                    destination=str(destination),
                    line=where.line,
                    column=where.column,
                )
                self.add(mode, "triggers", *[_end(t) for t in triggers.children])
                self.declare(members, name, "mode transition")
                transitions.append(mode)
            if block is not None:
                self.add(mode, "ownedPropertyAssociations", *self.associations(block.children))
        if modes:
            if classifier.modes:
                line, column = _position(section)
                self.warning(
                    "both 'requires modes' and 'modes' sections: their modes are kept in one list",
                    line,
                    column,
                )
            self.add(classifier, "modes", *modes)
        if transitions:
            self.add(classifier, "modeTransitions", *transitions)

    # ----------------------------------------------------------------- annexes

    def annex_subclause(self, node: Tree) -> EObject:
        name, content, in_modes = node.children
        annex = self.make(
            "AnnexSubclause",
            name=str(name),
            text=content[3:-3] if isinstance(content, Token) else None,
            line=name.line,
            column=name.column,
        )
        if in_modes is not None:
            self.add(annex, "inModes", *_mode_refs(in_modes))
        return annex

    def annex_library(self, node: Tree, visibility: str) -> EObject:
        name, content = node.children
        return self.make(
            "AnnexLibrary",
            name=str(name),
            visibility=self.visibility[visibility],
            text=content[3:-3] if isinstance(content, Token) else None,
            line=name.line,
            column=name.column,
        )

    # ----------------------------------------------------------------- property associations

    def associations(self, nodes: Sequence[Tree]) -> list[EObject]:
        out = []
        add = self.add
        new_association = self.new_association
        new_modal = self.new_modal
        for node in nodes:
            qname, append, constant, assignment, applies_to, in_binding = node.children
            first = qname.children[0]
            line, column = first.line, first.column
            pa = new_association(
                "::".join(qname.children),
                True if append is not None else None,
                True if constant is not None else None,
                line,
                column,
            )
            if assignment.data == "modal_property_value":
                modal = []
                for item in assignment.children:
                    value_node, in_modes = item.children
                    value_line, value_column = _position(value_node)
                    value = self.value(value_node, line, column, 0)
                    mpv = new_modal(value, value_line, value_column)
                    if in_modes is not None:
                        add(mpv, "inModes", *_mode_refs(in_modes))
                    modal.append(mpv)
                add(pa, "ownedValues", *modal)
            else:
                value_line, value_column = _position(assignment)
                value = self.value(assignment, line, column, 0)
                add(pa, "ownedValues", new_modal(value, value_line, value_column))
            if applies_to is not None:
                add(pa, "appliesTo", *[_path(p) for p in applies_to.children])
            if in_binding is not None:
                add(pa, "inBinding", *[_classifier_ref(c) for c in in_binding.children])
            out.append(pa)
        return out

    # ----------------------------------------------------------------- values

    def value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        if depth > _MAX_NESTING:
            raise self.fatal(f"a property value nested more than {_MAX_NESTING} levels deep", node)
        return self.values[node.data](node, line, column, depth)

    def number_position(self, sign: Tree | None, literal: Token) -> tuple[int, int]:
        if sign is not None:
            token = sign.children[0]
            return token.line, token.column
        return literal.line, literal.column

    def integer_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        sign, literal, unit = node.children
        number = int(literal) if len(literal) < 19 and literal.isdigit() else self.integer(literal)
        if sign is not None and sign.children[0] == "-":
            number = -number
        if not _ELONG_MIN <= number <= _ELONG_MAX:
            raise self.fatal(
                f"integer {'-' if number < 0 else ''}{_shown(literal)} does not fit in 64 bits (the range of "
                "an AADL integer is -2**63 .. 2**63-1)",
                sign if sign is not None else literal,
            )
        line, column = self.number_position(sign, literal)
        return self.new_integer(number, str(unit) if unit is not None else None, line, column)

    def integer(self, literal: Token) -> int:
        """An AADL integer literal: ``1_000``, ``16#FF#``, ``2#1#e10``, ``1e3``."""
        try:
            return _parse_integer(literal)
        except ValueError as exc:
            raise self.fatal(str(exc), literal) from None

    def real_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        sign, literal, unit = node.children
        number = float(literal.replace("_", ""))
        if math.isinf(number):
            raise self.fatal(f"real {_shown(literal)} is out of range (larger than a 64-bit float)", literal)
        if sign is not None and sign.children[0] == "-":
            number = -number
        line, column = self.number_position(sign, literal)
        return self.new_real(number, str(unit) if unit is not None else None, line, column)

    def named_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        first = node.children[0]
        return self.new_named("::".join(node.children), first.line, first.column)

    def signed_constant(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        sign, named = node.children
        token = sign.children[0]
        op = self.make("OperationValue", operator=str(token), line=token.line, column=token.column)
        self.add(op, "ownedOperands", self.named_value(named, line, column, depth))
        return op

    def boolean_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        token = node.children[0]
        return self.make("BooleanValue", value=token.lower() == "true", line=token.line, column=token.column)

    def string_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        token = node.children[0]
        return self.make("StringValue", value=_unescape(token), line=token.line, column=token.column)

    def list_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        items = [self.value(item, line, column, depth + 1) for item in node.children]
        if items:
            line, column = items[0].line, items[0].column
        value = self.make("ListValue", line=line, column=column)
        if items:
            self.add(value, "ownedItems", *items)
        return value

    def record_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        fields = []
        for field in node.children:
            name, item = field.children
            fields.append(
                self.make(
                    "FieldValue",
                    name=str(name),
                    value=self.value(item, name.line, name.column, depth + 1),
                    line=name.line,
                    column=name.column,
                )
            )
        if fields:
            line, column = fields[0].line, fields[0].column
        value = self.make("RecordValue", line=line, column=column)
        if fields:
            self.add(value, "ownedFields", *fields)
        return value

    def reference_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        path = node.children[0]
        line, column = _position(path)
        return self.make("ReferenceValue", path=_path(path), line=line, column=column)

    def classifier_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        ref = node.children[0]
        first = ref.children[0]
        return self.make(
            "ClassifierValue", classifier=_classifier_ref(ref), line=first.line, column=first.column
        )

    def computed_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        token = node.children[0]
        return self.make("ComputedValue", function=str(token), line=token.line, column=token.column)

    def operation_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        operator = node.data[:-6]  # or_value / and_value / not_value
        operands = []
        for item in node.children:
            # "(a or b)" reads as a one-element list; as an operand it can only be the expression
            while item.data == "list_value" and len(item.children) == 1:
                item = item.children[0]
            operands.append(self.value(item, line, column, depth + 1))
        line, column = _position(node)
        value = self.make("OperationValue", operator=operator, line=line, column=column)
        self.add(value, "ownedOperands", *operands)
        return value

    def range_value(self, node: Tree, line: int, column: int, depth: int) -> EObject:
        lower, upper, delta = node.children
        minimum = self.value(lower, line, column, depth + 1)
        return self.make(
            "RangeValue",
            minimum=minimum,
            maximum=self.value(upper, line, column, depth + 1),
            delta=self.value(delta, line, column, depth + 1) if delta is not None else None,
            line=minimum.line,
            column=minimum.column,
        )

    # ----------------------------------------------------------------- property sets

    def property_set(self, node: Tree) -> EObject:
        children = node.children
        name = children[0]
        self.check_end(name, children[-1], "property set", children[-1])
        pset = self.make(
            "PropertySet", name=str(name), line=name.line, column=name.column, sourceFile=self.filename
        )
        withs: list[str] = []
        types = []
        properties = []
        constants = []
        names: dict[str, int] = {}
        make = self.make
        for item in children[1:-1]:
            kind = item.data
            if kind == "property_definition":
                prop_name, inherit, ptype, default, owners = item.children
                type_pos = self.after(prop_name.end_pos, ":", "inherit")
                prop = make(
                    "Property",
                    name=str(prop_name),
                    inherit=True if inherit is not None else None,
                    defaultValue=self.value(default, prop_name.line, prop_name.column, 0)
                    if default is not None
                    else None,
                    line=prop_name.line,
                    column=prop_name.column,
                    **self.type_reference(ptype, "type", "ownedType", 0, type_pos),
                )
                if owners.data == "all_owners":
                    self.add(prop, "appliesTo", "all")
                else:
                    self.add(prop, "appliesTo", *[_owner(o) for o in owners.children])
                self.declare(names, prop_name, "property")
                properties.append(prop)
            elif kind == "property_type_declaration":
                type_name, ptype = item.children
                if ptype.data == "qname":
                    raise self.fatal(
                        f"property type {type_name} must be written out (aadlinteger, enumeration (...), "
                        f"...), not named as {'::'.join(ptype.children)}",
                        ptype,
                    )
                type_pos = self.after(type_name.end_pos, ":", "type")
                declared = self.property_type(ptype, 0, type_pos, type_name)
                self.declare(names, type_name, "property type")
                types.append(declared)
            elif kind == "property_constant":
                const_name, ptype, value = item.children
                type_pos = self.after(const_name.end_pos, ":", "constant")
                const = make(
                    "PropertyConstant",
                    name=str(const_name),
                    value=self.value(value, const_name.line, const_name.column, 0),
                    line=const_name.line,
                    column=const_name.column,
                    **self.type_reference(ptype, "type", "ownedType", 0, type_pos),
                )
                self.declare(names, const_name, "property constant")
                constants.append(const)
            else:  # with_clause
                withs.extend("::".join(q.children) for q in item.children)
        if withs:
            self.add(pset, "withs", *withs)
        if types:
            self.add(pset, "ownedPropertyTypes", *types)
        if properties:
            self.add(pset, "ownedProperties", *properties)
        if constants:
            self.add(pset, "ownedPropertyConstants", *constants)
        return pset

    def type_reference(self, ptype: Tree, named: str, owned: str, depth: int, pos: int) -> dict[str, Any]:
        """``{named: "Set::Type"}`` for a named type, ``{owned: PropertyType}`` for one written out
        (``pos``: where its text starts)."""
        if ptype.data == "qname":
            return {named: "::".join(ptype.children)}
        return {owned: self.property_type(ptype, depth + 1, pos)}

    def after(self, pos: int, *words: str) -> int:
        """The position after white space, comments and those of ``words`` that follow ``pos``."""
        text = self.text
        pos = _TRIVIA.match(text, pos).end()
        for word in words:
            end = pos + len(word)
            follows = text[end : end + 1]
            if text[pos:end].lower() == word and not (
                word.isalpha() and (follows.isalnum() or follows == "_")
            ):
                pos = _TRIVIA.match(text, end).end()
        return pos

    def line_column(self, pos: int) -> tuple[int, int]:
        """(line, column) of a position of the text (1-based, as the tokens')."""
        if self.newlines is None:
            self.newlines = [m.start() for m in re.finditer("\n", self.text)]
        before = bisect.bisect_left(self.newlines, pos)
        start = self.newlines[before - 1] + 1 if before else 0
        return before + 1, pos - start + 1

    def property_type(self, node: Tree, depth: int, pos: int, name: Token | None = None) -> EObject:
        """A property type written out, starting at ``pos``; ``name`` for ``name: type ...``."""
        if depth > _MAX_NESTING:
            raise self.fatal(f"a property type nested more than {_MAX_NESTING} levels deep", node)
        kind = node.data
        if name is not None:
            line, column = name.line, name.column
            named = {"name": str(name), "line": line, "column": column}
        else:
            line, column = self.line_column(pos)
            named = {"line": line, "column": column}
        make = self.make
        if kind == "boolean_type":
            return make("AadlBoolean", **named)
        if kind == "string_type":
            return make("AadlString", **named)
        if kind == "enumeration_type":
            ptype = make("EnumerationType", **named)
            literals = []
            seen: dict[str, int] = {}
            for token in node.children:
                literal = make("EnumerationLiteral", name=str(token), line=token.line, column=token.column)
                self.declare(seen, token, "enumeration literal")
                literals.append(literal)
            self.add(ptype, "ownedLiterals", *literals)
            return ptype
        if kind == "units_type":
            return self.units_type(node, named)
        if kind == "integer_type" or kind == "real_type":
            range_node, units = node.children
            unit_values: dict[str, Any] = {}
            if units is not None:
                if units.data == "units_ref":
                    unit_values["unitsType"] = "::".join(units.children[0].children)
                else:
                    unit_values["ownedUnitsType"] = self.units_type(units, None)
            return make(
                "AadlInteger" if kind == "integer_type" else "AadlReal",
                range=self.value(range_node, line, column, depth + 1) if range_node is not None else None,
                **named,
                **unit_values,
            )
        if kind == "range_type":
            inner = node.children[0]
            if inner.data not in ("qname", "integer_type", "real_type"):
                raise self.fatal("'range of' needs a number type (aadlinteger or aadlreal)", inner)
            inner_pos = self.after(pos, "range", "of")
            number = self.type_reference(inner, "numberType", "ownedNumberType", depth, inner_pos)
            return make("RangeType", **named, **number)
        if kind == "classifier_type" or kind == "reference_type":
            ptype = make("ClassifierType" if kind == "classifier_type" else "ReferenceType", **named)
            categories = [_owner(o) for o in node.children if o is not None]
            if categories:
                self.add(ptype, "categories", *categories)
            return ptype
        if kind == "record_type":
            ptype = make("RecordType", **named)
            fields = []
            seen = {}
            for field in node.children:
                field_name, field_type = field.children
                record_field = make(
                    "RecordField",
                    name=str(field_name),
                    line=field_name.line,
                    column=field_name.column,
                    **self.type_reference(
                        field_type, "type", "ownedType", depth, self.after(field_name.end_pos, ":")
                    ),
                )
                self.declare(seen, field_name, "record field")
                fields.append(record_field)
            self.add(ptype, "ownedFields", *fields)
            return ptype
        if kind == "list_type":
            inner_pos = self.after(pos, "list", "of")
            inner = self.type_reference(node.children[0], "elementType", "ownedElementType", depth, inner_pos)
            return make("ListType", **named, **inner)
        raise self.fatal(f"unexpected property type {kind}", node)  # the grammar has no other

    def units_type(self, node: Tree, named: dict[str, Any] | None) -> EObject:
        children = node.children
        base = children[0]
        if named is None:
            line, column = _position(node)
            named = {"line": line, "column": column}
        ptype = self.make("UnitsType", **named)
        literals = [self.make("UnitLiteral", name=str(base), line=base.line, column=base.column)]
        seen: dict[str, int] = {}
        self.declare(seen, base, "unit")
        for conversion in children[1:]:
            name, unit_base, factor = conversion.children
            literal = self.make(
                "UnitLiteral",
                name=str(name),
                baseUnit=str(unit_base),
                factor=self.value(factor, name.line, name.column, 0),
                line=name.line,
                column=name.column,
            )
            if unit_base.lower() not in seen:
                self.error(
                    f"unit {name} is defined from {unit_base}, which is not a unit declared before it",
                    unit_base.line,
                    unit_base.column,
                )
            self.declare(seen, name, "unit")
            literals.append(literal)
        self.add(ptype, "ownedLiterals", *literals)
        return ptype


# --------------------------------------------------------------------------- small tree helpers


def _words(node: Tree) -> str:
    """The keywords of a small node (category, direction, ...) as one lower-case phrase."""
    children = node.children
    if len(children) == 1:
        return children[0].lower()
    return " ".join(c.lower() for c in children)


def _position(node: Any) -> tuple[int | None, int | None]:
    """(line, column) of the first token of a node (or of a token)."""
    while True:
        if isinstance(node, Token):
            return node.line, node.column
        if isinstance(node, Tree):
            for child in node.children:
                if child is not None:
                    node = child
                    break
            else:
                return None, None
        else:
            return None, None


def _classifier_ref(node: Tree) -> str:
    children = node.children
    impl = children[-1]
    name = "::".join(children[:-1])
    return f"{name}.{impl}" if impl is not None else name


def _feature_classifier(node: Tree) -> str:
    if node.data == "prototype_ref":
        return f"prototype {node.children[0]}"
    return _classifier_ref(node)


def _array_size(node: Tree) -> str:
    size = node.children[0]
    if size is None:
        return ""
    if isinstance(size, Token):
        return _index(size)
    return "::".join(size.children)


def _path(node: Tree) -> str:
    parts = []
    for child in node.children:
        if isinstance(child, Token):
            parts.append(str(child))
        elif child.data == "indexed_element":
            name, index = child.children
            low, high = index.children
            if high is None:
                parts.append(f"{name}[{_index(low)}]")
            else:
                parts.append(f"{name}[{_index(low)} .. {_index(high)}]")
        else:  # annex_element
            parts.append(f"annex {child.children[0]}")
    return ".".join(parts)


def _index(token: Token) -> str:
    """An array size or index as decimal digits (as written if it cannot be converted)."""
    if token.isdigit():
        return str(token)
    try:
        return str(_parse_integer(token))
    except ValueError:
        return str(token)


def _end(node: Any) -> str:
    """A connection end or mode transition trigger as written."""
    data = node.data
    if data == "path":
        return _path(node)
    if data == "processor_port":
        return f"processor.{node.children[0]}"
    return f"self.{node.children[0]}"  # internal_event


def _mode_refs(node: Tree) -> list[str]:
    out = []
    for ref in node.children:
        mode, target = ref.children
        out.append(f"{mode} => {target}" if target is not None else str(mode))
    return out


def _owner(node: Tree) -> str:
    """An ``applies to`` owner or a classifier/reference type category, as written."""
    if node.data == "classifier_ref":
        return _classifier_ref(node)
    prefix, *words = node.children
    text = " ".join(words)
    if prefix is not None:
        return "".join(prefix.split()) + " " + text
    return text


# --------------------------------------------------------------------------- reading


def _raise_errors(errors: list[Diagnostic], kind: type[RosaadlError], what: str) -> None:
    if not errors:
        return
    first = errors[0]
    if len(errors) == 1:
        exc = kind(first.message, first.location)
    else:
        listing = "\n".join(f"  {d.location}: {d.message}" for d in errors)
        exc = kind(f"{first.message}\n{len(errors)} {what}:\n{listing}", first.location)
    exc.errors = list(errors)
    raise exc


def _report(diagnostics: Iterable[Diagnostic], warnings: list[Diagnostic] | None) -> None:
    for diagnostic in diagnostics:
        log.warning("%s", diagnostic)
        if warnings is not None:
            warnings.append(diagnostic)


def _build(text: str | bytes, filename: str) -> tuple[list[EObject], list[Diagnostic]]:
    """Parse and build one text; the new units (not yet added to ``model``) and warnings."""
    tree = parse(text, filename)
    if isinstance(text, bytes | bytearray | memoryview):  # the builder slices the decoded text
        text = bytes(text).decode("utf-8-sig")
    if text.startswith("\ufeff"):
        text = text[1:]
    builder = _Builder(text, filename)
    try:
        with gc_paused():
            units = builder.specification(tree)
    except RecursionError:
        raise AadlSyntaxError("the text nests too deeply to be read", file=filename) from None
    _raise_errors(builder.errors, ValidationError, "errors")
    return units, builder.warnings


def read_string(
    text: str | bytes,
    filename: str = "<string>",
    *,
    model: EObject | None = None,
    warnings: list[Diagnostic] | None = None,
) -> EObject:
    """Read the packages and property sets of one AADL text into ``model`` (a new
    ``AadlModel`` when None) and return the model.

    Raises :class:`AadlSyntaxError` (syntax, encoding, literals out of range) or
    :class:`ValidationError` (the legality rules checked while building; ``.errors`` lists
    every one found), both located; nothing is added to ``model`` then.
    Warnings are logged and appended to ``warnings`` when given.  Names are not resolved here:
    :func:`read_files` does that across files.
    """
    if model is None:
        stem = Path(filename).stem if filename and not filename.startswith("<") else ""
        model = _make("AadlModel", name=stem or "model")
    elif not isinstance(model, EObject) or model.eClass.name != "AadlModel":
        raise ValidationError("read_string adds to an AadlModel; got something else", file=filename)
    units, notes = _build(text, filename)
    if units:
        _add(model, "units", *units)
    _report(notes, warnings)
    return model


def library_files() -> list[Path]:
    """The ``.aadl`` files of the component library shipped with rosaadl, sorted."""
    root = resources.files("rosaadl.library")
    found: list[tuple[tuple[str, ...], Path]] = []
    stack: list[tuple[tuple[str, ...], Any]] = [((), root)]
    while stack:
        parts, folder = stack.pop()
        for entry in folder.iterdir():
            name = entry.name
            if entry.is_dir():
                if not name.startswith((".", "__")):
                    stack.append(((*parts, name), entry))
            elif name.lower().endswith(".aadl"):
                found.append(((*parts, name), Path(str(entry))))
    return [path for _, path in sorted(found)]


def _aadl_files_under(folder: Path) -> list[Path]:
    """The ``.aadl``/``.aadl2`` files under a folder, recursively, in sorted order (hidden
    folders and symbolic links to folders are not entered)."""
    found: list[tuple[tuple[str, ...], Path]] = []
    for current, dirs, names in os.walk(folder, followlinks=False):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        base = Path(current)
        parts = base.relative_to(folder).parts
        for name in names:
            if name.lower().endswith(AADL_SUFFIXES) and (base / name).is_file():
                found.append(((*parts, name), base / name))
    return [path for _, path in sorted(found)]


def _expand(paths: Iterable[str | os.PathLike[str]], seen: set[Path]) -> list[Path]:
    """Files as given and the AADL files under folders; files already in ``seen`` (resolved
    paths) are left out, so that a file named twice is read once."""
    out: list[Path] = []
    for item in paths:
        path = Path(item)
        if path.is_dir():
            found = _aadl_files_under(path)
        elif path.exists():
            found = [path]
        else:
            raise ParseError("no such file or folder", file=str(path))
        for file in found:
            key = file.resolve()
            if key not in seen:
                seen.add(key)
                out.append(file)
    return out


def _read_bytes(path: Path) -> bytes:
    try:
        return path.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the file: {exc.strerror or exc}", file=str(path)) from None


def read_files(
    paths: str | os.PathLike[str] | Iterable[str | os.PathLike[str]],
    *,
    include_library: bool = True,
    warnings: list[Diagnostic] | None = None,
    check: bool = True,
) -> EObject:
    """Read AADL files and folders (searched recursively for ``.aadl``/``.aadl2`` files, in
    sorted order) into one ``AadlModel``.

    With ``include_library`` the component library of rosaadl (``library_files()``: the
    predeclared property sets, SEI, Data_Model, Base_Types, ROS packages, hardware) is read
    first; a user unit named like a library unit replaces it, with a warning.  With ``check``
    every name, unit and enumeration literal is resolved across all units
    (:class:`rosaadl.resolution.Resolver`, then units, enumeration literals and record fields
    of every property value against its property's type); every error found is reported in
    one located :class:`NameResolutionError` (the first one's location, all of them in the
    message and in ``.errors``); warnings (a property set that is not loaded, a missing
    ``with`` clause, a name declared twice, prototypes) are logged and appended to ``warnings``.
    ``check=False`` reads without resolving (files that name packages not given, for example).
    """
    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    library = library_files() if include_library else []
    files = _expand(paths, {path.resolve() for path in library})
    model = _make("AadlModel", name="workspace")
    notes: list[Diagnostic] = []
    library_units: dict[str, EObject] = {}
    if include_library:
        for path in library:
            units, unit_notes = _build(_read_bytes(path), str(path))
            notes.extend(unit_notes)
            for unit in units:
                library_units.setdefault(unit.name.lower(), unit)
            if units:
                _add(model, "units", *units)
    for path in files:
        units, unit_notes = _build(_read_bytes(path), str(path))
        notes.extend(unit_notes)
        for unit in units:
            replaced = library_units.pop(unit.name.lower(), None)
            if replaced is not None:
                model.units.remove(replaced)
                notes.append(
                    Diagnostic(
                        "warning",
                        f"{unit.name} replaces the library's {replaced.name} ({replaced.sourceFile})",
                        Location(unit.sourceFile, unit.line, unit.column),
                    )
                )
        if units:
            _add(model, "units", *units)
    if check:
        with gc_paused(promote=False):  # the checks only add caches: no garbage to collect
            notes.extend(_check(model))
    _report([d for d in notes if d.severity != "error"], warnings)
    _raise_errors([d for d in notes if d.severity == "error"], NameResolutionError, "errors")
    return model


# --------------------------------------------------------------------------- checks across units


def _check(model: EObject) -> list[Diagnostic]:
    """Name resolution (``rosaadl.resolution``) and the units and literals of every value."""
    try:
        from rosaadl.resolution import Resolver
    except ImportError:  # name resolution has not landed: nothing to check against
        return []
    resolver = Resolver(model)
    diagnostics = list(resolver.check())
    seen = {(d.location.file, d.location.line, d.location.column) for d in diagnostics}
    for diagnostic in _ValueChecker(resolver).run(model):
        key = (diagnostic.location.file, diagnostic.location.line, diagnostic.location.column)
        if key not in seen:
            diagnostics.append(diagnostic)
    return diagnostics


class _ValueChecker:
    """Property values against their property's type: unit literals (a unit of the type's units;
    none where the type has no units; one on every number but 0 where it has), enumeration
    literals, record field names.  Values of unknown properties or types are left alone: the
    resolver reports those names."""

    def __init__(self, resolver: Any) -> None:
        self.resolver = resolver
        self.out: list[Diagnostic] = []

    def run(self, model: EObject) -> list[Diagnostic]:
        resolver = self.resolver
        for unit in model.units:
            kind = unit.eClass.name
            if kind == "PropertySet":
                for prop in unit.ownedProperties:
                    if prop.defaultValue is not None:
                        self.value(prop.defaultValue, resolver.resolved_type(prop), prop.name, prop, 0)
                for const in unit.ownedPropertyConstants:
                    if const.value is not None:
                        self.value(const.value, resolver.resolved_type(const), const.name, const, 0)
                continue
            stack: list[EObject] = [unit]
            while stack:
                element = stack.pop()
                for pa in getattr(element, "ownedPropertyAssociations", ()):
                    self.association(pa)
                for name in _MEMBER_LISTS.get(element.eClass.name, ()):
                    stack.extend(getattr(element, name))
        return self.out

    def association(self, pa: EObject) -> None:
        prop = self.resolver.association_property(pa)
        if prop is None:
            return  # unknown property: the resolver reports it
        ptype = self.resolver.resolved_type(prop)
        if ptype is None:
            return
        for modal in pa.ownedValues:
            if modal.value is not None:
                self.value(modal.value, ptype, pa.property, pa, 0)

    def error(self, element: EObject, message: str) -> None:
        self.out.append(Diagnostic("error", message, self.resolver.location(element)))

    def value(self, expr: EObject, ptype: EObject | None, prop: str, context: EObject, depth: int) -> None:
        if ptype is None or depth > _MAX_NESTING:
            return
        resolver = self.resolver
        kind = expr.eClass.name
        type_kind = ptype.eClass.name
        if type_kind == "ListType":
            element = resolver.element_type_once(ptype)
            if kind == "ListValue":
                for item in expr.ownedItems:
                    self.value(item, element, prop, context, depth + 1)
            else:
                self.value(expr, element, prop, context, depth + 1)
            return
        if kind in ("IntegerValue", "RealValue"):
            self.number(expr, ptype, prop)
        elif kind == "RangeValue":
            inner = ptype
            if type_kind == "RangeType":
                inner = ptype.ownedNumberType or resolver.property_type(ptype.numberType, ptype)
            for bound in (expr.minimum, expr.maximum, expr.delta):
                if bound is not None:
                    self.value(bound, inner, prop, context, depth + 1)
        elif kind == "OperationValue" and expr.operator in ("-", "+"):
            for operand in expr.ownedOperands:
                self.value(operand, ptype, prop, context, depth + 1)
        elif kind == "RecordValue" and type_kind == "RecordType":
            fields = {(f.name or "").lower(): f for f in ptype.ownedFields}
            for field in expr.ownedFields:
                declared = fields.get((field.name or "").lower())
                if declared is None:
                    names = ", ".join(f.name for f in ptype.ownedFields)
                    self.error(field, f"{prop} has no field {field.name} (its fields: {names})")
                elif field.value is not None:
                    self.value(field.value, resolver.resolved_type(declared), prop, context, depth + 1)
        elif kind == "NamedValue" and type_kind == "EnumerationType":
            name = expr.name or ""
            if "::" in name or resolver.enumeration_literal(ptype, name) is not None:
                return
            if resolver.constant(name, context) is not None or resolver.property(name, context) is not None:
                return
            literals = ", ".join(lit.name for lit in ptype.ownedLiterals)
            self.error(expr, f"{name} is not a literal of the type of {prop} (expected one of: {literals})")
        elif kind == "NamedValue" and type_kind == "UnitsType":
            name = expr.name or ""
            if "::" not in name and resolver.unit_literal(ptype, name) is None:
                literals = ", ".join(lit.name for lit in ptype.ownedLiterals)
                self.error(expr, f"{name} is not a unit of {_type_name(ptype)} (expected one of: {literals})")

    def number(self, expr: EObject, ptype: EObject, prop: str) -> None:
        resolver = self.resolver
        if ptype.eClass.name not in ("AadlInteger", "AadlReal", "RangeType", "UnitsType"):
            return
        units = resolver.units_type(ptype)
        unit = expr.unit
        if unit:
            if units is None:
                self.error(expr, f"{prop} takes a number without unit, not one in {unit}")
            elif resolver.unit_literal(ptype, unit) is None:
                literals = ", ".join(lit.name for lit in units.ownedLiterals)
                self.error(
                    expr,
                    f"{unit} is not a unit of {_type_name(units)}, the units of {prop} "
                    f"(expected one of: {literals})",
                )
        elif units is not None and (expr.value or 0) != 0:
            literals = ", ".join(lit.name for lit in units.ownedLiterals)
            self.error(expr, f"{prop} needs a unit of {_type_name(units)} ({literals})")


def _type_name(ptype: EObject) -> str:
    if ptype.name:
        owner = ptype.eContainer()
        return (
            f"{owner.name}::{ptype.name}"
            if owner is not None and owner.eClass.name == "PropertySet"
            else ptype.name
        )
    return "its units type"


# the members that hold property associations, by class
_MEMBER_LISTS: dict[str, tuple[str, ...]] = {
    "AadlPackage": ("classifiers",),
    "ComponentType": ("features", "flowSpecifications", "modes", "modeTransitions"),
    "ComponentImplementation": (
        "subcomponents",
        "connections",
        "flowImplementations",
        "endToEndFlows",
        "callSequences",
        "modes",
        "modeTransitions",
    ),
    "FeatureGroupType": ("features",),
    "CallSequence": ("calls",),
}

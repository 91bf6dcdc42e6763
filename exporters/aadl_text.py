"""AADL v2 text (SAE AS5506C) from the declarative AADL model.

:func:`write_unit` turns one ``AadlPackage`` or ``PropertySet`` into AADL text that OSATE
accepts: two spaces per level, sections in the standard's order, one blank line between
classifiers, a trailing newline. The same model always gives the same text, byte for byte.
:func:`write_units` names the texts (``a::b`` → ``a-b.aadl``) and :func:`write_model` writes them
atomically into a folder, never outside it.

Every name the writer puts in the text is checked: an element whose name is not an AADL
identifier, or a reference that is not a well-formed qualified name or path, is an
:class:`~rosaadl.errors.ExportError` naming the element, never text that would not read back.
Reserved words used as names (``data: out event data port``) are accepted, with a warning,
because real models do this and our reader reads them; OSATE does not.

How the opaque and list attributes of the metamodel are written:

* ``arrayDimensions``: one string per dimension, the size (``"3"``), a property constant
  (``"Pkg::Size"``) or ``""`` for ``[]``; written ``[3][Pkg::Size]``. A string already in
  brackets (``"[3]"``) is accepted too.
* ``prototypeBindings`` (classifiers and subcomponents): the binding text, with or without its
  outer parentheses (``"p => data T"`` or ``"(p => data T)"``); written in parentheses after the
  ``extends`` clause of a classifier, after the classifier of a subcomponent.
* ``Prototype.text``: the text after ``name:`` (and after ``refined to``), e.g. ``"data T"``.
* ``arrayElementBindings``: one implementation reference per element, written ``(A.i, B.i)``.
* ``AnnexSubclause.text`` / ``AnnexLibrary.text``: the annex text with or without its ``{** **}``
  delimiters; ``None`` is written ``none``.
* An access connection's category comes from ``Connection.accessCategory`` when it is set,
  else from the features and subcomponents its ends name (found in the model); when neither
  tells, ``access`` is written alone (our reader accepts it; OSATE needs the category) and a
  warning is logged.
* The direction of a feature group or abstract feature: ``in out`` is written as no direction
  word (OSATE's reading of an undirected one), ``in``/``out`` as such.
* Modal values are written in parentheses, ``(v1 in modes (a), v2)``, the form OSATE reads;
  a property block of a flow implementation is written although OSATE's grammar has none there.
"""

from __future__ import annotations

import logging
import math
import os
import re
from collections.abc import Iterable, Sequence
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import fileio
from rosaadl.errors import ExportError, Location

__all__ = ["write_unit", "write_units", "write_model", "unit_file_name", "format_real"]

log = logging.getLogger(__name__)

INDENT = "  "
#: Lines longer than this are wrapped where AADL allows it (enumerations, units, owner lists).
LINE_LENGTH = 100

# --------------------------------------------------------------------------- lexical rules

# AS5506C 15.3: identifier ::= identifier_letter {[underline] letter_or_digit}*
_ID = r"[A-Za-z](?:_?[A-Za-z0-9])*"
_ID_RE = re.compile(_ID + r"\Z")
_QNAME_RE = re.compile(rf"{_ID}(?:\s*::\s*{_ID})*\Z")
_CLASSIFIER_RE = re.compile(rf"{_ID}(?:\s*::\s*{_ID})*(?:\s*\.\s*{_ID})?\Z")
_IMPL_NAME_RE = re.compile(rf"({_ID})\s*\.\s*({_ID})\Z")
_INTEGER = r"[0-9](?:_?[0-9])*"
_ANNEX_TEXT = r"\{\*\*.*?\*\*\}"
_PATH_SEGMENT = rf"(?:{_ID}(?:\s*\[\s*{_INTEGER}\s*(?:\.\.\s*{_INTEGER}\s*)?\])?|annex\s*{_ANNEX_TEXT})"
_PATH_RE = re.compile(rf"{_PATH_SEGMENT}(?:\s*\.\s*{_PATH_SEGMENT})*\Z", re.S | re.I)
_MODE_REF_RE = re.compile(rf"({_ID})(?:\s*=>\s*({_ID}))?\Z")
_ARRAY_SIZE_RE = re.compile(rf"(?:{_INTEGER}|{_ID}(?:\s*::\s*{_ID})*)?\Z")
_OWNER_RE = re.compile(
    rf"(?:\{{\s*{_ID}\s*\}}\s*\*\*\s*)?[A-Za-z]+(?:\s+[A-Za-z]+)*\Z"  # metaclass words, annex prefix
    rf"|{_ID}(?:\s*::\s*{_ID})+(?:\s*\.\s*{_ID})?\Z"  # a qualified classifier
)

#: AADL reserved words (AS5506C 15.5); OSATE does not accept them as names.
_RESERVED_TEXT = """
    aadlboolean aadlinteger aadlreal aadlstring abstract access all and annex applies binding bus
    calls classifier compute connections constant data delta device end enumeration event extends
    false feature features flow flows group implementation in inherit initial inverse is list memory
    mode modes none not of or out package parameter path port private process processor properties
    property prototype prototypes provides public range record reference refined renames requires
    self set sink source subcomponents subprogram system thread to true type units virtual with"""
RESERVED_WORDS = frozenset(_RESERVED_TEXT.split())

_ACCESS_FEATURE_CATEGORY = {
    "busAccess": "bus",
    "dataAccess": "data",
    "subprogramAccess": "subprogram",
    "subprogramGroupAccess": "subprogram group",
    "virtualBusAccess": "virtual bus",
}
_ACCESS_COMPONENT_CATEGORY = {
    "bus": "bus",
    "data": "data",
    "subprogram": "subprogram",
    "subprogramGroup": "subprogram group",
    "virtualBus": "virtual bus",
}
_CONNECTION_WORDS = {
    "featureConnection": "feature",
    "parameterConnection": "parameter",
    "portConnection": "port",
    "featureGroupConnection": "feature group",
}
_FEATURE_WORDS = {
    "dataPort": "data port",
    "eventPort": "event port",
    "eventDataPort": "event data port",
    "parameter": "parameter",
    "busAccess": "bus access",
    "dataAccess": "data access",
    "subprogramAccess": "subprogram access",
    "subprogramGroupAccess": "subprogram group access",
    "virtualBusAccess": "virtual bus access",
    "featureGroup": "feature group",
    "abstractFeature": "feature",
}
_DIRECTED = frozenset({"dataPort", "eventPort", "eventDataPort", "parameter"})
_OPTIONALLY_DIRECTED = frozenset({"featureGroup", "abstractFeature"})
_BOOLEAN_OPERATORS = {"and": "and", "or": "or", "not": "not"}
_SIGN_OPERATORS = {"-": "-", "minus": "-", "+": "+", "plus": "+"}


# --------------------------------------------------------------------------- small helpers


def _literal(value: object) -> str:
    """The AADL spelling of an enumeration value (``thread group``), or ``""``."""
    if value is None:
        return ""
    return str(getattr(value, "literal", None) or getattr(value, "name", value))


def _enum_name(value: object) -> str:
    return str(getattr(value, "name", value)) if value is not None else ""


def _balanced(text: str) -> bool:
    pairs = {"(": ")", "[": "]", "{": "}"}
    stack: list[str] = []
    for char in text:
        if char in pairs:
            stack.append(pairs[char])
        elif char in ")]}" and (not stack or stack.pop() != char):
            return False
    return not stack


def _wrapped_in_parentheses(text: str) -> bool:
    """``(a => b)`` is wrapped; ``(a) , (b)`` is not."""
    if not (text.startswith("(") and text.endswith(")")):
        return False
    depth = 0
    for i, char in enumerate(text):
        if char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0 and i != len(text) - 1:
                return False
    return True


def format_real(value: float) -> str:
    """An AADL real literal that reads back as exactly ``value``: ``1.0``, ``2.5e-3`` → ``0.0025``.

    Python's shortest round-trip ``repr`` is used, rewritten so that there are digits on both
    sides of the point (``1e-05`` → ``1.0e-5``).
    """
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{value!r} has no AADL real literal")
    text = repr(number)
    sign = ""
    if text.startswith("-"):
        sign, text = "-", text[1:]
    mantissa, _, exponent = text.partition("e")
    if "." not in mantissa:
        mantissa += ".0"
    if exponent:
        return f"{sign}{mantissa}e{int(exponent)}"
    return sign + mantissa


def _string_literal(text: str) -> str:
    """An AADL string literal: ``"`` doubled as the standard says; a backslash, which begins an
    escape in OSATE's (and our reader's) string syntax, is written ``\\\\``."""
    return '"' + text.replace("\\", "\\\\").replace('"', '""') + '"'


def unit_file_name(unit: EObject) -> str:
    """``a::b`` → ``a-b.aadl``; the name must be an AADL (qualified) name."""
    name = (unit.name or "").strip()
    what = f"{unit.eClass.name} {name!r}" if name else f"a {unit.eClass.name} without a name"
    if not _QNAME_RE.match(name) or (unit.eClass.name == "PropertySet" and not _ID_RE.match(name)):
        raise ExportError(
            f"cannot write {what}: its name is not an AADL "
            f"{'identifier' if unit.eClass.name == 'PropertySet' else 'package name'} "
            "(letters, digits and single underscores, starting with a letter; '::' between parts)",
            Location(file=unit.sourceFile or None, line=unit.line or None, path=name or None),
        )
    return "-".join(part.strip() for part in name.split("::")) + ".aadl"


# --------------------------------------------------------------------------- the writer


class _UnitWriter:
    """Writes one model unit; ``lines`` collects the output, ``where`` names the element being written."""

    def __init__(self, unit: EObject) -> None:
        self.unit = unit
        self.lines: list[str] = []
        self.where: list[str] = []
        root = unit
        while root.eContainer() is not None:
            root = root.eContainer()
        self.root = root
        self._classifier_cache: dict[str, EObject | None] = {}

    # ----------------------------------------------------------------- errors and checks

    def error(self, message: str, element: EObject | None = None) -> ExportError:
        path = " / ".join(self.where) or None
        line = getattr(element, "line", None) or None if element is not None else None
        column = getattr(element, "column", None) or None if element is not None else None
        file = getattr(self.unit, "sourceFile", None) or None
        if line is None:
            file = None  # a file name without a line would point at the source, not the model
        return ExportError(message, Location(file=file, line=line, column=column, path=path))

    def ident(self, name: str | None, what: str, element: EObject | None = None) -> str:
        text = (name or "").strip()
        if not _ID_RE.match(text):
            shown = repr(name) if name else "no name"
            raise self.error(
                f"{what} has {shown}: an AADL identifier is letters, digits and single underscores, "
                "starting with a letter",
                element,
            )
        if text.lower() in RESERVED_WORDS:
            log.warning(
                "%s%s is named %r, an AADL reserved word: OSATE will not read it",
                f"in {' / '.join(self.where)}: " if self.where else "",
                what,
                text,
            )
        return text

    def checked(self, text: str | None, pattern: re.Pattern[str], what: str, element: EObject | None) -> str:
        value = " ".join((text or "").split()) if pattern is not _PATH_RE else (text or "").strip()
        if not pattern.match(value):
            raise self.error(f"{what} {text!r} is not well-formed", element)
        return value

    def qname(self, text: str | None, what: str, element: EObject | None = None) -> str:
        return self.checked(text, _QNAME_RE, what, element).replace(" ", "")

    def classifier_ref(self, text: str | None, what: str, element: EObject | None = None) -> str:
        return self.checked(text, _CLASSIFIER_RE, what, element).replace(" ", "")

    def path(self, text: str | None, what: str, element: EObject | None = None) -> str:
        value = self.checked(text, _PATH_RE, what, element)
        if "{**" not in value:
            value = re.sub(r"\s+", "", value).replace("..", " .. ")
        return value

    def opaque(self, text: str | None, what: str, element: EObject | None) -> str:
        value = " ".join((text or "").split())
        if not value or not _balanced(value) or ";" in value or "--" in value:
            raise self.error(f"{what} {text!r} cannot be written as AADL text", element)
        return value

    def bindings(self, text: str | None, element: EObject) -> str:
        value = self.opaque(text, "prototype bindings", element)
        return value if _wrapped_in_parentheses(value) else f"({value})"

    def in_modes(self, modes: Sequence[str], element: EObject) -> str:
        if not modes:
            return ""
        refs = []
        for mode in modes:
            match = _MODE_REF_RE.match(" ".join((mode or "").split()))
            if not match:
                raise self.error(f"mode reference {mode!r} is not a mode name (or 'm => n')", element)
            refs.append(match.group(1) + (f" => {match.group(2)}" if match.group(2) else ""))
        return f" in modes ({', '.join(refs)})"

    def array_dimensions(self, dims: Sequence[str], element: EObject) -> str:
        out = []
        for dim in dims:
            size = (dim or "").strip()
            if size.startswith("[") and size.endswith("]"):
                size = size[1:-1].strip()
            if not _ARRAY_SIZE_RE.match(size):
                raise self.error(f"array dimension {dim!r} is not a size or a property constant", element)
            out.append(f"[{size.replace(' ', '')}]")
        return "".join(out)

    # ----------------------------------------------------------------- output

    def emit(self, level: int, text: str) -> None:
        self.lines.append(INDENT * level + text if text else "")

    def emit_wrapped(self, level: int, head: str, items: Sequence[str], tail: str) -> None:
        """``head item, item, ... tail`` on one line, or one item per line when too long."""
        one_line = f"{head}{', '.join(items)}{tail}"
        if len(INDENT * level) + len(one_line) <= LINE_LENGTH or len(items) < 2:
            self.emit(level, one_line)
            return
        self.emit(level, head.rstrip())
        for i, item in enumerate(items):
            self.emit(level + 1, item + ("," if i < len(items) - 1 else tail))

    # ----------------------------------------------------------------- units

    def write(self) -> str:
        kind = self.unit.eClass.name
        if kind == "AadlPackage":
            self.package(self.unit)
        elif kind == "PropertySet":
            self.property_set(self.unit)
        else:
            raise ExportError(f"cannot write a {kind} as AADL text: expected an AadlPackage or a PropertySet")
        return "\n".join(self.lines) + "\n"

    def package(self, pkg: EObject) -> None:
        unit_file_name(pkg)  # checks the name
        name = "::".join(part.strip() for part in pkg.name.split("::"))
        self.where = [name]
        for part in name.split("::"):
            self.ident(part, "the package", pkg)

        def split(items: Iterable[EObject]) -> tuple[list[EObject], list[EObject]]:
            items = list(items)
            hidden = [i for i in items if _enum_name(i.visibility) == "private"]
            return [i for i in items if _enum_name(i.visibility) != "private"], hidden

        public, private = split(pkg.classifiers)
        renamings, private_renamings = split(pkg.renamings)
        annexes, private_annexes = split(pkg.annexLibraries)
        self.emit(0, f"package {name}")
        self.emit(0, "public")
        self.package_section(pkg.withs, renamings, public, annexes)
        if private or pkg.privateWiths or private_renamings or private_annexes:
            self.emit(0, "private")
            self.package_section(pkg.privateWiths, private_renamings, private, private_annexes)
        if pkg.ownedPropertyAssociations:
            self.emit(0, "properties")
            for assoc in pkg.ownedPropertyAssociations:
                self.property_association(1, assoc)
        self.emit(0, f"end {name};")

    def package_section(
        self,
        withs: Sequence[str],
        renamings: Iterable[EObject],
        classifiers: Sequence[EObject],
        annexes: Iterable[EObject],
    ) -> None:
        head = False
        if withs:
            names = [self.qname(w, "with clause", self.unit) for w in withs]
            self.emit_wrapped(1, "with ", names, ";")
            head = True
        for renaming in renamings:
            self.renaming(renaming)
            head = True
        first = not head
        for classifier in classifiers:
            if not first:
                self.emit(1, "")
            first = False
            self.classifier(classifier)
        for annex in annexes:
            if not first:
                self.emit(1, "")
            first = False
            self.where.append(f"annex {annex.name}")
            text = self.annex_text(annex)
            self.emit(1, f"annex {self.ident(annex.name, 'the annex library', annex)} {text};")
            self.where.pop()

    def renaming(self, ren: EObject) -> None:
        kind = _enum_name(ren.kind) or "classifier"
        self.where.append(f"renames {ren.target}")
        name = self.ident(ren.name, "the renaming", ren) + " " if ren.name else ""
        if kind == "package":
            if not name:
                raise self.error("a package renaming needs a name", ren)
            self.emit(1, f"{name}renames package {self.qname(ren.target, 'renamed package', ren)};")
        elif kind == "all":
            target = (ren.target or "").strip()
            if target.lower().replace(" ", "").endswith("::all"):
                target = target[: target.lower().rindex("all")].rstrip().removesuffix("::").rstrip()
            self.emit(1, f"renames package {self.qname(target, 'renamed package', ren)}::all;")
        elif kind == "featureGroupType":
            target = self.classifier_ref(ren.target, "renamed feature group type", ren)
            self.emit(1, f"{name}renames feature group {target};")
        else:
            target = self.classifier_ref(ren.target, "renamed classifier", ren)
            self.emit(1, f"{name}renames {_literal(ren.category)} {target};")
        self.where.pop()

    # ----------------------------------------------------------------- classifiers

    def classifier(self, cl: EObject) -> None:
        kind = cl.eClass.name
        if kind == "ComponentImplementation":
            name = self.implementation_name(cl)
            header = f"{_literal(cl.category)} implementation {name}"
        elif kind == "ComponentType":
            name = self.ident(cl.name, f"the {_literal(cl.category)} type", cl)
            self.where.append(name)
            header = f"{_literal(cl.category)} {name}"
        elif kind == "FeatureGroupType":
            name = self.ident(cl.name, "the feature group type", cl)
            self.where.append(name)
            header = f"feature group {name}"
        else:
            raise self.error(f"cannot write a {kind} in a package", cl)
        if cl.extended:
            header += " extends " + self.classifier_ref(cl.extended, "extended classifier", cl)
        if cl.prototypeBindings:
            header += " " + self.bindings(cl.prototypeBindings, cl)
        self.emit(1, header)
        self.prototypes(cl)
        if kind == "ComponentType":
            self.features(cl.features)
            self.flow_specifications(cl.flowSpecifications)
            self.modes(cl)
        elif kind == "ComponentImplementation":
            self.subcomponents(cl.subcomponents)
            self.call_sequences(cl.callSequences)
            self.connections(cl)
            self.flow_implementations(cl)
            self.modes(cl)
        else:
            self.features(cl.features)
            if cl.inverseOf:
                self.emit(
                    2, "inverse of " + self.classifier_ref(cl.inverseOf, "inverse feature group type", cl)
                )
        if cl.ownedPropertyAssociations:
            self.emit(2, "properties")
            for assoc in cl.ownedPropertyAssociations:
                self.property_association(3, assoc)
        for annex in cl.annexSubclauses:
            self.annex_subclause(2, annex)
        self.emit(1, f"end {name};")
        self.where.pop()

    def implementation_name(self, impl: EObject) -> str:
        raw = " ".join((impl.name or "").split())
        type_name = (impl.type or "").strip().rpartition("::")[2].strip()
        match = _IMPL_NAME_RE.match(raw)
        if match is None and type_name and _ID_RE.match(raw):
            match = _IMPL_NAME_RE.match(f"{type_name}.{raw}")
        if match is None:
            self.where.append(raw or "?")
            raise self.error(
                f"the {_literal(impl.category)} implementation has {impl.name!r}: expected 'Type.impl' "
                "(two AADL identifiers joined by a dot)",
                impl,
            )
        name = f"{match.group(1)}.{match.group(2)}"
        self.where.append(name)
        self.ident(match.group(1), "the implementation's type", impl)
        self.ident(match.group(2), "the implementation", impl)
        if type_name and type_name.lower() != match.group(1).lower():
            raise self.error(f"the implementation is named {name!r} but implements type {impl.type!r}", impl)
        return name

    def prototypes(self, cl: EObject) -> None:
        if not cl.prototypes:
            return
        self.emit(2, "prototypes")
        for proto in cl.prototypes:
            name = self.ident(proto.name, "a prototype", proto)
            self.where.append(name)
            text = (proto.text or "").strip().removesuffix(";").strip()
            text = self.opaque(text, "prototype", proto)
            refined = "refined to " if proto.refined else ""
            self.emit(3, f"{name}: {refined}{text};")
            self.where.pop()

    # ----------------------------------------------------------------- features

    def features(self, features: Sequence[EObject]) -> None:
        if not features:
            return
        self.emit(2, "features")
        for feature in features:
            self.feature(feature)

    def feature(self, f: EObject) -> None:
        name = self.ident(f.name, "a feature", f)
        self.where.append(name)
        category = _enum_name(f.category)
        words = _FEATURE_WORDS[category]
        parts = [f"{name}:"]
        if f.refined:
            parts.append("refined to")
        if category in _DIRECTED:
            parts.append(_literal(f.direction) or "in")
        elif category in _OPTIONALLY_DIRECTED:
            direction = _enum_name(f.direction)  # 'in out' is the default: no word
            if direction in ("in", "out"):
                parts.append(direction)
        else:
            parts.append(_literal(f.access) or "provides")
        parts.append(words)
        if f.inverse:
            if category != "featureGroup":
                raise self.error("only a feature group can be 'inverse of' its type", f)
            parts.append("inverse of")
        if f.classifier:
            parts.append(self.feature_classifier(f.classifier, f))
        text = " ".join(parts)
        if f.arrayDimensions:
            if len(f.arrayDimensions) > 1:
                raise self.error("a feature array has one dimension in AADL", f)
            text += " " + self.array_dimensions(f.arrayDimensions, f)
        self.element_with_properties(3, text, f.ownedPropertyAssociations, "")
        self.where.pop()

    def feature_classifier(self, text: str, element: EObject) -> str:
        value = " ".join(text.split())
        if value.lower().startswith("prototype "):
            return "prototype " + self.ident(value[10:].strip(), "the prototype reference", element)
        return self.classifier_ref(value, "feature classifier", element)

    # ----------------------------------------------------------------- implementations

    def subcomponents(self, subs: Sequence[EObject]) -> None:
        if not subs:
            return
        self.emit(2, "subcomponents")
        for sub in subs:
            name = self.ident(sub.name, "a subcomponent", sub)
            self.where.append(name)
            text = f"{name}: " + ("refined to " if sub.refined else "") + _literal(sub.category)
            if sub.classifier:
                text += " " + self.classifier_ref(sub.classifier, "subcomponent classifier", sub)
            if sub.prototypeBindings:
                if not sub.classifier:
                    raise self.error("prototype bindings need a classifier", sub)
                text += " " + self.bindings(sub.prototypeBindings, sub)
            if sub.arrayDimensions:
                text += " " + self.array_dimensions(sub.arrayDimensions, sub)
            if sub.arrayElementBindings:
                if not sub.arrayDimensions:
                    raise self.error("array element implementations need array dimensions", sub)
                refs = [self.element_implementation(ref, sub) for ref in sub.arrayElementBindings]
                text += f" ({', '.join(refs)})"
            self.element_with_properties(
                3, text, sub.ownedPropertyAssociations, self.in_modes(sub.inModes, sub)
            )
            self.where.pop()

    def element_implementation(self, text: str, element: EObject) -> str:
        value = " ".join((text or "").split())
        match = re.match(rf"{_ID}(?:\s*::\s*{_ID})*(?:\s*\.\s*{_ID})?", value)
        if match is None:
            raise self.error(f"array element implementation {text!r} is not a classifier reference", element)
        ref = match.group(0).replace(" ", "")
        rest = value[match.end() :].strip()
        return f"{ref} {self.bindings(rest, element)}" if rest else ref

    def call_sequences(self, sequences: Sequence[EObject]) -> None:
        if not sequences:
            return
        self.emit(2, "calls")
        for seq in sequences:
            name = self.ident(seq.name, "a call sequence", seq)
            self.where.append(name)
            self.emit(3, f"{name}: {{")
            for call in seq.calls:
                call_name = self.ident(call.name, "a subprogram call", call)
                called = " ".join((call.called or "").split())
                processor = re.fullmatch(rf"processor\s*\.\s*({_ID})", called, re.I)
                if processor:
                    called = f"processor.{processor.group(1)}"
                else:
                    called = self.classifier_ref(called, f"the subprogram called by {call_name!r}", call)
                self.element_with_properties(
                    4, f"{call_name}: subprogram {called}", call.ownedPropertyAssociations, ""
                )
            self.element_with_properties(
                3, "}", seq.ownedPropertyAssociations, self.in_modes(seq.inModes, seq)
            )
            self.where.pop()

    def connections(self, impl: EObject) -> None:
        if not impl.connections:
            return
        self.emit(2, "connections")
        for conn in impl.connections:
            label = conn.name or f"{conn.source} -> {conn.destination}"
            self.where.append(label)
            kind = _enum_name(conn.kind)
            if kind == "accessConnection":
                category = self.access_category(conn, impl)
                words = f"{category} access" if category else "access"
            elif kind in _CONNECTION_WORDS:
                words = _CONNECTION_WORDS[kind]
            else:
                raise self.error(f"a {_literal(conn.kind)} connection has no AADL text form", conn)
            text = f"{self.ident(conn.name, 'a connection', conn)}: " if conn.name else ""
            if conn.refined:
                if not conn.name:
                    raise self.error("a refined connection needs the name of the connection it refines", conn)
                text += "refined to "
            text += words
            if conn.source or conn.destination:
                if not (conn.source and conn.destination):
                    raise self.error("a connection needs both a source and a destination", conn)
                arrow = "<->" if conn.bidirectional else "->"
                source = self.connection_end(conn.source, "source", conn)
                destination = self.connection_end(conn.destination, "destination", conn)
                text += f" {source} {arrow} {destination}"
            elif not conn.refined:
                raise self.error("a connection needs a source and a destination", conn)
            self.element_with_properties(
                3, text, conn.ownedPropertyAssociations, self.in_modes(conn.inModes, conn)
            )
            self.where.pop()

    def connection_end(self, text: str, what: str, element: EObject) -> str:
        value = " ".join(text.split())
        special = re.fullmatch(rf"(processor|self)\s*\.\s*({_ID})", value, re.I)
        if special:
            return f"{special.group(1).lower()}.{special.group(2)}"
        return self.path(value, f"connection {what}", element)

    def access_category(self, conn: EObject, impl: EObject) -> str:
        given = _enum_name(conn.accessCategory)
        if given and given != "abstract":  # 'abstract' is the unset value
            category = _ACCESS_COMPONENT_CATEGORY.get(given)
            if category is None:
                raise self.error(f"{_literal(conn.accessCategory)!r} is not an access category", conn)
            return category
        for end in (conn.source, conn.destination):
            category = self.infer_access_category(end or "", impl)
            if category:
                return category
        log.warning(
            "in %s: the category of access connection %r is not set and its ends do not resolve in the "
            "model; writing 'access' without a category (OSATE needs one)",
            " / ".join(self.where[:-1]),
            conn.name or f"{conn.source} -> {conn.destination}",
        )
        return ""

    def infer_access_category(self, end: str, impl: EObject) -> str:
        parts = [p.strip() for p in end.split(".")]
        if len(parts) == 1:
            for sub in self.chain(impl, "subcomponents"):
                if (sub.name or "").lower() == parts[0].lower():
                    return _ACCESS_COMPONENT_CATEGORY.get(_enum_name(sub.category), "")
            own_type = self.type_of(impl)
            if own_type is not None:
                return self.feature_access_category(own_type, parts[0])
            return ""
        if len(parts) == 2:
            for sub in self.chain(impl, "subcomponents"):
                if (sub.name or "").lower() == parts[0].lower():
                    classifier = self.resolve(sub.classifier, impl) if sub.classifier else None
                    if classifier is None:
                        return ""
                    if classifier.eClass.name == "ComponentImplementation":
                        classifier = self.type_of(classifier)
                    if classifier is None:
                        return ""
                    return self.feature_access_category(classifier, parts[1])
        return ""

    def feature_access_category(self, classifier: EObject, name: str) -> str:
        for feature in self.chain(classifier, "features"):
            if (feature.name or "").lower() == name.lower():
                return _ACCESS_FEATURE_CATEGORY.get(_enum_name(feature.category), "")
        return ""

    def resolve(self, ref: str | None, context: EObject) -> EObject | None:
        if not ref:
            return None
        text = ref.replace(" ", "")
        pkg_name, _, local = text.rpartition("::")
        if not pkg_name:
            owner = context.eContainer()
            while owner is not None and owner.eClass.name != "AadlPackage":
                owner = owner.eContainer()
            pkg_name = owner.name if owner is not None else ""
        key = f"{pkg_name}::{local}".lower()
        if key in self._classifier_cache:
            return self._classifier_cache[key]
        found = None
        units = self.root.units if self.root.eClass.name == "AadlModel" else [self.root]
        for unit in units:
            if (
                unit.eClass.name == "AadlPackage"
                and (unit.name or "").replace(" ", "").lower() == pkg_name.lower()
            ):
                for classifier in unit.classifiers:
                    if (classifier.name or "").replace(" ", "").lower() == local.lower():
                        found = classifier
                        break
        self._classifier_cache[key] = found
        return found

    def type_of(self, impl: EObject) -> EObject | None:
        if impl.type:
            return self.resolve(impl.type, impl)
        name = (impl.name or "").partition(".")[0]
        return self.resolve(name, impl) if name else None

    def chain(self, classifier: EObject, feature: str) -> list[EObject]:
        """The ``feature`` items of a classifier and of the classifiers it extends (nearest first)."""
        out: list[EObject] = []
        seen: set[int] = set()
        current: EObject | None = classifier
        while current is not None and id(current) not in seen:
            seen.add(id(current))
            if current.eClass.findEStructuralFeature(feature) is not None:
                out.extend(getattr(current, feature))
            current = self.resolve(current.extended, current) if current.extended else None
        return out

    # ----------------------------------------------------------------- flows and modes

    def flow_specifications(self, flows: Sequence[EObject]) -> None:
        if not flows:
            return
        self.emit(2, "flows")
        for flow in flows:
            name = self.ident(flow.name, "a flow specification", flow)
            self.where.append(name)
            kind = _enum_name(flow.kind)
            text = f"{name}: " + ("refined to " if flow.refined else "") + f"flow {kind}"
            if kind == "source":
                ends = [flow.outEnd] if flow.outEnd else []
            elif kind == "sink":
                ends = [flow.inEnd] if flow.inEnd else []
            else:
                ends = [flow.inEnd, flow.outEnd] if (flow.inEnd or flow.outEnd) else []
                if ends and not all(ends):
                    raise self.error("a flow path needs both an in end and an out end", flow)
            if not ends and not flow.refined:
                raise self.error(f"a flow {kind} needs its end feature", flow)
            if ends:
                text += " " + " -> ".join(self.path(e, "flow end", flow) for e in ends)
            self.element_with_properties(
                3, text, flow.ownedPropertyAssociations, self.in_modes(flow.inModes, flow)
            )
            self.where.pop()

    def flow_implementations(self, impl: EObject) -> None:
        if not (impl.flowImplementations or impl.endToEndFlows):
            return
        self.emit(2, "flows")
        for flow in impl.flowImplementations:
            name = self.ident(flow.name, "a flow implementation", flow)
            self.where.append(name)
            if not flow.elements:
                raise self.error("a flow implementation needs its flow elements", flow)
            elements = " -> ".join(self.path(e, "flow element", flow) for e in flow.elements)
            text = f"{name}: flow {_enum_name(flow.kind)} {elements}"
            self.element_with_properties(
                3, text, flow.ownedPropertyAssociations, self.in_modes(flow.inModes, flow)
            )
            self.where.pop()
        for flow in impl.endToEndFlows:
            name = self.ident(flow.name, "an end-to-end flow", flow)
            self.where.append(name)
            text = f"{name}: " + ("refined to " if flow.refined else "") + "end to end flow"
            if flow.elements:
                text += " " + " -> ".join(self.path(e, "flow element", flow) for e in flow.elements)
            elif not flow.refined:
                raise self.error("an end-to-end flow needs its flow elements", flow)
            self.element_with_properties(
                3, text, flow.ownedPropertyAssociations, self.in_modes(flow.inModes, flow)
            )
            self.where.pop()

    def modes(self, cl: EObject) -> None:
        if not (cl.modes or cl.modeTransitions):
            return
        self.emit(2, "requires modes" if cl.requiresModes else "modes")
        for mode in cl.modes:
            name = self.ident(mode.name, "a mode", mode)
            self.where.append(name)
            text = f"{name}: " + ("initial " if mode.initial else "") + "mode"
            self.element_with_properties(3, text, mode.ownedPropertyAssociations, "")
            self.where.pop()
        for tr in cl.modeTransitions:
            label = tr.name or f"{tr.source} -> {tr.destination}"
            self.where.append(label)
            text = f"{self.ident(tr.name, 'a mode transition', tr)}: " if tr.name else ""
            source = self.ident(tr.source, "the transition's source mode", tr)
            destination = self.ident(tr.destination, "the transition's destination mode", tr)
            if not tr.triggers:
                raise self.error("a mode transition needs at least one trigger", tr)
            triggers = ", ".join(self.connection_end(t or "", "trigger", tr) for t in tr.triggers)
            text += f"{source} -[ {triggers} ]-> {destination}"
            self.element_with_properties(3, text, tr.ownedPropertyAssociations, "")
            self.where.pop()

    # ----------------------------------------------------------------- annexes

    def annex_text(self, annex: EObject) -> str:
        text = annex.text
        if text is None:
            return "none"
        delimited = text.startswith("{**") and text.endswith("**}") and len(text) >= 6
        inner = text[3:-3] if delimited else text
        if "**}" in inner:
            raise self.error("annex text cannot contain '**}'", annex)
        return "{**" + inner + "**}"

    def annex_subclause(self, level: int, annex: EObject) -> None:
        name = self.ident(annex.name, "an annex subclause", annex)
        self.where.append(f"annex {name}")
        text = self.annex_text(annex)
        self.emit(level, f"annex {name} {text}{self.in_modes(annex.inModes, annex)};")
        self.where.pop()

    # ----------------------------------------------------------------- property associations

    def modal_item(self, text: str, element: EObject) -> None:
        """A section item with its property block and ``in modes`` (subcomponents, connections, ...)."""
        suffix = self.in_modes(element.inModes, element)
        self.element_with_properties(3, text, element.ownedPropertyAssociations, suffix)

    def element_with_properties(self, level: int, text: str, assocs: Sequence[EObject], suffix: str) -> None:
        """``text {assoc; ...}suffix;``: inline for one short association, else one per line."""
        if not assocs:
            self.emit(level, f"{text}{suffix};")
            return
        rendered = [self.association_parts(a) for a in assocs]
        if len(rendered) == 1:
            head, tail = rendered[0]
            one = f"{head} {tail};" if tail else f"{head};"
            line = f"{text} {{ {one} }}{suffix};"
            if len(INDENT * level) + len(line) <= LINE_LENGTH:
                self.emit(level, line)
                return
        self.emit(level, f"{text} {{")
        for parts in rendered:
            self.emit_association(level + 1, parts)
        self.emit(level, f"}}{suffix};")

    def property_association(self, level: int, assoc: EObject) -> None:
        self.emit_association(level, self.association_parts(assoc))

    def emit_association(self, level: int, parts: tuple[str, str]) -> None:
        """One line; when too long, ``applies to``/``in binding`` go on a line of their own."""
        head, tail = parts
        line = f"{head} {tail};" if tail else f"{head};"
        if not tail or len(INDENT * level) + len(line) <= LINE_LENGTH:
            self.emit(level, line)
        else:
            self.emit(level, head)
            self.emit(level + 1, f"{tail};")

    def association_parts(self, assoc: EObject) -> tuple[str, str]:
        """``Name => value`` and what follows it (``applies to ...``, ``in binding (...)``)."""
        prop = self.qname(assoc.property, "property name", assoc)
        self.where.append(prop)
        arrow = "+=>" if assoc.append else "=>"
        constant = "constant " if assoc.constant else ""
        values = list(assoc.ownedValues)
        if not values:
            raise self.error("a property association needs a value", assoc)
        if len(values) == 1 and not values[0].inModes:
            value = self.value(values[0].value)
        else:
            modal = [v for v in values if v.inModes]
            default = [v for v in values if not v.inModes]
            if len(default) > 1:
                raise self.error("a modal property value can have only one value without 'in modes'", assoc)
            items = [self.value(v.value) + self.in_modes(v.inModes, v) for v in modal]
            items += [self.value(v.value) for v in default]
            value = f"({', '.join(items)})"
        tail = []
        if assoc.appliesTo:
            paths = [self.path(p, "'applies to' path", assoc) for p in assoc.appliesTo]
            tail.append("applies to " + ", ".join(paths))
        if assoc.inBinding:
            refs = [self.classifier_ref(c, "'in binding' classifier", assoc) for c in assoc.inBinding]
            tail.append(f"in binding ({', '.join(refs)})")
        self.where.pop()
        return f"{prop} {arrow} {constant}{value}", " ".join(tail)

    # ----------------------------------------------------------------- values

    def value(self, expr: EObject | None) -> str:
        if expr is None:
            raise self.error("a property value is missing")
        kind = expr.eClass.name
        method = getattr(self, f"value_{kind}", None)
        if method is None:
            raise self.error(f"a {kind} has no AADL text form", expr)
        return method(expr)

    def number_unit(self, expr: EObject) -> str:
        return " " + self.ident(expr.unit, "the unit", expr) if expr.unit else ""

    def value_IntegerValue(self, expr: EObject) -> str:  # noqa: N802 - dispatch on class names
        return f"{int(expr.value or 0)}{self.number_unit(expr)}"

    def value_RealValue(self, expr: EObject) -> str:  # noqa: N802
        try:
            text = format_real(expr.value or 0.0)
        except ValueError:
            raise self.error(f"the real value {expr.value!r} has no AADL literal", expr) from None
        return text + self.number_unit(expr)

    def value_RangeValue(self, expr: EObject) -> str:  # noqa: N802
        if expr.minimum is None or expr.maximum is None:
            raise self.error("a range needs a minimum and a maximum", expr)
        text = f"{self.range_bound(expr.minimum)} .. {self.range_bound(expr.maximum)}"
        if expr.delta is not None:
            text += f" delta {self.range_bound(expr.delta)}"
        return text

    def range_bound(self, expr: EObject) -> str:
        kind = expr.eClass.name
        if kind in ("IntegerValue", "RealValue", "NamedValue") or (
            kind == "OperationValue" and (expr.operator or "").lower() in _SIGN_OPERATORS
        ):
            return self.value(expr)
        raise self.error(f"a range bound must be a number or a constant, not a {kind}", expr)

    def value_BooleanValue(self, expr: EObject) -> str:  # noqa: N802
        return "true" if expr.value else "false"

    def value_StringValue(self, expr: EObject) -> str:  # noqa: N802
        return _string_literal(expr.value or "")

    def value_NamedValue(self, expr: EObject) -> str:  # noqa: N802
        return self.qname(expr.name, "named value", expr)

    def value_ReferenceValue(self, expr: EObject) -> str:  # noqa: N802
        return f"reference ({self.path(expr.path, 'reference path', expr)})"

    def value_ClassifierValue(self, expr: EObject) -> str:  # noqa: N802
        return f"classifier ({self.classifier_ref(expr.classifier, 'classifier value', expr)})"

    def value_ListValue(self, expr: EObject) -> str:  # noqa: N802
        return "(" + ", ".join(self.value(item) for item in expr.ownedItems) + ")"

    def value_RecordValue(self, expr: EObject) -> str:  # noqa: N802
        fields = []
        for field in expr.ownedFields:
            fields.append(f"{self.ident(field.name, 'a record field', field)} => {self.value(field.value)};")
        return "[" + " ".join(fields) + "]"

    def value_ComputedValue(self, expr: EObject) -> str:  # noqa: N802
        return f"compute ({self.ident(expr.function, 'the computed value function', expr)})"

    def value_OperationValue(self, expr: EObject) -> str:  # noqa: N802
        operator = (expr.operator or "").strip().lower()
        operands = list(expr.ownedOperands)
        if operator in _SIGN_OPERATORS:
            if len(operands) != 1:
                raise self.error(f"unary {operator!r} needs one operand", expr)
            operand = operands[0]
            kind = operand.eClass.name
            if kind == "NamedValue":
                return _SIGN_OPERATORS[operator] + self.value(operand)
            if kind in ("IntegerValue", "RealValue") and (operand.value or 0) >= 0:
                return _SIGN_OPERATORS[operator] + self.value(operand)
            raise self.error(f"a signed {kind} cannot be written in AADL", expr)
        if operator not in _BOOLEAN_OPERATORS:
            raise self.error(f"unknown operator {expr.operator!r} (expected and, or, not, + or -)", expr)
        if operator == "not":
            if len(operands) != 1:
                raise self.error("'not' needs one operand", expr)
            return "not " + self.boolean_operand(operands[0], ("and", "or"))
        if len(operands) < 2:
            raise self.error(f"'{operator}' needs at least two operands", expr)
        # 'not' binds tighter than 'and', 'and' tighter than 'or'; an operand that would otherwise
        # merge into this operation (or bind wrongly) is parenthesised, so the tree is kept
        nested = ("and", "or") if operator == "and" else ("or",)
        return f" {operator} ".join(self.boolean_operand(op, nested) for op in operands)

    def boolean_operand(self, expr: EObject, parenthesised: tuple[str, ...]) -> str:
        text = self.value(expr)
        if expr.eClass.name == "OperationValue" and (expr.operator or "").strip().lower() in parenthesised:
            return f"({text})"
        return text

    # ----------------------------------------------------------------- property sets

    def property_set(self, ps: EObject) -> None:
        unit_file_name(ps)
        name = self.ident(ps.name, "the property set", ps)
        self.where = [name]
        if ps.annexSubclauses:
            raise self.error("a property set cannot hold annex subclauses in AADL text", ps)
        self.emit(0, f"property set {name} is")
        groups = 0
        if ps.withs:
            self.emit_wrapped(1, "with ", [self.ident(w.strip(), "with clause", ps) for w in ps.withs], ";")
            groups += 1
        for items, method in (
            (ps.ownedPropertyTypes, self.property_type_declaration),
            (ps.ownedProperties, self.property_definition),
            (ps.ownedPropertyConstants, self.property_constant),
        ):
            if not items:
                continue
            if groups:
                self.emit(1, "")
            groups += 1
            for item in items:
                method(item)
        self.emit(0, f"end {name};")

    def property_type_declaration(self, ptype: EObject) -> None:
        name = self.ident(ptype.name, "a property type", ptype)
        self.where.append(name)
        kind = ptype.eClass.name
        head = f"{name}: type "
        if kind == "EnumerationType" and ptype.ownedLiterals:
            literals = [self.ident(lit.name, "an enumeration literal", lit) for lit in ptype.ownedLiterals]
            self.emit_wrapped(1, head + "enumeration (", literals, ");")
        elif kind == "UnitsType" and len(ptype.ownedLiterals) > 2:
            self.emit_wrapped(1, head + "units (", self.unit_literals(ptype), ");")
        else:
            self.emit(1, head + self.type_text(ptype) + ";")
        self.where.pop()

    def property_definition(self, prop: EObject) -> None:
        name = self.ident(prop.name, "a property", prop)
        self.where.append(name)
        text = f"{name}: " + ("inherit " if prop.inherit else "") + self.type_ref(prop)
        if prop.defaultValue is not None:
            text += " => " + self.value(prop.defaultValue)
        owners = self.owners(prop)
        self.emit_wrapped(1, f"{text} applies to (", owners, ");")
        self.where.pop()

    def property_constant(self, const: EObject) -> None:
        name = self.ident(const.name, "a property constant", const)
        self.where.append(name)
        if const.value is None:
            raise self.error("a property constant needs a value", const)
        self.emit(1, f"{name}: constant {self.type_ref(const)} => {self.value(const.value)};")
        self.where.pop()

    def owners(self, prop: EObject) -> list[str]:
        owners = [" ".join((o or "").split()) for o in prop.appliesTo]
        if not owners:
            raise self.error("a property definition needs its 'applies to' owners (or 'all')", prop)
        if any(o.lower() == "all" for o in owners):
            if len(owners) > 1:
                raise self.error("'applies to (all)' cannot list other owners", prop)
            return ["all"]
        for owner in owners:
            if not _OWNER_RE.match(owner):
                raise self.error(f"'applies to' owner {owner!r} is not a category or a classifier", prop)
        return [o.replace(" ::", "::").replace(":: ", "::") for o in owners]

    def type_ref(self, element: EObject, attribute: str = "type", owned: str = "ownedType") -> str:
        """A named type (qualified name) or a type written out."""
        owned_type = getattr(element, owned)
        if owned_type is not None:
            return self.type_text(owned_type)
        named = getattr(element, attribute)
        if not named:
            raise self.error("a type is missing", element)
        return self.qname(named, "property type name", element)

    def unit_literals(self, units: EObject) -> list[str]:
        out = []
        for i, lit in enumerate(units.ownedLiterals):
            name = self.ident(lit.name, "a unit literal", lit)
            if i == 0:
                if lit.baseUnit or lit.factor is not None:
                    raise self.error(f"the first unit {name!r} is the base unit: it has no conversion", lit)
                out.append(name)
                continue
            if not lit.baseUnit or lit.factor is None:
                raise self.error(f"unit {name!r} needs a base unit and a factor", lit)
            if lit.factor.eClass.name not in ("IntegerValue", "RealValue") or lit.factor.unit:
                raise self.error(f"the factor of unit {name!r} must be a number without unit", lit)
            base = self.ident(lit.baseUnit, "the base unit", lit)
            out.append(f"{name} => {base} * {self.value(lit.factor)}")
        return out

    def type_text(self, ptype: EObject) -> str:
        kind = ptype.eClass.name
        if kind == "AadlBoolean":
            return "aadlboolean"
        if kind == "AadlString":
            return "aadlstring"
        if kind == "EnumerationType":
            if not ptype.ownedLiterals:
                raise self.error("an enumeration type needs literals", ptype)
            literals = [self.ident(lit.name, "an enumeration literal", lit) for lit in ptype.ownedLiterals]
            return f"enumeration ({', '.join(literals)})"
        if kind == "UnitsType":
            if not ptype.ownedLiterals:
                raise self.error("a units type needs literals", ptype)
            return f"units ({', '.join(self.unit_literals(ptype))})"
        if kind in ("AadlInteger", "AadlReal"):
            text = "aadlinteger" if kind == "AadlInteger" else "aadlreal"
            if ptype.range is not None:
                if ptype.range.eClass.name != "RangeValue":
                    raise self.error("the range of a number type must be a range value", ptype)
                text += " " + self.value(ptype.range)
            if ptype.ownedUnitsType is not None:
                text += " " + self.type_text(ptype.ownedUnitsType)
            elif ptype.unitsType:
                text += " units " + self.qname(ptype.unitsType, "units type name", ptype)
            return text
        if kind == "RangeType":
            return "range of " + self.type_ref(ptype, "numberType", "ownedNumberType")
        if kind in ("ClassifierType", "ReferenceType"):
            word = "classifier" if kind == "ClassifierType" else "reference"
            categories = [" ".join((c or "").split()) for c in ptype.categories]
            for category in categories:
                if not _OWNER_RE.match(category):
                    raise self.error(f"{word} type category {category!r} is not well-formed", ptype)
            return f"{word} ({', '.join(categories)})" if categories else word
        if kind == "RecordType":
            if not ptype.ownedFields:
                raise self.error("a record type needs fields", ptype)
            fields = [
                f"{self.ident(field.name, 'a record field', field)}: {self.type_ref(field)};"
                for field in ptype.ownedFields
            ]
            return f"record ({' '.join(fields)})"
        if kind == "ListType":
            return "list of " + self.type_ref(ptype, "elementType", "ownedElementType")
        raise self.error(f"a {kind} has no AADL text form", ptype)


# --------------------------------------------------------------------------- public API


def write_unit(unit: EObject) -> str:
    """AADL text for one ``AadlPackage`` or ``PropertySet`` (ends with a newline).

    Raises :class:`ExportError` naming the element when something cannot be written as AADL.
    """
    if not isinstance(unit, EObject):
        raise ExportError(f"expected an AadlPackage or a PropertySet, got {type(unit).__name__}")
    return _UnitWriter(unit).write()


def write_units(units: Iterable[EObject]) -> dict[str, str]:
    """File name (``a::b`` → ``a-b.aadl``) → text, in the order of ``units``.

    Two units whose file names differ only by case (AADL names are case-insensitive) are an error.
    """
    out: dict[str, str] = {}
    seen: dict[str, str] = {}
    for unit in units:
        name = unit_file_name(unit)
        key = name.lower()
        if key in seen:
            raise ExportError(
                f"two model units would both be written to {name!r} ({seen[key]!r} and {unit.name!r}); "
                "AADL names are case-insensitive",
                Location(path=unit.name),
            )
        seen[key] = unit.name
        out[name] = write_unit(unit)
    return out


def write_model(model: EObject | Iterable[EObject], out_dir: str | os.PathLike[str]) -> list[Path]:
    """Write every unit of an ``AadlModel`` (or the given units) as ``<unit>.aadl`` into ``out_dir``.

    All texts are made before the first file is written, so an error leaves no output at all;
    each file is written atomically. A unit name that is not an AADL name (``../../etc``) is
    refused with :class:`ExportError`, and no path can land outside ``out_dir``.
    """
    if isinstance(model, EObject) and model.eClass.name in ("AadlPackage", "PropertySet"):
        units: list[EObject] = [model]
    elif isinstance(model, EObject) and model.eClass.name == "AadlModel":
        units = list(model.units)
    elif not isinstance(model, EObject):
        units = list(model)
    else:
        shown = model.eClass.name if isinstance(model, EObject) else type(model).__name__
        raise ExportError(f"expected an AadlModel, got {shown}")
    texts = write_units(units)
    targets = [(fileio.safe_join(out_dir, name), text) for name, text in texts.items()]
    written = []
    for target, text in targets:
        fileio.atomic_write_text(target, text)
        written.append(target)
    log.info("wrote %d AADL file(s) to %s", len(written), out_dir)
    return written

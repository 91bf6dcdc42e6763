"""The state of mapping one WebGME ROSMOD project onto ``rosmod.ecore``, and the helpers every part uses.

A :class:`Mapper` is one project's run: the model object made from each WebGME node (by path,
for the relations resolved later), the references to set at the end, and the run's
:class:`~rosaadl.importers.rosmod_text.context.ImportContext`. WebGME facts without a slot in
the metamodel are kept as ``properties``: attribute keys exactly as WebGME spells them, and
children without a slot as ``"<Kind>:<name>"`` properties whose value is a JSON object of their
attributes and pointers (:meth:`Mapper.opaque`). The parts of a project are mapped by
:mod:`.software`, :mod:`.systems` and :mod:`.deployments`.
"""

from __future__ import annotations

import json
import logging
from decimal import Decimal, InvalidOperation
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import ImportFormatError, Location, RosaadlError
from rosaadl.importers.rosmod_text.context import ImportContext
from rosaadl.importers.rosmod_text.statements import MAX_INTEGER, SCHEMES, scheme_literal, time_problem
from rosaadl.importers.rosmod_webgme.tree import Node, Tree

__all__ = ["SKIPPED_KINDS", "Mapper", "text", "type_name"]

log = logging.getLogger(__package__)

#: Kinds of WebGME nodes that hold nothing of the model (documentation, run results).
SKIPPED_KINDS = ("Documentation", "Code Documentation", "Results")


def text(value: Any) -> str:
    """An attribute value as property text (booleans as ``true``/``false``, JSON for structures)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (dict, list)):
        return json.dumps(value, sort_keys=True)
    return "" if value is None else str(value)


def type_name(target: Node, seen: tuple[str, ...] = ()) -> str | None:
    """``pkg/Name`` of a message, service or action node (external and advertised ones included)."""
    kind = target.meta_type
    if kind in ("Message", "Service", "Action"):
        parent = target.parent
        return f"{parent.name}/{target.name}" if parent is not None else target.name
    if kind in ("External Message", "External Service", "External Action"):
        package = target.attribute("Package")
        return f"{package}/{target.name}" if package else target.name
    if kind.startswith("Advertised ") and target.path not in seen:
        inner = target.pointer("Type")
        return type_name(inner, (*seen, target.path)) if inner is not None else None
    return None


def _decimal(value: Any) -> Decimal:
    return Decimal(repr(value)) if isinstance(value, float) else Decimal(str(value).strip())


class Mapper:
    """Maps the WebGME tree of one project onto a ``rosmod.Project`` (one run, no global state)."""

    def __init__(self, tree: Tree, filename: str, ctx: ImportContext) -> None:
        self.tree = tree
        self.filename = filename
        self.ctx = ctx
        self.by_path: dict[str, EObject] = {}  # WebGME node path → model object
        self.experiments: list[tuple[str, Node]] = []
        self.pending_components: list[tuple[EObject, Node, Node]] = []

    # -- diagnostics
    def warn(self, node: Node, message: str) -> None:
        self.ctx.warn(message, self.filename, path=node.element_path())

    def error(self, node: Node, message: str, cls: type[RosaadlError] = ImportFormatError) -> None:
        self.ctx.error(cls(message, Location(file=self.filename, path=node.element_path())))

    def warn_duplicates(self, node: Node, objects: Any, what: str, owner: str) -> None:
        """Warn at ``node`` for each name of ``objects`` used a second time (WebGME allows it)."""
        seen: set[str] = set()
        for obj in objects:
            if obj.name in seen:
                self.warn(node, f"{what} name {obj.name!r} is used twice in {owner}")
            seen.add(obj.name)

    # -- nodes
    def children(self, node: Node) -> list[Node]:
        """The children of ``node`` by name (those without a base, which WebGME drops, with a warning)."""
        out = []
        for child in node.children():
            if child.base is None:
                self.warn(child, "node without a base (WebGME drops such nodes); skipped")
                continue
            out.append(child)
        return sorted(out, key=lambda c: (c.name, c.relid))

    def unknown(self, parent: Node, child: Node, properties: Any) -> None:
        """Keep ``child``, which has no rosmod counterpart, as a property of ``parent`` (and say so)."""
        kind = child.meta_type or "?"
        if kind in SKIPPED_KINDS:
            return
        self.warn(
            child, f"{kind} {child.name!r} has no rosmod counterpart; kept as a property of {parent.name!r}"
        )
        properties.append(self.prop(f"{kind}:{child.name}", self.opaque(child)))

    # -- values
    def opaque(self, node: Node) -> str:
        """A JSON summary of an element the metamodel has no class for."""
        value: dict[str, Any] = {k: text(v) for k, v in node.project_attributes().items()}
        for name in ("Type", "Action", "Message", "Service", "src", "dst"):
            target = node.pointer(name)
            if target is not None:
                value[name] = type_name(target) or target.element_path()
        kids = [f"{c.meta_type}:{c.name}" for c in self.children(node)]
        if kids:
            value["children"] = kids
        return json.dumps(value, sort_keys=True)

    def opaque_attrs(self, node: Node) -> str:
        """A JSON object of the attributes ``node`` sets in the project."""
        return json.dumps({k: text(v) for k, v in node.project_attributes().items()}, sort_keys=True)

    def prop(self, key: str, value: Any) -> EObject:
        return model.new("rosmod.Property", key=key, value=text(value))

    def seconds(self, node: Node, attr: str) -> Decimal | None:
        value = node.attribute(attr)
        if value is None or value == "":
            return None
        try:
            number = _decimal(value)
        except InvalidOperation:
            self.error(node, f"{attr} = {value!r}: expected a number of seconds")
            return None
        if not number.is_finite() or number < 0:
            self.error(node, f"{attr} = {value!r}: expected a non-negative number of seconds")
            return None
        problem = time_problem(number)
        if problem is not None:
            self.error(node, f"{attr} = {value!r}: {problem}")
            return None
        return number

    def integer(self, node: Node, attr: str) -> int | None:
        value = node.attribute(attr)
        if value is None or value == "":
            return None
        try:
            number = _decimal(value)
            if number.is_finite() and abs(number) <= MAX_INTEGER and number == number.to_integral_value():
                return int(number)
        except InvalidOperation:
            pass
        self.error(node, f"{attr} = {value!r}: expected an integer")
        return None

    def scheme(self, node: Node, target: EObject, scheme: Any) -> None:
        """Set the scheduling scheme of ``target`` (an unknown one is kept as a property, with a warning)."""
        if scheme is None or scheme == "":
            return
        if scheme in SCHEMES:
            target.schedulingScheme = scheme_literal(scheme)
        else:
            self.warn(
                node,
                f"unknown scheduling scheme {scheme!r} (expected {', '.join(SCHEMES)}); kept as a property",
            )
            target.properties.append(self.prop("SchedulingScheme", scheme))

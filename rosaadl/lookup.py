"""AADL property value lookup on declarative elements and instance objects.

The rules are AADL's (SAE AS5506C §11.3), as OSATE applies them.  For a component the value of a
property comes from, in this order:

1. a *contained* property association (``applies to`` path) declared in an enclosing
   implementation or in the property block of an enclosing subcomponent — the outermost one wins;
2. the subcomponent's own associations (through ``refined to``);
3. the classifier: the implementation, its ``extends`` chain, then the type and its chain;
4. for an ``inherit`` property, the value of the containing component;
5. the property's default value.

Features look at their own associations, then at their classifier (a data type gives its
``Data_Size`` to the ports it types); connections at their declaration; modes and flows at their
declaration.  ``+=>`` appends the list items to the value found further down that order; values
in modes keep their ``in modes``; ``in binding`` associations apply when the component is bound
to a processor of the named classifier.

:class:`PropertyLookup` answers questions on declarative elements (classifiers, subcomponents,
features, connections, modes, flows) and on instance objects.  An instance object made by
:mod:`rosaadl.transforms.instantiate` already carries its resolved values; for other instance
trees the values are computed from the declarative model.  Values come back as
``PropertyExpression`` elements, or as Python values through :meth:`PropertyLookup.python_value`.
"""

from __future__ import annotations

import functools
import logging
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.bulk import FastBuilder, FastFactory
from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.properties import python_value as _python_value
from rosaadl.resolution import PathSegment, Resolver, split_path
from rosaadl.units import standard_units

__all__ = [
    "PropertyLookup",
    "Found",
    "ComponentNode",
    "Factory",
    "NoValue",
    "accepts",
    "resolve_instance_path",
]

log = logging.getLogger(__name__)

_STANDARD_UNITS = standard_units()

_PORT_WORDS = frozenset({"data port", "event port", "event data port"})
_ACCESS_WORDS = frozenset(
    {"bus access", "data access", "subprogram access", "subprogram group access", "virtual bus access"}
)
_UNIVERSAL = frozenset({"all", "named element", "element"})


def _words(text: str) -> str:
    return " ".join((text or "").lower().split())


def accepts(prop: EObject | None, kind: str, word: str) -> bool:
    """Whether property ``prop`` applies to an object of ``kind`` (``component``, ``feature``,
    ``connection``, ``flow``, ``end to end flow``, ``mode``) described by ``word``
    (``thread group``, ``event data port``, ``port connection``, ...).

    An unknown property (its set is not loaded) applies wherever it has a value.
    """
    if prop is None:
        return True
    for raw in prop.appliesTo:
        owner = _words(raw)
        if owner in _UNIVERSAL or "::" in owner:
            return True
        if kind == "component":
            if word == "abstract" or owner in (word, "component", f"{word} type", f"{word} implementation"):
                return True
        elif kind == "classifier":
            if owner == word:
                return True
        elif kind == "feature":
            if owner in (word, "feature"):
                return True
            if owner == "port" and word in _PORT_WORDS:
                return True
            if owner == "access" and word in _ACCESS_WORDS:
                return True
            if owner == "directed feature" and (
                word in _PORT_WORDS or word in ("parameter", "abstract feature")
            ):
                return True
            if owner == "feature" or (owner == "abstract feature" and word == "abstract feature"):
                return True
        elif kind == "connection":
            if owner in (word, "connection"):
                return True
        elif kind == "end to end flow":
            if owner in ("end to end flow", "flow"):
                return True
        elif kind == "flow":
            if owner in ("flow", "flow specification", "flow implementation", word):
                return True
        elif kind == "mode":
            if owner in ("mode", word):
                return True
        elif owner == word:
            return True
    return False


@dataclass
class Found:
    """The winning association(s) for one property on one object.

    ``parts`` runs from the highest precedence down: the first part is the association that set the
    value; when it appends (``+=>``), the following parts are the values it appends to.  Each part is
    ``(association or None, modal values [(expression, in modes)], anchor)``; the anchor is the
    component (node) relative to which ``reference (...)`` paths of that association are resolved.
    """

    parts: list[tuple[EObject | None, list[tuple[EObject, list[str]]], Any]]
    complete: bool = True  # False when only appending associations were found (no base value)

    @property
    def association(self) -> EObject | None:
        return self.parts[0][0] if self.parts else None


@dataclass(eq=False)
class ComponentNode:
    """A component in an instance hierarchy (or a declarative stand-in for one).

    ``obj`` is the instance object when there is one; ``sub`` the declaring subcomponent;
    ``classifier`` its component classifier (``impl``/``ctype`` its implementation and type).
    ``pending`` holds the contained associations (``applies to`` paths) that reach this component
    from above and from its own classifier, outermost first.
    """

    obj: EObject | None
    parent: ComponentNode | None
    sub: EObject | None
    classifier: EObject | None
    impl: EObject | None
    ctype: EObject | None
    category: str
    index: tuple[int, ...] = ()
    pending: list[tuple[tuple[PathSegment, ...], EObject, ComponentNode]] = field(default_factory=list)
    own: dict[str, tuple[EObject, ComponentNode]] = field(default_factory=dict)
    memo: dict[str, Found | None] = field(default_factory=dict)
    binding: list[EObject] | None = None

    @property
    def name(self) -> str:
        return (self.sub.name if self.sub is not None else None) or (getattr(self.obj, "name", "") or "")


_Entry = tuple[tuple[PathSegment, ...], EObject, ComponentNode]


class NoValue(Exception):
    """A value names a property (``Deadline => Period``) that has no value for the object."""


class PropertyLookup:
    """Property values of declarative elements and instance objects of one ``AadlModel``."""

    def __init__(self, model: EObject, resolver: Resolver | None = None) -> None:
        self.model = model
        self.resolver = resolver if resolver is not None else Resolver(model)
        self.diagnostics: list[Diagnostic] = []
        self._pa_info: dict[int, tuple[str, str, EObject | None]] = {}
        self._holder: dict[int, dict[str, list[EObject]]] = {}
        self._contained: dict[int, list[tuple[tuple[PathSegment, ...], EObject]]] = {}
        self._classifier: dict[int, dict[str, list[EObject]]] = {}
        self._classifier_contained: dict[int, list[tuple[tuple[PathSegment, ...], EObject]]] = {}
        self._used: dict[int, set[str]] = {}
        self._model_used: set[str] | None = None
        self._props: dict[str, EObject | None] = {}
        self._displays: dict[str, str] = {}
        self._eval_stack: list[tuple[int, str]] = []
        self._templates: dict[tuple[int, int, int], _Make] = {}
        self._pa_data: dict[int, tuple[list[tuple[EObject, list[str]]], bool, tuple[str, ...]]] = {}
        self._template_keep: list[tuple[EObject, EObject | None, EObject | None]] = []
        self.factory = Factory()

    # ------------------------------------------------------------------ property names

    def pa_info(self, pa: EObject) -> tuple[str, str, EObject | None]:
        """``(key, display name, Property or None)`` of an association (cached)."""
        key = id(pa)
        info = self._pa_info.get(key)
        if info is None:
            prop = self.resolver.association_property(pa)
            if prop is not None:
                display = self.resolver.qualified_name(prop)
            else:
                display = "".join((pa.property or "").split())
            info = (display.lower(), display, prop)
            self._pa_info[key] = info
            self._props.setdefault(info[0], prop)
            self._displays.setdefault(info[0], display)
        return info

    def property_key(self, name: str | EObject, context: EObject | None = None) -> str:
        """The lookup key of a property given by name (``Period``, ``SEI::MIPSBudget``) or element."""
        if isinstance(name, EObject):
            display = self.resolver.qualified_name(name)
            key = display.lower()
            self._props.setdefault(key, name)
            self._displays.setdefault(key, display)
            return key
        prop = self.resolver.property(name, context)
        display = self.resolver.qualified_name(prop) if prop is not None else "".join(name.split())
        key = display.lower()
        self._props.setdefault(key, prop)
        self._displays.setdefault(key, display)
        return key

    def definition(self, key: str) -> EObject | None:
        return self._props.get(key)

    def display_name(self, key: str) -> str:
        return self._displays.get(key, key)

    # ------------------------------------------------------------------ associations by holder

    def holder_associations(self, holder: EObject) -> dict[str, list[EObject]]:
        """Associations without ``applies to`` held by one element, by key, last declared first."""
        key = id(holder)
        table = self._holder.get(key)
        if table is None:
            table = {}
            for pa in reversed(list(_owned_pas(holder))):
                if pa.appliesTo:
                    continue
                table.setdefault(self.pa_info(pa)[0], []).append(pa)
            self._holder[key] = table
        return table

    def contained_associations(self, holder: EObject) -> list[tuple[tuple[PathSegment, ...], EObject]]:
        """``(path, association)`` for each ``applies to`` path of a holder, last declared first."""
        key = id(holder)
        table = self._contained.get(key)
        if table is None:
            table = []
            for pa in reversed(list(_owned_pas(holder))):
                for path in reversed(list(pa.appliesTo)):
                    segments = tuple(split_path(path))
                    if segments:
                        self.pa_info(pa)
                        table.append((segments, pa))
            self._contained[key] = table
        return table

    def _chain_holders(self, classifier: EObject) -> list[EObject]:
        """The classifiers whose associations a component classifier sees: the implementation chain
        then the type chain (nearest first); for other classifiers their extends chain."""
        holders = list(self.resolver.extends_chain(classifier))
        if _is(classifier, "ComponentImplementation"):
            ctype = self.resolver.implementation_type(classifier)
            if ctype is not None:
                holders.extend(self.resolver.extends_chain(ctype))
        return holders

    def classifier_associations(self, classifier: EObject) -> dict[str, list[EObject]]:
        """Associations of a classifier through its chains, by key, in precedence order."""
        key = id(classifier)
        table = self._classifier.get(key)
        if table is None:
            table = {}
            for holder in self._chain_holders(classifier):
                for pkey, pas in self.holder_associations(holder).items():
                    table.setdefault(pkey, []).extend(pas)
            self._classifier[key] = table
        return table

    def classifier_contained(self, classifier: EObject) -> list[tuple[tuple[PathSegment, ...], EObject]]:
        key = id(classifier)
        table = self._classifier_contained.get(key)
        if table is None:
            table = []
            for holder in self._chain_holders(classifier):
                table.extend(self.contained_associations(holder))
            self._classifier_contained[key] = table
        return table

    def used_properties(self, classifier: EObject | None) -> set[str]:
        """Keys of every property associated anywhere inside a classifier and its chains
        (what OSATE calls the used property definitions)."""
        if classifier is None:
            return set()
        key = id(classifier)
        used = self._used.get(key)
        if used is None:
            used = set()
            for holder in self._chain_holders(classifier):
                for obj in _model.walk(holder):
                    if obj.eClass.name == "PropertyAssociation":
                        used.add(self.pa_info(obj)[0])
            self._used[key] = used
        return used

    def model_properties(self) -> set[str]:
        """Keys of every property associated anywhere in the model's units (cached)."""
        used = self._model_used
        if used is None:
            used = set()
            for unit in self.model.units:
                for obj in _model.walk(unit):
                    if obj.eClass.name == "PropertyAssociation":
                        used.add(self.pa_info(obj)[0])
            self._model_used = used
        return used

    # ------------------------------------------------------------------ nodes and contained PAs

    def root_node(self, classifier: EObject | None, obj: EObject | None = None) -> ComponentNode:
        impl, ctype = self._impl_type(classifier)
        category = _category_word(classifier, None, obj)
        node = ComponentNode(obj, None, None, classifier, impl, ctype, category)
        self._add_own_contained(node, [])
        return node

    def child_node(
        self,
        parent: ComponentNode,
        sub: EObject | None,
        classifier: EObject | None,
        obj: EObject | None = None,
        index: Iterable[int] = (),
        name: str | None = None,
    ) -> ComponentNode:
        impl, ctype = self._impl_type(classifier)
        category = _category_word(classifier, sub, obj)
        node = ComponentNode(obj, parent, sub, classifier, impl, ctype, category, tuple(index))
        wanted = (name or node.name).lower()
        incoming: list[_Entry] = []
        for segments, pa, anchor in parent.pending:
            first = segments[0]
            if first.key == wanted and first.matches(node.index):
                incoming.append((segments[1:], pa, anchor))
        # the subcomponent's own property block: paths relative to this component, declared in
        # the parent's implementation (outer to this component's classifier)
        if sub is not None:
            for member in self.resolver.refinement_chain(sub):
                for segments, pa in self.contained_associations(member):
                    incoming.append((segments, pa, parent))
        self._add_own_contained(node, incoming)
        return node

    def _add_own_contained(self, node: ComponentNode, incoming: list[_Entry]) -> None:
        entries = list(incoming)
        if node.classifier is not None:
            for segments, pa in self.classifier_contained(node.classifier):
                entries.append((segments, pa, node))
        pending: list[_Entry] = []
        own = node.own
        for segments, pa, anchor in entries:
            if segments:
                pending.append((segments, pa, anchor))
            else:
                own.setdefault(self.pa_info(pa)[0], (pa, anchor))
        node.pending = pending

    def _impl_type(self, classifier: EObject | None) -> tuple[EObject | None, EObject | None]:
        if classifier is None:
            return None, None
        if _is(classifier, "ComponentImplementation"):
            return classifier, self.resolver.implementation_type(classifier)
        if _is(classifier, "ComponentType"):
            return None, classifier
        return None, None

    def contained_for(
        self, node: ComponentNode, names: list[tuple[str, int]]
    ) -> dict[str, tuple[EObject, Any]]:
        """Contained associations reaching an element of ``node`` named by the path ``names``
        (``[(feature group, index), (port, index)]``, a connection, mode or flow name)."""
        result: dict[str, tuple[EObject, Any]] = {}
        depth = len(names)
        for segments, pa, anchor in node.pending:
            if len(segments) != depth:
                continue
            if all(
                seg.key == name.lower() and seg.matches(index)
                for seg, (name, index) in zip(segments, names, strict=True)
            ):
                result.setdefault(self.pa_info(pa)[0], (pa, anchor))
        return result

    # ------------------------------------------------------------------ lookup chains

    def _binding_ok(self, pa: EObject, node: ComponentNode | None, binding: Callable | None) -> bool:
        data = self._pa_data.get(id(pa))
        if data is None:
            self._pa_values(pa)
            data = self._pa_data[id(pa)]
        if not data[2]:
            return True
        classifiers = binding(node) if binding is not None else None
        if not classifiers:
            return False
        for name in pa.inBinding:
            wanted = self.resolver.classifier(name, pa)
            if wanted is None:
                continue
            for cls in classifiers:
                if cls is wanted or any(c is wanted for c in self._chain_holders(cls)):
                    return True
        return False

    def _pa_values(self, pa: EObject) -> tuple[list[tuple[EObject, list[str]]], bool]:
        """``([(value, in modes)], appends)`` of an association (cached)."""
        key = id(pa)
        data = self._pa_data.get(key)
        if data is None:
            values = [(mv.value, list(mv.inModes)) for mv in pa.ownedValues if mv.value is not None]
            data = (values, bool(pa.append), tuple(pa.inBinding))
            self._pa_data[key] = data
        return data[0], data[1]

    def _combine(
        self,
        candidates: Iterator[tuple[EObject, Any]],
        base: Callable[[], Found | None] | None,
    ) -> Found | None:
        parts: list[tuple[EObject | None, list[tuple[EObject, list[str]]], Any]] = []
        for pa, anchor in candidates:
            values, append = self._pa_values(pa)
            if not values:
                continue
            parts.append((pa, values, anchor))
            if not append:
                return Found(parts)
        if base is not None:
            below = base()
            if below is not None:
                parts.extend(below.parts)
                return Found(parts, below.complete)
        if parts:
            return Found(parts, complete=False)
        return None

    def component_found(self, node: ComponentNode, key: str, binding: Callable | None = None) -> Found | None:
        """The value of property ``key`` for a component (without the default value)."""
        if key in node.memo:
            return node.memo[key]
        node.memo[key] = None  # a property whose lookup depends on itself finds nothing
        prop = self._props.get(key)

        def candidates() -> Iterator[tuple[EObject, Any]]:
            contained = node.own.get(key)
            if contained is not None and self._binding_ok(contained[0], node, binding):
                yield contained
            if node.sub is not None:
                for member in self.resolver.refinement_chain(node.sub):
                    for pa in self.holder_associations(member).get(key, ()):
                        if self._binding_ok(pa, node, binding):
                            yield pa, node.parent
            if node.classifier is not None:
                for pa in self.classifier_associations(node.classifier).get(key, ()):
                    if self._binding_ok(pa, node, binding):
                        yield pa, node

        base = None
        if prop is not None and prop.inherit and node.parent is not None:
            parent = node.parent

            def base() -> Found | None:
                return self.component_found(parent, key, binding)

        found = self._combine(candidates(), base)
        node.memo[key] = found
        return found

    def feature_found(
        self,
        node: ComponentNode,
        chain: list[EObject],
        names: list[tuple[str, int]],
        key: str,
        binding: Callable | None = None,
    ) -> Found | None:
        """The value for a feature of component ``node``; ``chain`` lists the feature declarations
        from the outermost feature group down to the feature, ``names`` their instance names."""
        prop = self._props.get(key)
        feature = chain[-1]

        def candidates() -> Iterator[tuple[EObject, Any]]:
            contained = self.contained_for(node, names).get(key)
            if contained is not None:
                yield contained
            for member in self.resolver.refinement_chain(feature):
                for pa in self.holder_associations(member).get(key, ()):
                    yield pa, node
            classifier = self.resolver.feature_classifier(feature)
            if classifier is not None:
                for pa in self.classifier_associations(classifier).get(key, ()):
                    yield pa, node

        base = None
        if prop is not None and prop.inherit:

            def base() -> Found | None:
                return self.component_found(node, key, binding)

        return self._combine(candidates(), base)

    def connection_found(
        self,
        references: list[tuple[EObject, ComponentNode]],
        owner: ComponentNode | None,
        key: str,
        binding: Callable | None = None,
    ) -> Found | None:
        """The value for a semantic connection: the first of its declarations (in path order) that
        has one, each looked up with its contained associations and refinements."""
        prop = self._props.get(key)
        for connection, context in references:

            def candidates(connection=connection, context=context) -> Iterator[tuple[EObject, Any]]:
                contained = self.contained_for(context, [(connection.name or "", 0)]).get(key)
                if contained is not None:
                    yield contained
                for member in self.resolver.refinement_chain(connection):
                    for pa in self.holder_associations(member).get(key, ()):
                        yield pa, context

            found = self._combine(candidates(), None)
            if found is not None:
                return found
        if prop is not None and prop.inherit and owner is not None:
            return self.component_found(owner, key, binding)
        return None

    def element_found(
        self, node: ComponentNode, element: EObject, key: str, binding: Callable | None = None
    ) -> Found | None:
        """The value for a mode, flow specification, flow implementation or end-to-end flow of
        ``node`` (contained associations, the declaration and its refinements, inherit)."""
        prop = self._props.get(key)

        def candidates() -> Iterator[tuple[EObject, Any]]:
            contained = self.contained_for(node, [(element.name or "", 0)]).get(key)
            if contained is not None:
                yield contained
            for member in self.resolver.refinement_chain(element):
                for pa in self.holder_associations(member).get(key, ()):
                    yield pa, node

        base = None
        if prop is not None and prop.inherit:

            def base() -> Found | None:
                return self.component_found(node, key, binding)

        return self._combine(candidates(), base)

    def default_found(self, key: str, anchor: Any = None) -> Found | None:
        prop = self._props.get(key)
        if prop is None or prop.defaultValue is None:
            return None
        return Found([(None, [(prop.defaultValue, [])], anchor)])

    def with_default(self, found: Found | None, key: str, anchor: Any = None) -> Found | None:
        """``found`` completed by the default value (when there is no value, or only appends)."""
        if found is not None and found.complete:
            return found
        default = self.default_found(key, anchor)
        if found is None:
            return default
        if default is None:
            return found
        return Found(found.parts + default.parts)

    # ------------------------------------------------------------------ values

    def build_value(
        self,
        found: Found,
        key: str,
        *,
        evaluate: Callable[[str], Found | None] | None = None,
        reference: Callable[[Any, str], EObject | None] | None = None,
        in_mode: str | None = None,
        keep_modes: bool = True,
    ) -> list[tuple[EObject, list[str]]]:
        """New value elements for a found value: ``[(expression, in modes)]``.

        Units and enumeration literals take their declared spelling, constants their value,
        named properties (``Deadline => Period``) the value ``evaluate`` gives for them (a
        :class:`NoValue` when it has none), and ``reference (...)`` paths become
        ``InstanceReferenceValue`` where ``reference`` resolves them (else they stay
        ``ReferenceValue`` and a warning is recorded).
        """
        prop = self._props.get(key)
        ptype = self.resolver.resolved_type(prop) if prop is not None else None
        top_pa, top_values, top_anchor = found.parts[0]
        context = top_pa if top_pa is not None else prop
        selected = _select_modal(top_values, in_mode) if not keep_modes else top_values
        below: list[tuple[EObject, EObject | None, Any]] = []
        if len(found.parts) > 1 and top_pa is not None and top_pa.append:
            for pa, values, anchor in reversed(found.parts[1:]):
                ctx = pa if pa is not None else prop
                for expr, _modes in _select_modal(values, in_mode)[:1]:
                    below.append((expr, ctx, anchor))
        factory = self.factory
        result = []
        for expr, modes in selected:
            made = self._template(expr, ptype, context)(top_anchor, evaluate, reference)
            if below:
                items: list[EObject] = []
                for lower, ctx, anchor in below:
                    copy = self._template(lower, ptype, ctx)(anchor, evaluate, reference)
                    items.extend(_list_items(copy))
                items.extend(_list_items(made))
                made = factory.new("ListValue")
                factory.extend(made, "ownedItems", items)
            result.append((made, list(modes) if keep_modes else []))
        return result

    def _template(self, expr: EObject, ptype: EObject | None, context: EObject | None) -> _Make:
        """A function that makes a normalised copy of ``expr`` (cached per expression, type and
        context): the resolution work is done once, the copies are made per instance object."""
        key = (id(expr), id(ptype), id(context))
        make = self._templates.get(key)
        if make is None:
            make = self._compile(expr, ptype, context, ())
            self._templates[key] = make
            self._template_keep.append((expr, ptype, context))
        return make

    def _compile(
        self, expr: EObject, ptype: EObject | None, context: EObject | None, constants: tuple[int, ...]
    ) -> _Make:
        kind = expr.eClass.name
        resolver = self.resolver
        factory = self.factory
        if kind in ("IntegerValue", "RealValue"):
            number = expr.value
            unit = expr.unit
            if unit:
                unit = resolver.unit_literal(ptype, unit) or _STANDARD_UNITS.spelling(unit)
                return lambda anchor, evaluate, reference: factory.new(kind, value=number, unit=unit)
            return lambda anchor, evaluate, reference: factory.new(kind, value=number)
        if kind == "RangeValue":
            inner = ptype
            if inner is not None and _is(inner, "RangeType"):
                inner = inner.ownedNumberType or resolver.property_type(inner.numberType, inner)
            parts = [
                (name, self._compile(part, inner, context, constants))
                for name, part in (
                    ("minimum", expr.minimum),
                    ("maximum", expr.maximum),
                    ("delta", expr.delta),
                )
                if part is not None
            ]

            def make_range(anchor, evaluate, reference):
                made = factory.new("RangeValue")
                for name, make in parts:
                    factory.set(made, name, make(anchor, evaluate, reference))
                return made

            return make_range
        if kind == "BooleanValue":
            flag = bool(expr.value)
            return lambda anchor, evaluate, reference: factory.new(kind, value=flag)
        if kind == "StringValue":
            text = expr.value
            return lambda anchor, evaluate, reference: factory.new(kind, value=text)
        if kind == "NamedValue":
            return self._compile_named(expr, ptype, context, constants)
        if kind == "ReferenceValue":
            path = expr.path or ""

            def make_reference(anchor, evaluate, reference):
                target = reference(anchor, path) if reference is not None else None
                if target is not None:
                    return factory.new("InstanceReferenceValue", referencedInstanceObject=target)
                if reference is not None:
                    self.diagnostics.append(
                        Diagnostic(
                            "warning",
                            f"reference ({path}) does not resolve to an instance object",
                            self._where(context, anchor),
                        )
                    )
                return factory.new("ReferenceValue", path=path)

            return make_reference
        if kind == "InstanceReferenceValue":
            target = expr.referencedInstanceObject
            return lambda anchor, evaluate, reference: factory.new(kind, referencedInstanceObject=target)
        if kind == "ClassifierValue":
            name = expr.classifier
            found = resolver.classifier(name, context) if context is not None else None
            qualified = resolver.qualified_name(found) if found is not None else name
            return lambda anchor, evaluate, reference: factory.new(kind, classifier=qualified)
        if kind == "ListValue":
            inner = resolver.element_type_once(ptype)
            items = [self._compile(item, inner, context, constants) for item in expr.ownedItems]

            def make_list(anchor, evaluate, reference):
                made = factory.new("ListValue")
                factory.extend(made, "ownedItems", [make(anchor, evaluate, reference) for make in items])
                return made

            return make_list
        if kind == "RecordValue":
            fields = []
            for fv in expr.ownedFields:
                ftype = resolver.record_field_type(ptype, fv.name)
                make = self._compile(fv.value, ftype, context, constants) if fv.value is not None else None
                fields.append((fv.name, make))

            def make_record(anchor, evaluate, reference):
                made = factory.new("RecordValue")
                values = []
                for name, make in fields:
                    field_value = factory.new("FieldValue", name=name)
                    if make is not None:
                        factory.set(field_value, "value", make(anchor, evaluate, reference))
                    values.append(field_value)
                factory.extend(made, "ownedFields", values)
                return made

            return make_record
        if kind == "ComputedValue":
            function = expr.function
            return lambda anchor, evaluate, reference: factory.new(kind, function=function)
        if kind == "OperationValue":
            operator = expr.operator
            operands = [self._compile(o, ptype, context, constants) for o in expr.ownedOperands]

            def make_operation(anchor, evaluate, reference):
                made = factory.new("OperationValue", operator=operator)
                factory.extend(
                    made, "ownedOperands", [make(anchor, evaluate, reference) for make in operands]
                )
                return made

            return make_operation
        raise ModelError(f"unknown property value kind {kind}")

    def _compile_named(
        self, expr: EObject, ptype: EObject | None, context: EObject | None, constants: tuple[int, ...]
    ) -> _Make:
        resolver = self.resolver
        factory = self.factory
        name = expr.name or ""

        def literal_maker(text: str) -> _Make:
            return lambda anchor, evaluate, reference: factory.new("NamedValue", name=text)

        if "::" not in name:
            literal = resolver.enumeration_literal(ptype, name)
            if literal is not None:
                return literal_maker(literal)
        const = resolver.constant(name, context) if context is not None else resolver.constant(name)
        if const is not None and const.value is not None and id(const) not in constants:
            return self._compile(
                const.value, resolver.resolved_type(const) or ptype, const, (*constants, id(const))
            )
        prop = resolver.property(name, context) if context is not None else resolver.property(name)
        if prop is not None:
            key = self.property_key(prop)
            fallback = name

            def make_property(anchor, evaluate, reference):
                if evaluate is None:
                    return factory.new("NamedValue", name=fallback)
                marker = (id(anchor), key)
                if marker in self._eval_stack:
                    raise NoValue(f"{self.display_name(key)} depends on itself")
                self._eval_stack.append(marker)
                try:
                    found = evaluate(key)
                    if found is None:
                        raise NoValue(f"{self.display_name(key)} has no value here")
                    values = self.build_value(
                        found, key, evaluate=evaluate, reference=reference, keep_modes=False
                    )
                finally:
                    self._eval_stack.pop()
                if not values:
                    raise NoValue(f"{self.display_name(key)} has no value here")
                return values[0][0]

            return make_property
        return literal_maker(name)

    def _where(self, context: EObject | None, anchor: Any) -> Location:
        path = None
        obj = getattr(anchor, "obj", None)
        if obj is not None and _is(obj, "InstanceObject"):
            path = _model.instance_path(obj)
        if context is not None and _is(context, "Element"):
            return self.resolver.location(context, path=path)
        return Location(path=path)

    def association(
        self,
        obj: EObject,
        key: str,
        found: Found,
        *,
        evaluate: Callable[[str], Found | None] | None = None,
        reference: Callable[[Any, str], EObject | None] | None = None,
    ) -> EObject | None:
        """A new ``PropertyAssociation`` for an instance object holding a found value, or None when
        the value names a property that has no value there (``Deadline => Period`` without a
        ``Period``)."""
        try:
            values = self.build_value(found, key, evaluate=evaluate, reference=reference)
        except NoValue:
            return None
        factory = self.factory
        modal = []
        for expr, modes in values:
            mpv = factory.new("ModalPropertyValue")
            factory.set(mpv, "value", expr)
            if modes:
                factory.extend(mpv, "inModes", modes)
            modal.append(mpv)
        association = factory.new("PropertyAssociation", property=self.display_name(key))
        factory.extend(association, "ownedValues", modal)
        return association

    # ------------------------------------------------------------------ public questions

    def value(
        self,
        element: EObject,
        prop: str | EObject,
        *,
        in_mode: str | None = None,
        in_binding: str | EObject | Iterable[str | EObject] | None = None,
    ) -> EObject | None:
        """The value (a ``PropertyExpression``) of ``prop`` for a declarative element or an instance
        object, following AADL's lookup rules; None when the property has no value there.

        ``in_mode`` selects the value of a modal association; ``in_binding`` names the processor
        classifier(s) the element is bound to, which makes ``in binding`` associations apply.
        Instance objects that carry resolved values (as made by instantiation) answer from them.
        """
        context = element if not _is(element, "InstanceObject") else None
        key = self.property_key(prop, context)
        if _is(element, "InstanceObject"):
            own = self._own_instance_value(element, key, in_mode)
            if own is not None:
                return own
        binding = self._binding_callback(in_binding, element)
        found, evaluate, reference = self._find(element, key, binding)
        if found is None:
            return None
        try:
            values = self.build_value(
                found, key, evaluate=evaluate, reference=reference, in_mode=in_mode, keep_modes=False
            )
        except NoValue:
            return None
        return values[0][0] if values else None

    def python_value(
        self,
        element: EObject,
        prop: str | EObject,
        default: Any = None,
        *,
        in_mode: str | None = None,
        in_binding: str | EObject | Iterable[str | EObject] | None = None,
    ) -> Any:
        """:meth:`value` decoded by :func:`rosaadl.properties.python_value` (numbers with units)."""
        expr = self.value(element, prop, in_mode=in_mode, in_binding=in_binding)
        if expr is None:
            return default
        return _python_value(expr)

    def _own_instance_value(self, obj: EObject, key: str, in_mode: str | None) -> EObject | None:
        if obj.eClass.findEStructuralFeature("ownedPropertyAssociations") is None:
            return None
        found = None
        for pa in obj.ownedPropertyAssociations:
            if pa.appliesTo:
                continue
            written = "".join((pa.property or "").split()).lower()
            if (
                written == key
                or ("::" not in written and written == key.rpartition("::")[2])
                or ("::" not in key and written.rpartition("::")[2] == key)
            ):
                found = pa
        if found is None:
            return None
        values = [(mv.value, list(mv.inModes)) for mv in found.ownedValues if mv.value is not None]
        selected = _select_modal(values, in_mode)
        return selected[0][0] if selected else None

    def _binding_callback(self, in_binding, element) -> Callable | None:
        if in_binding is None:
            return None
        items = [in_binding] if isinstance(in_binding, (str, EObject)) else list(in_binding)
        classifiers = []
        for item in items:
            cls = item if isinstance(item, EObject) else self.resolver.classifier(item, element)
            if cls is None and isinstance(item, str):
                raise ModelError(f"binding classifier {item!r} not found")
            if cls is not None:
                classifiers.append(cls)

        def binding(_node) -> list[EObject]:
            return classifiers

        return binding

    def _find(self, element: EObject, key: str, binding: Callable | None):
        """Found value, evaluate callback and reference callback for any supported element."""
        resolver = self.resolver
        kind = element.eClass.name
        reference = None
        if _is(element, "InstanceObject"):
            return self._find_instance(element, key, binding)
        if _is(element, "Classifier"):
            if _is(element, "FeatureGroupType"):
                table = self.classifier_associations(element)
                found = self._combine(((pa, None) for pa in table.get(key, ())), None)
                return self.with_default(found, key), None, None
            node = self.root_node(element)

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.component_found(node, k, binding), k, node)

            return evaluate(key), evaluate, reference
        owner = element.eContainer()
        owner_node = self.root_node(owner) if owner is not None and _is(owner, "Classifier") else None
        if kind == "Subcomponent" and owner_node is not None:
            node = self.child_node(owner_node, element, resolver.subcomponent_classifier(element))

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.component_found(node, k, binding), k, node)

            return evaluate(key), evaluate, reference
        if kind == "Feature" and owner_node is not None:
            chain = [element]
            names = [(element.name or "", 0)]

            def evaluate(k: str) -> Found | None:
                return self.with_default(
                    self.feature_found(owner_node, chain, names, k, binding), k, owner_node
                )

            return evaluate(key), evaluate, reference
        if kind == "Connection" and owner_node is not None:

            def evaluate(k: str) -> Found | None:
                return self.with_default(
                    self.connection_found([(element, owner_node)], owner_node, k, binding), k, owner_node
                )

            return evaluate(key), evaluate, reference
        if owner_node is not None and kind in (
            "Mode",
            "ModeTransition",
            "FlowSpecification",
            "FlowImplementation",
            "EndToEndFlow",
        ):

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.element_found(owner_node, element, k, binding), k, owner_node)

            return evaluate(key), evaluate, reference
        raise ModelError(f"no property lookup for a {kind}")

    # ------------------------------------------------------------------ instance objects

    def _instance_node(self, ci: EObject, cache: dict[int, ComponentNode]) -> ComponentNode:
        node = cache.get(id(ci))
        if node is not None:
            return node
        parent_obj = ci.eContainer()
        resolver = self.resolver
        classifier = resolver.classifier(ci.classifier) if ci.classifier else None
        if parent_obj is None or not _is(parent_obj, "ComponentInstance"):
            node = self.root_node(classifier, ci)
        else:
            parent = self._instance_node(parent_obj, cache)
            sub = None
            wanted = (ci.subcomponent or ci.name or "").lower()
            for candidate in resolver.subcomponents(parent.impl):
                if (candidate.name or "").lower() == wanted:
                    sub = candidate
                    break
            if classifier is None and sub is not None:
                classifier = resolver.subcomponent_classifier(sub)
            node = self.child_node(parent, sub, classifier, ci, list(ci.index), ci.name)
        cache[id(ci)] = node
        return node

    def _find_instance(self, obj: EObject, key: str, binding: Callable | None):
        cache: dict[int, ComponentNode] = {}
        resolver = self.resolver
        reference = _instance_reference
        kind = obj.eClass.name
        if kind in ("ComponentInstance", "SystemInstance"):
            node = self._instance_node(obj, cache)

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.component_found(node, k, binding), k, node)

            return evaluate(key), evaluate, reference
        if kind == "FeatureInstance":
            path: list[EObject] = []
            current = obj
            while current is not None and current.eClass.name == "FeatureInstance":
                path.append(current)
                current = current.eContainer()
            path.reverse()
            if current is None:
                return None, None, reference
            node = self._instance_node(current, cache)
            chain: list[EObject] = []
            features = resolver.features(node.classifier)
            for fi in path:
                decl = _by_name(features, fi.feature or fi.name)
                if decl is None:
                    return None, None, reference
                chain.append(decl)
                fgt = resolver.feature_classifier(decl)
                features = (
                    resolver.feature_group_features(fgt)[0]
                    if fgt is not None and _is(fgt, "FeatureGroupType")
                    else []
                )
            names = [(fi.name or "", fi.index or 0) for fi in path]

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.feature_found(node, chain, names, k, binding), k, node)

            return evaluate(key), evaluate, reference
        if kind == "ConnectionInstance":
            owner_obj = obj.eContainer()
            owner = self._instance_node(owner_obj, cache) if owner_obj is not None else None
            refs = []
            for ref in obj.connectionReferences:
                if ref.context is None:
                    continue
                context = self._instance_node(ref.context, cache)
                decl = _by_name(resolver.connections(context.impl), ref.connection)
                if decl is not None:
                    refs.append((decl, context))

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.connection_found(refs, owner, k, binding), k, owner)

            return evaluate(key), evaluate, reference
        if kind in ("ModeInstance", "EndToEndFlowInstance", "FlowSpecificationInstance"):
            owner_obj = obj.eContainer()
            node = self._instance_node(owner_obj, cache)
            if kind == "ModeInstance":
                decl = _by_name(resolver.modes(node.classifier), obj.mode or obj.name)
            elif kind == "EndToEndFlowInstance":
                decl = _by_name(resolver.end_to_end_flows(node.impl), obj.flow or obj.name)
            else:
                decl = _by_name(resolver.flow_specifications(node.classifier), obj.name)
            if decl is None:
                return None, None, reference

            def evaluate(k: str) -> Found | None:
                return self.with_default(self.element_found(node, decl, k, binding), k, node)

            return evaluate(key), evaluate, reference
        raise ModelError(f"no property lookup for a {kind}")


def _instance_reference(anchor: Any, path: str) -> EObject | None:
    obj = getattr(anchor, "obj", None)
    if obj is None:
        return None
    return resolve_instance_path(obj, path)


def resolve_instance_path(start: EObject, path: str) -> EObject | None:
    """The instance object a ``reference (a.b[2].c)`` path names, relative to component ``start``."""
    current = start
    for segment in split_path(path):
        wanted = segment.key
        found = None
        for child in _model.instance_children(current):
            if (child.name or "").lower() != wanted:
                continue
            index = getattr(child, "index", None)
            if segment.ranges:
                if segment.matches(
                    list(index) if index is not None and not isinstance(index, int) else index
                ):
                    found = child
                    break
            else:
                found = child
                break
        if found is None:
            return None
        current = found
    return current


# ---------------------------------------------------------------------- helpers


def _is(obj: object, *names: str) -> bool:
    """Is ``obj`` an instance of one of the metamodel classes ``names``?"""
    if not isinstance(obj, EObject):
        return False
    return _class_is(obj.eClass, names)


@functools.lru_cache(maxsize=4096)
def _class_is(eclass: object, names: tuple[str, ...]) -> bool:
    """The answer of :func:`_is` for one metaclass (immutable metadata, so cached)."""
    return eclass.name in names or any(sup.name in names for sup in eclass.eAllSuperTypes())


def _owned_pas(holder: EObject) -> Iterable[EObject]:
    if holder.eClass.findEStructuralFeature("ownedPropertyAssociations") is None:
        return ()
    return holder.ownedPropertyAssociations


def _by_name(elements: Iterable[EObject], name: str | None) -> EObject | None:
    wanted = (name or "").lower()
    for element in elements:
        if (element.name or "").lower() == wanted:
            return element
    return None


def _category_word(classifier: EObject | None, sub: EObject | None, obj: EObject | None) -> str:
    """OSATE's component category: the classifier's unless abstract, then the subcomponent's."""
    for source in (classifier, sub, obj):
        if source is None:
            continue
        category = getattr(source, "category", None)
        if category is None:
            continue
        text = getattr(category, "literal", None) or getattr(category, "name", None) or str(category)
        if text and text != "abstract":
            return text
    return "abstract"


def _select_modal(
    values: list[tuple[EObject, list[str]]], in_mode: str | None
) -> list[tuple[EObject, list[str]]]:
    if not values:
        return []
    if in_mode is not None:
        wanted = in_mode.lower()
        for expr, modes in values:
            if any(m.lower() == wanted for m in modes):
                return [(expr, modes)]
    for expr, modes in values:
        if not modes:
            return [(expr, modes)]
    return [values[0]]


def _list_items(expr: EObject) -> list[EObject]:
    """The items of a list value (detached from it), or the value itself."""
    if expr.eClass.name != "ListValue":
        return [expr]
    items = list(expr.ownedItems)
    expr.ownedItems.clear()
    return items


class Factory:
    """Makes model objects for bulk producers such as instantiation, by class and feature name,
    on :class:`rosaadl.bulk.FastBuilder` (no per-assignment checks or notifications; the objects
    behave like ordinary ones).  Counts what it made, by class (:attr:`made`)."""

    def __init__(self) -> None:
        self.builder = FastBuilder()
        #: how many objects of each class this factory made
        self.made: dict[str, int] = {}

    def new(self, class_name: str, /, **values: Any) -> EObject:
        """A new object of class ``class_name`` with single-valued features set (None skipped)."""
        made = self.made
        made[class_name] = made.get(class_name, 0) + 1
        return self.builder.make(class_name, **values)

    def set(self, obj: EObject, name: str, value: Any) -> None:
        """Set a single-valued feature of an object made by this factory."""
        slot = self.builder.slot(obj.eClass, name)
        if slot.many:
            raise ModelError(f"{obj.eClass.name}.{name} is many-valued; use extend")
        if slot.containment:
            FastFactory.set_child(obj, slot, value)
        else:
            FastFactory.set_value(obj, slot, value)

    def extend(self, obj: EObject, name: str, values: Iterable[Any]) -> None:
        """Append to a many-valued feature of an object made by this factory (nothing when empty,
        so that an empty list is never recorded as set)."""
        values = list(values)
        if values:
            self.builder.add(obj, name, *values)


_Make = Callable[[Any, Any, Any], EObject]

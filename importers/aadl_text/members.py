"""The members of classifiers in AADL text into model objects.

:class:`MemberBuilder` builds what the sections of a component type, component implementation
or feature group type declare: prototypes (kept as text), features, subcomponents (with array
dimensions and element implementations), subprogram call sequences, connections, flow
specifications, flow implementations and end-to-end flows, modes and mode transitions, and
annex subclauses (kept as text).  Each member's name is declared in its classifier's namespace
and each member is checked against the legality rules (:mod:`.legality`) as it is built.
"""

from __future__ import annotations

from typing import Any

from lark import Token, Tree
from pyecore.ecore import EObject

from rosaadl.importers.aadl_text.factory import add, literals, make, maker
from rosaadl.importers.aadl_text.legality import Legality
from rosaadl.importers.aadl_text.lexical import SourceText
from rosaadl.importers.aadl_text.tree import (
    array_size,
    classifier_ref,
    end_text,
    feature_classifier,
    keywords,
    mode_refs,
    path_text,
    position,
)
from rosaadl.importers.aadl_text.values import ValueBuilder

__all__ = ["MemberBuilder"]

#: features whose direction may be left out: then they are "in out" (unless they refine one)
_UNDIRECTED_NODES = frozenset({"feature_group", "abstract_feature"})


class MemberBuilder:
    """Builds the members of the classifiers of one file; ``members`` arguments are the
    namespace of the classifier being built (name -> line of its first declaration)."""

    def __init__(self, source: SourceText, rules: Legality, values: ValueBuilder) -> None:
        self.source = source
        self.rules = rules
        self.associations = values.associations
        self.new_feature = maker(
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
        known = literals()
        self.categories = known.categories
        self.feature_categories = known.feature_categories
        self.directions = known.directions
        self.access = known.access
        self.connection_kinds = known.connection_kinds
        self.flow_kinds = known.flow_kinds

    def properties_and_modes(self, owner: EObject, block: Tree | None, in_modes: Tree | None) -> None:
        """The property associations (``{ ... }``) and ``in modes`` clause of a member."""
        if block is not None:
            add(owner, "ownedPropertyAssociations", *self.associations(block.children))
        if in_modes is not None:
            add(owner, "inModes", *mode_refs(in_modes))

    # ----------------------------------------------------------------- prototypes

    def prototypes(self, section: Tree, members: dict[str, int]) -> list[EObject]:
        out = []
        for node in section.children:
            name, refined = node.children[:2]
            start = self.source.after(name.end_pos, ":", "refined", "to")
            proto = make(
                "Prototype",
                name=str(name),
                refined=True if refined is not None else None,
                text=self.source.until_end(start),
                line=name.line,
                column=name.column,
            )
            self.rules.declare(members, name, "prototype")
            out.append(proto)
        if out:
            first = section.children[0].children[0]
            self.rules.warning(
                "prototypes are kept as text but not interpreted: bindings are not applied "
                "when the model is instantiated",
                first.line,
                first.column,
            )
        return out

    # ----------------------------------------------------------------- features

    def features(self, section: Tree, category: str | None, members: dict[str, int]) -> list[EObject]:
        """The features of a component type of ``category`` (None: of a feature group type)."""
        out = []
        new_feature = self.new_feature
        rules = self.rules
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
                word = keywords(direction)
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
                feature_classifier(classifier) if classifier is not None else None,
                name.line,
                name.column,
            )
            if array is not None:
                add(feature, "arrayDimensions", array_size(array))
            if block is not None:
                add(feature, "ownedPropertyAssociations", *self.associations(block.children))
            rules.feature(category, kind, name)
            rules.declare(members, name, "feature")
            out.append(feature)
        return out

    # ----------------------------------------------------------------- implementations

    def subcomponents(self, section: Tree, category: str, members: dict[str, int]) -> list[EObject]:
        out = []
        rules = self.rules
        for node in section.children:
            name, refined, cat_node, classifier, bindings, dims, elements, block, in_modes = node.children
            sub_category = keywords(cat_node)
            sub = make(
                "Subcomponent",
                name=str(name),
                category=self.categories[sub_category],
                refined=True if refined is not None else None,
                classifier=classifier_ref(classifier) if classifier is not None else None,
                prototypeBindings=self.source.bindings(bindings) if bindings is not None else None,
                line=name.line,
                column=name.column,
            )
            if dims is not None:
                add(sub, "arrayDimensions", *[array_size(d) for d in dims.children])
            if elements is not None:
                add(sub, "arrayElementBindings", *[self.element_implementation(e) for e in elements.children])
            self.properties_and_modes(sub, block, in_modes)
            rules.subcomponent(category, sub_category, name)
            rules.declare(members, name, "subcomponent")
            out.append(sub)
        return out

    def element_implementation(self, node: Tree) -> str:
        """An array element implementation: ``"A.impl"`` or ``"A.impl (p => data D)"``."""
        ref, bindings = node.children
        text = classifier_ref(ref)
        return f"{text} {self.source.bindings(bindings)}" if bindings is not None else text

    def call_sequences(self, section: Tree, members: dict[str, int]) -> list[EObject]:
        out = []
        declare = self.rules.declare
        for node in section.children:
            children = node.children
            name = children[0]
            block, in_modes = children[-2:]
            seq = make("CallSequence", name=str(name), line=name.line, column=name.column)
            declare(members, name, "call sequence")
            calls = []
            for call_node in children[1:-2]:
                call_name, called, call_block = call_node.children
                if called.data == "processor_subprogram":
                    called_text = f"processor.{called.children[0]}"
                else:
                    called_text = classifier_ref(called)
                call = make(
                    "SubprogramCall",
                    name=str(call_name),
                    called=called_text,
                    line=call_name.line,
                    column=call_name.column,
                )
                if call_block is not None:
                    add(call, "ownedPropertyAssociations", *self.associations(call_block.children))
                declare(members, call_name, "subprogram call")
                calls.append(call)
            add(seq, "calls", *calls)
            self.properties_and_modes(seq, block, in_modes)
            out.append(seq)
        return out

    def connections(self, section: Tree, category: str, members: dict[str, int]) -> list[EObject]:
        out = []
        rules = self.rules
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
                    words = keywords(qualifier)
                    if kind == "access_connection":
                        values["accessCategory"] = self.categories[words]
                    elif words != "port":
                        rules.warning_at(
                            f"'{words}' connections are AADL v1 syntax: read as a port connection", qualifier
                        )
            else:
                source, direction, destination, block, in_modes = children[2:]
            line, column = position(name if name is not None else node)
            connection = make(
                "Connection",
                name=str(name) if name is not None else None,
                kind=self.connection_kinds[kind],
                refined=True if refined is not None else None,
                source=end_text(source) if source is not None else None,
                destination=end_text(destination) if destination is not None else None,
                bidirectional=True if direction is not None and direction.children[0] == "<->" else None,
                line=line,
                column=column,
                **values,
            )
            self.properties_and_modes(connection, block, in_modes)
            rules.connection(category, kind, name, source is not None or refined is not None, line, column)
            rules.declare(members, name, "connection")
            out.append(connection)
        return out

    # ----------------------------------------------------------------- flows

    def flow_specs(self, section: Tree, members: dict[str, int]) -> list[EObject]:
        out = []
        rules = self.rules
        for node in section.children:
            kind = node.data
            children = node.children
            name, refined = children[:2]
            block, in_modes = children[-2:]
            ends: dict[str, Any] = {}
            if kind == "flow_path_spec":
                if children[2] is not None:
                    ends["inEnd"] = path_text(children[2])
                    ends["outEnd"] = path_text(children[3])
            elif children[2] is not None:
                ends["outEnd" if kind == "flow_source_spec" else "inEnd"] = path_text(children[2])
            rules.flow_ends(name, bool(ends) or refined is not None)
            flow = make(
                "FlowSpecification",
                name=str(name),
                kind=self.flow_kinds[kind],
                refined=True if refined is not None else None,
                line=name.line,
                column=name.column,
                **ends,
            )
            self.properties_and_modes(flow, block, in_modes)
            rules.declare(members, name, "flow")
            out.append(flow)
        return out

    def flow_impls(self, impl: EObject, section: Tree, members: dict[str, int]) -> None:
        """The flow implementations and end-to-end flows of ``impl``."""
        flows = []
        end_to_end = []
        rules = self.rules
        for node in section.children:
            kind = node.data
            children = node.children
            name = children[0]
            block, in_modes = children[-2:]
            if kind == "end_to_end_flow":
                refined, segments = children[1:3]
                flow = make(
                    "EndToEndFlow",
                    name=str(name),
                    refined=True if refined is not None else None,
                    line=name.line,
                    column=name.column,
                )
                rules.flow_ends(name, segments is not None or refined is not None, end_to_end=True)
                rules.declare(members, name, "flow")
                end_to_end.append(flow)
            else:
                segments = children[1]
                flow = make(
                    "FlowImplementation",
                    name=str(name),
                    kind=self.flow_kinds[kind],
                    line=name.line,
                    column=name.column,
                )
                rules.declare(members, name, "flow")
                flows.append(flow)
            if segments is not None:
                add(flow, "elements", *[path_text(p) for p in segments.children])
            self.properties_and_modes(flow, block, in_modes)
        if flows:
            add(impl, "flowImplementations", *flows)
        if end_to_end:
            add(impl, "endToEndFlows", *end_to_end)

    # ----------------------------------------------------------------- modes

    def modes(self, classifier: EObject, section: Tree, members: dict[str, int]) -> None:
        """The modes and mode transitions of ``classifier``."""
        modes = []
        transitions = []
        declare = self.rules.declare
        for node in section.children:
            children = node.children
            if node.data == "mode":
                name, initial, block = children
                mode = make(
                    "Mode",
                    name=str(name),
                    initial=True if initial is not None else None,
                    line=name.line,
                    column=name.column,
                )
                declare(members, name, "mode")
                modes.append(mode)
            else:
                name, source, triggers, destination, block = children
                where = name if name is not None else source
                mode = make(
                    "ModeTransition",
                    name=str(name) if name is not None else None,
                    source=str(source),
                    destination=str(destination),
                    line=where.line,
                    column=where.column,
                )
                add(mode, "triggers", *[end_text(t) for t in triggers.children])
                declare(members, name, "mode transition")
                transitions.append(mode)
            if block is not None:
                add(mode, "ownedPropertyAssociations", *self.associations(block.children))
        if modes:
            if classifier.modes:
                self.rules.warning_at(
                    "both 'requires modes' and 'modes' sections: their modes are kept in one list", section
                )
            add(classifier, "modes", *modes)
        if transitions:
            add(classifier, "modeTransitions", *transitions)

    # ----------------------------------------------------------------- annexes

    def annex_subclause(self, node: Tree) -> EObject:
        """An annex subclause: its text as written between ``{**`` and ``**}`` (None for ``none``)."""
        name, content, in_modes = node.children
        annex = make(
            "AnnexSubclause",
            name=str(name),
            text=content[3:-3] if isinstance(content, Token) else None,
            line=name.line,
            column=name.column,
        )
        if in_modes is not None:
            add(annex, "inModes", *mode_refs(in_modes))
        return annex

"""The AADL builder: the parse tree of one text into the model units it declares.

:func:`build_units` walks the tree that :func:`rosaadl.importers.aadl_syntax.parse` gives once,
depth first, and returns the packages and property sets of the text as model objects (made with
:class:`rosaadl.bulk.FastFactory`, see :mod:`.factory`) together with what the legality rules
(:mod:`.legality`) found.  :class:`UnitBuilder` builds packages: their sections, ``with``
clauses, renamings, annex libraries and classifiers (component types, component
implementations, feature group types); it hands each classifier's sections to
:class:`.members.MemberBuilder`, property associations to :class:`.values.ValueBuilder` and
property sets to :class:`.property_sets.PropertySetBuilder`, all four around the same source
text and legality rules.
"""

from __future__ import annotations

from typing import Any

from lark import Token, Tree
from pyecore.ecore import EObject

from rosaadl.importers.aadl_text.factory import add, literals, make
from rosaadl.importers.aadl_text.legality import Legality
from rosaadl.importers.aadl_text.lexical import SourceText
from rosaadl.importers.aadl_text.members import MemberBuilder
from rosaadl.importers.aadl_text.property_sets import PropertySetBuilder
from rosaadl.importers.aadl_text.tree import classifier_ref, keywords
from rosaadl.importers.aadl_text.values import ValueBuilder

__all__ = ["UnitBuilder", "build_units"]


def build_units(root: Tree, text: str, filename: str) -> tuple[list[EObject], Legality]:
    """The model units of a parsed text (``text``: the text it was parsed from), and the legality
    rules of the file with the errors and warnings they found.  Raises the located
    :class:`rosaadl.errors.AadlSyntaxError` of a literal out of range."""
    builder = UnitBuilder(SourceText(text), Legality(filename))
    return builder.specification(root), builder.rules


class UnitBuilder:
    """Builds the packages and property sets of one file."""

    def __init__(self, source: SourceText, rules: Legality) -> None:
        self.source = source
        self.rules = rules
        self.filename = rules.filename
        self.values = ValueBuilder(rules)
        self.members = MemberBuilder(source, rules, self.values)
        self.property_sets = PropertySetBuilder(source, rules, self.values)
        known = literals()
        self.categories = known.categories
        self.visibility = known.visibility
        self.rename_kinds = known.rename_kinds

    def specification(self, root: Tree) -> list[EObject]:
        units = []
        for node in root.children:
            if node.data == "package":
                units.append(self.package(node))
            else:
                units.append(self.property_sets.property_set(node, self.filename))
        return units

    # ----------------------------------------------------------------- packages

    def package(self, node: Tree) -> EObject:
        qname, public, private, properties, end = node.children
        name = "::".join(qname.children)
        first = qname.children[0]
        self.rules.end_name(name, "::".join(end.children), "package", end.children[0])
        pkg = make("AadlPackage", name=name, line=first.line, column=first.column, sourceFile=self.filename)
        self.rules.begin_package()
        for section, visibility in ((public, "public"), (private, "private")):
            if section is not None:
                self.package_section(pkg, section, visibility)
        if properties is not None:
            add(pkg, "ownedPropertyAssociations", *self.values.associations(properties.children))
        self.rules.end_package()
        return pkg

    def package_section(self, pkg: EObject, section: Tree, visibility: str) -> None:
        withs: list[str] = []
        classifiers = []
        renamings = []
        annexes = []
        rules = self.rules
        vis = self.visibility[visibility]
        for item in section.children:
            kind = item.data
            if kind == "component_type":
                classifiers.append(self.component_type(item, vis))
                rules.component_type(item)
            elif kind == "component_implementation":
                classifiers.append(self.component_implementation(item, vis))
                rules.component_implementation(item)
            elif kind == "with_clause":
                withs.extend("::".join(q.children) for q in item.children)
            elif kind == "feature_group_type":
                classifiers.append(self.feature_group_type(item, vis))
                rules.feature_group_type(item)
            elif kind == "annex_library":
                annexes.append(self.annex_library(item, vis))
            else:
                renamings.append(self.renaming(item, vis))
        if withs:
            add(pkg, "withs" if visibility == "public" else "privateWiths", *withs)
        if classifiers:
            add(pkg, "classifiers", *classifiers)
        if renamings:
            add(pkg, "renamings", *renamings)
        if annexes:
            add(pkg, "annexLibraries", *annexes)

    def renaming(self, node: Tree, visibility: Any) -> EObject:
        kind = node.data
        children = node.children
        if kind == "package_rename":
            alias, target = children
            return make(
                "Renaming",
                name=str(alias),
                kind=self.rename_kinds["package"],
                visibility=visibility,
                target="::".join(target.children),
                line=alias.line,
                column=alias.column,
            )
        if kind == "package_rename_all":
            first = children[0]
            return make(
                "Renaming",
                kind=self.rename_kinds["all"],
                visibility=visibility,
                target="::".join(children),
                line=first.line,
                column=first.column,
            )
        if kind == "feature_group_type_rename":
            alias, target = children
            where = alias if alias is not None else target.children[0]
            return make(
                "Renaming",
                name=str(alias) if alias is not None else None,
                kind=self.rename_kinds["feature group"],
                visibility=visibility,
                target=classifier_ref(target),
                line=where.line,
                column=where.column,
            )
        alias, category, target = children  # component_type_rename
        where = alias if alias is not None else category.children[0]
        return make(
            "Renaming",
            name=str(alias) if alias is not None else None,
            kind=self.rename_kinds["classifier"],
            visibility=visibility,
            category=self.categories[keywords(category)],
            target=classifier_ref(target),
            line=where.line,
            column=where.column,
        )

    def annex_library(self, node: Tree, visibility: Any) -> EObject:
        name, content = node.children
        return make(
            "AnnexLibrary",
            name=str(name),
            visibility=visibility,
            text=content[3:-3] if isinstance(content, Token) else None,
            line=name.line,
            column=name.column,
        )

    # ----------------------------------------------------------------- classifiers

    def component_type(self, node: Tree, visibility: Any) -> EObject:
        children = node.children
        category_node, name, extends, bindings = children[:4]
        category = keywords(category_node)
        self.rules.end_name(name, children[-1], f"{category} type", children[-1])
        sections = children[4:-1]
        ctype = make(
            "ComponentType",
            name=str(name),
            category=self.categories[category],
            requiresModes=True if any(s.data == "requires_modes" for s in sections) else None,
            visibility=visibility,
            extended=classifier_ref(extends.children[0]) if extends is not None else None,
            prototypeBindings=self.source.bindings(bindings) if bindings is not None else None,
            line=name.line,
            column=name.column,
        )
        members: dict[str, int] = {}
        builder = self.members
        for section in sections:
            kind = section.data
            if kind == "features":
                add(ctype, "features", *builder.features(section, category, members))
            elif kind == "flow_specs":
                self.rules.type_section(category, section)
                add(ctype, "flowSpecifications", *builder.flow_specs(section, members))
            elif kind == "modes" or kind == "requires_modes":
                self.rules.type_section(category, section)
                builder.modes(ctype, section, members)
            else:
                self.shared_section(ctype, section, members)
        return ctype

    def component_implementation(self, node: Tree, visibility: Any) -> EObject:
        children = node.children
        category_node, impl_name, extends, bindings = children[:4]
        category = keywords(category_node)
        type_token, impl_token = impl_name.children
        name = f"{type_token}.{impl_token}"
        end_type, end_impl = children[-1].children
        self.rules.end_name(name, f"{end_type}.{end_impl}", f"{category} implementation", end_type)
        impl = make(
            "ComponentImplementation",
            name=name,
            type=str(type_token),
            category=self.categories[category],
            visibility=visibility,
            extended=classifier_ref(extends.children[0]) if extends is not None else None,
            prototypeBindings=self.source.bindings(bindings) if bindings is not None else None,
            line=type_token.line,
            column=type_token.column,
        )
        members: dict[str, int] = {}
        builder = self.members
        for section in children[4:-1]:
            kind = section.data
            if kind == "subcomponents":
                add(impl, "subcomponents", *builder.subcomponents(section, category, members))
            elif kind == "connections":
                add(impl, "connections", *builder.connections(section, category, members))
            elif kind == "flow_impls":
                self.rules.implementation_section(category, section)
                builder.flow_impls(impl, section, members)
            elif kind == "calls":
                self.rules.implementation_section(category, section)
                add(impl, "callSequences", *builder.call_sequences(section, members))
            elif kind == "modes":
                builder.modes(impl, section, members)
            else:
                self.shared_section(impl, section, members)
        return impl

    def feature_group_type(self, node: Tree, visibility: Any) -> EObject:
        children = node.children
        name, extends, bindings = children[:3]
        self.rules.end_name(name, children[-1], "feature group type", children[-1])
        sections = children[3:-1]
        inverse = next((s.children[0] for s in sections if s.data == "inverse_of"), None)
        fgt = make(
            "FeatureGroupType",
            name=str(name),
            inverseOf=classifier_ref(inverse) if inverse is not None else None,
            visibility=visibility,
            extended=classifier_ref(extends.children[0]) if extends is not None else None,
            prototypeBindings=self.source.bindings(bindings) if bindings is not None else None,
            line=name.line,
            column=name.column,
        )
        members: dict[str, int] = {}
        for section in sections:
            kind = section.data
            if kind == "features":
                add(fgt, "features", *self.members.features(section, None, members))
            elif kind != "inverse_of":  # inverse_of: set above
                self.shared_section(fgt, section, members)
        return fgt

    def shared_section(self, classifier: EObject, section: Tree, members: dict[str, int]) -> None:
        """A section that every kind of classifier may have: properties, prototypes or an annex
        subclause."""
        kind = section.data
        if kind == "properties":
            add(classifier, "ownedPropertyAssociations", *self.values.associations(section.children))
        elif kind == "prototypes":
            add(classifier, "prototypes", *self.members.prototypes(section, members))
        else:  # annex_subclause
            add(classifier, "annexSubclauses", self.members.annex_subclause(section))

"""The AADL builder: the text of one file into the model units it declares, built while it is parsed.

:func:`read_units` parses a text with :func:`rosaadl.importers.aadl_syntax.parse` and builds
each classifier, package and property set as soon as the parser has made its node (the parser's
``hooks``): the tree of a part is released once it is built, so that the whole tree of a large
file is never held, only the model, the text and the tree of the part being read.  It returns
the packages and property sets of the text as model objects (made with
:class:`rosaadl.bulk.FastFactory`, see :mod:`.factory`) together with what the legality rules
(:mod:`.legality`) found.  :class:`UnitBuilder` builds packages: their sections, ``with``
clauses, renamings, annex libraries and classifiers (component types, component
implementations, feature group types); it hands each classifier's sections to
:class:`.members.MemberBuilder`, property associations to :class:`.values.ValueBuilder` and
property sets to :class:`.property_sets.PropertySetBuilder`, all four around the same source
text and legality rules.  :func:`build_units` builds the same from a whole parse tree.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from lark import Token, Tree
from pyecore.ecore import EObject

from rosaadl.errors import AadlSyntaxError
from rosaadl.importers.aadl_syntax import parse
from rosaadl.importers.aadl_text.factory import add, literals, make, update
from rosaadl.importers.aadl_text.legality import Legality
from rosaadl.importers.aadl_text.lexical import SourceText
from rosaadl.importers.aadl_text.members import MemberBuilder
from rosaadl.importers.aadl_text.property_sets import PropertySetBuilder
from rosaadl.importers.aadl_text.tree import classifier_ref, keywords
from rosaadl.importers.aadl_text.values import ValueBuilder

__all__ = ["UnitBuilder", "build_units", "read_units"]


def build_units(root: Tree, text: str, filename: str) -> tuple[list[EObject], Legality]:
    """The model units of a parsed text (``text``: the text it was parsed from), and the legality
    rules of the file with the errors and warnings they found.  Raises the located
    :class:`rosaadl.errors.AadlSyntaxError` of a literal out of range."""
    builder = UnitBuilder(SourceText(text), Legality(filename))
    return builder.specification(root), builder.rules


def read_units(text: str, filename: str, *, quote: bool = True) -> tuple[list[EObject], Legality]:
    """The model units of a text, built while it is parsed, and the legality rules of the file
    with the errors and warnings they found.

    Raises the located :class:`rosaadl.errors.AadlSyntaxError` of a syntax error (without
    ``quote``, showing nothing of the text: :func:`parse`), else of the first literal out of
    range, else of a text that nests too deeply: a syntax error anywhere in the text comes
    first, as when the whole tree was parsed before it was built.
    """
    builder = UnitBuilder(SourceText(text), Legality(filename))
    failed: list[AadlSyntaxError] = []

    def building(build: Callable[[Tree], Any]) -> Callable[[Tree], Any]:
        def hook(node: Tree) -> Any:
            if failed:  # the text is read only for its syntax errors now
                return None
            try:
                return build(node)
            except AadlSyntaxError as exc:
                failed.append(exc)
            except RecursionError:
                failed.append(AadlSyntaxError("the text nests too deeply to be read", file=filename))
            return None

        return hook

    hooks = {name: building(build) for name, build in builder.hooks().items()}
    root = parse(text, filename, quote=quote, hooks=hooks)
    if failed:
        raise failed[0]
    return root.children, builder.rules


class UnitBuilder:
    """Builds the packages and property sets of one file, from a whole parse tree
    (:meth:`specification`) or part by part while it is parsed (:meth:`hooks`)."""

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
                units.append(self.property_set(node))
        return units

    def hooks(self) -> dict[str, Callable[[Tree], Any]]:
        """What builds each node that :func:`parse` makes, when given as its ``hooks``: each
        classifier (an object without its visibility, which its section sets), each package
        (around the classifiers already built) and each property set, in text order."""
        return {
            "component_type": self._classifier(self.component_type, self.rules.component_type),
            "component_implementation": self._classifier(
                self.component_implementation, self.rules.component_implementation
            ),
            "feature_group_type": self._classifier(self.feature_group_type, self.rules.feature_group_type),
            "package": self.package,
            "property_set": self.property_set,
        }

    def _classifier(
        self, build: Callable[[Tree, Any], EObject], declare: Callable[[Tree], None]
    ) -> Callable[[Tree], EObject]:
        def classifier(node: Tree) -> EObject:
            self.rules.begin_package()
            built = build(node, None)
            declare(node)
            return built

        return classifier

    def property_set(self, node: Tree) -> EObject:
        return self.property_sets.property_set(node, self.filename)

    # ----------------------------------------------------------------- packages

    def package(self, node: Tree) -> EObject:
        qname, public, private, properties, end = node.children
        name = "::".join(qname.children)
        first = qname.children[0]
        start = self.rules.begin_package()  # (already open when a classifier was built)
        self.rules.end_name(name, "::".join(end.children), "package", end.children[0], first=start)
        pkg = make("AadlPackage", name=name, line=first.line, column=first.column, sourceFile=self.filename)
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
            if not isinstance(item, Tree):  # a classifier built while parsing
                update(item, visibility=vis)
                classifiers.append(item)
                continue
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

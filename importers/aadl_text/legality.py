"""The legality rules of AADL text that the grammar leaves to the reader, and what they find.

The tables say what SAE AS5506C (sections 4-7, as OSATE's grammar states them) allows where:
which feature kinds a component type of each category may declare (:data:`FEATURES_ALLOWED`),
which subcomponent categories (:data:`SUBCOMPONENTS_ALLOWED`) and connection kinds
(:data:`CONNECTIONS_ALLOWED`) an implementation may hold, which implementations have calls
(:data:`CALLS_ALLOWED`), flows and modes.  Virtual bus access goes wherever bus access does.

:class:`Legality` applies them while the builder walks the parse tree of one file, together
with the rules on names (``end`` names, a name declared twice in one namespace, an
implementation of another category than its type, a unit defined from an unknown one), and
collects what it finds as located diagnostics: errors, which the reader raises together as one
:class:`rosaadl.errors.ValidationError`, and warnings (the builder's notes among them).
"""

from __future__ import annotations

from typing import Any

from lark import Token, Tree

from rosaadl.errors import AadlSyntaxError, Diagnostic, Location
from rosaadl.importers.aadl_text.tree import CATEGORIES, CONNECTION_NODES, FEATURE_NODES, keywords, position

__all__ = [
    "CALLS_ALLOWED",
    "CONNECTIONS_ALLOWED",
    "FEATURES_ALLOWED",
    "SUBCOMPONENTS_ALLOWED",
    "Legality",
]

# --------------------------------------------------------------------------- tables

_PORTS = frozenset({"dataPort", "eventPort", "eventDataPort"})
_BUS_ACCESS = frozenset({"busAccess", "virtualBusAccess"})
_COMMON_FEATURES = frozenset({"featureGroup", "abstractFeature"})
_CALLABLE = frozenset({"subprogramAccess", "subprogramGroupAccess"})
_SOFTWARE_FEATURES = _PORTS | _COMMON_FEATURES | _CALLABLE | {"dataAccess"}
_PLATFORM_FEATURES = _PORTS | _COMMON_FEATURES | _CALLABLE | _BUS_ACCESS

#: The feature kinds (``FeatureCategory`` literal names) a component type of each category may declare.
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

_SOFTWARE_PARTS = frozenset({"data", "subprogram", "subprogram group", "abstract"})

#: The subcomponent categories an implementation of each category may hold.
SUBCOMPONENTS_ALLOWED: dict[str, frozenset[str]] = {
    "abstract": CATEGORIES,
    "system": CATEGORIES - {"thread", "thread group"},
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
#: The connection kinds an implementation of each category may hold.
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

# --------------------------------------------------------------------------- the rules of one file


class Legality:
    """The legality rules of one file, applied as its parse tree is built, and the located
    errors and warnings found in it (in the order found)."""

    def __init__(self, filename: str) -> None:
        self.filename = filename
        self.errors: list[Diagnostic] = []
        self.warnings: list[Diagnostic] = []
        # the package being built: its classifier names, the category of each component type
        # and, for each implementation, (type name, implementation name, category); and where
        # its diagnostics begin in ``errors`` (None: no package open)
        self._classifier_names: dict[str, int] = {}
        self._types: dict[str, tuple[Token, str]] = {}
        self._implementations: list[tuple[Token, Token, str]] = []
        self._package_start: int | None = None

    # ----------------------------------------------------------------- diagnostics

    def error(self, message: str, line: int | None, column: int | None) -> None:
        self.errors.append(Diagnostic("error", message, Location(self.filename, line, column)))

    def warning(self, message: str, line: int | None, column: int | None) -> None:
        self.warnings.append(Diagnostic("warning", message, Location(self.filename, line, column)))

    def error_at(self, message: str, where: Any) -> None:
        """An error located at the first token of a node."""
        line, column = position(where)
        self.error(message, line, column)

    def warning_at(self, message: str, where: Any) -> None:
        """A warning located at the first token of a node."""
        line, column = position(where)
        self.warning(message, line, column)

    def fatal(self, message: str, where: Any) -> AadlSyntaxError:
        """An error that stops the reading of the file (to raise), located at a node."""
        line, column = position(where)
        return AadlSyntaxError(message, file=self.filename, line=line, column=column)

    # ----------------------------------------------------------------- names

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

    def end_name(self, name: str, end: str, what: str, where: Any, *, first: int | None = None) -> None:
        """A package, classifier or property set ends with its own name (the error is put at
        index ``first`` of ``errors`` when given: a package's, before those of its members)."""
        if name.lower() != end.lower():
            line, column = position(where)
            self.error(f"{what} {name} ends with 'end {end}': expected 'end {name}'", line, column)
            if first is not None:
                self.errors.insert(first, self.errors.pop())

    # ----------------------------------------------------------------- packages

    def begin_package(self) -> int:
        """Open the package being built, when none is (its first member calls this, or the
        package itself when it has none); the index in ``errors`` where its diagnostics begin."""
        if self._package_start is None:
            self._classifier_names = {}
            self._types = {}
            self._implementations = []
            self._package_start = len(self.errors)
        return self._package_start

    def component_type(self, node: Tree) -> None:
        """A component type of the package (its name declared)."""
        name = node.children[1]
        self.declare(self._classifier_names, name, "classifier")
        self._types.setdefault(name.lower(), (name, keywords(node.children[0])))

    def component_implementation(self, node: Tree) -> None:
        """A component implementation of the package (its name declared)."""
        type_name, impl_name = node.children[1].children
        self.declare(self._classifier_names, type_name, "classifier", f"{type_name}.{impl_name}")
        self._implementations.append((type_name, impl_name, keywords(node.children[0])))

    def feature_group_type(self, node: Tree) -> None:
        """A feature group type of the package (its name declared)."""
        self.declare(self._classifier_names, node.children[0], "classifier")

    def end_package(self) -> None:
        """An implementation has the category of its type (when the type is in this package);
        the package is closed."""
        for type_name, impl_name, impl_category in self._implementations:
            ctype = self._types.get(type_name.lower())
            if ctype is None:
                continue
            declared, type_category = ctype
            if impl_category != type_category:
                self.error(
                    f"{impl_category} implementation {type_name}.{impl_name} implements {type_category} "
                    f"type {declared}: the categories must be the same",
                    type_name.line,
                    type_name.column,
                )
        self._classifier_names = {}
        self._types = {}
        self._implementations = []
        self._package_start = None

    # ----------------------------------------------------------------- sections of classifiers

    def type_section(self, category: str, section: Tree) -> None:
        """Flow specifications and modes of a component type."""
        if not section.children:
            return
        kind = section.data
        if kind == "flow_specs" and category in _NO_FLOW_SPECS:
            self.error_at(f"a {category} type cannot have flow specifications", section)
        elif kind in ("modes", "requires_modes") and category in _NO_TYPE_MODES:
            self.error_at(f"a {category} type cannot have modes", section)

    def implementation_section(self, category: str, section: Tree) -> None:
        """Flows and subprogram calls of a component implementation."""
        if not section.children:
            return
        kind = section.data
        if kind == "flow_impls" and category in _NO_FLOW_IMPLS:
            self.error_at(f"a {category} implementation cannot have flows", section)
        elif kind == "calls" and category not in CALLS_ALLOWED:
            self.error_at(
                f"a {category} implementation cannot have subprogram calls "
                "(only thread, subprogram and abstract implementations can)",
                section,
            )

    # ----------------------------------------------------------------- members

    def feature(self, category: str | None, kind: str, name: Token) -> None:
        """A feature (node ``kind``) of a component type of ``category`` (None: of a feature
        group type, which may have any)."""
        allowed = FEATURES_ALLOWED.get(category or "")
        if allowed is None:
            return
        category_name, text = FEATURE_NODES[kind]
        if category_name not in allowed:
            self.error(f"a {category} cannot have {text} features ({name})", name.line, name.column)

    def subcomponent(self, category: str, sub_category: str, name: Token) -> None:
        """A subcomponent of ``sub_category`` in an implementation of ``category``."""
        allowed = SUBCOMPONENTS_ALLOWED[category]
        if sub_category not in allowed:
            self.error(
                f"a {category} implementation cannot contain {sub_category} subcomponents ({name}); "
                f"it can contain: {', '.join(sorted(allowed))}",
                name.line,
                name.column,
            )

    def connection(
        self,
        category: str,
        kind: str,
        name: Token | None,
        complete: bool,
        line: int | None,
        column: int | None,
    ) -> None:
        """A connection (node ``kind``) of an implementation of ``category``; ``complete``: it
        has its ends (or refines a connection that has)."""
        word = CONNECTION_NODES[kind]
        if word not in CONNECTIONS_ALLOWED[category]:
            self.error(
                f"a {category} implementation cannot have {word} connections"
                + (f" ({name})" if name is not None else ""),
                line,
                column,
            )
        if not complete:
            self.error("a connection needs a source and a destination", line, column)

    def flow_ends(self, name: Token, complete: bool, end_to_end: bool = False) -> None:
        """A flow specification has its end features, an end-to-end flow its elements (unless
        they refine one)."""
        if complete:
            return
        if end_to_end:
            self.error(f"end-to-end flow {name} needs its flow elements", name.line, name.column)
        else:
            self.error(f"flow {name} needs its end feature", name.line, name.column)

    def unit_base(self, units: dict[str, int], name: Token, base: Token) -> None:
        """A unit is defined from one declared before it in its units type (``units``)."""
        if base.lower() not in units:
            self.error(
                f"unit {name} is defined from {base}, which is not a unit declared before it",
                base.line,
                base.column,
            )

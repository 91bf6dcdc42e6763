"""The vocabulary of the parse tree and small readers of its nodes.

The node names and child layouts are those of ``aadl.lark`` (see
:mod:`rosaadl.importers.aadl_syntax`); the tables here say which model literal each kind of
node stands for (:data:`CATEGORIES`, :data:`FEATURE_NODES`, :data:`CONNECTION_NODES`,
:data:`FLOW_KIND_NODES`).  Each function here turns one small node into the string
the metamodel keeps: a classifier reference ``Pkg::T.impl``, a path ``a.b[2].c``, an array size,
a connection end, a mode reference, an ``applies to`` owner; or gives the keywords of a node and
the position of its first token.
"""

from __future__ import annotations

from typing import Any

from lark import Token, Tree

from rosaadl.importers.aadl_text.lexical import parse_integer

__all__ = [
    "CATEGORIES",
    "CONNECTION_NODES",
    "FEATURE_NODES",
    "FLOW_KIND_NODES",
    "array_size",
    "classifier_ref",
    "end_text",
    "feature_classifier",
    "keywords",
    "mode_refs",
    "owner_text",
    "path_text",
    "position",
]

#: The 14 component categories, in the words :func:`keywords` gives for a category node.
CATEGORIES = frozenset(
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

#: The feature nodes: their ``FeatureCategory`` literal name and their AADL words.
FEATURE_NODES: dict[str, tuple[str, str]] = {
    "data_port": ("dataPort", "data port"),
    "event_port": ("eventPort", "event port"),
    "event_data_port": ("eventDataPort", "event data port"),
    "parameter": ("parameter", "parameter"),
    "feature_group": ("featureGroup", "feature group"),
    "abstract_feature": ("abstractFeature", "feature"),
    "data_access": ("dataAccess", "data access"),
    "bus_access": ("busAccess", "bus access"),
    "virtual_bus_access": ("virtualBusAccess", "virtual bus access"),
    "subprogram_access": ("subprogramAccess", "subprogram access"),
    "subprogram_group_access": ("subprogramGroupAccess", "subprogram group access"),
}

#: The connection nodes: their ``ConnectionKind`` in AADL words.
CONNECTION_NODES: dict[str, str] = {
    "port_connection": "port",
    "access_connection": "access",
    "feature_group_connection": "feature group",
    "feature_connection": "feature",
    "parameter_connection": "parameter",
}

#: The flow specification and flow implementation nodes: their ``FlowKind``.
FLOW_KIND_NODES: dict[str, str] = {
    "flow_source_spec": "source",
    "flow_sink_spec": "sink",
    "flow_path_spec": "path",
    "flow_source_impl": "source",
    "flow_sink_impl": "sink",
    "flow_path_impl": "path",
}


def keywords(node: Tree) -> str:
    """The keywords of a small node (category, direction, ...) as one lower-case phrase."""
    children = node.children
    if len(children) == 1:
        return children[0].lower()
    return " ".join(c.lower() for c in children)


def position(node: Any) -> tuple[int | None, int | None]:
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


def classifier_ref(node: Tree) -> str:
    """A classifier reference as written: ``Pkg::T`` or ``Pkg::T.impl``."""
    children = node.children
    impl = children[-1]
    name = "::".join(children[:-1])
    return f"{name}.{impl}" if impl is not None else name


def feature_classifier(node: Tree) -> str:
    """The classifier of a feature: a classifier reference or ``prototype p``."""
    if node.data == "prototype_ref":
        return f"prototype {node.children[0]}"
    return classifier_ref(node)


def array_size(node: Tree) -> str:
    """An array dimension: ``"3"``, ``"Pkg::Size"`` or ``""`` for ``[]``."""
    size = node.children[0]
    if size is None:
        return ""
    if isinstance(size, Token):
        return _index(size)
    return "::".join(size.children)


def path_text(node: Tree) -> str:
    """A path as written: ``a.b[2].c``, ``a[1 .. 3]``, ``annex EMV2``."""
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
        return str(parse_integer(token))
    except ValueError:
        return str(token)


def end_text(node: Any) -> str:
    """A connection end or mode transition trigger as written."""
    data = node.data
    if data == "path":
        return path_text(node)
    if data == "processor_port":
        return f"processor.{node.children[0]}"
    return f"self.{node.children[0]}"  # internal_event


def mode_refs(node: Tree) -> list[str]:
    """The modes of an ``in modes`` clause: ``"m"`` or ``"m => n"``."""
    out = []
    for ref in node.children:
        mode, target = ref.children
        out.append(f"{mode} => {target}" if target is not None else str(mode))
    return out


def owner_text(node: Tree) -> str:
    """An ``applies to`` owner or a classifier/reference type category, as written."""
    if node.data == "classifier_ref":
        return classifier_ref(node)
    prefix, *rest = node.children
    text = " ".join(rest)
    if prefix is not None:
        return "".join(prefix.split()) + " " + text
    return text

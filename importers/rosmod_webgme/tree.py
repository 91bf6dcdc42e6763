"""The WebGME tree of an export, navigated as WebGME's own core does (``common/core`` of webgme-engine).

``project.json`` holds content-addressed objects: each has an ``_id`` ("#sha1"), attributes
``atr``, registry ``reg``, relations ``ovr`` and its children as ``relid → hash`` keys.
:class:`Tree` indexes them and gives :class:`Node` objects by path; a node follows WebGME's rules:

* relations (pointers ``base``, ``src``/``dst``, ``Message``…, set members) live in the ``ovr``
  overlays of the common ancestor of their ends, possibly *sharded* into separate objects;
* a node inherits attributes from its ``base`` chain, and an instance inherits the children of
  its base (same relids, with the instance's own data overriding); relations inside an
  instantiated subtree are translated into the instance;
* a node's type is the first node of its base chain that belongs to the META aspect.

Loops and runaway depths in a hostile export are refused with a located error.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from rosaadl.importers.rosmod_webgme.archive import fail

__all__ = ["Tree", "Node"]

_MAX_CHAIN = 2_000  # longest base chain / containment depth followed
_NULL = object()  # a pointer set to null (as opposed to no pointer at all)
_RESERVED = frozenset({"atr", "reg", "ovr"})


class Tree:
    """The content-addressed objects of one export, navigated as WebGME's core does."""

    def __init__(self, doc: dict[str, Any], filename: str) -> None:
        self.filename = filename
        self.objects: dict[str, dict] = {}
        for index, obj in enumerate(doc["objects"]):
            if not isinstance(obj, dict) or not isinstance(obj.get("_id"), str):
                raise fail(f"objects[{index}] has no '_id'", filename, path=f"project.json/objects[{index}]")
            self.objects[obj["_id"]] = obj
        self._overlays: dict[int, dict[str, dict]] = {}
        self._nodes: dict[str, Node] = {}
        root_data = self.objects.get(doc["rootHash"])
        if root_data is None:
            raise fail(f"the root object {doc['rootHash']} is missing (truncated export?)", filename)
        self.root = Node(self, "", "", None, root_data)
        self._nodes[""] = self.root
        self.meta_paths = self._meta_paths()

    # -- raw data
    def fetch(self, ref: Any, where: str) -> dict:
        if isinstance(ref, dict):
            return ref
        obj = self.objects.get(ref) if isinstance(ref, str) else None
        if obj is None:
            raise fail(
                f"object {ref!r} is missing from project.json (truncated export?)", self.filename, path=where
            )
        return obj

    def overlays(self, data: dict, where: str) -> dict[str, dict]:
        key = id(data)
        cached = self._overlays.get(key)
        if cached is not None:
            return cached
        ovr = data.get("ovr")
        merged: dict[str, dict] = {}
        if isinstance(ovr, dict):
            if ovr.get("sharded"):
                for shard_id, ref in sorted(ovr.items()):
                    if shard_id == "sharded":
                        continue
                    shard = self.fetch(ref, f"{where} (overlay shard {shard_id})")
                    items = shard.get("items")
                    if isinstance(items, dict):
                        merged.update((k, v) for k, v in items.items() if isinstance(v, dict))
            else:
                merged = {k: v for k, v in ovr.items() if isinstance(v, dict)}
        self._overlays[key] = merged
        return merged

    def _meta_paths(self) -> set[str]:
        paths = set()
        prefix = "/_sets/MetaAspectSet/"
        for source, entry in self.overlays(self.root.data, "root").items():
            target = entry.get("member")
            if source.startswith(prefix) and "/" not in source[len(prefix) :] and isinstance(target, str):
                paths.add(target)
        if not paths:  # older exports: every META node carries its _meta rules
            raise fail("the export has no META aspect (not a WebGME project)", self.filename)
        return paths

    # -- nodes by path
    def node(self, path: str, where: str) -> Node:
        cached = self._nodes.get(path)
        if cached is not None:
            return cached
        current = self.root
        for relid in path.split("/")[1:]:
            child = current.child(relid)
            if child is None:
                raise fail(f"a relation points at {path!r}, which does not exist", self.filename, path=where)
            current = child
        return current


def _own_relids(data: dict) -> list[str]:
    return [
        key
        for key, value in data.items()
        if key not in _RESERVED
        and not key.startswith("_")
        and (isinstance(value, (str, dict)))
        and (not isinstance(value, str) or value.startswith("#"))
    ]


class Node:
    """One node of the tree: its data, containment, inheritance, attributes and pointers."""

    __slots__ = ("tree", "path", "relid", "parent", "data", "_base", "_relids", "_children", "_busy")

    def __init__(self, tree: Tree, path: str, relid: str, parent: Node | None, data: dict) -> None:
        self.tree = tree
        self.path = path
        self.relid = relid
        self.parent = parent
        self.data = data
        self._base: Any = _NULL  # not computed yet
        self._relids: list[str] | None = None
        self._children: dict[str, Node] = {}
        self._busy = False

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"<webgme node {self.path or '/'} {self.name!r}>"

    # -- containment
    def child(self, relid: str) -> Node | None:
        node = self._children.get(relid)
        if node is not None:
            return node
        if relid not in self.relids():
            return None
        own = self.data.get(relid) if relid in _own_relids(self.data) else None
        data = self.tree.fetch(own, f"{self.path}/{relid}") if own is not None else {}
        if self.path.count("/") > _MAX_CHAIN:
            raise fail("the containment tree is nested too deeply", self.tree.filename, path=self.path)
        node = Node(self.tree, f"{self.path}/{relid}", relid, self, data)
        self._children[relid] = node
        self.tree._nodes.setdefault(node.path, node)
        return node

    def relids(self) -> list[str]:
        if self._relids is None:
            seen = dict.fromkeys(_own_relids(self.data))
            base = self.base
            if base is not None:
                seen.update(dict.fromkeys(base.relids()))
            self._relids = list(seen)
        return self._relids

    def children(self) -> list[Node]:
        out = [self.child(r) for r in self.relids()]
        return [c for c in out if c is not None]

    def ancestors(self) -> Iterator[Node]:
        node: Node | None = self
        while node is not None:
            yield node
            node = node.parent

    # -- inheritance
    @property
    def base(self) -> Node | None:
        if self._base is not _NULL:
            return self._base
        if self._busy:
            raise fail("the inheritance (base) chain loops", self.tree.filename, path=self.path)
        self._busy = True
        try:
            self._base = self._compute_base()
        finally:
            self._busy = False
        return self._base

    def _compute_base(self) -> Node | None:
        if self.parent is None:
            return None
        parent_base = self.parent.base
        if parent_base is not None and self.relid in parent_base.relids():
            return parent_base.child(self.relid)
        target = self.own_pointer("base")
        if target is None or target is _NULL:
            return None
        node = self.tree.node(target, self.path)
        if node is self or self.path.startswith(node.path + "/"):
            raise fail("a node is its own base (or contains it)", self.tree.filename, path=self.path)
        return node

    def bases(self) -> Iterator[Node]:
        node: Node | None = self
        seen: set[int] = set()
        while node is not None:
            if id(node) in seen:
                raise fail("the inheritance (base) chain loops", self.tree.filename, path=self.path)
            seen.add(id(node))
            if len(seen) > _MAX_CHAIN:
                raise fail("the inheritance (base) chain is too long", self.tree.filename, path=self.path)
            yield node
            node = node.base

    # -- attributes, pointers
    def attribute(self, name: str) -> Any:
        for node in self.bases():
            atr = node.data.get("atr")
            if isinstance(atr, dict) and name in atr:
                return atr[name]
        return None

    def own_attribute_names(self) -> list[str]:
        atr = self.data.get("atr")
        return [k for k in atr if not k.startswith("_")] if isinstance(atr, dict) else []

    def attribute_names(self) -> list[str]:
        """The names of every attribute set on this node or its bases, sorted."""
        names: dict[str, None] = {}
        for layer in self.bases():
            for key in layer.own_attribute_names():
                names.setdefault(key)
        return sorted(names)

    def project_attributes(self) -> dict[str, Any]:
        """Attributes set in the project (own or inherited from non-META bases), without ``name``."""
        out: dict[str, Any] = {}
        for layer in self.bases():
            if layer.is_meta():
                break
            for key in layer.own_attribute_names():
                if key != "name" and key not in out:
                    out[key] = layer.data["atr"][key]
        return dict(sorted(out.items()))

    @property
    def name(self) -> str:
        value = self.attribute("name")
        return value if isinstance(value, str) else ""

    def own_pointer(self, name: str, source_suffix: str = "") -> Any:
        """The pointer as stored in the overlays of this node's ancestors (WebGME's inner core)."""
        for ancestor in self.ancestors():
            rel = self.path[len(ancestor.path) :] + source_suffix
            entry = self.tree.overlays(ancestor.data, ancestor.path).get(rel)
            if entry is not None and name in entry:
                target = entry[name]
                if not isinstance(target, str) or "_nullptr" in target:
                    return _NULL
                return ancestor.path + target if target else ancestor.path
        return None

    def pointer(self, name: str) -> Node | None:
        """Follow a pointer with WebGME's inheritance rules; None when unset or null."""
        path = self._pointer_path(name)
        if path is None or path is _NULL:
            return None
        return self.tree.node(path, f"{self.path} ({name})")

    def _pointer_path(self, name: str) -> Any:
        own = self.own_pointer(name)
        if own is not None:
            return own
        base_path = None
        for base in list(self.bases())[1:]:
            base_path = base.own_pointer(name)
            if base_path is not None:
                break
        has_null = False
        source = ""
        node: Node | None = self
        while node is not None:
            for layer in node.bases():
                entry = self.tree.overlays(layer.data, layer.path).get(source)
                if entry is not None and name in entry:
                    target = entry[name]
                    if isinstance(target, str) and "_nullptr" not in target:
                        return node.path + target if target else node.path
                    has_null = True
                    break
            source = f"/{node.relid}{source}"
            parent = node.parent
            if parent is None:
                break
            parent_of_base = node.base.parent.path if node.base is not None and node.base.parent else None
            base_of_parent = parent.base.path if parent.base is not None else None
            node = parent if parent_of_base == base_of_parent else None
        if base_path is not None and base_path is not _NULL:
            return base_path
        return _NULL if has_null or base_path is _NULL else None

    def set_members(self, set_name: str) -> list[Node]:
        sets = self.data.get("_sets")
        members = sets.get(set_name) if isinstance(sets, dict) else None
        out = []
        if isinstance(members, dict):
            for member_id in sorted(members):
                if member_id in _RESERVED or member_id.startswith("_"):
                    continue
                target = self.own_pointer("member", f"/_sets/{set_name}/{member_id}")
                if isinstance(target, str):
                    out.append(self.tree.node(target, f"{self.path} (set {set_name})"))
        return out

    @property
    def meta_type(self) -> str:
        for node in self.bases():
            if node.path in self.tree.meta_paths:
                return node.name
        return ""

    def is_meta(self) -> bool:
        return self.path in self.tree.meta_paths

    def element_path(self) -> str:
        """The names from below the root down to this node (``AGSE/Software/motor_controller``)."""
        names = [n.name or n.relid for n in reversed(list(self.ancestors()))][1:]
        return "/".join(names)

"""WebGME ROSMOD exports (``.webgmex``) → ``rosmod.ecore`` models, one ``Project`` per ROSMOD project.

A ``.webgmex`` file is a zip archive whose ``project.json`` holds the content-addressed objects of
one WebGME project tree (``{rootHash, objects: [...]}``; each object has an ``_id`` "#sha1",
attributes ``atr``, registry ``reg``, relations ``ovr`` and its children as ``relid → hash``
keys). The archive's other members (``<hash>.content``/``.metadata``: experiment logs) are not
read. The reader follows WebGME's own rules (``common/core`` of webgme-engine):

* relations (pointers ``base``, ``src``/``dst``, ``Message``…, set members) live in the ``ovr``
  overlays of the common ancestor of their ends, possibly *sharded* into separate objects;
* a node inherits attributes from its ``base`` chain, and an instance inherits the children of
  its base (same relids, with the instance's own data overriding); relations inside an
  instantiated subtree are translated into the instance;
* a node's type is the first node of its base chain that belongs to the META aspect.

Mapping to ``rosmod.ecore`` (WebGME facts without a slot go into ``properties``; keys of
attributes are kept exactly as WebGME spells them; children without a slot become
``"<Kind>:<name>"`` properties whose value is a JSON object of their attributes and pointers):

* ``Software`` → packages with messages (``Definition`` parsed as ROS ``.msg``), services,
  components (timers, publishers, subscribers, clients, servers); ``External Message``/``Service``
  are not project types, ports that use them get ``<Package>/<name>``; actions, action clients
  and servers, state machines and constraints become ``Action:``/``Action Client:``/``Action
  Server:``/``State Machine:``/``Constraint:`` properties; libraries become project properties;
* ``Systems`` → one :class:`System` each with hosts (``Architecture``, ``OS``, ``ROS Install``,
  the first member of the host's ``Users`` set → ``username``/``sshKey``/``deploymentPath``, the
  ``IP`` of a link from one of its interfaces → ``ipAddress``), networks and links;
* ``Deployments`` → one :class:`Deployment` each; containers are kept as ``Container:<name>``
  deployment properties and as the ``container`` property of their nodes; a deployed component
  is a :class:`ComponentInstance` of the software component it derives from (its ``componentRef``
  is ``<package>/<component>``), with its effective scheduling scheme, its ``Logging*``
  attributes as ``logging`` entries, and the values it overrides (on itself or on the timers and
  ports it inherits) as properties ``<attribute>`` / ``<child>.<attribute>``;
* ``Experiments`` are kept as ``Experiment:<name>`` deployment properties; when every experiment
  of a deployment uses the same system, that system becomes the deployment's ``system``.
  WebGME nodes are not bound to hosts (experiments map them at run time), so ``Node.host`` is
  unset.
"""

from __future__ import annotations

import json
import logging
import os
import zipfile
import zlib
from collections.abc import Iterator
from decimal import Decimal, InvalidOperation
from pathlib import PurePosixPath
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, ImportFormatError, Location, NameResolutionError, RosaadlError
from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_text import RosmodImportError, scheme_literal

__all__ = [
    "MAX_TOTAL_BYTES",
    "MAX_MEMBERS",
    "read_webgmex",
    "project_names",
    "load_project_json",
]

log = logging.getLogger(__name__)

#: Refuse archives whose members add up to more than this many bytes (uncompressed).
MAX_TOTAL_BYTES = 200 * 1024 * 1024
#: Refuse archives with more members than this.
MAX_MEMBERS = 20_000
_MAX_CHAIN = 2_000  # longest base chain / containment depth followed
_NULL = object()  # a pointer set to null (as opposed to no pointer at all)
_RESERVED = frozenset({"atr", "reg", "ovr"})


def _fail(message: str, filename: str, path: str | None = None, **where: Any) -> ImportFormatError:
    return ImportFormatError(message, Location(file=filename, path=path, **where))


# =========================================================================== archive


def _check_member_name(name: str, filename: str) -> None:
    pure = PurePosixPath(name.replace("\\", "/"))
    if (
        name.startswith(("/", "\\"))
        or (len(name) > 1 and name[1] == ":")
        or ".." in pure.parts
        or "\x00" in name
    ):
        raise _fail(
            f"the archive member {name!r} points outside the archive (absolute path or '..'); "
            "refusing the file (nothing was extracted)",
            filename,
            path=name,
        )


def load_project_json(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The parsed ``project.json`` of a ``.webgmex`` archive, after the archive's safety checks.

    Refused with a located :class:`ImportFormatError`: a file that is not a zip archive, a
    truncated or corrupt archive, a member named with an absolute path or ``..``, more than
    :data:`MAX_MEMBERS` members or more than :data:`MAX_TOTAL_BYTES` uncompressed bytes,
    encrypted members, a missing or malformed ``project.json``.
    """
    filename = os.fspath(path)
    try:
        if not zipfile.is_zipfile(filename):
            raise _fail("not a zip archive: a .webgmex export is a zip file holding project.json", filename)
        with zipfile.ZipFile(filename) as archive:
            infos = archive.infolist()
            if len(infos) > MAX_MEMBERS:
                raise _fail(
                    f"the archive has {len(infos)} members (more than {MAX_MEMBERS}); refused", filename
                )
            total = 0
            for info in infos:
                _check_member_name(info.filename, filename)
                total += info.file_size
            if total > MAX_TOTAL_BYTES:
                raise _fail(
                    f"the archive would unpack to {total} bytes (more than {MAX_TOTAL_BYTES}); refused",
                    filename,
                )
            try:
                info = archive.getinfo("project.json")
            except KeyError:
                raise _fail("the archive has no project.json (not a WebGME export)", filename) from None
            if info.flag_bits & 0x1:
                raise _fail("project.json is encrypted", filename, path="project.json")
            data = bytearray()
            with archive.open(info) as handle:
                while True:
                    chunk = handle.read(1 << 20)
                    if not chunk:
                        break
                    data.extend(chunk)
                    if len(data) > MAX_TOTAL_BYTES:
                        raise _fail(
                            f"project.json unpacks to more than {MAX_TOTAL_BYTES} bytes; refused",
                            filename,
                            path="project.json",
                        )
    except (zipfile.BadZipFile, zipfile.LargeZipFile, zlib.error, EOFError, NotImplementedError) as exc:
        raise _fail(f"corrupt or truncated zip archive: {exc}", filename) from None
    except OSError as exc:
        raise _fail(f"cannot read the archive: {exc.strerror or exc}", filename) from None
    try:
        doc = json.loads(bytes(data).decode("utf-8-sig"))
    except UnicodeDecodeError as exc:
        raise _fail(
            f"project.json is not UTF-8 text (byte {exc.start})", filename, path="project.json"
        ) from None
    except json.JSONDecodeError as exc:
        raise _fail(
            f"malformed project.json: {exc.msg}",
            filename,
            path="project.json",
            line=exc.lineno,
            column=exc.colno,
        ) from None
    except RecursionError:
        raise _fail("project.json is nested too deeply", filename, path="project.json") from None
    if (
        not isinstance(doc, dict)
        or not isinstance(doc.get("rootHash"), str)
        or not isinstance(doc.get("objects"), list)
    ):
        raise _fail(
            "project.json is not a WebGME export (expected an object with 'rootHash' and 'objects')",
            filename,
            path="project.json",
        )
    return doc


# =========================================================================== the WebGME tree


class _Tree:
    """The content-addressed objects of one export, navigated as WebGME's core does."""

    def __init__(self, doc: dict[str, Any], filename: str) -> None:
        self.filename = filename
        self.objects: dict[str, dict] = {}
        for index, obj in enumerate(doc["objects"]):
            if not isinstance(obj, dict) or not isinstance(obj.get("_id"), str):
                raise _fail(f"objects[{index}] has no '_id'", filename, path=f"project.json/objects[{index}]")
            self.objects[obj["_id"]] = obj
        self._overlays: dict[int, dict[str, dict]] = {}
        self._nodes: dict[str, _Node] = {}
        root_data = self.objects.get(doc["rootHash"])
        if root_data is None:
            raise _fail(f"the root object {doc['rootHash']} is missing (truncated export?)", filename)
        self.root = _Node(self, "", "", None, root_data)
        self._nodes[""] = self.root
        self.meta_paths = self._meta_paths()

    # -- raw data
    def fetch(self, ref: Any, where: str) -> dict:
        if isinstance(ref, dict):
            return ref
        obj = self.objects.get(ref) if isinstance(ref, str) else None
        if obj is None:
            raise _fail(
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
            raise _fail("the export has no META aspect (not a WebGME project)", self.filename)
        return paths

    # -- nodes by path
    def node(self, path: str, where: str) -> _Node:
        cached = self._nodes.get(path)
        if cached is not None:
            return cached
        current = self.root
        for relid in path.split("/")[1:]:
            child = current.child(relid)
            if child is None:
                raise _fail(f"a relation points at {path!r}, which does not exist", self.filename, path=where)
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


class _Node:
    __slots__ = ("tree", "path", "relid", "parent", "data", "_base", "_relids", "_children", "_busy")

    def __init__(self, tree: _Tree, path: str, relid: str, parent: _Node | None, data: dict) -> None:
        self.tree = tree
        self.path = path
        self.relid = relid
        self.parent = parent
        self.data = data
        self._base: Any = _NULL  # not computed yet
        self._relids: list[str] | None = None
        self._children: dict[str, _Node] = {}
        self._busy = False

    def __repr__(self) -> str:  # pragma: no cover - debugging aid
        return f"<webgme node {self.path or '/'} {self.name!r}>"

    # -- containment
    def child(self, relid: str) -> _Node | None:
        node = self._children.get(relid)
        if node is not None:
            return node
        if relid not in self.relids():
            return None
        own = self.data.get(relid) if relid in _own_relids(self.data) else None
        data = self.tree.fetch(own, f"{self.path}/{relid}") if own is not None else {}
        if self.path.count("/") > _MAX_CHAIN:
            raise _fail("the containment tree is nested too deeply", self.tree.filename, path=self.path)
        node = _Node(self.tree, f"{self.path}/{relid}", relid, self, data)
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

    def children(self) -> list[_Node]:
        out = [self.child(r) for r in self.relids()]
        return [c for c in out if c is not None]

    def ancestors(self) -> Iterator[_Node]:
        node: _Node | None = self
        while node is not None:
            yield node
            node = node.parent

    # -- inheritance
    @property
    def base(self) -> _Node | None:
        if self._base is not _NULL:
            return self._base
        if self._busy:
            raise _fail("the inheritance (base) chain loops", self.tree.filename, path=self.path)
        self._busy = True
        try:
            self._base = self._compute_base()
        finally:
            self._busy = False
        return self._base

    def _compute_base(self) -> _Node | None:
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
            raise _fail("a node is its own base (or contains it)", self.tree.filename, path=self.path)
        return node

    def bases(self) -> Iterator[_Node]:
        node: _Node | None = self
        seen: set[int] = set()
        while node is not None:
            if id(node) in seen:
                raise _fail("the inheritance (base) chain loops", self.tree.filename, path=self.path)
            seen.add(id(node))
            if len(seen) > _MAX_CHAIN:
                raise _fail("the inheritance (base) chain is too long", self.tree.filename, path=self.path)
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

    def pointer(self, name: str) -> _Node | None:
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
        node: _Node | None = self
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

    def set_members(self, set_name: str) -> list[_Node]:
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

    def named_path(self) -> str:
        names = [n.name or n.relid for n in reversed(list(self.ancestors()))]
        return "/".join(names)


# =========================================================================== mapping to rosmod.ecore

_LOGGING_KEYS = ("EnableLogging", "LoggingUnit")
_SCHEMES = ("FIFO", "PFIFO", "EDF")
_LIBRARY_KINDS = ("System Library", "Source Library", "Development Library", "Library")
_SKIPPED_KINDS = ("Documentation", "Code Documentation", "Results")


def _text(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (dict, list)):
        return json.dumps(value, sort_keys=True)
    return "" if value is None else str(value)


def _set(obj: EObject, **values: Any) -> None:
    """Set the features whose value is not None (unset features keep the metamodel default)."""
    for key, value in values.items():
        if value is not None:
            setattr(obj, key, value)


def _is_logging_key(key: str) -> bool:
    return key.startswith("Logging") or key in _LOGGING_KEYS


class _Mapper:
    """Maps the WebGME tree of one project onto a ``rosmod.Project`` (one run, no global state)."""

    def __init__(self, tree: _Tree, filename: str, warnings: list[Diagnostic] | None) -> None:
        self.tree = tree
        self.filename = filename
        self.warnings = warnings
        self.errors: list[RosaadlError] = []
        self.by_path: dict[str, EObject] = {}  # WebGME node path → model object
        self.experiments: list[tuple[str, _Node]] = []
        self.pending_components: list[tuple[EObject, _Node, _Node]] = []

    # -- diagnostics
    def where(self, node: _Node) -> str:
        names = [n.name or n.relid for n in reversed(list(node.ancestors()))][1:]
        return "/".join(names)

    def warn(self, node: _Node, message: str) -> None:
        diag = Diagnostic("warning", message, Location(file=self.filename, path=self.where(node)))
        log.warning("%s", diag)
        if self.warnings is not None:
            self.warnings.append(diag)

    def error(self, node: _Node, message: str, cls: type[RosaadlError] = ImportFormatError) -> None:
        self.errors.append(cls(message, Location(file=self.filename, path=self.where(node))))

    # -- generic helpers
    def children(self, node: _Node) -> list[_Node]:
        out = []
        for child in node.children():
            if child.base is None:
                self.warn(child, "node without a base (WebGME drops such nodes); skipped")
                continue
            out.append(child)
        return sorted(out, key=lambda c: (c.name, c.relid))

    def project_attrs(self, node: _Node) -> dict[str, Any]:
        """Attributes set in the project (own or inherited from non-META bases), without ``name``."""
        out: dict[str, Any] = {}
        for layer in node.bases():
            if layer.is_meta():
                break
            for key in layer.own_attribute_names():
                if key != "name" and key not in out:
                    out[key] = layer.data["atr"][key]
        return dict(sorted(out.items()))

    def all_attr_names(self, node: _Node) -> list[str]:
        names: dict[str, None] = {}
        for layer in node.bases():
            for key in layer.own_attribute_names():
                names.setdefault(key)
        return sorted(names)

    def opaque(self, node: _Node) -> str:
        """A JSON summary of an element the metamodel has no class for."""
        value: dict[str, Any] = {k: _text(v) for k, v in self.project_attrs(node).items()}
        for name in ("Type", "Action", "Message", "Service", "src", "dst"):
            target = node.pointer(name)
            if target is not None:
                value[name] = self.type_name(target) or self.where(target)
        kids = [f"{c.meta_type}:{c.name}" for c in self.children(node)]
        if kids:
            value["children"] = kids
        return json.dumps(value, sort_keys=True)

    def prop(self, key: str, value: Any) -> EObject:
        return model.new("rosmod.Property", key=key, value=_text(value))

    def seconds(self, node: _Node, attr: str) -> Decimal | None:
        value = node.attribute(attr)
        if value is None or value == "":
            return None
        try:
            number = Decimal(repr(value)) if isinstance(value, float) else Decimal(str(value).strip())
        except InvalidOperation:
            self.error(node, f"{attr} = {value!r}: expected a number of seconds")
            return None
        if not number.is_finite() or number < 0:
            self.error(node, f"{attr} = {value!r}: expected a non-negative number of seconds")
            return None
        return number

    def integer(self, node: _Node, attr: str) -> int | None:
        value = node.attribute(attr)
        if value is None or value == "":
            return None
        try:
            number = Decimal(repr(value)) if isinstance(value, float) else Decimal(str(value).strip())
            if number.is_finite() and number == number.to_integral_value():
                return int(number)
        except InvalidOperation:
            pass
        self.error(node, f"{attr} = {value!r}: expected an integer")
        return None

    def type_name(self, target: _Node, seen: tuple[str, ...] = ()) -> str | None:
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
            return self.type_name(inner, (*seen, target.path)) if inner is not None else None
        return None

    # -- project
    def project(self, node: _Node) -> EObject:
        project = model.new("rosmod.Project", name=node.name, formatVersion="webgme", path=self.filename)
        for key, value in self.project_attrs(node).items():
            project.properties.append(self.prop(key, value))
        software_nodes = []
        for child in self.children(node):
            kind = child.meta_type
            if kind == "Software":
                software_nodes.append(child)
            elif kind == "Systems":
                for system in self.children(child):
                    if system.meta_type == "System":
                        project.systems.append(self.system(system))
                    else:
                        self.unknown(child, system, project.properties)
            elif kind == "Deployments":
                for dep in self.children(child):
                    if dep.meta_type == "Deployment":
                        project.deployments.append(self.deployment(dep))
                    else:
                        self.unknown(child, dep, project.properties)
            elif kind == "Experiments":
                self.experiments.extend((child.name, e) for e in self.children(child))
            elif kind in _SKIPPED_KINDS:
                log.debug("skipped %s %s", kind, self.where(child))
            else:
                self.unknown(node, child, project.properties)
        if software_nodes:
            software = model.new(
                "rosmod.Software", name=software_nodes[0].name, sourceFile=os.path.basename(self.filename)
            )
            if len(software_nodes) > 1:
                self.warn(node, f"{len(software_nodes)} Software folders; their packages are merged")
            for sw in software_nodes:
                self.software(sw, software, project)
            project.software = software
        self.finish(project)
        return project

    def unknown(self, parent: _Node, child: _Node, properties: Any) -> None:
        kind = child.meta_type or "?"
        if kind in _SKIPPED_KINDS:
            return
        self.warn(
            child, f"{kind} {child.name!r} has no rosmod counterpart; kept as a property of {parent.name!r}"
        )
        properties.append(self.prop(f"{kind}:{child.name}", self.opaque(child)))

    # -- software
    def software(self, node: _Node, software: EObject, project: EObject) -> None:
        for child in self.children(node):
            kind = child.meta_type
            if kind == "Package":
                software.packages.append(self.package(child))
            elif kind in _LIBRARY_KINDS:
                project.properties.append(self.prop(f"{kind}:{child.name}", self.opaque(child)))
            elif kind == "External Definitions":
                for ext in self.children(child):
                    project.properties.append(
                        self.prop(f"{ext.meta_type}:{ext.name}", json.dumps({"Type": self.type_name(ext)}))
                    )
            elif kind not in _SKIPPED_KINDS:
                self.unknown(node, child, project.properties)
        for package in software.packages:
            self.check_unique(node, package.messages, "message", package.name)
            self.check_unique(node, package.services, "service", package.name)
            self.check_unique(node, package.components, "component", package.name)
        self.check_unique(node, software.packages, "package", node.name)

    def check_unique(self, node: _Node, objects: Any, what: str, owner: str) -> None:
        seen: set[str] = set()
        for obj in objects:
            if obj.name in seen:
                self.warn(node, f"{what} name {obj.name!r} is used twice in {owner!r}")
            seen.add(obj.name)

    def package(self, node: _Node) -> EObject:
        package = model.new("rosmod.Package", name=node.name)
        self.by_path[node.path] = package
        for key, value in self.project_attrs(node).items():
            package.properties.append(self.prop(key, value))
        for child in self.children(node):
            kind = child.meta_type
            if kind == "Message":
                package.messages.append(self.message(child, node.name))
            elif kind == "Service":
                package.services.append(self.service(child, node.name))
            elif kind == "Component":
                package.components.append(self.component(child, node.name))
            elif kind in ("Action", "Advertised Message", "Advertised Service", "Advertised Action"):
                package.properties.append(self.prop(f"{kind}:{child.name}", self.opaque(child)))
            elif kind not in _SKIPPED_KINDS:
                self.unknown(node, child, package.properties)
        return package

    def definition_errors(self, node: _Node, exc: ros_msg.RosMessageError) -> None:
        for err in exc.errors:
            loc = err.location
            self.errors.append(
                ImportFormatError(
                    f"Definition: {err.message}",
                    Location(file=self.filename, line=loc.line, column=loc.column, path=self.where(node)),
                )
            )

    def message(self, node: _Node, package: str) -> EObject:
        text = _text(node.attribute("Definition"))
        msg = model.new("rosmod.Message", name=node.name, definition=text)
        try:
            ros_msg.fill_message(msg, package=package)
        except ros_msg.RosMessageError as exc:
            self.definition_errors(node, exc)
        self.by_path[node.path] = msg
        return msg

    def service(self, node: _Node, package: str) -> EObject:
        text = _text(node.attribute("Definition"))
        srv = model.new("rosmod.Service", name=node.name, definition=text)
        try:
            ros_msg.fill_service(srv, package=package)
        except ros_msg.RosMessageError as exc:
            self.definition_errors(node, exc)
        self.by_path[node.path] = srv
        return srv

    _SLOTS = {
        "Timer": ("Period", "Priority", "Deadline", "Operation"),
        "Publisher": ("Latching",),
        "Subscriber": ("Priority", "Deadline", "Operation"),
        "Server": ("Priority", "Deadline", "Operation"),
        "Client": (),
    }
    _TYPE_POINTER = {
        "Publisher": "Message",
        "Subscriber": "Message",
        "Client": "Service",
        "Server": "Service",
    }

    def component(self, node: _Node, package: str) -> EObject:
        comp = model.new("rosmod.Component", name=node.name)
        self.by_path[node.path] = comp
        scheme = node.attribute("SchedulingScheme")
        self.scheme(node, comp, scheme)
        for key, value in self.project_attrs(node).items():
            if key != "SchedulingScheme":
                comp.properties.append(self.prop(key, value))
        libraries = node.set_members("Libraries")
        if libraries:
            comp.properties.append(self.prop("Libraries", ", ".join(sorted(lib.name for lib in libraries))))
        for child in self.children(node):
            kind = child.meta_type
            if kind == "Timer":
                timer = model.new(
                    "rosmod.Timer",
                    name=child.name,
                    period=self.seconds(child, "Period"),
                    priority=self.integer(child, "Priority"),
                    deadline=self.seconds(child, "Deadline"),
                    operation=_text(child.attribute("Operation")) or None,
                )
                comp.timers.append(timer)
                self.by_path[child.path] = timer
            elif kind in self._TYPE_POINTER:
                port = model.new(f"rosmod.{kind}", name=child.name)
                target = child.pointer(self._TYPE_POINTER[kind])
                _set(port, type=self.type_name(target) if target is not None else None)
                if port.type is None:
                    self.warn(child, f"{kind} {child.name!r} has no {self._TYPE_POINTER[kind].lower()} type")
                if target is not None and target.meta_type.startswith("Advertised "):
                    comp.properties.append(
                        self.prop(f"{child.name}.Topic", f"{target.parent.name}/{target.name}")
                    )
                if kind in ("Subscriber", "Server"):
                    _set(
                        port,
                        priority=self.integer(child, "Priority"),
                        deadline=self.seconds(child, "Deadline"),
                        operation=_text(child.attribute("Operation")) or None,
                    )
                if kind == "Publisher":
                    latching = child.attribute("Latching")
                    _set(port, latching=None if latching is None else latching in (True, "true", "True"))
                comp.ports.append(port)
                self.by_path[child.path] = port
            elif kind in _SKIPPED_KINDS:
                continue
            else:
                comp.properties.append(self.prop(f"{kind}:{child.name}", self.opaque(child)))
                continue
            for key, value in self.project_attrs(child).items():
                if key not in self._SLOTS.get(kind, ()):
                    comp.properties.append(self.prop(f"{child.name}.{key}", value))
        return comp

    def scheme(self, node: _Node, target: EObject, scheme: Any) -> None:
        if scheme is None or scheme == "":
            return
        if scheme in _SCHEMES:
            target.schedulingScheme = scheme_literal(scheme)
        else:
            self.warn(
                node,
                f"unknown scheduling scheme {scheme!r} (expected {', '.join(_SCHEMES)}); kept as a property",
            )
            target.properties.append(self.prop("SchedulingScheme", scheme))

    # -- systems
    def system(self, node: _Node) -> EObject:
        system = model.new("rosmod.System", name=node.name, sourceFile=os.path.basename(self.filename))
        self.by_path[node.path] = system
        links = []
        for child in self.children(node):
            kind = child.meta_type
            if kind == "Host":
                system.hosts.append(self.host(child))
            elif kind == "Network":
                network = model.new(
                    "rosmod.Network",
                    name=child.name,
                    subnet=_text(child.attribute("Subnet")) or None,
                    netmask=_text(child.attribute("Netmask")) or None,
                )
                system.networks.append(network)
                self.by_path[child.path] = network
            elif kind == "Link":
                links.append(child)
            elif kind == "User":
                system.properties.append(
                    self.prop(
                        f"User:{child.name}",
                        json.dumps(
                            {k: _text(child.attribute(k)) for k in ("Directory", "Key")}, sort_keys=True
                        ),
                    )
                )
            elif kind not in _SKIPPED_KINDS:
                self.unknown(node, child, system.properties)
        for child in links:
            link = model.new("rosmod.Link", name=child.name, ip=_text(child.attribute("IP")) or None)
            src = child.pointer("src")
            dst = child.pointer("dst")
            interface = self.by_path.get(src.path) if src is not None else None
            network = self.by_path.get(dst.path) if dst is not None else None
            if interface is not None and interface.eClass.name == "Interface":
                link.interface = interface
                link.host = interface.eContainer()
            elif src is not None:
                self.warn(
                    child,
                    f"link {child.name!r}: its src {self.where(src)!r} is not an interface of this system",
                )
            if network is not None and network.eClass.name == "Network":
                link.network = network
            elif dst is not None:
                self.warn(
                    child, f"link {child.name!r}: its dst {self.where(dst)!r} is not a network of this system"
                )
            for key, value in self.project_attrs(child).items():
                if key != "IP":
                    self.warn(child, f"link attribute {key!r} = {_text(value)!r} has no rosmod slot; dropped")
            system.links.append(link)
            if link.host is not None and link.host.ipAddress is None and link.ip:
                link.host.ipAddress = link.ip
        return system

    def host(self, node: _Node) -> EObject:
        host = model.new(
            "rosmod.Host",
            name=node.name,
            architecture=_text(node.attribute("Architecture")) or None,
            os=_text(node.attribute("OS")) or None,
            installPath=_text(node.attribute("ROS Install")) or None,
        )
        self.by_path[node.path] = host
        for key, value in self.project_attrs(node).items():
            if key not in ("Architecture", "OS", "ROS Install"):
                host.properties.append(self.prop(key, value))
        users = sorted(node.set_members("Users"), key=lambda u: (u.name, u.path))
        if users:
            first = users[0]
            host.username = first.name
            host.sshKey = _text(first.attribute("Key")) or None
            host.deploymentPath = _text(first.attribute("Directory")) or None
            if len(users) > 1:
                host.properties.append(self.prop("Users", ", ".join(u.name for u in users)))
        for child in self.children(node):
            if child.meta_type == "Interface":
                interface = model.new("rosmod.Interface", name=child.name)
                host.interfaces.append(interface)
                self.by_path[child.path] = interface
            elif child.meta_type not in _SKIPPED_KINDS:
                host.properties.append(self.prop(f"{child.meta_type}:{child.name}", self.opaque(child)))
        return host

    # -- deployments
    def deployment(self, node: _Node) -> EObject:
        deployment = model.new(
            "rosmod.Deployment", name=node.name, sourceFile=os.path.basename(self.filename)
        )
        self.by_path[node.path] = deployment
        for container in self.children(node):
            if container.meta_type != "Container":
                self.unknown(node, container, deployment.properties)
                continue
            deployment.properties.append(
                self.prop(f"Container:{container.name}", self.opaque_attrs(container))
            )
            for child in self.children(container):
                if child.meta_type == "Node":
                    deployment.nodes.append(self.node(child, container))
                elif child.meta_type not in _SKIPPED_KINDS:
                    deployment.properties.append(
                        self.prop(f"{child.meta_type}:{child.name}", self.opaque(child))
                    )
        seen: set[str] = set()
        for item in deployment.nodes:
            if item.name in seen:
                self.warn(node, f"node name {item.name!r} is used twice in deployment {node.name!r}")
            seen.add(item.name)
        return deployment

    def opaque_attrs(self, node: _Node) -> str:
        return json.dumps({k: _text(v) for k, v in self.project_attrs(node).items()}, sort_keys=True)

    def node(self, node: _Node, container: _Node) -> EObject:
        item = model.new(
            "rosmod.Node",
            name=node.name,
            priority=self.integer(node, "Priority"),
            arguments=_text(node.attribute("Arguments")) or None,
        )
        item.properties.append(self.prop("container", container.name))
        for key, value in self.project_attrs(node).items():
            if key not in ("Priority", "Arguments"):
                item.properties.append(self.prop(key, value))
        for child in self.children(node):
            if child.meta_type == "Component":
                item.componentInstances.append(self.instance(child))
            elif child.meta_type not in _SKIPPED_KINDS:
                item.properties.append(self.prop(f"{child.meta_type}:{child.name}", self.opaque(child)))
        return item

    def software_component(self, node: _Node) -> _Node | None:
        for layer in list(node.bases())[1:]:
            if layer.is_meta():
                return None
            if (
                layer.meta_type == "Component"
                and layer.parent is not None
                and layer.parent.meta_type == "Package"
            ):
                return layer
        return None

    def instance(self, node: _Node) -> EObject:
        inst = model.new("rosmod.ComponentInstance", name=node.name)
        definition = self.software_component(node)
        if definition is None:
            self.error(
                node,
                f"component {node.name!r} is not an instance of a software component",
                NameResolutionError,
            )
        else:
            inst.componentRef = f"{definition.parent.name}/{definition.name}"
            self.pending_components.append((inst, definition, node))
        self.scheme(node, inst, node.attribute("SchedulingScheme"))
        for key in self.all_attr_names(node):
            if _is_logging_key(key):
                inst.logging.append(self.prop(key, node.attribute(key)))
        base = node.base
        for key in node.own_attribute_names():
            if key in ("name", "SchedulingScheme") or _is_logging_key(key):
                continue
            value = node.data["atr"][key]
            if base is None or base.attribute(key) != value:
                inst.properties.append(self.prop(key, value))
        self.overrides(node, inst, "")
        return inst

    def overrides(self, node: _Node, inst: EObject, prefix: str) -> None:
        """Values an instance sets on the timers/ports it inherits (and children it adds)."""
        base = node.base
        base_relids = set(base.relids()) if base is not None else set()
        for child in self.children(node):
            label = f"{prefix}{child.name}"
            if child.relid not in base_relids:
                self.warn(
                    child,
                    f"{child.meta_type} {child.name!r} exists only in this instance; kept as a property",
                )
                inst.properties.append(self.prop(f"{child.meta_type}:{label}", self.opaque(child)))
                continue
            child_base = child.base
            for key in child.own_attribute_names():
                value = child.data["atr"][key]
                if child_base is None or child_base.attribute(key) != value:
                    inst.properties.append(self.prop(f"{label}.{key}", value))
            self.overrides(child, inst, f"{label}.")

    # -- cross references
    def finish(self, project: EObject) -> None:
        for inst, definition, node in self.pending_components:
            comp = self.by_path.get(definition.path)
            if comp is None:
                self.error(
                    node,
                    f"component {inst.componentRef!r} is not part of this project's software",
                    NameResolutionError,
                )
            else:
                inst.component = comp
        self.pending_components = []
        systems_of: dict[str, set[str]] = {}
        for _folder, exp in self.experiments:
            dep_node = exp.pointer("Deployment")
            sys_node = exp.pointer("System")
            deployment = self.by_path.get(dep_node.path) if dep_node is not None else None
            system = self.by_path.get(sys_node.path) if sys_node is not None else None
            value = {"System": system.name if system is not None else None}
            value.update({k: _text(v) for k, v in self.project_attrs(exp).items()})
            if deployment is None:
                project.properties.append(
                    self.prop(f"Experiment:{exp.name}", json.dumps(value, sort_keys=True))
                )
                continue
            deployment.properties.append(
                self.prop(f"Experiment:{exp.name}", json.dumps(value, sort_keys=True))
            )
            systems_of.setdefault(deployment.name + "\x00" + dep_node.path, set()).add(
                sys_node.path if system is not None else ""
            )
        for key, paths in systems_of.items():
            dep_path = key.split("\x00", 1)[1]
            deployment = self.by_path[dep_path]
            if len(paths) == 1 and "" not in paths:
                system = self.by_path[next(iter(paths))]
                deployment.system = system
                deployment.systemName = system.name
        self.experiments = []


def _project_nodes(tree: _Tree) -> list[_Node]:
    found: list[_Node] = []
    stack = [tree.root]
    while stack:
        node = stack.pop()
        for child in node.children():
            if child.is_meta():
                continue
            if child.meta_type == "Project":
                found.append(child)
            elif child.meta_type in ("Projects", "") or child.parent is tree.root:
                stack.append(child)
    return sorted(found, key=lambda n: (n.name, n.path))


def project_names(path: str | os.PathLike[str]) -> list[str]:
    """Names of the ROSMOD projects in a ``.webgmex`` archive (sorted)."""
    filename = os.fspath(path)
    tree = _Tree(load_project_json(filename), filename)
    return [n.name for n in _project_nodes(tree)]


def read_webgmex(
    path: str | os.PathLike[str],
    *,
    project: str | None = None,
    warnings: list[Diagnostic] | None = None,
) -> list[EObject]:
    """Read the ROSMOD projects of a ``.webgmex`` archive (all of them, or the one named ``project``).

    Returns one ``rosmod.Project`` per WebGME project, sorted by name. Problems are raised
    together as a :class:`~rosaadl.importers.rosmod_text.RosmodImportError` whose errors name
    the archive and the element path (``AGSE/Software/motor_controller/…``).
    """
    filename = os.fspath(path)
    try:
        tree = _Tree(load_project_json(filename), filename)
        nodes = _project_nodes(tree)
        if project is not None:
            chosen = [n for n in nodes if n.name == project]
            if not chosen:
                known = ", ".join(repr(n.name) for n in nodes) or "none"
                raise NameResolutionError(
                    f"no project {project!r} in the archive (projects: {known})", file=filename
                )
            nodes = chosen
        projects = []
        errors: list[RosaadlError] = []
        for node in nodes:
            mapper = _Mapper(tree, filename, warnings)
            projects.append(mapper.project(node))
            errors.extend(mapper.errors)
    except RosmodImportError:
        raise
    except RosaadlError as exc:
        raise RosmodImportError([exc]) from None
    except RecursionError:
        raise RosmodImportError(
            [ImportFormatError("the project tree is nested too deeply", Location(file=filename))]
        ) from None
    if errors:
        raise RosmodImportError(errors)
    return projects

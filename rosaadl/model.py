"""The model API: a thin typed façade over the pyecore objects of our metamodels.

Code outside ``metamodels/`` uses these helpers instead of pyecore's reflective calls:

* :func:`new` creates an object of a metamodel class, rejecting unknown keyword arguments and
  accepting enumeration values by name or AADL literal (``"thread group"``);
* :func:`children`, :func:`parent`, :func:`walk` navigate containment;
* :func:`qualified_name` / :func:`find_unit` / :func:`find_classifier` work with AADL names
  (``Pkg::Type.impl``, case-insensitive as in AADL);
* :func:`is_a` tests an object against metamodel classes by name (answered once per class);
* :func:`instance_path` / :func:`find_instance` convert between instance objects and their
  dotted paths (``top.sw.cam.publisher``, array elements as ``cam[2]``, one segment:
  :func:`instance_segment`); :func:`component_instances` walks a component instance tree;
* :func:`save` / :func:`load` persist any of our models as XMI (``.xmi``) or JSON (``.json``).
"""

from __future__ import annotations

import contextlib
import functools
import io
import json
import os
import sys
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any

from lxml import etree
from pyecore.ecore import EClass, EEnum, EEnumLiteral, EObject
from pyecore.resources import URI
from pyecore.resources.json import JsonResource
from pyecore.resources.xmi import XMIResource

from rosaadl import metamodels
from rosaadl.arguments import checked, describe, expect_path
from rosaadl.bulk import FastBuilder, stored_value  # FastBuilder re-exported: bulk construction by name
from rosaadl.errors import Location, ModelError, RosaadlError, UsageError, ValidationError
from rosaadl.fileio import JsonLimitError, atomic_write_bytes, loads_bounded

__all__ = [
    "new",
    "FastBuilder",
    "eclass_of",
    "is_a",
    "children",
    "parent",
    "walk",
    "root_of",
    "qualified_name",
    "split_qualified",
    "find_unit",
    "find_classifier",
    "instance_path",
    "instance_segment",
    "component_instances",
    "find_instance",
    "instance_children",
    "save",
    "load",
    "dumps_xmi",
    "loads_xmi",
    "dumps_json",
    "loads_json",
    "model_equal",
    "model_differences",
    "model_depth",
    "MAX_MODEL_DEPTH",
    "EINT_RANGE",
]


# --------------------------------------------------------------------------- construction


def eclass_of(name: str | EClass) -> EClass:
    """The metamodel class for ``"ComponentType"`` / ``"rosmod.Component"`` / an EClass."""
    if isinstance(name, EClass):
        return name
    return metamodels.load().eclass(name)


def _coerce(feature, value: Any) -> Any:
    etype = feature.eType
    if isinstance(etype, EEnum) and isinstance(value, str):
        return etype.from_string(value)
    return value


def new(eclass: str | EClass, /, **values: Any) -> EObject:
    """Create an object of ``eclass`` with feature values; unknown features are an error.

    Many-valued features take any iterable; enumeration features take the literal object, its
    name (``threadGroup``) or its AADL spelling (``thread group``).
    """
    cls = eclass_of(eclass)
    if cls.abstract:
        raise ModelError(f"{cls.name} is abstract; use one of its subclasses")
    obj = cls()
    for key, value in values.items():
        feature = cls.findEStructuralFeature(key)
        if feature is None:
            allowed = ", ".join(sorted(f.name for f in cls.eAllStructuralFeatures()))
            raise ModelError(f"{cls.name} has no feature {key!r} (expected one of: {allowed})")
        if value is None:
            continue
        if feature.many:
            if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
                raise ModelError(f"{cls.name}.{key} is many-valued; expected a list, got {value!r}")
            items = [_coerce(feature, v) for v in value]  # a list: pyecore's EList iterates twice
            if items:
                getattr(obj, key).extend(items)
        else:
            try:
                setattr(obj, key, _coerce(feature, value))
            except RosaadlError:
                raise
            except Exception as exc:  # pyecore BadValueError and friends
                raise ModelError(f"{cls.name}.{key}: {exc}") from None
    return obj


def is_a(obj: object, *eclasses: str | EClass) -> bool:
    """Is ``obj`` an instance of one of the metamodel classes ``eclasses``?

    A class is given as an EClass, by name (``"ComponentInstance"``: a class of that name in any
    of our metamodels, or one of its superclasses) or qualified by its package
    (``"rosmod.ComponentInstance"``). The answer for each object class is computed once.
    """
    if not isinstance(obj, EObject):
        return False
    return _class_is(obj.eClass, eclasses)


@functools.lru_cache(maxsize=4096)
def _class_is(eclass: EClass, wanted: tuple[str | EClass, ...]) -> bool:
    """The answer of :func:`is_a` for one metaclass (immutable metadata, so cached)."""
    kinds = (eclass, *eclass.eAllSuperTypes())
    for item in wanted:
        if isinstance(item, EClass):
            if item in kinds:
                return True
            continue
        package, _, name = item.rpartition(".")
        if name not in _class_names():
            raise ModelError(f"no metamodel class {item!r}")
        if any(k.name == name and (not package or k.ePackage.name == package) for k in kinds):
            return True
    return False


@functools.cache
def _class_names() -> frozenset[str]:
    """The names of every class of our metamodels (to reject a misspelt name in :func:`is_a`)."""
    packages = metamodels.load().packages()
    return frozenset(c.name for p in packages for c in p.eClassifiers if isinstance(c, EClass))


# --------------------------------------------------------------------------- navigation


@functools.cache
def _containments(eclass: EClass) -> tuple[tuple[str, bool], ...]:
    """(name, many) of the containment references of a class, in feature order (metadata only)."""
    # eAllStructuralFeatures, not eAllReferences: the latter is a set, whose order changes from run to run
    return tuple(
        (f.name, bool(f.many)) for f in eclass.eAllStructuralFeatures() if getattr(f, "containment", False)
    )


def children(obj: EObject) -> list[EObject]:
    """Direct contained objects, in feature order then list order (deterministic)."""
    out: list[EObject] = []
    store = obj.__dict__
    for name, many in _containments(obj.eClass):
        holder = store.get(name)  # pyecore keeps each set feature's value holder in the instance dict
        if holder is None:
            continue
        if many:
            out.extend(holder)
        else:
            value = holder._value
            if value is not None:
                out.append(value)
    return out


def parent(obj: EObject) -> EObject | None:
    return obj.eContainer()


def walk(obj: EObject) -> Iterator[EObject]:
    """``obj`` and everything it contains, depth first, in document order."""
    if not isinstance(obj, EObject):
        raise UsageError(f"walk(): obj must be EObject, not {describe(obj)}")
    stack = [obj]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(reversed(children(current)))


def root_of(obj: EObject) -> EObject:
    while obj.eContainer() is not None:
        obj = obj.eContainer()
    return obj


# --------------------------------------------------------------------------- AADL names


def split_qualified(name: str) -> tuple[str | None, str]:
    """``"a::b::T.impl"`` → ``("a::b", "T.impl")``; ``"T"`` → ``(None, "T")``."""
    if "::" in name:
        pkg, _, local = name.rpartition("::")
        return pkg, local
    return None, name


def qualified_name(obj: EObject) -> str:
    """``Pkg::Classifier`` for a classifier, property, type or constant; the name for a unit."""
    owner = obj.eContainer()
    if owner is None or not hasattr(obj, "name"):
        return getattr(obj, "name", "") or ""
    if is_a(owner, "ModelUnit"):
        return f"{owner.name}::{obj.name}"
    return obj.name or ""


def find_unit(model: EObject, name: str) -> EObject | None:
    """The package or property set called ``name`` (case-insensitive) in an ``AadlModel``."""
    wanted = name.lower()
    for unit in model.units:
        if unit.name and unit.name.lower() == wanted:
            return unit
    return None


def find_classifier(model: EObject, name: str, context: EObject | None = None) -> EObject | None:
    """Find ``Pkg::T`` / ``Pkg::T.impl`` (or an unqualified name inside ``context``'s package)."""
    pkg_name, local = split_qualified(name)
    if pkg_name is None:
        unit = context if context is not None and is_a(context, "AadlPackage") else None
        if unit is None and context is not None:
            unit = next((u for u in _ancestors(context) if is_a(u, "AadlPackage")), None)
        if unit is None:
            return None
    else:
        unit = find_unit(model, pkg_name)
        if unit is None or not is_a(unit, "AadlPackage"):
            return None
    wanted = local.lower()
    for classifier in unit.classifiers:
        if classifier.name and classifier.name.lower() == wanted:
            return classifier
    return None


def _ancestors(obj: EObject) -> Iterator[EObject]:
    current = obj
    while current is not None:
        yield current
        current = current.eContainer()


# --------------------------------------------------------------------------- instance paths


def instance_segment(obj: EObject) -> str:
    """An instance object's own segment of its path: its name, with its array index as
    ``cam[2]`` (index 0 or none: the name alone; a multi-dimensional index: ``m[1][2]``)."""
    name = obj.name or ""
    index = getattr(obj, "index", None)
    if index is None:
        return name
    if isinstance(index, int):
        return f"{name}[{index}]" if index > 0 else name
    return name + "".join(f"[{i}]" for i in index)


def instance_children(obj: EObject) -> list[EObject]:
    """Named instance objects directly under ``obj`` (components, features, connections, modes, flows)."""
    out: list[EObject] = []
    for feature in (
        "componentInstances",
        "featureInstances",
        "connectionInstances",
        "modeInstances",
        "modeTransitionInstances",
        "flowSpecifications",
        "endToEndFlows",
    ):
        if obj.eClass.findEStructuralFeature(feature) is not None:
            out.extend(getattr(obj, feature))
    return out


def component_instances(root: EObject, *, include_root: bool = True) -> list[EObject]:
    """``root`` (unless ``include_root`` is false) and every component instance below it,
    depth first, in model order."""
    out: list[EObject] = []
    stack = [root] if include_root else list(reversed(root.componentInstances))
    while stack:
        current = stack.pop()
        out.append(current)
        stack.extend(reversed(current.componentInstances))
    return out


def instance_path(obj: EObject) -> str:
    """``top.sw.cam.publisher`` for an instance object (root name first)."""
    parts = []
    current = obj
    while current is not None and is_a(current, "InstanceObject"):
        parts.append(instance_segment(current))
        current = current.eContainer()
    return ".".join(reversed(parts))


@checked
def find_instance(root: EObject, path: str) -> EObject:
    """The instance object at ``path`` (as made by :func:`instance_path`), or a located error.

    The first segment may name the root or be omitted. Names are matched case-insensitively,
    and connection names that contain dots (``a.b -> c.d``) are matched whole.
    """
    text = path.strip()
    lowered = text.lower()
    root_seg = instance_segment(root).lower()
    if lowered == root_seg:
        return root
    if lowered.startswith(root_seg + "."):
        text = text[len(root_seg) + 1 :]
    current = root
    remaining = text
    while remaining:
        best = None
        for child in instance_children(current):
            seg = instance_segment(child)
            low = seg.lower()
            rem_low = remaining.lower()
            if (rem_low == low or rem_low.startswith(low + ".")) and (
                best is None or len(seg) > len(best[1])
            ):
                best = (child, seg)
        if best is None:
            raise ModelError(
                f"no instance {remaining.split('.')[0]!r} under {instance_path(current)!r}",
                Location(path=path),
            )
        current = best[0]
        remaining = remaining[len(best[1]) + 1 :]
    return current


# --------------------------------------------------------------------------- persistence


#: The deepest containment (objects within objects) rosaadl writes and reads back: room for the
#: deepest instance hierarchy the instantiator makes (1 000 levels) and what its components hold.
#: libxml2's own limit for the XMI (2 048 nested elements) stands above it.
MAX_MODEL_DEPTH = 2_000

#: libxml2's nesting limit in its deep ("huge") mode.
_XML_DEPTH = 2_048

#: Interpreter frames pyecore's JSON and XMI writers, and the JSON reader, use per level.
_FRAMES_PER_LEVEL = 4


def model_depth(root: EObject) -> int:
    """How many objects deep the containment tree of ``root`` is (``root`` alone: 1)."""
    deepest = 0
    stack = [(root, 1)]
    while stack:
        obj, depth = stack.pop()
        deepest = max(deepest, depth)
        stack.extend((child, depth + 1) for child in children(obj))
    return deepest


@contextlib.contextmanager
def _recursion_room(levels: int) -> Iterator[None]:
    """Run pyecore's recursive writers and readers with room for ``levels`` of containment.

    pyecore recurses once per level; the interpreter's limit (1 000 frames) would stop it near
    250 levels. The limit is raised for the duration of the call only, and restored after. It is
    process-wide: loads and saves running at once in several threads may restore it while another
    still needs the room (that one then fails with a located "nested too deeply" error, or
    pyecore's RecursionError on saving); rosaadl itself loads and saves from one thread.
    """
    previous = sys.getrecursionlimit()
    wanted = previous + _FRAMES_PER_LEVEL * levels
    if wanted > previous:
        sys.setrecursionlimit(wanted)
    try:
        yield
    finally:
        sys.setrecursionlimit(previous)


#: EMF's ``EInt`` is a Java ``int``: a value outside this range is refused on reading.
EINT_RANGE = (-(2**31), 2**31 - 1)


def _eint_error(obj: EObject, feature) -> str | None:
    """Why the single-valued ``EInt`` ``feature`` of ``obj`` is outside Java's ``int``, or None."""
    if feature.many or feature.eType.name != "EInt":
        return None
    value = obj.eGet(feature)
    low, high = EINT_RANGE
    if isinstance(value, int) and not low <= value <= high:
        return f"{feature.name} {value} is out of range (an EInt holds {low}..{high})"
    return None


def _eint_errors(obj: EObject) -> Iterator[str]:
    """The messages of the ``EInt`` attributes of ``obj`` outside Java's ``int`` range."""
    for feature in obj.eClass.eAllAttributes():
        message = _eint_error(obj, feature)
        if message:
            yield message


class _HardenedXMIResource(XMIResource):
    """pyecore's XMI reader on a parser with entities, DTDs and network off, with located errors."""

    def __init__(self, uri=None, *, filename: str = "<model>", data: bytes | None = None):
        super().__init__(uri)
        self._filename = filename
        self._data = data

    def load(self, options=None):  # noqa: D102 - same contract as XMIResource.load
        from rosaadl.fileio import parse_xml_bytes

        try:
            tree = parse_xml_bytes(self._data or b"", self._filename, deep=True)
        except RosaadlError as exc:
            message = exc.message
            if "Excessive depth" in message:  # libxml2's advice (XML_PARSE_HUGE) is already taken
                message = f"the XML is nested too deeply (more than {_XML_DEPTH} elements)"
            raise ValidationError(message, exc.location) from None
        # comments and processing instructions carry no model content; pyecore cannot skip them
        etree.strip_tags(tree, etree.Comment, etree.ProcessingInstruction)
        self._tree = tree
        self.options = options or {}
        self.cache_enabled = True
        xmlroot = tree.getroot()
        self.prefixes.update(xmlroot.nsmap)
        self.reverse_nsmap = {v: k for k, v in self.prefixes.items()}
        self.xsitype = f"{{{self.prefixes.get('xsi')}}}type"
        self.xmiid = f"{{{self.prefixes.get('xmi')}}}id"
        self.schema_tag = f"{{{self.prefixes.get('xsi')}}}schemaLocation"
        self.schema_locations = {}
        real_roots = xmlroot if xmlroot.tag == f"{{{self.prefixes.get('xmi')}}}XMI" else [xmlroot]
        for root in real_roots:
            modelroot = self._located(root, self._init_modelroot, root)
            for child in root:
                self._decode_eobject(child, modelroot)
        if self.contents:
            try:
                self._decode_ereferences()
            except RosaadlError:
                raise
            except Exception as exc:
                raise ValidationError(f"a reference does not resolve: {exc}", file=self._filename) from None
        self._clean_registers()

    def _located(self, node, func, *args):
        try:
            return func(*args)
        except ValidationError:
            raise
        except Exception as exc:
            message = exc.message if isinstance(exc, RosaadlError) else str(exc) or exc.__class__.__name__
            raise ValidationError(
                f"element <{etree.QName(node).localname}>: {message}",
                file=self._filename,
                line=node.sourceline,
                path=self._tree.getpath(node),
            ) from None

    def _decode_eobject(self, current_node, parent_eobj):
        """pyecore's decoding of an element and what it holds, in the same (document) order, with
        a stack instead of recursion: the depth of a model is bounded by the parser alone."""
        stack = [(current_node, parent_eobj)]
        while stack:
            node, parent_obj = stack.pop()
            eobject = self._located(node, self._decode_one, node, parent_obj)
            if eobject is not None:
                stack.extend((child, eobject) for child in reversed(node))

    def _decode_one(self, node, parent_eobj):
        """One element (pyecore's ``_decode_eobject`` without its recursion): the object made for
        it, attached to its container, or None when its children are not objects of their own.
        The attributes written as child elements are decoded here, outside ``_decode_node``."""
        feat_container, eobject, eatts, erefs, from_tag = self._decode_node(parent_eobj, node)
        for eattribute, value in eatts:
            self._decode_eattribute_value(eobject, eattribute, value, from_tag)
        if erefs:
            self._later.append((eobject, erefs))
        if not feat_container:
            return None
        if feat_container.many:
            parent_eobj.__getattribute__(feat_container._name).append(eobject)
        else:
            parent_eobj.__setattr__(feat_container._name, eobject)
        return eobject

    def _decode_node(self, parent_eobj, node):
        return self._located(node, super()._decode_node, parent_eobj, node)

    def _decode_attribute(self, owner, key, value, node):
        return self._located(node, super()._decode_attribute, owner, key, value, node)

    @staticmethod
    def _decode_eattribute_value(eobject, eattribute, value, from_tag=False):
        # runs inside _decode_eobject, whose node locates the error
        XMIResource._decode_eattribute_value(eobject, eattribute, value, from_tag)
        message = _eint_error(eobject, eattribute)
        if message:
            raise ModelError(message)


class _MemoryURI(URI):
    """A URI whose output stream is an in-memory buffer (saves go through atomic_write)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.buffer = io.BytesIO()

    def create_outstream(self):
        return self.buffer

    def close_stream(self):
        pass


def _new_uri(name: str) -> URI:
    return _MemoryURI(name)


def _canonical_feature_order(root: EObject) -> None:
    """pyecore writes features in the order they were *set*; put them in metamodel order so that
    the same model always gives the same bytes, however it was built."""
    order_cache: dict[int, dict[object, int]] = {}
    for obj in walk(root):
        isset = obj._isset
        if not isset:
            continue
        eclass = obj.eClass
        order = order_cache.get(id(eclass))
        if order is None:
            order = {f: i for i, f in enumerate(eclass.eAllStructuralFeatures())}
            order_cache[id(eclass)] = order
        ordered = sorted(isset, key=lambda f: order.get(f, len(order)))
        isset.clear()
        store = obj.__dict__
        for feature in ordered:
            # an emptied list stays "set" in pyecore, which then writes its repr ("EOrderedSet()")
            if feature.many and not len(store.get(feature.name, ())):
                continue
            isset[feature] = None


def _writable_depth(root: EObject) -> int:
    depth = model_depth(root)
    if depth > MAX_MODEL_DEPTH:
        raise ModelError(f"the model is {depth} objects deep; rosaadl writes at most {MAX_MODEL_DEPTH}")
    return depth


def dumps_xmi(root: EObject) -> bytes:
    """Serialise a model (its root object) as XMI bytes, deterministically."""
    _canonical_feature_order(root)
    rset = metamodels.new_resource_set()
    resource = XMIResource(_new_uri("model.xmi"))
    rset.resources["model.xmi"] = resource
    resource.resource_set = rset
    previous = root.eResource
    resource.append(root)
    try:
        with _recursion_room(_writable_depth(root)):
            resource.save()
    finally:
        resource.remove(root)
        if previous is not None:
            previous.append(root)
    return resource.uri.buffer.getvalue()


def loads_xmi(data: bytes, filename: str = "<model>") -> EObject:
    rset = metamodels.new_resource_set()
    resource = _HardenedXMIResource(_new_uri(filename), filename=filename, data=data)
    resource.resource_set = rset
    rset.resources[filename] = resource
    with _recursion_room(MAX_MODEL_DEPTH):  # pyecore's eResource climbs the containers
        resource.load()
    return _single_root(resource, filename)


def dumps_json(root: EObject) -> bytes:
    """Serialise a model as JSON bytes (pyecore's JSON layout), deterministically."""
    _canonical_feature_order(root)
    rset = metamodels.new_resource_set()
    resource = JsonResource(_new_uri("model.json"), indent=1)
    resource.resource_set = rset
    previous = root.eResource
    resource.append(root)
    try:
        with _recursion_room(_writable_depth(root)):
            resource.save()
    finally:
        resource.remove(root)
        if previous is not None:
            previous.append(root)
    return resource.uri.buffer.getvalue()


class _LocatedJsonResource(JsonResource):
    def __init__(self, uri, *, filename: str, data: bytes):
        super().__init__(uri)
        self._filename = filename
        self._data = data

    def load(self, options=None):  # noqa: D102
        try:
            text = self._data.decode("utf-8-sig")
            with _recursion_room(MAX_MODEL_DEPTH):
                json_value = loads_bounded(text, allow_nan=False)
                self._decode(json_value, options)
        except JsonLimitError as exc:
            raise ValidationError(str(exc), file=self._filename) from None
        except UnicodeDecodeError as exc:
            raise ValidationError(f"not UTF-8 text (byte {exc.start})", file=self._filename) from None
        except RecursionError:
            raise ValidationError(
                f"the model is nested too deeply (more than {MAX_MODEL_DEPTH} objects)", file=self._filename
            ) from None
        except json.JSONDecodeError as exc:
            raise ValidationError(
                f"malformed JSON: {exc.msg}", file=self._filename, line=exc.lineno, column=exc.colno
            ) from None
        for root in self.contents:
            _resolve_proxies(root, self._filename)
            for obj in walk(root):
                for message in _eint_errors(obj):
                    raise ValidationError(f"{_json_label(obj)}: {message}", file=self._filename)

    def _decode(self, json_value: Any, options) -> None:
        """pyecore's objects from the parsed JSON (its ``load`` after ``json.load``)."""
        self.options = options or {}
        self.cache_enabled = True
        values = json_value if isinstance(json_value, list) else [json_value]
        try:
            for value in values:
                if not isinstance(value, dict) or "eClass" not in value:
                    raise ValidationError("expected a JSON object with an 'eClass' key", file=self._filename)
                self.to_obj(value, first=True)
            for inst, refs in self._load_href.items():
                self.process_inst(inst, refs)
        except (RosaadlError, RecursionError):
            raise
        except Exception as exc:
            raise ValidationError(f"does not conform to the metamodel: {exc}", file=self._filename) from None
        self._load_href.clear()
        self._find_feature.cache_clear()
        self.cache_enabled = False


def _json_label(obj: EObject) -> str:
    """``Field 'x' in Message 'Image'``: where an object is, for errors without a line."""
    parts = []
    while obj is not None:
        name = getattr(obj, "name", None)
        parts.append(f"{obj.eClass.name} {name!r}" if isinstance(name, str) else obj.eClass.name)
        obj = obj.eContainer()
    return " in ".join(parts[:3])


def _resolve_proxies(root: EObject, filename: str) -> None:
    """Replace pyecore's lazy proxies by the objects they name; a dangling one is a located error."""
    from pyecore.ecore import EProxy

    for obj in walk(root):
        for feature in obj.eClass.eAllReferences():
            if feature.containment or feature.transient:
                continue
            value = obj.eGet(feature)
            items = list(value) if feature.many else [value]
            if not any(isinstance(v, EProxy) for v in items):
                continue
            resolved = []
            for item in items:
                if isinstance(item, EProxy):
                    try:
                        item.force_resolve()
                        item = item._wrapped
                    except Exception:
                        raise ValidationError(
                            f"{obj.eClass.name}.{feature.name} refers to an object that does not exist",
                            file=filename,
                        ) from None
                resolved.append(item)
            if feature.many:
                value.clear()
                value.extend(resolved)
            else:
                obj.eSet(feature, resolved[0])


def loads_json(data: bytes, filename: str = "<model>") -> EObject:
    rset = metamodels.new_resource_set()
    resource = _LocatedJsonResource(_new_uri(filename), filename=filename, data=data)
    resource.resource_set = rset
    rset.resources[filename] = resource
    resource.load()
    return _single_root(resource, filename)


def _single_root(resource, filename: str) -> EObject:
    if len(resource.contents) != 1:
        raise ValidationError(
            f"expected exactly one root object, found {len(resource.contents)}", file=filename
        )
    root = resource.contents[0]
    if not isinstance(root, EObject) or root.eClass.ePackage not in metamodels.load().packages():
        raise ValidationError("the root object is not of a rosaadl metamodel", file=filename)
    return root


def _format_of(path: Path, fmt: str | None) -> str:
    if fmt:
        return fmt
    suffix = path.suffix.lower()
    if suffix in (".xmi", ".aadlxmi", ".rosmodxmi", ".trace"):
        return "xmi"
    if suffix == ".json":
        return "json"
    raise ModelError(f"cannot tell the model format of {str(path)!r}: use a .xmi or .json file name")


@checked
def save(root: EObject, path: str | os.PathLike[str], fmt: str | None = None) -> Path:
    """Write a model as XMI or JSON (by extension), atomically."""
    target = Path(path)
    kind = _format_of(target, fmt)
    data = dumps_xmi(root) if kind == "xmi" else dumps_json(root)
    atomic_write_bytes(target, data)
    return target


@checked
def load(path: str | os.PathLike[str], fmt: str | None = None) -> EObject:
    """Read a model written by :func:`save`; errors name the file and line."""
    source = expect_path(path)
    kind = _format_of(source, fmt)
    try:
        data = source.read_bytes()
    except OSError as exc:
        raise ValidationError(f"cannot read the file: {exc.strerror}", file=str(path)) from None
    return loads_xmi(data, str(path)) if kind == "xmi" else loads_json(data, str(path))


# --------------------------------------------------------------------------- comparison


def _value_repr(value: Any) -> Any:
    """An attribute value as a comparable Python value (enum literals by name)."""
    if isinstance(value, EEnumLiteral):
        return value.name
    return value  # numbers (Decimal by value: 0.0 == 0), strings, booleans


_UNSET = object()


def model_differences(a: EObject, b: EObject, *, ignore: Iterable[str] = ("line", "column")) -> list[str]:
    """Structural differences between two models (empty when equal). References compare by path."""
    skip = set(ignore)
    diffs: list[str] = []
    index_a = {id(o): i for i, o in enumerate(walk(a))}
    index_b = {id(o): i for i, o in enumerate(walk(b))}

    def where(obj: EObject) -> str:
        parts = []
        while obj is not None:
            parts.append(f"{obj.eClass.name}({getattr(obj, 'name', '') or ''})")
            obj = obj.eContainer()
        return "/".join(reversed(parts))

    plans: dict[int, list] = {}

    def plan(eclass: EClass) -> list:
        found = plans.get(id(eclass))
        if found is None:
            found = [
                (f, f.name, bool(f.many), f.get_default_value() if not f.many else None)
                for f in eclass.eAllStructuralFeatures()
                if f.name not in skip and not f.transient
            ]
            plans[id(eclass)] = found
        return found

    def value(obj: EObject, name: str, many: bool, default: Any) -> Any:
        held = stored_value(obj, name, _UNSET)  # without the getter, which makes a holder
        if held is _UNSET:
            return () if many else default
        return held

    def compare(x: EObject, y: EObject) -> None:
        if x.eClass is not y.eClass and x.eClass.name != y.eClass.name:
            diffs.append(f"{where(x)}: class {x.eClass.name} != {y.eClass.name}")
            return
        for feature, name, many, default in plan(x.eClass):
            vx, vy = value(x, name, many, default), value(y, name, many, default)
            if feature.is_reference:
                if feature.containment:
                    lx = list(vx) if feature.many else [vx] if vx is not None else []
                    ly = list(vy) if feature.many else [vy] if vy is not None else []
                    if len(lx) != len(ly):
                        diffs.append(f"{where(x)}.{feature.name}: {len(lx)} != {len(ly)} objects")
                        continue
                    for cx, cy in zip(lx, ly, strict=True):
                        compare(cx, cy)
                else:
                    lx = list(vx) if feature.many else [vx]
                    ly = list(vy) if feature.many else [vy]
                    px = [index_a.get(id(o)) if o is not None else None for o in lx]
                    py = [index_b.get(id(o)) if o is not None else None for o in ly]
                    if px != py:
                        diffs.append(f"{where(x)}.{feature.name}: references differ")
            else:
                lx = [_value_repr(v) for v in vx] if feature.many else _value_repr(vx)
                ly = [_value_repr(v) for v in vy] if feature.many else _value_repr(vy)
                if lx != ly:
                    diffs.append(f"{where(x)}.{feature.name}: {lx!r} != {ly!r}")

    compare(a, b)
    return diffs


def model_equal(a: EObject, b: EObject) -> bool:
    return not model_differences(a, b)

"""Transformation traces as ``trace.ecore`` models.

A trace records, per rule application, the source objects and the target objects. Objects are
identified by a *stable key*: the chain of containment features and names from the model root
(``/units[nd_usb_cam]/classifiers[usb_cam_nd.impl]``), which survives edits that reorder or
insert siblings, unlike positional XMI fragments. A trace is saved and read back like any model
(:func:`rosaadl.model.save` / :func:`rosaadl.model.load`); :class:`TraceIndex` answers "what did
this source become" and "where did this target come from" from a live or a reloaded trace.
A rule's targets are usually made before they have a container: :func:`key_targets` keys them
again once the target model is complete (:class:`KeyCache` computes each container's key once).
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.bulk import FastBuilder
from rosaadl.errors import ModelError

__all__ = [
    "element_key",
    "KeyCache",
    "find_by_key",
    "new_trace",
    "add_link",
    "key_targets",
    "TraceIndex",
    "save_trace",
    "load_trace",
]


def _step(obj: EObject) -> str:
    feature = obj.eContainmentFeature()
    container = obj.eContainer()
    name = getattr(obj, "name", None) if obj.eClass.findEStructuralFeature("name") is not None else None
    if name:
        return f"{feature.name}[{name}]"
    if feature.many:
        return f"{feature.name}.{container.eGet(feature).index(obj)}"
    return feature.name


def element_key(obj: EObject) -> str:
    """The stable key of ``obj`` inside its model: containment features and names from the root."""
    steps = []
    current = obj
    while current.eContainer() is not None:
        steps.append(_step(current))
        current = current.eContainer()
    return "/" + "/".join(reversed(steps))


class KeyCache:
    """:func:`element_key` for many objects of one model, each container's key computed once."""

    def __init__(self) -> None:
        self._keys: dict[int, str] = {}

    def key(self, obj: EObject) -> str:
        found = self._keys.get(id(obj))
        if found is None:
            container = obj.eContainer()
            found = "/" if container is None else f"{self.key(container).rstrip('/')}/{_step(obj)}"
            self._keys[id(obj)] = found
        return found


def find_by_key(root: EObject, key: str) -> EObject | None:
    """The object with :func:`element_key` ``key`` under ``root`` (None when it is gone)."""
    if key in ("", "/"):
        return root
    current = root
    for step in key.strip("/").split("/"):
        if "[" in step and step.endswith("]"):
            feature_name, _, name = step[:-1].partition("[")
            feature = current.eClass.findEStructuralFeature(feature_name)
            if feature is None:
                return None
            values = current.eGet(feature) if feature.many else [current.eGet(feature)]
            current = next((v for v in values if v is not None and getattr(v, "name", None) == name), None)
        elif "." in step:
            feature_name, _, index = step.partition(".")
            feature = current.eClass.findEStructuralFeature(feature_name)
            if feature is None or not feature.many:
                return None
            if not index.isdigit():
                return None
            values = current.eGet(feature)
            position = int(index)
            current = values[position] if position < len(values) else None
        else:
            feature = current.eClass.findEStructuralFeature(step)
            current = current.eGet(feature) if feature is not None else None
        if current is None:
            return None
    return current


def _end(obj: EObject, builder: FastBuilder) -> EObject:
    return builder.make(
        "trace.TraceElement",
        uri="",
        path=element_key(obj),
        className=obj.eClass.name,
        object=obj,
    )


def new_trace(transformation: str) -> EObject:
    return model.new("trace.Trace", transformation=transformation)


def add_link(
    trace: EObject,
    rule: str,
    sources: Iterable[EObject],
    targets: Iterable[EObject],
    *,
    builder: FastBuilder | None = None,
) -> EObject:
    """Record one rule application, each end keyed where its object is now (see
    :func:`key_targets`); pass the run's ``builder`` when adding many links."""
    builder = builder or FastBuilder()
    link = builder.make("trace.TraceLink", rule=rule)
    ends = [_end(s, builder) for s in sources]
    if ends:
        builder.add(link, "sources", *ends)
    ends = [_end(t, builder) for t in targets]
    if ends:
        builder.add(link, "targets", *ends)
    builder.add(trace, "links", link)
    return link


def key_targets(trace: EObject) -> None:
    """Key every target end again where its object is now: the targets of a transformation get
    their containers after their link was recorded."""
    keys = KeyCache()
    for link in trace.links:
        for end in link.targets:
            end.path = keys.key(end.object)


class TraceIndex:
    """Look-ups over a trace: by source key and by target key (live objects when available)."""

    def __init__(self, trace: EObject) -> None:
        self.trace = trace
        self._by_source: dict[str, list[EObject]] = {}
        self._by_target: dict[str, list[EObject]] = {}
        for link in trace.links:
            for end in link.sources:
                self._by_source.setdefault(end.path, []).append(link)
            for end in link.targets:
                self._by_target.setdefault(end.path, []).append(link)

    def links_from(self, source: EObject | str) -> list[EObject]:
        key = source if isinstance(source, str) else element_key(source)
        return list(self._by_source.get(key, []))

    def links_to(self, target: EObject | str) -> list[EObject]:
        key = target if isinstance(target, str) else element_key(target)
        return list(self._by_target.get(key, []))

    def origin_keys(self, target: EObject | str) -> list[str]:
        """Keys of the source objects a target was made from (for name/identity reuse)."""
        return [end.path for link in self.links_to(target) for end in link.sources]

    def rules(self) -> list[str]:
        return sorted({link.rule for link in self.trace.links})


def save_trace(trace: EObject, path: str | Path) -> Path:
    return model.save(trace, path, fmt="json" if str(path).endswith(".json") else "xmi")


def load_trace(path: str | Path) -> EObject:
    loaded = model.load(path, fmt="json" if str(path).endswith(".json") else "xmi")
    if not model.is_a(loaded, "trace.Trace"):
        raise ModelError(f"{path}: expected a trace model, found a {loaded.eClass.name}")
    return loaded

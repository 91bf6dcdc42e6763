"""Transformation traces as ``trace.ecore`` models.

A trace records, per rule application, the source objects and the target objects. Objects are
identified by a *stable key*: the chain of containment features and names from the model root
(``/units[nd_usb_cam]/classifiers[usb_cam_nd.impl]``), which survives edits that reorder or
insert siblings, unlike positional XMI fragments. A trace is saved and read back like any model
(:func:`rosaadl.model.save` / :func:`rosaadl.model.load`); :class:`TraceIndex` answers "what did
this source become" and "where did this target come from" from a live or a reloaded trace.
A rule's targets are usually made before they have a container: :func:`key_targets` keys them
again once the target model is complete. The keys are those of :mod:`rosaadl.element_keys`.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.bulk import FastBuilder
from rosaadl.element_keys import element_key, find_by_key  # re-exported: the keys a trace holds
from rosaadl.errors import ModelError

__all__ = [
    "element_key",
    "find_by_key",
    "new_trace",
    "add_link",
    "key_targets",
    "TraceIndex",
    "save_trace",
    "load_trace",
]


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
    keys: dict[int, str] = {}
    for link in trace.links:
        for end in link.targets:
            end.path = element_key(end.object, keys)


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

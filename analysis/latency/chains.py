"""Flows derived from topic chains: chains of threads over port connections.

A ROS model rarely declares end-to-end flows; its topics are port connections between the
threads of its nodes. A chain of threads ``t0 -> t1 -> ... -> tn`` becomes the flow
``t0, c01, t1, c12, ..., tn`` (each connection the port connection from one thread to the
next), which the flow latency analysis walks like any end-to-end flow.
"""

from __future__ import annotations

from typing import Any

from rosaadl.analysis.instance_values import SystemMode, category_of, instance_root, system_modes
from rosaadl.errors import Diagnostic, Location
from rosaadl.model import component_instances, instance_path

__all__ = ["thread_chains", "chain_elements", "thread_links", "thread_of"]


def thread_of(end: Any) -> Any | None:
    """The thread a connection end belongs to (None when it is not inside a thread)."""
    current = end
    while current is not None:
        if hasattr(current, "componentInstances") and category_of(current) == "thread":
            return current
        if hasattr(current, "componentInstances") and current is not end:
            return None
        current = current.eContainer()
    return None


def thread_links(root: Any, mode: SystemMode) -> list[tuple[Any, Any, Any]]:
    """(source thread, connection, destination thread) of every port connection between threads."""
    links = []
    for ci in component_instances(root):
        for conn in ci.connectionInstances:
            kind = getattr(getattr(conn, "kind", None), "name", "")
            if kind not in ("portConnection", "") or not mode.active(conn):
                continue
            src, dst = thread_of(conn.source), thread_of(conn.destination)
            if src is not None and dst is not None and src is not dst:
                links.append((src, conn, dst))
    return links


def thread_chains(source: Any, limit: int = 100) -> list[list[Any]]:
    """Every maximal path of threads over port connections (from threads nothing feeds to threads
    that feed nothing; cycles are cut), in model order, at most ``limit`` of them."""
    root = instance_root(source)
    links = thread_links(root, system_modes(root)[0])
    successors: dict[int, list[Any]] = {}
    has_input: set[int] = set()
    threads: set[int] = set()
    for src, _conn, dst in links:
        targets = successors.setdefault(id(src), [])
        if all(t is not dst for t in targets):
            targets.append(dst)
        has_input.add(id(dst))
        threads.update((id(src), id(dst)))
    order = [ci for ci in component_instances(root) if id(ci) in threads]
    chains: list[list[Any]] = []

    def extend(path: list[Any]) -> None:
        if len(chains) >= limit:
            return
        nexts = [t for t in successors.get(id(path[-1]), []) if all(t is not p for p in path)]
        if not nexts:
            if len(path) > 1:
                chains.append(list(path))
            return
        for nxt in nexts:
            path.append(nxt)
            extend(path)
            path.pop()

    starts = [t for t in order if id(t) not in has_input] or order[:1]
    for start in starts:
        extend([start])
    return chains


def chain_elements(root: Any, threads: list[Any], diagnostics: list[Diagnostic]) -> list[Any]:
    """The flow elements of a chain of threads: each thread, then the port connection to the
    next one (a missing connection is a warning, and the hop has no connection row)."""
    links = thread_links(root, system_modes(root)[0])
    elements: list[Any] = [threads[0]]
    for src, dst in zip(threads, threads[1:], strict=False):
        conn = next((c for a, c, b in links if a is src and b is dst), None)
        if conn is None:
            diagnostics.append(
                Diagnostic(
                    "warning",
                    f"no port connection from {instance_path(src)} to {instance_path(dst)}; "
                    "the hop is counted without transmission",
                    Location(path=instance_path(dst)),
                )
            )
        else:
            elements.append(conn)
        elements.append(dst)
    return elements

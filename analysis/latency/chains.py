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

__all__ = ["thread_chains", "chain_elements", "refine_by_threads", "thread_links", "thread_of"]


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


def refine_by_threads(root: Any, elements: list[Any], reader: Any) -> tuple[list[Any], bool]:
    """A flow whose elements are flow specifications of node processes without a flow
    implementation, refined by the threads its connections reach (rosaadl's rule for ROS models,
    whose topics are port connections between the threads of the nodes): such a flow
    specification, when it has no ``Latency`` of its own, becomes the thread its incoming
    connection ends in, then the thread its outgoing connection starts from (with the port
    connection between the two when there is one). OSATE would count such a process as adding no
    latency. Whether anything was refined comes second."""
    from rosaadl.analysis.latency.contributors import component_of, is_connection

    links = thread_links(root, system_modes(root)[0])
    out: list[Any] = []
    refined = False
    for index, element in enumerate(elements):
        component = (
            None
            if is_connection(element) or hasattr(element, "componentInstances")
            else component_of(element)
        )
        if component is None or category_of(component) in ("thread", "device", "abstract"):
            out.append(element)
            continue
        if reader.value(element, "Communication_Properties::Latency") is not None:
            out.append(element)
            continue
        before = elements[index - 1] if index > 0 and is_connection(elements[index - 1]) else None
        after = (
            elements[index + 1] if index + 1 < len(elements) and is_connection(elements[index + 1]) else None
        )
        inner = [
            t
            for t in (
                thread_of(before.destination) if before else None,
                thread_of(after.source) if after else None,
            )
            if t is not None and _inside(t, component)
        ]
        if not inner:
            out.append(element)
            continue
        refined = True
        out.append(inner[0])
        if len(inner) == 2 and inner[1] is not inner[0]:
            conn = next((c for a, c, b in links if a is inner[0] and b is inner[1]), None)
            if conn is not None:
                out.append(conn)
            out.append(inner[1])
    return out, refined


def _inside(obj: Any, container: Any) -> bool:
    current = obj
    while current is not None:
        if current is container:
            return True
        current = current.eContainer()
    return False

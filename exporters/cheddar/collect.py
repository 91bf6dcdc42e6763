"""Reading a system instance into the intermediate Cheddar system.

The steps run in the order that lets each one find what it refers to: processors (and SoCs)
first, then networks, address spaces, tasks (in their Cheddar section order when imported),
resources, buffers and messages, the dependencies imported from Cheddar, and last the port
connections between threads. What the file had beyond its entities (the order of its sections,
sections kept verbatim) comes from the root's ``Cheddar_Properties``.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.exporters.cheddar import hardware, software
from rosaadl.exporters.cheddar.communication import port_connection
from rosaadl.exporters.cheddar.context import ExportContext, category_of
from rosaadl.exporters.cheddar.system import Collection
from rosaadl.importers.cheddar.vocabulary import CP

__all__ = ["collect"]


def collect(ctx: ExportContext) -> Collection:
    """The Cheddar entities of ``ctx.root``; problems are collected in ``ctx``."""
    c = Collection(ctx)
    props = ctx.props(ctx.root)
    order = props.get(CP + "Section_Order")
    if isinstance(order, list):
        c.system.section_order = [str(s).lower() for s in order]
    kept = props.get(CP + "Unmodelled_Elements")
    if isinstance(kept, list):
        for item in kept:
            if (
                isinstance(item, dict)
                and isinstance(item.get("Section"), str)
                and isinstance(item.get("Xml"), str)
            ):
                c.system.kept.append((item["Section"].lower(), item["Xml"]))
    by_category: dict[str | None, list[EObject]] = {}
    for obj in ctx.everything:
        by_category.setdefault(category_of(obj), []).append(obj)
    socs = c.soc_ids = hardware.find_socs(c)
    for obj in ctx.everything:
        if id(obj) in socs or hardware.is_top_processor(c, obj):
            hardware.processor(c, obj)
    for obj in by_category.get("bus", []):
        hardware.network(c, obj)
    for obj in by_category.get("process", []):
        software.space(c, obj)
    for thread in _by_section_index(ctx, by_category.get("thread", [])):
        software.task(c, thread)
    for data in _by_section_index(ctx, by_category.get("data", [])):
        software.data_component(c, data)
    imported = [o for o in ctx.connections if ctx.props(o).has(CP + "Dependency_Type")]
    for connection in _by_section_index(ctx, imported):
        software.imported_dependency(c, connection)
    for connection in ctx.connections:
        if (
            not ctx.props(connection).has(CP + "Dependency_Type")
            and connection.kind is not None
            and connection.kind.name == "portConnection"
        ):
            port_connection(c, connection)
    return c


def _by_section_index(ctx: ExportContext, objects: list[EObject]) -> list[EObject]:
    """``objects`` in their Cheddar section order (``Section_Index``), the others after them."""

    def key(obj: EObject) -> tuple[int, int, int]:
        index = ctx.props(obj).get(CP + "Section_Index")
        if isinstance(index, int) and not isinstance(index, bool):
            return (0, index, ctx.order[id(obj)])
        return (1, 0, ctx.order[id(obj)])

    return sorted(objects, key=key)

"""The hardware of the instance as Cheddar processors, cores and networks, and where each
component runs.

Top-level ``processor`` instances are processors; one with ``processor`` subcomponents is a
multi-core processor whose core units are its innermost processors; a ``system`` holding only
processors (at least two, possibly in processor-only clusters) and memories is a multi-core SoC
(as the component library models boards). Buses are networks. :func:`binding_target` follows
``Actual_Processor_Binding`` up the containers and through virtual processors, and
:func:`cpu_names` names the processor and core a binding lands on.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.exporters.cheddar.context import category_of
from rosaadl.exporters.cheddar.system import Collection, Core, Network, Processor
from rosaadl.importers.cheddar.vocabulary import BINDING, CP
from rosaadl.properties import Reference

__all__ = ["find_socs", "in_soc", "processor", "network", "binding_target", "cpu_names"]


def find_socs(c: Collection) -> set[int]:
    """Systems that are multi-core SoCs: below them only processors (at least two), in
    processor-only subsystems (clusters) or not, and memories. The outermost one counts."""
    memo: dict[int, tuple[bool, int]] = {}

    def shape(obj: EObject) -> tuple[bool, int]:
        found = memo.get(id(obj))
        if found is not None:
            return found
        only, count = True, 0
        for child in obj.componentInstances:
            category = child.category.name if child.category is not None else ""
            if category == "processor":
                count += 1
            elif category == "system":
                inner_only, inner_count = shape(child)
                only = only and inner_only
                count += inner_count
            elif category != "memory":
                only = False
        memo[id(obj)] = (only, count)
        return only, count

    chosen: set[int] = set()
    for obj in c.ctx.everything:
        if obj is c.ctx.root or category_of(obj) != "system" or c.ctx.imported(obj):
            continue
        only, count = shape(obj)
        if only and count >= 2 and not in_soc(obj, chosen):
            chosen.add(id(obj))
    return chosen


def in_soc(obj: EObject, socs: set[int]) -> bool:
    """Is ``obj`` inside one of the SoC systems ``socs``?"""
    current = obj.eContainer()
    while current is not None:
        if id(current) in socs:
            return True
        current = current.eContainer()
    return False


def is_top_processor(c: Collection, obj: EObject) -> bool:
    """A processor instance that is a Cheddar processor: not inside a processor or an SoC."""
    if category_of(obj) != "processor" or in_soc(obj, c.soc_ids):
        return False
    current = obj.eContainer()
    while current is not None and model.is_a(current, "ComponentInstance"):
        if current.category is not None and current.category.name == "processor":
            return False
        current = current.eContainer()
    return True


def processor(c: Collection, obj: EObject) -> None:
    """A processor (or SoC) and its cores; every processor inside it runs on it."""
    ctx = c.ctx
    cores = _leaf_processors(obj)
    entity = Processor(ctx.name(obj), ctx.ident(obj), obj, ctx.imported(obj), multi=bool(cores))
    if cores:
        for core in cores:
            made = Core(ctx.name(core), ctx.ident(core), core, ctx.imported(core))
            entity.cores.append(made)
            c.cpu_of_processor[id(core)] = (entity, made)
        for middle in model.component_instances(obj, include_root=False):
            if id(middle) not in c.cpu_of_processor and category_of(middle) in (
                "processor",
                "virtual processor",
                "system",
            ):
                c.cpu_of_processor[id(middle)] = (entity, None)
    else:
        core_name = ctx.props(obj).get(CP + "Core_Name")
        if isinstance(core_name, str):
            entity.cores.append(Core(core_name, ctx.ident(obj, CP + "Core_Id"), obj, True))
        else:
            entity.cores.append(Core(f"core_unit_{entity.name}", None, obj, False))
        for inner in model.component_instances(obj, include_root=False):
            if category_of(inner) == "virtual processor":
                c.cpu_of_processor[id(inner)] = (entity, None)
    c.cpu_of_processor[id(obj)] = (entity, None)
    c.system.processors.append(entity)


def _leaf_processors(obj: EObject) -> list[EObject]:
    """The cores of a processor or SoC system: its innermost processors, in order."""
    found = []
    for child in obj.componentInstances:
        if child.category is None:
            continue
        if child.category.name == "processor" or (
            child.category.name == "system" and obj.category.name == "system"
        ):
            inner = _leaf_processors(child)
            found.extend(inner if inner or child.category.name == "system" else [child])
    return found


def network(c: Collection, obj: EObject) -> None:
    """A bus as a network (its Cheddar kind from ``Network_Kind``, else a generic network)."""
    ctx = c.ctx
    kind = ctx.props(obj).get(CP + "Network_Kind")
    tag = str(kind).lower() if kind is not None else "generic_network"
    c.system.networks.append(Network(ctx.name(obj), ctx.ident(obj), obj, ctx.imported(obj), tag))


def binding_target(c: Collection, obj: EObject) -> EObject | str | None:
    """The processor (or core) ``obj`` is bound to, following containers and virtual processors."""
    current = obj
    seen = 0
    while current is not None and model.is_a(current, "ComponentInstance"):
        value = c.ctx.props(current).get(BINDING)
        if value is not None:
            target = value[0] if isinstance(value, list) and value else value
            if isinstance(target, Reference):
                return target.path
            if isinstance(target, EObject):
                if id(target) in c.cpu_of_processor:
                    return target
                if target.category is not None and target.category.name == "virtual processor" and seen < 16:
                    seen += 1
                    current = target
                    continue
                return target
            return None
        current = current.eContainer()
    return None


def cpu_names(c: Collection, target: EObject | str | None) -> tuple[str | None, str | None]:
    """(cpu_name, core_name) of a binding target."""
    if target is None:
        return None, None
    if isinstance(target, str):
        return target, None
    found = c.cpu_of_processor.get(id(target))
    if found is None:
        # bound inside a virtual processor's container chain: find the processor around it
        current = target.eContainer()
        while current is not None and id(current) not in c.cpu_of_processor:
            current = current.eContainer()
        if current is None:
            return None, None
        found = c.cpu_of_processor[id(current)]
    processor_entity, core = found
    return processor_entity.name, core.name if core is not None else None

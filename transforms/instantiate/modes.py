"""Modes: mode instances, mode transition instances, system operation modes, modal connections.

Each component gets the mode instances of its classifier and the transitions between them
(triggered by port instances). The system operation modes are the combinations of the modes of
all modal components that can be current together (a modal subcomponent counts only in the
modes of its parent it exists in), as OSATE enumerates them; a connection instance exists in the
system operation modes in which all its hops and ends are active (:func:`connection_modes`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl.resolution import split_path

from .mirrors import ComponentMirror, ConnectionRecord, FeatureMirror

if TYPE_CHECKING:
    from .connection_instances import ConnectionInfo
    from .instantiator import Instantiator

__all__ = [
    "MAX_SYSTEM_OPERATION_MODES",
    "connection_modes",
    "mode_instances",
    "mode_transitions",
    "system_operation_modes",
]

#: OSATE's default limit on the number of system operation modes.
MAX_SYSTEM_OPERATION_MODES = 1000


def mode_instances(st: Instantiator, ci: ComponentMirror) -> None:
    """The mode instances of a component's classifier."""
    factory = st.factory
    for mode in st.resolver.modes(ci.node.classifier):
        mi = factory.new("ModeInstance", name=mode.name, mode=mode.name, initial=bool(mode.initial))
        ci.modes[(mode.name or "").lower()] = mi
        ci.mode_list.append(mi)
    factory.extend(ci.obj, "modeInstances", ci.mode_list)


def mode_transitions(st: Instantiator, ci: ComponentMirror) -> None:
    """The mode transition instances of a component (after its features and subcomponents,
    whose ports trigger them)."""
    transitions = st.resolver.mode_transitions(ci.node.classifier)
    for transition in transitions:
        _mode_transition(st, ci, transition)
    if transitions:
        st.factory.extend(ci.obj, "modeTransitionInstances", [mti for mti, _ in ci.transitions])


def _mode_transition(st: Instantiator, ci: ComponentMirror, transition: EObject) -> None:
    src = ci.modes.get((transition.source or "").lower())
    dst = ci.modes.get((transition.destination or "").lower())
    name = transition.name
    triggers = list(transition.triggers)
    if not name:
        event = ""
        if triggers:
            segments = split_path(triggers[0])
            event = "_".join(s.name for s in segments)
        name = f"{transition.source}_{event + '_' if event else ''}{transition.destination}"
    factory = st.factory
    mti = factory.new("ModeTransitionInstance", name=name, source=src, destination=dst)
    for trigger in triggers:
        segments = split_path(trigger)
        port: FeatureMirror | None = None
        if len(segments) == 1:
            port = ci.feature(segments[0].key)
        elif len(segments) == 2:
            child = ci.child(segments[0].key)
            if child is not None:
                port = child.feature(segments[1].key)
            else:
                group = ci.feature(segments[0].key)
                port = group.child(segments[1].key) if group is not None else None
        if port is not None:
            factory.extend(mti, "triggers", [port.obj])
    ci.transitions.append((mti, transition))


def system_operation_modes(st: Instantiator) -> None:
    """The system operation modes of the system instance (``No Modes`` when nothing is modal)."""
    root = st.root
    modal = [ci for ci in st.components if ci.mode_list]
    system = root.obj
    factory = st.factory
    if not modal:
        som = factory.new("SystemOperationMode", name="No Modes")
        factory.extend(system, "systemOperationModes", [som])
        st.soms = [(som, frozenset())]
        return
    combos: list[list[EObject]] = []

    def active(ci: ComponentMirror, chosen: dict[int, EObject]) -> bool:
        current: ComponentMirror | None = ci
        while current is not None and current.parent is not None:
            if current.in_modes:
                mode = chosen.get(id(current.parent))
                if mode is None or not any(mode is m for m in current.in_modes):
                    return False
            current = current.parent
        return True

    def walk(i: int, chosen: dict[int, EObject], current: list[EObject]) -> None:
        if len(combos) >= MAX_SYSTEM_OPERATION_MODES:
            return
        if i == len(modal):
            combos.append(list(current))
            return
        ci = modal[i]
        if not active(ci, chosen):
            walk(i + 1, chosen, current)
            return
        for mi in ci.mode_list:
            chosen[id(ci)] = mi
            current.append(mi)
            walk(i + 1, chosen, current)
            current.pop()
            del chosen[id(ci)]

    walk(0, {}, [])
    if len(combos) >= MAX_SYSTEM_OPERATION_MODES:
        st.warn(f"system operation modes limited to {MAX_SYSTEM_OPERATION_MODES}", system.name)
    for number, combo in enumerate(combos):
        som = factory.new("SystemOperationMode", name=f"som_{number}")
        factory.extend(som, "currentModes", combo)
        factory.extend(system, "systemOperationModes", [som])
        st.soms.append((som, frozenset(id(m) for m in combo)))


def _component_active(ci: ComponentMirror, som_modes: frozenset[int]) -> bool:
    """Does ``ci`` exist in the system operation mode of mode instances ``som_modes``?"""
    current: ComponentMirror | None = ci
    while current is not None:
        if current.in_modes and not any(id(m) in som_modes for m in current.in_modes):
            return False
        current = current.parent
    return True


def _end_active(end: Any, som_modes: frozenset[int]) -> bool:
    if isinstance(end, FeatureMirror):
        return _component_active(end.owner, som_modes)
    if isinstance(end, ComponentMirror):
        return _component_active(end, som_modes)
    return True


def connection_modes(st: Instantiator, record: ConnectionRecord, info: ConnectionInfo) -> bool:
    """OSATE's fillInModes: the system operation modes in which a modal connection exists.
    Returns False when the connection exists in none (it is then not created)."""
    refs = list(zip(info.connections, info.contexts, strict=False))

    def modes_of(index: int) -> list[EObject] | None:
        conn, ci = refs[index]
        if conn.modes:
            return [ci.modes[m] for m in conn.modes if m in ci.modes]
        current: ComponentMirror | None = ci
        while current is not None and current.parent is not None:
            if current.in_modes:
                return list(current.in_modes)
            current = current.parent
        return None

    start = None
    first_modes = None
    for index in range(len(refs)):
        first_modes = modes_of(index)
        if first_modes is not None:
            start = index
            break
    if start is None:
        return True
    selected: list[EObject] = []

    def generate(index: int, chosen: list[EObject]) -> None:
        if index == len(refs):
            wanted = {id(m) for m in chosen}
            for som, current in st.soms:
                if not wanted <= current:
                    continue
                if any(som is s for s in selected):
                    continue
                if not _end_active(info.src, current) or not _end_active(record.dst, current):
                    continue
                if not all(_component_active(ctx, current) for _, ctx in refs):
                    continue
                selected.append(som)
            return
        next_modes = modes_of(index)
        if next_modes is not None:
            for mi in next_modes:
                chosen.append(mi)
                generate(index + 1, chosen)
                chosen.pop()
        else:
            generate(index + 1, chosen)

    for mi in first_modes or []:
        generate(start + 1, [mi])
    if not selected:
        return False
    order = {id(som): i for i, (som, _) in enumerate(st.soms)}
    selected.sort(key=lambda s: order[id(s)])
    st.factory.extend(record.obj, "inSystemOperationModes", [s.name for s in selected])
    return True

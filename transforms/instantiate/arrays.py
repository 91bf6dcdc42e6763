"""Component and feature arrays: the sizes of their dimensions, and the connections between elements.

Connection instances are first made between first array elements only (as OSATE does);
:func:`expand_arrays` then replicates them to the other elements: across arrays following
``Connection_Pattern`` (default: one to one for arrays of equal size, else all to all), and into
the other elements of arrays whose first element holds connections.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from pyecore.ecore import EObject

from rosaadl import model as _model

from .connection_instances import attach, connection_name, remove_connection
from .mirrors import ComponentMirror, ConnectionRecord, FeatureMirror

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["array_sizes", "expand_arrays"]

_Move = Callable[[ComponentMirror | None], ComponentMirror | None]
_Mirror = Callable[[EObject], Any]


def array_sizes(st: Instantiator, dims: Iterable[str], element: EObject, path: Any) -> list[int]:
    """The size of each array dimension of ``element``: a number or an integer property constant
    (0, and an error, for anything else; 1, and a warning, for ``[]``)."""
    sizes = []
    for dim in dims:
        text = "".join((dim or "").split())
        if not text:
            st.warn("array dimension without a size; one element instantiated", path, element)
            sizes.append(1)
            continue
        if text.isdecimal():
            sizes.append(int(text))
            continue
        const = st.resolver.constant(text, element)
        value = None
        if const is not None and _model.is_a(const.value, "IntegerValue"):
            value = const.value.value
        if value is None:
            st.error(f"array size {text} is not an integer or an integer property constant", path, element)
            sizes.append(0)
        else:
            sizes.append(int(value))
    return sizes


def expand_arrays(st: Instantiator) -> None:
    """Replicate the connection instances made between first array elements to the other elements."""
    order = st.components
    if not any(ci.index for ci in order):
        return
    index: dict[int, Any] = {}

    def mirror(obj: EObject) -> Any:
        """The component or feature mirror of an instance object (the index made on first use)."""
        if not index:
            index.update(_mirror_index(order))
        return index.get(id(obj))

    for container in order:
        if _first_elements_only(container):
            for record in list(container.connections):
                _replicate(st, container, record, mirror)
    for container in order:
        if _first_elements_only(container):
            continue
        twin = _twin(st.root, container)
        if twin is None or twin is container:
            continue
        depth = len(_lineage(twin))

        def move(
            ci: ComponentMirror | None,
            twin: ComponentMirror = twin,
            container: ComponentMirror = container,
            depth: int = depth,
        ) -> ComponentMirror | None:
            return _rebase(ci, twin, container, depth)

        for record in list(twin.connections):
            _add_replica(st, container, record, move, move, mirror)


def _first_elements_only(ci: ComponentMirror) -> bool:
    current: ComponentMirror | None = ci
    while current is not None:
        if any(i > 1 for i in current.index):
            return False
        current = current.parent
    return True


def _lineage(ci: ComponentMirror) -> list[ComponentMirror]:
    """The components from the root down to ``ci``."""
    chain = []
    current: ComponentMirror | None = ci
    while current is not None:
        chain.append(current)
        current = current.parent
    return list(reversed(chain))


def _twin(root: ComponentMirror, ci: ComponentMirror) -> ComponentMirror | None:
    """The component at the same place as ``ci`` with every array index set to 1."""
    current = root
    for step in _lineage(ci)[1:]:
        ones = tuple(1 for _ in step.index)
        current = next((c for c in current.by_sub.get(step.sub_key, []) if c.index == ones), None)
        if current is None:
            return None
    return current


def _rebase(
    ci: ComponentMirror | None, twin: ComponentMirror, container: ComponentMirror, depth: int
) -> ComponentMirror | None:
    """The component under ``container`` at the place ``ci`` has under ``twin``."""
    if ci is None:
        return None
    chain = _lineage(ci)
    if len(chain) < depth or chain[depth - 1] is not twin:
        return ci
    current = container
    for step in chain[depth:]:
        current = next((c for c in current.by_sub.get(step.sub_key, []) if c.index == step.index), None)
        if current is None:
            return None
    return current


def _array_steps(container: ComponentMirror, end: Any) -> list[ComponentMirror]:
    """Array components on the path from ``container`` (exclusive) down to ``end``."""
    ci = end.owner if isinstance(end, FeatureMirror) else end
    steps = []
    while ci is not None and ci is not container:
        if ci.index:
            steps.append(ci)
        ci = ci.parent
    return list(reversed(steps))


def _replicate(
    st: Instantiator, container: ComponentMirror, record: ConnectionRecord, mirror: _Mirror
) -> None:
    src_steps = _array_steps(container, record.src)
    dst_steps = _array_steps(container, record.dst)
    if not src_steps and not dst_steps:
        return
    pattern = _connection_pattern(st, record)

    def combos(steps: list[ComponentMirror]) -> list[tuple[tuple[int, ...], ...]]:
        ranges = []
        for step in steps:
            siblings = step.parent.by_sub.get(step.sub_key, [])
            ranges.append(sorted({c.index for c in siblings}))
        return [tuple(c) for c in itertools.product(*ranges)] if ranges else [()]

    pairs = [
        (s, d)
        for s in combos(src_steps)
        for d in combos(dst_steps)
        if _pattern_allows(pattern, src_steps, dst_steps, s, d)
    ]
    first_src = tuple(step.index for step in src_steps)
    first_dst = tuple(step.index for step in dst_steps)
    if (first_src, first_dst) not in pairs:
        # the first-element connection itself is not part of the pattern
        remove_connection(container, record)
    for s, d in pairs:
        if s == first_src and d == first_dst:
            continue
        src_map = {id(step): idx for step, idx in zip(src_steps, s, strict=True)}
        dst_map = {id(step): idx for step, idx in zip(dst_steps, d, strict=True)}

        def source_side(ci: ComponentMirror | None, src_map: dict = src_map) -> ComponentMirror | None:
            return _translate_ci(container, ci, src_map)

        def destination_side(ci: ComponentMirror | None, dst_map: dict = dst_map) -> ComponentMirror | None:
            return _translate_ci(container, ci, dst_map)

        _add_replica(st, container, record, source_side, destination_side, mirror)


def _add_replica(
    st: Instantiator,
    container: ComponentMirror,
    record: ConnectionRecord,
    source_side: _Move,
    destination_side: _Move,
    mirror: _Mirror,
) -> None:
    """A copy of a connection instance with its source-side components moved by
    ``source_side`` and its destination-side ones by ``destination_side``."""
    src = _translate(record.src, source_side)
    dst = _translate(record.dst, destination_side)
    if src is None or dst is None:
        return
    for existing in container.conn_index.get((id(src), id(dst)), ()):
        if len(existing.decls) == len(record.decls) and all(
            a is b for a, b in zip(existing.decls, record.decls, strict=True)
        ):
            return
    name = connection_name(container, src, dst)
    if record.obj.bidirectional and not st.legacy:
        name = name.replace("->", "<->")
    factory = st.factory
    conni = factory.new(
        "ConnectionInstance",
        name=name,
        complete=True if record.obj.complete else None,
        bidirectional=True if record.obj.bidirectional else None,
        kind=record.obj.kind,
        source=src.obj,
        destination=dst.obj,
    )
    # references before the one declared in the container are on the source side
    across = next((i for i, c in enumerate(record.contexts) if c is container), None)
    refs = []
    contexts = []
    for position, ref in enumerate(record.obj.connectionReferences):
        before = across is not None and position < across
        at = across is not None and position == across
        context_side = source_side if before or (across is None) else destination_side
        values = {}
        context = _translate(mirror(ref.context), context_side) if ref.context is not None else None
        if context is not None:
            values["context"] = context.obj
        contexts.append(context)
        for attr, side in (
            ("source", source_side if before or at else destination_side),
            ("destination", source_side if before else destination_side),
        ):
            value = getattr(ref, attr)
            if value is not None:
                moved = _translate(mirror(value), side)
                if moved is not None:
                    values[attr] = moved.obj
        refs.append(factory.new("ConnectionReference", connection=ref.connection, **values))
    factory.extend(conni, "connectionReferences", refs)
    factory.extend(conni, "inSystemOperationModes", list(record.obj.inSystemOperationModes))
    attach(st, container, ConnectionRecord(conni, src, dst, list(record.decls), record.kind, contexts))


def _connection_pattern(st: Instantiator, record: ConnectionRecord) -> list[list[str]]:
    """Connection_Pattern of the declarations of a connection instance (lower-case literals)."""
    lookup = st.lookup
    key = lookup.property_key("Communication_Properties::Connection_Pattern")
    for decl in record.decls:
        for member in st.resolver.refinement_chain(decl):
            for pa in lookup.holder_associations(member).get(key, ()):
                for mv in pa.ownedValues:
                    value = mv.value
                    if value is None:
                        continue
                    rows = value.ownedItems if _model.is_a(value, "ListValue") else [value]
                    pattern = []
                    for row in rows:
                        items = row.ownedItems if _model.is_a(row, "ListValue") else [row]
                        pattern.append(
                            [(i.name or "").lower() for i in items if _model.is_a(i, "NamedValue")]
                        )
                    return pattern
    return []


def _pattern_allows(
    pattern: list[list[str]],
    src_steps: list[ComponentMirror],
    dst_steps: list[ComponentMirror],
    s: tuple[tuple[int, ...], ...],
    d: tuple[tuple[int, ...], ...],
) -> bool:
    """Whether source indices ``s`` connect to destination indices ``d`` (first array level
    on each side; deeper levels connect every element)."""
    if not src_steps or not dst_steps:
        return True
    si, di = s[0], d[0]
    first_src, first_dst = src_steps[0], dst_steps[0]
    src_siblings = first_src.parent.by_sub[first_src.sub_key]
    dst_siblings = first_dst.parent.by_sub[first_dst.sub_key]
    sizes_s = [max(c.index[k] for c in src_siblings) for k in range(len(si))]
    sizes_d = [max(c.index[k] for c in dst_siblings) for k in range(len(di))]
    row = pattern[0] if pattern else []
    for k in range(min(len(si), len(di))):
        rule = row[k] if k < len(row) else ("one_to_one" if sizes_s[k] == sizes_d[k] else "all_to_all")
        a, b, n = si[k], di[k], sizes_d[k]
        if rule == "one_to_one" and a != b:
            return False
        if rule == "next" and b != a + 1:
            return False
        if rule == "previous" and b != a - 1:
            return False
        if rule == "cyclic_next" and b != (a % n) + 1:
            return False
        if rule == "cyclic_previous" and b != ((a - 2) % n) + 1:
            return False
        if rule == "one_to_all" and a != 1:
            return False
        if rule == "all_to_one" and b != 1:
            return False
    return True


def _translate_ci(
    container: ComponentMirror, ci: ComponentMirror | None, mapping: dict[int, tuple[int, ...]]
) -> ComponentMirror | None:
    """The component at the place of ``ci`` under ``container`` with the array steps named in
    ``mapping`` (by the id of the first-element step) moved to other indices."""
    if ci is None:
        return None
    chain = []
    current: ComponentMirror | None = ci
    while current is not None and current is not container:
        chain.append(current)
        current = current.parent
    if current is None:
        return ci
    result = container
    for step in reversed(chain):
        index = mapping.get(id(step), step.index)
        result = next((c for c in result.by_sub.get(step.sub_key, []) if c.index == index), None)
        if result is None:
            return None
    return result


def _translate(end: Any, move: _Move) -> Any:
    """A component or feature end moved to another component by ``move``."""
    if isinstance(end, ComponentMirror):
        return move(end)
    if isinstance(end, FeatureMirror):
        owner = move(end.owner)
        if owner is None:
            return None
        names = []
        current: FeatureMirror | None = end
        while current is not None:
            names.append((current.key, current.index))
            current = current.parent
        fi: FeatureMirror | None = None
        for key, index in reversed(names):
            pool = owner.features if fi is None else fi.children
            fi = next((f for f in pool if f.key == key and f.index == index), None)
            if fi is None:
                return None
        return fi
    return end


def _mirror_index(order: list[ComponentMirror]) -> dict[int, Any]:
    """The mirror of each component and feature instance object, by the object's id."""
    index: dict[int, Any] = {}
    for ci in order:
        index[id(ci.obj)] = ci
        stack = list(ci.features)
        while stack:
            fi = stack.pop()
            index[id(fi.obj)] = fi
            stack.extend(fi.children)
    return index

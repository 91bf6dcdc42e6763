"""The ``.aadl`` sidecars of an export: the units its hrefs point into, and what they ``with``.

OSATE resolves an instance file's hrefs (``../P.aadl#…``) against the ``.aadl`` files beside
its ``instances`` folder. :func:`sidecar_texts` writes those the document referred to
(``Declarations.used_units``), and the units they name in ``with`` clauses, with
:mod:`rosaadl.exporters.aadl_text`; OSATE's own property sets and packages are not written.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import ExportError, Location

from .osate_sets import osate_unit
from .state import Writer

__all__ = ["sidecar_texts"]


def sidecar_texts(w: Writer) -> dict[str, str]:
    """The ``.aadl`` texts of the units the file refers to and the units they name in ``with``."""
    from rosaadl.exporters.aadl_text import unit_file_name, write_unit

    if w.resolver is None:
        return {}
    order: list[EObject] = []
    seen: set[int] = set()
    pending = list(w.links.used_units.values())
    missing: set[str] = set()
    while pending:
        unit = pending.pop(0)
        if id(unit) in seen or osate_unit(unit.name):
            continue
        seen.add(id(unit))
        order.append(unit)
        for name in list(unit.withs) + list(getattr(unit, "privateWiths", []) or []):
            target = w.resolver.unit(name)
            if target is None:
                if not osate_unit(name):
                    missing.add(name)
                continue
            pending.append(target)
    if missing:
        w.warn(f"units named in with clauses are not in the model, not written: {', '.join(sorted(missing))}")
    texts: dict[str, str] = {}
    lowered: dict[str, str] = {}
    for unit in sorted(order, key=lambda u: (u.name or "").lower()):
        name = unit_file_name(unit)
        if name.lower() in lowered:
            raise ExportError(
                f"units {lowered[name.lower()]!r} and {unit.name!r} would both be written to {name!r}",
                Location(path=unit.name),
            )
        lowered[name.lower()] = unit.name
        texts[name] = write_unit(unit)
    return texts

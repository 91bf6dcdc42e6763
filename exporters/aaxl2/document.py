"""The ``.aaxl2`` document: its roots, its namespaces, its writing again for an era, its report.

:func:`write_document` gives every instance object its path, writes the document
(:func:`document_text`: the system instance alone, or an ``xmi:XMI`` document with the further
component instance roots; the namespaces the root declares, with those annex instances bring),
writes it again while a value turns out to exist only in an older layout of one of OSATE's
property sets (every reference into that set then follows that layout), and reports what was
left out (:func:`report`).
"""

from __future__ import annotations

from rosaadl.importers import osate_eras

from .instances import emit_component
from .paths import assign_paths, extra_roots
from .state import Writer
from .vocabulary import NAMESPACES

__all__ = ["write_document", "document_text", "report"]


def write_document(w: Writer) -> bytes:
    """The ASCII bytes of the document, its warnings reported on ``w``."""
    w.roots = [w.system, *extra_roots(w)]
    assign_paths(w)
    for _attempt in range(4):
        text = document_text(w)
        if not w.wanted_set_eras:
            break
        # a value exists only in an older layout of one of OSATE's sets: write every
        # reference into that set in that layout, and start again
        w.set_eras.update(w.wanted_set_eras)
    report(w)
    return text.encode("ascii")


def document_text(w: Writer) -> str:
    """One writing of the document (what it learns is reset first)."""
    w.out = body = []
    w.links.reset()
    w.skipped.clear()
    w.literal_cache.clear()
    w.extra_ns.clear()
    w.wanted_set_eras = {}
    multi = len(w.roots) > 1
    if multi:
        for number, root in enumerate(w.roots):
            tag = "instance:SystemInstance" if number == 0 else "instance:ComponentInstance"
            emit_component(w, "  ", root, tag)
    else:
        emit_component(w, "", w.system, "instance:SystemInstance", root_attrs="\x00")
    namespaces = dict(NAMESPACES)
    for prefix, uri in w.extra_ns.items():
        namespaces.setdefault(prefix, uri)
    ordered = [("xmi", namespaces.pop("xmi")), ("xsi", namespaces.pop("xsi"))]
    ordered += sorted(namespaces.items())
    declaration = ' xmi:version="2.0"' + "".join(f' xmlns:{p}="{u}"' for p, u in ordered)
    head = '<?xml version="1.0" encoding="ASCII"?>\n'
    if multi:
        return head + f"<xmi:XMI{declaration}>\n" + "".join(body) + "</xmi:XMI>\n"
    body[0] = body[0].replace("\x00", declaration, 1)
    return head + "".join(body)


def report(w: Writer) -> None:
    """Warnings for what the document leaves out or writes in an older era's layout."""
    for set_name, era in sorted(w.set_eras.items()):
        spelled = next((n for n in osate_eras.table(era).property_sets() if n.lower() == set_name), set_name)
        w.warn(
            f"references into OSATE's {spelled} follow its {era} layout: a value "
            "exists only there (OSATE has since renamed it, and today's OSATE does not resolve it)"
        )
    for what, count in sorted(w.links.missing.items()):
        w.warn(
            f"{count} {what} link(s) left out: the declarative element is not in the model "
            "(OSATE re-instantiates from the .aadl sources)"
        )
    if w.links.guessed_units:
        names = ", ".join(sorted(w.links.guessed_units.values(), key=str.lower))
        w.warn(f"units not in the model, referred to as ../<name>.aadl: {names}")
    for line in w.skipped[:20]:
        w.warn(f"property association left out: {line}")
    if len(w.skipped) > 20:
        w.warn(f"... and {len(w.skipped) - 20} more property association(s) left out")

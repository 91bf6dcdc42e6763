"""A package as AADL text: ``package a::b public ... private ... properties ... end a::b;``.

Each section holds its ``with`` clauses (wrapped when long), renames, classifiers (one blank line
between them) and annex libraries; the private section is written only when it holds something.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from pyecore.ecore import EObject

from rosaadl.exporters.aadl_text.associations import property_association
from rosaadl.exporters.aadl_text.classifiers import annex_text, classifier
from rosaadl.exporters.aadl_text.context import UnitContext
from rosaadl.exporters.aadl_text.lexical import enum_name, literal, unit_file_name

__all__ = ["package"]


def package(ctx: UnitContext, pkg: EObject) -> None:
    """The whole package."""
    unit_file_name(pkg)  # checks the name
    name = "::".join(part.strip() for part in pkg.name.split("::"))
    ctx.where = [name]
    for part in name.split("::"):
        ctx.ident(part, "the package", pkg)

    def split(items: Iterable[EObject]) -> tuple[list[EObject], list[EObject]]:
        items = list(items)
        hidden = [i for i in items if enum_name(i.visibility) == "private"]
        return [i for i in items if enum_name(i.visibility) != "private"], hidden

    public, private = split(pkg.classifiers)
    renamings, private_renamings = split(pkg.renamings)
    annexes, private_annexes = split(pkg.annexLibraries)
    ctx.emit(0, f"package {name}")
    ctx.emit(0, "public")
    _section(ctx, pkg.withs, renamings, public, annexes)
    if private or pkg.privateWiths or private_renamings or private_annexes:
        ctx.emit(0, "private")
        _section(ctx, pkg.privateWiths, private_renamings, private, private_annexes)
    if pkg.ownedPropertyAssociations:
        ctx.emit(0, "properties")
        for assoc in pkg.ownedPropertyAssociations:
            property_association(ctx, 1, assoc)
    ctx.emit(0, f"end {name};")


def _section(
    ctx: UnitContext,
    withs: Sequence[str],
    renamings: Iterable[EObject],
    classifiers: Sequence[EObject],
    annexes: Iterable[EObject],
) -> None:
    head = False
    if withs:
        names = [ctx.qname(w, "with clause", ctx.unit) for w in withs]
        ctx.emit_wrapped(1, "with ", names, ";")
        head = True
    for renaming in renamings:
        _renaming(ctx, renaming)
        head = True
    first = not head
    for item in classifiers:
        if not first:
            ctx.emit(1, "")
        first = False
        classifier(ctx, item)
    for annex in annexes:
        if not first:
            ctx.emit(1, "")
        first = False
        ctx.where.append(f"annex {annex.name}")
        text = annex_text(ctx, annex)
        ctx.emit(1, f"annex {ctx.ident(annex.name, 'the annex library', annex)} {text};")
        ctx.where.pop()


def _renaming(ctx: UnitContext, ren: EObject) -> None:
    kind = enum_name(ren.kind) or "classifier"
    ctx.where.append(f"renames {ren.target}")
    name = ctx.ident(ren.name, "the renaming", ren) + " " if ren.name else ""
    if kind == "package":
        if not name:
            raise ctx.error("a package renaming needs a name", ren)
        ctx.emit(1, f"{name}renames package {ctx.qname(ren.target, 'renamed package', ren)};")
    elif kind == "all":
        target = (ren.target or "").strip()
        if target.lower().replace(" ", "").endswith("::all"):
            target = target[: target.lower().rindex("all")].rstrip().removesuffix("::").rstrip()
        ctx.emit(1, f"renames package {ctx.qname(target, 'renamed package', ren)}::all;")
    elif kind == "featureGroupType":
        target = ctx.classifier_ref(ren.target, "renamed feature group type", ren)
        ctx.emit(1, f"{name}renames feature group {target};")
    else:
        target = ctx.classifier_ref(ren.target, "renamed classifier", ren)
        ctx.emit(1, f"{name}renames {literal(ren.category)} {target};")
    ctx.where.pop()

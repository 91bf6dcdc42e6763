"""The AADL text writer's public functions: one unit as text, units by file name, a model to a folder."""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import fileio
from rosaadl.arguments import checked
from rosaadl.errors import ExportError, Location
from rosaadl.exporters.aadl_text.context import UnitContext
from rosaadl.exporters.aadl_text.lexical import unit_file_name
from rosaadl.exporters.aadl_text.packages import package
from rosaadl.exporters.aadl_text.property_sets import property_set
from rosaadl.model import is_a

__all__ = ["write_unit", "write_units", "write_model"]

log = logging.getLogger(__package__)  # the writer's one logger, rosaadl.exporters.aadl_text


def write_unit(unit: EObject) -> str:
    """AADL text for one ``AadlPackage`` or ``PropertySet`` (ends with a newline).

    Raises :class:`ExportError` naming the element when something cannot be written as AADL.
    """
    if not isinstance(unit, EObject):
        raise ExportError(f"expected an AadlPackage or a PropertySet, got {type(unit).__name__}")
    ctx = UnitContext(unit)
    if is_a(unit, "AadlPackage"):
        package(ctx, unit)
    elif is_a(unit, "PropertySet"):
        property_set(ctx, unit)
    else:
        raise ExportError(
            f"cannot write a {unit.eClass.name} as AADL text: expected an AadlPackage or a PropertySet"
        )
    return ctx.text()


def write_units(units: Iterable[EObject]) -> dict[str, str]:
    """File name (``a::b`` → ``a-b.aadl``) → text, in the order of ``units``.

    Two units whose file names differ only by case (AADL names are case-insensitive) are an error.
    """
    out: dict[str, str] = {}
    seen: dict[str, str] = {}
    for unit in units:
        name = unit_file_name(unit)
        key = name.lower()
        if key in seen:
            raise ExportError(
                f"two model units would both be written to {name!r} ({seen[key]!r} and {unit.name!r}); "
                "AADL names are case-insensitive",
                Location(path=unit.name),
            )
        seen[key] = unit.name
        out[name] = write_unit(unit)
    return out


@checked
def write_model(model: EObject | Iterable[EObject], out_dir: str | os.PathLike[str]) -> list[Path]:
    """Write every unit of an ``AadlModel`` (or the given units) as ``<unit>.aadl`` into ``out_dir``.

    All texts are made before the first file is written, so an error leaves no output at all;
    the files are written all-or-nothing. A unit name that is not an AADL name (``../../etc``) is
    refused with :class:`ExportError`, and no path can land outside ``out_dir``.
    """
    if is_a(model, "AadlPackage", "PropertySet"):
        units: list[EObject] = [model]
    elif is_a(model, "AadlModel"):
        units = list(model.units)
    elif not isinstance(model, EObject):
        try:
            units = list(model)
        except TypeError:
            raise ExportError(f"expected an AadlModel, got {type(model).__name__}") from None
    else:
        raise ExportError(f"expected an AadlModel, got {model.eClass.name}")
    texts = write_units(units)
    targets = [(fileio.safe_join(out_dir, name), text) for name, text in texts.items()]
    written = fileio.write_files(targets)
    log.info("wrote %d AADL file(s) to %s", len(written), out_dir)
    return written

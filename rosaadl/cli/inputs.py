"""Inputs shared by the verbs that work on AADL models: reading them, and choosing the instance.

AADL text files and folders are read together into one model (with the component library);
a rosaadl model file, an OSATE ``.aaxl2`` or a Cheddar file is read on its own. ``--root``
names the implementation to instantiate, or picks one of the instances a file already holds.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, UsageError
from rosaadl.fileio import existing
from rosaadl.formats import read_input, reader_for

__all__ = ["Inputs", "read_aadl_inputs", "read_rosmod_inputs", "read_generator_inputs", "choose_instance"]

_AADL_SUFFIXES = (".aadl", ".aadl2")


@dataclass
class Inputs:
    """One AADL model (declarative units and/or instances) and the warnings met reading it."""

    model: EObject
    warnings: list[Diagnostic] = field(default_factory=list)


def read_aadl_inputs(
    paths: Sequence[Path], *, strict: bool = False, time_unit: str = "us", lenient: bool = False
) -> Inputs:
    """Read the inputs of an AADL verb into one ``AadlModel`` (``lenient``: a classifier or
    package of AADL text that is not found is a warning, see ``aadl_text.read_files``)."""
    if not paths:
        raise UsageError("no input given")
    for path in paths:
        if not existing(path):
            raise UsageError("no such file or folder", file=str(path))
    text = [p for p in paths if p.is_dir() or p.suffix.lower() in _AADL_SUFFIXES]
    others = [p for p in paths if p not in text]
    if text and others:
        raise UsageError(
            "give either AADL text (files and folders) or one model file (.xmi, .json, .aaxl2, Cheddar)",
            file=str(others[0]),
        )
    if len(others) > 1:
        raise UsageError("give one model file at a time", file=str(others[1]))
    if text:
        for path in text:
            if path.is_dir():
                reader = reader_for(path)
                if reader.name != "aadl":
                    raise UsageError(f"the folder is a {reader.description}, not AADL text", file=str(path))
        from rosaadl.importers import aadl_text

        warnings: list[Diagnostic] = []
        model = aadl_text.read_files(list(text), warnings=warnings, lenient=lenient)
        return Inputs(model, warnings)
    loaded = read_input(others[0], strict=strict, time_unit=time_unit)
    if loaded.kind != "aadl" or loaded.root.eClass.name != "AadlModel":
        raise UsageError(
            "expected an AADL model, got a ROSMOD project (convert it first)", file=str(others[0])
        )
    return Inputs(loaded.root, list(loaded.warnings))


def choose_instance(
    inputs: Inputs,
    root: str | None,
    *,
    lenient: bool = False,
    compatibility: str = "current",
) -> EObject:
    """The instance to work on: ``root`` instantiated from the declarative units, or one of the
    instances the input already holds (by root implementation or instance name)."""
    model = inputs.model
    existing = list(model.instances)
    if root:
        wanted = root.lower()
        for instance in existing:
            names = {(instance.classifier or "").lower(), (instance.name or "").lower()}
            if wanted in names or (instance.classifier or "").lower().endswith("::" + wanted):
                return instance
        if not any(u.eClass.name == "AadlPackage" for u in model.units):
            choices = ", ".join(i.classifier or i.name for i in existing) or "none"
            raise UsageError(f"no instance of {root!r} in the input (it holds: {choices})")
        from rosaadl.transforms.instantiate import instantiate

        return instantiate(
            model, root, diagnostics=inputs.warnings, strict=not lenient, compatibility=compatibility
        )
    if len(existing) == 1:
        return existing[0]
    if existing:
        choices = ", ".join(i.classifier or i.name for i in existing)
        raise UsageError(f"the input holds several instances ({choices}); choose one with --root")
    raise UsageError("--root is required: name the system implementation to instantiate (Pkg::Sys.impl)")


def read_rosmod_inputs(path: Path, project: str | None) -> tuple[Inputs, object]:
    """A ROSMOD project converted to AADL, with the library, and the conversion's trace."""
    from rosaadl.formats import read_input
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl
    from rosaadl.workflow.workspace import library_unit_names

    loaded = read_input(path, project=project)
    if len(loaded.roots) > 1:
        names = ", ".join(r.name for r in loaded.roots)
        raise UsageError(
            f"the input holds several projects ({names}); choose one with --project", file=str(path)
        )
    converted = rosmod_to_aadl(loaded.root, reserved_units=library_unit_names())
    warnings: list[Diagnostic] = list(loaded.warnings) + list(converted.warnings)
    workspace = read_files([], warnings=warnings, check=False)
    workspace.units.extend(list(converted.model.units))
    return Inputs(workspace, warnings), converted.trace


def read_generator_inputs(
    paths: Sequence[Path], *, project: str | None = None, lenient: bool = False
) -> tuple[Inputs, object]:
    """The inputs of a verb that generates code: AADL (see :func:`read_aadl_inputs`), or one
    ROSMOD project converted on the way (with the conversion's trace; None for AADL)."""
    for path in paths:
        if not existing(path):
            raise UsageError("no such file or folder", file=str(path))
    if len(paths) == 1 and reader_for(paths[0]).name in ("rosmod", "webgme"):
        return read_rosmod_inputs(paths[0], project)
    return read_aadl_inputs(list(paths), lenient=lenient), None

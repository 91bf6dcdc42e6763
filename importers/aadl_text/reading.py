"""Reading AADL text: the entry points of the reader, from strings, files, folders and the library.

:func:`read_string` parses and builds one text into an ``AadlModel``; :func:`read_files` reads
files and folders (:data:`AADL_SUFFIXES`, folders searched recursively in sorted order) together
with the component library of rosaadl (:func:`library_files`), then checks names, units and
enumeration literals across all units (:mod:`.checks`).  Errors are raised together, located;
warnings are logged (logger ``rosaadl.importers.aadl_text``) and handed to the caller.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable
from importlib import resources
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl.arguments import checked, expect_path
from rosaadl.bulk import gc_paused
from rosaadl.errors import (
    Diagnostic,
    Location,
    NameResolutionError,
    ParseError,
    RosaadlError,
    ValidationError,
)
from rosaadl.fileio import existing
from rosaadl.importers.aadl_syntax import decode
from rosaadl.importers.aadl_text.checks import check_names_and_values
from rosaadl.importers.aadl_text.factory import add, make
from rosaadl.importers.aadl_text.units import read_units
from rosaadl.model import is_a

__all__ = ["AADL_SUFFIXES", "library_files", "read_files", "read_string"]

log = logging.getLogger("rosaadl.importers.aadl_text")

#: File name suffixes searched for in folders (compared case-insensitively).
AADL_SUFFIXES: tuple[str, ...] = (".aadl", ".aadl2")


def _raise_errors(errors: list[Diagnostic], kind: type[RosaadlError], what: str) -> None:
    if not errors:
        return
    first = errors[0]
    if len(errors) == 1:
        exc = kind(first.message, first.location)
    else:
        listing = "\n".join(f"  {d.location}: {d.message}" for d in errors)
        exc = kind(f"{first.message}\n{len(errors)} {what}:\n{listing}", first.location)
    exc.errors = list(errors)
    raise exc


def _report(diagnostics: Iterable[Diagnostic], warnings: list[Diagnostic] | None) -> None:
    for diagnostic in diagnostics:
        log.warning("%s", diagnostic)
        if warnings is not None:
            warnings.append(diagnostic)


def _build(text: str | bytes, filename: str, *, quote: bool = True) -> tuple[list[EObject], list[Diagnostic]]:
    """Parse and build one text; the new units (not yet added to a model) and warnings.
    Without ``quote`` a syntax error shows nothing of the text (:func:`parse`)."""
    if isinstance(text, bytes | bytearray | memoryview):  # decoded once: the builder slices the text
        text = decode(bytes(text), filename)
    if text.startswith("\ufeff"):
        text = text[1:]
    with gc_paused():
        units, rules = read_units(text, filename, quote=quote)
    _raise_errors(rules.errors, ValidationError, "errors")
    return units, rules.warnings


def _build_file(path: Path, *, quote: bool = True) -> tuple[list[EObject], list[Diagnostic]]:
    """:func:`_build` of a file's text, its bytes released once decoded."""
    return _build(decode(_read_bytes(path), str(path)), str(path), quote=quote)


def read_string(
    text: str | bytes,
    filename: str = "<string>",
    *,
    model: EObject | None = None,
    warnings: list[Diagnostic] | None = None,
) -> EObject:
    """Read the packages and property sets of one AADL text into ``model`` (a new
    ``AadlModel`` when None) and return the model.

    Raises :class:`AadlSyntaxError` (syntax, encoding, literals out of range) or
    :class:`ValidationError` (the legality rules checked while building; ``.errors`` lists
    every one found), both located; nothing is added to ``model`` then.
    Warnings are logged and appended to ``warnings`` when given.  Names are not resolved here:
    :func:`read_files` does that across files.
    """
    if model is None:
        stem = Path(filename).stem if filename and not filename.startswith("<") else ""
        model = make("AadlModel", name=stem or "model")
    elif not is_a(model, "AadlModel"):
        raise ValidationError("read_string adds to an AadlModel; got something else", file=filename)
    units, notes = _build(text, filename)
    if units:
        add(model, "units", *units)
    _report(notes, warnings)
    return model


def library_files() -> list[Path]:
    """The ``.aadl`` files of the component library shipped with rosaadl, sorted."""
    root = resources.files("rosaadl.library")
    found: list[tuple[tuple[str, ...], Path]] = []
    stack: list[tuple[tuple[str, ...], Any]] = [((), root)]
    while stack:
        parts, folder = stack.pop()
        for entry in folder.iterdir():
            name = entry.name
            if entry.is_dir():
                if not name.startswith((".", "__")):
                    stack.append(((*parts, name), entry))
            elif name.lower().endswith(".aadl"):
                found.append(((*parts, name), Path(str(entry))))
    return [path for _, path in sorted(found)]


def _aadl_files_under(folder: Path) -> list[Path]:
    """The ``.aadl``/``.aadl2`` files under a folder, recursively, in sorted order (hidden
    folders and symbolic links to folders are not entered)."""
    found: list[tuple[tuple[str, ...], Path]] = []
    for current, dirs, names in os.walk(folder, followlinks=False):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        base = Path(current)
        parts = base.relative_to(folder).parts
        for name in names:
            if name.lower().endswith(AADL_SUFFIXES) and (base / name).is_file():
                found.append(((*parts, name), base / name))
    return [path for _, path in sorted(found)]


def _input_root(path: Path) -> Path:
    """The folder whose files an input names: a folder given (its own name kept even when it
    is a symbolic link), or the folder of a file given; the folders above it resolved."""
    absolute = Path(os.path.abspath(path))
    parent = absolute.parent.resolve()
    return parent / absolute.name if path.is_dir() else parent


def _expand(paths: Iterable[str | os.PathLike[str]], seen: set[Path]) -> list[tuple[Path, bool]]:
    """Files as given and the AADL files under folders, each with whether its real path lies
    inside the input that named it (not reached through a symbolic link out of it: such a
    file's syntax errors quote none of its text); files already in ``seen`` (resolved paths)
    are left out, so that a file named twice is read once."""
    out: list[tuple[Path, bool]] = []
    for item in paths:
        path = expect_path(item, "an AADL file or folder")
        if not existing(path, ParseError):
            raise ParseError("no such file or folder", file=str(path))
        root = _input_root(path)
        found = _aadl_files_under(path) if path.is_dir() else [path]
        for file in found:
            key = file.resolve()
            if key not in seen:
                seen.add(key)
                out.append((file, key.is_relative_to(root)))
    return out


def _read_bytes(path: Path) -> bytes:
    try:
        return path.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the file: {exc.strerror or exc}", file=str(path)) from None


@checked
def read_files(
    paths: str | os.PathLike[str] | Iterable[str | os.PathLike[str]],
    *,
    include_library: bool = True,
    warnings: list[Diagnostic] | None = None,
    check: bool = True,
    lenient: bool = False,
) -> EObject:
    """Read AADL files and folders (searched recursively for ``.aadl``/``.aadl2`` files, in
    sorted order) into one ``AadlModel``.

    With ``include_library`` the component library of rosaadl (``library_files()``: the
    predeclared property sets, the sets and packages OSATE's contribution plug-in ships, ROS
    packages, hardware) is read first; a user unit named like a library unit replaces it, with
    a warning.  With ``check``
    every name, unit and enumeration literal is resolved across all units
    (:class:`rosaadl.resolution.Resolver`, then units, enumeration literals and record fields
    of every property value against its property's type); every error found is reported in
    one located :class:`NameResolutionError` (the first one's location, all of them in the
    message and in ``.errors``); warnings (a property set that is not loaded, a missing
    ``with`` clause, a name declared twice, prototypes) are logged and appended to ``warnings``.
    ``check=False`` reads without resolving (files that name packages not given, for example).
    ``lenient`` keeps going past a classifier or package that is not found (a warning, as OSATE
    does; the instantiator's ``strict=False`` then instantiates without it): the model of a
    project whose with-ed package is missing is read.
    """
    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    library = library_files() if include_library else []
    files = _expand(paths, {path.resolve() for path in library})
    model = make("AadlModel", name="workspace")
    notes: list[Diagnostic] = []
    library_units: dict[str, EObject] = {}
    if include_library:
        for path in library:
            units, unit_notes = _build_file(path)
            notes.extend(unit_notes)
            for unit in units:
                library_units.setdefault(unit.name.lower(), unit)
            if units:
                add(model, "units", *units)
    for path, inside in files:
        units, unit_notes = _build_file(path, quote=inside)
        notes.extend(unit_notes)
        for unit in units:
            replaced = library_units.pop(unit.name.lower(), None)
            if replaced is not None:
                model.units.remove(replaced)
                notes.append(
                    Diagnostic(
                        "warning",
                        f"{unit.name} replaces the library's {replaced.name} ({replaced.sourceFile})",
                        Location(unit.sourceFile, unit.line, unit.column),
                    )
                )
        if units:
            add(model, "units", *units)
    if check:
        with gc_paused(promote=False):  # the checks only add caches: no garbage to collect
            notes.extend(check_names_and_values(model, lenient=lenient))
    _report([d for d in notes if d.severity != "error"], warnings)
    _raise_errors([d for d in notes if d.severity == "error"], NameResolutionError, "errors")
    return model

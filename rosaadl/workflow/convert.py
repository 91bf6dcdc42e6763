"""``rosaadl convert`` as functions: files in, ROSMOD ⇄ AADL transformations, files out.

:func:`convert_project_files` reads a ROSMOD project (a folder, an ``.rml``/``.rosml`` file or a
``.webgmex`` archive), converts it with :func:`rosaadl.transforms.rosmod_to_aadl.rosmod_to_aadl`
and writes the AADL packages (and the trace); :func:`convert_aadl_files` reads AADL files with
the component library, converts them with
:func:`rosaadl.transforms.aadl_to_rosmod.aadl_to_rosmod` (with the forward trace, read from its
file, when given) and writes a ROSMOD v0.3 project. The transformations themselves read and
write no file: what they need from outside the model (the trace, the library's units) comes
from here.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Sequence
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import fileio
from rosaadl import model as _model
from rosaadl.errors import Diagnostic
from rosaadl.transforms import trace as tracing
from rosaadl.transforms.aadl_to_rosmod import aadl_to_rosmod, is_rosmod_convention, top_level_systems
from rosaadl.transforms.rosmod_to_aadl import NameScope, aadl_identifier, rosmod_to_aadl
from rosaadl.workflow.workspace import library_unit_names

__all__ = ["convert_project_files", "convert_aadl_files", "library_units"]

log = logging.getLogger(__name__)


def convert_project_files(
    source: str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    *,
    project: str | None = None,
    trace_file: str | os.PathLike[str] | None = None,
    warnings: list[Diagnostic] | None = None,
) -> list[Path]:
    """``rosaadl convert PROJECT_DIR|FILE.webgmex -o OUT_DIR [--project NAME] [--trace FILE]``.

    Reads a textual project (folder or ``.rml``/``.rosml`` file) or a ``.webgmex`` archive,
    converts every project (or the one named ``project``) and writes one ``.aadl`` file per
    package into ``out_dir`` (one subfolder per project, named after it, when an archive holds
    several), with the trace when ``trace_file`` is given (``<stem>_<project><suffix>`` per
    project then; ``.json`` or XMI by the suffix). Every file is made before the first one is
    written, each atomically; the paths written.
    """
    from rosaadl.exporters.aadl_text import write_units
    from rosaadl.importers import rosmod_text, rosmod_webgme

    path = Path(source)
    if path.suffix.lower() == ".webgmex":
        projects = rosmod_webgme.read_webgmex(path, project=project, warnings=warnings)
    else:
        projects = [rosmod_text.read_project(path, warnings=warnings)]
    several = len(projects) > 1
    outputs: list[tuple[Path, bytes]] = []
    folders = NameScope()
    for item in projects:
        result = rosmod_to_aadl(item, trace=trace_file is not None, reserved_units=library_unit_names())
        if warnings is not None:
            warnings.extend(Diagnostic("warning", w.message, w.location) for w in result.warnings)
        folder = Path(out_dir) / folders.take(item.name) if several else Path(out_dir)
        for name, text in write_units(result.model.units).items():
            outputs.append((fileio.safe_join(folder, name), text.encode("utf-8")))
        if trace_file is not None and result.trace is not None:
            target = Path(trace_file)
            if several:
                target = target.with_name(f"{target.stem}_{aadl_identifier(item.name)}{target.suffix}")
            as_json = target.suffix.lower() == ".json"
            outputs.append(
                (target, _model.dumps_json(result.trace) if as_json else _model.dumps_xmi(result.trace))
            )
    for target, data in outputs:
        fileio.atomic_write_bytes(target, data)
    log.info("wrote %d file(s) for %d project(s)", len(outputs), len(projects))
    return [target for target, _ in outputs]


def library_units(model: EObject) -> list[EObject]:
    """The units of ``model`` read from the component library's files (``library_files``)."""
    from rosaadl.importers.aadl_text import library_files

    files = {str(path.resolve()) for path in library_files()}
    found = []
    for unit in model.units:
        source = getattr(unit, "sourceFile", None)
        try:
            if source and str(Path(source).resolve()) in files:
                found.append(unit)
        except OSError:  # pragma: no cover - a path the OS cannot resolve
            continue
    return found


def convert_aadl_files(
    paths: Sequence[str | os.PathLike[str]],
    out_dir: str | os.PathLike[str],
    *,
    trace_file: str | os.PathLike[str] | None = None,
    roots: Sequence[str] | None = None,
    warnings: list[Diagnostic] | None = None,
) -> list[Path]:
    """``rosaadl convert MODEL.aadl... --to rosmod -o OUT_DIR [--trace FILE] [--root ...]``.

    Reads the AADL files and folders with the library, converts them (with the forward
    conversion's trace when ``trace_file`` is given; a best-effort conversion instantiates
    ``roots``, by default the top-level system implementations of the given files) and writes
    a ROSMOD v0.3 project into ``out_dir``; the paths written.
    """
    from rosaadl.exporters.rosmod_text import write_project
    from rosaadl.importers.aadl_text import read_files

    aadl = read_files(paths, warnings=warnings)
    if roots is None and not is_rosmod_convention(aadl):
        given = [Path(p).resolve() for p in paths]

        def is_given(unit: EObject) -> bool:
            source = getattr(unit, "sourceFile", None)
            if not source:
                return False
            resolved = Path(source).resolve()
            return any(resolved == g or g in resolved.parents for g in given)

        roots = top_level_systems(aadl, [u for u in aadl.units if is_given(u)])
    forward = tracing.load_trace(trace_file) if trace_file is not None else None
    project = aadl_to_rosmod(aadl, trace=forward, roots=roots, library=library_units(aadl), warnings=warnings)
    return write_project(project, out_dir, warnings=warnings)

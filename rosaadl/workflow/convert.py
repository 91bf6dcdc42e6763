"""``rosaadl convert`` as functions: files in, ROSMOD ⇄ AADL transformations, files out.

:func:`convert_project_files` reads a ROSMOD project (a folder, an ``.rml``/``.rosml`` file or a
``.webgmex`` archive), converts it with :func:`rosaadl.transforms.rosmod_to_aadl.rosmod_to_aadl`
and writes the AADL packages (and the trace); :func:`convert_aadl_files` reads AADL files with
the component library, converts them with
:func:`rosaadl.transforms.aadl_to_rosmod.aadl_to_rosmod` (with the forward trace, read from its
file, when given) and writes a ROSMOD v0.3 project. The transformations themselves read and
write no file: what they need from outside the model (the trace, the library's units) comes
from here.

A ``.webgmex`` archive of several projects converts into one folder per project (and one trace
per project, :func:`project_trace`); converted back, such a folder gives one ROSMOD project per
project folder (:func:`project_folders`), since the projects' packages share names (two
projects may each have a ``Local_hardware``) and so cannot be one AADL workspace.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Sequence
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import fileio
from rosaadl import model as _model
from rosaadl.errors import Diagnostic, UsageError
from rosaadl.formats import read_input, reader_for
from rosaadl.properties import own_property
from rosaadl.transforms import trace as tracing
from rosaadl.transforms.aadl_to_rosmod import aadl_to_rosmod, is_rosmod_convention, top_level_systems
from rosaadl.transforms.rosmod_to_aadl import UNIT_KIND, NameScope, rosmod_to_aadl
from rosaadl.workflow.workspace import library_unit_names

__all__ = ["convert_project_files", "convert_aadl_files", "library_units", "project_folders", "project_trace"]

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
    several), with the trace when ``trace_file`` is given (one per project then, named by
    :func:`project_trace` after the project's folder; ``.json`` or XMI by the suffix). Every
    file is made before the first one is written, each atomically; the paths written.
    """
    from rosaadl.exporters.aadl_text import write_units
    from rosaadl.importers import rosmod_text
    from rosaadl.importers.rosmod_webgme.projects import read_webgmex_projects

    path = Path(source)
    if path.suffix.lower() == ".webgmex":
        projects = read_webgmex_projects(path, project=project, warnings=warnings)
    elif path.suffix.lower() in (".xmi", ".json") or (
        path.is_dir() and not rosmod_text.is_rosmod_project(path) and reader_for(path).name == "ros2-package"
    ):
        projects = [_rosmod_model(path, warnings)]
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
            target = project_trace(trace_file, folder.name) if several else Path(trace_file)
            as_json = target.suffix.lower() == ".json"
            outputs.append(
                (target, _model.dumps_json(result.trace) if as_json else _model.dumps_xmi(result.trace))
            )
    fileio.write_files(outputs)
    log.info("wrote %d file(s) for %d project(s)", len(outputs), len(projects))
    return [target for target, _ in outputs]


def _rosmod_model(path: Path, warnings: list[Diagnostic] | None) -> EObject:
    """The ROSMOD project of a rosaadl model file (``import ros2-package``, ``import ros2-graph``)
    or of ROS 2 packages read statically; a :class:`UsageError` for an AADL model."""
    loaded = read_input(path)
    if loaded.kind != "rosmod":
        raise UsageError("the model is not a ROSMOD project (convert --to aadl takes one)", file=str(path))
    if warnings is not None:
        warnings.extend(loaded.warnings)
    return loaded.root


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


def project_trace(trace_file: str | os.PathLike[str], folder: str) -> Path:
    """The trace of one project of several: ``<stem>_<project folder><suffix>`` beside
    ``trace_file`` (``run.trace.xmi`` → ``run.trace_AGSE.xmi``)."""
    target = Path(trace_file)
    return target.with_name(f"{target.stem}_{folder}{target.suffix}")


def project_folders(source: str | os.PathLike[str]) -> list[Path]:
    """The folders of the ROSMOD projects converted to AADL that ``source`` holds, when it holds
    several: what :func:`convert_project_files` writes for an archive of several projects, one
    subfolder per project, each with one project package (``ROSMOD_Properties::Unit_Kind =>
    Project``) and no package outside them. ``[]`` for a file, one project or other AADL."""
    from rosaadl.importers.aadl_text import AADL_SUFFIXES, read_files

    folder = Path(source)
    if not folder.is_dir() or any(
        p.is_file() and p.name.lower().endswith(AADL_SUFFIXES) for p in folder.iterdir()
    ):
        return []
    projects: dict[str, int] = {}  # project folder → its project packages
    for unit in read_files([folder], include_library=False, check=False).units:
        parts = Path(unit.sourceFile).relative_to(folder).parts
        kind = own_property(unit, UNIT_KIND) if _model.is_a(unit, "AadlPackage") else None
        projects[parts[0]] = projects.get(parts[0], 0) + int(str(kind).lower() == "project")
    if len(projects) < 2 or any(count != 1 for count in projects.values()):
        return []
    return [folder / name for name in sorted(projects)]


def _existing_trace(trace_file: str | os.PathLike[str] | None, several: bool) -> EObject | None:
    if trace_file is None:
        return None
    if not Path(trace_file).is_file():
        hint = " (with several projects, each project folder has its own trace)" if several else ""
        raise UsageError(f"no such trace file{hint}", file=str(trace_file))
    return tracing.load_trace(trace_file)


def _rosmod_project(
    paths: Sequence[str | os.PathLike[str]],
    forward: EObject | None,
    roots: Sequence[str] | None,
    warnings: list[Diagnostic] | None,
) -> EObject:
    """The ROSMOD project of AADL files and folders read together with the library."""
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
    return aadl_to_rosmod(aadl, trace=forward, roots=roots, library=library_units(aadl), warnings=warnings)


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
    a ROSMOD v0.3 project into ``out_dir``; the paths written. A single folder holding several
    converted projects (:func:`project_folders`) gives one project per project folder, each
    into the folder of the same name under ``out_dir`` and with its own trace
    (:func:`project_trace`). Every project is converted and made before the first file is
    written, each atomically.
    """
    from rosaadl.exporters.rosmod_text import render_project

    folders = project_folders(paths[0]) if len(paths) == 1 else []
    if folders:
        jobs = [
            (
                [folder],
                Path(out_dir) / folder.name,
                project_trace(trace_file, folder.name) if trace_file else None,
            )
            for folder in folders
        ]
        log.info("%d projects in %s: each converted on its own", len(folders), paths[0])
    else:
        jobs = [(list(paths), Path(out_dir), trace_file)]
    traces = [_existing_trace(trace, bool(folders)) for _, _, trace in jobs]  # all, before any reading
    outputs: list[tuple[Path, str]] = []
    for (sources, target, _), forward in zip(jobs, traces, strict=True):
        project = _rosmod_project(sources, forward, roots, warnings)
        for relative, text in render_project(project, warnings=warnings).items():
            outputs.append((fileio.safe_join(target, *relative.split("/")), text))
    return fileio.write_files(outputs)

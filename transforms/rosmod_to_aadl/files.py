"""ROSMOD project files → AADL files (``rosaadl convert``): :func:`convert_project_files`.

It reads and writes files, so it belongs to the workflow layer (``rosaadl/workflow/convert.py``),
where it moves; until then it is kept here unchanged, with the conversion it calls reserving the
library's unit names, as the workflow's callers of :func:`.conversion.rosmod_to_aadl` do.
"""

from __future__ import annotations

import logging
import os
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic
from rosaadl.transforms.rosmod_to_aadl import conversion
from rosaadl.transforms.rosmod_to_aadl.conversion import ConversionResult
from rosaadl.transforms.rosmod_to_aadl.names import NameScope, aadl_identifier

__all__ = ["convert_project_files"]

log = logging.getLogger(__name__)


def rosmod_to_aadl(project: EObject, *, trace: bool = True) -> ConversionResult:
    """:func:`.conversion.rosmod_to_aadl` with the library's unit names reserved."""
    from rosaadl.workflow.workspace import library_unit_names

    return conversion.rosmod_to_aadl(project, trace=trace, reserved_units=library_unit_names())


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
    from rosaadl import fileio
    from rosaadl import model as _model
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
        result = rosmod_to_aadl(item, trace=trace_file is not None)
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

"""``rosaadl convert``: ROSMOD projects to AADL, and AADL back to a ROSMOD project, with a trace."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import Options, Report, pass_options
from rosaadl.errors import Diagnostic, RosaadlError, UsageError
from rosaadl.formats import expand_errors

__all__ = ["command"]


@click.command("convert")
@click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option(
    "--to",
    "target",
    type=click.Choice(["aadl", "rosmod"]),
    default="aadl",
    show_default=True,
    help="aadl: a ROSMOD project (folder, .rml, .webgmex, or a ROSMOD model .xmi/.json such as "
    "import ros2-package writes, or ROS 2 package folders) to AADL packages; rosmod: AADL to a "
    "ROSMOD v0.3 project.",
)
@click.option("-o", "--output", "out", type=click.Path(path_type=Path), required=True, help="Output folder.")
@click.option(
    "--project", help="The project to take from a .webgmex archive (default: each, in a subfolder)."
)
@click.option(
    "--trace",
    "trace_file",
    type=click.Path(path_type=Path),
    help="Trace file (.xmi or .json): written by ROSMOD -> AADL, read by AADL -> ROSMOD to keep names "
    "(several projects: one per project, <stem>_<project folder><suffix>).",
)
@click.option("--root", "roots", multiple=True, help="AADL -> ROSMOD: system implementation(s) to convert.")
@pass_options
def command(
    options: Options,
    inputs: tuple[Path, ...],
    target: str,
    out: Path,
    project: str | None,
    trace_file: Path | None,
    roots: tuple[str, ...],
) -> None:
    """Convert ROSMOD ⇄ AADL."""
    for path in inputs:
        if not path.exists():
            raise UsageError("no such file or folder", file=str(path))
    report = Report()
    warnings: list[Diagnostic] = []
    try:
        if target == "aadl":
            if len(inputs) != 1:
                raise UsageError("give one ROSMOD project (a folder, an .rml file or a .webgmex archive)")
            from rosaadl.workflow.convert import convert_project_files

            written = convert_project_files(
                inputs[0], out, project=project, trace_file=trace_file, warnings=warnings
            )
        else:
            from rosaadl.workflow.convert import convert_aadl_files

            written = convert_aadl_files(
                list(inputs), out, trace_file=trace_file, roots=list(roots) or None, warnings=warnings
            )
    except UsageError:
        raise
    except RosaadlError as exc:
        for error in expand_errors(exc):
            report.error(error)
        sys.exit(report.emit(options))
    for warning in warnings:
        if warning.severity == "warning":
            report.warn(warning)
    for path in written:
        report.say(str(path))
    options.progress(f"wrote {len(written)} file(s) to {out}")
    report.data["written"] = [str(p) for p in written]
    sys.exit(report.emit(options))

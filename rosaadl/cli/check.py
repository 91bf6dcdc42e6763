"""``rosaadl check INPUT...``: read inputs with the reader that knows them and report every problem."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import Options, Report, inputs_argument, pass_options
from rosaadl.formats import check_file

__all__ = ["command"]


@click.command("check")
@inputs_argument
@click.option("--strict", is_flag=True, help="Treat what readers tolerate (unknown elements...) as errors.")
@pass_options
def command(options: Options, inputs: tuple[Path, ...], strict: bool) -> None:
    """Validate inputs: rosaadl models (.xmi/.json), AADL text, OSATE .aaxl2, Cheddar XML,
    ROSMOD projects (folders, .rml, .webgmex)."""
    report = Report()
    checked = []
    for path in inputs:
        errors, warnings = check_file(path, strict=strict)
        for error in errors:
            report.error(error)
        for warning in warnings:
            report.warn(warning)
        checked.append({"file": str(path), "errors": len(errors), "warnings": len(warnings)})
        status = "ok" if not errors else f"{len(errors)} error(s)"
        report.say(f"{path}: {status}" + (f", {len(warnings)} warning(s)" if warnings else ""))
    report.data["files"] = checked
    sys.exit(report.emit(options))

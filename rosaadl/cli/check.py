"""``rosaadl check INPUT...``: read inputs with the reader that knows them and report every problem.

AADL text given together (files and folders) is checked as one workspace, as ``instantiate``,
``analyze`` and OSATE read it, so ``rosaadl check *.aadl`` resolves the packages the files name
in each other; every other input is checked alone (:func:`rosaadl.formats.check_inputs`).
"""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import Options, Report, inputs_argument, pass_options
from rosaadl.formats import check_inputs

__all__ = ["command"]


@click.command("check")
@inputs_argument
@click.option("--strict", is_flag=True, help="Treat what readers tolerate (unknown elements...) as errors.")
@pass_options
def command(options: Options, inputs: tuple[Path, ...], strict: bool) -> None:
    """Validate inputs: rosaadl models (.xmi/.json), AADL text, OSATE .aaxl2, Cheddar XML,
    ROSMOD projects (folders, .rml, .webgmex), ROS 2 rclpy packages (folders with package.xml).
    AADL files and folders given together are one workspace: a package of one may be named from
    another."""
    report = Report()
    checked = []
    for result in check_inputs(list(inputs), strict=strict):
        errors, warnings = result.errors, result.warnings
        for error in errors:
            report.error(error)
        for warning in warnings:
            report.warn(warning)
        checked.append({"file": str(result.path), "errors": len(errors), "warnings": len(warnings)})
        status = "ok" if not errors else f"{len(errors)} error(s)"
        report.say(f"{result.path}: {status}" + (f", {len(warnings)} warning(s)" if warnings else ""))
    report.data["files"] = checked
    sys.exit(report.emit(options))

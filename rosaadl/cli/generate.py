"""``rosaadl generate rclpy INPUTS... --root Pkg::Sys.impl -o WS/src``: ROS 2 packages from the model."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import (
    Options,
    Report,
    inputs_argument,
    lenient_option,
    output_option,
    pass_options,
    root_option,
)
from rosaadl.cli.inputs import choose_instance, read_generator_inputs

__all__ = ["command"]


@click.group("generate")
def command() -> None:
    """Generate code from a model."""


@command.command("rclpy")
@inputs_argument
@root_option("The system implementation to generate for (or the instance to take).")
@output_option("The workspace's src folder (WS/src).")
@click.option("--force", is_flag=True, help="Overwrite files that carry no user-code marker.")
@click.option("--dry-run", is_flag=True, help="Say what would change; write nothing.")
@click.option(
    "--trace",
    "trace_file",
    type=click.Path(path_type=Path),
    help="A trace of renames since the last generation (user code moves with its element).",
)
@click.option("--app-name", help="Name of the application's packages (default: the root type's name).")
@click.option("--project", help="The project to take from a .webgmex archive.")
@lenient_option()
@pass_options
def generate_rclpy(
    options: Options,
    inputs: tuple[Path, ...],
    root: str | None,
    out: Path,
    force: bool,
    dry_run: bool,
    trace_file: Path | None,
    app_name: str | None,
    project: str | None,
    lenient: bool,
) -> None:
    """ament_python packages (one Node per AADL process), interfaces and launch files (inputs: AADL
    text, a rosaadl model, an .aaxl2, or a ROSMOD project converted on the way)."""
    from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace

    loaded, rosmod_trace = read_generator_inputs(inputs, project=project, lenient=lenient)
    instance = choose_instance(loaded, root, lenient=lenient)
    report = Report()
    result = generate_workspace(
        instance,
        out,
        force=force,
        dry_run=dry_run,
        trace=trace_file,
        rosmod_trace=rosmod_trace,
        options=GenerationOptions(app_name=app_name),
    )
    report.note([*loaded.warnings, *result.diagnostics])
    counts: dict[str, int] = {}
    for change in result.changes:
        counts[change.action] = counts.get(change.action, 0) + 1
        if change.action in ("create", "update", "skip"):
            report.say(f"{change.action:9} {change.path}" + (f"  ({change.reason})" if change.reason else ""))
    for move in result.orphaned:
        report.say(f"orphaned  {move.name}")
    verb = "would write" if dry_run else "wrote"
    options.progress(f"{verb} {counts.get('create', 0) + counts.get('update', 0)} file(s) to {out}")
    report.data.update(
        {
            "output": str(out),
            "dry_run": dry_run,
            "changes": counts,
            "moved": len(result.moved),
            "orphaned": [m.name for m in result.orphaned],
        }
    )
    sys.exit(report.emit(options))

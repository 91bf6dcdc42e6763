"""``rosaadl import INPUT -o MODEL``: read another tool's file into a rosaadl model (XMI or JSON)."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl import model
from rosaadl.cli.common import Options, Report, output_option, pass_options, time_unit_option
from rosaadl.errors import UsageError
from rosaadl.formats import expand_errors, read_input

__all__ = ["command"]


@click.command("import")
@click.argument("source", type=click.Path(path_type=Path))
@output_option("Model file to write (.xmi or .json).")
@time_unit_option("What Cheddar's plain integer times are.")
@click.option("--project", help="The project to take from a .webgmex archive holding several.")
@click.option("--strict", is_flag=True, help="Treat what readers tolerate (unknown elements...) as errors.")
@pass_options
def command(
    options: Options, source: Path, out: Path, time_unit: str, project: str | None, strict: bool
) -> None:
    """Import an OSATE .aaxl2, a Cheddar .xmlv3/.xml, a ROSMOD project or .webgmex, or AADL text."""
    from rosaadl.errors import RosaadlError

    if out.suffix.lower() not in (".xmi", ".json"):
        raise UsageError("the output must be a .xmi or .json model file", file=str(out))
    report = Report()
    try:
        loaded = read_input(source, time_unit=time_unit, project=project, strict=strict)
    except UsageError:
        raise
    except RosaadlError as exc:
        for error in expand_errors(exc):
            report.error(error)
        sys.exit(report.emit(options))
    if len(loaded.roots) > 1:
        names = ", ".join(getattr(r, "name", "?") for r in loaded.roots)
        raise UsageError(
            f"the input holds several projects ({names}); choose one with --project", file=str(source)
        )
    report.note(loaded.warnings, info=True)
    written = model.save(loaded.root, out)
    options.progress(f"wrote {written}")
    report.say(f"{source} -> {written}")
    report.data.update({"input": str(source), "output": str(written), "kind": loaded.kind})
    sys.exit(report.emit(options))

"""``rosaadl export FORMAT INPUTS... -o OUT``: write a model in another tool's format."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import Options, Report, pass_options
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs

__all__ = ["command"]


@click.group("export")
def command() -> None:
    """Write AADL text, OSATE .aaxl2, Cheddar XML or ROSMOD projects."""


def _report_warnings(report: Report, warnings) -> None:
    for warning in warnings:
        (report.error if warning.severity == "error" else report.warn)(warning)


@command.command("aadl")
@click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("-o", "--output", "out", type=click.Path(path_type=Path), required=True, help="Output folder.")
@pass_options
def export_aadl(options: Options, inputs: tuple[Path, ...], out: Path) -> None:
    """AADL text: one .aadl file per package and property set of the inputs (not the library's)."""
    from rosaadl.exporters import aadl_text

    report = Report()
    loaded = read_aadl_inputs(list(inputs))
    library = {p.resolve() for p in _library_files()}
    units = [u for u in loaded.model.units if not u.sourceFile or Path(u.sourceFile).resolve() not in library]
    written = aadl_text.write_model(units, out)
    _report_warnings(report, [w for w in loaded.warnings if w.severity != "info"])
    for path in written:
        report.say(str(path))
    report.data["written"] = [str(p) for p in written]
    sys.exit(report.emit(options))


def _library_files() -> list[Path]:
    from rosaadl.importers.aadl_text import library_files

    return list(library_files())


@command.command("cheddar")
@click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--root", help="The system implementation to instantiate, or the instance to take.")
@click.option(
    "-o",
    "--output",
    "out",
    type=click.Path(path_type=Path),
    required=True,
    help="Cheddar file to write (.xmlv3 or .xml).",
)
@click.option("--cheddar-format", type=click.Choice(["2", "3"]), default="3", show_default=True)
@click.option(
    "--time-unit",
    type=click.Choice(["us", "ms"]),
    default="us",
    show_default=True,
    help="The unit of Cheddar's integer times; a time that is not a whole number is an error.",
)
@click.option("--lenient", is_flag=True, help="Instantiate subcomponents whose classifier does not resolve.")
@pass_options
def export_cheddar(
    options: Options,
    inputs: tuple[Path, ...],
    root: str | None,
    out: Path,
    cheddar_format: str,
    time_unit: str,
    lenient: bool,
) -> None:
    """Cheddar XML (v3 by default, v2 on request) of a deployed system."""
    from rosaadl.exporters import cheddar

    report = Report()
    loaded = read_aadl_inputs(list(inputs), time_unit=time_unit)
    instance = choose_instance(loaded, root, lenient=lenient)
    notes: list = []
    written = cheddar.write_cheddar(
        instance, out, cheddar_format=int(cheddar_format), time_unit=time_unit, diagnostics=notes
    )
    _report_warnings(report, [w for w in loaded.warnings + notes if w.severity != "info"])
    options.progress(f"wrote {written}")
    report.say(f"{instance.name} -> {written}")
    report.data.update({"instance": instance.name, "output": str(written)})
    sys.exit(report.emit(options))


@command.command("aaxl2")
@click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--root", help="The system implementation to instantiate, or the instance to take.")
@click.option(
    "-o",
    "--output",
    "out",
    type=click.Path(path_type=Path),
    required=True,
    help="Output folder: instances/<Root>_Instance.aaxl2 and the .aadl files it refers to.",
)
@click.option("--lenient", is_flag=True, help="Instantiate subcomponents whose classifier does not resolve.")
@pass_options
def export_aaxl2(
    options: Options, inputs: tuple[Path, ...], root: str | None, out: Path, lenient: bool
) -> None:
    """OSATE instance model (.aaxl2) with its AADL sidecars, as OSATE itself writes it."""
    from rosaadl.exporters import aaxl2

    report = Report()
    loaded = read_aadl_inputs(list(inputs))
    instance = choose_instance(loaded, root, lenient=lenient)
    notes: list = []
    written = aaxl2.write_aaxl2(instance, out, warnings=notes)
    _report_warnings(report, [w for w in loaded.warnings + notes if w.severity != "info"])
    options.progress(f"wrote {written}")
    report.say(f"{instance.name} -> {written}")
    report.data.update({"instance": instance.name, "output": str(written)})
    sys.exit(report.emit(options))

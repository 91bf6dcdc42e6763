"""``rosaadl analyze INPUTS... --root Pkg::Sys.impl``: CPU/MIPS, budgets, bus load, schedulability,
simulation, latency and deployment search on a deployed system."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import click

from rosaadl.cli.common import (
    EXIT_ERRORS,
    EXIT_OK,
    Options,
    Report,
    inputs_argument,
    lenient_option,
    output_option,
    pass_options,
    root_option,
    time_unit_option,
)
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs

__all__ = ["command"]


class _AnalysesOption(click.Option):
    """``--only``, whose help lists the analyses registered when the help is shown."""

    def get_help_record(self, ctx: click.Context) -> tuple[str, str] | None:
        from rosaadl.analysis.registry import analyses

        known = analyses()
        others = [a.name for a in known if not a.default]
        self.help = f"Comma-separated analyses: {','.join(a.name for a in known)} (default: all" + (
            f" but {','.join(others)})." if others else ")."
        )
        return super().get_help_record(ctx)


@click.command("analyze")
@inputs_argument
@root_option()
@click.option("--only", cls=_AnalysesOption)
@output_option("Folder for the OSATE-style CSV reports.", required=False)
@time_unit_option()
@lenient_option()
@click.option(
    "--html",
    "html_dir",
    type=click.Path(path_type=Path),
    help="Folder for the HTML report (report.html with plots, and report.json).",
)
@click.option(
    "--latency-preferences",
    "latency_code",
    default="AS-MF-ET-EQ",
    show_default=True,
    metavar="XX-MF|PE-ET|DL-EQ|FQ",
    help="OSATE's latency preferences (the system kind pair is ignored: both are reported).",
)
@click.option(
    "--compare",
    "measurements_file",
    type=click.Path(path_type=Path),
    help="A measured run (measurements.json): every prediction beside its measurement, error in %.",
)
@pass_options
def command(
    options: Options,
    inputs: tuple[Path, ...],
    root: str | None,
    only: str | None,
    out: Path | None,
    time_unit: str,
    lenient: bool,
    html_dir: Path | None,
    latency_code: str,
    measurements_file: Path | None,
) -> None:
    """Analyse a deployment; exit 1 when an analysis finds an overload or a missed deadline.
    Inputs may be AADL text, a rosaadl model, an OSATE .aaxl2 or a Cheddar file."""
    from rosaadl.analysis.latency import latency_preferences
    from rosaadl.analysis.report import parse_only, run_analyses

    selected = parse_only(only)  # a bad --only is a usage error before any reading
    preferences = latency_preferences(latency_code)
    measurements = None
    if measurements_file is not None:
        from rosaadl.errors import ParseError
        from rosaadl.importers.measurements import read_measurements

        try:
            measurements = read_measurements(measurements_file)
        except ParseError as exc:  # every problem of the file, located, and nothing written
            refused = Report()
            refused.note(exc.errors or [exc])
            sys.exit(refused.emit(options))
        selected = parse_only([*selected, "compare"])
    loaded = read_aadl_inputs(list(inputs), time_unit=time_unit, lenient=lenient)
    instance = choose_instance(loaded, root, lenient=lenient)
    if measurements is not None and measurements.period_scale != 1:
        from rosaadl.transforms.time_scale import scale_periods

        scale_periods(instance, measurements.period_scale)
        options.progress(
            f"the model's periods × {measurements.period_scale:g}, as the measured run scaled them"
        )
    options.progress(f"analysing {instance.name}: {', '.join(selected)}")
    report = run_analyses(instance, selected, latency_preferences=preferences, measurements=measurements)
    written = report.write_csv(out) if out is not None else []
    pages = []
    if html_dir is not None:
        from rosaadl.exporters.report import write_report

        pages = write_report(instance, report, html_dir)
    if options.format == "json":
        document = json.loads(report.to_json())
        reading = [w.as_dict() for w in loaded.warnings if w.severity == "warning"]
        document["warnings"] = reading + document.get("warnings", [])
        if written:
            document["csv"] = [str(p) for p in written]
        if pages:
            document["html"] = [str(p) for p in pages]
        click.echo(json.dumps(document, indent=2))
    else:
        click.echo(report.text())
        for path in [*written, *pages]:
            options.progress(f"wrote {path}")
    sys.exit(EXIT_OK if report.ok else EXIT_ERRORS)

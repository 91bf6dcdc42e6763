"""``rosaadl instantiate INPUTS... --root Pkg::Sys.impl -o OUT``: the deployed system as an instance model."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl import model
from rosaadl.cli.common import Options, Report, pass_options
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs
from rosaadl.errors import UsageError

__all__ = ["command"]


@click.command("instantiate")
@click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))
@click.option("--root", required=True, help="The root system implementation (Pkg::Sys.impl).")
@click.option(
    "-o",
    "--output",
    "out",
    type=click.Path(path_type=Path),
    required=True,
    help="Model file to write (.xmi or .json): the declarative units and the instance.",
)
@click.option(
    "--lenient",
    is_flag=True,
    help="Instantiate subcomponents whose classifier does not resolve without it (a warning), as OSATE does.",
)
@click.option(
    "--compat",
    type=click.Choice(["current", "osate-2.0"]),
    default="current",
    show_default=True,
    help="Connection rules of current OSATE, or of OSATE 2.0 (files with systemImplementation).",
)
@pass_options
def command(
    options: Options, inputs: tuple[Path, ...], root: str, out: Path, lenient: bool, compat: str
) -> None:
    """Instantiate a system implementation of AADL text (folders are searched for .aadl files;
    the component library is always on the path)."""
    if out.suffix.lower() not in (".xmi", ".json"):
        raise UsageError("the output must be a .xmi or .json model file", file=str(out))
    report = Report()
    loaded = read_aadl_inputs(list(inputs))
    instance = choose_instance(loaded, root, lenient=lenient, compatibility=compat)
    for warning in loaded.warnings:
        if warning.severity == "error":
            report.error(warning)
        elif warning.severity == "warning":
            report.warn(warning)
    counts = {
        "components": 1 + sum(1 for o in instance.eAllContents() if o.eClass.name == "ComponentInstance"),
        "features": sum(1 for o in instance.eAllContents() if o.eClass.name == "FeatureInstance"),
        "connections": sum(1 for o in instance.eAllContents() if o.eClass.name == "ConnectionInstance"),
    }
    written = model.save(loaded.model, out)
    options.progress(f"wrote {written}")
    report.say(
        f"{instance.name}: {counts['components']} components, {counts['features']} features, "
        f"{counts['connections']} connections -> {written}"
    )
    report.data.update(
        {"instance": instance.name, "root": instance.classifier, "output": str(written), **counts}
    )
    sys.exit(report.emit(options))

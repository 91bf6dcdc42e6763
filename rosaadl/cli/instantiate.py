"""``rosaadl instantiate INPUTS... --root Pkg::Sys.impl -o OUT``: the deployed system as an instance model."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl import model
from rosaadl.cli.common import (
    Options,
    Report,
    inputs_argument,
    lenient_option,
    output_option,
    pass_options,
    root_option,
)
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs
from rosaadl.errors import UsageError

__all__ = ["command"]


@click.command("instantiate")
@inputs_argument
@root_option("The root system implementation (Pkg::Sys.impl).", required=True)
@output_option("Model file to write (.xmi or .json): the declarative units and the instance.")
@lenient_option(
    "Instantiate subcomponents whose classifier does not resolve without it (a warning), as OSATE does."
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
    loaded = read_aadl_inputs(list(inputs), lenient=lenient)
    instance = choose_instance(loaded, root, lenient=lenient, compatibility=compat)
    report.note(loaded.warnings)
    counts = {
        "components": len(model.component_instances(instance)),
        "features": sum(1 for o in model.walk(instance) if model.is_a(o, "FeatureInstance")),
        "connections": sum(1 for o in model.walk(instance) if model.is_a(o, "ConnectionInstance")),
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

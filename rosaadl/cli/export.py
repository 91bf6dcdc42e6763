"""``rosaadl export FORMAT INPUTS... -o OUT``: write a model in another tool's format.

One sub-command per writer of :func:`rosaadl.formats.writers`, made from its entry: a writer of
declarative AADL gets the packages of the inputs (not the library's), a writer of instances gets
the instance ``--root`` names (instantiated when the inputs are AADL text).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

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
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs
from rosaadl.formats import Writer, writers

__all__ = ["command"]


@click.group("export")
def command() -> None:
    """Write AADL text, OSATE .aaxl2 or Cheddar XML."""


def _library_files() -> set[Path]:
    from rosaadl.importers.aadl_text import library_files

    return {p.resolve() for p in library_files()}


def _export(options: Options, item: Writer, inputs: tuple[Path, ...], out: Path, **given: Any) -> None:
    report = Report()
    root = given.pop("root", None)
    lenient = given.pop("lenient", False)
    reading = {o.name: given[o.name] for o in item.options if o.reading}
    loaded = read_aadl_inputs(list(inputs), lenient=lenient, **reading)
    notes: list = []
    if item.takes == "units":
        library = _library_files()
        units = [
            u for u in loaded.model.units if not u.sourceFile or Path(u.sourceFile).resolve() not in library
        ]
        written = item.write(units, out, notes, **given)
        report.note([*loaded.warnings, *notes])
        for path in written:
            report.say(str(path))
        report.data["written"] = [str(p) for p in written]
    else:
        instance = choose_instance(loaded, root, lenient=lenient)
        main, *_ = item.write(instance, out, notes, **given)
        report.note([*loaded.warnings, *notes])
        options.progress(f"wrote {main}")
        report.say(f"{instance.name} -> {main}")
        report.data.update({"instance": instance.name, "output": str(main)})
    sys.exit(report.emit(options))


def _subcommand(item: Writer) -> click.Command:
    def run(options: Options, inputs: tuple[Path, ...], out: Path, **given: Any) -> None:
        _export(options, item, inputs, out, **given)

    decorators: list[Callable[[Any], Any]] = [inputs_argument]
    if item.takes == "instance":
        decorators.append(root_option())
    decorators.append(output_option(item.output))
    for option in item.options:
        decorators.append(
            click.option(
                option.flag,
                option.name,
                type=click.Choice(list(option.choices)),
                default=option.default,
                show_default=True,
                help=option.help or None,
            )
        )
    if item.takes == "instance":
        decorators.append(lenient_option())
    function: Any = pass_options(run)
    for decorator in reversed(decorators):
        function = decorator(function)
    return click.command(item.name, help=item.description)(function)


for _writer in writers():
    command.add_command(_subcommand(_writer))

"""``rosaadl convert``: registered now, implemented by the ROSMOD issue."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("convert", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: comes with the ROSMOD issue."""
    not_yet("convert", "comes with the ROSMOD issue")

"""``rosaadl export FORMAT MODEL``: write a model in another tool's format (formats land per issue)."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("export", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: aadl, aaxl2, cheddar and rosmod writers come with their issues."""
    not_yet("export", "comes with the AADL text, OSATE, Cheddar and ROSMOD issues")

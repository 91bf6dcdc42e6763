"""``rosaadl import``: registered now, implemented by the OSATE .aaxl2 and Cheddar issues."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("import", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: comes with the OSATE .aaxl2 and Cheddar issues."""
    not_yet("import", "comes with the OSATE .aaxl2 and Cheddar issues")

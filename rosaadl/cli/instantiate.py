"""``rosaadl instantiate``: registered now, implemented by the AADL text issue."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("instantiate", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: comes with the AADL text issue."""
    not_yet("instantiate", "comes with the AADL text issue")

"""``rosaadl analyze``: registered now, implemented by the analyses issue."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("analyze", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: comes with the analyses issue."""
    not_yet("analyze", "comes with the analyses issue")

"""``rosaadl library``: registered now, implemented by the component library issue."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("library", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: comes with the component library issue."""
    not_yet("library", "comes with the component library issue")

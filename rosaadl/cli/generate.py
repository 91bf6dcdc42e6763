"""``rosaadl generate``: registered now, implemented by the rclpy generation issue."""

from __future__ import annotations

import click

from rosaadl.cli.common import not_yet

__all__ = ["command"]


@click.command("generate", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def command(args: tuple[str, ...]) -> None:
    """Not implemented yet: comes with the rclpy generation issue."""
    not_yet("generate", "comes with the rclpy generation issue")

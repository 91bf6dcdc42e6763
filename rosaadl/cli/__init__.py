"""The ``rosaadl`` command line: one module per verb, shared options and exit codes in ``common``."""

from __future__ import annotations

import logging
import sys
import traceback

import click

from rosaadl import __version__
from rosaadl.cli.common import (
    DEBUG_HELP,
    EXIT_ERRORS,
    EXIT_INTERNAL,
    EXIT_USAGE,
    FORMAT_HELP,
    FORMATS,
    Options,
    VerbGroup,
)
from rosaadl.errors import RosaadlError, UsageError

__all__ = ["cli", "main"]


@click.group(cls=VerbGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.option(
    "--format",
    "fmt",
    type=click.Choice(FORMATS),
    default="text",
    show_default=True,
    help=f"{FORMAT_HELP} Also accepted after the verb.",
)
@click.option("--debug", is_flag=True, help=f"{DEBUG_HELP} Also accepted after the verb.")
@click.option("-v", "--verbose", count=True, help="More progress output on stderr (repeatable).")
@click.option("-q", "--quiet", count=True, help="Less output on stderr (repeatable).")
@click.version_option(__version__, prog_name="rosaadl")
@click.pass_context
def cli(ctx: click.Context, fmt: str, debug: bool, verbose: int, quiet: int) -> None:
    """rosaadl: ROSMOD, AADL, OSATE, Cheddar and ROS 2 from one command line."""
    ctx.obj = Options(format=fmt, debug=debug, verbosity=verbose - quiet)
    # warnings reach the user through each verb's report; -v shows the library log as well
    level = logging.ERROR - 10 * (verbose - quiet)
    logging.basicConfig(
        level=max(logging.DEBUG, min(logging.CRITICAL, level)),
        stream=sys.stderr,
        format="%(levelname)s %(name)s: %(message)s",
    )


def _register() -> None:
    from rosaadl.cli import analyze, check, convert, demo, export, generate, import_, instantiate, library

    for module in (check, import_, convert, instantiate, analyze, export, generate, library, demo):
        cli.add_command(module.command)


_register()


def main(argv: list[str] | None = None) -> int:
    """Entry point: runs the group and maps outcomes to exit codes (never an unasked traceback)."""
    debug = "--debug" in (argv if argv is not None else sys.argv[1:])
    try:
        result = cli.main(args=argv, prog_name="rosaadl", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except click.exceptions.Abort:
        click.echo("aborted", err=True)
        return EXIT_ERRORS
    except click.exceptions.ClickException as exc:  # usage errors: unknown option, missing argument
        exc.show()
        return EXIT_USAGE if isinstance(exc, click.UsageError) else exc.exit_code
    except UsageError as exc:
        click.echo(f"error: {exc}", err=True)
        return EXIT_USAGE
    except RosaadlError as exc:
        click.echo(f"error: {exc}", err=True)
        return EXIT_ERRORS
    except SystemExit as exc:
        return exc.code if isinstance(exc.code, int) else EXIT_ERRORS
    except KeyboardInterrupt:
        click.echo("interrupted", err=True)
        return 130
    except Exception as exc:  # noqa: BLE001 - the one place internal errors are turned into exit 3
        if debug:
            traceback.print_exc()
        else:
            click.echo(
                f"internal error: {exc.__class__.__name__}: {exc} (run with --debug for the traceback)",
                err=True,
            )
        return EXIT_INTERNAL
    return result if isinstance(result, int) else 0

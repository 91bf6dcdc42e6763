"""The ``rosaadl`` command line: one module per verb, shared options and exit codes in ``common``."""

from __future__ import annotations

import contextlib
import logging
import signal
import sys
import threading
import traceback
from collections.abc import Iterator

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

__all__ = ["cli", "main", "Interrupted"]

_STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(BaseException):
    """SIGINT or SIGTERM arrived: unwinds like ``KeyboardInterrupt``, so every write in
    progress removes its temporaries, and the command ends with ``128 + signal number``."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _interrupt(signum: int, _frame: object) -> None:
    # a second signal while the first unwinds must not cut the clean-up short
    for other in _STOP_SIGNALS:
        signal.signal(other, signal.SIG_IGN)
    raise Interrupted(signum)


@contextlib.contextmanager
def _stop_signals_interrupt() -> Iterator[None]:
    """SIGINT and SIGTERM raise :class:`Interrupted` for the block (main thread only), then
    the handlers in place before are put back."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {signum: signal.getsignal(signum) for signum in _STOP_SIGNALS}
    for signum in _STOP_SIGNALS:
        signal.signal(signum, _interrupt)
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler if handler is not None else signal.SIG_DFL)


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
    from rosaadl.cli import (
        analyze,
        check,
        convert,
        demo,
        deploy,
        export,
        generate,
        import_,
        instantiate,
        library,
        run,
    )

    for module in (check, import_, convert, instantiate, analyze, deploy, export, generate, run, library, demo):
        cli.add_command(module.command)


_register()


def main(argv: list[str] | None = None) -> int:
    """Entry point: runs the group and maps outcomes to exit codes (never an unasked traceback)."""
    debug = "--debug" in (argv if argv is not None else sys.argv[1:])
    try:
        with _stop_signals_interrupt():
            result = cli.main(args=argv, prog_name="rosaadl", standalone_mode=False)
    except Interrupted as exc:
        click.echo(f"interrupted ({exc}): no output file was left half-written", err=True)
        return 128 + exc.signum
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

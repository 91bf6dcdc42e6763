"""What every verb shares: the run options, the options several verbs take, the report it prints,
and the exit-code policy.

Exit codes: 0 ok, 1 model/validation/analysis errors, 2 usage, 3 internal error.
With ``--format json`` stdout carries exactly one JSON document::

    {"ok": bool, "errors": [{"message", "file", "line", "column", "path", ...}], "warnings": [...], ...}

Progress and logs go to stderr; data goes to stdout or files.

The run options ``--format`` and ``--debug`` go before the verb (``rosaadl --format json check
x``) or after it (``rosaadl check x --format json``), as users of ``git`` and ``ros2`` type
them: :class:`VerbGroup` gives every verb and sub-verb its own copy of them
(:func:`accept_run_options`); given in both places, the one after the verb wins.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

import click

from rosaadl.errors import Diagnostic, RosaadlError

__all__ = [
    "Options",
    "Report",
    "VerbGroup",
    "accept_run_options",
    "EXIT_OK",
    "EXIT_ERRORS",
    "EXIT_USAGE",
    "EXIT_INTERNAL",
    "pass_options",
    "inputs_argument",
    "output_option",
    "root_option",
    "lenient_option",
    "time_unit_option",
    "FORMATS",
    "FORMAT_HELP",
    "DEBUG_HELP",
]

EXIT_OK = 0
EXIT_ERRORS = 1
EXIT_USAGE = 2
EXIT_INTERNAL = 3


@dataclass
class Options:
    """Global options of one invocation (``--format``, ``--debug``, verbosity)."""

    format: str = "text"
    debug: bool = False
    verbosity: int = 0

    def progress(self, message: str) -> None:
        if self.verbosity >= 0:
            click.echo(message, err=True)


pass_options = click.make_pass_decorator(Options, ensure=True)

FORMATS = ("text", "json")
FORMAT_HELP = "Output format of results on stdout."
DEBUG_HELP = "Show tracebacks of internal errors."


def _given_format(ctx: click.Context, _param: click.Parameter, value: str | None) -> None:
    if value is not None:
        ctx.ensure_object(Options).format = value


def _given_debug(ctx: click.Context, _param: click.Parameter, value: bool) -> None:
    if value:
        ctx.ensure_object(Options).debug = True


def _run_options() -> list[click.Option]:
    """``--format`` and ``--debug`` as a verb takes them: they set the invocation's
    :class:`Options` (given to the verb by :data:`pass_options`) and are not passed themselves."""
    return [
        click.Option(
            ["--format", "run_format"],
            type=click.Choice(FORMATS),
            default=None,
            expose_value=False,
            callback=_given_format,
            help=f"{FORMAT_HELP} [default: text]",
        ),
        click.Option(
            ["--debug", "run_debug"],
            is_flag=True,
            default=False,
            expose_value=False,
            callback=_given_debug,
            help=DEBUG_HELP,
        ),
    ]


def accept_run_options(command: click.Command) -> click.Command:
    """Let ``command``, and every sub-command of it when it is a group, take ``--format`` and
    ``--debug`` after its name; a command that already takes them is left as it is."""
    taken = {opt for param in command.params for opt in getattr(param, "opts", ())}
    command.params.extend(option for option in _run_options() if option.opts[0] not in taken)
    if isinstance(command, click.Group):
        for sub in command.commands.values():
            accept_run_options(sub)
    return command


class VerbGroup(click.Group):
    """The ``rosaadl`` group: each verb added to it takes the run options after its name too."""

    def add_command(self, cmd: click.Command, name: str | None = None) -> None:
        super().add_command(accept_run_options(cmd), name)


F = TypeVar("F", bound=Callable[..., Any])


def inputs_argument(function: F) -> F:
    """``INPUTS...``: one or more files or folders."""
    return click.argument("inputs", nargs=-1, required=True, type=click.Path(path_type=Path))(function)


def output_option(help: str, *, required: bool = True) -> Callable[[F], F]:
    """``-o/--output OUT`` (the parameter ``out``); ``help`` says whether it is a file or a folder."""
    return click.option(
        "-o", "--output", "out", type=click.Path(path_type=Path), required=required, help=help
    )


def root_option(
    help: str = "The system implementation to instantiate, or the instance to take.",
    *,
    required: bool = False,
) -> Callable[[F], F]:
    """``--root Pkg::Sys.impl``."""
    return click.option("--root", required=required, help=help)


def lenient_option(
    help: str = "Instantiate subcomponents whose classifier does not resolve.",
) -> Callable[[F], F]:
    """``--lenient``: keep going where a classifier does not resolve (a warning), as OSATE does."""
    return click.option("--lenient", is_flag=True, help=help)


def time_unit_option(
    help: str = "What Cheddar's plain integer times are (Cheddar inputs).",
) -> Callable[[F], F]:
    """``--time-unit us|ms``: the unit of Cheddar's integer times."""
    return click.option(
        "--time-unit", type=click.Choice(["us", "ms"]), default="us", show_default=True, help=help
    )


def _diag_dict(item: RosaadlError | Diagnostic) -> dict[str, Any]:
    data = item.as_dict()
    data.setdefault("severity", "error" if isinstance(item, RosaadlError) else item.severity)
    return data


@dataclass
class Report:
    """The outcome of a verb: errors, warnings, and verb-specific data; printed once at the end."""

    errors: list[RosaadlError | Diagnostic] = field(default_factory=list)
    warnings: list[RosaadlError | Diagnostic] = field(default_factory=list)
    data: dict[str, Any] = field(default_factory=dict)
    lines: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.errors

    def error(self, item: RosaadlError | Diagnostic) -> None:
        self.errors.append(item)

    def warn(self, item: RosaadlError | Diagnostic) -> None:
        self.warnings.append(item)

    def note(self, items: Iterable[RosaadlError | Diagnostic], *, info: bool = False) -> None:
        """Findings of a reader, transformation or writer: errors as errors, warnings as warnings,
        information left out (kept as warnings when ``info``)."""
        for item in items:
            severity = "error" if isinstance(item, RosaadlError) else item.severity
            if severity == "error":
                self.error(item)
            elif severity == "warning" or info:
                self.warn(item)

    def say(self, line: str) -> None:
        self.lines.append(line)

    def as_json(self) -> dict[str, Any]:
        return {
            "ok": self.ok,
            "errors": [_diag_dict(e) for e in self.errors],
            "warnings": [_diag_dict(w) for w in self.warnings],
            **self.data,
        }

    def emit(self, options: Options) -> int:
        if options.format == "json":
            click.echo(json.dumps(self.as_json(), indent=2, sort_keys=False, default=str))
        else:
            for line in self.lines:
                click.echo(line)
            if options.verbosity >= 0:
                for warning in self.warnings:
                    click.echo(
                        f"warning: {warning}" if isinstance(warning, RosaadlError) else str(warning), err=True
                    )
            for error in self.errors:
                click.echo(f"error: {error}" if isinstance(error, RosaadlError) else str(error), err=True)
        return EXIT_OK if self.ok else EXIT_ERRORS

"""The error collection of one ROSMOD import run: :class:`ImportContext` and :class:`RosmodImportError`.

A reader does not stop at the first problem: it records every located error and warning of a
run in an :class:`ImportContext` and raises them together, as one :class:`RosmodImportError`,
once it has read all it could. The textual and the WebGME readers share both.
"""

from __future__ import annotations

import logging

from rosaadl.errors import CollectedErrors, Diagnostic, ImportFormatError, Location, RosaadlError

__all__ = ["RosmodImportError", "ImportContext"]

_log = logging.getLogger(__package__)


class RosmodImportError(CollectedErrors, ImportFormatError):
    """One or more located problems in a ROSMOD project; ``errors`` lists every one of them."""

    stage = "import"

    def diagnostics(self) -> list[Diagnostic]:
        return [e.as_diagnostic() for e in self.errors]


class ImportContext:
    """Errors and warnings of one import run (no global state).

    Warnings are logged (on ``log``, the reader's logger) and appended to ``warnings`` when it
    is a list; ``strict`` is the reader's strict mode, for readers that have one.
    """

    def __init__(
        self, warnings: list[Diagnostic] | None, strict: bool = False, *, log: logging.Logger = _log
    ) -> None:
        self.errors: list[RosaadlError] = []
        self.warnings = warnings
        self.strict = strict
        self.log = log

    def error(self, exc: RosaadlError) -> None:
        """Record ``exc``; an error that stands for several (``CollectedErrors``) adds each of them."""
        if isinstance(exc, CollectedErrors):
            self.errors.extend(exc.errors)
        else:
            self.errors.append(exc)

    def warn(
        self,
        message: str,
        file: str | None = None,
        line: int | None = None,
        column: int | None = None,
        path: str | None = None,
    ) -> None:
        diag = Diagnostic("warning", message, Location(file=file, line=line, column=column, path=path))
        self.log.warning("%s", diag)
        if self.warnings is not None:
            self.warnings.append(diag)

    def raise_if_errors(self) -> None:
        if self.errors:
            raise RosmodImportError(self.errors)

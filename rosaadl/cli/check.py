"""``rosaadl check FILE...``: validate input files with the reader that knows them."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import Options, Report, pass_options
from rosaadl.errors import Diagnostic, RosaadlError, UsageError
from rosaadl.formats import check_file

__all__ = ["command"]


@click.command("check")
@click.argument("files", nargs=-1, required=True, type=click.Path(path_type=Path))
@pass_options
def command(options: Options, files: tuple[Path, ...]) -> None:
    """Validate model files (our XMI/JSON models; more formats as readers land)."""
    report = Report()
    checked = []
    for path in files:
        if not path.exists():
            raise UsageError("no such file", file=str(path))
        findings = check_file(path)
        for finding in findings:
            severity = finding.severity if isinstance(finding, Diagnostic) else "error"
            (report.warn if severity == "warning" else report.error)(finding)
        errors = sum(1 for f in findings if not (isinstance(f, Diagnostic) and f.severity != "error"))
        checked.append({"file": str(path), "errors": errors})
        report.say(f"{path}: {'ok' if errors == 0 else f'{errors} error(s)'}")
    report.data["files"] = checked
    sys.exit(report.emit(options))


_ = RosaadlError  # re-exported for type checkers of verb modules

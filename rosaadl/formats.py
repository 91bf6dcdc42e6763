"""Which reader handles which input: the one table ``check``, ``import`` and friends consult.

Each importer adds itself here as it lands; a file no reader knows is a usage error.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from rosaadl.errors import Diagnostic, RosaadlError, UsageError

__all__ = ["Reader", "readers", "reader_for", "check_file"]


@dataclass(frozen=True)
class Reader:
    """A file format rosaadl reads: how to recognise it and how to check it."""

    name: str
    suffixes: tuple[str, ...]
    check: Callable[[Path], list[Diagnostic]]  # raises RosaadlError on a fatal problem
    description: str = ""


def _check_model_file(path: Path) -> list[Diagnostic]:
    from rosaadl import model
    from rosaadl.validation import validate

    root = model.load(path)
    return validate(root, str(path))


def readers() -> tuple[Reader, ...]:
    return (
        Reader("model-xmi", (".xmi",), _check_model_file, "a rosaadl model saved as XMI"),
        Reader("model-json", (".json",), _check_model_file, "a rosaadl model saved as JSON"),
    )


def reader_for(path: Path) -> Reader:
    suffix = path.suffix.lower()
    for reader in readers():
        if suffix in reader.suffixes:
            return reader
    known = ", ".join(sorted({s for r in readers() for s in r.suffixes}))
    raise UsageError(f"no reader for {path.name!r} (known file types: {known})", file=str(path))


def check_file(path: Path) -> list[Diagnostic | RosaadlError]:
    """Check one file; fatal problems come back as the raised error, not as an exception."""
    reader = reader_for(path)
    try:
        return list(reader.check(path))
    except RosaadlError as exc:
        return [exc]

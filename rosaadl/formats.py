"""Which reader handles which input: the one table ``check``, ``import`` and friends consult.

Each format says how to recognise an input (file suffix, or a folder test), how to read it into
one of our models, and what that model is. Reading returns a :class:`Loaded`; problems are
raised as located :class:`~rosaadl.errors.RosaadlError`\\ s (a reader that collects several
raises one error whose ``errors`` attribute lists them all).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, RosaadlError, UsageError

__all__ = ["Loaded", "Reader", "readers", "reader_for", "read_input", "check_file", "expand_errors"]


@dataclass
class Loaded:
    """What a reader produced: the root(s) of our models and the warnings met on the way."""

    roots: list[EObject]
    warnings: list[Diagnostic] = field(default_factory=list)
    kind: str = "model"  # "aadl" | "rosmod" | "model"

    @property
    def root(self) -> EObject:
        return self.roots[0]


@dataclass(frozen=True)
class Reader:
    """A format rosaadl reads."""

    name: str
    suffixes: tuple[str, ...]
    read: Callable[..., Loaded]
    description: str = ""
    folder: Callable[[Path], bool] | None = None  # recognises a folder input


def _read_model_file(path: Path, **_: Any) -> Loaded:
    from rosaadl import model
    from rosaadl.validation import validate

    root = model.load(path)
    problems = validate(root, str(path))
    if problems:
        raise _Collected(problems)
    kind = "rosmod" if root.eClass.ePackage.name == "rosmod" else "aadl"
    return Loaded([root], kind=kind)


def _read_aadl(path: Path, **_: Any) -> Loaded:
    from rosaadl.importers import aadl_text

    warnings: list[Diagnostic] = []
    root = aadl_text.read_files([path], warnings=warnings)
    return Loaded([root], warnings, kind="aadl")


def _read_aaxl2(path: Path, *, strict: bool = False, **_: Any) -> Loaded:
    from rosaadl.importers import aaxl2

    result = aaxl2.read_aaxl2(path, strict=strict)
    return Loaded([result.model], list(result.warnings), kind="aadl")


def _read_cheddar(path: Path, *, strict: bool = False, time_unit: str = "us", **_: Any) -> Loaded:
    from rosaadl.importers import cheddar

    warnings: list[Diagnostic] = []
    root = cheddar.load_cheddar(path, time_unit=time_unit, strict=strict, diagnostics=warnings)
    return Loaded([root], warnings, kind="aadl")


def _read_rosmod_text(path: Path, *, strict: bool = False, **_: Any) -> Loaded:
    from rosaadl.importers import rosmod_text

    warnings: list[Diagnostic] = []
    project = rosmod_text.read_project(path, warnings=warnings, strict=strict)
    return Loaded([project], warnings, kind="rosmod")


def _read_webgmex(path: Path, *, project: str | None = None, **_: Any) -> Loaded:
    from rosaadl.importers import rosmod_webgme

    warnings: list[Diagnostic] = []
    projects = rosmod_webgme.read_webgmex(path, project=project, warnings=warnings)
    if not projects:
        raise UsageError(
            "the archive holds no ROSMOD project" + (f" named {project!r}" if project else ""), file=str(path)
        )
    return Loaded(list(projects), warnings, kind="rosmod")


def _is_rosmod_folder(path: Path) -> bool:
    from rosaadl.importers import rosmod_text

    return rosmod_text.is_rosmod_project(path)


def _is_aadl_folder(path: Path) -> bool:
    return any(p.suffix.lower() in (".aadl", ".aadl2") for p in path.rglob("*") if p.is_file())


def readers() -> tuple[Reader, ...]:
    """Every format, most specific first (folders: ROSMOD projects before AADL folders)."""
    return (
        Reader("model-xmi", (".xmi",), _read_model_file, "a rosaadl model saved as XMI"),
        Reader("model-json", (".json",), _read_model_file, "a rosaadl model saved as JSON"),
        Reader(
            "rosmod",
            (".rml", ".rosml"),
            _read_rosmod_text,
            "a ROSMOD textual project (folder or .rml)",
            folder=_is_rosmod_folder,
        ),
        Reader("webgme", (".webgmex",), _read_webgmex, "a WebGME ROSMOD export"),
        Reader("aaxl2", (".aaxl2",), _read_aaxl2, "an OSATE instance or declarative model"),
        Reader("cheddar", (".xmlv3", ".xml"), _read_cheddar, "a Cheddar 2 or 3 model"),
        Reader(
            "aadl",
            (".aadl", ".aadl2"),
            _read_aadl,
            "AADL text (a file or a folder of .aadl files)",
            folder=_is_aadl_folder,
        ),
    )


def reader_for(path: Path) -> Reader:
    if path.is_dir():
        for reader in readers():
            if reader.folder is not None and reader.folder(path):
                return reader
        raise UsageError("the folder holds neither a ROSMOD project nor .aadl files", file=str(path))
    suffix = path.suffix.lower()
    for reader in readers():
        if suffix in reader.suffixes:
            return reader
    known = ", ".join(sorted({s for r in readers() for s in r.suffixes}))
    raise UsageError(
        f"no reader for {path.name!r} (known file types: {known}, or a ROSMOD project folder)", file=str(path)
    )


def read_input(path: Path, **options: Any) -> Loaded:
    """Read one input with the reader its name or content calls for."""
    if not path.exists():
        raise UsageError("no such file or folder", file=str(path))
    return reader_for(path).read(path, **options)


class _Collected(RosaadlError):
    """Several located problems found by one reader, raised together."""

    def __init__(self, problems: list[RosaadlError | Diagnostic]) -> None:
        first = problems[0]
        super().__init__(
            f"{len(problems)} problem(s); first: {first}", getattr(first, "location", None), errors=problems
        )


def expand_errors(exc: RosaadlError) -> list[RosaadlError | Diagnostic]:
    """The individual located errors behind ``exc`` (readers that collect raise them together)."""
    return list(exc.errors) or [exc]


def check_file(path: Path, **options: Any) -> tuple[list[RosaadlError | Diagnostic], list[Diagnostic]]:
    """Read one input; returns (errors, warnings) instead of raising for model problems."""
    try:
        loaded = read_input(path, **options)
    except UsageError:
        raise
    except RosaadlError as exc:
        return expand_errors(exc), []
    return [], loaded.warnings

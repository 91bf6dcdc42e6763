"""The formats rosaadl reads and writes: the tables ``check``, ``import`` and ``export`` consult.

Readers: each format says how to recognise an input (file suffix, or a folder test), how to read
it into one of our models, and what that model is. Reading returns a :class:`Loaded`; problems
are raised as located :class:`~rosaadl.errors.RosaadlError`\\ s (a reader that collects several
raises one error whose ``errors`` attribute lists them all).

Writers: each format says what it writes (declarative AADL packages, or a system instance), what
``-o`` names (a file or a folder), the options it takes, and how to write. ``rosaadl export``
has one sub-command per writer. A new format is one module in ``importers/`` or ``exporters/``
plus one entry in :func:`readers` or :func:`writers`; the modules are imported only when used.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl.arguments import checked, expect_path
from rosaadl.errors import Diagnostic, NameResolutionError, RosaadlError, UsageError
from rosaadl.fileio import existing

__all__ = [
    "Loaded",
    "Reader",
    "readers",
    "reader_for",
    "read_input",
    "check_file",
    "Checked",
    "check_inputs",
    "expand_errors",
    "WriterOption",
    "Writer",
    "writers",
    "writer",
]


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
    from rosaadl.importers.rosmod_webgme.projects import read_webgmex_projects

    warnings: list[Diagnostic] = []
    projects = read_webgmex_projects(path, project=project, warnings=warnings)
    return Loaded(list(projects), warnings, kind="rosmod")


def _is_rosmod_folder(path: Path) -> bool:
    from rosaadl.importers import rosmod_text

    return rosmod_text.is_rosmod_project(path)


def _read_ros2_package(path: Path, **_: Any) -> Loaded:
    from rosaadl.importers.ros2_package import read_ros2_packages

    warnings: list[Diagnostic] = []
    project = read_ros2_packages([path], warnings)
    return Loaded([project], warnings, kind="rosmod")


def _is_ros2_package_folder(path: Path) -> bool:
    from rosaadl.importers.ros2_package import is_ros2_package_folder

    return is_ros2_package_folder(path)


def _is_aadl_folder(path: Path) -> bool:
    return any(p.suffix.lower() in (".aadl", ".aadl2") for p in path.rglob("*") if p.is_file())


def readers() -> tuple[Reader, ...]:
    """Every format, most specific first (folders: ROSMOD projects, then AADL folders, then ROS 2
    packages)."""
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
        # after AADL folders: a folder of .aadl files that also holds a ROS 2 workspace (the
        # demo's output) stays an AADL folder
        Reader(
            "ros2-package",
            (),
            _read_ros2_package,
            "ROS 2 rclpy packages, read statically (a package folder or a workspace holding them)",
            folder=_is_ros2_package_folder,
        ),
    )


def reader_for(path: str | os.PathLike[str]) -> Reader:
    """The reader for ``path``: by its suffix, or for a folder, by what the folder holds."""
    path = expect_path(path)
    if path.is_dir():
        for reader in readers():
            if reader.folder is not None and reader.folder(path):
                return reader
        raise UsageError(
            "the folder holds neither a ROSMOD project nor .aadl files (nor a ROS 2 package.xml)",
            file=str(path),
        )
    suffix = path.suffix.lower()
    for reader in readers():
        if suffix in reader.suffixes:
            return reader
    known = ", ".join(sorted({s for r in readers() for s in r.suffixes}))
    raise UsageError(
        f"no reader for {path.name!r} (known file types: {known}, or a ROSMOD project folder)", file=str(path)
    )


@checked
def read_input(path: str | os.PathLike[str], **options: Any) -> Loaded:
    """Read one input with the reader its name or content calls for."""
    path = expect_path(path)
    if not existing(path):
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


def check_file(
    path: str | os.PathLike[str], **options: Any
) -> tuple[list[RosaadlError | Diagnostic], list[Diagnostic]]:
    """Read one input; returns (errors, warnings) instead of raising for model problems."""
    try:
        loaded = read_input(path, **options)
    except UsageError:
        raise
    except RosaadlError as exc:
        return expand_errors(exc), []
    return [], loaded.warnings


@dataclass
class Checked:
    """What :func:`check_inputs` found in one input: its errors and its warnings."""

    path: Path
    errors: list[RosaadlError | Diagnostic] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)


@checked
def check_inputs(paths: list[str | os.PathLike[str]], **options: Any) -> list[Checked]:
    """Read every input as the verbs read it; one :class:`Checked` per input, in the order given.

    AADL text given together (``.aadl``/``.aadl2`` files and folders of them) is one workspace,
    read with the component library as ``instantiate`` and ``analyze`` read their inputs: package
    and property set names lie in one global name space (AS5506C 4.2, "Packages"), which OSATE
    fills with every AADL file of the project (and of the projects it references) and its
    contributed property sets, so a package of one file may be named from another (``with``,
    ``extends``, classifiers, property sets). Each finding goes to the input it is
    located in (the first AADL input when it is located elsewhere). Every other input (a rosaadl
    model, an ``.aaxl2``, a Cheddar file, a ROSMOD project) is read alone, with ``options``. A
    missing input, or one rosaadl has no reader for, is a :class:`UsageError` before any reading.
    """
    given = [expect_path(path) for path in paths]
    for path in given:
        if not existing(path):
            raise UsageError("no such file or folder", file=str(path))
    kinds = [reader_for(path).name for path in given]
    results = [Checked(path) for path in given]
    workspace = [result for result, kind in zip(results, kinds, strict=True) if kind == "aadl"]
    if workspace:
        errors, warnings = _check_aadl_workspace([result.path for result in workspace])
        for item in errors:
            _input_of(item, workspace).errors.append(item)
        for warning in warnings:
            _input_of(warning, workspace).warnings.append(warning)
    for result, kind in zip(results, kinds, strict=True):
        if kind != "aadl":
            result.errors, result.warnings = check_file(result.path, **options)
    return results


def _check_aadl_workspace(paths: list[Path]) -> tuple[list[RosaadlError | Diagnostic], list[Diagnostic]]:
    """(errors, warnings) of AADL files and folders read together with the library. A file that
    does not read (syntax, legality rules) stops the reading of the workspace: then every input is
    read alone, so that each one's own errors are all reported, and names are not resolved."""
    from rosaadl.importers import aadl_text

    warnings: list[Diagnostic] = []
    try:
        aadl_text.read_files(paths, warnings=warnings)
    except UsageError:
        raise
    except NameResolutionError as exc:
        return expand_errors(exc), warnings
    except RosaadlError:
        pass
    else:
        return [], warnings
    errors: list[RosaadlError | Diagnostic] = []
    warnings = []
    for path in paths:
        try:
            aadl_text.read_files([path], include_library=False, check=False, warnings=warnings)
        except UsageError:
            raise
        except RosaadlError as exc:
            errors.extend(expand_errors(exc))
    warnings.append(Diagnostic("warning", "names are not resolved across the files until every file reads"))
    return errors, warnings


def _input_of(item: RosaadlError | Diagnostic, inputs: list[Checked]) -> Checked:
    """The input ``item`` is located in: that file, or the folder that holds it."""
    where = item.location.file
    if where:
        found = Path(where).resolve()
        for candidate in inputs:
            given = candidate.path.resolve()
            if found == given or given in found.parents:
                return candidate
    return inputs[0]


# =============================================================================== writers


@dataclass(frozen=True)
class WriterOption:
    """An option of a writer (``--cheddar-format 2``): its keyword, the choices and the default."""

    name: str  #: the keyword argument of the writer (``cheddar_format``)
    choices: tuple[str, ...]
    default: str | None  #: None: the writer chooses (the help says how)
    help: str = ""
    reading: bool = False  #: also given to the reader of the inputs (Cheddar's time unit)

    @property
    def flag(self) -> str:
        return "--" + self.name.replace("_", "-")


@dataclass(frozen=True)
class Writer:
    """A format rosaadl writes.

    ``write(source, out, warnings, **options)`` writes ``source`` (a list of AADL units when
    ``takes`` is ``"units"``, a ``SystemInstance`` when it is ``"instance"``) to ``out`` and
    returns what it wrote, the main file first; it appends its warnings to ``warnings``.
    """

    name: str
    description: str
    takes: str  #: "units" | "instance"
    output: str  #: what ``-o`` names
    write: Callable[..., list[Path]]
    options: tuple[WriterOption, ...] = ()


def _write_aadl(units: list[EObject], out: Path, warnings: list[Diagnostic]) -> list[Path]:
    from rosaadl.exporters import aadl_text

    return aadl_text.write_model(units, out)


def _write_cheddar(
    instance: EObject,
    out: Path,
    warnings: list[Diagnostic],
    *,
    cheddar_format: str | None = None,
    time_unit: str = "us",
) -> list[Path]:
    from rosaadl.exporters import cheddar

    chosen = int(cheddar_format) if cheddar_format is not None else None
    written = cheddar.write_cheddar(
        instance, out, cheddar_format=chosen, time_unit=time_unit, diagnostics=warnings
    )
    return [written]


def _write_aaxl2(instance: EObject, out: Path, warnings: list[Diagnostic]) -> list[Path]:
    from rosaadl.exporters import aaxl2

    return [aaxl2.write_aaxl2(instance, out, warnings=warnings)]


def writers() -> tuple[Writer, ...]:
    """Every format rosaadl writes, in the order ``rosaadl export --help`` lists them."""
    return (
        Writer(
            "aadl",
            "AADL text: one .aadl file per package and property set of the inputs (not the library's).",
            "units",
            "Output folder.",
            _write_aadl,
        ),
        Writer(
            "cheddar",
            "Cheddar XML (v3 by default, v2 on request) of a deployed system.",
            "instance",
            "Cheddar file to write (.xmlv3 or .xml).",
            _write_cheddar,
            (
                WriterOption(
                    "cheddar_format",
                    ("2", "3"),
                    None,
                    "Cheddar 3 or 2 [default: the format a Cheddar input was read in, else 3].",
                ),
                WriterOption(
                    "time_unit",
                    ("us", "ms"),
                    "us",
                    "The unit of Cheddar's integer times; a time that is not a whole number is an error.",
                    reading=True,
                ),
            ),
        ),
        Writer(
            "aaxl2",
            "OSATE instance model (.aaxl2) with its AADL sidecars, as OSATE itself writes it.",
            "instance",
            "Output folder: instances/<Root>_Instance.aaxl2 and the .aadl files it refers to.",
            _write_aaxl2,
        ),
    )


def writer(name: str) -> Writer:
    """The writer called ``name``; a :class:`UsageError` naming the known ones otherwise."""
    for item in writers():
        if item.name == name:
            return item
    raise UsageError(f"no writer {name!r} (known: {', '.join(w.name for w in writers())})")

"""The files of ROS 2 packages, read safely: ``package.xml`` manifests, Python sources,
``.msg``/``.srv`` definitions.

Every file is read whole, refused above :data:`MAX_FILE_BYTES`, decoded as UTF-8; a file that is
a link leading outside the folders given is not read. ``package.xml`` is parsed with the
hardened parser (entities, DTDs and the network refused). A folder walk stops at
:data:`MAX_FILES` files and never follows links or enters ``build``, ``install``, ``log`` or
hidden folders. Each problem is a located diagnostic; nothing here raises for a bad file.
"""

from __future__ import annotations

import ast
import os
import warnings as python_warnings
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from rosaadl.errors import Diagnostic, ImportFormatError, Location
from rosaadl.fileio import parse_xml_bytes

__all__ = [
    "MAX_FILE_BYTES",
    "MAX_FILES",
    "Manifest",
    "find_packages",
    "read_manifest",
    "read_text",
    "parse_python",
    "package_files",
]

#: Largest source, manifest or interface file read.
MAX_FILE_BYTES = 4 * 1024 * 1024
#: Most files looked at under the folders given.
MAX_FILES = 20_000
#: Deepest folder looked into for packages.
MAX_DEPTH = 8
_SKIPPED = {"build", "install", "log", "__pycache__", "node_modules"}


@dataclass
class Manifest:
    """What ``package.xml`` says: the package name, build type and dependencies."""

    name: str
    folder: Path
    build_type: str = ""
    depends: list[str] = field(default_factory=list)


def _inside(path: Path, roots: list[Path]) -> bool:
    try:
        resolved = path.resolve()
    except (OSError, RuntimeError):
        return False
    return any(resolved == root or root in resolved.parents for root in roots)


def read_text(path: Path, shown: str, roots: list[Path], problems: list[Diagnostic]) -> str | None:
    """The UTF-8 text of ``path``; None (and a located diagnostic) when it cannot be read."""
    if not _inside(path, roots):
        problems.append(
            Diagnostic("warning", "a link that leads outside the folders given; not read", Location(shown))
        )
        return None
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            problems.append(
                Diagnostic(
                    "warning", f"the file is {size} bytes (above {MAX_FILE_BYTES}); not read", Location(shown)
                )
            )
            return None
        data = path.read_bytes()
    except OSError as exc:
        problems.append(
            Diagnostic("warning", f"cannot read the file: {exc.strerror or exc}", Location(shown))
        )
        return None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        problems.append(Diagnostic("warning", "the file is not UTF-8 text; not read", Location(shown, line)))
        return None


def parse_python(text: str, shown: str, problems: list[Diagnostic]) -> ast.Module | None:
    """The syntax tree of ``text``; None (and a located diagnostic) on a syntax error."""
    try:
        with python_warnings.catch_warnings():
            python_warnings.simplefilter("ignore")
            return ast.parse(text, filename=shown)
    except SyntaxError as exc:
        problems.append(
            Diagnostic(
                "warning",
                f"Python syntax error: {exc.msg}; the file is not read",
                Location(shown, exc.lineno, exc.offset),
            )
        )
    except (ValueError, RecursionError, MemoryError) as exc:
        problems.append(
            Diagnostic(
                "warning", f"the file cannot be parsed ({exc.__class__.__name__}); not read", Location(shown)
            )
        )
    return None


def read_manifest(folder: Path, roots: list[Path], problems: list[Diagnostic]) -> Manifest | None:
    """The manifest of the package in ``folder``; None (and a located diagnostic) when it does
    not read or names no package."""
    path = folder / "package.xml"
    shown = str(path)
    text = read_text(path, shown, roots, problems)
    if text is None:
        return None
    try:
        root = parse_xml_bytes(text.encode("utf-8"), shown).getroot()
    except ImportFormatError as exc:
        problems.append(Diagnostic("warning", f"{exc.message}; the package is not read", exc.location))
        return None
    if root.tag != "package":
        problems.append(
            Diagnostic(
                "warning",
                f"the root element is <{root.tag}>, not <package>; not read",
                Location(shown, root.sourceline),
            )
        )
        return None
    name = (root.findtext("name") or "").strip()
    if not name or not all(c.isalnum() or c in "_-" for c in name):
        where = root.find("name")
        problems.append(
            Diagnostic(
                "warning",
                f"<name> {name!r} is not a ROS package name; the package is not read",
                Location(shown, where.sourceline if where is not None else root.sourceline),
            )
        )
        return None
    build_type = (root.findtext("export/build_type") or "").strip()
    depends = [
        (e.text or "").strip() for e in root if e.tag in ("depend", "exec_depend", "build_depend") and e.text
    ]
    return Manifest(name, folder, build_type, depends)


def _walk(folder: Path, depth: int) -> Iterator[Path]:
    """The files under ``folder`` (links and skipped folders left out), at most :data:`MAX_DEPTH` deep."""
    try:
        entries = sorted(os.scandir(folder), key=lambda e: e.name)
    except OSError:
        return
    for entry in entries:
        if entry.name.startswith("."):
            continue
        try:
            if entry.is_dir(follow_symlinks=False):
                if entry.name not in _SKIPPED and depth < MAX_DEPTH:
                    yield from _walk(Path(entry.path), depth + 1)
            elif entry.is_file(follow_symlinks=True):
                yield Path(entry.path)
        except OSError:
            continue


def find_packages(folders: list[Path], problems: list[Diagnostic]) -> list[Path]:
    """The package folders (holding ``package.xml``) in or under ``folders``."""
    found: list[Path] = []
    count = 0
    for folder in folders:
        if (folder / "package.xml").is_file():
            found.append(folder)
            continue
        for path in _walk(folder, 0):
            count += 1
            if count > MAX_FILES:
                problems.append(
                    Diagnostic(
                        "warning",
                        f"more than {MAX_FILES} files: the rest is not looked at",
                        Location(str(folder)),
                    )
                )
                return found
            if path.name == "package.xml" and not any(
                path.parent == f or f in path.parent.parents for f in found
            ):
                found.append(path.parent)
    return found


def package_files(folder: Path) -> Iterator[Path]:
    """The files of the package in ``folder`` (its tests left out)."""
    for path in _walk(folder, 0):
        relative = path.relative_to(folder).parts
        if relative[0] == "test":
            continue
        yield path

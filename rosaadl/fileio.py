"""Atomic, contained file writes; hardened XML and bounded JSON parsing for every reader."""

from __future__ import annotations

import contextlib
import json
import os
import re
import secrets
import shutil
import signal
import stat
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO, Any

from lxml import etree

from rosaadl.arguments import expect_path
from rosaadl.errors import ExportError, ImportFormatError, Location, RosaadlError, UsageError

__all__ = [
    "atomic_write",
    "atomic_write_bytes",
    "atomic_write_text",
    "write_files",
    "sweep_temporaries",
    "TEMPORARY_PREFIX",
    "safe_join",
    "safe_xml_parser",
    "parse_xml_bytes",
    "element_path",
    "cannot_write",
    "existing",
    "JSON_INT_DIGITS",
    "JsonLimitError",
    "loads_bounded",
]


TEMPORARY_PREFIX = ".rosaadl-"
"""Every temporary file rosaadl makes is ``.rosaadl-<pid>-<random>.tmp`` beside its target.

The name is short and of fixed length (at most 33 bytes), so any target name the file system
accepts can be written (a temporary named after its target would exceed the name limit for a
target within a few characters of it), and it carries the writer's process id, so a later run
can tell a stale temporary (its writer is gone: killed, or the machine stopped) from one that a
running process is still writing.
"""

_TEMPORARY = re.compile(r"\.rosaadl-(\d{1,10})-[0-9a-f]{12}\.tmp")
_LEGACY_SUFFIX = re.compile(r"\.[a-z0-9_]{8}\.tmp")  # tempfile.mkstemp names of earlier versions
_DEFERRED_SIGNALS = (signal.SIGINT, signal.SIGTERM)
_FILE_MODE = 0o666  # the kernel applies the user's umask, as for any file a program creates


def _create_temporary(folder: Path) -> tuple[int, Path]:
    """Create an empty temporary file in ``folder``: its descriptor and path.

    Opened with mode ``0o666`` so that the output gets the user's umask like any other file
    the user makes (``mkstemp`` would make it ``0600``).
    """
    while True:
        path = folder / f"{TEMPORARY_PREFIX}{os.getpid()}-{secrets.token_hex(6)}.tmp"
        try:
            return os.open(
                path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), _FILE_MODE
            ), path
        except FileExistsError:
            continue


def _discard(path: Path | None) -> None:
    if path is not None:
        with contextlib.suppress(OSError):
            os.unlink(path)


@contextmanager
def _temporary_beside(target: Path, mode: str) -> Iterator[tuple[IO, Path]]:
    """A new temporary file beside ``target``, open in ``mode``, and its path; synced when the
    block ends, removed if it raises (an :class:`OSError` becomes an :class:`ExportError`)."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = _create_temporary(target.parent)
    except OSError as exc:
        raise cannot_write(target, exc) from None
    try:
        encoding = None if "b" in mode else "utf-8"
        newline = None if "b" in mode else ""
        with os.fdopen(fd, mode, encoding=encoding, newline=newline) as handle:
            yield handle, tmp
            handle.flush()
            os.fsync(handle.fileno())
    except BaseException as exc:
        _discard(tmp)
        if isinstance(exc, OSError):
            raise cannot_write(target, exc) from None
        raise


@contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "wb") -> Iterator[IO]:
    """Write to a temporary file beside ``path`` and rename it into place on success.

    On any exception (an interrupt included) the temporary file is removed and ``path`` is left
    as it was: a failed run never leaves a partial output file. A file the system refuses to
    write (its folder is a file, the name is too long, the path is a folder) is an
    :class:`ExportError` naming it. The file gets the user's umask.
    """
    target = expect_path(path, "the file to write", error=ExportError)
    _refuse_folder(target)
    sweep_temporaries([target.parent], targets=[target])
    written: Path | None = None
    try:
        with _temporary_beside(target, mode) as (handle, written):
            yield handle
        os.replace(written, target)
    except BaseException as exc:
        _discard(written)
        if isinstance(exc, OSError):
            raise cannot_write(target, exc) from None
        raise


def write_files(
    files: Iterable[tuple[str | os.PathLike[str], str | bytes]], *, workers: int = 1
) -> list[Path]:
    """Write a set of files all-or-nothing: every one, or (on any error or interrupt) none.

    Every content is first written to a synced temporary beside its target (``workers``
    threads at once when above 1: syncing many files concurrently is much faster); only when
    all are complete are they renamed into place, with SIGINT and SIGTERM held back for the
    few renames and delivered right after. A rename the system refuses (a name too long, a
    folder in the way) puts back the files already renamed, from hard links (or copies) of
    what was there before. Stale temporaries of our own naming in the targets' folders are
    swept first. ``str`` contents are written as UTF-8. Returns the targets, in order.
    """
    jobs = [(expect_path(path, "the file to write", error=ExportError), data) for path, data in files]
    targets = [target for target, _ in jobs]
    for target in targets:
        _refuse_folder(target)
    sweep_temporaries(sorted({target.parent for target in targets}), targets=targets)
    temporaries: list[Path | None] = [None] * len(jobs)

    def prepare(index: int) -> None:
        target, data = jobs[index]
        with _temporary_beside(target, "w" if isinstance(data, str) else "wb") as (handle, tmp):
            temporaries[index] = tmp
            handle.write(data)

    try:
        if workers > 1 and len(jobs) > 1:
            _in_threads(prepare, len(jobs), workers)
        else:
            for index in range(len(jobs)):
                prepare(index)
        with _signals_held():
            _rename_all([(tmp, target) for tmp, (target, _) in zip(temporaries, jobs, strict=True)])
    except BaseException:
        for tmp in temporaries:
            _discard(tmp)
        raise
    return targets


def _in_threads(work: Callable[[int], None], count: int, workers: int) -> None:
    """Run ``work(0..count-1)`` on ``workers`` threads; the first error is raised once every
    started job has ended and none is left to start (so nothing is written after it)."""
    from concurrent.futures import ThreadPoolExecutor

    pool = ThreadPoolExecutor(max_workers=workers)
    try:
        # an interrupt while the pool starts a thread would leave that thread out of the join
        with _signals_held():
            futures = [pool.submit(work, index) for index in range(count)]
        for future in futures:
            future.result()
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _rename_all(pairs: list[tuple[Path, Path]]) -> None:
    """Rename each temporary onto its target; on a refusal, put back what was there."""
    backups: list[tuple[Path, Path | None]] = []  # (renamed target, its former content or None)
    for tmp, target in pairs:
        try:
            backup = _backup(target)
            try:
                os.replace(tmp, target)
            except OSError:
                _discard(backup)
                raise
        except OSError as exc:
            for renamed, former in reversed(backups):
                if former is not None:
                    with contextlib.suppress(OSError):
                        os.replace(former, renamed)
                else:
                    _discard(renamed)
            raise cannot_write(target, exc) from None
        backups.append((target, backup))
    for _, backup in backups:
        _discard(backup)


def _backup(target: Path) -> Path | None:
    """A hard link (or a copy) of ``target``'s current content beside it; ``None`` if no file."""
    if not os.path.isfile(target):
        return None
    fd, path = _create_temporary(target.parent)
    os.close(fd)
    os.unlink(path)
    try:
        os.link(target, path)
    except OSError:
        shutil.copy2(target, path)
    return path


@contextmanager
def _signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back for the block, then deliver the ones that came.

    Python runs signal handlers in the main thread only, so elsewhere this does nothing.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    arrived: list[int] = []
    previous = {signum: signal.getsignal(signum) for signum in _DEFERRED_SIGNALS}
    for signum in _DEFERRED_SIGNALS:
        signal.signal(signum, lambda number, _frame: arrived.append(number))
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler if handler is not None else signal.SIG_DFL)
        for signum in dict.fromkeys(arrived):
            signal.raise_signal(signum)


def sweep_temporaries(folders: Iterable[Path], *, targets: Iterable[Path] = ()) -> None:
    """Remove stale temporaries of our own naming from ``folders``.

    A temporary ``.rosaadl-<pid>-<random>.tmp`` is stale when no process ``<pid>`` runs (its
    writer was killed before it could clean up); those of running processes are left alone.
    The temporaries of earlier versions, ``.<target name>.<8 characters>.tmp``, are removed
    for the ``targets`` about to be written. A folder that cannot be listed is skipped.
    """
    legacy = {target.name for target in targets}
    for folder in folders:
        try:
            names = os.listdir(folder)
        except OSError:
            continue
        for name in names:
            match = _TEMPORARY.fullmatch(name)
            if match is not None:
                if not _running(int(match.group(1))):
                    _discard(Path(folder) / name)
            elif name.startswith(".") and name.endswith(".tmp") and legacy:
                stem = _LEGACY_SUFFIX.sub("", name)[1:]
                if stem != name[1:] and stem in legacy:
                    _discard(Path(folder) / name)


def _running(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True  # someone else's process, or a pid we cannot ask about: leave it
    return True


def _refuse_folder(target: Path) -> None:
    """A target that is an existing folder is refused before anything is written."""
    try:
        is_folder = stat.S_ISDIR(target.stat().st_mode)
    except (OSError, ValueError):
        return
    if is_folder:
        raise cannot_write(target, IsADirectoryError(21, "Is a directory"))


def cannot_write(target: Path, exc: OSError) -> ExportError:
    """The located error for a file or folder the system refused to make at ``target``."""
    blocker = next((p for p in target.parents if _is_file(p)), None)
    if isinstance(exc, (FileExistsError, NotADirectoryError)) and blocker is not None:
        reason = f"{blocker} is a file, not a folder"
    elif isinstance(exc, IsADirectoryError):
        reason = "it is a folder"
    else:
        reason = exc.strerror or str(exc)
    return ExportError(f"cannot write here: {reason}", file=str(target))


def _is_file(path: Path) -> bool:
    try:
        return not stat.S_ISDIR(path.stat().st_mode)
    except (OSError, ValueError):
        return False


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (see :func:`atomic_write`)."""
    write_files([(path, data)])


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    """Write ``text`` as UTF-8 to ``path`` atomically (see :func:`atomic_write`)."""
    write_files([(path, text)])


def safe_join(root: str | os.PathLike[str], *parts: str) -> Path:
    """Join ``parts`` under ``root`` and refuse any result outside it (``..``, absolute, links)."""
    try:
        base = Path(root).resolve()
        candidate = base.joinpath(*parts)
        resolved = candidate.resolve()
    except (OSError, ValueError) as exc:
        raise ExportError(f"cannot write {'/'.join(parts)!r} under {str(root)!r}: {exc}") from None
    if resolved != base and base not in resolved.parents:
        raise ExportError(
            f"refusing to write {'/'.join(parts)!r}: it would land outside the output directory {str(root)!r}"
        )
    return candidate


def safe_xml_parser(*, remove_blank_text: bool = False, deep: bool = False) -> etree.XMLParser:
    """An lxml parser with entity resolution, DTD loading and network access all off.

    ``deep`` raises libxml2's nesting limit from 256 to 2 048 elements (its "huge" mode, which
    also lifts its text-size limits; entities stay refused): for our own deep models.
    """
    return etree.XMLParser(
        resolve_entities=False,
        no_network=True,
        load_dtd=False,
        dtd_validation=False,
        huge_tree=deep,
        remove_blank_text=remove_blank_text,
        remove_comments=False,
    )


def element_path(element: etree._Element) -> str:
    """A readable XPath-like path for an element (``/cheddar/tasks/periodic_task[2]``)."""
    tree = element.getroottree()
    try:
        path = tree.getpath(element)
    except ValueError:
        return element.tag if isinstance(element.tag, str) else "?"
    # Make namespaced steps readable: {uri}name -> prefix:name
    return path


def parse_xml_bytes(
    data: bytes,
    filename: str,
    *,
    allow_doctype: bool = False,
    remove_blank_text: bool = False,
    deep: bool = False,
) -> etree._ElementTree:
    """Parse ``data`` with the hardened parser; errors become located :class:`ImportFormatError`.

    ``remove_blank_text`` drops whitespace-only text between elements (indentation), for
    readers that never look at it: the tree has half the nodes, and parses and frees faster.
    ``deep``: see :func:`safe_xml_parser`.

    A DOCTYPE that declares entities is refused (entity-expansion bombs, external entities);
    a plain DOCTYPE is refused too unless ``allow_doctype`` (Cheddar v2 files carry one).
    """
    if not data or data.isspace():
        raise ImportFormatError("the file is empty; expected an XML document", file=filename, line=1)
    try:
        tree = etree.ElementTree(
            etree.fromstring(data, safe_xml_parser(remove_blank_text=remove_blank_text, deep=deep))
        )
    except etree.XMLSyntaxError as exc:
        line, column = exc.position if exc.position else (None, None)
        raise ImportFormatError(
            f"malformed XML: {exc.msg}", file=filename, line=line, column=column
        ) from None
    docinfo = tree.docinfo
    if docinfo.doctype:
        internal = docinfo.internalDTD
        entities = [e.name for e in internal.iterentities()] if internal is not None else []
        if entities:
            problem = f"declares entities ({', '.join(entities[:5])})"
        elif docinfo.system_url:
            problem = f"refers to an external DTD ({docinfo.system_url})"
        elif not allow_doctype:
            problem = "is not expected here"
        else:
            problem = ""
        if problem:
            raise ImportFormatError(
                f"the document's DOCTYPE {problem}; DTD entities and external DTDs are refused "
                "(expected a plain XML document)",
                Location(file=filename, line=1),
            )
    return tree


def existing(path: str | os.PathLike[str], error: type[RosaadlError] = UsageError) -> bool:
    """Whether ``path`` names something that exists; a path the system cannot look up at all
    (a name too long, a NUL byte, a loop of links) is an ``error`` naming it."""
    target = expect_path(path)
    try:
        target.stat()
    except (FileNotFoundError, NotADirectoryError):
        return False
    except OSError as exc:
        raise error(f"cannot use this path: {exc.strerror or exc}", file=str(target)) from None
    return True


# --------------------------------------------------------------------------- JSON text
# Python's json.loads raises a bare ValueError for an integer literal longer than the
# interpreter's conversion limit (4 300 digits) and RecursionError for deep nesting; readers of
# user files call loads_bounded and turn JsonLimitError (and json.JSONDecodeError) into their
# own located errors.

#: The longest integer literal accepted (Python's own default conversion limit).
JSON_INT_DIGITS = 4300


class JsonLimitError(ValueError):
    """The JSON text is well formed but beyond what a reader accepts."""


def _bounded_int(text: str) -> int:
    digits = len(text.lstrip("-"))
    if digits > JSON_INT_DIGITS:
        raise JsonLimitError(f"an integer of {digits} digits (at most {JSON_INT_DIGITS})")
    return int(text)


def _refused_constant(name: str) -> float:
    raise JsonLimitError(f"{name} is not a JSON number")


def loads_bounded(text: str, *, allow_nan: bool = True) -> Any:
    """``json.loads(text)`` with long integers, deep nesting and (unless ``allow_nan``) the
    non-standard ``NaN``/``Infinity`` refused as :class:`JsonLimitError`."""
    extra = {} if allow_nan else {"parse_constant": _refused_constant}
    try:
        return json.loads(text, parse_int=_bounded_int, **extra)
    except RecursionError:
        raise JsonLimitError("the JSON is nested too deeply") from None

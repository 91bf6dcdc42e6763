"""The files of a textual ROSMOD project: reading one safely, listing side files, naming them.

Every model file is read whole as UTF-8 (a byte-order mark is dropped), refused above
:data:`MAX_FILE_BYTES` with a located error; an undecodable byte is reported at its line and
column. Files are named in messages as the user named the project (:func:`shown_path`).
"""

from __future__ import annotations

import os
from pathlib import Path

from rosaadl.errors import ParseError

__all__ = ["MAX_FILE_BYTES", "read_text", "side_files", "shown_path"]

#: Largest model file read (text or JSON); larger files are refused with a located error.
MAX_FILE_BYTES = 64 * 1024 * 1024


def read_text(path: Path, shown: str) -> str:
    """The text of ``path`` (named ``shown`` in errors); a located :class:`ParseError` if unreadable."""
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise ParseError(
                f"the file is {size} bytes; ROSMOD model files above {MAX_FILE_BYTES} bytes are refused",
                file=shown,
            )
        data = path.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the file: {exc.strerror}", file=shown) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise ParseError(
            f"not UTF-8 text (byte 0x{data[exc.start]:02x}); expected a ROSMOD text file",
            file=shown,
            line=line,
            column=column,
        ) from None


def side_files(folder: Path, suffix: str) -> list[Path]:
    """The files of ``folder`` whose names end with ``suffix``, by name (none if it is no folder)."""
    if not folder.is_dir():
        return []
    return sorted(
        (p for p in folder.iterdir() if p.is_file() and p.name.endswith(suffix)), key=lambda p: p.name
    )


def shown_path(shown_root: str, rel: Path | str) -> str:
    """``rel`` (relative to the project folder) as the user named that folder, ``shown_root``."""
    rel_text = Path(rel).as_posix()
    if not shown_root:
        return rel_text
    return os.path.join(shown_root, rel_text)

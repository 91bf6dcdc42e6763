"""The ``.webgmex`` archive: a zip file whose ``project.json`` holds one WebGME project tree.

:func:`load_project_json` opens the archive with the checks a file from elsewhere deserves (no
member outside the archive, bounded size and count, no encryption, a bounded number of JSON
values so that the parsed tree stays bounded too) and returns the parsed
``project.json`` (``{rootHash, objects: [...]}``). The archive's other members
(``<hash>.content``/``.metadata``: experiment logs) are not read, and nothing is extracted.
"""

from __future__ import annotations

import json
import os
import zipfile
import zlib
from pathlib import PurePosixPath
from typing import Any

from rosaadl.arguments import expect_path
from rosaadl.errors import ImportFormatError, Location
from rosaadl.fileio import JsonLimitError, loads_bounded
from rosaadl.importers.json_limits import MAX_JSON_VALUES, json_value_bound

__all__ = ["MAX_TOTAL_BYTES", "MAX_MEMBERS", "load_project_json", "fail"]

#: Refuse archives whose members add up to more than this many bytes (uncompressed).
MAX_TOTAL_BYTES = 200 * 1024 * 1024
#: Refuse archives with more members than this.
MAX_MEMBERS = 20_000


def fail(message: str, filename: str, path: str | None = None, **where: Any) -> ImportFormatError:
    """An :class:`ImportFormatError` located in the export ``filename`` (at ``path``, line, column)."""
    return ImportFormatError(message, Location(file=filename, path=path, **where))


def _check_member_name(name: str, filename: str) -> None:
    pure = PurePosixPath(name.replace("\\", "/"))
    if (
        name.startswith(("/", "\\"))
        or (len(name) > 1 and name[1] == ":")
        or ".." in pure.parts
        or "\x00" in name
    ):
        raise fail(
            f"the archive member {name!r} points outside the archive (absolute path or '..'); "
            "refusing the file (nothing was extracted)",
            filename,
            path=name,
        )


def load_project_json(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The parsed ``project.json`` of a ``.webgmex`` archive, after the archive's safety checks.

    Refused with a located :class:`ImportFormatError`: a file that is not a zip archive, a
    truncated or corrupt archive, a member named with an absolute path or ``..``, more than
    :data:`MAX_MEMBERS` members or more than :data:`MAX_TOTAL_BYTES` uncompressed bytes,
    a ``project.json`` of more than :data:`~rosaadl.importers.json_limits.MAX_JSON_VALUES`
    values (a small text of many small values would amplify to gigabytes once parsed),
    encrypted members, a missing or malformed ``project.json``.
    """
    expect_path(path)
    filename = os.fspath(path)
    try:
        if not zipfile.is_zipfile(filename):
            raise fail("not a zip archive: a .webgmex export is a zip file holding project.json", filename)
        with zipfile.ZipFile(filename) as archive:
            infos = archive.infolist()
            if len(infos) > MAX_MEMBERS:
                raise fail(
                    f"the archive has {len(infos)} members (more than {MAX_MEMBERS}); refused", filename
                )
            total = 0
            for info in infos:
                _check_member_name(info.filename, filename)
                total += info.file_size
            if total > MAX_TOTAL_BYTES:
                raise fail(
                    f"the archive would unpack to {total} bytes (more than {MAX_TOTAL_BYTES}); refused",
                    filename,
                )
            try:
                info = archive.getinfo("project.json")
            except KeyError:
                raise fail("the archive has no project.json (not a WebGME export)", filename) from None
            if info.flag_bits & 0x1:
                raise fail("project.json is encrypted", filename, path="project.json")
            data = bytearray()
            with archive.open(info) as handle:
                while True:
                    chunk = handle.read(1 << 20)
                    if not chunk:
                        break
                    data.extend(chunk)
                    if len(data) > MAX_TOTAL_BYTES:
                        raise fail(
                            f"project.json unpacks to more than {MAX_TOTAL_BYTES} bytes; refused",
                            filename,
                            path="project.json",
                        )
    except (zipfile.BadZipFile, zipfile.LargeZipFile, zlib.error, EOFError, NotImplementedError) as exc:
        raise fail(f"corrupt or truncated zip archive: {exc}", filename) from None
    except OSError as exc:
        raise fail(f"cannot read the archive: {exc.strerror or exc}", filename) from None
    values = json_value_bound(data)
    if values > MAX_JSON_VALUES:
        raise fail(
            f"project.json holds about {values} JSON values (more than {MAX_JSON_VALUES}); refused "
            "before parsing, to bound memory",
            filename,
            path="project.json",
        )
    try:
        doc = loads_bounded(bytes(data).decode("utf-8-sig"))
    except UnicodeDecodeError as exc:
        raise fail(
            f"project.json is not UTF-8 text (byte {exc.start})", filename, path="project.json"
        ) from None
    except json.JSONDecodeError as exc:
        raise fail(
            f"malformed project.json: {exc.msg}",
            filename,
            path="project.json",
            line=exc.lineno,
            column=exc.colno,
        ) from None
    except JsonLimitError as exc:
        raise fail(f"project.json: {exc}", filename, path="project.json") from None
    if (
        not isinstance(doc, dict)
        or not isinstance(doc.get("rootHash"), str)
        or not isinstance(doc.get("objects"), list)
    ):
        raise fail(
            "project.json is not a WebGME export (expected an object with 'rootHash' and 'objects')",
            filename,
            path="project.json",
        )
    return doc

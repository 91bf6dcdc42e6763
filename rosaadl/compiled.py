"""The modules rosaadl compiles with Cython when it is installed, and the check that each compiled
module was built from the source file it stands beside.

The OSATE ``.aaxl2`` reader and the pyecore bulk factory are plain Python modules. ``setup.py``
also compiles each one, unchanged, into an extension module of the same name, which Python
imports instead of the source (an editable install puts it beside the source). The compiled
module does exactly what the source does, 8-14 % faster on an import of a corpus file. Where
Cython or a C compiler is missing, the package installs without them and runs the source.

A compiled module built from another version of its source would run that other version
unnoticed, so each compiled module checks at import that the source beside it is the one it
was built from (:func:`check_built_from_source`), against the hashes ``setup.py`` writes into
``rosaadl/_compiled_sources.py`` when it compiles.

This module is read by ``setup.py`` before rosaadl is installed: it imports nothing of rosaadl.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["MODULES", "HASHES_FILE", "source_hash", "check_built_from_source"]

# module name → its source, relative to the project root
MODULES = {
    "rosaadl.importers.aaxl2": "importers/aaxl2.py",
    "rosaadl.bulk": "rosaadl/bulk.py",
}
# written by setup.py when it compiles, relative to the project root (not kept in git)
HASHES_FILE = "rosaadl/_compiled_sources.py"


def source_hash(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def check_built_from_source(name: str, file: str | None, hashes: dict[str, str] | None = None) -> None:
    """Refuse to import the compiled module ``name`` (at ``file``) when the source beside it is
    not the one it was compiled from. Nothing is checked when ``file`` is the source itself, or
    when no source stands beside the compiled module (an install that ships only the latter).

    ``hashes``: module name → hash of its source when compiled; by default, those setup.py wrote.
    """
    if not file or file.endswith(".py"):
        return
    source = Path(file).with_name(name.rpartition(".")[2] + ".py")
    if not source.is_file():
        return
    if hashes is None:
        try:
            from rosaadl._compiled_sources import SHA256 as hashes  # type: ignore[import-not-found]
        except ImportError:
            hashes = {}
    if hashes.get(name) != source_hash(source):
        raise ImportError(
            f"{file} was compiled from another version of {source}: rebuild it (`make venv`, or "
            "`pip install -e .`), or delete it to run the source",
            name=name,
            path=file,
        )

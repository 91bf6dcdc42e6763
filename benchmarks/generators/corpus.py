"""Where the real-world corpus is, and which of its files each reader takes.

``$ROSAADL_CORPUS`` or ``../shared/corpus`` beside the project root; the benchmarks read the
corpus files as they are, next to the generated inputs of this package, and the corpus tests
take their file lists from here.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["aadl_files", "aadl_sources", "aadl_texts", "aaxl2_instance_files", "corpus_dir"]

ROOT = Path(__file__).resolve().parents[2]


def corpus_dir() -> Path:
    """``$ROSAADL_CORPUS`` or ``../shared/corpus`` beside the project root (it may not exist)."""
    env = os.environ.get("ROSAADL_CORPUS")
    return Path(env) if env else ROOT.parent / "shared" / "corpus"


def aadl_files(folder: Path | None = None) -> list[Path]:
    """Every ``.aadl``/``.aadl2`` file below ``folder`` (the corpus by default), sorted; none
    when the folder does not exist."""
    folder = corpus_dir() if folder is None else folder
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in (".aadl", ".aadl2"))


def aadl_sources(folder: Path) -> list[Path]:
    """The AADL sources of one OSATE project of the corpus: :func:`aadl_files`, the same file
    copied twice (gtse-atsv-tier0) taken once."""
    seen, out = set(), []
    for path in aadl_files(folder):
        digest = hashlib.sha1(path.read_bytes()).hexdigest()
        if digest not in seen:
            seen.add(digest)
            out.append(path)
    return out


def aadl_texts(folder: Path | None = None) -> list[tuple[str, bytes]]:
    """The name and bytes of each of :func:`aadl_files`."""
    return [(str(p), p.read_bytes()) for p in aadl_files(folder)]


def aaxl2_instance_files(corpus: Path | None = None, *, wrapped: bool = False) -> list[Path]:
    """The ``.aaxl2`` files of system instances below ``osate/aaxl2`` of the corpus, sorted (by
    their first 800 bytes); with ``wrapped``, those whose root is an ``xmi:XMI`` wrapper too."""
    folder = (corpus_dir() if corpus is None else corpus) / "osate" / "aaxl2"
    if not folder.is_dir():
        return []
    files = []
    for path in sorted(folder.rglob("*.aaxl2")):
        head = path.read_bytes()[:800]
        if b"instance:SystemInstance" in head or (wrapped and b"xmi:XMI" in head):
            files.append(path)
    return files

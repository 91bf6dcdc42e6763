"""Where the real-world corpus is, and which of its files each reader takes.

``$ROSAADL_CORPUS`` or ``../shared/corpus`` beside the project root; the benchmarks read the
corpus files as they are, next to the generated inputs of this package, and the corpus tests
take their file lists from here.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["aadl_files", "aadl_texts", "corpus_dir"]

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


def aadl_texts(folder: Path | None = None) -> list[tuple[str, bytes]]:
    """The name and bytes of each of :func:`aadl_files`."""
    return [(str(p), p.read_bytes()) for p in aadl_files(folder)]

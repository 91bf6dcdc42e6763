"""Shared fixtures: where the real-world corpus is, and a skip when it is absent."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def corpus_dir() -> Path:
    """``$ROSAADL_CORPUS`` or ``../shared/corpus`` beside the project root."""
    env = os.environ.get("ROSAADL_CORPUS")
    return Path(env) if env else ROOT.parent / "shared" / "corpus"


@pytest.fixture(scope="session")
def corpus() -> Path:
    path = corpus_dir()
    if not path.is_dir():
        pytest.skip(f"real-world corpus not found at {path} (set ROSAADL_CORPUS to its folder)")
    return path

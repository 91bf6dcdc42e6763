"""The AADL text writer through the reader: corpus, library and every construct read back equal."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from aadl_writer_models import (
    N,
    everything_model,
    write_unit,
    write_units,
)

from rosaadl import model
from rosaadl.exporters.aadl_text import write_model
from rosaadl.importers.aadl_text import read_files, read_string

ROOT = Path(__file__).resolve().parents[2]


IGNORED = ("line", "column", "sourceFile")


def _differences(a, b) -> list[str]:
    return model.model_differences(a, b, ignore=IGNORED)


def _read_each(paths: list[Path]):
    """One AadlModel holding the units of ``paths`` (read one by one, names not resolved)."""
    ws = N("AadlModel", name="ws")
    for path in paths:
        read_string(path.read_bytes(), str(path), model=ws)
    return ws


def _round_trip(first, out: Path):
    """write(first) read back equals first, and writing it again gives the same text."""
    written = write_model(first, out)
    second = _read_each(written)
    diffs = _differences(first, second)
    assert not diffs, "\n".join(diffs[:20])
    assert write_units(second.units) == {p.name: p.read_bytes().decode("utf-8") for p in written}
    return second


def _corpus_dir() -> Path:
    env = os.environ.get("ROSAADL_CORPUS")
    return Path(env) if env else ROOT.parent / "shared" / "corpus"


CORPUS = _corpus_dir()
CORPUS_FOLDERS = ("osate/aaxl2", "osate/busload", "aadl-ros", "cheddar", "osate/predeclared")
CORPUS_FILES = sorted(
    p for folder in CORPUS_FOLDERS if (CORPUS / folder).is_dir() for p in (CORPUS / folder).rglob("*.aadl")
)
LIBRARY_FILES = sorted((ROOT / "library").rglob("*.aadl"))


def _params(files: list[Path], base: Path, reason: str):
    return [pytest.param(p, id=str(p.relative_to(base))) for p in files] or [
        pytest.param(None, marks=pytest.mark.skip(reason=reason))
    ]


@pytest.mark.corpus
@pytest.mark.parametrize("path", _params(CORPUS_FILES, CORPUS, f"real-world corpus not found at {CORPUS}"))
def test_corpus_round_trip(path: Path, tmp_path: Path) -> None:
    first = _read_each([path])
    assert first.units, f"{path} holds no package or property set"
    _round_trip(first, tmp_path)


@pytest.mark.parametrize("path", _params(LIBRARY_FILES, ROOT / "library", "no library .aadl files"))
def test_library_round_trip(path: Path, tmp_path: Path) -> None:
    _round_trip(_read_each([path]), tmp_path)


def test_library_written_text_resolves(tmp_path: Path) -> None:
    """The whole library, written and read back with names resolved across files, is the same model."""
    first = read_files([], include_library=True)
    written = write_model(first, tmp_path)
    second = read_files(written, include_library=False)
    diffs = _differences(first, second)
    assert not diffs, "\n".join(diffs[:20])


def test_everything_model_round_trip(tmp_path: Path) -> None:
    ws = everything_model()
    first = _read_each(write_model(ws, tmp_path / "first"))
    _round_trip(first, tmp_path / "second")
    # what the reader made of the text is what the model said, as the reader keeps bindings (with
    # their parentheses) and annex text (without its delimiters)
    ws.units[0].classifiers[2].prototypeBindings = "(msg => data Base_Types::Integer)"
    ws.units[0].annexLibraries[0].text = " error types Fail: type; end types; "
    assert sorted(_differences(ws, first)) == sorted(
        [
            # the access category the model left open is inferred by the writer from the ends
            "AadlModel(ws)/AadlPackage(robot::nav)/ComponentImplementation(nav_proc.impl)/Connection(c_map)"
            ".accessCategory: 'abstract' != 'data'",
            "AadlModel(ws)/AadlPackage(robot::nav)/ComponentImplementation(rig.impl)/Connection(c_lan)"
            ".accessCategory: 'abstract' != 'bus'",
        ]
    )


def test_undirected_features_keep_no_direction() -> None:
    text = (
        "package P\npublic\n  system T\n    features\n      fg: feature group G;\n      af: feature;\n"
        "  end T;\nend P;\n"
    )
    assert write_unit(read_string(text, "p.aadl").units[0]) == text


def test_corpus_files_are_found(corpus: Path) -> None:
    assert len(CORPUS_FILES) >= 100
    assert {p.relative_to(corpus).parts[0] for p in CORPUS_FILES} == {"osate", "aadl-ros", "cheddar"}
    assert len(LIBRARY_FILES) >= 10


def test_call_properties_and_private_renamings_and_annexes_round_trip() -> None:
    text = (
        "package cb\npublic\n  subprogram sp\n  end sp;\n  thread t\n  end t;\n  thread implementation t.i\n"
        '  calls\n    seq: { c1: subprogram sp {Source_Name => "x";}; };\n  end t.i;\nprivate\n'
        "  with Base_Types;\n  sp2 renames subprogram sp;\n"
        "  annex EMV2 {** error types end types; **};\nend cb;\n"
    )
    first = read_string(text, "cb.aadl")
    unit = next(u for u in first.units if u.name == "cb")
    written = write_unit(unit)
    assert 'c1: subprogram sp { Source_Name => "x"; };' in written
    assert written.index("private") < written.index("sp2 renames") < written.index("annex EMV2")
    second = read_string(written, "again.aadl")
    again = next(u for u in second.units if u.name == "cb")
    assert model.model_differences(unit, again, ignore=IGNORED) == []

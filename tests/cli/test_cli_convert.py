"""``rosaadl convert`` ROSMOD → AADL → ROSMOD from the command line, with the trace."""

from __future__ import annotations

from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.cli import main
from rosaadl.importers.rosmod_text import read_project


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.corpus
def test_rosmod_to_aadl_and_back_with_trace(corpus: Path, tmp_path: Path, capsys) -> None:
    project = corpus / "rosmod/textual-v0.3/three-components"
    trace = tmp_path / "run.trace.xmi"
    code, _, err = run(["convert", str(project), "-o", str(tmp_path / "aadl"), "--trace", str(trace)], capsys)
    assert code == 0, err
    assert trace.exists() and any(p.suffix == ".aadl" for p in (tmp_path / "aadl").iterdir())
    code, _, err = run(["check", str(tmp_path / "aadl")], capsys)
    assert code == 0, err
    code, _, err = run(
        [
            "convert",
            str(tmp_path / "aadl"),
            "--to",
            "rosmod",
            "-o",
            str(tmp_path / "back"),
            "--trace",
            str(trace),
        ],
        capsys,
    )
    assert code == 0, err
    original, back = read_project(project), read_project(tmp_path / "back")
    assert sorted(c.name for p in back.software.packages for c in p.components) == sorted(
        c.name for p in original.software.packages for c in p.components
    )
    assert sorted(d.name for d in back.deployments) == sorted(d.name for d in original.deployments)
    _ = model  # the projects are rosmod models


@pytest.mark.corpus
def test_webgmex_archive_converts_each_project_into_a_subfolder(corpus: Path, tmp_path: Path, capsys) -> None:
    seed = corpus / "rosmod/webgme/samples-2018-05-19_noTLC.webgmex"
    code, _, err = run(["convert", str(seed), "-o", str(tmp_path / "out")], capsys)
    assert code == 0, err
    assert len([p for p in (tmp_path / "out").iterdir() if p.is_dir()]) == 4


def test_convert_bad_inputs(tmp_path: Path, capsys) -> None:
    code, _, err = run(["convert", str(tmp_path / "none"), "-o", str(tmp_path / "o")], capsys)
    assert code == 2 and "no such file" in err
    broken = tmp_path / "broken"
    (broken / "01-Software").mkdir(parents=True)
    (broken / "broken.rosmod").write_text("This is a ROSMOD Project")
    (broken / "01-Software" / "software.rml").write_text("package p\n{\n  component C : Base\n  {\n")
    code, _, err = run(["convert", str(broken), "-o", str(tmp_path / "o")], capsys)
    assert code == 1 and "software.rml:" in err
    assert not (tmp_path / "o").exists()

"""``rosaadl import`` and ``check`` on real files of every supported tool, and on bad input."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.cli import main


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def _aaxl2(corpus: Path) -> Path:
    return next((corpus / "osate/aaxl2/ex-latency-normal").rglob("*.aaxl2"))


@pytest.mark.corpus
@pytest.mark.parametrize(
    ("relative", "kind", "root_class"),
    [
        ("cheddar/rm_test_case_3tasks.xml", "aadl", "AadlModel"),
        ("cheddar/ravenscar_pip_resource.xmlv3", "aadl", "AadlModel"),
        ("rosmod/textual-v0.3/three-components", "rosmod", "Project"),
        (None, "aadl", "AadlModel"),
    ],
    ids=["cheddar-v2", "cheddar-v3", "rosmod-project", "aaxl2"],
)
def test_import_real_files(corpus: Path, tmp_path: Path, capsys, relative, kind, root_class) -> None:
    source = corpus / relative if relative else _aaxl2(corpus)
    out = tmp_path / "model.json"
    code, stdout, stderr = run(["--format", "json", "import", str(source), "-o", str(out)], capsys)
    assert code == 0, stderr
    doc = json.loads(stdout)
    assert doc["ok"] is True and doc["kind"] == kind and doc["output"] == str(out)
    loaded = model.load(out)
    assert loaded.eClass.name == root_class
    code, _, stderr = run(["check", str(out)], capsys)
    assert code == 0, stderr


@pytest.mark.corpus
def test_webgmex_with_several_projects_needs_project(corpus: Path, tmp_path: Path, capsys) -> None:
    seed = corpus / "rosmod/webgme/samples-2018-05-19_noTLC.webgmex"
    code, _, err = run(["import", str(seed), "-o", str(tmp_path / "x.json")], capsys)
    assert code == 2 and "--project" in err and "AGSE" in err
    code, _, err = run(["import", str(seed), "--project", "AGSE", "-o", str(tmp_path / "agse.xmi")], capsys)
    assert code == 0, err
    assert model.load(tmp_path / "agse.xmi").name == "AGSE"


def test_bad_inputs_are_located_exit_1_and_write_nothing(tmp_path: Path, capsys) -> None:
    truncated = tmp_path / "t.aaxl2"
    truncated.write_text(
        '<?xml version="1.0" encoding="ASCII"?>\n<instance:SystemInstance xmlns:instance="x"\n'
    )
    bomb = tmp_path / "b.xmlv3"
    bomb.write_text('<?xml version="1.0"?>\n<!DOCTYPE c [<!ENTITY a "aaaa">]>\n<cheddar>&a;</cheddar>\n')
    evil_zip = tmp_path / "evil.webgmex"
    with zipfile.ZipFile(evil_zip, "w") as archive:
        archive.writestr("../../x", "boom")
    not_zip = tmp_path / "n.webgmex"
    not_zip.write_bytes(b"not a zip at all")
    for bad in (truncated, bomb, evil_zip, not_zip):
        out = tmp_path / f"{bad.stem}.json"
        code, stdout, err = run(["--format", "json", "import", str(bad), "-o", str(out)], capsys)
        assert code == 1, (bad, err)
        doc = json.loads(stdout)
        assert doc["ok"] is False and doc["errors"]
        assert all(e["file"] and str(bad.name) in e["file"] for e in doc["errors"]), doc["errors"]
        assert not out.exists()
    assert not (tmp_path.parent / "x").exists()


def test_usage_errors(tmp_path: Path, capsys) -> None:
    code, _, err = run(["import", str(tmp_path / "missing.aaxl2"), "-o", str(tmp_path / "m.xmi")], capsys)
    assert code == 2 and "no such file" in err
    source = tmp_path / "m.xmlv3"
    source.write_text("<cheddar/>")
    code, _, err = run(["import", str(source), "-o", str(tmp_path / "m.txt")], capsys)
    assert code == 2 and ".xmi or .json" in err
    empty = tmp_path / "empty"
    empty.mkdir()
    code, _, err = run(["check", str(empty)], capsys)
    assert code == 2 and "neither a ROSMOD project nor .aadl files" in err

"""``rosaadl check``: AADL text given together is one workspace; other inputs are checked alone."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.cli import main
from rosaadl.formats import check_inputs
from tests.importers.test_aadl_text_files import PROJECTS

FUNCTIONAL = """package functional
public
  abstract sensing
  features
    reading : out data port;
  end sensing;
end functional;
"""

ROBOT = """package robot
public
  with functional;
  abstract lidar extends functional::sensing
  end lidar;
end robot;
"""


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture
def two_files(tmp_path: Path) -> tuple[Path, Path]:
    functional, robot = tmp_path / "functional.aadl", tmp_path / "robot.aadl"
    functional.write_text(FUNCTIONAL)
    robot.write_text(ROBOT)
    return functional, robot


def test_files_given_together_name_each_other(two_files, capsys) -> None:
    functional, robot = two_files
    code, out, err = run(["check", str(functional), str(robot)], capsys)
    assert code == 0, err
    assert out.splitlines() == [f"{functional}: ok", f"{robot}: ok"]
    code, out, err = run(["check", str(robot), str(functional)], capsys)
    assert code == 0, err


def test_a_file_alone_still_misses_what_it_names(two_files, capsys) -> None:
    _, robot = two_files
    code, out, err = run(["check", str(robot), "--format", "json"], capsys)
    assert code == 1
    doc = json.loads(out)
    (error,) = [e for e in doc["errors"] if "functional::sensing" in e["message"]]
    assert "not found" in error["message"] and error["file"] == str(robot) and error["line"] == 4


def test_a_folder_and_a_file_are_one_workspace(two_files, tmp_path, capsys) -> None:
    functional, robot = two_files
    folder = tmp_path / "packages"
    folder.mkdir()
    functional.rename(folder / functional.name)
    code, _, err = run(["check", str(folder), str(robot)], capsys)
    assert code == 0, err


def test_each_finding_goes_to_the_input_it_is_in(two_files, tmp_path, capsys) -> None:
    functional, robot = two_files
    other = tmp_path / "other.aadl"
    other.write_text(ROBOT.replace("package robot", "package other").replace("end robot", "end other"))
    other.write_text(other.read_text().replace("functional::sensing", "functional::nothing"))
    code, out, _ = run(["--format", "json", "check", str(functional), str(robot), str(other)], capsys)
    assert code == 1
    doc = json.loads(out)
    assert [(f["file"], f["errors"]) for f in doc["files"]] == [
        (str(functional), 0),
        (str(robot), 0),
        (str(other), 1),
    ]
    (error,) = doc["errors"]
    assert error["file"] == str(other) and "functional::nothing" in error["message"]


def test_files_that_do_not_read_are_each_reported(two_files, tmp_path, capsys) -> None:
    functional, robot = two_files
    broken = tmp_path / "broken.aadl"
    broken.write_text("package broken\npublic\n  system s\n")
    truncated = tmp_path / "truncated.aadl"
    truncated.write_text(FUNCTIONAL[: len(FUNCTIONAL) // 2])
    code, out, err = run(
        ["--format", "json", "check", str(functional), str(broken), str(robot), str(truncated)], capsys
    )
    assert code == 1, err
    doc = json.loads(out)
    assert {f["file"] for f in doc["files"] if f["errors"]} == {str(broken), str(truncated)}
    assert all(isinstance(e["line"], int) for e in doc["errors"])
    assert any("not resolved across the files" in w["message"] for w in doc["warnings"])


def test_other_formats_are_checked_alone_beside_aadl(two_files, tmp_path, capsys) -> None:
    functional, robot = two_files
    ws = model.new("AadlModel", name="ws", units=[model.new("AadlPackage", name="p")])
    xmi = model.save(ws, tmp_path / "good.xmi")
    code, out, err = run(["check", str(functional), str(xmi), str(robot)], capsys)
    assert code == 0, err
    assert out.splitlines() == [f"{functional}: ok", f"{xmi}: ok", f"{robot}: ok"]
    results = check_inputs([functional, xmi, robot])
    assert [r.path for r in results] == [functional, xmi, robot]


def test_a_missing_input_is_a_usage_error_before_reading(two_files, tmp_path, capsys) -> None:
    functional, _ = two_files
    code, out, err = run(["check", str(functional), str(tmp_path / "nope.aadl")], capsys)
    assert code == 2 and "no such file" in err and out == ""


# ----------------------------------------------------------------- the corpus's OSATE projects

#: Each OSATE project of the corpus (a folder of ``osate/aaxl2/``; gtse-atsv-tier0 holds two
#: copies of one Eclipse project, and one project is one copy) with, when its sources are
#: incomplete, the names its errors must all be about: the one table of the corpus's projects,
#: kept with the reader's tests (which also check that it lists every case).
OSATE_PROJECTS: dict[str, tuple[str, ...]] = {
    folder.removeprefix("osate/aaxl2/"): incomplete[0] if incomplete else ()
    for folder, options, incomplete in PROJECTS
    if folder.startswith("osate/aaxl2/") and not options
}


def _aadl_files(folder: Path) -> list[str]:
    """What ``find PROJECT -name '*.aadl'`` gives (and ``.aadl2``, the older suffix)."""
    return sorted(
        str(p) for p in folder.rglob("*") if p.suffix.lower() in (".aadl", ".aadl2") and p.is_file()
    )


def test_the_table_holds_complete_and_incomplete_projects() -> None:
    assert len(OSATE_PROJECTS) >= 20
    assert OSATE_PROJECTS["ex-carsystem"] and not OSATE_PROJECTS["ex-latency-normal"]


@pytest.mark.corpus
@pytest.mark.parametrize(("project", "missing"), OSATE_PROJECTS.items(), ids=list(OSATE_PROJECTS))
def test_check_every_file_of_a_corpus_project(corpus: Path, project: str, missing, capsys) -> None:
    """``rosaadl check $(find PROJECT -name '*.aadl')``: 0 on a complete project, 1 with located
    "not found" errors, about the missing packages only, on an incomplete one."""
    folder = corpus / "osate" / "aaxl2" / project
    if not folder.is_dir():
        pytest.skip(f"{project} is not in the corpus")
    files = _aadl_files(folder)
    assert files
    code, out, err = run(["--format", "json", "check", *files], capsys)
    doc = json.loads(out)
    if not missing:
        assert code == 0, "\n".join(e["message"] for e in doc["errors"]) + err
        return
    assert code == 1 and doc["errors"]
    for error in doc["errors"]:
        assert error["file"] in files and isinstance(error["line"], int), error
        assert "not found" in error["message"] and any(name in error["message"] for name in missing), error

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


def to_aadl_and_back(source: Path, tmp_path: Path, capsys) -> tuple[Path, Path]:
    """``convert SOURCE -o aadl --trace T`` then ``convert aadl --to rosmod -o back --trace T``."""
    aadl, back, trace = tmp_path / "aadl", tmp_path / "back", tmp_path / "run.trace.xmi"
    code, _, err = run(["convert", str(source), "-o", str(aadl), "--trace", str(trace)], capsys)
    assert code == 0, err
    code, _, err = run(
        ["convert", str(aadl), "--to", "rosmod", "-o", str(back), "--trace", str(trace)], capsys
    )
    assert code == 0, err
    return aadl, back


def assert_same_components_and_deployments(original, back) -> None:
    assert sorted(c.name for p in back.software.packages for c in p.components) == sorted(
        c.name for p in original.software.packages for c in p.components
    )
    assert sorted(d.name for d in back.deployments) == sorted(d.name for d in original.deployments)


@pytest.mark.corpus
def test_rosmod_to_aadl_and_back_with_trace(corpus: Path, tmp_path: Path, capsys) -> None:
    project = corpus / "rosmod/textual-v0.3/three-components"
    aadl, back = to_aadl_and_back(project, tmp_path, capsys)
    assert (tmp_path / "run.trace.xmi").exists() and any(p.suffix == ".aadl" for p in aadl.iterdir())
    code, _, err = run(["check", str(aadl)], capsys)
    assert code == 0, err
    assert_same_components_and_deployments(read_project(project), read_project(back))
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


# ----------------------------------------------------- several projects: one folder per project

RML = """package nav
{
  component Planner : Base
  {
    publisher <nav/Goal> goal_pub;
    subscriber <nav/Goal> goal_sub { priority = 60; deadline = 0.250; }
    timer tick { period = 0.1; priority = 50; deadline = 0.05; }
  }
}
"""
RHW = 'hardware board-1 { ip_address = "10.0.0.2"; arch = armv7l; }\n'
RDP = """using Local;
node planner_node
{
  properties { ref = "Local/board-1"; priority = 70; }
  component_instance planner { properties { ref = "nav/Planner"; scheduling_scheme = PFIFO; } }
}
"""


def _rosmod_project(folder: Path, name: str) -> Path:
    """A small v0.3 project; two of them share their package, hardware and deployment names, as
    the projects of one WebGME archive do (``Local`` hardware in each)."""
    files = {
        f"{name}.rosmod": "This is a ROSMOD Project",
        "01-Software/nav.rml": RML,
        "01-Software/msg/nav.Goal.msg": "float64 x\n",
        "02-Hardware/Local.rhw": RHW,
        "03-Deployment/Local Deployment.rdp": RDP,
    }
    for relative, text in files.items():
        (folder / relative).parent.mkdir(parents=True, exist_ok=True)
        (folder / relative).write_text(text)
    return folder


@pytest.fixture
def two_projects_as_aadl(tmp_path: Path, capsys) -> Path:
    """What ``convert`` writes for an archive of two projects: one AADL folder per project, and
    one trace per project (``run.trace_<folder>.xmi``)."""
    from rosaadl.workflow.convert import convert_project_files, project_trace

    out = tmp_path / "aadl"
    for name in ("alpha", "beta"):
        source = _rosmod_project(tmp_path / "rosmod" / name, name)
        convert_project_files(source, out / name, trace_file=project_trace(tmp_path / "run.trace.xmi", name))
    return out


def test_a_folder_of_several_projects_converts_each_on_its_own(
    two_projects_as_aadl, tmp_path, capsys
) -> None:
    back = tmp_path / "back"
    code, out, err = run(["convert", str(two_projects_as_aadl), "--to", "rosmod", "-o", str(back)], capsys)
    assert code == 0, err
    assert sorted(p.name for p in back.iterdir()) == ["alpha", "beta"]
    for name in ("alpha", "beta"):
        project = read_project(back / name)
        assert project.name == name
        assert [c.name for p in project.software.packages for c in p.components] == ["Planner"]
        assert [d.name for d in project.deployments] == ["Local Deployment"]


def test_each_project_takes_its_own_trace(two_projects_as_aadl, tmp_path, capsys) -> None:
    back = tmp_path / "back"
    trace = tmp_path / "run.trace.xmi"
    code, _, err = run(
        ["convert", str(two_projects_as_aadl), "--to", "rosmod", "-o", str(back), "--trace", str(trace)],
        capsys,
    )
    assert code == 0, err
    assert {h.name for h in read_project(back / "beta").systems[0].hosts} == {"board-1"}
    (tmp_path / "run.trace_beta.xmi").unlink()
    code, _, err = run(
        [
            "convert",
            str(two_projects_as_aadl),
            "--to",
            "rosmod",
            "-o",
            str(tmp_path / "b2"),
            "--trace",
            str(trace),
        ],
        capsys,
    )
    assert code == 2 and "run.trace_beta.xmi" in err and "no such trace file" in err
    assert not (tmp_path / "b2").exists()


def test_a_broken_project_among_several_writes_nothing(two_projects_as_aadl, tmp_path, capsys) -> None:
    broken = next((two_projects_as_aadl / "beta").glob("nav*.aadl"))
    broken.write_text(broken.read_text()[:200])
    code, _, err = run(
        ["convert", str(two_projects_as_aadl), "--to", "rosmod", "-o", str(tmp_path / "back")], capsys
    )
    assert code == 1 and f"{broken}:" in err
    assert not (tmp_path / "back").exists()


def test_folders_that_are_not_several_projects_stay_one_workspace(two_projects_as_aadl, tmp_path) -> None:
    from rosaadl.workflow.convert import project_folders

    assert project_folders(two_projects_as_aadl) == [
        two_projects_as_aadl / "alpha",
        two_projects_as_aadl / "beta",
    ]
    assert project_folders(two_projects_as_aadl / "alpha") == []  # one project
    nested = tmp_path / "nested"
    (nested / "a").mkdir(parents=True)
    (nested / "b").mkdir()
    (nested / "a" / "p.aadl").write_text("package p\npublic\n  system s\n  end s;\nend p;\n")
    (nested / "b" / "q.aadl").write_text("package q\npublic\n  system t\n  end t;\nend q;\n")
    assert project_folders(nested) == []  # plain AADL in subfolders: no project package
    (nested / "c").mkdir()
    for name in ("alpha", "beta"):  # a third folder that is no project: one workspace
        for source in (two_projects_as_aadl / name).iterdir():
            (nested / name).mkdir(exist_ok=True)
            (nested / name / source.name).write_bytes(source.read_bytes())
    assert project_folders(nested) == []


@pytest.mark.corpus
def test_webgmex_archive_to_aadl_and_back_per_project(corpus: Path, tmp_path: Path, capsys) -> None:
    from rosaadl.importers.rosmod_webgme import read_webgmex

    seed = corpus / "rosmod/webgme/samples-2018-05-19_noTLC.webgmex"
    aadl, back = to_aadl_and_back(seed, tmp_path, capsys)
    folders = sorted(p.name for p in aadl.iterdir())
    assert sorted(p.name for p in back.iterdir()) == folders and len(folders) == 4
    originals = {p.name.replace(" ", "_"): p for p in read_webgmex(seed)}  # the folders' names
    for folder in folders:
        assert_same_components_and_deployments(originals[folder], read_project(back / folder))


@pytest.mark.corpus
def test_a_convert_that_fails_on_the_sixth_file_writes_none(corpus: Path, tmp_path: Path, capsys) -> None:
    """The sixth output's name is taken by a folder: exit 1 naming it, and none of the other
    files is written (all are written to temporaries first, then renamed)."""
    out = tmp_path / "aadl"
    (out / "Component_2_Benchmark_deployment.aadl").mkdir(parents=True)
    code, _, err = run(
        ["convert", str(corpus / "rosmod/textual-v0.3/three-components"), "-o", str(out)], capsys
    )
    assert code == 1 and "Component_2_Benchmark_deployment.aadl" in err and "folder" in err, err
    assert [p.name for p in out.iterdir()] == ["Component_2_Benchmark_deployment.aadl"]

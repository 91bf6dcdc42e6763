"""``rosaadl demo``: the whole workflow on the bundled example, its artefacts, its summary, and one
clear line for bad input."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import time

import pytest

from rosaadl.cli import main
from rosaadl.cli.demo import STAGES, example_project

PIONEER_LINE = (
    "pioneer_3dx: core little_proc1 (Exynos_5422::ARM_A7) at 118.1 % — overloaded (not schedulable, "
    "3 deadline misses in simulation); proposed binding passes (max core 74 %)"
)


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    """One real run of ``rosaadl demo -o OUT`` in a process of its own."""
    out = tmp_path_factory.mktemp("demo") / "out"
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "rosaadl", "demo", "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    return done, out, time.perf_counter() - started


def test_demo_runs_every_stage_and_exits_0(demo) -> None:
    done, _out, seconds = demo
    assert done.returncode == 0, done.stderr
    progress = [line for line in done.stderr.splitlines() if line.startswith("[")]
    assert [line.partition("]")[0] + "]" for line in progress] == [
        f"[{i}/{len(STAGES)}]" for i in range(1, 11)
    ]
    assert "pending" not in done.stdout
    assert seconds < 60


def test_demo_summary_names_the_overload_and_the_remedy(demo) -> None:
    done, out, _ = demo
    lines = [line.strip() for line in done.stdout.splitlines()]
    assert PIONEER_LINE in lines
    assert "leo_rover: binding passes (max core proc1 at 31.5 %)" in lines
    proposed = next(line for line in lines if line.startswith("proposed (pioneer_3dx_proposed):"))
    assert "tracker_node on big_proc" in proposed
    assert any(line.startswith("budget finding on pioneer_3dx:") for line in lines)
    assert str(out) in lines[0]


ARTEFACTS = [
    "report.html",
    "report.json",
    "aadl/tracking.aadl",
    "aadl/pioneer_3dx_deployment.aadl",
    "aadl/leo_rover_deployment.aadl",
    "aadl/pioneer_3dx_bound.aadl",
    "aadl/leo_rover_bound.aadl",
    "aadl/pioneer_3dx_proposed.aadl",
    "ros2_ws/src/tracking_bringup/package.xml",
]
PER_DEPLOYMENT = [
    "report.html",
    "report.json",
    "analysis/analyses.json",
    "analysis/tracking_impl_Instance__BoundResourceAnalysis.csv",
    "analysis/tracking_impl_Instance__BusLoad.csv",
    "analysis/tracking_impl_Instance__Schedulability.csv",
    "{name}.xmlv3",
    "osate/instances/{package}_tracking_impl_Instance.aaxl2",
    "osate/{package}.aadl",
]
DEPLOYMENTS = {
    "pioneer_3dx": "pioneer_3dx_bound",
    "leo_rover": "leo_rover_bound",
    "pioneer_3dx_proposed": "pioneer_3dx_proposed",
}


def test_every_artefact_exists_and_is_not_empty(demo) -> None:
    _done, out, _ = demo
    expected = [out / name for name in ARTEFACTS]
    for name, package in DEPLOYMENTS.items():
        expected += [out / name / item.format(name=name, package=package) for item in PER_DEPLOYMENT]
    missing = [str(p.relative_to(out)) for p in expected if not p.is_file() or p.stat().st_size == 0]
    assert missing == []
    assert (out / "pioneer_3dx" / "analysis" / "tracking_impl_Instance__Deployment.csv").is_file()
    assert len(list((out / "ros2_ws" / "src").rglob("*.py"))) > 5


def test_the_headline_report_shows_the_overload_and_the_proposal(demo) -> None:
    _done, out, _ = demo
    view = json.loads((out / "report.json").read_text())
    assert view["classifier"] == "pioneer_3dx_bound::tracking.impl"
    headlines = {h["key"]: h for h in view["findings"]["headlines"]}
    assert headlines["cpu"]["value"] == "118.1 %"
    assert headlines["deploy"]["value"] == "feasible"
    html = (out / "report.html").read_text()
    assert "<svg" in html and "Proposed deployment" in html
    leo = json.loads((out / "leo_rover" / "report.json").read_text())
    assert leo["ok"] is True


def test_analyses_json_is_the_analyze_verbs_document(demo) -> None:
    _done, out, _ = demo
    document = json.loads((out / "pioneer_3dx" / "analysis" / "analyses.json").read_text())
    assert document["ok"] is False
    cores = {
        p["path"].rpartition(".")[2]: p["load_percent"] for p in document["analyses"]["cpu"]["processors"]
    }
    assert cores["little_proc1"] == pytest.approx(118.06)
    assert document["analyses"]["deployment"]["feasible"] is True


def test_json_format_gives_one_document(tmp_path, capsys) -> None:
    code = main(["--format", "json", "-q", "demo", "-o", str(tmp_path / "out")])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    document = json.loads(captured.out)
    assert document["ok"] is True and document["pending"] == []
    assert [s["stage"] for s in document["stages"]] == [key for key, _ in STAGES]
    assert document["deployments"]["pioneer_3dx"]["overloaded"][0]["core"].endswith("little_proc1")
    assert document["deployments"]["pioneer_3dx_proposed"]["binding_passes"] is True
    assert document["workspace_from"] == "pioneer_3dx_proposed"
    assert captured.err == ""  # -q: no progress


# ----------------------------------------------------------------------------- bad input


def one_line(err: str) -> str:
    lines = [line for line in err.splitlines() if line.strip()]
    assert len(lines) == 1, err
    return lines[0]


def test_missing_project_folder_is_a_usage_error(tmp_path, capsys) -> None:
    code = main(["demo", "--project", str(tmp_path / "nowhere"), "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2
    assert one_line(err) == f"error: no ROSMOD project folder at {tmp_path / 'nowhere'}"
    assert not (tmp_path / "out").exists()


def test_empty_folder_is_not_a_project(tmp_path, capsys) -> None:
    (tmp_path / "empty").mkdir()
    code = main(["demo", "--project", str(tmp_path / "empty"), "-o", str(tmp_path / "out")])
    assert code == 2
    assert "is not a ROSMOD project folder" in one_line(capsys.readouterr().err)


def test_missing_bindings_file(tmp_path, capsys) -> None:
    project = tmp_path / "tracking"
    shutil.copytree(example_project(), project)
    (project / "bindings.json").unlink()
    code = main(["demo", "--project", str(project), "-o", str(tmp_path / "out")])
    assert code == 2
    assert "no bindings file at" in one_line(capsys.readouterr().err)


def test_output_that_is_a_file(tmp_path, capsys) -> None:
    (tmp_path / "out").write_text("x")
    code = main(["demo", "-o", str(tmp_path / "out")])
    assert code == 2
    assert "is a file, not a folder" in one_line(capsys.readouterr().err)


def test_a_wrong_binding_fails_its_stage_with_a_located_error(tmp_path, capsys) -> None:
    project = tmp_path / "tracking"
    shutil.copytree(example_project(), project)
    bindings = project / "bindings.json"
    bindings.write_text(bindings.read_text().replace("little_proc1", "little_proc9", 1))
    code = main(["demo", "--project", str(project), "-o", str(tmp_path / "out")])
    captured = capsys.readouterr()
    assert code == 1
    errors = [line for line in captured.err.splitlines() if line.startswith("error:")]
    assert len(errors) == 1
    assert f"{bindings}:10 deployments.pioneer_3dx.nodes.usb_cam_node.core" in errors[0]
    assert "the robot has no core" in errors[0]
    assert "[3/10] bind the deployments to robots of the library: failed" in captured.err
    assert "failed stages: bind" in captured.out
    assert not (tmp_path / "out" / "report.html").exists()


def test_a_failing_export_stage_does_not_stop_the_others(tmp_path, capsys) -> None:
    out = tmp_path / "out"
    (out / "ros2_ws").mkdir(parents=True)
    (out / "ros2_ws" / "src").write_text("not a folder")
    code = main(["demo", "-o", str(out)])
    captured = capsys.readouterr()
    assert code == 1
    assert "[9/10] generate the ROS 2 workspace: failed" in captured.err
    errors = [line for line in captured.err.splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and str(out / "ros2_ws" / "src") in errors[0]
    assert "failed stages: rclpy" in captured.out
    assert PIONEER_LINE in [line.strip() for line in captured.out.splitlines()]
    assert (out / "report.html").stat().st_size > 0  # the report stage still ran


def test_summary_counts_what_each_folder_received(tmp_path, capsys, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)  # a relative output folder, as `make demo` gives it
    assert main(["demo", "-o", "demo-out"]) == 0
    out = capsys.readouterr().out
    (line,) = [ln for ln in out.splitlines() if ln.strip().startswith("produced:")]
    counts = dict(re.findall(r"(\S+) \((\d+) files?\)", line))
    on_disk = {
        p.name: sum(1 for f in p.rglob("*") if f.is_file())
        for p in (tmp_path / "demo-out").iterdir()
        if p.is_dir()
    }
    for folder, files in on_disk.items():
        assert int(counts[folder]) == files, (folder, line)

"""``instantiate``, ``export`` and ``analyze`` from the command line, on the library's systems."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.cli import main

ROOT = Path(__file__).resolve().parents[2]
SYSTEMS = ROOT / "library" / "systems"


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_instantiate_writes_model_with_instance(tmp_path: Path, capsys) -> None:
    out = tmp_path / "tracking.xmi"
    code, stdout, err = run(
        [
            "--format",
            "json",
            "instantiate",
            str(SYSTEMS),
            "--root",
            "sys_tracking::tracking.impl",
            "-o",
            str(out),
        ],
        capsys,
    )
    assert code == 0, err
    doc = json.loads(stdout)
    assert doc["ok"] and doc["instance"] == "tracking_impl_Instance" and doc["components"] > 20
    loaded = model.load(out)
    (instance,) = loaded.instances
    path = "tracking_impl_Instance.p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1"
    assert model.find_instance(instance, path).category.name == "processor"


@pytest.mark.parametrize(
    ("root", "message"),
    [("sys_tracking::nope.impl", "not found"), ("sys_tracking::tracking", "implementation")],
)
def test_wrong_root_is_one_clear_line_and_exit_1(tmp_path: Path, capsys, root, message) -> None:
    code, _, err = run(["instantiate", str(SYSTEMS), "--root", root, "-o", str(tmp_path / "x.xmi")], capsys)
    assert code == 1 and message in err
    assert not (tmp_path / "x.xmi").exists()


def test_missing_input_and_empty_folder_are_usage_errors(tmp_path: Path, capsys) -> None:
    code, _, err = run(["analyze", str(tmp_path / "missing.aadl"), "--root", "a::b.i"], capsys)
    assert code == 2 and "no such file" in err
    (tmp_path / "empty").mkdir()
    code, _, err = run(["analyze", str(tmp_path / "empty"), "--root", "a::b.i"], capsys)
    assert code == 2 and "neither a ROSMOD project nor .aadl files" in err
    code, _, err = run(
        ["analyze", str(SYSTEMS), "--root", "sys_tracking::tracking.impl", "--only", "cpu,nope"], capsys
    )
    assert code == 2 and "unknown analysis nope" in err


def test_analyze_reports_the_overloaded_core_and_exits_1(tmp_path: Path, capsys) -> None:
    code, stdout, _ = run(
        [
            "--format",
            "json",
            "analyze",
            str(SYSTEMS),
            "--root",
            "sys_tracking::tracking.impl",
            "--only",
            "cpu,bus",
            "-o",
            str(tmp_path / "csv"),
        ],
        capsys,
    )
    assert code == 1
    doc = json.loads(stdout)
    assert doc["ok"] is False
    cores = {p["path"].rsplit(".", 1)[-1]: p for p in doc["analyses"]["cpu"]["processors"]}
    assert cores["big_proc2"]["load_percent"] == pytest.approx(111.0, abs=0.01)
    assert cores["big_proc1"]["load_percent"] == pytest.approx(6.96, abs=0.01)
    assert any("big_proc2" in (e.get("path") or "") for e in doc["errors"])
    assert sorted(p.suffix for p in (tmp_path / "csv").iterdir()) and doc["csv"]


def test_analyze_rover_passes(capsys) -> None:
    code, stdout, err = run(
        ["analyze", str(SYSTEMS), "--root", "sys_rover::rover.impl", "--only", "cpu,sched"], capsys
    )
    assert code == 0, stdout + err


def test_export_cheddar_and_reimport(tmp_path: Path, capsys) -> None:
    target = tmp_path / "tracking.xmlv3"
    code, _, err = run(
        ["export", "cheddar", str(SYSTEMS), "--root", "sys_tracking::tracking.impl", "-o", str(target)],
        capsys,
    )
    assert code == 0, err
    assert "not exported as a task" in err  # threads without execution time are said to be left out
    code, _, err = run(["import", str(target), "-o", str(tmp_path / "back.json")], capsys)
    assert code == 0, err


def test_export_aadl_writes_only_the_users_units(tmp_path: Path, capsys) -> None:
    source = tmp_path / "src"
    source.mkdir()
    (source / "demo.aadl").write_text(
        "package demo\npublic\n  thread worker\n  properties\n    Period => 10 ms;\n"
        "  end worker;\nend demo;\n"
    )
    code, stdout, err = run(["export", "aadl", str(source), "-o", str(tmp_path / "out")], capsys)
    assert code == 0, err
    assert [p.name for p in (tmp_path / "out").iterdir()] == ["demo.aadl"]
    assert "Period => 10 ms;" in (tmp_path / "out" / "demo.aadl").read_text()


def test_export_aaxl2_conforms_to_osates_metamodel(tmp_path: Path, capsys, corpus) -> None:
    import importlib.util
    import sys

    helper = Path(__file__).resolve().parents[1] / "exporters" / "osate_conformance.py"
    spec = importlib.util.spec_from_file_location("osate_conformance_cli", helper)
    conformance = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = conformance  # its dataclasses look their module up
    spec.loader.exec_module(conformance)
    code, _, err = run(
        ["export", "aaxl2", str(SYSTEMS), "--root", "sys_rover::rover.impl", "-o", str(tmp_path / "osate")],
        capsys,
    )
    assert code == 0, err
    (written,) = (tmp_path / "osate" / "instances").glob("*.aaxl2")
    result = conformance.check(written.read_bytes(), corpus / "osate" / "metamodel")
    assert result.ok, result
    code, _, err = run(["import", str(written), "-o", str(tmp_path / "back.json")], capsys)
    assert code == 0, err


def test_generate_rclpy_keeps_user_code_and_writes_nothing_on_dry_run(tmp_path: Path, capsys) -> None:
    out = tmp_path / "ws" / "src"
    args = ["generate", "rclpy", str(SYSTEMS), "--root", "sys_rover::rover.impl", "-o", str(out)]
    code, stdout, err = run(args, capsys)
    assert code == 0, err
    nodes = sorted(p for p in out.rglob("*.py") if "<user-code" in p.read_text())
    assert nodes, "generated nodes carry user-code markers"
    first = nodes[0]
    text = first.read_text()
    marker_end = text.index("# </user-code>")
    edited = (
        text[:marker_end] + "        self.get_logger().info('kept')  # hand-written\n" + text[marker_end:]
    )
    first.write_text(edited)
    code, _, err = run(args, capsys)
    assert code == 0, err
    assert "# hand-written" in first.read_text()
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    code, _, err = run([*args, "--dry-run"], capsys)
    assert code == 0, err
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before


def test_analyze_with_options_after_the_verb(capsys) -> None:
    """Options after the verb, as users type them: ``rosaadl analyze M --root R --format json``."""
    code, out, err = run(
        ["analyze", str(SYSTEMS), "--root", "sys_rover::rover.impl", "--only", "cpu", "--format", "json"],
        capsys,
    )
    assert code == 0, err
    assert json.loads(out)["ok"] is True

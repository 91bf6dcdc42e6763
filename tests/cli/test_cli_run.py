"""``rosaadl run`` without ROS 2 running: its arguments, bad inputs as located errors (exit 1 or
2, never a traceback), the run folder it generates, and user code kept when it regenerates."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rosaadl.cli import main
from rosaadl.workflow.run import PLAN_FILE

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "tracking"
ROOT = "leo_rover_deployment::leo_rover.impl"


@pytest.fixture
def no_ros(monkeypatch):
    """This Python as if it had no ROS 2 runtime."""
    monkeypatch.setattr("rosaadl.workflow.run.environment.ROS_MODULES", ("rosaadl_no_such_module",))


def test_duration_is_required(capsys):
    assert main(["run", str(EXAMPLE), "--root", ROOT]) == 2
    assert "--duration" in capsys.readouterr().err


def test_missing_input_is_a_usage_error(tmp_path, capsys):
    assert main(["run", str(tmp_path / "absent"), "--duration", "2"]) == 2
    assert "no such file or folder" in capsys.readouterr().err


def test_a_broken_run_folder_is_a_located_error(tmp_path, capsys):
    (tmp_path / PLAN_FILE).write_text('{"version": 1, "app": ', encoding="utf-8")
    assert main(["run", str(tmp_path), "--duration", "2", "--format", "json"]) == 1
    err = capsys.readouterr().err
    assert f"{tmp_path / PLAN_FILE}: unreadable run plan" in err
    assert "Traceback" not in err


def test_missing_runtime_says_how_to_install_it_and_user_code_survives_regeneration(tmp_path, capsys, no_ros):
    out = tmp_path / "run"
    args = ["run", str(EXAMPLE), "--root", ROOT, "--duration", "2", "-o", str(out)]
    assert main(args) == 1
    err = capsys.readouterr().err
    assert "the ROS 2 runtime is not installed" in err and "'.[ros]'" in err
    plan = json.loads((out / PLAN_FILE).read_text())
    assert [n["name"] for n in plan["nodes"]] == ["usb_cam_node", "tracker_node", "pos_to_cmd_node"]
    # user code written in the run folder is kept when the model is run again
    module = next((out / "src").glob("*/*/usb_cam*.py"))
    text = module.read_text()
    start = text.index("# <user-code name=", text.index("def on_"))
    line_end = text.index("\n", start) + 1
    module.write_text(text[:line_end] + "        self.frames = 42  # hand-written\n" + text[line_end:])
    assert main(args) == 1
    assert "self.frames = 42  # hand-written" in module.read_text()
    # and the run folder runs in place, without the model
    capsys.readouterr()
    assert main(["run", str(out), "--duration", "2", "--format", "json"]) == 1
    report = json.loads(capsys.readouterr().out)
    assert report["ok"] is False and report["nodes"] == [] and report["topics"] == []
    assert "the ROS 2 runtime is not installed" in report["errors"][0]["message"]
    assert main(["run", str(out), "--duration", "2", "-o", str(tmp_path / "other")]) == 2

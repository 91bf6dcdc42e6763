"""The executor analysis on instances (rosaadl.analysis.executor_analysis)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import rosaadl.library
from benchmarks.bench_executor import executor_fleet
from rosaadl.analysis import run_analyses
from rosaadl.analysis.executor_analysis import analyze_executors
from rosaadl.importers.aadl_text import read_files
from rosaadl.transforms.instantiate import instantiate

SYSTEMS = sorted(str(p) for p in (Path(rosaadl.library.__file__).parent / "systems").glob("*.aadl"))


@pytest.fixture(scope="module")
def rover():
    return instantiate(read_files(SYSTEMS, include_library=True), "sys_rover::rover.impl")


def test_tracking_report_shows_executor_bounds_beside_thread_bounds_and_the_chain(rover):
    report = run_analyses(rover)
    data = json.loads(report.to_json())["analyses"]["executor"]
    rows = {row["path"].rpartition(".")[2]: row for row in data["callbacks"]}
    assert rows["image_broadcaster"] == {
        "path": "rover_impl_Instance.rover_sw.usbcam.image_broadcaster",
        "executor": "rover_impl_Instance.rover_sw.usbcam",
        "kind": "timer",
        "wcrt": rows["image_broadcaster"]["thread_wcrt"],  # alone on its executor: its WCET
        "thread_wcrt": rows["image_broadcaster"]["thread_wcrt"],
        "deadline": 33333,
        "met": True,
    }
    assert rows["image_tracker"]["kind"] == "subscription"
    assert rows["image_tracker"]["wcrt"] is not None
    chains = {c["name"]: c for c in data["chains"]}
    camera_to_command = chains["rover_sw.usbcam.image_broadcaster -> rover_sw.poscmd.cmd_publisher"]
    assert [p.rpartition(".")[2] for p in camera_to_command["paths"]] == [
        "image_broadcaster", "image_tracker", "point_broadcaster", "point_receiver", "cmd_publisher",
    ]  # fmt: skip
    # timers add their period (sampling), subscriptions only their response time
    by = {p.rpartition(".")[2]: rows[p.rpartition(".")[2]]["wcrt"] for p in camera_to_command["paths"]}
    expected = 33333 + by["image_broadcaster"] + by["image_tracker"] + 100000 + by["point_broadcaster"]
    expected += by["point_receiver"] + 100000 + by["cmd_publisher"]
    assert camera_to_command["reaction_time"] == pytest.approx(expected, abs=1)
    assert camera_to_command["data_age"] == camera_to_command["reaction_time"]
    text = "\n".join(report.text()) if isinstance(report.text(), list) else report.text()
    assert "Callbacks under their executors" in text and "Cause-effect chains" in text


def test_generated_fleet_groups_callbacks_by_executor_and_kind():
    result = analyze_executors(executor_fleet(8, 4))
    assert len(result.executors) == 8
    assert {e.kind for e in result.executors} == {"single_threaded", "multi_threaded"}
    kinds = [c.kind for c in result.callbacks if c.executor.endswith("node0")]
    assert kinds == ["timer", "timer", "subscription", "subscription", "subscription"]
    assert len(result.chains) == 4
    assert all(c.wcrt is not None for c in result.callbacks)

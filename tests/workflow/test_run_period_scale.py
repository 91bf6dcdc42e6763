"""``rosaadl run --period-scale F|auto``: the nodes' periods scaled, and the model of such a run."""

from __future__ import annotations

from fractions import Fraction
from pathlib import Path

import pytest
from offset_sample import OFFSET_ROOT, write_offset_tracking

import rosaadl.library
from rosaadl.cli import main
from rosaadl.errors import ModelError
from rosaadl.exporters.rclpy import plan_workspace
from rosaadl.importers.aadl_text import read_files
from rosaadl.model import find_instance
from rosaadl.properties import property_value
from rosaadl.transforms.instantiate import instantiate
from rosaadl.transforms.time_scale import scale_periods
from rosaadl.workflow.run.cores import Machine
from rosaadl.workflow.run.period_scale import (
    auto_period_scale,
    parse_period_scale,
    predicted_cpu_loads,
    scaled_plan,
)
from rosaadl.workflow.run.plan import RunError, run_plan

SYSTEMS = Path(rosaadl.library.__file__).parent / "systems"
ROOT = "sys_tracking::tracking.impl"


@pytest.fixture(scope="module")
def plan():
    return run_plan(plan_workspace(instantiate(read_files([SYSTEMS]), ROOT)))


def _parameters(plan, node: str) -> dict:
    return dict(next(n for n in plan.nodes if n.name == node).parameters)


def test_periods_and_deadlines_are_scaled_and_execution_times_kept(plan) -> None:
    scaled = scaled_plan(plan, 2.0)
    before, after = _parameters(plan, "ocv_color_tracking"), _parameters(scaled, "ocv_color_tracking")
    assert after["image_tracker.period"] == pytest.approx(2 * before["image_tracker.period"])
    assert after["image_tracker.deadline"] == pytest.approx(2 * before["image_tracker.deadline"])
    assert after["image_tracker.cet_max"] == before["image_tracker.cet_max"] == 0.037
    assert after["image_tracker.priority"] == before["image_tracker.priority"]
    image = next(t for t in scaled.topics if t.name == "/usb_cam/image_raw")
    assert image.model_rate_hz == pytest.approx(30.0003 / 2, rel=1e-4)
    assert scaled_plan(plan, 1.0) is plan and _parameters(plan, "ocv_color_tracking") == before


def test_auto_keeps_every_cpu_of_two_at_most_60_percent(plan) -> None:
    here = Machine(cpus=[0, 1])
    # usb_cam on core 0 and pos_to_cmd on core 4 share CPU 0, the tracker (111 %) has CPU 1
    loads = predicted_cpu_loads(plan.nodes, here)
    assert loads[1] == pytest.approx(111.0, abs=0.01)
    assert loads[0] == pytest.approx(6.957 + 1.06, abs=0.01)
    assert auto_period_scale(plan.nodes, here) == 1.9  # 111 / 1.9 = 58.4 %; 111 / 1.8 = 61.7 %
    assert auto_period_scale(plan.nodes, Machine(cpus=list(range(8)))) == 1.9
    lightly = [n for n in plan.nodes if n.name != "ocv_color_tracking"]
    assert auto_period_scale(lightly, here) == 1.0


@pytest.mark.parametrize("text", ["0", "-1", "nan", "inf", "fast"])
def test_a_scale_that_is_no_positive_number_is_refused(text, capsys) -> None:
    with pytest.raises(RunError, match="greater than 0 or auto"):
        parse_period_scale(text)
    assert main(["run", str(SYSTEMS), "--root", ROOT, "--duration", "1", "--period-scale", text]) == 2


def test_auto_and_numbers_are_read() -> None:
    assert parse_period_scale("auto") is None and parse_period_scale("AUTO") is None
    assert parse_period_scale("1.9") == 1.9


def test_the_model_of_a_scaled_run_has_its_periods_and_deadlines_scaled() -> None:
    instance = instantiate(read_files([SYSTEMS]), ROOT)
    assert scale_periods(instance, 1.9) == 10  # the Periods of 3 processes, 6 threads and the camera
    tracker = find_instance(instance, "rem_trk_sw.tracker.image_tracker")
    assert property_value(tracker, "Period").to("ns") == 63332700  # 33333 us × 1.9
    assert property_value(tracker, "Compute_Execution_Time").maximum.to("us") == 37000
    assert property_value(find_instance(instance, "p3DX.camera"), "Period").to("ns") == 63332700
    assert scale_periods(instance, Fraction(1)) == 0
    with pytest.raises(ModelError, match="positive number"):
        scale_periods(instance, 0)


def test_a_dispatch_offset_is_given_to_its_timer_and_scaled_with_the_periods(tmp_path) -> None:
    """A periodic thread's Dispatch_Offset reaches its node as ``<thread>.offset`` (seconds,
    where the generated timer releases in its period); a period scale multiplies it with the
    periods, in the run's parameters as in the model of the run."""
    workspace = read_files([SYSTEMS, write_offset_tracking(tmp_path)])
    plan = run_plan(plan_workspace(instantiate(workspace, OFFSET_ROOT)))
    assert _parameters(plan, "pos_to_cmd")["cmd_publisher.offset"] == pytest.approx(0.02)
    assert "point_broadcaster.offset" not in _parameters(plan, "ocv_color_tracking")  # none: 0
    assert _parameters(scaled_plan(plan, 3.0), "pos_to_cmd")["cmd_publisher.offset"] == pytest.approx(0.06)
    instance = instantiate(workspace, OFFSET_ROOT)
    scale_periods(instance, 3)
    thread = find_instance(instance, "rem_trk_sw.poscmd.cmd_publisher")
    assert property_value(thread, "Dispatch_Offset").to("ms") == pytest.approx(60)
    assert property_value(thread, "Period").to("ms") == pytest.approx(300)

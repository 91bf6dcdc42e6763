"""The CPU speed gauges of a measured run (``rosaadl.workflow.run.cpu_speed``): real gauge
processes on this machine's CPUs."""

from __future__ import annotations

import os
import time

import pytest

from rosaadl.workflow.run.cpu_speed import MAX_CPUS, CpuSpeedGauges, gauge_work, speed_of
from rosaadl.workflow.run.measured_window import MeasuredWindow


def test_one_iteration_is_python_object_work() -> None:
    assert gauge_work()[:3] == [46, 44, 42] and len(gauge_work()) == 24


@pytest.mark.parametrize(
    ("result", "speed"),
    [
        ({"loops": 3000, "cpu_ns": 10_000_000, "samples": 20}, 300.0),
        ({"loops": 0, "cpu_ns": 10_000_000}, None),
        ({"loops": 10, "cpu_ns": 0}, None),
        ({"loops": "many", "cpu_ns": 10}, None),
        ({}, None),
    ],
)
def test_the_speed_is_loops_per_cpu_ms(result, speed) -> None:
    assert speed_of(result) == speed


def test_gauges_run_idle_on_their_cpus_and_report_a_speed(tmp_path) -> None:
    cpus = sorted(os.sched_getaffinity(0))
    gauges = CpuSpeedGauges(tmp_path)
    gauges.start(set(cpus))
    time.sleep(0.5)
    for cpu, (process, _out) in gauges.running.items():
        assert os.sched_getaffinity(process.pid) == {cpu}
        assert os.sched_getscheduler(process.pid) == os.SCHED_IDLE  # it does not delay the nodes
    speeds = gauges.stop()
    assert sorted(speeds) == cpus[:MAX_CPUS]
    assert all(50 < s < 5000 for s in speeds.values()), speeds
    assert gauges.stop() == {}  # stopping again: nothing left
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"cpu_speed.{c}.json" for c in cpus[:MAX_CPUS]]


def test_a_gauge_that_wrote_nothing_is_left_out(tmp_path) -> None:
    gauges = CpuSpeedGauges(tmp_path)
    gauges.start({min(os.sched_getaffinity(0))})
    [(process, out)] = gauges.running.values()
    process.kill()
    process.wait()
    assert gauges.stop() == {} and not out.exists()


def test_a_node_s_speed_is_the_mean_over_the_cpus_it_may_run_on(tmp_path) -> None:
    window = MeasuredWindow(tmp_path, [])
    window.allowed = {"/pinned": {1}, "/free": {0, 1, 2}, "/elsewhere": {7}}
    window.cpu_speeds = {0: 300.0, 1: 330.0, 2: 315.0}
    assert window.process_speeds() == {"/pinned": 330.0, "/free": 315.0}

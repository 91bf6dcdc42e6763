"""Starting and stopping the nodes of ``rosaadl run`` (without ROS 2: small Python programs stand
for the nodes): the command line the launch file implies, the prefix on this machine's cores,
and the stop sequence SIGINT → SIGTERM → SIGKILL with what it took."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from rosaadl.workflow.run.cores import Machine, map_cpus, node_prefix, shared_cpus
from rosaadl.workflow.run.plan import NodeLaunch, RunError
from rosaadl.workflow.run.processes import (
    node_command,
    parameter_text,
    start_node,
    stop_nodes,
    wait_started,
)

#: A node that ends 0 on SIGINT, one that ignores SIGINT (ends on SIGTERM), one that ignores both.
PROGRAMS = {
    "polite": "import signal, sys, time\n"
    "signal.signal(signal.SIGINT, lambda *a: sys.exit(0))\nprint('up', flush=True)\ntime.sleep(60)\n",
    "deaf": "import signal, time\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\ntime.sleep(60)\n",
    "stubborn": "import signal, time\n"
    "signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
    "signal.signal(signal.SIGTERM, signal.SIG_IGN)\ntime.sleep(60)\n",
    "crash": "import sys\nprint('boom', flush=True)\nsys.exit(3)\n",
}


def _launch(name: str, **extra) -> NodeLaunch:
    return NodeLaunch(name=name, namespace="", package="pkg", executable=name, path=f"sys.{name}", **extra)


def _install(tmp_path: Path) -> Path:
    install = tmp_path / "install"
    folder = install / "lib" / "pkg"
    folder.mkdir(parents=True)
    for name, text in PROGRAMS.items():
        script = folder / name
        script.write_text(f"#!{sys.executable}\n{text}", encoding="utf-8")
        script.chmod(0o755)
    return install


def test_parameters_are_written_as_ros_args_takes_them():
    assert [parameter_text(v) for v in (True, 3, 0.05, 1e-05, 2.0, "it's")] == [
        "true",
        "3",
        "0.05",
        "1e-05",
        "2.0",
        "'it''s'",
    ]


def test_the_command_is_the_launch_files_node(tmp_path):
    node = _launch(
        "cam", parameters=[("t.period", 0.05), ("t.priority", 60)], remappings=[("out", "/cam/image")]
    )
    node.namespace = "/robot"
    command = node_command(node, tmp_path, ["taskset", "-c", "1"], [("rosaadl.emulate", True)])
    assert command == [
        "taskset",
        "-c",
        "1",
        str(tmp_path / "lib" / "pkg" / "cam"),
        "--ros-args",
        "-r",
        "__node:=cam",
        "-r",
        "__ns:=/robot",
        "-p",
        "t.period:=0.05",
        "-p",
        "t.priority:=60",
        "-p",
        "rosaadl.emulate:=true",
        "-r",
        "out:=/cam/image",
    ]


def test_model_cores_map_onto_this_machine():
    assert map_cpus([0, 1], [0, 1]) == ([0, 1], [])
    assert map_cpus([2, 5], [0, 1]) == ([0, 1], [(2, 0), (5, 1)])
    assert map_cpus([4, 6], [0, 1]) == ([0], [(4, 0), (6, 0)])
    assert map_cpus([3], [2, 7]) == ([7], [(3, 7)])


def test_prefix_warns_for_a_missing_core_and_drops_a_forbidden_chrt():
    node = _launch("n", cpus=[1, 4], policy="SCHED_FIFO", priority=60)
    here = Machine(cpus=[0, 1], realtime={"SCHED_FIFO": True}, taskset="taskset", chrt="chrt")
    prefix, warnings = node_prefix(node, here)
    assert prefix == ["taskset", "-c", "0,1", "chrt", "-f", "60"]
    assert len(warnings) == 1 and "core 4 of the model does not exist here" in warnings[0]
    here.realtime["SCHED_FIFO"] = False
    prefix, warnings = node_prefix(node, here)
    assert prefix == ["taskset", "-c", "0,1"]
    assert "SCHED_FIFO priority 60 cannot be set here" in warnings[-1]


def test_real_time_is_not_applied_on_a_cpu_several_model_cores_share():
    """Model cores 0, 1, 2 on a 2-CPU machine: core 2 joins core 0 on CPU 0, whose nodes lose their
    SCHED_FIFO priority (the higher one would starve the other); CPU 1 keeps it."""
    nodes = [
        _launch("a", cpus=[0], policy="SCHED_FIFO", priority=55),
        _launch("b", cpus=[1], policy="SCHED_FIFO", priority=60),
        _launch("c", cpus=[2], policy="SCHED_FIFO", priority=50),
    ]
    here = Machine(cpus=[0, 1], realtime={"SCHED_FIFO": True}, taskset="taskset", chrt="chrt")
    shared = shared_cpus(nodes, here)
    assert shared == {0}
    prefixes = [node_prefix(n, here, shared) for n in nodes]
    assert [p for p, _ in prefixes] == [
        ["taskset", "-c", "0"],
        ["taskset", "-c", "1", "chrt", "-f", "60"],
        ["taskset", "-c", "0"],
    ]
    assert "runs nodes of several cores of the model" in prefixes[0][1][0]
    assert prefixes[1][1] == []


def test_stop_sequence_reports_what_each_node_needed(tmp_path):
    install = _install(tmp_path)
    logs = tmp_path / "logs"
    logs.mkdir()
    started = [
        start_node(n, node_command(n, install, []), dict(os.environ), logs, tmp_path)
        for n in (_launch("polite"), _launch("deaf"), _launch("stubborn"))
    ]
    wait_started(started, 1.0)
    assert all(p.started for p in started)
    stop_nodes(started, grace=1.0, term=1.0)
    polite, deaf, stubborn = started
    assert (polite.exit_code, polite.stopped_by, polite.warnings) == (0, "SIGINT", [])
    assert (deaf.exit_code, deaf.stopped_by) == (-15, "SIGTERM")
    assert "did not stop within 1 s of SIGINT; sent SIGTERM" in deaf.warnings[0]
    assert (stubborn.exit_code, stubborn.stopped_by) == (-9, "SIGKILL")
    assert len(stubborn.warnings) == 2
    assert "up" in polite.log.read_text()


def test_a_node_that_dies_at_start_is_not_started(tmp_path):
    install = _install(tmp_path)
    node = _launch("crash")
    process = start_node(node, node_command(node, install, []), dict(os.environ), tmp_path, tmp_path)
    wait_started([process], 5.0)
    assert (process.started, process.exit_code, process.stopped_by) == (False, 3, "")
    assert "boom" in process.log.read_text()


def test_a_missing_executable_is_a_located_error(tmp_path):
    node = _launch("absent")
    with pytest.raises(RunError, match="no executable absent in package pkg") as caught:
        start_node(node, node_command(node, tmp_path, []), dict(os.environ), tmp_path, tmp_path)
    assert caught.value.location.file.endswith("lib/pkg/absent")

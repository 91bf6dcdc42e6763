"""What the generated code does for a run (no ROS 2 runtime needed here; the runtime tests in
``test_rclpy_runtime`` run it): the workload twin of each dispatch (Compute_Execution_Time,
Data_Size, which thread sends a component's own ports), user code that replaces it, thread
priorities, the shutdown on SIGINT, and the launch prefixes fitted to the machine's cores."""

from __future__ import annotations

import ast
import logging
import os
import re
import shlex
import subprocess
from pathlib import Path

import pytest
from conftest import corpus_dir
from offset_sample import OFFSET_ROOT, write_offset_tracking
from ros_runtime import launch_nodes
from test_rclpy_models import services_instance, tracking_instance

from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace, preservation
from rosaadl.exporters.rclpy.nodes import ThreadPlan
from rosaadl.exporters.rclpy.twin import skeleton_before_twin
from rosaadl.importers import aadl_text
from rosaadl.transforms.instantiate import instantiate

OPTIONS = GenerationOptions(year=2024)


@pytest.fixture(scope="module")
def library():
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    return aadl_text.read_files([], include_library=True, check=False)


@pytest.fixture(scope="module")
def library_ws(library, tmp_path_factory):
    """The library's tracking application (its CETs and Data_Sizes)."""
    instance = instantiate(library, "sys_tracking::tracking.impl")
    try:
        out = tmp_path_factory.mktemp("twin") / "src"
        return out, generate_workspace(instance, out, options=OPTIONS)
    finally:
        library.instances.remove(instance)


@pytest.fixture(scope="module")
def tracking_ws(tmp_path_factory):
    """The synthetic tracking application of ``test_rclpy_models`` (pos_to_cmd bound to CPU 4)."""
    _, instance = tracking_instance()
    out = tmp_path_factory.mktemp("synthetic") / "src"
    return out, generate_workspace(instance, out, options=OPTIONS)


def _classes(result):
    return {cls.node_name: cls for cls in result.plan.classes}


def _methods(path: Path) -> dict[str, ast.FunctionDef]:
    tree = ast.parse(path.read_text())
    return {n.name: n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}


def test_each_thread_has_its_cet_and_each_out_port_its_data_size(library_ws):
    _, result = library_ws
    classes = _classes(result)
    tracker = {t.ident: t for t in classes["ocv_color_tracking"].threads}
    assert tracker["image_tracker"].cet == pytest.approx((0.037, 0.037))
    camera = {t.ident: t for t in classes["usb_cam"].threads}
    [image] = camera["image_broadcaster"].twin_outputs
    assert (image.name, image.data_size, image.msg.full_name) == ("pub_msg", 921_000, "sensor_msgs/msg/Image")
    [point] = tracker["point_broadcaster"].twin_outputs
    assert point.data_size == 24 and point.msg.full_name == "geometry_msgs/msg/Point"


def test_every_dispatch_skeleton_ends_with_the_twin(library_ws):
    """Each dispatching callback's user block holds the skeleton ``self.emulate('<thread>')`` after
    its debug line; the twin's parameters are declared with the model's values; the payload of
    each out port is built once with its Data_Size."""
    out, result = library_ws
    for cls in result.plan.classes:
        path = out / cls.package / cls.package / f"{cls.module}.py"
        text = path.read_text()
        parsed = preservation.parse(text, "hash", str(path))
        for thread in cls.threads:
            if not thread.dispatches:
                continue
            names = [thread.marker] if thread.timer else []
            names += [p.marker for p in thread.inputs if p.triggers] + [s.marker for s in thread.servers]
            for name in names:
                lines = parsed.blocks[name].text().strip().splitlines()
                assert lines[-1].strip() == f"self.emulate({thread.ident!r})", (path, name)
        assert "self.declare_parameter('rosaadl.emulate', False)" in text
        assert "self.declare_parameter('rosaadl.emulate_cet', 'max')" in text
    camera = (out / "usb_cam/usb_cam/usb_cam.py").read_text()
    assert "self.payload(self.pub_image_broadcaster_pub_msg, 921000)," in camera
    assert "# pub_msg: sensor_msgs/msg/Image, Data_Size 921000 B" in camera
    tracker = (out / "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py").read_text()
    assert "self.declare_parameter('image_tracker.cet_max', 0.037)" in tracker


def test_warning_not_warn_and_a_clean_exit_on_sigint(library_ws):
    """``get_logger().warn`` is deprecated on current ROS 2; ``main`` catches the SIGINT that rclpy
    turns into ``ExternalShutdownException`` (or ``KeyboardInterrupt`` before the executor runs)
    and shuts down with ``rclpy.try_shutdown``, so the node exits 0."""
    out, result = library_ws
    for cls in result.plan.classes:
        path = out / cls.package / cls.package / f"{cls.module}.py"
        text = path.read_text()
        assert ".warn(" not in text and "get_logger().warning(" in text
        main = ast.unparse(_methods(path)["main"])
        assert "except (KeyboardInterrupt, ExternalShutdownException):" in main
        assert "rclpy.try_shutdown()" in main and "rclpy.shutdown()" not in main
        assert "node.start_timers()" in main.split("executor.spin()")[0]
        # a SIGINT while the executor makes its first wait set: the RCLError of the shut-down
        # context is the stop asked for; with the context still up it is raised
        handler = main.split("except _rclpy.RCLError:")[1].split("finally:")[0]
        assert "if rclpy.ok():" in handler and "raise" in handler
        assert "from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy" in text
        # the wait loop lets each task it gave reach its worker before it looks again (rclpy
        # offers a task no worker has started again and again: a seven-callback node took a
        # third of a CPU and missed timer periods under SCHED_FIFO)
        assert "executor.wait_for_ready_callbacks = hand_off(executor.wait_for_ready_callbacks)" in main
        waits = ast.unparse(_methods(path)["hand_off"])
        assert "task.executing() or task.done()" in waits and "time.sleep(HAND_OFF_POLL)" in waits


def test_timer_dispatches_are_released_on_their_schedule(library_ws):
    """A timer's dispatch is measured from when the timer was due (its next call less one period),
    and every timer restarts as the executor starts, so the first dispatch is not measured from
    the node's construction."""
    out, _ = library_ws
    path = out / "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py"
    methods = _methods(path)
    assert "started = self.release_of(self.timer_point_broadcaster)" in ast.unparse(
        methods["on_point_broadcaster"]
    )
    assert "timer.reset()" in ast.unparse(methods["start_timers"])


def test_each_dispatch_takes_its_threads_priority(tmp_path):
    """Every dispatching callback first takes its thread's priority; an explicit SCHED_FIFO of the
    thread is passed on, else the policy the node was started with (the launch prefix's chrt)."""
    _, instance = services_instance()
    out = tmp_path / "src"
    result = generate_workspace(instance, out, options=OPTIONS)
    for cls in result.plan.classes:
        text = (out / cls.package / cls.package / f"{cls.module}.py").read_text()
        for thread in cls.threads:
            if thread.dispatches:
                policy = "os.SCHED_FIFO" if thread.policy.lower() == "sched_fifo" else "None"
                assert f"self.take_priority({thread.ident!r}, {policy})" in text
    assert "self.take_priority('comp_timer', None)" in "".join(p.read_text() for p in out.rglob("*.py"))
    plans = {
        policy: ThreadPlan("t", "t", "Periodic", "", (), policy=policy).sched_policy for policy in POLICIES
    }
    assert plans == {
        "SCHED_FIFO": "os.SCHED_FIFO",
        "SCHED_RR": "os.SCHED_RR",
        "SCHED_OTHERS": "None",
        "": "None",
    }


POLICIES = ("SCHED_FIFO", "SCHED_RR", "SCHED_OTHERS", "")


def test_user_code_replaces_the_twin_and_old_skeletons_take_it(tmp_path):
    """A block holding the user's code is kept and does not emulate; a block that still holds the
    skeleton of a generator without the twin (no ``self.emulate`` line) takes the new skeleton."""
    _, instance = tracking_instance()
    out = tmp_path / "src"
    generate_workspace(instance, out, options=OPTIONS)
    path = out / "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py"
    text = path.read_text()
    old_skeleton = "        self.get_logger().debug('point_broadcaster: dispatched')\n"
    text = text.replace(old_skeleton + "        self.emulate('point_broadcaster')\n", old_skeleton)
    user = "        self.pub_image_tracker_x = None  # the user's tracking code\n"
    text = re.sub(
        r"(# <user-code name=\"ocv_color_tracking.image_tracker.cb_msg\">\n).*?(\s*# </user-code>)",
        lambda m: m[1] + user.rstrip("\n") + m[2],
        text,
        flags=re.S,
    )
    path.write_text(text)
    generate_workspace(instance, out, options=OPTIONS)
    blocks = {n: b.text() for n, b in preservation.parse(path.read_text(), "hash").blocks.items()}
    assert blocks["ocv_color_tracking.image_tracker.cb_msg"].strip() == user.strip()
    assert "self.emulate('point_broadcaster')" in blocks["ocv_color_tracking.point_broadcaster"]


def test_skeleton_before_twin_is_only_the_old_default():
    new = [(True, "self.get_logger().debug('t: dispatched')"), (True, "self.emulate('t')")]
    assert skeleton_before_twin([(True, "self.get_logger().debug('t: dispatched')")], new)
    assert not skeleton_before_twin([(True, "self.get_logger().debug('t: dispatched')")], new[:1])
    assert not skeleton_before_twin([(True, "do_things()")], new)
    assert not skeleton_before_twin(new, new)


@pytest.mark.corpus
def test_a_components_own_ports_are_sent_by_its_timer(library, tmp_path):
    """A ROSMOD component's publisher is a port of its thread group that no thread handles: the
    twin sends it from the component's timer thread (the first periodic thread of its group)."""
    from rosaadl.importers.rosmod_text import read_project
    from rosaadl.transforms import rosmod_to_aadl

    folder = corpus_dir() / "rosmod/textual-v0.3/ten-components"
    if not folder.is_dir():
        pytest.skip(f"{folder} is not in the corpus")
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    library = aadl_text.read_files([], include_library=True, check=False)
    converted = rosmod_to_aadl.rosmod_to_aadl(read_project(folder))
    library.units.extend(list(converted.model.units))
    root = next(r for d, r in sorted(converted.roots.items()) if d.startswith("periodic_timer_pub_sub"))
    result = generate_workspace(
        instantiate(library, root, strict=False),
        tmp_path / "src",
        options=OPTIONS,
        rosmod_trace=converted.trace,
    )
    publisher = _classes(result)["periodic_publisher"]
    [timer] = [t for t in publisher.threads if t.timer == "periodic"]
    [component] = [t for t in publisher.threads if t.container]
    assert component.outputs and timer.twin_outputs == component.outputs
    text = next((tmp_path / "src").rglob("periodic_publisher.py")).read_text()
    assert f"{timer.ident!r}: [" in text and f"self.payload(self.{component.outputs[0].attr}," in text


def test_launch_prefix_fits_this_machine(tracking_ws, monkeypatch, capsys):
    """The model binds pos_to_cmd to CPU 4 (``taskset -c 4``), which a 2-core machine does not have:
    ``taskset`` then fails and the node never starts.  The launch file maps a missing CPU onto
    those the machine gives (CPU modulo their count) with a warning, and drops ``chrt`` where
    real-time scheduling is not permitted."""
    out, _ = tracking_ws
    launch = out / "tracking_bringup/launch/tracking.launch.py"
    assert "prefix='taskset -c 4'," in launch.read_text()  # the model's binding stays in the file
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1})
    nodes = {n["name"]: n for n in launch_nodes(launch)}
    assert nodes["pos_to_cmd"]["prefix"] == "taskset -c 0"  # 4 modulo 2
    assert (
        nodes["usb_cam"]["prefix"] == "taskset -c 0"
        and nodes["ocv_color_tracking"]["prefix"] == "taskset -c 1"
    )
    assert (
        "CPUs 4 of the model are not all on this machine (it has 2): taskset -c 0" in capsys.readouterr().err
    )
    monkeypatch.undo()
    here = sorted(os.sched_getaffinity(0))
    fitted = [n["prefix"] for n in launch_nodes(launch)]
    for prefix in fitted:
        assert subprocess.run([*shlex.split(prefix), "true"], timeout=30).returncode == 0, prefix
    if 4 not in here:  # the model's prefix as it was generated before: the node would not start
        failed = subprocess.run(["taskset", "-c", "4", "true"], capture_output=True, timeout=30)
        assert failed.returncode != 0


def test_chrt_is_dropped_where_realtime_is_not_permitted(tmp_path, monkeypatch, capsys):
    _, instance = services_instance()
    out = tmp_path / "src"
    generate_workspace(instance, out, options=OPTIONS)
    launch = out / "app_bringup/launch/app.launch.py"

    def refuse(pid, policy, param):
        raise PermissionError(1, "Operation not permitted")

    monkeypatch.setattr(os, "sched_setscheduler", refuse)
    prefixes = [n.get("prefix") for n in launch_nodes(launch)]
    assert "chrt -f 70" in launch.read_text() and not any("chrt" in (p or "") for p in prefixes)
    assert "real-time scheduling (chrt -f 70) is not permitted here" in capsys.readouterr().err


def test_timers_release_on_their_period_grid_and_their_dispatch_offset(tmp_path):
    """Each generated timer declares ``<thread>.offset`` (its Dispatch_Offset, 0.0 without; the
    docstring says it), the launch file gives an instance's Dispatch_Offset, and ``start_timers``
    puts each generated timer's first release at the next k * Period + offset of the node's clock
    (rcl counts a reset's first release one period from now: the period is made that gap for the
    reset, then put back); the start-up heap is frozen out of the collector before the executor spins."""
    workspace = aadl_text.read_files([write_offset_tracking(tmp_path / "model")], include_library=True)
    out = tmp_path / "src"
    generate_workspace(instantiate(workspace, OFFSET_ROOT), out, options=OPTIONS)
    path = out / "nd_pos_to_cmd/nd_pos_to_cmd/pos_to_cmd.py"
    text = path.read_text()
    assert "self.declare_parameter('cmd_publisher.offset', 0.02)" in text
    assert "Compute_Execution_Time 1060 us .. 1060 us, Dispatch_Offset 20 ms" not in text
    assert "Deadline 100000 us, Dispatch_Offset 20 ms" in text
    assert "point_receiver.offset" not in text  # a subscription's thread has no timer
    methods = _methods(path)
    start = ast.unparse(methods["start_timers"])
    assert "timed = ('cmd_publisher',)" in start
    assert "threads = {id(getattr(self, 'timer_' + thread)): thread for thread in timed}" in start
    grid = start.split("period = timer.timer_period_ns")[1]
    assert "first = (offset - self.get_clock().now().nanoseconds) % period or period" in grid
    assert grid.index("timer.timer_period_ns = first") < grid.index("timer.reset()")
    assert grid.index("timer.reset()") < grid.index("timer.timer_period_ns = period")
    main = ast.unparse(methods["main"])
    assert main.index("node.start_timers()") < main.index("gc.freeze()") < main.index("executor.spin()")
    launch = launch_nodes(next(out.glob("*_bringup/launch/*.launch.py")))
    offsets = {n["name"]: n["parameters"][0].get("cmd_publisher.offset") for n in launch}
    assert offsets["pos_to_cmd"] == pytest.approx(0.02)

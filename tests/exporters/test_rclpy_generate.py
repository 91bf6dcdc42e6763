"""The generated workspace of the tracking application and of the services model: layout,
package manifests, setup files, messages, deployment, determinism, dry runs and ``force``."""

from __future__ import annotations

import ast
import compileall
import io
import subprocess
import sys
from contextlib import redirect_stdout
from pathlib import Path

import pytest
from test_rclpy_models import hostile_instance, services_instance, tracking_instance

from rosaadl import model
from rosaadl.errors import GenerationError, UsageError
from rosaadl.exporters.rclpy import MANIFEST_NAME, GenerationOptions, generate_workspace, plan_workspace
from rosaadl.fileio import parse_xml_bytes

OPTIONS = GenerationOptions(year=2024)


@pytest.fixture(scope="module")
def tracking_ws(tmp_path_factory):
    ws, instance = tracking_instance()
    out = tmp_path_factory.mktemp("tracking") / "src"
    result = generate_workspace(instance, out, options=OPTIONS)
    return out, result


@pytest.fixture(scope="module")
def services_ws(tmp_path_factory):
    ws, instance = services_instance()
    out = tmp_path_factory.mktemp("services") / "src"
    result = generate_workspace(instance, out, options=OPTIONS)
    return out, result


def files_of(root: Path) -> dict[str, bytes]:
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


# --------------------------------------------------------------------------- layout


def test_tracking_layout(tracking_ws):
    out, result = tracking_ws
    packages = sorted(p.name for p in out.iterdir() if p.is_dir())
    assert packages == [
        "nd_ocv_color_tracking",
        "nd_pos_to_cmd",
        "tracking_bringup",
        "tracking_interfaces",
        "usb_cam",
    ]
    for pkg in ("nd_ocv_color_tracking", "nd_pos_to_cmd", "usb_cam", "tracking_bringup"):
        for name in ("package.xml", "setup.py", "setup.cfg", f"resource/{pkg}", f"{pkg}/__init__.py"):
            assert (out / pkg / name).is_file(), (pkg, name)
        for test in ("test_copyright.py", "test_flake8.py", "test_pep257.py"):
            assert (out / pkg / "test" / test).is_file()
        assert (out / pkg / "resource" / pkg).read_bytes() == b""
    assert (out / "usb_cam/usb_cam/usb_cam.py").is_file()
    assert (out / "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py").is_file()
    assert (out / "nd_pos_to_cmd/nd_pos_to_cmd/pos_to_cmd.py").is_file()
    launches = sorted(p.name for p in (out / "tracking_bringup/launch").iterdir())
    assert launches == ["p3_dx_odroid_xu4_exynos_soc.launch.py", "tracking.launch.py"]
    assert sorted(p.name for p in (out / "tracking_interfaces/msg").iterdir()) == ["VideoStream.msg"]
    assert (out / MANIFEST_NAME).is_file()
    assert sorted(result.written) == sorted(files_of(out).keys() - {MANIFEST_NAME})
    assert not result.skipped and not result.moved and not result.orphaned


def _xml(path: Path):
    return parse_xml_bytes(path.read_bytes(), str(path)).getroot()


def test_package_xml_format_3_with_dependencies(tracking_ws):
    out, _ = tracking_ws
    root = _xml(out / "nd_ocv_color_tracking/package.xml")
    assert root.tag == "package" and root.get("format") == "3"
    assert root.findtext("name") == "nd_ocv_color_tracking"
    assert [d.text for d in root.findall("depend")] == ["rclpy", "geometry_msgs", "sensor_msgs"]
    assert root.find("export/build_type").text == "ament_python"
    assert sorted(d.text for d in root.findall("test_depend")) == [
        "ament_copyright",
        "ament_flake8",
        "ament_pep257",
        "python3-pytest",
    ]
    usb = _xml(out / "usb_cam/package.xml")
    assert [d.text for d in usb.findall("depend")] == ["rclpy", "sensor_msgs", "tracking_interfaces"]
    interfaces = _xml(out / "tracking_interfaces/package.xml")
    assert interfaces.find("export/build_type").text == "ament_cmake"
    assert [d.text for d in interfaces.findall("buildtool_depend")] == [
        "ament_cmake",
        "rosidl_default_generators",
    ]
    assert interfaces.findtext("member_of_group") == "rosidl_interface_packages"
    bringup = _xml(out / "tracking_bringup/package.xml")
    assert [d.text for d in bringup.findall("exec_depend")] == [
        "launch",
        "launch_ros",
        "nd_ocv_color_tracking",
        "nd_pos_to_cmd",
        "usb_cam",
    ]


def _setup_call(path: Path) -> ast.Call:
    tree = ast.parse(path.read_text())
    return next(
        n
        for n in ast.walk(tree)
        if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id == "setup"
    )


def test_setup_py_and_setup_cfg(tracking_ws):
    out, _ = tracking_ws
    call = _setup_call(out / "usb_cam/setup.py")
    kwargs = {k.arg: k.value for k in call.keywords}
    packages = kwargs["packages"]
    assert ast.unparse(packages) == "find_packages(exclude=['test'])"
    data_files = ast.unparse(kwargs["data_files"])
    assert "('share/ament_index/resource_index/packages', ['resource/' + package_name])" in data_files
    assert "('share/' + package_name, ['package.xml'])" in data_files
    scripts = ast.literal_eval(kwargs["entry_points"])["console_scripts"]
    assert scripts == ["usb_cam = usb_cam.usb_cam:main"]
    bringup = {k.arg: k.value for k in _setup_call(out / "tracking_bringup/setup.py").keywords}
    launch = ast.unparse(bringup["data_files"])
    assert (
        "'launch/tracking.launch.py'" in launch and "'launch/p3_dx_odroid_xu4_exynos_soc.launch.py'" in launch
    )
    cfg = (out / "usb_cam/setup.cfg").read_text()
    assert "[develop]\nscript_dir=$base/lib/usb_cam\n[install]\ninstall_scripts=$base/lib/usb_cam\n" in cfg


def test_generated_python_compiles(tracking_ws, services_ws):
    for out, _ in (tracking_ws, services_ws):
        with redirect_stdout(io.StringIO()):
            assert compileall.compile_dir(str(out), quiet=1, force=True)
        done = subprocess.run(
            [sys.executable, "-m", "compileall", "-q", str(out)], capture_output=True, text=True
        )
        assert done.returncode == 0, done.stdout + done.stderr


# --------------------------------------------------------------------------- messages and deployment


def test_standard_and_custom_messages(tracking_ws, services_ws):
    out, _ = tracking_ws
    tracker = (out / "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py").read_text()
    assert "from sensor_msgs.msg import Image" in tracker
    assert "from geometry_msgs.msg import Point" in tracker
    assert (
        "from geometry_msgs.msg import Point, Twist"
        in (out / "nd_pos_to_cmd/nd_pos_to_cmd/pos_to_cmd.py").read_text()
    )
    assert (
        "from tracking_interfaces.msg import VideoStream" in (out / "usb_cam/usb_cam/usb_cam.py").read_text()
    )
    assert (out / "tracking_interfaces/msg/VideoStream.msg").read_text().splitlines()[1:3] == [
        "# ros_data::video_stream.rgb has no known structure: its content as bytes.",
        "uint8[] data",
    ]
    services, _ = services_ws
    pose = (services / "app_interfaces/msg/Pose.msg").read_text().splitlines()
    assert pose[1:4] == ["float64 x", "float64 y", "geometry_msgs/Point heading"]
    srv = (services / "app_interfaces/srv/GetPlan.srv").read_text().splitlines()
    assert srv[1] == "Pose goal" and "---" in srv and srv[srv.index("---") + 1] == "uint32 steps"
    cmake = (services / "app_interfaces/CMakeLists.txt").read_text()
    assert (
        '"msg/Pose.msg"' in cmake and '"srv/GetPlan.srv"' in cmake and "DEPENDENCIES geometry_msgs" in cmake
    )
    pool = (services / "planning/planning/pool_node.py").read_text()
    assert "from std_msgs.msg import Empty, String" in pool


def test_qos_from_queue_size_and_port_kind(tracking_ws, services_ws):
    out, _ = tracking_ws
    usb = (out / "usb_cam/usb_cam/usb_cam.py").read_text()
    assert "depth=512" in usb  # Queue_Size => 512 applies to pub_msg (xu4_a15)
    services, _ = services_ws
    pool = (services / "planning/planning/pool_node.py").read_text()
    job = pool[pool.index("self.sub_workers_job") :]
    assert "depth=8" in job[:400] and "KEEP_LAST" in job[:400] and "RELIABLE" in job[:400]
    status = pool[pool.index("self.sub_mon_status") :]
    assert "depth=1" in status[:400]
    assert "self.inbox_mon_status = deque(maxlen=1)" in pool  # a data port read by a periodic thread


def test_launch_bindings_priorities_remappings_parameters(tracking_ws, services_ws):
    out, _ = tracking_ws
    launch = (out / "tracking_bringup/launch/tracking.launch.py").read_text()
    tree = ast.parse(launch)
    nodes = [n for n in ast.walk(tree) if isinstance(n, ast.Call) and getattr(n.func, "id", "") == "Node"]
    by_name = {}
    for node in nodes:
        kwargs = {k.arg: k.value for k in node.keywords}
        by_name[ast.literal_eval(kwargs["name"])] = kwargs
    assert sorted(by_name) == ["ocv_color_tracking", "pos_to_cmd", "usb_cam"]
    # cores in declaration order of the Exynos: big_proc1..4 are 0..3, little_proc1 is 4
    assert ast.literal_eval(by_name["usb_cam"]["prefix"]) == "taskset -c 0"
    assert ast.literal_eval(by_name["ocv_color_tracking"]["prefix"]) == "taskset -c 1"
    assert ast.literal_eval(by_name["pos_to_cmd"]["prefix"]) == "taskset -c 4"
    remaps = dict(ast.literal_eval(by_name["ocv_color_tracking"]["remappings"]))
    assert remaps == {"image_in": "/usb_cam/image_raw", "point_out": "/ocv_color_tracking/point_out"}
    assert (
        dict(ast.literal_eval(by_name["pos_to_cmd"]["remappings"]))["point_in"]
        == "/ocv_color_tracking/point_out"
    )
    params = ast.literal_eval(by_name["ocv_color_tracking"]["parameters"])[0]
    assert params["image_tracker.period"] == pytest.approx(0.033333)
    assert params["point_broadcaster.deadline"] == pytest.approx(0.1)
    services, _ = services_ws
    app = (services / "app_bringup/launch/app.launch.py").read_text()
    assert "prefix='chrt -f 70'," in app  # Priority 70 on the process, no policy: SCHED_FIFO
    assert "('plan', '/planner/get_plan')" in app and "('get_plan', '/planner/get_plan')" in app
    assert "('pose_out', '/plan/poses')" in app and "('jobs', '/plan/poses')" in app
    host1 = (services / "app_bringup/launch/host1.launch.py").read_text()
    assert "name='planner'" in host1 and "name='pool'" not in host1


def test_docstrings_carry_the_timing_properties(tracking_ws):
    out, _ = tracking_ws
    tree = ast.parse((out / "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py").read_text())
    methods = {n.name: ast.get_docstring(n) for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
    doc = " ".join(methods["on_image_tracker_cb_msg"].split())
    assert "Period 33333 us" in doc and "Deadline 33333 us" in doc
    assert "Compute_Execution_Time 37000 us .. 37000 us" in doc
    assert "check_deadline" in methods


# --------------------------------------------------------------------------- determinism, dry run, force


def test_generation_is_deterministic(tmp_path):
    _, first = tracking_instance()
    _, second = tracking_instance()
    generate_workspace(first, tmp_path / "a", options=OPTIONS)
    generate_workspace(second, tmp_path / "b", options=OPTIONS)
    assert files_of(tmp_path / "a") == files_of(tmp_path / "b")
    again = generate_workspace(second, tmp_path / "b", options=OPTIONS)
    assert {c.action for c in again.changes} == {"unchanged"}


def test_dry_run_writes_nothing(tmp_path):
    _, instance = tracking_instance()
    result = generate_workspace(instance, tmp_path / "src", options=OPTIONS, dry_run=True)
    assert result.dry_run and result.written
    assert not (tmp_path / "src").exists()


def test_files_without_markers_need_force(tmp_path):
    _, instance = tracking_instance()
    out = tmp_path / "src"
    generate_workspace(instance, out, options=OPTIONS)
    setup_cfg = out / "usb_cam/setup.cfg"
    setup_cfg.write_text("[develop]\nscript_dir=mine\n")  # taken over by hand: no marker left
    node = out / "usb_cam/usb_cam/usb_cam.py"
    node.write_text("print('mine')\n")
    result = generate_workspace(instance, out, options=OPTIONS)
    assert sorted(result.skipped) == ["usb_cam/setup.cfg", "usb_cam/usb_cam/usb_cam.py"]
    assert setup_cfg.read_text() == "[develop]\nscript_dir=mine\n"
    assert node.read_text() == "print('mine')\n"
    forced = generate_workspace(instance, out, options=OPTIONS, force=True)
    assert "usb_cam/setup.cfg" in forced.written and "<user-code" in setup_cfg.read_text()


def test_root_selection_and_instantiation(tmp_path):
    ws, _ = tracking_instance()
    plan = plan_workspace(ws, options=OPTIONS)  # the single instance
    assert plan.app == "tracking"
    fresh, _ = tracking_instance()
    fresh.instances.clear()
    with pytest.raises(UsageError):
        plan_workspace(fresh)
    plan = plan_workspace(fresh, root="sys_tracking::tracking.impl", options=OPTIONS)
    assert [c.module for c in plan.classes] == ["usb_cam", "ocv_color_tracking", "pos_to_cmd"]
    with pytest.raises(UsageError):
        plan_workspace(fresh, options=GenerationOptions(license="GPL-3.0"))
    with pytest.raises(UsageError):
        plan_workspace(model.new("AadlPackage", name="p"))


def test_a_process_root_and_a_file_as_output(tmp_path):
    _, system = services_instance()
    status = model.find_instance(system, "status")
    plan = plan_workspace(system, options=OPTIONS)
    assert any(c.module == "status_node" for c in plan.classes)
    assert status is not None
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(GenerationError):
        generate_workspace(system, blocker, options=OPTIONS)


def test_same_classifier_instances_share_a_class(tmp_path):
    _, system = hostile_instance()
    plan = plan_workspace(system, options=OPTIONS)
    assert len(plan.classes) == 1 and len(plan.nodes) == 2
    assert [n.node_name for n in plan.nodes] == ["etc_passwd", "etc_passwd"]  # in two namespaces
    assert plan.nodes[1].namespace.startswith("/a_rather_long_namespace_segment/")
    _, system = hostile_instance()
    for assoc in list(system.componentInstances[1].ownedPropertyAssociations):
        if assoc.property.endswith("Namespace"):
            system.componentInstances[1].ownedPropertyAssociations.remove(assoc)
    plan = plan_workspace(system, options=OPTIONS)
    assert [n.node_name for n in plan.nodes] == ["etc_passwd", "etc_passwd_2"]  # one namespace


def test_files_and_folders_in_the_way_are_located_errors(tmp_path):
    _, instance = tracking_instance()
    out = tmp_path / "src"
    (out / "usb_cam").mkdir(parents=True)
    (out / "usb_cam" / "setup.py").mkdir()  # a folder where a file goes
    with pytest.raises(GenerationError) as caught:
        generate_workspace(instance, out, options=OPTIONS)
    assert caught.value.location.file.endswith("usb_cam/setup.py")
    assert sorted(p.name for p in out.rglob("*")) == ["setup.py", "usb_cam"]  # nothing written
    (out / "usb_cam" / "setup.py").rmdir()
    (out / "nd_pos_to_cmd").write_text("a file where a package folder goes")
    with pytest.raises(GenerationError, match="a file is where a generated folder goes"):
        generate_workspace(instance, out, options=OPTIONS)


OWN_PORTS = """
package own_ports
public
  data Msg
  end Msg;

  thread tick
    features
      out_msg: out event data port Msg;
    properties
      Dispatch_Protocol => Periodic;
      Period => 100 ms;
  end tick;

  thread implementation tick.impl
  end tick.impl;

  thread group component
    features
      status: out event data port Msg;
      relay: out event data port Msg;
  end component;

  thread group implementation component.impl
    subcomponents
      ticker: thread tick.impl;
    connections
      c1: port ticker.out_msg -> relay;
  end component.impl;

  process node
  end node;

  process implementation node.impl
    subcomponents
      comp: thread group component.impl;
  end node.impl;

  system top
  end top;

  system implementation top.impl
    subcomponents
      n: process node.impl;
  end top.impl;
end own_ports;
"""


def test_a_thread_groups_own_port_that_nothing_reaches_still_publishes():
    """A thread group's port that no connection reaches is the component's own (a ROSMOD
    component's publisher that no subscriber of its deployment reads): it gets a publisher; a
    port that only passes a thread's port through does not get a second one."""
    from rosaadl.importers import aadl_text

    declarative = aadl_text.read_string(OWN_PORTS, "own_ports.aadl")
    plan = plan_workspace(declarative, root="own_ports::top.impl", options=OPTIONS)
    [cls] = plan.classes
    published = sorted(p.rel_path for t in cls.threads for p in t.ports if p.direction == "out")
    assert published == [("comp", "status"), ("comp", "ticker", "out_msg")]

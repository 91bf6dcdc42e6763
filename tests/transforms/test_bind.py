"""Binding ROSMOD deployments to robots of the library: the package, the rates, the figures, the
deployment search, and located errors for every kind of wrong bindings file."""

from __future__ import annotations

import copy
import json
import shutil
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.analysis.deployment import search_deployment
from rosaadl.analysis.report import run_analyses
from rosaadl.errors import ModelError, ParseError
from rosaadl.exporters.aadl_text import write_model, write_unit
from rosaadl.importers.aadl_text import read_files, read_string
from rosaadl.importers.rosmod_text import read_project
from rosaadl.transforms.bind import (
    MAX_BINDINGS_BYTES,
    BindingError,
    BindingsFile,
    bind_deployment,
    parse_bindings,
    robot_cores,
)
from rosaadl.transforms.instantiate import instantiate
from rosaadl.workflow.binding import bind_project, propose_binding, read_bindings

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "tracking"
LITTLE1 = "OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc1"
BINDINGS = json.loads((EXAMPLE / "bindings.json").read_text())


@pytest.fixture(scope="module")
def library():
    return read_files([], include_library=True)


@pytest.fixture(scope="module")
def project():
    return read_project(EXAMPLE)


@pytest.fixture(scope="module")
def bound(project, library):
    return bind_project(project, read_bindings(EXAMPLE / "bindings.json"), library)


@pytest.fixture(scope="module")
def instances(bound, tmp_path_factory):
    """The bound deployments written, read back from the files with the library, instantiated."""
    folder = tmp_path_factory.mktemp("bound")
    paths = [write_model([b.package], folder)[0] for b in bound.values()]
    aadl = read_files(paths)
    return {name: instantiate(aadl, b.root) for name, b in bound.items()}


def loads(instance) -> dict[str, Fraction]:
    """Core (path inside the robot) → CPU load (1 = 100 %) from the bound resource analysis."""
    report = run_analyses(instance, "cpu")
    prefix = f"{instance.name}.robot."
    return {
        row.path.removeprefix(prefix): row.load_percent / 100
        for row in report.cpu.processors
        if row.load_percent is not None and row.load_percent > 0
    }


def spec_text(data: dict) -> str:
    return json.dumps(data, indent=2)


def edited(change) -> dict:
    data = copy.deepcopy(BINDINGS)
    change(data)
    return data


# ----------------------------------------------------------------------------- the package


def test_pioneer_is_bound_to_its_little_core_with_the_a7_measurements(bound) -> None:
    pioneer = bound["pioneer_3dx"]
    assert pioneer.root == "pioneer_3dx_bound::tracking.impl"
    assert pioneer.robot == "pioneer_3dx::Pioneer_3DX.impl"
    assert [(n.process, n.implementation, n.core, n.core_type) for n in pioneer.nodes] == [
        ("usb_cam_node", "nd_usb_cam::usb_cam_nd.xu4_a7", LITTLE1, "Exynos_5422::ARM_A7"),
        (
            "tracker_node",
            "nd_ocv_color_tracking::ocv_color_tracking_nd.xu4_a7",
            LITTLE1,
            "Exynos_5422::ARM_A7",
        ),
        ("pos_to_cmd_node", "nd_pos_to_cmd::pos_to_cmd_nd.xu4_a7", LITTLE1, "Exynos_5422::ARM_A7"),
    ]
    assert [(t.connection, t.message_type, t.source, t.destination, t.bus) for t in pioneer.topics] == [
        (
            "topic_Image",
            "tracking/Image",
            "usb_cam_node.rgb_image_raw_out",
            "tracker_node.image_in",
            "ROSbus",
        ),
        ("topic_Point", "tracking/Point", "tracker_node.point_out", "pos_to_cmd_node.point_in", "ROSbus"),
    ]
    assert len(pioneer.cores) == 8


def test_the_package_is_shaped_like_the_librarys_reference_systems(bound) -> None:
    text = write_unit(bound["pioneer_3dx"].package)
    assert "with nd_ocv_color_tracking, nd_pos_to_cmd, nd_usb_cam, pioneer_3dx, ros;" in text
    assert "robot: system pioneer_3dx::Pioneer_3DX.impl;" in text
    assert "ROSbus: virtual bus ros::ROSbus.impl;" in text
    assert "robot_rgb_stream_out: port robot.rgb_stream_out -> usb_cam_node.rgb_stream_in;" in text
    assert "robot_cmd_vel_in: port pos_to_cmd_node.cmd_vel_out -> robot.cmd_vel_in;" in text
    assert f"Actual_Processor_Binding => (reference (robot.{LITTLE1}))" in text
    assert "Actual_Connection_Binding => (reference (ROSbus)) applies to topic_Image;" in text
    assert "Actual_Connection_Binding => (reference (robot.usb_bus)) applies to robot_rgb_stream_out;" in text
    leo = bound["leo_rover"]
    assert {n.implementation.rpartition(".")[2] for n in leo.nodes} == {"rpi4_a72"}
    assert {n.core for n in leo.nodes} == {"RaspberryPi4B.BCM2711_SOC.proc1"}


def test_rosmod_rates_go_on_the_library_threads(bound) -> None:
    timings = {
        node.process: {t.thread: (t.period, t.deadline, t.priority) for t in node.timings}
        for node in bound["pioneer_3dx"].nodes
    }
    s = Decimal
    assert timings["usb_cam_node"] == {
        "image_broadcaster": (s("0.05"), s("0.05"), 60),  # frame_timer
        "usbSpinner": (s("0.05"), None, None),  # the node's rate
        "": (s("0.05"), None, 60),  # the process: node rate and node priority
    }
    assert timings["tracker_node"] == {
        "image_tracker": (s("0.05"), s("0.05"), 55),  # the image topic, at usb_cam's rate
        "point_broadcaster": (s("0.1"), s("0.1"), 50),  # target_timer
        "": (s("0.05"), None, 55),
    }
    assert timings["pos_to_cmd_node"] == {
        "point_receiver": (s("0.1"), s("0.1"), 50),
        "cmd_publisher": (s("0.1"), s("0.1"), 50),
        "": (s("0.1"), None, 50),
    }
    text = write_unit(bound["pioneer_3dx"].package)
    assert "Period => 50 ms applies to tracker_node.image_tracker;" in text
    assert "Period => 100 ms applies to tracker_node.point_broadcaster;" in text


def test_binding_is_deterministic_and_reads_back(project, library, bound) -> None:
    again = bind_project(project, read_bindings(EXAMPLE / "bindings.json"), library)
    for name, b in bound.items():
        text = write_unit(b.package)
        assert write_unit(again[name].package) == text
        back = read_string(text, "back.aadl")
        assert write_unit(back.units[0]) == text


# ----------------------------------------------------------------------------- the figures


def test_pioneer_overloads_its_little_core_118_percent(instances) -> None:
    # 18500/50000 + 40000/50000 + 1060/100000: usb_cam, tracker, pos_to_cmd on one Cortex-A7
    assert loads(instances["pioneer_3dx"]) == {LITTLE1: Fraction(11806, 10000)}
    report = run_analyses(instances["pioneer_3dx"])
    assert not report.ok
    assert any(d.schedulable is False for d in report.schedulability.domains)
    assert sum(t.deadline_misses for t in report.simulation.tasks) > 0


def test_leo_rover_fits_on_one_cortex_a72_core(instances) -> None:
    # 8411/50000 + 7283/50000 + 104/100000
    assert loads(instances["leo_rover"]) == {"RaspberryPi4B.BCM2711_SOC.proc1": Fraction(31492, 100000)}
    assert run_analyses(instances["leo_rover"]).ok


def test_an_unknown_process_of_a_bound_deployment_is_a_binding_error(bound) -> None:
    assert bound["pioneer_3dx"].node("tracker_node").process == "tracker_node"
    with pytest.raises(BindingError, match="has no process 'ghost_node'"):
        bound["pioneer_3dx"].node("ghost_node")


def test_robot_cores_lists_every_core_with_its_type(library) -> None:
    cores = robot_cores(library, "pioneer_3dx::Pioneer_3DX.impl")
    assert [c.path.rpartition(".")[2] for c in cores] == [f"big_proc{i}" for i in range(1, 5)] + [
        f"little_proc{i}" for i in range(1, 5)
    ]
    assert {c.kind for c in cores} == {"Exynos_5422::ARM_A15", "Exynos_5422::ARM_A7"}
    assert not library.instances  # the robot's instance is not left behind


# ----------------------------------------------------------------------------- the search


@pytest.fixture(scope="module")
def proposal(project, bound, instances):
    return propose_binding(project, bound["pioneer_3dx"], instances["pioneer_3dx"])


def test_search_uses_each_nodes_measurements_for_each_core_type(proposal) -> None:
    big1 = "OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1"
    demands = proposal.demands
    assert demands["tracker_node"][big1] == Fraction(37000, 50000)  # its xu4_a15 PDM
    assert demands["tracker_node"][LITTLE1] == Fraction(40000, 50000)  # its xu4_a7 PDM
    assert demands["usb_cam_node"][big1] == Fraction(2319, 50000)
    assert demands["usb_cam_node"][LITTLE1] == Fraction(18500, 50000)
    assert demands["pos_to_cmd_node"][LITTLE1] == Fraction(1060, 100000)


def test_proposed_binding_passes_with_the_tracker_on_a_big_core(proposal, tmp_path) -> None:
    assert proposal.feasible and proposal.search.method == "cp-sat" and proposal.search.optimal
    assert proposal.search.max_load == Fraction(74, 100)
    assert "big_procs_cluster" in proposal.cores["tracker_node"]
    assert len(set(proposal.cores.values())) == 3
    proposed = proposal.bound
    assert proposed.root == "pioneer_3dx_proposed::tracking.impl"
    by_process = {n.process: n for n in proposed.nodes}
    assert by_process["tracker_node"].implementation.endswith(".xu4_a15")
    (path,) = write_model([proposed.package], tmp_path)
    instance = instantiate(read_files([path]), proposed.root)
    assert max(loads(instance).values()) == Fraction(74, 100)
    report = run_analyses(instance)
    assert not any(r.overloaded for r in report.cpu.processors)
    assert report.schedulability.ok
    assert all(t.deadline_misses == 0 for t in report.simulation.tasks)


def test_search_refuses_execution_times_for_unknown_elements(instances) -> None:
    instance = instances["pioneer_3dx"]
    root = instance.name
    with pytest.raises(ModelError, match="not a process searched"):
        search_deployment(instance, execution_times={"nowhere": {}})
    with pytest.raises(ModelError, match="not a candidate processor"):
        search_deployment(instance, execution_times={f"{root}.tracker_node": {"robot.nowhere": {}}})
    with pytest.raises(ModelError, match="not a thread"):
        search_deployment(
            instance, execution_times={"tracker_node": {f"robot.{LITTLE1}": {"no_thread": Fraction(1, 100)}}}
        )


def test_a_node_with_times_for_some_cores_runs_only_there(instances) -> None:
    instance = instances["pioneer_3dx"]
    big2 = "robot.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc2"
    result = search_deployment(
        instance,
        ["tracker_node"],
        execution_times={"tracker_node": {big2: {"image_tracker": Fraction(1, 100)}}},
    )
    assert result.binding(f"{instance.name}.tracker_node") == f"{instance.name}.{big2}"
    assert result.max_load == Fraction(1, 5)  # 10 ms every 50 ms, not scaled by the MIPS capacities


# ----------------------------------------------------------------------------- rates without timers


def write_variant(tmp_path: Path, old: str, new: str) -> Path:
    folder = tmp_path / "tracking"
    shutil.copytree(EXAMPLE, folder)
    rml = folder / "01-Software" / "tracking.rml"
    text = rml.read_text()
    assert old in text
    rml.write_text(text.replace(old, new))
    return folder


def test_a_component_without_timer_publishes_at_its_subscribers_rate(tmp_path, library) -> None:
    timer = """    timer target_timer
    {
      period = 0.1;
      priority = 50;
      deadline = 0.1;
    }
"""
    folder = write_variant(tmp_path, timer, "")
    project = read_project(folder)
    pioneer = bind_deployment(
        project, read_bindings(folder / "bindings.json").deployments["pioneer_3dx"], library
    )
    tracker = pioneer.node("tracker_node")
    timing = {t.thread: (t.period, t.source) for t in tracker.timings}
    assert timing["point_broadcaster"] == (Decimal("0.05"), "callback of image_in")
    receiver = {t.thread: t.period for t in pioneer.node("pos_to_cmd_node").timings}
    assert receiver["point_receiver"] == Decimal("0.05")  # the topic now comes every 50 ms


def test_ports_can_be_mapped_by_hand_or_left_unconnected(project, library) -> None:
    def unmap(data: dict) -> None:
        data["deployments"]["pioneer_3dx"]["nodes"]["usb_cam_node"]["ports"] = {"image_raw": None}
        data["deployments"]["pioneer_3dx"]["nodes"]["tracker_node"]["ports"] = {"target": "point_out"}

    spec = parse_bindings(spec_text(edited(unmap))).deployments["pioneer_3dx"]
    pioneer = bind_deployment(project, spec, library)
    assert [t.connection for t in pioneer.topics] == ["topic_Point"]
    # the rates are the ROSMOD model's, whether the AADL connection is made or not
    timing = {t.thread: t.source for t in pioneer.node("tracker_node").timings}
    assert timing["image_tracker"] == "topic tracking/Image (published every 0.05 s)"


# ----------------------------------------------------------------------------- errors


def _node(field: str, value):
    def change(data: dict) -> None:
        data["deployments"]["pioneer_3dx"]["nodes"]["tracker_node"][field] = value

    return change


def _deployment(field: str, value):
    def change(data: dict) -> None:
        if value is None:
            del data["deployments"]["pioneer_3dx"][field]
        else:
            data["deployments"]["pioneer_3dx"][field] = value

    return change


def _wifibot(data: dict) -> None:
    pioneer = data["deployments"]["pioneer_3dx"]
    pioneer["robot"] = "wifibot::WifiBot.impl"
    pioneer["robot_connections"] = []
    for entry in pioneer["nodes"].values():
        entry["core"] = "LE376.Atom_SOC.proc1"


def _rename_node(data: dict) -> None:
    nodes = data["deployments"]["pioneer_3dx"]["nodes"]
    nodes["tracker"] = nodes.pop("tracker_node")


def _extra_node(data: dict) -> None:
    data["deployments"]["pioneer_3dx"]["nodes"]["ghost_node"] = {"library": "x::y", "core": LITTLE1}


def _link(field: str, value):
    def change(data: dict) -> None:
        data["deployments"]["pioneer_3dx"]["robot_connections"][0][field] = value

    return change


def _unknown_deployment(data: dict) -> None:
    data["deployments"]["mars_rover"] = data["deployments"].pop("pioneer_3dx")


ERRORS = [
    pytest.param(
        _node("library", "nd_nothing::nothing_nd"),
        "nodes.tracker_node.library",
        "is not a process type or implementation of the library",
        id="unknown-library-node",
    ),
    pytest.param(
        _node("library", "pioneer_3dx::Pioneer_3DX.impl"),
        "nodes.tracker_node.library",
        "is not a process type",
        id="library-entry-not-a-node",
    ),
    pytest.param(
        _node("core", "OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc9"),
        "nodes.tracker_node.core",
        "the robot has no core 'OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc9'",
        id="unknown-core",
    ),
    pytest.param(
        _node("core", "OdroidXU4.Exynos_SOC"),
        "nodes.tracker_node.core",
        "the robot has no core",
        id="core-path-is-a-chip",
    ),
    pytest.param(
        _wifibot,
        "nodes.usb_cam_node.core",
        "has no platform-dependent implementation for core LE376.Atom_SOC.proc1 (Atom_D510::Atom_core)",
        id="no-pdm-for-the-core-type",
    ),
    pytest.param(
        _node("library", "nd_ocv_color_tracking::ocv_color_tracking_nd.xu4_a15"),
        "nodes.tracker_node.core",
        "was measured on exynos_5422::arm_a15, but core",
        id="pdm-of-another-core-type",
    ),
    pytest.param(
        _node("ports", {"no_such_port": "image_in"}),
        "nodes.tracker_node.ports.no_such_port",
        "has no publisher or subscriber 'no_such_port'",
        id="unknown-rosmod-port",
    ),
    pytest.param(
        _node("ports", {"image_in": "point_out"}),
        "nodes.tracker_node.ports.image_in",
        "has no in port 'point_out'",
        id="library-port-of-the-wrong-direction",
    ),
    pytest.param(
        _node("library", "nd_pos_to_cmd::pos_to_cmd_nd"),
        "nodes.tracker_node",
        "has no in port of a data type named 'image'",
        id="node-without-the-topics-port",
    ),
    pytest.param(
        _rename_node,
        "deployments.pioneer_3dx.nodes",
        "no binding for ROSMOD node 'tracker_node'",
        id="node-missing",
    ),
    pytest.param(_extra_node, "nodes.ghost_node", "has no ROSMOD node 'ghost_node'", id="node-unknown"),
    pytest.param(
        _deployment("robot", "pioneer_3dx::Pioneer_3DX"),
        "deployments.pioneer_3dx.robot",
        "is not a system implementation",
        id="robot-is-a-type",
    ),
    pytest.param(
        _deployment("topic_bus", "can_bus"),
        "deployments.pioneer_3dx.topic_bus",
        "is neither ros::ROSbus nor a bus of pioneer_3dx::Pioneer_3DX.impl (its buses: usb_bus)",
        id="unknown-topic-bus",
    ),
    pytest.param(
        _link("robot_port", "lidar_out"),
        "robot_connections[0]",
        "has no port 'lidar_out'",
        id="unknown-robot-port",
    ),
    pytest.param(
        _link("port", "no_port"), "robot_connections[0]", "has no port 'no_port'", id="unknown-node-port"
    ),
    pytest.param(
        _link("port", "rgb_image_raw_out"),
        "robot_connections[0]",
        "both out ports",
        id="two-out-ports",
    ),
    pytest.param(
        _link("bus", "eth_bus"), "robot_connections[0].bus", "has no bus 'eth_bus'", id="unknown-link-bus"
    ),
    pytest.param(
        _link("node", "camera_node"),
        "robot_connections[0]",
        "'camera_node' is not a node",
        id="unknown-link-node",
    ),
    pytest.param(
        _unknown_deployment,
        "deployments.mars_rover",
        "the project has no deployment 'mars_rover'",
        id="deployment",
    ),
]


@pytest.mark.parametrize(("change", "path", "message"), ERRORS)
def test_wrong_bindings_are_located_at_their_entry(change, path, message, project, library) -> None:
    text = spec_text(edited(change))
    spec = parse_bindings(text, "bindings.json")
    with pytest.raises(BindingError) as caught:
        bind_project(project, spec, library)
    error = caught.value
    assert message in error.message
    assert error.location.file == "bindings.json"
    assert error.location.path is not None and error.location.path.endswith(path)
    # the line is the entry's line in the file
    assert error.location.line is not None
    key = path.rpartition(".")[2].partition("[")[0]
    assert f'"{key}"' in text.splitlines()[error.location.line - 1]
    assert not library.instances


PARSE_ERRORS = [
    pytest.param(b'{"deployments": {', "not valid JSON", id="truncated"),
    pytest.param(b'{"deployments": {}, "deployments": {}}', "given twice", id="duplicate-member"),
    pytest.param(
        b'{"version": 1, "deployments": {"a": {"robot": "r", "nodes": NaN}}}', "not valid JSON", id="nan"
    ),
    pytest.param(b"\xff\xfe{}", "not UTF-8", id="not-utf8"),
    pytest.param(b"[" * 100_000 + b"]" * 100_000, "nested too deeply", id="deep-nesting"),
    pytest.param(b" " * (MAX_BINDINGS_BYTES + 1), "larger than", id="huge"),
]


@pytest.mark.parametrize(("data", "message"), PARSE_ERRORS)
def test_malformed_bindings_files_are_parse_errors(data, message) -> None:
    with pytest.raises(ParseError, match=message) as caught:
        parse_bindings(data, "bindings.json")
    assert caught.value.location.file == "bindings.json"


def test_json_syntax_errors_give_line_and_column() -> None:
    with pytest.raises(ParseError) as caught:
        parse_bindings('{\n  "version": 1,\n  "deployments": {,}\n}', "b.json")
    assert (caught.value.location.line, caught.value.location.column) == (3, 19)


MEMBER_ERRORS = [
    pytest.param(lambda d: d.update(version=2), "version", "unsupported version 2", id="version"),
    pytest.param(lambda d: d.update(extra=1), "extra", "unknown member 'extra'", id="unknown-top-member"),
    pytest.param(lambda d: d.pop("deployments"), "", "missing member 'deployments'", id="no-deployments"),
    pytest.param(lambda d: d.update(deployments={}), "deployments", "one member per deployment", id="empty"),
    pytest.param(
        _node("cores", LITTLE1), "nodes.tracker_node.cores", "unknown member 'cores'", id="typo-in-a-node"
    ),
    pytest.param(
        _node("core", 3), "nodes.tracker_node.core", "expected a non-empty string, got a number", id="type"
    ),
    pytest.param(_node("core", "  "), "nodes.tracker_node.core", "got an empty string", id="blank"),
    pytest.param(_node("core", "a\x00b"), "nodes.tracker_node.core", "no control characters", id="control"),
    pytest.param(
        _deployment("robot", None), "deployments.pioneer_3dx", "missing member 'robot'", id="no-robot"
    ),
    pytest.param(_deployment("nodes", []), "nodes", "one member per ROSMOD node", id="nodes-list"),
    pytest.param(
        _deployment("robot_connections", {}), "robot_connections", "expected a list", id="links-object"
    ),
    pytest.param(_link("hub", "x"), "robot_connections[0].hub", "unknown member 'hub'", id="link-member"),
]


@pytest.mark.parametrize(("change", "path", "message"), MEMBER_ERRORS)
def test_wrong_members_are_located(change, path, message) -> None:
    with pytest.raises(BindingError) as caught:
        parse_bindings(spec_text(edited(change)), "bindings.json")
    assert message in caught.value.message
    assert (caught.value.location.path or "").endswith(path)


def test_missing_bindings_file(tmp_path) -> None:
    with pytest.raises(ParseError, match="cannot read the bindings file") as caught:
        read_bindings(tmp_path / "nope.json")
    assert caught.value.location.file == str(tmp_path / "nope.json")


def test_the_library_is_read_when_not_given(project) -> None:
    spec = read_bindings(EXAMPLE / "bindings.json").deployments["leo_rover"]
    bound = bind_project(project, BindingsFile(file=None, deployments={"leo_rover": spec}))
    assert bound["leo_rover"].root == "leo_rover_bound::tracking.impl"


def test_only_rosmod_projects_are_bound(library) -> None:
    spec = read_bindings(EXAMPLE / "bindings.json").deployments["leo_rover"]
    with pytest.raises(BindingError, match="expected a rosmod Project"):
        bind_deployment(model.new("AadlModel", name="m"), spec, library)

"""The library read, instantiated and looked up: every figure of the paper's Tables 1 and 2.

Reads the whole library with the AADL reader, instantiates the node implementations (PIM and
the four PDMs of each node), the boards and robots, and the two example systems, then reads back
through the instances' resolved properties every value of Table 2 (with its unit), the hardware
capacities, the makers of Table 1, the bindings of the deployments and the path
``p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1``.

The constants below are the paper's figures as transcribed; when the paper's text is at hand
(``../shared/papers``, or ``$ROSAADL_PAPERS``), the library's figures are also checked against the
tables read from it, so a wrong figure in the library fails whichever way it is looked at.
"""

from __future__ import annotations

import logging
import os
import re
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.errors import ModelError
from rosaadl.importers.aadl_text import read_files
from rosaadl.lookup import PropertyLookup
from rosaadl.properties import EnumLiteral, Range, property_value
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity

ROOT = Path(__file__).resolve().parents[2]

# ----------------------------------------------------------------------------- Table 2
# node classifier, work thread, PIM period (us), the thread that publishes, its period (us)
NODES = {
    "usb_cam": ("nd_usb_cam::usb_cam_nd", "image_broadcaster", 33333, "image_broadcaster", 33333),
    "pos_to_cmd": ("nd_pos_to_cmd::pos_to_cmd_nd", "cmd_publisher", 100000, "cmd_publisher", 100000),
    "ocv_color_tracking": (
        "nd_ocv_color_tracking::ocv_color_tracking_nd",
        "image_tracker",
        33333,
        "point_broadcaster",
        100000,
    ),
}

# node, PDM, CET (us), MIPSBudget, raw MIPS, IPC, CPU load % (Table 2), reference core
TABLE2 = [
    ("usb_cam", "xu4_a15", 2319, 141.00, 197.00, 1.40, 6.96, "Exynos_5422::ARM_A15"),
    ("usb_cam", "xu4_a7", 18500, 776.00, 256, 0.33, 55.50, "Exynos_5422::ARM_A7"),
    ("usb_cam", "xavier_carmel", 2529, 99.36, 212.62, 2.14, 7.59, "Carmel::Carmel_core"),
    ("usb_cam", "rpi4_a72", 8411, 388.89, 350, 0.90, 25.23, "BCM2711::Cortex_A72"),
    ("pos_to_cmd", "xu4_a15", 700, 8.62, 1.03, 0.12, 0.70, "Exynos_5422::ARM_A15"),
    ("pos_to_cmd", "xu4_a7", 1060, 9.34, 1.12, 0.12, 1.06, "Exynos_5422::ARM_A7"),
    ("pos_to_cmd", "xavier_carmel", 288, 7.69, 1.00, 0.13, 0.29, "Carmel::Carmel_core"),
    ("pos_to_cmd", "rpi4_a72", 104, 4.49, 1.57, 0.35, 0.10, "BCM2711::Cortex_A72"),
    ("ocv_color_tracking", "xu4_a15", 37000, 2205, 4300, 1.95, 111, "Exynos_5422::ARM_A15"),
    ("ocv_color_tracking", "xu4_a7", 40000, 1705, 1450, 0.85, 120, "Exynos_5422::ARM_A7"),
    ("ocv_color_tracking", "xavier_carmel", 4127, 158, 370, 2.34, 12.38, "Carmel::Carmel_core"),
    ("ocv_color_tracking", "rpi4_a72", 7283, 338, 321, 0.95, 21.85, "BCM2711::Cortex_A72"),
]
TABLE2_IDS = [f"{row[0]}.{row[1]}" for row in TABLE2]

# port, Data_Size in bytes (Table 2 and the paper's ros_data listing)
DATA_SIZES = {
    "usb_cam": {"rgb_stream_in": 921000, "rgb_image_raw_out": 921000},
    "pos_to_cmd": {"point_in": 24, "cmd_vel_out": 48},
    "ocv_color_tracking": {"image_in": 921000, "point_out": 24},
}

# ----------------------------------------------------------------------------- Tables 1 and 2: hardware
# root classifier, core path inside it, MIPSCapacity (None: no figure), GHz (None: no figure), cores
CORES = [
    ("Odroid_XU4::Odroid_XU4.impl", "Exynos_SOC.big_procs_cluster.big_proc{}", 2000, 2.0, 4),
    ("Odroid_XU4::Odroid_XU4.impl", "Exynos_SOC.little_procs_cluster.little_proc{}", 1100, 1.4, 4),
    ("Jetson_Xavier_NX::Jetson_Xavier_NX.impl", "Carmel_SOC.proc{}", 2400, 1.9, 6),
    ("Raspberry_PI4B::Raspberry_PI4B.impl", "BCM2711_SOC.proc{}", 1500, 1.5, 4),
    ("LE_376::LE_376.impl", "Atom_SOC.proc{}", None, None, 2),
]

# robot classifier, board subcomponent, SoC subcomponent, robot maker, board maker, SoC maker (Table 1)
ROBOTS = [
    (
        "pioneer_3dx::Pioneer_3DX.impl",
        "OdroidXU4",
        "Exynos_SOC",
        "Generation Robots",
        "Hardkernel",
        "Samsung",
    ),
    ("rover_pro::Rover_Pro.impl", "JetsonXavierNX", "Carmel_SOC", "Rover Robotics", "NVIDIA", "NVIDIA"),
    (
        "turtlebot_2::TurtleBot_2.impl",
        "RaspberryPi4B",
        "BCM2711_SOC",
        "ClearPath Robotics",
        "Raspberry Pi",
        "Broadcom",
    ),
    ("leo_rover::LeoRover.impl", "RaspberryPi4B", "BCM2711_SOC", "Kell Ideas", "Raspberry Pi", "Broadcom"),
    ("wifibot::WifiBot.impl", "LE376", "Atom_SOC", "Nexter Robotics", "Commell", "Intel"),
]

# Table 2 "MIPS_demand" (MIPSCapacity of the core x CPU load) per node and core, and
# "Bandwidth_demand" in KBytes/s of each node's output topic
MIPS_DEMAND = {
    "usb_cam": {"xu4_a15": 139, "xu4_a7": 610, "xavier_carmel": 182, "rpi4_a72": 378},
    "pos_to_cmd": {"xu4_a15": 14.00, "xu4_a7": 11.66, "xavier_carmel": 6.91, "rpi4_a72": 1.56},
    "ocv_color_tracking": {"xu4_a15": 2220, "xu4_a7": 1320, "xavier_carmel": 297, "rpi4_a72": 328},
}
CORE_OF_PDM = {
    "xu4_a15": ("Odroid_XU4::Odroid_XU4.impl", "Exynos_SOC.big_procs_cluster.big_proc1"),
    "xu4_a7": ("Odroid_XU4::Odroid_XU4.impl", "Exynos_SOC.little_procs_cluster.little_proc1"),
    "xavier_carmel": ("Jetson_Xavier_NX::Jetson_Xavier_NX.impl", "Carmel_SOC.proc1"),
    "rpi4_a72": ("Raspberry_PI4B::Raspberry_PI4B.impl", "BCM2711_SOC.proc1"),
}
BANDWIDTH = {
    "usb_cam": ("rgb_image_raw_out", "image_broadcaster", 27630),
    "pos_to_cmd": ("cmd_vel_out", "cmd_publisher", 0.48),
    "ocv_color_tracking": ("point_out", "point_broadcaster", 0.24),
}

SYSTEMS = ["sys_tracking::tracking.impl", "sys_rover::rover.impl"]


# ----------------------------------------------------------------------------- helpers


@pytest.fixture(scope="module")
def library():
    return read_files([], include_library=True)


@pytest.fixture(scope="module")
def tracking(library):
    return instantiate(library, "sys_tracking::tracking.impl")


@pytest.fixture(scope="module")
def rover(library):
    return instantiate(library, "sys_rover::rover.impl")


def _in(value, unit: str) -> float:
    assert isinstance(value, Quantity), f"expected a number with a unit, got {value!r}"
    return value.to(unit)


def _category(obj) -> str:
    """The component category as one lower-case word (``virtualBus`` -> ``virtualbus``)."""
    return str(obj.category).replace(" ", "").lower()


def _references(value) -> list:
    assert isinstance(value, list), f"expected a list of references, got {value!r}"
    return value


def _connection_through(root, context_path: str, connection: str):
    """The connection instances whose declared connections include ``connection`` of ``context``."""
    context = model.find_instance(root, context_path)
    found = []
    for obj in model.walk(root):
        if obj.eClass.name != "ConnectionInstance":
            continue
        for ref in obj.connectionReferences:
            if ref.connection == connection and ref.context is context:
                found.append(obj)
    return found


# ----------------------------------------------------------------------------- reading


def test_library_reads_without_warnings(caplog) -> None:
    found: list = []
    with caplog.at_level(logging.WARNING, logger="rosaadl"):
        library = read_files([], include_library=True, warnings=found)
    assert [str(d) for d in found] == []
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert warnings == []
    names = {unit.name for unit in library.units}
    for name in (
        "ros",
        "ros_data",
        "nd_usb_cam",
        "sys_tracking",
        "sys_rover",
        "ROS_Properties",
        "ROS_Profiling",
    ):
        assert name in names


# message, Data_Size in bytes: the paper's sizes and the ROS definitions of fixed-size messages
MESSAGE_SIZES = {
    "ros_data::Image.rgb": 921000,
    "ros_data::video_stream.rgb": 921000,
    "ros_data::Point.impl": 24,
    "ros_data::Twist": 48,
    "ros_data::Twist.impl": 48,
    "ros_data::Vector3.impl": 24,
    "ros_data::Quaternion.impl": 32,
    "ros_data::Pose.impl": 56,
    "ros_data::Bool": 1,
    "ros_data::Int32": 4,
    "ros_data::Float64": 8,
    "ros_data::Empty": 0,
    "ros_data::ColorRGBA": 16,
}


def test_declarative_lookup_of_message_sizes(library) -> None:
    lookup = PropertyLookup(library)
    for name, size in MESSAGE_SIZES.items():
        classifier = model.find_classifier(library, name)
        assert classifier is not None, name
        assert _in(lookup.python_value(classifier, "Data_Size"), "Bytes") == size, name
    # variable-size messages have none
    for name in ("ros_data::Image.impl", "ros_data::String", "ros_data::Header", "ros_data::TFMessage"):
        assert lookup.python_value(model.find_classifier(library, name), "Data_Size") is None, name
    image = lookup.python_value(
        model.find_classifier(library, "ros_data::Image"), "ROS_Properties::Message_Type"
    )
    assert image == "sensor_msgs/Image"


def test_declarative_lookup_of_the_work_thread_deadline(library) -> None:
    # Deadline defaults to the Period (Timing_Properties), so the PIM's deadline is its period
    lookup = PropertyLookup(library)
    thread = model.find_classifier(library, "nd_usb_cam::imagePublisher.xu4_a15")
    assert _in(lookup.python_value(thread, "Deadline"), "us") == 33333


@pytest.mark.parametrize("root", SYSTEMS + [row[0] for row in ROBOTS])
def test_system_instantiates_without_warnings(library, root: str, caplog) -> None:
    diagnostics: list = []
    with caplog.at_level(logging.WARNING, logger="rosaadl"):
        instance = instantiate(library, root, diagnostics=diagnostics)
    assert instance.eClass.name == "SystemInstance"
    assert instance.classifier.lower() == root.lower()
    assert [str(d) for d in diagnostics if d.severity != "info"] == []
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert warnings == []


# ----------------------------------------------------------------------------- nodes (Table 2)


@pytest.mark.parametrize("node", sorted(NODES))
def test_pim_carries_the_period(library, node: str) -> None:
    classifier, work, period, publisher, out_period = NODES[node]
    root = instantiate(library, f"{classifier}.impl")
    assert _in(property_value(root, "Period"), "us") == period
    assert _in(property_value(model.find_instance(root, work), "Period"), "us") == period
    assert _in(property_value(model.find_instance(root, publisher), "Period"), "us") == out_period
    # no measurement on the PIM
    assert property_value(model.find_instance(root, work), "Compute_Execution_Time") is None
    assert property_value(root, "SEI::MIPSBudget") is None


@pytest.mark.parametrize("row", TABLE2, ids=TABLE2_IDS)
def test_pdm_carries_table2(library, row) -> None:
    node, pdm, cet, budget, raw, ipc, load, core = row
    classifier, work, period, _publisher, _out = NODES[node]
    root = instantiate(library, f"{classifier}.{pdm}")
    thread = model.find_instance(root, work)
    assert _category(thread) == "thread"

    cet_value = property_value(thread, "Compute_Execution_Time")
    assert isinstance(cet_value, Range)
    library_cet = _in(cet_value.maximum, "us")
    library_period = _in(property_value(thread, "Timing_Properties::Period"), "us")
    assert _in(cet_value.minimum, "us") == cet
    assert library_cet == cet
    assert library_period == period
    # the paper's CPU load, from the library's figures
    assert 100 * library_cet / library_period == pytest.approx(load, abs=0.01 if load < 100 else 0.5)

    library_budget = _in(property_value(root, "SEI::MIPSBudget"), "MIPS")
    library_raw = _in(property_value(root, "ROS_Profiling::Raw_MIPS"), "MIPS")
    library_ipc = property_value(root, "ROS_Profiling::IPC")
    assert library_budget == pytest.approx(budget)
    assert library_raw == pytest.approx(raw)
    assert library_ipc == pytest.approx(ipc)
    # the library's MIPSBudget is its raw MIPS / IPC, to the rounding of the paper's two-decimal IPC
    assert library_raw / library_ipc == pytest.approx(library_budget, rel=0.03)
    assert str(property_value(thread, "Reference_Processor")).lower() == core.lower()


def test_usb_cam_queue_size_on_xu4_a15(library) -> None:
    root = instantiate(library, "nd_usb_cam::usb_cam_nd.xu4_a15")
    port = model.find_instance(root, "image_broadcaster.pub_msg")
    assert property_value(port, "Queue_Size") == 512
    other = instantiate(library, "nd_usb_cam::usb_cam_nd.rpi4_a72")
    assert property_value(model.find_instance(other, "image_broadcaster.pub_msg"), "Queue_Size") == 1


@pytest.mark.parametrize("node", sorted(NODES))
def test_ports_carry_message_sizes(library, node: str) -> None:
    classifier = NODES[node][0]
    root = instantiate(library, f"{classifier}.impl")
    for port, size in DATA_SIZES[node].items():
        assert _in(property_value(model.find_instance(root, port), "Data_Size"), "Bytes") == size, port


@pytest.mark.parametrize("row", TABLE2, ids=TABLE2_IDS)
def test_mips_demand_on_the_measured_core(library, row) -> None:
    node, pdm, cet, *_rest = row
    classifier, work, period, _publisher, _out = NODES[node]
    board, core_path = CORE_OF_PDM[pdm]
    core = model.find_instance(instantiate(library, board), core_path)
    capacity = _in(property_value(core, "SEI::MIPSCapacity"), "MIPS")
    thread = model.find_instance(instantiate(library, f"{classifier}.{pdm}"), work)
    cet_us = _in(property_value(thread, "Compute_Execution_Time").maximum, "us")
    period_us = _in(property_value(thread, "Period"), "us")
    assert capacity * cet_us / period_us == pytest.approx(MIPS_DEMAND[node][pdm], rel=0.01)


@pytest.mark.parametrize("node", sorted(NODES))
def test_bandwidth_demand_of_the_output_topic(library, node: str) -> None:
    port, publisher, kbytes_per_s = BANDWIDTH[node]
    root = instantiate(library, f"{NODES[node][0]}.impl")
    size = _in(property_value(model.find_instance(root, port), "Data_Size"), "Bytes")
    period = _in(property_value(model.find_instance(root, publisher), "Period"), "sec")
    assert size / period / 1000 == pytest.approx(kbytes_per_s, rel=0.001)


def test_image_size_is_written_as_the_paper_does(library) -> None:
    root = instantiate(library, "nd_usb_cam::usb_cam_nd.impl")
    size = property_value(model.find_instance(root, "rgb_image_raw_out"), "Data_Size")
    assert (size.value, size.unit) == (921, "KByte")
    # 921 KByte every 33333 us: the paper's 27.63 MBytes/s
    assert _in(size, "Bytes") / 33333e-6 / 1e6 == pytest.approx(27.63, abs=0.005)


def test_thread_kinds_and_dispatch(library) -> None:
    root = instantiate(library, "nd_usb_cam::usb_cam_nd.impl")
    publisher = model.find_instance(root, "image_broadcaster")
    spinner = model.find_instance(root, "usbSpinner")
    assert property_value(publisher, "Dispatch_Protocol") == EnumLiteral("Periodic")
    assert property_value(spinner, "Dispatch_Protocol") == EnumLiteral("Sporadic")
    assert property_value(publisher, "ROS_Properties::Thread_Kind") == EnumLiteral("Publisher")
    assert property_value(spinner, "ROS_Properties::Thread_Kind") == EnumLiteral("Spinner")
    assert property_value(root, "ROS_Properties::Node_Name") == "usb_cam"


# ----------------------------------------------------------------------------- hardware (Tables 1 and 2)


@pytest.mark.parametrize("row", CORES, ids=[f"{row[0]}:{row[1]}" for row in CORES])
def test_cores_carry_capacity_and_frequency(library, row) -> None:
    root_name, pattern, mips, ghz, count = row
    root = instantiate(library, root_name)
    cores = [model.find_instance(root, pattern.format(i)) for i in range(1, count + 1)]
    with pytest.raises(ModelError):  # one core more than the chip has is not there
        model.find_instance(root, pattern.format(count + 1))
    for core in cores:
        assert _category(core) == "processor"
        capacity = property_value(core, "SEI::MIPSCapacity")
        frequency = property_value(core, "Hardware_Properties::Clock_Frequency")
        if mips is None:
            assert capacity is None and frequency is None  # the paper gives no figure
        else:
            assert _in(capacity, "MIPS") == pytest.approx(mips)
            assert _in(frequency, "GHz") == pytest.approx(ghz)


@pytest.mark.parametrize("row", ROBOTS, ids=[row[0] for row in ROBOTS])
def test_robots_boards_and_socs_name_their_makers(library, row) -> None:
    root_name, board, soc, robot_maker, board_maker, soc_maker = row
    root = instantiate(library, root_name)
    assert property_value(root, "Hardware_Properties::Maker") == robot_maker
    assert property_value(model.find_instance(root, board), "Hardware_Properties::Maker") == board_maker
    soc_instance = model.find_instance(root, f"{board}.{soc}")
    assert property_value(soc_instance, "Hardware_Properties::Maker") == soc_maker


@pytest.mark.parametrize(
    ("classifier", "mbps"),
    [
        ("USB::usb.v2_0", 480),
        ("USB::usb.v3_0", 5000),
        ("ETHERNET::ethernet.fast", 100),
        ("ETHERNET::ethernet.gigabit", 1000),
    ],
)
def test_bus_capacities_are_the_standards_rates(library, classifier: str, mbps: int, tmp_path) -> None:
    # buses are checked inside the robots that carry them, or on their own through a probe system
    probe = tmp_path / "bus_probe.aadl"
    package, _, impl = classifier.partition("::")
    probe.write_text(
        f"package bus_probe\npublic\n  with {package};\n  system probe end probe;\n"
        f"  system implementation probe.impl\n    subcomponents\n      b: bus {classifier};\n"
        "  end probe.impl;\nend bus_probe;\n",
        encoding="utf-8",
    )
    probed = read_files([probe], include_library=True)
    root = instantiate(probed, "bus_probe::probe.impl")
    bus = model.find_instance(root, "b")
    assert _in(property_value(bus, "SEI::BandWidthCapacity"), "Mbps") == pytest.approx(mbps)


# ----------------------------------------------------------------------------- the example systems


def test_tracking_binds_usb_cam_to_big_proc1(tracking) -> None:
    core = model.find_instance(tracking, "p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1")
    assert _category(core) == "processor"
    assert _in(property_value(core, "SEI::MIPSCapacity"), "MIPS") == 2000
    usbcam = model.find_instance(tracking, "rem_trk_sw.usbcam")
    assert _references(property_value(usbcam, "Actual_Processor_Binding")) == [core]
    # threads inherit their process's binding
    thread = model.find_instance(tracking, "rem_trk_sw.usbcam.image_broadcaster")
    assert _references(property_value(thread, "Actual_Processor_Binding")) == [core]
    assert _in(property_value(thread, "Compute_Execution_Time").maximum, "us") == 2319


def test_tracking_binds_every_node_to_a_core(tracking) -> None:
    expected = {
        "rem_trk_sw.usbcam": "p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1",
        "rem_trk_sw.tracker": "p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc2",
        "rem_trk_sw.poscmd": "p3DX.OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc1",
    }
    for node, core in expected.items():
        bound = _references(property_value(model.find_instance(tracking, node), "Actual_Processor_Binding"))
        assert bound == [model.find_instance(tracking, core)], node


def test_tracking_binds_topics_to_rosbus(tracking) -> None:
    rosbus = model.find_instance(tracking, "ROSbus")
    assert _category(rosbus) == "virtualbus"
    for name in ("con6", "con7"):
        connections = _connection_through(tracking, "rem_trk_sw", name)
        assert len(connections) == 1, name
        assert _references(property_value(connections[0], "Actual_Connection_Binding")) == [rosbus]
    image = _connection_through(tracking, "rem_trk_sw", "con6")[0]
    assert model.instance_path(image.source).endswith("usbcam.image_broadcaster.pub_msg")
    assert model.instance_path(image.destination).endswith("tracker.image_tracker.cb_msg")
    camera = _connection_through(tracking, model.instance_path(tracking), "cam_stream")
    assert len(camera) == 1
    usb = model.find_instance(tracking, "p3DX.usb_bus")
    assert _references(property_value(camera[0], "Actual_Connection_Binding")) == [usb]


def test_tracking_has_the_end_to_end_flow(tracking) -> None:
    flows = [obj for obj in model.walk(tracking) if obj.eClass.name == "EndToEndFlowInstance"]
    assert [flow.name for flow in flows] == ["etef_tracking"]


def test_rover_runs_the_rpi4_measurements(rover) -> None:
    expected = {"usbcam": ("proc1", 8411), "tracker": ("proc2", 7283), "poscmd": ("proc3", 104)}
    work = {"usbcam": "image_broadcaster", "tracker": "image_tracker", "poscmd": "cmd_publisher"}
    for node, (core, cet) in expected.items():
        process = model.find_instance(rover, f"rover_sw.{node}")
        target = model.find_instance(rover, f"leo.RaspberryPi4B.BCM2711_SOC.{core}")
        assert _references(property_value(process, "Actual_Processor_Binding")) == [target]
        thread = model.find_instance(process, work[node])
        assert _in(property_value(thread, "Compute_Execution_Time").minimum, "us") == cet
    rosbus = model.find_instance(rover, "ROSbus")
    for name in ("con6", "con7"):
        (connection,) = _connection_through(rover, "rover_sw", name)
        assert _references(property_value(connection, "Actual_Connection_Binding")) == [rosbus]


# ----------------------------------------------------------------------------- the paper's own tables

PAPER = (
    Path(os.environ.get("ROSAADL_PAPERS") or ROOT.parent / "shared" / "papers") / "aadl-ros-library-paper.txt"
)
# Table 2's four measurement columns, as the paper heads them, and the PDMs that carry them
PAPER_CORES = ("ARM A15", "ARM A7", "NVIDIA Carmel", "ARM A72")
PAPER_PDMS = ("xu4_a15", "xu4_a7", "xavier_carmel", "rpi4_a72")
# the port whose Data_Size Table 2 gives for each node (IN for usb_cam, OUT for the others)
PAPER_DATA_PORT = {"usb_cam": "rgb_stream_in", "pos_to_cmd": "cmd_vel_out", "ocv_color_tracking": "point_out"}
# Table 1's robots, and where the library holds them: robot classifier, board and SoC subcomponents
PAPER_ROBOTS = {row[0].partition("::")[0].replace("_", "").lower(): row[:3] for row in ROBOTS}
# Where the library's makers differ from the paper's spelling (compared case-insensitively), and why
MAKER_SPELLINGS = {
    "Commel": ("Commell", "the LE-376's maker is Commell; the paper misspells it"),
    "RaspBerry": ("Raspberry Pi", "the board's maker is Raspberry Pi (Ltd), as the library names it"),
}


def _number(cell: str) -> float | None:
    try:
        return float(cell)
    except ValueError:
        return None


@pytest.fixture(scope="module")
def paper() -> dict:
    """The paper's Table 1 rows and Table 2 figures, read from its text (tab-separated tables)."""
    if not PAPER.is_file():
        pytest.skip(f"the paper's text is not at {PAPER} (set ROSAADL_PAPERS to its folder)")
    lines = PAPER.read_text(encoding="utf-8").splitlines()
    table1 = lines.index("Table 1: Hardware models: Robots & SBC")
    robots, previous = {}, None
    for line in lines[table1 + 3 :]:
        if not line.strip():
            break
        cells = [cell.strip() for cell in line.split("\t")]
        if previous is not None:
            cells = [prev if cell == '"' else cell for cell, prev in zip(cells, previous, strict=False)]
        robots[cells[0]] = {"robot": cells[1], "board": cells[3], "soc": cells[5]}
        previous = cells
    table2 = next(i for i, line in enumerate(lines) if line.startswith("Table 2: Catalog of models"))
    figures: dict[str, dict[str, list[float]]] = {}
    node = "hardware"
    for line in lines[table2 + 1 :]:
        cells = [cell.strip() for cell in line.split("\t") if cell.strip()]
        if not cells:
            if node != "hardware":
                break
            continue
        if cells[0] in NODES:
            node, cells = cells[0], cells[1:]
        # the label is the cell before the first figure (or the first cell of a row of names)
        first = next((k for k, cell in enumerate(cells) if _number(cell) is not None), None)
        if first is None:
            label, values = cells[0], cells[1:]
        elif first == 0:
            continue
        else:
            label, values = cells[first - 1], [_number(cell) for cell in cells[first:]]
        label = re.sub(r"\s*\(.*\)$", "", label)  # "Period (μ s)" -> "Period"
        figures.setdefault(node, {})[label] = values
    assert figures["hardware"]["CPU"] == list(PAPER_CORES), "Table 2's columns moved"
    return {"robots": robots, "table2": figures}


@pytest.mark.corpus
@pytest.mark.parametrize("node", sorted(NODES))
def test_node_figures_are_the_papers(library, paper, node: str) -> None:
    figures = paper["table2"][node]
    classifier, work, _period, publisher, _out = NODES[node]
    pim = instantiate(library, f"{classifier}.impl")
    assert _in(property_value(model.find_instance(pim, work), "Period"), "us") == figures["Period"][0]
    if "Period OUT" in figures:
        out = property_value(model.find_instance(pim, publisher), "Period")
        assert _in(out, "us") == figures["Period OUT"][0]
    # the paper writes pos_to_cmd's 48 (a Twist) under "Kbyte": the figure is bytes (ROS's Twist)
    size = property_value(model.find_instance(pim, PAPER_DATA_PORT[node]), "Data_Size")
    assert _in(size, "Bytes") == figures["Data_Size"][0]
    port, sender, _ = BANDWIDTH[node]
    size = _in(property_value(model.find_instance(pim, port), "Data_Size"), "Bytes")
    rate = _in(property_value(model.find_instance(pim, sender), "Period"), "sec")
    assert size / rate / 1000 == pytest.approx(figures["Bandwidth_demand"][0], rel=0.001)

    for column, pdm in enumerate(PAPER_PDMS):
        root = instantiate(library, f"{classifier}.{pdm}")
        thread = model.find_instance(root, work)
        cet = _in(property_value(thread, "Compute_Execution_Time").maximum, "us")
        period = _in(property_value(thread, "Period"), "us")
        assert cet == figures["Compute_execution_time"][column], pdm
        assert _in(property_value(root, "SEI::MIPSBudget"), "MIPS") == pytest.approx(
            figures["MIPSBudget"][column]
        ), pdm
        assert _in(property_value(root, "ROS_Profiling::Raw_MIPS"), "MIPS") == pytest.approx(
            figures["MIPS"][column]
        ), pdm
        assert property_value(root, "ROS_Profiling::IPC") == pytest.approx(figures["IPC"][column]), pdm
        load = figures["CPU_load %"][column]
        assert 100 * cet / period == pytest.approx(load, abs=0.01 if load < 100 else 0.5), pdm
        board, core_path = CORE_OF_PDM[pdm]
        core = model.find_instance(instantiate(library, board), core_path)
        capacity = _in(property_value(core, "SEI::MIPSCapacity"), "MIPS")
        demand = figures["MIPS_demand"][column]
        assert capacity * cet / period == pytest.approx(demand, rel=0.01), pdm


@pytest.mark.corpus
@pytest.mark.parametrize("pdm", PAPER_PDMS)
def test_core_figures_are_the_papers(library, paper, pdm: str) -> None:
    column = PAPER_PDMS.index(pdm)
    board, core_path = CORE_OF_PDM[pdm]
    core = model.find_instance(instantiate(library, board), core_path)
    hardware = paper["table2"]["hardware"]
    assert _in(property_value(core, "SEI::MIPSCapacity"), "MIPS") == hardware["MIPSCapacity"][column]
    frequency = property_value(core, "Hardware_Properties::Clock_Frequency")
    assert _in(frequency, "GHz") == pytest.approx(hardware["frequency"][column])


@pytest.mark.corpus
def test_makers_are_the_papers(library, paper) -> None:
    assert {name.replace(" ", "").lower() for name in paper["robots"]} == set(PAPER_ROBOTS)
    for name, makers in paper["robots"].items():
        classifier, board, soc = PAPER_ROBOTS[name.replace(" ", "").lower()]
        root = instantiate(library, classifier)
        held = {
            "robot": property_value(root, "Hardware_Properties::Maker"),
            "board": property_value(model.find_instance(root, board), "Hardware_Properties::Maker"),
            "soc": property_value(model.find_instance(root, f"{board}.{soc}"), "Hardware_Properties::Maker"),
        }
        for part, maker in makers.items():
            expected = MAKER_SPELLINGS.get(maker, (maker, ""))[0]
            assert held[part].lower() == expected.lower(), f"{name} {part}: {held[part]!r}, paper {maker!r}"

"""The component library API: list, describe, and measured profiles turned into PDM packages.

The profile tests go the whole way: a CSV becomes AADL packages on disk, which are read back with
the library, instantiated in a small system that binds the new PDMs to library cores, and whose
values are read back through the property lookup with their units. Malformed files must name the
row and the column of every problem (file:line:column) and write nothing.
"""

from __future__ import annotations

import logging
from decimal import Decimal
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosaadl import model
from rosaadl.errors import RosaadlError
from rosaadl.importers.aadl_text import read_files
from rosaadl.lookup import PropertyLookup
from rosaadl.properties import Range
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity
from rosaadl.workflow.library_add_profile import add_profiles
from rosaadl.workflow.library_catalog import ComponentNotFound, describe, list_packages, read_library
from rosaadl.workflow.library_measurements import COLUMNS, MeasurementError, parse_measurements

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "examples" / "profiles" / "sample_measurements.csv"
HEADER = ",".join(COLUMNS)

# node, thread, PDM, CET (us), raw MIPS, IPC of the sample file
SAMPLE_ROWS = [
    ("nd_usb_cam_profiles::usb_cam_nd.le376_atom", "image_broadcaster", 6100, 310, 0.62),
    ("nd_usb_cam_profiles::usb_cam_nd.le376_atom", "usbSpinner", 950, 310, 0.62),
    ("nd_ocv_color_tracking_profiles::ocv_color_tracking_nd.le376_atom", "image_tracker", 29500, 1180, 0.58),
    ("nd_pos_to_cmd_profiles::pos_to_cmd_nd.le376_atom", "cmd_publisher", 410, 1.25, 0.21),
]

# The paper's Table 2 as a measurements file (boards and cores named as the library's PDMs)
TABLE2_CSV = f"""{HEADER}
usb_cam,image_broadcaster,xu4,a15,33333,2319,197.00,1.40,921000
usb_cam,image_broadcaster,xu4,a7,33333,18500,256,0.33,921000
usb_cam,image_broadcaster,xavier,carmel,33333,2529,212.62,2.14,921000
usb_cam,image_broadcaster,rpi4,a72,33333,8411,350,0.90,921000
pos_to_cmd,cmd_publisher,xu4,a15,100000,700,1.03,0.12,48
pos_to_cmd,cmd_publisher,xu4,a7,100000,1060,1.12,0.12,48
pos_to_cmd,cmd_publisher,xavier,carmel,100000,288,1.00,0.13,48
pos_to_cmd,cmd_publisher,rpi4,a72,100000,104,1.57,0.35,48
ocv_color_tracking,image_tracker,xu4,a15,33333,37000,4300,1.95,
ocv_color_tracking,image_tracker,xu4,a7,33333,40000,1450,0.85,
ocv_color_tracking,image_tracker,xavier,carmel,33333,4127,370,2.34,
ocv_color_tracking,image_tracker,rpi4,a72,33333,7283,321,0.95,
"""

SYSTEM = """
package profile_test_sys
public
  with ros, LE_376, nd_usb_cam_profiles, nd_ocv_color_tracking_profiles, nd_pos_to_cmd_profiles;

  system app
  end app;

  system implementation app.impl
    subcomponents
      board: system LE_376::LE_376.impl;
      cam: process nd_usb_cam_profiles::usb_cam_nd.le376_atom;
      trk: process nd_ocv_color_tracking_profiles::ocv_color_tracking_nd.le376_atom;
      cmd: process nd_pos_to_cmd_profiles::pos_to_cmd_nd.le376_atom;
      ROSbus: virtual bus ros::ROSbus.impl;
    connections
      c1: port cam.rgb_image_raw_out -> trk.image_in;
      c2: port trk.point_out -> cmd.point_in;
    properties
      Actual_Processor_Binding => (reference (board.Atom_SOC.proc1)) applies to cam, trk;
      Actual_Processor_Binding => (reference (board.Atom_SOC.proc2)) applies to cmd;
      Actual_Connection_Binding => (reference (ROSbus)) applies to c1, c2;
  end app.impl;
end profile_test_sys;
"""

# A node that is not in the library: a talker with a publishing thread and a thread with two
# outgoing data ports.
TALKER = """
package nd_talker
public
  with ros, ros_data, ROS_Properties;

  process talker_nd extends ros::node
    features
      chatter_out: out event data port ros_data::String;
      status_out: out event data port ros_data::Bool;
    properties
      ROS_Properties::Node_Name => "talker";
  end talker_nd;

  process implementation talker_nd.impl extends ros::node.impl
    subcomponents
      chatter: thread chatterPublisher.impl;
      status: thread twoPorts.impl;
    connections
      c1: port chatter.pub_msg -> chatter_out;
      c2: port status.a -> status_out;
    properties
      Period => 100 ms;
  end talker_nd.impl;

  thread chatterPublisher extends ros::publisher
    features
      pub_msg: refined to out event data port ros_data::String;
  end chatterPublisher;

  thread implementation chatterPublisher.impl
    properties
      Period => 100 ms;
  end chatterPublisher.impl;

  thread twoPorts extends ros::timer
    features
      a: out event data port ros_data::Bool;
      b: out event data port ros_data::Bool;
  end twoPorts;

  thread implementation twoPorts.impl
    properties
      Period => 100 ms;
  end twoPorts.impl;
end nd_talker;
"""


@pytest.fixture(scope="module")
def library():
    return read_library()


@pytest.fixture(scope="module")
def sample_out(tmp_path_factory):
    out = tmp_path_factory.mktemp("profiles")
    warnings: list = []
    result = add_profiles(SAMPLE, out, warnings=warnings)
    return out, result, warnings


def _csv(tmp_path: Path, text: str, name: str = "m.csv") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _us(value) -> float:
    assert isinstance(value, Quantity), f"expected a number with a unit, got {value!r}"
    return value.to("us")


def _errors(text: str) -> list[MeasurementError]:
    _, errors, _ = parse_measurements(text, "m.csv")
    return errors


# =========================================================================== list


def test_list_has_every_unit_and_classifier(library) -> None:
    packages = list_packages(library)
    assert [p.name for p in packages] == sorted((u.name for u in library.units), key=str.lower)
    by_name = {p.name: p for p in packages}
    for unit in library.units:
        summary = by_name[unit.name]
        if unit.eClass.name == "PropertySet":
            assert summary.kind == "property set"
            assert list(summary.properties) == [p.name for p in unit.ownedProperties]
        else:
            assert summary.kind == "package"
            assert [c.name for c in summary.components] == [c.name for c in unit.classifiers]
        assert summary.library is True
        assert summary.file and not summary.file.startswith("/") and summary.file.endswith(".aadl")
    cam = {c.name: c for c in by_name["nd_usb_cam"].components}
    assert cam["usb_cam_nd"].as_dict() == {
        "name": "usb_cam_nd",
        "category": "process",
        "kind": "type",
        "extends": "ros::node",
    }
    assert cam["usb_cam_nd.xu4_a15"].kind == "implementation"
    assert cam["usb_cam_nd.xu4_a15"].extends == "nd_usb_cam::usb_cam_nd.impl"
    assert cam["imagePublisher.impl"].extends is None
    assert by_name["nd_usb_cam"].file == "nodes/nd_usb_cam.aadl"
    assert "Raw_MIPS" in by_name["ROS_Profiling"].properties
    assert str(cam["usb_cam_nd.impl"]) == "process implementation usb_cam_nd.impl extends ros::node.impl"


def test_list_includes_inputs(tmp_path) -> None:
    talker = _csv(tmp_path, TALKER, "nd_talker.aadl")
    workspace = read_library([talker])
    summary = {p.name: p for p in list_packages(workspace)}["nd_talker"]
    assert summary.library is False and summary.file == str(talker)
    assert [c.name for c in summary.components][:2] == ["talker_nd", "talker_nd.impl"]


# =========================================================================== describe


def test_describe_a_pdm(library) -> None:
    info = describe(library, "nd_usb_cam::usb_cam_nd.xu4_a15")
    assert info["what"] == "classifier" and info["category"] == "process" and info["kind"] == "implementation"
    assert info["extends"] == ["nd_usb_cam::usb_cam_nd.impl", "ros::node.impl"]
    assert info["type"] == "nd_usb_cam::usb_cam_nd" and info["type_extends"] == ["ros::node"]
    assert info["file"] == "nodes/nd_usb_cam.aadl" and info["line"] > 0 and info["library"] is True
    features = {f["name"]: f for f in info["features"]}
    assert features["rgb_image_raw_out"]["direction"] == "out"
    assert features["rgb_image_raw_out"]["category"] == "event data port"
    assert features["rgb_image_raw_out"]["classifier"] == "ros_data::Image.rgb"
    assert features["rgb_stream_in"]["direction"] == "in"
    subs = {s["name"]: s for s in info["subcomponents"]}
    assert subs["image_broadcaster"]["classifier"] == "nd_usb_cam::imagePublisher.xu4_a15"
    assert subs["image_broadcaster"]["refined"] is True
    assert subs["image_broadcaster"]["from"] == "nd_usb_cam::usb_cam_nd.xu4_a15"
    assert subs["usbSpinner"]["from"] == "nd_usb_cam::usb_cam_nd.impl"
    connections = {c["name"]: c for c in info["connections"]}
    assert connections["con1"]["source"] == "image_broadcaster.pub_msg"
    assert connections["con1"]["destination"] == "rgb_image_raw_out" and connections["con1"]["kind"] == "port"
    props = {p["property"]: p for p in info["properties"] if not p["applies_to"]}
    assert props["SEI::MIPSBudget"]["value"] == "141.0 MIPS"
    assert (props["SEI::MIPSBudget"]["number"], props["SEI::MIPSBudget"]["unit"]) == (141.0, "MIPS")
    assert props["ROS_Profiling::IPC"]["number"] == 1.4 and props["ROS_Profiling::IPC"]["unit"] is None
    assert props["Timing_Properties::Reference_Processor"]["value"] == "classifier (Exynos_5422::ARM_A15)"
    assert props["Timing_Properties::Period"] == {
        "property": "Timing_Properties::Period",
        "value": "33333 us",
        "number": 33333,
        "unit": "us",
        "applies_to": [],
        "from": "nd_usb_cam::usb_cam_nd.impl",
    }
    assert props["ROS_Properties::Node_Name"]["from"] == "nd_usb_cam::usb_cam_nd"
    topic = [p for p in info["properties"] if p["applies_to"] == ["rgb_image_raw_out"]]
    assert topic and topic[0]["value"] == '"/usb_cam/image_raw"'


def test_describe_a_thread_pdm_and_a_type(library) -> None:
    info = describe(library, "nd_usb_cam::imagePublisher.xu4_a15")
    props = {(p["property"], tuple(p["applies_to"])): p for p in info["properties"]}
    cet = props[("Timing_Properties::Compute_Execution_Time", ())]
    assert cet["value"] == "2319 us .. 2319 us"
    assert cet["minimum"] == {"number": 2319, "unit": "us"} and cet["maximum"] == {
        "number": 2319,
        "unit": "us",
    }
    assert props[("Communication_Properties::Queue_Size", ("pub_msg",))]["value"] == "512"
    assert props[("Thread_Properties::Dispatch_Protocol", ())]["from"] == "ros::publisher"
    assert props[("Timing_Properties::Period", ())]["from"] == "nd_usb_cam::imagePublisher.impl"
    # unqualified names are searched in every package
    ctype = describe(library, "imagepublisher")
    assert ctype["name"] == "nd_usb_cam::imagePublisher" and ctype["kind"] == "type"
    assert ctype["implementations"] == [
        f"nd_usb_cam::imagePublisher.{pdm}"
        for pdm in ("impl", "xu4_a15", "xu4_a7", "xavier_carmel", "rpi4_a72")
    ]
    extended_by = set(describe(library, "ros::publisher")["extended_by"])
    assert {
        "nd_usb_cam::imagePublisher",
        "nd_pos_to_cmd::cmdPublisher",
        "nd_ocv_color_tracking::pointPublisher",
    } <= extended_by
    assert "nd_usb_cam::usbcam_spinner" not in extended_by


def test_describe_packages_and_property_sets(library) -> None:
    pkg = describe(library, "nd_usb_cam")
    assert pkg["what"] == "package" and pkg["withs"][:2] == ["ros", "ros_data"]
    assert {c["name"] for c in pkg["components"]} >= {"usb_cam_nd", "usb_cam_nd.impl", "usb_cam_nd.rpi4_a72"}
    # a package wins over a classifier of the same name, which is named as well
    board = describe(library, "Odroid_XU4")
    assert board["what"] == "package" and board["see_also"] == ["Odroid_XU4::Odroid_XU4"]
    assert describe(library, "Odroid_XU4::Odroid_XU4")["category"] == "system"
    pset = describe(library, "ROS_Profiling")
    assert pset["what"] == "property set"
    raw = {p["name"]: p for p in pset["properties"]}["Raw_MIPS"]
    assert raw["type"] == "aadlreal units SEI::Processor_Speed_Units"
    assert raw["applies_to"] == ["thread", "thread group", "process", "system"]


def test_describe_unknown_and_ambiguous(library, tmp_path) -> None:
    with pytest.raises(ComponentNotFound) as caught:
        describe(library, "imagePublishr")
    assert "nd_usb_cam::imagePublisher" in caught.value.candidates
    assert "imagePublishr" in str(caught.value)
    with pytest.raises(ComponentNotFound) as caught:
        describe(library, "nd_usb_cam::no_such_thing")
    assert "not a package" in caught.value.message
    # the same name in two packages
    other = _csv(
        tmp_path,
        "package other_pkg\npublic\n  thread imagePublisher\n  end imagePublisher;\nend other_pkg;\n",
        "other_pkg.aadl",
    )
    workspace = read_library([other])
    with pytest.raises(ComponentNotFound) as caught:
        describe(workspace, "imagePublisher")
    assert caught.value.candidates == ["nd_usb_cam::imagePublisher", "other_pkg::imagePublisher"]
    assert "ambiguous" in caught.value.message
    assert describe(workspace, "other_pkg::imagePublisher")["file"] == str(other)


# =========================================================================== parsing measurements


def test_sample_parses() -> None:
    rows, errors, warnings = parse_measurements(SAMPLE.read_bytes(), str(SAMPLE))
    assert errors == [] and warnings == []
    assert [r.row for r in rows] == [1, 2, 3, 4]
    first = rows[0]
    assert (first.node, first.thread, first.pdm) == ("nd_usb_cam", "image_broadcaster", "le376_atom")
    assert (first.period_ns, first.cet_ns, first.data_size) == (33_333_000, 6_100_000, 921000)
    assert first.mips_budget == Decimal("500.00")
    assert rows[1].data_size is None
    assert first.processor == "Atom_D510::Atom_core"
    # lines count comments and the header
    lines = SAMPLE.read_text().splitlines()
    assert first.line > 2 and lines[first.line - 1].startswith("nd_usb_cam,image_broadcaster")
    assert lines[rows[3].line - 1].startswith("pos_to_cmd,cmd_publisher")


@pytest.mark.parametrize(
    ("raw", "ipc", "budget"),
    [("197", "1.40", "140.71"), ("256", "0.33", "775.76"), ("212.62", "2.14", "99.36"), ("1", "8", "0.13")],
)
def test_mips_budget_is_raw_over_ipc_rounded_to_two_decimals(raw, ipc, budget) -> None:
    rows, errors, _ = parse_measurements(f"{HEADER}\nn,t,b,c,1,1,{raw},{ipc},\n")
    assert errors == []
    assert rows[0].mips_budget == Decimal(budget)


# one bad cell per case: (row text, column named in the error, words of the message)
BAD_ROWS = [
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,abc,310,0.62,", "cet_us", "expected a number"),
    ("nd_usb_cam,image_broadcaster,le376,atom,-33333,6100,310,0.62,", "period_us", "must be positive"),
    ("nd_usb_cam,image_broadcaster,le376,atom,0,6100,310,0.62,", "period_us", "must be positive"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,0,310,0.62,", "cet_us", "must be positive"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,0,", "ipc", "IPC is zero"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,0.000,", "ipc", "IPC is zero"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,-1,", "ipc", "must be positive"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,-310,0.62,", "mips_raw", "must be positive"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,NaN,0.62,", "mips_raw", "expected a number"),
    ("nd_usb_cam,image_broadcaster,le376,atom,inf,6100,310,0.62,", "period_us", "expected a number"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,0.62,12.5", "data_size_bytes", "whole number"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,0.62,-1", "data_size_bytes", "negative"),
    ("nd_usb_cam,image_broadcaster,../etc,atom,33333,6100,310,0.62,", "board", "not a board name"),
    ("nd_usb_cam,image_broadcaster,le376,a/b,33333,6100,310,0.62,", "core", "not a core name"),
    ("nd_usb_cam,image_broadcaster,le376_,atom,33333,6100,310,0.62,", "board", "not a board name"),
    ("nd_usb_cam,,le376,atom,33333,6100,310,0.62,", "thread", "empty"),
    ("../../x,t,le376,atom,33333,6100,310,0.62,", "node", "is not a node"),
    ("nd_usb_cam,image_broadcaster,le376,atom,1e30,6100,310,0.62,", "period_us", "out of range"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,1e999999999,310,0.62,", "cet_us", "out of range"),
    (
        "nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,0.62,1e999999999",
        "data_size_bytes",
        "out of range",
    ),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,0.0001,310,0.62,", "cet_us", "below a nanosecond"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,1e9,", "ipc", "out of range"),
    ("nd_usb_cam,image_broadcaster,le376,atom,33333,6100,310,1e-999999,", "ipc", "out of range"),
    ("nd_usb_cam,image_broadcaster,le376,atom", "period_us", "no value for period_us, cet_us, mips_raw, ipc"),
]


@pytest.mark.parametrize(("row", "column", "words"), BAD_ROWS, ids=[f"{c}-{w}" for _, c, w in BAD_ROWS])
def test_bad_cell_names_row_and_column(row: str, column: str, words: str) -> None:
    errors = _errors(f"# a comment\n{HEADER}\n{row}\n")
    assert len(errors) == 1, [str(e) for e in errors]
    error = errors[0]
    assert error.location.file == "m.csv" and error.location.line == 3
    assert error.location.column == COLUMNS.index(column) + 1
    assert f"row 1, column {column}:" in error.message
    assert words in error.message
    assert f"m.csv:3:{COLUMNS.index(column) + 1}: row 1, column {column}" in str(error)


def test_every_error_of_a_file_is_reported() -> None:
    text = "\n".join(
        [
            HEADER,
            "a,t,b,c,1,x,1,1,",  # cet_us
            "a,t,b,c,1,1,1,1,",  # good
            "",
            "a,t,b,c,0,1,1,0,",  # period_us and ipc
            "a,t,b,c,1,1,1,1,1,1",  # extra field
        ]
    )
    rows, errors, _ = parse_measurements(text, "m.csv")
    assert len(rows) == 1
    located = [(e.location.line, e.location.column) for e in errors]
    assert located == [(2, 6), (5, 5), (5, 8), (6, 10)]
    assert "row 3, column period_us" in errors[1].message and "row 4" in errors[3].message


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("node,thread,board,core,period_us,mips_raw,ipc,data_size_bytes\nx\n", 1, "missing column cet_us"),
        ("", 1, "the file is empty"),
        ("# only a comment\n\n", 1, "no header line"),
        (f"{HEADER}\n", 1, "no measurement rows"),
        (f"{HEADER},node\n", 1, "named twice"),
        (f"{HEADER},,x\n", 1, "has no name"),
        (f'{HEADER}\n"a,t,b,c,1,1,1,1,\n', 2, "malformed CSV"),
        (f'{HEADER}\n"a"b,t,b,c,1,1,1,1,\n', 2, "malformed CSV"),
        (f"{HEADER}\n" + "x" * 200_000 + "\n", 2, "malformed CSV"),
    ],
    ids=[
        "missing-column",
        "empty",
        "comments-only",
        "no-rows",
        "twice",
        "unnamed",
        "quote",
        "bad-quote",
        "huge-field",
    ],
)
def test_bad_files_are_located(text: str, line: int, words: str) -> None:
    errors = _errors(text)
    assert errors, "expected an error"
    assert any(words in e.message and e.location.line == line for e in errors), [str(e) for e in errors]


def test_hostile_bytes_are_located() -> None:
    _, errors, _ = parse_measurements(f"{HEADER}\nabc\xff".encode("latin-1"), "m.csv")
    assert "not UTF-8" in errors[0].message and errors[0].location.line == 2
    _, errors, _ = parse_measurements(f"{HEADER}\n\na,\x00".encode(), "m.csv")
    assert "NUL" in errors[0].message and errors[0].location.line == 3
    _, errors, _ = parse_measurements(b"x" * (16 * 1024 * 1024 + 1), "m.csv")
    assert "larger than" in errors[0].message
    rows, errors, _ = parse_measurements(f"{HEADER}\n" + "a,t,b,c,1,1,1,1,\n" * 12, "m.csv", max_rows=10)
    assert "more than 10 rows" in errors[0].message and errors[0].location.line == 12 and len(rows) == 10


def test_unknown_columns_warn_and_optional_values_may_be_left_off() -> None:
    rows, errors, warnings = parse_measurements(f"{HEADER},comment\na,t,b,c,1,1,1,1\n", "m.csv")
    assert errors == [] and rows[0].data_size is None
    assert len(warnings) == 1 and "comment" in warnings[0].message and warnings[0].location.column == 10


def test_utf8_bom_crlf_quotes_and_spaces() -> None:
    text = (
        "\ufeff"
        + HEADER.upper()
        + "\r\n"
        + ' nd_usb_cam , "image_broadcaster", le376 ,atom,33333,6100.25,310,0.62, \r\n'
    )
    rows, errors, _ = parse_measurements(text.encode("utf-8"), "m.csv")
    assert errors == []
    assert (rows[0].node, rows[0].thread, rows[0].board, rows[0].cet_ns) == (
        "nd_usb_cam",
        "image_broadcaster",
        "le376",
        6_100_250,
    )


# =========================================================================== add-profile: the sample


def test_sample_writes_one_package_per_node(sample_out) -> None:
    out, result, warnings = sample_out
    assert warnings == []
    assert sorted(p.name for p in out.iterdir()) == [
        "nd_ocv_color_tracking_profiles.aadl",
        "nd_pos_to_cmd_profiles.aadl",
        "nd_usb_cam_profiles.aadl",
    ]
    assert result.packages == [
        "nd_ocv_color_tracking_profiles",
        "nd_pos_to_cmd_profiles",
        "nd_usb_cam_profiles",
    ]
    text = (out / "nd_usb_cam_profiles.aadl").read_text()
    # the paper's style
    for line in (
        "  with nd_usb_cam, SEI, ROS_Profiling, Atom_D510;",
        "  usb_cam_nd renames process nd_usb_cam::usb_cam_nd;",
        "  process implementation usb_cam_nd.le376_atom extends nd_usb_cam::usb_cam_nd.impl",
        "      image_broadcaster: refined to thread imagePublisher.le376_atom;",
        "      SEI::MIPSBudget => 500.0 MIPS;",
        "      ROS_Profiling::Raw_MIPS => 310.0 MIPS;",
        "      ROS_Profiling::IPC => 0.62;",
        "      Reference_Processor => classifier (Atom_D510::Atom_core);",
        "  thread implementation imagePublisher.le376_atom extends nd_usb_cam::imagePublisher.impl",
        "      Compute_Execution_Time => 6100 us .. 6100 us;",
    ):
        assert line in text.splitlines(), line
    # the message sizes and periods equal the PIM's: nothing is repeated
    assert "Data_Size" not in text and "Period" not in text
    assert [i.process for i in result.implementations] == sorted({row[0] for row in SAMPLE_ROWS})


def test_sample_packages_read_without_warnings(sample_out, caplog) -> None:
    out, _, _ = sample_out
    found: list = []
    with caplog.at_level(logging.WARNING, logger="rosaadl"):
        workspace = read_files([out], warnings=found)
    assert [str(d) for d in found] == []
    assert model.find_unit(workspace, "nd_usb_cam_profiles") is not None


def test_sample_instantiates_bound_and_carries_the_values(sample_out, tmp_path) -> None:
    out, _, _ = sample_out
    system = _csv(tmp_path, SYSTEM, "profile_test_sys.aadl")
    workspace = read_files([out, system])
    diagnostics: list = []
    root = instantiate(workspace, "profile_test_sys::app.impl", diagnostics=diagnostics)
    assert [str(d) for d in diagnostics if d.severity == "warning"] == []
    lookup = PropertyLookup(workspace)
    paths = {
        "nd_usb_cam_profiles::usb_cam_nd.le376_atom": "cam",
        "nd_ocv_color_tracking_profiles::ocv_color_tracking_nd.le376_atom": "trk",
        "nd_pos_to_cmd_profiles::pos_to_cmd_nd.le376_atom": "cmd",
    }
    for process, thread, cet, raw, ipc in SAMPLE_ROWS:
        node = model.find_instance(root, f"{root.name}.{paths[process]}")
        assert node.classifier == process
        budget = lookup.python_value(node, "SEI::MIPSBudget")
        assert budget.to("MIPS") == pytest.approx(round(raw / ipc, 2))
        assert budget.unit == "MIPS"
        assert lookup.python_value(node, "ROS_Profiling::Raw_MIPS") == Quantity(float(raw), "MIPS")
        assert lookup.python_value(node, "ROS_Profiling::IPC") == pytest.approx(ipc)
        assert str(lookup.python_value(node, "Reference_Processor")) == "Atom_D510::Atom_core"
        bound = lookup.python_value(node, "Actual_Processor_Binding")
        assert model.instance_path(bound[0]).endswith(
            "board.Atom_SOC." + ("proc2" if "pos" in process else "proc1")
        )
        work = model.find_instance(root, f"{root.name}.{paths[process]}.{thread}")
        span = lookup.python_value(work, "Compute_Execution_Time")
        assert isinstance(span, Range) and (_us(span.minimum), _us(span.maximum)) == (cet, cet)
        assert span.minimum.to("ms") == pytest.approx(cet / 1000)
        assert work.classifier.endswith(".le376_atom")
        # the PIM's Period and the message size come through unchanged
        period = 100000 if "pos_to_cmd" in process else 33333
        assert _us(lookup.python_value(work, "Period")) == period
    image = model.find_instance(root, f"{root.name}.cam.image_broadcaster.pub_msg")
    assert lookup.python_value(image, "Data_Size").to("Bytes") == 921000
    # CPU load = CET / Period, as the analyses compute it
    tracker = model.find_instance(root, f"{root.name}.trk.image_tracker")
    load = _us(lookup.python_value(tracker, "Compute_Execution_Time").maximum) / _us(
        lookup.python_value(tracker, "Period")
    )
    assert load == pytest.approx(29500 / 33333)


def test_same_input_gives_identical_files(sample_out, tmp_path) -> None:
    out, _, _ = sample_out
    again = tmp_path / "again"
    add_profiles(SAMPLE, again)
    for path in out.iterdir():
        assert (again / path.name).read_bytes() == path.read_bytes()


# =========================================================================== add-profile: the paper's Table 2


def test_table2_reproduces_the_library_pdms(tmp_path) -> None:
    out = tmp_path / "out"
    warnings: list = []
    result = add_profiles(_csv(tmp_path, TABLE2_CSV), out, warnings=warnings)
    # each PDM exists in the library already: said once per PDM, and nothing else
    assert len(warnings) == 12 and all("already exists" in w.message for w in warnings)
    workspace = read_files([out])
    lookup = PropertyLookup(workspace)
    for impl in result.implementations:
        mine = model.find_classifier(workspace, impl.process)
        theirs = model.find_classifier(workspace, impl.process.replace("_profiles::", "::"))
        assert mine is not None and theirs is not None
        for prop in ("ROS_Profiling::Raw_MIPS", "ROS_Profiling::IPC", "Reference_Processor", "Period"):
            assert lookup.python_value(mine, prop) == lookup.python_value(theirs, prop), (impl.process, prop)
        # the paper rounds MIPSBudget from unrounded IPC figures: equal within the IPC's rounding
        raw = lookup.python_value(mine, "ROS_Profiling::Raw_MIPS").to("MIPS")
        ipc = lookup.python_value(mine, "ROS_Profiling::IPC")
        paper = lookup.python_value(theirs, "SEI::MIPSBudget").to("MIPS")
        low, high = raw / (ipc + 0.005), raw / (ipc - 0.005)
        assert low - 1 <= paper <= high + 1, impl.process
        assert lookup.python_value(mine, "SEI::MIPSBudget").to("MIPS") == round(raw / ipc + 1e-9, 2)
        thread = model.find_classifier(workspace, impl.threads[0])
        paper_thread = model.find_classifier(workspace, impl.threads[0].replace("_profiles::", "::"))
        assert lookup.python_value(thread, "Compute_Execution_Time") == lookup.python_value(
            paper_thread, "Compute_Execution_Time"
        )


# =========================================================================== add-profile: variants


def test_node_and_thread_spellings(tmp_path) -> None:
    text = f"""{HEADER}
nd_usb_cam::usb_cam_nd,imagePublisher,b1,c1,33333,1,1,1,
usb_cam_nd,image_broadcaster,b2,c2,33333,2,1,1,
usb_cam,IMAGE_BROADCASTER,b3,c3,33333,3,1,1,
ND_USB_CAM,usbSpinner,b4,c4,33333,4,1,1,
"""
    warnings: list = []
    result = add_profiles(_csv(tmp_path, text), tmp_path / "out", warnings=warnings)
    assert [i.process for i in result.implementations] == [
        f"nd_usb_cam_profiles::usb_cam_nd.b{n}_c{n}" for n in range(1, 5)
    ]
    # no library PDM is named b1_c1...: no Reference_Processor, said once per PDM
    assert len(warnings) == 4 and all("no Reference_Processor" in w.message for w in warnings)
    assert "Reference_Processor" not in (tmp_path / "out" / "nd_usb_cam_profiles.aadl").read_text()


def test_a_new_node_from_the_inputs(tmp_path) -> None:
    talker = _csv(tmp_path, TALKER, "nd_talker.aadl")
    text = f"""{HEADER},processor
talker,chatter,rpi4,a72,100000,120.5,12,0.5,300,BCM2711::Cortex_A72
talker_nd,status,rpi4,a72,50000,80,12,0.5,,BCM2711::Cortex_A72
"""
    warnings: list = []
    out = tmp_path / "out"
    result = add_profiles(_csv(tmp_path, text), out, inputs=[talker], warnings=warnings)
    assert result.packages == ["nd_talker_profiles"]
    assert [w for w in warnings if "Period" in w.message][0].location.line == 3
    written = (out / "nd_talker_profiles.aadl").read_text()
    assert "Compute_Execution_Time => 120500 ns .. 120500 ns;" in written
    assert "Data_Size => 300 Bytes applies to pub_msg;" in written
    assert "Period => 50000 us;" in written and "SEI::MIPSBudget => 24.0 MIPS;" in written
    workspace = read_files([talker, out])
    root = instantiate(workspace, "nd_talker_profiles::talker_nd.rpi4_a72")
    lookup = PropertyLookup(workspace)
    chatter = model.find_instance(root, f"{root.name}.chatter")
    assert lookup.python_value(chatter, "Compute_Execution_Time").maximum.to("us") == pytest.approx(120.5)
    port = model.find_instance(root, f"{root.name}.chatter.pub_msg")
    assert lookup.python_value(port, "Data_Size") == Quantity(300, "Bytes")
    status = model.find_instance(root, f"{root.name}.status")
    assert lookup.python_value(status, "Period").to("ms") == 50
    assert str(lookup.python_value(root, "Reference_Processor")) == "BCM2711::Cortex_A72"


def test_profiles_are_added_to_earlier_ones(sample_out, tmp_path) -> None:
    out = tmp_path / "out"
    add_profiles(SAMPLE, out)
    first = (out / "nd_usb_cam_profiles.aadl").read_text()
    # a new board for usb_cam: the earlier PDMs stay
    more = f"{HEADER}\nusb_cam,image_broadcaster,xu4,a7,33333,18000,256,0.33,\n"
    warnings: list = []
    result = add_profiles(_csv(tmp_path, more), out, warnings=warnings)
    assert result.packages == ["nd_usb_cam_profiles"]
    text = (out / "nd_usb_cam_profiles.aadl").read_text()
    assert "usb_cam_nd.le376_atom" in text and "usb_cam_nd.xu4_a7" in text
    assert "Reference_Processor => classifier (Exynos_5422::ARM_A7);" in text
    # measuring a PDM again replaces it whole (its other threads included), with a warning
    again = f"{HEADER}\nusb_cam,image_broadcaster,le376,atom,33333,7000,300,0.6,\n"
    warnings = []
    add_profiles(_csv(tmp_path, again, "again.csv"), out, warnings=warnings)
    text = (out / "nd_usb_cam_profiles.aadl").read_text()
    assert "7000 us .. 7000 us" in text and "6100 us" not in text
    assert "usbcam_spinner.le376_atom" not in text and "usbSpinner: refined" not in text
    assert "usb_cam_nd.xu4_a7" in text
    assert any("replaced" in w.message for w in warnings)
    read_files([out])
    assert first != text


# =========================================================================== add-profile: errors


def _assert_nothing_written(out: Path) -> None:
    assert not out.exists() or list(out.iterdir()) == []


@pytest.mark.parametrize(
    ("rows", "line", "column", "words"),
    [
        ("nd_nothing,t,b,c,1,1,1,1,", 2, "node", "unknown node 'nd_nothing'"),
        ("usb_cam,no_thread,b,c,1,1,1,1,", 2, "thread", "unknown thread 'no_thread'"),
        (
            "usb_cam,image_broadcaster,b,c,1,1,1,1,\nnd_usb_cam,imagePublisher,b,c,1,1,1,1,",
            3,
            "node",
            "duplicate measurement",
        ),
        (
            "usb_cam,image_broadcaster,b,c,1,1,1,1,\nusb_cam,usbSpinner,b,c,1,1,2,1,",
            3,
            "mips_raw",
            "differs from row 1",
        ),
        (
            "usb_cam,image_broadcaster,b,c,1,1,1,1,\nusb_cam,usbSpinner,b,c,1,1,1,3,",
            3,
            "ipc",
            "differs from row 1",
        ),
        (
            "usb_cam,image_broadcaster,b,c,1,1,1,1,,Exynos_5422::A15_cluster",
            2,
            "processor",
            "not a processor",
        ),
        ("usb_cam,image_broadcaster,b,c,1,1,1,1,,No::Such", 2, "processor", "not found"),
        ("ros::node,x,b,c,1,1,1,1,", 2, "thread", "has the threads none"),
    ],
    ids=[
        "node",
        "thread",
        "duplicate",
        "mips-differ",
        "ipc-differ",
        "not-processor",
        "no-processor",
        "no-threads",
    ],
)
def test_rows_that_do_not_match_the_library(tmp_path, rows, line, column, words) -> None:
    out = tmp_path / "out"
    with pytest.raises(MeasurementError) as caught:
        add_profiles(_csv(tmp_path, f"{HEADER},processor\n{rows}\n"), out)
    errors = caught.value.errors
    assert len(errors) == 1, [str(e) for e in errors]
    error = errors[0]
    assert error.location.line == line and words in error.message, str(error)
    assert f"column {column}" in error.message or f"columns {column}" in error.message
    assert error.location.file == str(tmp_path / "m.csv")
    _assert_nothing_written(out)


def test_ambiguous_node_and_data_port(tmp_path) -> None:
    talker = _csv(tmp_path, TALKER, "nd_talker.aadl")
    twin = _csv(tmp_path, TALKER.replace("nd_talker", "nd_talker2"), "nd_talker2.aadl")
    text = f"{HEADER}\ntalker_nd,chatter,b,c,1,1,1,1,\nnd_talker::talker_nd,status,b,c,1,1,1,1,8\n"
    with pytest.raises(MeasurementError) as caught:
        add_profiles(_csv(tmp_path, text), tmp_path / "out", inputs=[talker, twin])
    first, second = caught.value.errors
    assert "names several nodes" in first.message and "nd_talker2::talker_nd" in first.message
    assert "column data_size_bytes" in second.message and "2 outgoing data ports (a, b)" in second.message
    assert "2 problems" in str(caught.value)
    _assert_nothing_written(tmp_path / "out")


def test_all_errors_together_and_nothing_written(tmp_path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("x")
    text = (
        f"{HEADER}\nusb_cam,image_broadcaster,b,c,1,x,1,1,\nnd_nothing,t,b,c,1,1,1,1,\n"
        "usb_cam,nope,b,c,1,1,1,0,\n"
    )
    with pytest.raises(MeasurementError) as caught:
        add_profiles(_csv(tmp_path, text), out)
    located = [(e.location.line, e.location.column) for e in caught.value.errors]
    assert located == [(2, 6), (3, 1), (4, 8)]
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]


def test_an_unrelated_file_in_the_output_is_not_replaced(tmp_path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "nd_usb_cam_profiles.aadl").write_text("package something_else\npublic\nend something_else;\n")
    with pytest.raises(RosaadlError) as caught:
        add_profiles(SAMPLE, out)
    assert "something_else" in str(caught.value)
    assert (out / "nd_usb_cam_profiles.aadl").read_text().startswith("package something_else")
    assert sorted(p.name for p in out.iterdir()) == ["nd_usb_cam_profiles.aadl"]


def test_output_that_is_a_file(tmp_path) -> None:
    target = tmp_path / "file"
    target.write_text("x")
    with pytest.raises(MeasurementError, match="not a folder"):
        add_profiles(SAMPLE, target)
    assert target.read_text() == "x"


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet=st.sampled_from(list('abc019.,-"\n\r #_:e') + ["\x00", "é", "\ufeff"]), max_size=300))
def test_any_text_gives_rows_or_located_errors(text: str) -> None:
    rows, errors, warnings = parse_measurements(HEADER + "\n" + text, "m.csv")
    for error in errors:
        assert isinstance(error, MeasurementError)
        assert error.location.file == "m.csv" and error.location.line is not None
    for row in rows:
        assert row.period_ns > 0 and row.cet_ns > 0 and row.ipc > 0 and row.mips_raw > 0


def test_every_library_name_is_described(library) -> None:
    import json

    count = 0
    for unit in library.units:
        info = describe(library, unit.name)
        assert info["name"] == unit.name
        json.dumps(info)
        for classifier in getattr(unit, "classifiers", ()):
            qualified = f"{unit.name}::{classifier.name}"
            info = describe(library, qualified)
            assert info["name"] == qualified and info["what"] == "classifier"
            json.dumps(info)
            count += 1
    assert count == sum(len(getattr(u, "classifiers", ())) for u in library.units) > 150


def test_build_profiles_in_memory(library) -> None:
    from rosaadl.exporters.aadl_text import write_unit
    from rosaadl.workflow.library_profiles import build_profiles

    rows, errors, _ = parse_measurements(SAMPLE.read_bytes(), str(SAMPLE))
    assert errors == []
    workspace = library
    units, implementations, problems, warnings = build_profiles(workspace, rows)
    assert problems == [] and warnings == []
    assert [u.name for u in units] == [
        "nd_ocv_color_tracking_profiles",
        "nd_pos_to_cmd_profiles",
        "nd_usb_cam_profiles",
    ]
    assert "usb_cam_nd.le376_atom" in write_unit(units[2])
    assert [i.rows for i in implementations] == [[3], [4], [1, 2]]
    bad = [*rows, rows[0]]
    units, _, problems, _ = build_profiles(workspace, bad)
    assert units == [] and len(problems) == 1 and "columns node, thread, board, core" in problems[0].message

"""``rosaadl library list | show | add-profile``: the JSON documents, the text, the exit codes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from rosaadl.cli import main
from rosaadl.importers.aadl_text import read_files

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "examples" / "profiles" / "sample_measurements.csv"
HEADER = "node,thread,board,core,period_us,cet_us,mips_raw,ipc,data_size_bytes"


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture(scope="module")
def library():
    return read_files([], include_library=True)


# --------------------------------------------------------------------------- list


@pytest.mark.parametrize("where", ["verb", "global"])
def test_list_json_has_every_package_with_its_components(library, capsys, where) -> None:
    args = (
        ["library", "list", "--format", "json"]
        if where == "verb"
        else ["--format", "json", "library", "list"]
    )
    code, out, err = run(args, capsys)
    assert code == 0, err
    doc = json.loads(out)
    assert doc["ok"] is True and doc["errors"] == [] and doc["warnings"] == []
    packages = {p["name"]: p for p in doc["packages"]}
    assert set(packages) == {unit.name for unit in library.units}
    for unit in library.units:
        entry = packages[unit.name]
        assert entry["file"].endswith(".aadl") and entry["library"] is True
        if unit.eClass.name == "PropertySet":
            assert entry["kind"] == "property set" and entry["components"] == []
            continue
        assert entry["kind"] == "package"
        assert [c["name"] for c in entry["components"]] == [c.name for c in unit.classifiers]
        for component in entry["components"]:
            assert set(component) == {"name", "category", "kind", "extends"}
            assert component["kind"] in ("type", "implementation")
    cam = {c["name"]: c for c in packages["nd_usb_cam"]["components"]}
    assert cam["usb_cam_nd"] == {
        "name": "usb_cam_nd",
        "category": "process",
        "kind": "type",
        "extends": "ros::node",
    }
    assert cam["usb_cam_nd.xavier_carmel"]["extends"] == "nd_usb_cam::usb_cam_nd.impl"
    assert {c["category"] for c in packages["Exynos_5422"]["components"]} >= {"processor", "system"}
    # the paper's package tree is all there
    for name in (
        "ros",
        "ros_data",
        "nd_usb_cam",
        "nd_pos_to_cmd",
        "nd_ocv_color_tracking",
        "sys_rover",
        "leo_rover",
    ):
        assert packages[name]["components"], name


def test_list_text(capsys) -> None:
    code, out, err = run(["library", "list"], capsys)
    assert code == 0, err
    lines = out.splitlines()
    assert "nd_usb_cam (package, nodes/nd_usb_cam.aadl)" in lines
    assert "  process implementation usb_cam_nd.xu4_a15 extends nd_usb_cam::usb_cam_nd.impl" in lines
    assert any(
        line.startswith("ROS_Profiling (property set, properties/ROS_Profiling.aadl)") for line in lines
    )
    assert "components" in err  # the count, on stderr


def test_list_with_an_unreadable_input_exits_1(tmp_path, capsys) -> None:
    bad = tmp_path / "bad.aadl"
    bad.write_text("package bad public system s end t; end bad;")
    code, out, _ = run(["library", "list", str(bad), "--format", "json"], capsys)
    assert code == 1
    doc = json.loads(out)
    assert doc["ok"] is False and doc["errors"][0]["file"] == str(bad) and doc["errors"][0]["line"] == 1


# --------------------------------------------------------------------------- show


def test_show_a_pdm_text(capsys) -> None:
    code, out, err = run(["library", "show", "usb_cam_nd.xu4_a15"], capsys)
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0].startswith(
        "nd_usb_cam::usb_cam_nd.xu4_a15: process implementation (library: nodes/nd_usb_cam.aadl:"
    )
    assert "  extends: nd_usb_cam::usb_cam_nd.impl -> ros::node.impl" in lines
    assert (
        "    rgb_image_raw_out: out event data port ros_data::Image.rgb  (from nd_usb_cam::usb_cam_nd)"
        in lines
    )
    assert "    image_broadcaster: refined to thread nd_usb_cam::imagePublisher.xu4_a15" in lines
    assert "    SEI::MIPSBudget => 141.0 MIPS" in lines
    assert "    Timing_Properties::Period => 33333 us  (from nd_usb_cam::usb_cam_nd.impl)" in lines


def test_show_json(capsys) -> None:
    code, out, err = run(
        ["library", "show", "nd_pos_to_cmd::cmdPublisher.rpi4_a72", "--format", "json"], capsys
    )
    assert code == 0, err
    doc = json.loads(out)
    component = doc["component"]
    assert component["category"] == "thread" and component["kind"] == "implementation"
    assert component["extends"] == ["nd_pos_to_cmd::cmdPublisher.impl"]
    cet = {p["property"]: p for p in component["properties"]}["Timing_Properties::Compute_Execution_Time"]
    assert cet["minimum"] == {"number": 104, "unit": "us"}
    features = {f["name"]: f for f in component["features"]}
    assert (
        features["pub_msg"]["classifier"] == "ros_data::Twist" and features["pub_msg"]["direction"] == "out"
    )
    code, out, _ = run(["--format", "json", "library", "show", "ros"], capsys)
    assert code == 0 and json.loads(out)["package"]["what"] == "package"


@pytest.mark.parametrize(
    ("name", "words", "candidate"),
    [
        ("imagePublishr", "not a package", "nd_usb_cam::imagePublisher"),
        ("Exynos_5422::ARM_A16", "not a package", "Exynos_5422::ARM_A15"),
    ],
)
def test_show_unknown_exits_1_with_candidates(capsys, name, words, candidate) -> None:
    code, out, err = run(["library", "show", name, "--format", "json"], capsys)
    assert code == 1
    doc = json.loads(out)
    assert doc["ok"] is False and words in doc["errors"][0]["message"]
    assert candidate in doc["candidates"] and candidate in doc["errors"][0]["candidates"]
    code, out, err = run(["library", "show", name], capsys)
    assert code == 1 and candidate in err and out == ""


def test_show_ambiguous_exits_1(tmp_path, capsys) -> None:
    other = tmp_path / "other_pkg.aadl"
    other.write_text(
        "package other_pkg\npublic\n  thread cmdPublisher\n  end cmdPublisher;\nend other_pkg;\n"
    )
    code, out, _ = run(["library", "show", "cmdPublisher", str(other), "--format", "json"], capsys)
    assert code == 1
    doc = json.loads(out)
    assert doc["candidates"] == ["nd_pos_to_cmd::cmdPublisher", "other_pkg::cmdPublisher"]
    assert "ambiguous" in doc["errors"][0]["message"]


# --------------------------------------------------------------------------- add-profile


def test_add_profile_sample(tmp_path, capsys) -> None:
    out = tmp_path / "profiles"
    code, stdout, err = run(
        ["library", "add-profile", str(SAMPLE), "-o", str(out), "--format", "json"], capsys
    )
    assert code == 0, err
    doc = json.loads(stdout)
    assert doc["ok"] is True and doc["warnings"] == []
    assert doc["input"] == str(SAMPLE) and doc["output"] == str(out)
    assert doc["packages"] == [
        "nd_ocv_color_tracking_profiles",
        "nd_pos_to_cmd_profiles",
        "nd_usb_cam_profiles",
    ]
    assert [Path(f).name for f in doc["files"]] == [f"{p}.aadl" for p in doc["packages"]]
    cam = [i for i in doc["implementations"] if i["node"] == "nd_usb_cam::usb_cam_nd"][0]
    assert cam == {
        "node": "nd_usb_cam::usb_cam_nd",
        "process": "nd_usb_cam_profiles::usb_cam_nd.le376_atom",
        "threads": [
            "nd_usb_cam_profiles::imagePublisher.le376_atom",
            "nd_usb_cam_profiles::usbcam_spinner.le376_atom",
        ],
        "rows": [1, 2],
        "mips_budget": 500.0,
        "reference_processor": "Atom_D510::Atom_core",
    }
    # the new packages are listed and shown with the library
    code, stdout, _ = run(["library", "list", str(out), "--format", "json"], capsys)
    packages = {p["name"]: p for p in json.loads(stdout)["packages"]}
    assert packages["nd_usb_cam_profiles"]["library"] is False
    assert [c["name"] for c in packages["nd_usb_cam_profiles"]["components"]] == [
        "usb_cam_nd.le376_atom",
        "imagePublisher.le376_atom",
        "usbcam_spinner.le376_atom",
    ]
    code, stdout, err = run(
        ["library", "show", "nd_usb_cam_profiles::imagePublisher.le376_atom", str(out)], capsys
    )
    assert code == 0, err
    assert "    Timing_Properties::Compute_Execution_Time => 6100 us .. 6100 us" in stdout.splitlines()
    assert "  extends: nd_usb_cam::imagePublisher.impl" in stdout.splitlines()
    # text output
    code, stdout, err = run(["library", "add-profile", str(SAMPLE), "-o", str(tmp_path / "t")], capsys)
    assert code == 0, err
    assert f"wrote {tmp_path / 't' / 'nd_usb_cam_profiles.aadl'}" in stdout.splitlines()


def test_add_profile_malformed_names_row_and_column(tmp_path, capsys) -> None:
    csv = tmp_path / "bad.csv"
    csv.write_text(
        f"{HEADER}\n"
        "usb_cam,image_broadcaster,xu4,a15,33333,fast,197,1.40,921000\n"
        "usb_cam,image_broadcaster,le376,atom,-1,6100,310,0,\n"
        "nd_nothing,x,le376,atom,33333,6100,310,0.62,\n"
    )
    out = tmp_path / "out"
    code, stdout, stderr = run(
        ["library", "add-profile", str(csv), "-o", str(out), "--format", "json"], capsys
    )
    assert code == 1
    doc = json.loads(stdout)
    assert doc["ok"] is False and doc["files"] == []
    located = [(e["file"], e["line"], e["column"]) for e in doc["errors"]]
    assert located == [(str(csv), 2, 6), (str(csv), 3, 5), (str(csv), 3, 8), (str(csv), 4, 1)]
    messages = [e["message"] for e in doc["errors"]]
    assert messages[0].startswith("row 1, column cet_us:")
    assert messages[1].startswith("row 2, column period_us:") and "positive" in messages[1]
    assert messages[2].startswith("row 2, column ipc:") and "IPC is zero" in messages[2]
    assert messages[3].startswith("row 3, column node:") and "unknown node" in messages[3]
    assert not out.exists()
    code, stdout, stderr = run(["library", "add-profile", str(csv), "-o", str(out)], capsys)
    assert code == 1 and stdout == ""
    assert f"error: {csv}:2:6: row 1, column cet_us:" in stderr
    assert f"error: {csv}:4:1: row 3, column node:" in stderr


def test_add_profile_missing_column_and_missing_file(tmp_path, capsys) -> None:
    csv = tmp_path / "m.csv"
    csv.write_text("node,thread,board,core,period_us,mips_raw,ipc,data_size_bytes\nx,y,b,c,1,1,1,\n")
    code, _, stderr = run(["library", "add-profile", str(csv), "-o", str(tmp_path / "o")], capsys)
    assert code == 1 and f"{csv}:1: header: missing column cet_us" in stderr
    code, _, stderr = run(
        ["library", "add-profile", str(tmp_path / "none.csv"), "-o", str(tmp_path / "o")], capsys
    )
    assert code == 1 and "cannot read" in stderr
    assert not (tmp_path / "o").exists()


def test_add_profile_usage_errors_exit_2(capsys) -> None:
    code, _, err = run(["library", "add-profile", str(SAMPLE)], capsys)
    assert code == 2 and "--output" in err
    code, _, err = run(["library", "no-such-thing"], capsys)
    assert code == 2
    code, _, err = run(["library", "list", "--format", "yaml"], capsys)
    assert code == 2

"""``rosaadl library add-profile measurements.json``: a measured run becomes PDMs of its nodes."""

from __future__ import annotations

import json

import pytest

from rosaadl.cli import main
from rosaadl.errors import ParseError, RosaadlError
from rosaadl.model import find_instance
from rosaadl.properties import property_value
from rosaadl.transforms.instantiate import instantiate
from rosaadl.workflow.library_add_profile import add_profiles
from rosaadl.workflow.library_catalog import read_library
from tests.measurements_sample import tracking_measurements, tracking_measurements_text


def _run_file(tmp_path, **run):
    document = tracking_measurements()
    document["run"].update(run)
    target = tmp_path / "measurements.json"
    target.write_text(tracking_measurements_text(document))
    return target


def test_a_run_becomes_pdms_for_its_board_and_core(tmp_path) -> None:
    out = tmp_path / "profiles"
    result = add_profiles(_run_file(tmp_path, board="xu4", core="a15"), out)
    assert sorted(p.name for p in result.files) == ["nd_pos_to_cmd_profiles.aadl", "nd_usb_cam_profiles.aadl"]
    usb = (out / "nd_usb_cam_profiles.aadl").read_text()
    assert "process implementation usb_cam_nd.xu4_a15 extends nd_usb_cam::usb_cam_nd.impl" in usb
    # the mean CPU time 2330 us plus the middleware's share: 2330 × 8.1 / (2330 / 33340 × 100)
    assert "Compute_Execution_Time => 2700540 ns .. 2700540 ns;" in usb
    assert "Data_Size => 921600 Bytes applies to pub_msg;" in usb
    assert "SEI::MIPSBudget =>" not in usb and "Raw_MIPS =>" not in usb and "Period =>" not in usb
    assert "Reference_Processor => classifier (Exynos_5422::" in usb
    assert [impl.mips_budget for impl in result.implementations] == [None, None]


def test_the_profiled_node_predicts_the_measured_process_load(tmp_path) -> None:
    out = tmp_path / "profiles"
    add_profiles(_run_file(tmp_path, board="host", core="x86"), out)
    instance = instantiate(read_library([out]), "nd_usb_cam_profiles::usb_cam_nd.host_x86")
    thread = find_instance(instance, "image_broadcaster")
    cet = property_value(thread, "Compute_Execution_Time").maximum.to("us")
    period = property_value(thread, "Period").to("us")
    # the node's measured CPU load (8.1 % of a core at a mean period of 33.34 ms) again
    assert cet / period * 100 == pytest.approx(8.1 * 33340 / period, rel=1e-6)


def test_a_run_without_board_and_core_is_refused_at_run(tmp_path) -> None:
    document = tracking_measurements()
    target = tmp_path / "measurements.json"
    target.write_text(tracking_measurements_text(document))
    out = tmp_path / "profiles"
    with pytest.raises(RosaadlError) as caught:
        add_profiles(target, out)
    assert any(e.location.path == "$.run.board" and e.location.line for e in caught.value.errors)
    assert not out.exists()


def test_a_truncated_run_is_refused_with_its_line(tmp_path, capsys) -> None:
    target = _run_file(tmp_path, board="xu4", core="a15")
    text = target.read_text()
    target.write_text(text[:400])
    with pytest.raises(ParseError) as caught:
        add_profiles(target, tmp_path / "profiles")
    assert caught.value.location.line is not None
    code = main(["--format", "json", "library", "add-profile", str(target), "-o", str(tmp_path / "p")])
    document = json.loads(capsys.readouterr().out)
    assert code == 1 and document["errors"][0]["file"] == str(target)
    assert not (tmp_path / "p").exists()

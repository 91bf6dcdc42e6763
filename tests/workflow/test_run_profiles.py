"""``rosaadl run`` names the profile of each measured process (``processes[].profile``, and
``run.board``/``run.core`` when one), so that ``library add-profile`` needs no hand edit; and the
CPU time of a process counted to the nanosecond."""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import pytest

import rosaadl.library
from rosaadl.errors import RosaadlError
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.measurements import parse_measurements
from rosaadl.transforms.instantiate import instantiate
from rosaadl.workflow.library_add_profile import add_profiles
from rosaadl.workflow.run.measure import cpu_seconds_between, measurements_document, thread_cpu_ns
from rosaadl.workflow.run.profiles import host_profile, model_profile, run_profile
from tests.measurements_sample import (
    tracking_measurements,
    write_tracking_measurements,
)
from tests.workflow.test_run_measure import NODES, TOPICS

SYSTEMS = Path(rosaadl.library.__file__).parent / "systems"
ROOT = "sys_tracking::tracking.impl"


@pytest.fixture(scope="module")
def tracking():
    return instantiate(read_files([SYSTEMS]), ROOT)


def test_an_emulated_process_is_profiled_as_the_pdm_of_the_core_it_is_bound_to(tracking) -> None:
    assert model_profile(tracking, "rem_trk_sw.usbcam") == ("xu4", "a15")
    assert model_profile(tracking, "rem_trk_sw.tracker") == ("xu4", "a15")
    assert model_profile(tracking, "rem_trk_sw.poscmd") == ("xu4", "a7")  # bound to a LITTLE core
    assert model_profile(tracking, "rem_trk_sw") is None  # not a PDM
    assert model_profile(tracking, "no.such.process") is None


def test_user_code_is_profiled_as_this_machine() -> None:
    assert run_profile(["xu4", "a15"], emulate=True) == ("xu4", "a15")
    assert run_profile(["xu4", "a15"], emulate=False) == host_profile()
    assert run_profile(None, emulate=True) == host_profile()
    board, core = host_profile()
    assert board == "host" and core and core.replace("_", "").isalnum()


def _document(profiles):
    return measurements_document(
        nodes=NODES,
        traces={},
        cpu_load={"/cam": 12.5, "/trk": 30.0},
        cores={"/cam": 0, "/trk": None},
        topics=TOPICS,
        chains=[],
        run={"duration_s": 0.1, "emulate": True, "host_cores": 2, "period_scale": 1.9},
        profiles=profiles,
    )


def test_the_document_names_each_process_s_profile_and_the_run_s_when_one() -> None:
    document = _document({"/cam": ("xu4", "a15"), "/trk": ("xu4", "a7")})
    read = parse_measurements(json.dumps(document))
    assert [p.profile for p in read.processes] == [("xu4", "a15"), ("xu4", "a7")]
    assert read.run_value("board") is None and read.period_scale == 1.9
    same = parse_measurements(json.dumps(_document({"/cam": ("xu4", "a15"), "/trk": ("xu4", "a15")})))
    assert (same.run_value("board"), same.run_value("core")) == ("xu4", "a15")


def _run_file(tmp_path, profiles) -> Path:
    document = tracking_measurements()
    document["version"] = 2
    for process, profile in zip(document["processes"], profiles, strict=True):
        process["profile"] = profile
    target = write_tracking_measurements(tmp_path, document)
    return target


def test_add_profile_takes_each_process_s_profile_without_hand_edits(tmp_path) -> None:
    target = _run_file(tmp_path, [{"board": "xu4", "core": "a15"}, {"board": "xu4", "core": "a7"}])
    result = add_profiles(target, tmp_path / "profiles")
    usb = (tmp_path / "profiles" / "nd_usb_cam_profiles.aadl").read_text()
    cmd = (tmp_path / "profiles" / "nd_pos_to_cmd_profiles.aadl").read_text()
    assert "process implementation usb_cam_nd.xu4_a15 extends" in usb
    assert "process implementation pos_to_cmd_nd.xu4_a7 extends" in cmd
    assert len(result.files) == 2


def test_a_bad_profile_name_is_refused_where_it_is(tmp_path) -> None:
    target = _run_file(tmp_path, [{"board": "xu 4", "core": "a15"}, {"board": "xu4", "core": "a7"}])
    with pytest.raises(RosaadlError) as caught:
        add_profiles(target, tmp_path / "profiles")
    where = [e.location for e in caught.value.errors]
    assert any(w.path == "$.processes[0].profile.board" and w.line for w in where)
    assert not (tmp_path / "profiles").exists()


def test_a_process_s_cpu_time_is_counted_per_thread_to_the_nanosecond() -> None:
    before = thread_cpu_ns(os.getpid())
    if before is None:
        pytest.skip("this kernel keeps no per-thread schedstat")
    began = time.thread_time()
    while time.thread_time() - began < 0.05:
        pass
    spent = cpu_seconds_between(before, thread_cpu_ns(os.getpid()))
    assert 0.045 < spent < 0.5
    assert thread_cpu_ns(2**22 + 12345) is None

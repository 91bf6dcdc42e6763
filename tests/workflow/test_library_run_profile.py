"""``rosaadl library add-profile measurements.json``: a measured run becomes PDMs of its nodes."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import rosaadl.library
from rosaadl.cli import main
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs
from rosaadl.errors import ParseError, RosaadlError
from rosaadl.model import find_instance
from rosaadl.properties import property_value
from rosaadl.transforms.instantiate import instantiate
from rosaadl.workflow.library_add_profile import add_profiles
from rosaadl.workflow.library_catalog import read_library
from tests.measurements_sample import (
    tracking_measurements,
    tracking_profiled,
    write_tracking_measurements,
)


def _run_file(tmp_path, version=1, latencies=(), **run):
    """The sample run; ``latencies``: the ``dispatch_latency_us`` of its threads (version 3)."""
    document = tracking_measurements()
    document["version"] = version
    document["run"].update(run)
    for thread, latency in zip(document["threads"], latencies, strict=False):
        thread["dispatch_latency_us"] = latency
    target = write_tracking_measurements(tmp_path, document)
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
    target = write_tracking_measurements(tmp_path, document)
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


SYSTEMS = Path(rosaadl.library.__file__).parent / "systems"
#: A timer thread's measured dispatch latency (µs) and one never released idle.
LATENCIES = ({"min": 612.5, "mean": 1034.25, "max": 1842.2}, None)


def test_a_measured_dispatch_latency_becomes_the_thread_pdm_s_rounded_up_max(tmp_path) -> None:
    out = tmp_path / "profiles"
    add_profiles(_run_file(tmp_path, 3, LATENCIES, board="xu4", core="a15"), out)
    usb = (out / "nd_usb_cam_profiles.aadl").read_text()
    assert "  with nd_usb_cam, ROS_Properties, Exynos_5422;" in usb
    assert (
        "  thread implementation imagePublisher.xu4_a15 extends nd_usb_cam::imagePublisher.impl\n"
        "    properties\n"
        "      Compute_Execution_Time => 2700540 ns .. 2700540 ns;\n"
        "      ROS_Properties::Dispatch_Latency => 1843 us;\n"
    ) in usb
    assert "-- a timer thread its measured ROS_Properties::Dispatch_Latency." in usb
    # a null latency (and a file of version 1 or 2) writes nothing of it
    pos = (out / "nd_pos_to_cmd_profiles.aadl").read_text()
    assert "Dispatch_Latency" not in pos and "ROS_Properties" not in pos


def test_a_run_of_an_earlier_version_writes_no_dispatch_latency(tmp_path) -> None:
    out = tmp_path / "profiles"
    add_profiles(_run_file(tmp_path, 2, board="xu4", core="a15"), out)
    usb = (out / "nd_usb_cam_profiles.aadl").read_text()
    assert "Dispatch_Latency" not in usb and "ROS_Properties" not in usb


def test_the_profiled_dispatch_latency_reaches_the_analysed_system(tmp_path, capsys) -> None:
    out = tmp_path / "profiles"
    add_profiles(_run_file(tmp_path, 3, LATENCIES, board="xu4", core="a15"), out)
    system = tmp_path / "tracking_profiled.aadl"
    system.write_text(tracking_profiled({"usbcam": "nd_usb_cam_profiles::usb_cam_nd.xu4_a15"}))
    inputs = [str(SYSTEMS), str(out), str(system)]
    root = "tracking_profiled::tracking_profiled.impl"
    instance = choose_instance(read_aadl_inputs([Path(i) for i in inputs]), root)  # as analyze does
    camera = find_instance(instance, "rem_trk_sw.usbcam.image_broadcaster")
    assert property_value(camera, "ROS_Properties::Dispatch_Latency").to("us") == 1843
    command = find_instance(instance, "rem_trk_sw.poscmd.cmd_publisher")
    assert property_value(command, "ROS_Properties::Dispatch_Latency") is None  # not profiled
    code = main(["--format", "json", "analyze", *inputs, "--root", root, "--only", "executor"])
    report = json.loads(capsys.readouterr().out)
    assert code == 0 and report["ok"], report["errors"]
    callback = next(
        c
        for c in report["analyses"]["executor"]["callbacks"]
        if c["path"].endswith("usbcam.image_broadcaster")
    )
    assert callback["kind"] == "timer" and callback["wcrt"] == pytest.approx(2700.54 + 1843)


def _twin_run(tmp_path):
    """The sample run as version 4: the workload twin held 2210.5 us of each dispatch of usb_cam's
    thread, whose CPU the run gauged at 331.2 loops per CPU ms; pos_to_cmd's CPU not gauged."""
    document = tracking_measurements()
    document["version"] = 4
    document["run"].update(board="xu4", core="a15")
    document["threads"][0]["twin_execution_time_us"] = 2210.5
    document["processes"][0]["cpu_speed"] = 331.2
    return write_tracking_measurements(tmp_path, document)


def test_the_twin_s_time_and_the_cpu_speed_go_into_the_thread_pdm(tmp_path) -> None:
    out = tmp_path / "profiles"
    add_profiles(_twin_run(tmp_path), out)
    usb = (out / "nd_usb_cam_profiles.aadl").read_text()
    assert "  with nd_usb_cam, ROS_Properties, Exynos_5422;" in usb
    assert (
        "      Compute_Execution_Time => 2700540 ns .. 2700540 ns;\n"
        "      ROS_Properties::Twin_Execution_Time => 2210500 ns;\n"
        "      ROS_Properties::Profiled_CPU_Speed => 331.2;\n"
    ) in usb
    assert "-- (ROS_Properties::Twin_Execution_Time, Profiled_CPU_Speed)." in usb
    pos = (out / "nd_pos_to_cmd_profiles.aadl").read_text()
    assert "Twin_" not in pos and "ROS_Properties" not in pos
    instance = instantiate(read_library([out]), "nd_usb_cam_profiles::usb_cam_nd.xu4_a15")
    thread = find_instance(instance, "image_broadcaster")
    assert property_value(thread, "ROS_Properties::Twin_Execution_Time").to("us") == 2210.5
    assert property_value(thread, "ROS_Properties::Profiled_CPU_Speed") == 331.2


def test_compare_rescales_a_profiled_process_to_the_speed_its_run_measured(tmp_path, capsys) -> None:
    out = tmp_path / "profiles"
    add_profiles(_twin_run(tmp_path), out)
    system = tmp_path / "tracking_profiled.aadl"
    system.write_text(tracking_profiled({"usbcam": "nd_usb_cam_profiles::usb_cam_nd.xu4_a15"}))
    document = tracking_measurements()
    document["version"] = 4
    document["processes"][0]["cpu_speed"] = 298.08  # the CPU at 0.9 x the profile's speed
    document["processes"][1]["cpu_speed"] = 400.0  # pos_to_cmd: its profile has no speed
    (tmp_path / "slow").mkdir()
    slow = write_tracking_measurements(tmp_path / "slow", document)
    args = [str(SYSTEMS), str(out), str(system), "--root", "tracking_profiled::tracking_profiled.impl"]
    code = main(["--format", "json", "analyze", *args, "--compare", str(slow), "--only", "cpu,compare"])
    report = json.loads(capsys.readouterr().out)
    # the sample's made-up response times and latency pass their bounds: the only errors
    assert code == 1 and all(e["message"].startswith("measured ") for e in report["errors"])
    items = {(i["path"].partition(".")[2], i["quantity"]): i for i in report["analyses"]["compare"]["items"]}
    plain = items[("rem_trk_sw.usbcam", "cpu_load_percent")]["predicted"]
    rescaled = items[("rem_trk_sw.usbcam", "cpu_load_at_run_speed_percent")]
    # 2210.5 us of the CET of 2700.54 us burned by the twin; the rest takes 1 / 0.9 as long
    assert rescaled["predicted"] == pytest.approx(plain * (2210.5 + (2700.54 - 2210.5) / 0.9) / 2700.54)
    assert rescaled["measured"] == 8.1
    assert ("rem_trk_sw.poscmd", "cpu_load_at_run_speed_percent") not in items
    warning = next(w for w in report["warnings"] if "speed" in w["message"])
    assert "0.90× the speed of the process's profile" in warning["message"]
    assert warning["path"].endswith("rem_trk_sw.usbcam")
    # a run at the profile's speed: the same prediction, no warning
    document["processes"][0]["cpu_speed"] = 331.2
    (tmp_path / "same").mkdir()
    same = write_tracking_measurements(tmp_path / "same", document)
    main(["--format", "json", "analyze", *args, "--compare", str(same), "--only", "cpu,compare"])
    report = json.loads(capsys.readouterr().out)
    items = {(i["path"].partition(".")[2], i["quantity"]): i for i in report["analyses"]["compare"]["items"]}
    assert items[("rem_trk_sw.usbcam", "cpu_load_at_run_speed_percent")]["predicted"] == pytest.approx(plain)
    assert not any("speed" in w["message"] for w in report["warnings"])


def test_an_out_of_range_dispatch_latency_is_refused_at_its_path(tmp_path) -> None:
    huge = {"min": 1.0, "mean": 2.0, "max": 1e300}
    target = _run_file(tmp_path, 3, (huge,), board="xu4", core="a15")
    with pytest.raises(RosaadlError) as caught:
        add_profiles(target, tmp_path / "profiles")
    where = caught.value.location
    assert where.path == "$.threads[0].dispatch_latency_us.max" and where.line is not None
    assert not (tmp_path / "profiles").exists()


def test_the_middleware_is_charged_evenly_to_every_dispatch_of_the_node(tmp_path) -> None:
    """The tracker: its image callback (37 ms every 100 ms) and its point timer (0.2 ms every
    300 ms) take 37.07 % of a CPU, the node 41.3 %: the 4.23 % beyond, 42 333 µs of CPU a second
    over 13.33 dispatches a second, is 3175 µs per dispatch, added to each callback's mean (the
    executor's wake-up, wait set and hand-over cost about the same for either); the profile's
    Σ CET / Period is the node's measured load."""
    document = tracking_measurements()
    document["threads"] += [
        {
            "path": f"rem_trk_sw.tracker.{name}",
            "process": "rem_trk_sw.tracker",
            "dispatches": 10,
            "period_us": {"mean": period, "jitter": 0.0},
            "execution_time_us": {"min": cet, "mean": cet, "max": cet},
            "response_time_us": {"min": cet, "mean": cet, "max": cet},
            "deadline_misses": 0,
        }
        for name, period, cet in (
            ("image_tracker", 100_000.0, 37_000.0),
            ("point_broadcaster", 300_000.0, 200.0),
        )
    ]
    document["processes"].append(
        {"path": "rem_trk_sw.tracker", "node": "ocv_color_tracking", "cpu_load_percent": 41.3, "core": 1}
    )
    document["run"].update(board="xu4", core="a15")
    run = write_tracking_measurements(tmp_path, document)
    add_profiles(run, tmp_path / "profiles")
    instance = instantiate(
        read_library([tmp_path / "profiles"]), "nd_ocv_color_tracking_profiles::ocv_color_tracking_nd.xu4_a15"
    )
    per_dispatch = (41.3 - 37.0 - 200 / 3000) / 100 * 1e6 / (10 + 10 / 3)
    assert per_dispatch == pytest.approx(3175.0)
    load = 0.0
    for name, period, cet in (("image_tracker", 100_000, 37_000), ("point_broadcaster", 300_000, 200)):
        thread = find_instance(instance, name)
        profiled = property_value(thread, "Compute_Execution_Time").maximum.to("us")
        assert profiled == pytest.approx(cet + per_dispatch, abs=0.001)
        load += profiled / period * 100
    assert load == pytest.approx(41.3, rel=1e-6)


#: A node as ROSMOD projects become AADL: the process holds the component as a thread group,
#: the component its callbacks' threads.
ROSMOD_SHAPED = """package rosmod_shaped
public
  with ROS_Properties;
  thread timer_callback
  end timer_callback;
  thread implementation timer_callback.impl
    properties
      Dispatch_Protocol => Periodic;
      Period => 100 ms;
  end timer_callback.impl;
  thread group Pinger
  end Pinger;
  thread group implementation Pinger.impl
    subcomponents
      ping_timer: thread timer_callback.impl;
      echo_timer: thread timer_callback.impl { Period => 50 ms; };
  end Pinger.impl;
  process Ping_Node
  end Ping_Node;
  process implementation Ping_Node.impl
    subcomponents
      Pinger: thread group Pinger.impl;
  end Ping_Node.impl;
  process Pong_Node
  end Pong_Node;
  process implementation Pong_Node.impl
    subcomponents
      Ponger: thread group Pinger.impl;
  end Pong_Node.impl;
  system App
  end App;
  system implementation App.impl
    subcomponents
      Ping_Node: process Ping_Node.impl;
      Pong_Node: process Pong_Node.impl;
  end App.impl;
end rosmod_shaped;
"""


def _rosmod_shaped_run(tmp_path, twin: bool = False) -> Path:
    """A run of the ROSMOD-shaped model; ``twin``: version 4, ping_timer ran the workload twin
    (echo_timer did not) and the process measured its gauge."""
    model = tmp_path / "model"
    model.mkdir()
    (model / "rosmod_shaped.aadl").write_text(ROSMOD_SHAPED)
    threads = [
        {
            "path": f"Ping_Node.Pinger.{name}",
            "process": "Ping_Node",
            "dispatches": 100,
            "period_us": {"mean": period, "jitter": 300.0},
            "execution_time_us": {"min": cet - 10, "mean": cet, "max": cet + 30},
            "response_time_us": {"min": cet, "mean": cet + 20, "max": cet + 90},
            "deadline_misses": 0,
            "dispatch_latency_us": {"min": 300.0, "mean": 400.0, "max": 812.4},
        }
        for name, period, cet in (("ping_timer", 100000.0, 1000.0), ("echo_timer", 50000.0, 500.0))
    ]
    document = {
        "format": "rosaadl-measurements",
        "version": 3,
        "model": {"root": "rosmod_shaped::App.impl"},
        "run": {"duration_s": 10.0, "emulate": True, "emulate_cet": "max", "board": "bbb", "core": "a8"},
        "threads": threads,
        "processes": [
            {"path": "Ping_Node", "classifier": "rosmod_shaped::Ping_Node.impl", "cpu_load_percent": 2.6}
        ],
        "topics": [],
        "chains": [],
    }
    if twin:
        document["version"] = 4
        threads[0]["twin_execution_time_us"] = 950.25
        document["processes"][0]["cpu_speed"] = 300.5
    write_tracking_measurements(tmp_path, document)
    return model


def test_threads_in_a_thread_group_get_their_values_on_the_process_pdm_at_their_path(tmp_path) -> None:
    """ROSMOD's components are thread groups: their threads' measured values go to the node's PDM
    as contained property associations, and the PDM's instance carries them where they were
    measured."""
    model = _rosmod_shaped_run(tmp_path)
    out = tmp_path / "profiles"
    add_profiles(tmp_path / "measurements.json", out, inputs=[model])
    text = (out / "rosmod_shaped_profiles.aadl").read_text()
    assert "process implementation Ping_Node.bbb_a8 extends rosmod_shaped::Ping_Node.impl" in text
    assert "ROS_Properties::Dispatch_Latency => 813 us applies to Pinger.ping_timer;" in text
    assert "thread implementation" not in text  # no thread PDM: the values sit on the process's
    instance = instantiate(read_library([model, out]), "rosmod_shaped_profiles::Ping_Node.bbb_a8")
    # 2.6 % of a CPU: the callbacks 1 % each, 10 + 20 dispatches a second share the other 6 ms
    # a second: 200 us each
    for name, cet_us in (("ping_timer", 1200), ("echo_timer", 700)):
        thread = find_instance(instance, f"Pinger.{name}")
        cet = property_value(thread, "Compute_Execution_Time")
        assert cet.minimum.to("us") == cet.maximum.to("us") == cet_us


def test_a_thread_group_s_threads_get_the_twin_s_values_at_their_path(tmp_path) -> None:
    """Every thread of a process that gauged the CPU keeps the speed; one the twin did not run
    in keeps no speed-independent time (0): all its CPU time follows the speed."""
    model = _rosmod_shaped_run(tmp_path, twin=True)
    out = tmp_path / "profiles"
    add_profiles(tmp_path / "measurements.json", out, inputs=[model])
    text = (out / "rosmod_shaped_profiles.aadl").read_text()
    assert "ROS_Properties::Twin_Execution_Time => 950250 ns applies to Pinger.ping_timer;" in text
    assert "ROS_Properties::Profiled_CPU_Speed => 300.5 applies to Pinger.ping_timer;" in text
    assert "ROS_Properties::Twin_Execution_Time => 0 us applies to Pinger.echo_timer;" in text
    assert "ROS_Properties::Profiled_CPU_Speed => 300.5 applies to Pinger.echo_timer;" in text
    instance = instantiate(read_library([model, out]), "rosmod_shaped_profiles::Ping_Node.bbb_a8")
    thread = find_instance(instance, "Pinger.ping_timer")
    assert property_value(thread, "ROS_Properties::Twin_Execution_Time").to("ns") == 950250
    assert property_value(thread, "ROS_Properties::Profiled_CPU_Speed") == 300.5


def test_a_twin_without_its_process_s_gauge_keeps_no_speed_and_says_so(tmp_path) -> None:
    document = tracking_measurements()
    document["version"] = 4
    document["run"].update(board="xu4", core="a15")
    document["threads"][1]["twin_execution_time_us"] = 900.0
    out = tmp_path / "profiles"
    result = add_profiles(write_tracking_measurements(tmp_path, document), out)
    assert "Twin_" not in (out / "nd_pos_to_cmd_profiles.aadl").read_text()
    [warning] = [w for w in result.warnings if "twin" in w.message]
    assert "rem_trk_sw.poscmd.cmd_publisher ran the workload twin" in warning.message
    assert warning.location.path == "$.threads[1]" and warning.location.line


def test_an_out_of_range_twin_time_is_refused_at_its_path(tmp_path) -> None:
    document = tracking_measurements()
    document["version"] = 4
    document["run"].update(board="xu4", core="a15")
    document["threads"][0]["twin_execution_time_us"] = 1e300
    document["processes"][0]["cpu_speed"] = 330.0
    with pytest.raises(RosaadlError) as caught:
        add_profiles(write_tracking_measurements(tmp_path, document), tmp_path / "profiles")
    assert any(e.location.path == "$.threads[0].twin_execution_time_us" for e in caught.value.errors)
    assert not (tmp_path / "profiles").exists()


def test_a_thread_in_a_thread_group_is_named_by_its_path_or_its_own_name(tmp_path) -> None:
    model = tmp_path / "model"
    model.mkdir()
    (model / "rosmod_shaped.aadl").write_text(ROSMOD_SHAPED)
    rows = "node,thread,board,core,period_us,cet_us,mips_raw,ipc,data_size_bytes\n"
    rows += "rosmod_shaped::Ping_Node,Pinger.ping_timer,bbb,a8,100000,900,500,0.6,\n"
    rows += "rosmod_shaped::Ping_Node,echo_timer,bbb,a8,50000,400,500,0.6,\n"
    (tmp_path / "m.csv").write_text(rows)
    add_profiles(tmp_path / "m.csv", tmp_path / "out", inputs=[model])
    text = (tmp_path / "out" / "rosmod_shaped_profiles.aadl").read_text()
    assert "Compute_Execution_Time => 900 us .. 900 us applies to Pinger.ping_timer;" in text
    assert "Compute_Execution_Time => 400 us .. 400 us applies to Pinger.echo_timer;" in text
    rows += "rosmod_shaped::Ping_Node,pinger,bbb,a8,50000,400,500,0.6,\n"
    (tmp_path / "m.csv").write_text(rows)
    with pytest.raises(
        RosaadlError,
        match=r"unknown thread 'pinger': .* has the threads Pinger\.ping_timer, Pinger\.echo_timer",
    ):
        add_profiles(tmp_path / "m.csv", tmp_path / "out2", inputs=[model])


def test_nodes_of_one_package_share_its_profiles_package_and_keep_each_other_s_pdms(tmp_path) -> None:
    """A ROSMOD deployment declares all its nodes in one package: their PDMs go to one profiles
    package; measuring one of them again replaces its PDM and keeps the other's."""
    model = tmp_path / "model"
    model.mkdir()
    (model / "rosmod_shaped.aadl").write_text(ROSMOD_SHAPED)
    header = "node,thread,board,core,period_us,cet_us,mips_raw,ipc,data_size_bytes\n"
    rows = "rosmod_shaped::Ping_Node,ping_timer,bbb,a8,100000,900,500,0.6,\n"
    rows += "rosmod_shaped::Pong_Node,Ponger.ping_timer,bbb,a8,100000,800,400,0.5,\n"
    (tmp_path / "m.csv").write_text(header + rows)
    out = tmp_path / "out"
    add_profiles(tmp_path / "m.csv", out, inputs=[model])
    assert [p.name for p in out.iterdir()] == ["rosmod_shaped_profiles.aadl"]
    text = (out / "rosmod_shaped_profiles.aadl").read_text()
    assert "process implementation Ping_Node.bbb_a8 extends" in text
    assert "process implementation Pong_Node.bbb_a8 extends" in text
    (tmp_path / "again.csv").write_text(
        header + "rosmod_shaped::Ping_Node,ping_timer,bbb,a8,100000,700,500,0.6,\n"
    )
    add_profiles(tmp_path / "again.csv", out, inputs=[model])
    text = (out / "rosmod_shaped_profiles.aadl").read_text()
    assert "Compute_Execution_Time => 700 us .. 700 us applies to Pinger.ping_timer;" in text
    assert "Compute_Execution_Time => 800 us .. 800 us applies to Ponger.ping_timer;" in text
    assert "900 us" not in text

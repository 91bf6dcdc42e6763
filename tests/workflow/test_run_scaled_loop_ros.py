"""The measurement loop on this machine, on a real ROS 2 runtime (``make ros``): the library's
tracking example, emulated, with its periods scaled for the cores here (``--period-scale 3``: the
tracker's 111 % of a core becomes 37 %; ``auto``'s 1.9, 58 %, leaves a 2-core machine that runs
other work too little room: there the tracker missed 8 % of its images), measured; its
measurements made into profiles (``library add-profile``, no hand edit), the model analysed
again with them, and that prediction of each process's CPU load held to a second measured run
(within 5 %, the paper's claim, for the tracker, the whole application and each process, the
prediction taken at the CPU speed the second run measured: ``cpu_load_at_run_speed_percent``;
:data:`DURATION` says why the runs are 30 s long); the executor analysis's bounds of the scaled
model beside the measured callbacks and chain.

A run whose threads did not all reach 97 % of their modelled dispatches (the machine stalled, or
another program took the CPUs) is run again, at most twice, so that a stall does not decide.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from ros_runtime import runtime_marks

import rosaadl.library
from rosaadl.analysis.compare import SPEED_TOLERANCE
from rosaadl.importers.measurements import read_measurements
from tests.measurements_sample import tracking_profiled

pytestmark = [*runtime_marks(), pytest.mark.slow]

SYSTEMS = Path(rosaadl.library.__file__).parent / "systems"
ROOT = "sys_tracking::tracking.impl"
#: The paper's claim: the analyses predict within 5 %.
CLAIM = 5.0
#: The modelled dispatches a run must reach to count (a stalled run is run again).
REACHED = 0.97
#: Seconds measured per run. A process's measured CPU load is its mean over the window, and the
#: small processes' (pos_to_cmd 0.85 % of a CPU, usb_cam 3.7 %: half or more of each rclpy's
#: executor and DDS, whose CPU time per wake-up varies with how the other processes on the CPU
#: and the host leave the caches: ±13 % from one 3 s window of a run to the next) repeats over
#: 10 s windows only to about ±9 %: the profiled prediction then missed by up to 8.9 %
#: (pos_to_cmd, 4 loops in 10 over 5 %). Over 30 s and 40 s windows (8 and 18 loops here) each
#: process whose two runs' CPUs ran within SPEED_TOLERANCE of one speed (43 of 78) was within
#: 5 %, worst 2.8 %.
DURATION = 30
#: A process whose two runs' CPU speeds differ by more than the comparison's SPEED_TOLERANCE (it
#: warns) ran on what is not quite the same machine: the gauge follows the middleware only in part
#: (its run-to-run change about 0.7 times the gauge's here, 35 loops), so the rescaled prediction
#: is held to this instead (in the 26 loops above, with speed changes of 5 to 20 %: worst 5.5 %).
SHIFTED = 10.0
#: Beyond this speed change the process is held only to the comparison's warning (twice in 36
#: loops here: 38 % and 28 %, the rescaled prediction then 15.5 % and 6.0 % off).
SPEED_SPREAD = 0.2
#: The period scale of the runs (see the module docstring).
SCALE = 3.0

#: The tracking system with the profiled nodes, in its own package (the profiles' PDMs refine
#: the processes of the library's system; every instance path stays the same).
PROFILED = tracking_profiled(
    {
        "usbcam": "nd_usb_cam_profiles::usb_cam_nd.xu4_a15",
        "tracker": "nd_ocv_color_tracking_profiles::ocv_color_tracking_nd.xu4_a15",
        "poscmd": "nd_pos_to_cmd_profiles::pos_to_cmd_nd.xu4_a7",
    }
)


def _rosaadl(*args: str, timeout: int = 600) -> dict:
    done = subprocess.run(
        [sys.executable, "-m", "rosaadl", "--format", "json", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    try:
        return json.loads(done.stdout)
    except ValueError:
        raise AssertionError(done.stderr[-3000:]) from None


def _reached(measurements: Path) -> bool:
    """Every periodic or triggered thread reached REACHED of its modelled dispatches."""
    read = read_measurements(measurements)
    scale, seconds = read.period_scale, read.run_value("duration_s")
    plan = json.loads((measurements.parent / "rosaadl-run.json").read_text())
    periods = {
        (node["path"].partition(".")[2] + "." + name[: -len(".period")]): value
        for node in plan["nodes"]
        for name, value in node["parameters"]
        if name.endswith(".period") and value
    }
    expected = {path: seconds / (period * scale) for path, period in periods.items()}
    return all(
        t.dispatches >= REACHED * expected[t.path]
        for t in read.threads
        if t.path in expected and t.dispatches
    )


def _measured_run(folder: Path, copy: Path, *model: str) -> Path:
    """A measured, emulated, scaled run (of the model, or again of the run folder), its
    measurements copied to ``copy``; run again (at most twice) until it reached its dispatches."""
    for attempt in range(3):
        source = model if model and attempt == 0 else (str(folder), "--no-build")
        report = _rosaadl(
            "run", *source, *(["-o", str(folder)] if source == model else []), "--duration", str(DURATION),
            "--emulate", "--measure", "--period-scale", str(SCALE),
        )  # fmt: skip
        assert report["ok"], report["errors"]
        if _reached(folder / "measurements.json"):
            break
    shutil.copy(folder / "measurements.json", copy)
    return copy


@pytest.fixture(scope="module")
def loop(tmp_path_factory) -> dict:
    base = tmp_path_factory.mktemp("loop")
    first = _measured_run(base / "run", base / "first.json", str(SYSTEMS), "--root", ROOT)
    compared = _rosaadl("analyze", str(SYSTEMS), "--root", ROOT, "--compare", str(first))
    profiled = _rosaadl("library", "add-profile", str(first), "-o", str(base / "profiles"))
    assert profiled["ok"], profiled["errors"]
    (base / "tracking_profiled.aadl").write_text(PROFILED)
    second = _measured_run(base / "run", base / "second.json")
    again = _rosaadl(
        "analyze", str(SYSTEMS), str(base / "profiles"), str(base / "tracking_profiled.aadl"),
        "--root", "tracking_profiled::tracking_profiled.impl", "--compare", str(second),
    )  # fmt: skip
    return {"first": first, "compared": compared, "second": second, "again": again}


def _items(report: dict, quantity: str) -> dict[str, dict]:
    return {
        i["path"].partition("_Instance.")[2] or i["path"]: i
        for i in report["analyses"]["compare"]["items"]
        if i["quantity"] == quantity
    }


def test_the_run_is_scaled_for_this_machine_and_says_so(loop) -> None:
    read = read_measurements(loop["first"])
    assert read.period_scale == SCALE
    assert loop["compared"]["analyses"]["compare"]["period_scale"] == SCALE
    tracker = _items(loop["compared"], "cpu_load_percent")["rem_trk_sw.tracker"]
    assert tracker["predicted"] == pytest.approx(111.0 / SCALE, rel=1e-3)
    assert {p.path.rpartition(".")[2]: p.profile for p in read.processes} == {
        "usbcam": ("xu4", "a15"),
        "tracker": ("xu4", "a15"),
        "poscmd": ("xu4", "a7"),
    }


def test_per_process_load_is_compared_then_predicted_within_5_percent_after_profiling(loop) -> None:
    first = _items(loop["compared"], "cpu_load_percent")
    for process in ("rem_trk_sw.usbcam", "rem_trk_sw.tracker", "rem_trk_sw.poscmd"):
        assert first[process]["predicted"] > 0 and first[process]["measured"] > 0
    plain = _items(loop["again"], "cpu_load_percent")
    after = _items(loop["again"], "cpu_load_at_run_speed_percent")
    processes = ("rem_trk_sw.usbcam", "rem_trk_sw.tracker", "rem_trk_sw.poscmd")
    # the CPUs of every process were gauged in both runs: its profile and the second run have a speed
    assert set(after) == set(processes), sorted(after)
    errors = {p: after[p]["error_percent"] for p in processes}
    speeds = {
        run: {
            p.path.partition("_Instance.")[2] or p.path: p.cpu_speed
            for p in read_measurements(loop[run]).processes
        }
        for run in ("first", "second")
    }
    print(
        "per-process CPU load error, profiled prediction vs second run (%):",
        errors,
        "at the profile's speed:",
        {p: plain[p]["error_percent"] for p in processes},
        "CPU speeds:",
        speeds,
    )
    # the tracker (90 % of the application's CPU time) and the whole application: within 5 %,
    # at the profile's speed and at the run's
    for items in (plain, after):
        predicted, measured = (sum(items[p][key] for p in processes) for key in ("predicted", "measured"))
        assert abs(items["rem_trk_sw.tracker"]["error_percent"]) <= CLAIM, errors
        assert abs(measured - predicted) / predicted * 100 <= CLAIM, (predicted, measured)
    # each process within 5 % where the two runs' CPUs ran at one speed; else the comparison says
    # that they did not, and the rescaled prediction is held to SHIFTED (see there)
    warned = {
        w["path"].partition("_Instance.")[2]
        for w in loop["again"]["warnings"]
        if "the speed of the process's profile" in w["message"] and w["path"]
    }
    for p in processes:
        shift = abs(speeds["first"][p] / speeds["second"][p] - 1)
        if shift <= SPEED_TOLERANCE:
            assert abs(errors[p]) <= CLAIM, (p, after[p], errors)
            continue
        assert p in warned, (p, loop["again"]["warnings"])
        if shift <= SPEED_SPREAD:
            assert abs(errors[p]) <= SHIFTED, (p, after[p], errors)


@pytest.mark.parametrize("analysis", ["compared", "again"], ids=["library-model", "profiled-model"])
def test_every_executor_bound_is_held_to_the_measured_maximum_with_its_pessimism(loop, analysis) -> None:
    """The library model's bounds against the first run, and the profiled model's (its execution
    times with the middleware's share, the executor's measured dispatch latency) against the
    second: each bound beside its measured maximum, violated exactly when below it, with its
    pessimism; the processes analysed on the CPUs the run put them on (fewer than the model's
    cores here), as the comparison says."""
    compare = loop[analysis]["analyses"]["compare"]
    if read_measurements(loop["first"]).run_value("host_cores") < 3:  # the model has 3 cores
        assert compare["placement"] and all(g["core"].startswith("CPU ") for g in compare["placement"])
    bounds = [i for i in compare["items"] if i["quantity"] in ("executor_response_time_us", "data_age_us")]
    callbacks = {i["path"].rpartition(".")[2] for i in bounds if i["quantity"] == "executor_response_time_us"}
    assert callbacks == {
        "image_broadcaster",
        "image_tracker",
        "point_broadcaster",
        "point_receiver",
        "cmd_publisher",
    }
    assert any(i["path"].endswith("etef_tracking") for i in bounds if i["quantity"] == "data_age_us")
    # the library gives point_broadcaster and point_receiver no Compute_Execution_Time: their
    # figure is an estimate there, not a bound (a warning says so); profiled, every one is a bound
    untimed = {i["path"].rpartition(".")[2] for i in bounds if i["bound"] is None}
    assert untimed == ({"point_broadcaster", "point_receiver"} if analysis == "compared" else set())
    held = {w["path"].rpartition(".")[2] for w in loop[analysis]["warnings"] if "not held" in w["message"]}
    assert held == untimed
    bounds = [i for i in bounds if i["bound"] is not None]
    ratios = {(p["path"], p["quantity"]): p["ratio"] for p in compare["pessimism"]}
    for item in bounds:
        assert item["violated"] == (item["measured"] > item["bound"])
        assert ratios[(item["path"], item["quantity"])] == pytest.approx(
            item["bound"] / item["measured"], rel=1e-5
        )
    print(analysis, "bound / measured:", {k[0].rpartition(".")[2] + " " + k[1]: v for k, v in ratios.items()})

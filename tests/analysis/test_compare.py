"""``rosaadl analyze --compare measurements.json``: every prediction beside its measurement."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import rosaadl.library
from rosaadl.analysis import run_analyses
from rosaadl.analysis.compare import compare_text
from rosaadl.cli import main
from rosaadl.exporters.report import render_report
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.measurements import parse_measurements
from rosaadl.transforms.instantiate import instantiate
from tests.measurements_sample import (
    tracking_measurements,
    tracking_measurements_text,
    write_tracking_measurements,
)

SYSTEMS = Path(rosaadl.library.__file__).parent / "systems"
ROOT = "sys_tracking::tracking.impl"
KEYS = ["path", "quantity", "predicted", "measured", "error_percent", "bound", "violated"]


@pytest.fixture(scope="module")
def tracking():
    return instantiate(read_files([SYSTEMS]), ROOT)


def _compare(instance, document=None, only="cpu,bus,sched,latency,compare"):
    measurements = parse_measurements(tracking_measurements_text(document), "m.json")
    return run_analyses(instance, only, measurements=measurements)


def test_items_have_the_issue_s_keys_and_errors_in_percent(tracking) -> None:
    report = _compare(tracking)
    items = report.as_dict()["analyses"]["compare"]["items"]
    assert all(list(item) == KEYS for item in items)
    result = report.result("compare")
    cet = result.item("rem_trk_sw.usbcam.image_broadcaster", "execution_time_us")
    assert cet.predicted == 2319 and cet.measured == 2330
    assert cet.error_percent == pytest.approx((2330 - 2319) / 2319 * 100)
    assert cet.bound is None and not cet.violated


def test_per_process_load_separates_callbacks_from_the_middleware(tracking) -> None:
    result = _compare(tracking).result("compare")
    process = result.item("rem_trk_sw.usbcam", "cpu_load_percent")
    callbacks = result.item("rem_trk_sw.usbcam", "callback_cpu_load_percent")
    middleware = result.item("rem_trk_sw.usbcam", "middleware_cpu_load_percent")
    assert process.predicted == pytest.approx(2319 / 33333 * 100)
    assert process.measured == 8.1
    assert callbacks.measured == pytest.approx(2330 / 33340 * 100)
    assert middleware.predicted is None
    assert middleware.measured == pytest.approx(8.1 - callbacks.measured)
    core = result.item("p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1", "cpu_load_percent")
    assert core.measured == 8.1 and core.predicted == pytest.approx(process.predicted)


def test_topic_bandwidth_is_compared_in_kbps(tracking) -> None:
    item = (
        _compare(tracking)
        .result("compare")
        .item("rem_trk_sw.usbcam.image_broadcaster.pub_msg", "bandwidth_kbps")
    )
    assert item.measured == 27648.0
    assert item.predicted == pytest.approx(921600 * 30000 / 1001 / 1000, rel=1e-3)


def test_a_response_time_over_its_bound_is_an_error_finding(tracking) -> None:
    report = _compare(tracking)
    item = report.result("compare").item("rem_trk_sw.usbcam.image_broadcaster", "response_time_us")
    assert (item.bound, item.measured, item.violated) == (2319, 2900, True)
    assert not report.ok
    assert any("response_time_us 2900.00 is above its bound 2319.00" in d.message for d in report.errors)


def test_a_response_time_within_its_bound_passes(tracking) -> None:
    document = tracking_measurements()
    for thread in document["threads"]:
        thread["response_time_us"] = {"min": 900.0, "mean": 950.0, "max": 1000.0}
    result = _compare(tracking, document, "sched,compare").result("compare")
    assert [i.violated for i in result.items if i.quantity == "response_time_us"] == [False, False]
    assert result.ok


def test_chain_latency_is_held_to_the_asynchronous_bounds(tracking) -> None:
    document = tracking_measurements()
    document["chains"][0]["latency_us"] = {"min": 30000.0, "mean": 90000.0, "max": 150000.0}
    report = _compare(tracking, document, "latency,compare")
    result = report.result("compare")
    worst = result.item("rem_trk_sw.etef_tracking", "latency_us")
    best = result.item("rem_trk_sw.etef_tracking", "latency_min_us")
    assert (worst.bound, worst.measured, worst.violated) == (139319, 150000, True)
    assert (best.bound, best.measured, best.violated) == (39319, 30000, True)
    synchronous = result.item("rem_trk_sw.etef_tracking", "latency_sync_us")
    assert synchronous.bound is None
    assert not report.ok


def test_what_the_model_does_not_hold_is_a_warning(tracking) -> None:
    document = tracking_measurements()
    document["threads"][0]["path"] = "rem_trk_sw.usbcam.ghost"
    result = _compare(tracking, document, "cpu,compare").result("compare")
    assert any(
        "thread rem_trk_sw.usbcam.ghost matches no prediction" in d.message for d in result.diagnostics
    )


def test_text_csv_and_html_show_the_comparison(tracking) -> None:
    report = _compare(tracking)
    text = report.text()
    assert "Predicted vs measured (m.json)" in text
    assert "middleware_cpu_load_percent" in text
    csv_text = report.csv_files()["tracking_impl_Instance__Compare.csv"]
    assert csv_text.splitlines()[0] == ",".join(KEYS)
    html, _data = render_report(tracking, report)
    assert 'id="compare"' in html and "chart-compare" in html and "+25.1 %, violated" in html


def test_the_report_has_no_comparison_section_without_measurements(tracking) -> None:
    html, _data = render_report(tracking, run_analyses(tracking, "cpu"))
    assert 'id="compare"' not in html


def _analyze_json(capsys, *args: str) -> tuple[int, dict]:
    code = main(["--format", "json", "analyze", str(SYSTEMS), "--root", ROOT, *args])
    return code, json.loads(capsys.readouterr().out)


def test_cli_compare_in_json_exits_1_on_a_violated_bound(tmp_path, capsys) -> None:
    target = write_tracking_measurements(tmp_path)
    code, document = _analyze_json(capsys, "--only", "cpu", "--compare", str(target))
    assert code == 1
    assert set(document["analyses"]) == {"cpu", "compare"}
    assert document["analyses"]["compare"]["measurements"] == str(target)


def test_cli_refuses_a_truncated_measurements_file_with_a_located_error(tmp_path, capsys) -> None:
    target = tmp_path / "measurements.json"
    text = tracking_measurements_text()
    target.write_text(text[:300])
    out = tmp_path / "csv"
    code, document = _analyze_json(capsys, "--compare", str(target), "-o", str(out))
    assert code == 1 and not out.exists()
    assert document["errors"][0]["file"] == str(target) and document["errors"][0]["line"] is not None


def test_compare_without_measurements_says_what_it_needs(tracking) -> None:
    report = run_analyses(tracking, "compare")
    assert any("needs measurements" in d.message for d in report.errors)


def test_a_run_of_the_extended_system_matches_the_extending_one(tracking) -> None:
    document = tracking_measurements()
    for thread in document["threads"]:
        thread["path"] = "tracking_base_Instance." + thread["path"]
    result = _compare(tracking, document, "cpu,compare").result("compare")
    item = result.item("rem_trk_sw.usbcam.image_broadcaster", "execution_time_us")
    assert item.measured == 2330.0


def test_executor_bounds_follow_the_cores_the_run_put_the_processes_on(tracking) -> None:
    """The model keeps usb_cam and pos_to_cmd on two cores; a run on a smaller machine put them
    on one: the executor bounds compared are those of the processes as they ran (each executor
    then also waits for the other's callbacks), and the comparison says so."""
    apart = _compare(tracking, only="sched,executor,compare").result("compare")
    alone = apart.item("rem_trk_sw.poscmd.cmd_publisher", "executor_response_time_us").bound
    assert not apart.placement and "placement" not in apart.as_dict()
    document = tracking_measurements()
    document["processes"][1]["core"] = 0
    report = _compare(tracking, document, only="sched,executor,compare")
    together = report.result("compare")
    html, _data = render_report(tracking, report)
    assert (
        "The executor bounds are those of the processes on the cores the run used\n"
        "  (CPU 0: rem_trk_sw.usbcam, rem_trk_sw.poscmd)." in html
    )
    shared = together.item("rem_trk_sw.poscmd.cmd_publisher", "executor_response_time_us").bound
    assert shared > alone
    assert together.as_dict()["placement"] == [
        {
            "core": "CPU 0",
            "processes": [
                "tracking_impl_Instance.rem_trk_sw.usbcam",
                "tracking_impl_Instance.rem_trk_sw.poscmd",
            ],
        }
    ]
    text = "\n".join(compare_text(together))
    assert (
        "executor bounds for the processes on the cores the run used "
        "(CPU 0: rem_trk_sw.usbcam, rem_trk_sw.poscmd)" in text
    )
    document["processes"][1]["core"] = None  # a process the run did not pin: the model's cores
    unpinned = _compare(tracking, document, only="sched,executor,compare").result("compare")
    assert not unpinned.placement
    assert unpinned.item("rem_trk_sw.poscmd.cmd_publisher", "executor_response_time_us").bound == alone


def test_executor_bounds_of_callbacks_without_execution_times_are_not_held_to_the_run(
    corpus, tmp_path
) -> None:
    """A ROSMOD project gives no execution times: the executor analysis counts them as 0, so a
    callback's own bound is no claim; the comparison shows the estimate beside the run, holds no
    bound, and says why, instead of calling every measured response time a violation."""
    converted = tmp_path / "aadl"
    assert (
        main(["-q", "convert", str(corpus / "rosmod/textual-v0.3/client-server"), "-o", str(converted)]) == 0
    )
    instance = instantiate(read_files([converted]), "Benchmark_deployment::Benchmark.impl")
    process = "Benchmark_impl_Instance.Client_Node"
    document = {
        "format": "rosaadl-measurements",
        "version": 1,
        "model": {"root": "Benchmark_deployment::Benchmark.impl"},
        "run": {"duration_s": 8.0, "emulate": True, "host_cores": 2},
        "threads": [
            {
                "path": f"{process}.Client.client_timer",
                "process": process,
                "dispatches": 2,
                "period_us": {"mean": 5000000.0, "jitter": 0.0},
                "execution_time_us": {"min": 68.6, "mean": 98.9, "max": 129.1},
                "response_time_us": {"min": 1056.5, "mean": 1187.0, "max": 1317.5},
                "deadline_misses": 0,
            }
        ],
        "processes": [{"path": process, "node": "client_node", "cpu_load_percent": 0.093}],
        "topics": [],
        "chains": [],
    }
    report = _compare(instance, document, only="sched,executor,compare")
    item = report.result("compare").item("Client_Node.Client.client_timer", "executor_response_time_us")
    assert (item.predicted, item.measured, item.bound, item.violated) == (0, 1317.5, None, False)
    assert [d.location.path for d in report.diagnostics if "not held to the run" in d.message] == [
        f"{process}.Client.client_timer"
    ]


def test_a_load_at_another_speed_rescales_what_the_twin_did_not_burn() -> None:
    from fractions import Fraction

    from rosaadl.analysis.compare import load_at_speed

    # 60 of 100 us burned; the other 40 take 300 / 250 as long on the slower CPU
    assert load_at_speed(Fraction(10), Fraction(100), Fraction(60), 300.0, 250.0) == Fraction(108, 10)
    assert load_at_speed(Fraction(10), Fraction(100), Fraction(60), 300.0, 300.0) == 10
    assert load_at_speed(Fraction(10), Fraction(100), Fraction(150), 300.0, 150.0) == 10  # all burned
    assert load_at_speed(Fraction(10), Fraction(100), Fraction(0), 300.0, 150.0) == 20  # none burned
    assert load_at_speed(Fraction(10), Fraction(0), Fraction(0), 300.0, 150.0) == 10

"""``analyze --compare`` of a run with scaled periods, and the executor analysis's bounds held to
the measured callbacks and chains (with their pessimism, bound ÷ measured)."""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import pytest

import rosaadl.library
from rosaadl.cli import main
from tests.measurements_sample import (
    tracking_measurements,
    write_tracking_measurements,
)

SYSTEMS = Path(rosaadl.library.__file__).parent / "systems"
ROOT = "sys_tracking::tracking.impl"


def _scaled_run(tmp_path, scale: float) -> Path:
    document = tracking_measurements()
    document["version"] = 2
    document["run"]["period_scale"] = scale
    for thread in document["threads"]:
        thread["period_us"]["mean"] *= scale
    target = write_tracking_measurements(tmp_path, document)
    return target


def _compare(folder: Path, scale: float) -> dict:
    output = io.StringIO()
    with contextlib.redirect_stdout(output):
        code = main(
            [
                "--format",
                "json",
                "analyze",
                str(SYSTEMS),
                "--root",
                ROOT,
                "--compare",
                str(_scaled_run(folder, scale)),
            ]
        )
    document = json.loads(output.getvalue())
    document["code"] = code
    return document


@pytest.fixture(scope="module")
def scaled(tmp_path_factory) -> dict:
    """The comparison of a run at period scale 1.9 (analysed once for the module)."""
    return _compare(tmp_path_factory.mktemp("scaled"), 1.9)


def _item(document: dict, path: str, quantity: str) -> dict:
    return next(
        i
        for i in document["analyses"]["compare"]["items"]
        if i["path"].endswith(path) and i["quantity"] == quantity
    )


def test_a_scaled_run_is_compared_with_the_scaled_model(scaled) -> None:
    document = scaled
    assert document["analyses"]["compare"]["period_scale"] == 1.9
    usbcam = _item(document, "rem_trk_sw.usbcam.image_broadcaster", "cpu_load_percent")
    assert usbcam["predicted"] == pytest.approx(2319 / (33333 * 1.9) * 100, rel=1e-6)
    assert usbcam["measured"] == pytest.approx(2330 / (33340 * 1.9) * 100, rel=1e-6)
    assert abs(usbcam["error_percent"]) < 1  # the same work at the same scaled rate
    process = _item(document, "rem_trk_sw.usbcam", "cpu_load_percent")
    assert process["predicted"] == pytest.approx(2319 / (33333 * 1.9) * 100, rel=1e-6)
    chain = _item(document, "rem_trk_sw.etef_tracking", "latency_us")
    assert chain["bound"] == 229319  # 139319 with every period of the chain × 1.9
    bandwidth = _item(document, "rem_trk_sw.usbcam.image_broadcaster.pub_msg", "bandwidth_kbps")
    assert bandwidth["predicted"] == pytest.approx(27630.28 / 1.9, rel=1e-4)


@pytest.fixture(scope="module")
def unscaled(tmp_path_factory) -> dict:
    return _compare(tmp_path_factory.mktemp("unscaled"), 1.0)


def test_an_unscaled_run_is_compared_with_the_model_as_it_is(unscaled) -> None:
    assert _item(unscaled, "rem_trk_sw.etef_tracking", "latency_us")["bound"] == 139319


def test_executor_bounds_are_held_to_the_callbacks_and_chains_with_their_pessimism(scaled) -> None:
    document = scaled
    compare = document["analyses"]["compare"]
    broadcaster = _item(document, "rem_trk_sw.usbcam.image_broadcaster", "executor_response_time_us")
    # the executor analysis's WCRT of the camera's timer callback, alone in its node: its CET
    assert broadcaster["bound"] == 2319 and broadcaster["measured"] == 2900 and broadcaster["violated"]
    chain = _item(document, "rem_trk_sw.etef_tracking", "data_age_us")
    assert chain["bound"] == pytest.approx(330711.7) and not chain["violated"]
    ratios = {(p["path"].rpartition(".")[2], p["quantity"]): p["ratio"] for p in compare["pessimism"]}
    assert ratios[("etef_tracking", "data_age_us")] == pytest.approx(330711.7 / 120000, rel=1e-6)
    assert ratios[("image_broadcaster", "executor_response_time_us")] == pytest.approx(2319 / 2900, rel=1e-6)
    assert document["code"] == 1 and any(
        "executor_response_time_us" in e["message"] for e in document["errors"]
    )


def test_the_text_names_the_scale_and_the_pessimism(tmp_path, capsys) -> None:
    main(
        [
            "analyze",
            str(SYSTEMS),
            "--root",
            ROOT,
            "--only",
            "compare",
            "--compare",
            str(_scaled_run(tmp_path, 1.9)),
            "--html",
            str(tmp_path / "out"),
        ]
    )
    text = capsys.readouterr().out
    assert "the model with its periods × 1.9, as the run scaled them" in text
    assert "bound/measured" in text
    html = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert "The model with its periods × 1.9, as the run scaled them." in html


def test_each_bus_s_total_is_the_measured_bandwidth_of_the_topics_bound_to_it(unscaled) -> None:
    document = unscaled
    ros_bus = _item(document, "ROSbus", "bus_bandwidth_kbps")
    # the image and point ports bound to the ROS virtual bus (bound to no physical bus, so their
    # Data_Size × rate); the sample measured the image topic only
    assert ros_bus["predicted"] == pytest.approx(27630.28 + 0.24, abs=0.01)
    assert ros_bus["measured"] == pytest.approx(27648.0)
    # the USB bus carries the camera device's stream, which no topic of the run carries
    assert not [i for i in document["analyses"]["compare"]["items"] if i["path"].endswith("usb_bus")]
    assert any(
        w["path"].endswith("p3DX.usb_bus") and "not compared" in w["message"] for w in document["warnings"]
    )

"""A measurements.json of the library's tracking example (sys_tracking::tracking.impl), as a
measured run would give it: the numbers are made up around the model's own figures."""

from __future__ import annotations

import copy
import json
from pathlib import Path
from typing import Any

__all__ = ["tracking_measurements", "tracking_measurements_text", "tracking_profiled"]

_SAMPLE: dict[str, Any] = {
    "format": "rosaadl-measurements",
    "version": 1,
    "model": {"root": "sys_tracking::tracking.impl"},
    "run": {"duration_s": 15.0, "emulate": True, "emulate_cet": "max", "host_cores": 2},
    "threads": [
        {
            "path": "rem_trk_sw.usbcam.image_broadcaster",
            "process": "rem_trk_sw.usbcam",
            "dispatches": 450,
            "period_us": {"mean": 33340.0, "jitter": 900.0},
            "execution_time_us": {"min": 2300.0, "mean": 2330.0, "max": 2500.0},
            "response_time_us": {"min": 2350.0, "mean": 2400.0, "max": 2900.0},
            "deadline_us": 33333.0,
            "deadline_misses": 0,
        },
        {
            "path": "rem_trk_sw.poscmd.cmd_publisher",
            "process": "rem_trk_sw.poscmd",
            "dispatches": 150,
            "period_us": {"mean": 100010.0, "jitter": 500.0},
            "execution_time_us": {"min": 1040.0, "mean": 1050.0, "max": 1100.0},
            "response_time_us": {"min": 1060.0, "mean": 1080.0, "max": 1200.0},
            "deadline_us": 100000.0,
            "deadline_misses": 0,
        },
    ],
    "processes": [
        {
            "path": "rem_trk_sw.usbcam",
            "node": "usb_cam",
            "classifier": "nd_usb_cam::usb_cam_nd.xu4_a15",
            "cpu_load_percent": 8.1,
            "core": 0,
        },
        {"path": "rem_trk_sw.poscmd", "node": "pos_to_cmd", "cpu_load_percent": 1.6, "core": 1},
    ],
    "topics": [
        {
            "name": "/image",
            "type": "sensor_msgs/msg/Image",
            "port": "rem_trk_sw.usbcam.image_broadcaster.pub_msg",
            "messages": 450,
            "rate_hz": 30.0,
            "bytes_per_message": 921600,
            "bandwidth_bytes_per_s": 27648000.0,
        }
    ],
    "chains": [
        {
            "name": "rem_trk_sw.etef_tracking",
            "topics": ["/image", "/point"],
            "samples": 140,
            "latency_us": {"min": 40100.0, "mean": 70000.0, "max": 120000.0},
        }
    ],
}


def tracking_measurements() -> dict[str, Any]:
    """A fresh copy of the sample document (edit it freely)."""
    return copy.deepcopy(_SAMPLE)


def tracking_measurements_text(document: dict[str, Any] | None = None) -> str:
    """The sample (or ``document``) as the indented JSON text a run writes."""
    return json.dumps(tracking_measurements() if document is None else document, indent=2) + "\n"


def write_tracking_measurements(folder: Path, document: dict[str, Any] | None = None) -> Path:
    """``folder/measurements.json`` holding the sample (or ``document``), as a run writes it."""
    target = Path(folder) / "measurements.json"
    target.write_text(tracking_measurements_text(document), encoding="utf-8")
    return target


def tracking_profiled(refinements: dict[str, str]) -> str:
    """The AADL text of package ``tracking_profiled``: the tracking system
    (``tracking_profiled::tracking_profiled.impl``) whose software system refines each process
    named in ``refinements`` to the profile's PDM given (``{"usbcam":
    "nd_usb_cam_profiles::usb_cam_nd.xu4_a15"}``); every instance path stays the same."""
    packages = sorted({pdm.partition("::")[0] for pdm in refinements.values()})
    refined = "".join(f"      {name}: refined to process {pdm};\n" for name, pdm in refinements.items())
    sw, whole = "tracking_sw_profiled", "tracking_profiled"
    return (
        f"package tracking_profiled\npublic\n  with sw_tracking, sys_tracking, {', '.join(packages)};\n"
        f"  system {sw} extends sw_tracking::tracking_sw\n  end {sw};\n"
        f"  system implementation {sw}.impl extends sw_tracking::tracking_sw.impl\n"
        f"    subcomponents\n{refined}  end {sw}.impl;\n"
        f"  system {whole} extends sys_tracking::tracking\n  end {whole};\n"
        f"  system implementation {whole}.impl extends sys_tracking::tracking.impl\n"
        f"    subcomponents\n      rem_trk_sw: refined to system {sw}.impl;\n  end {whole}.impl;\n"
        "end tracking_profiled;\n"
    )

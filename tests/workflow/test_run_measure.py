"""``rosaadl run --measure``: trace files and /proc samples aggregated into measurements.json."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field

import pytest

from rosaadl.importers.measurements import parse_measurements
from rosaadl.workflow.run.measure import (
    ChainPlan,
    chain_latencies,
    chain_plans,
    measurements_document,
    process_core,
    process_cpu_seconds,
    read_trace,
    read_traces,
)

MS = 1_000_000  # ns


@dataclass
class Node:
    name: str
    path: str
    parameters: list = field(default_factory=list)

    @property
    def full_name(self) -> str:
        return f"/{self.name}"


@dataclass
class Topic:
    name: str
    type: str = "std_msgs/msg/String"
    messages: int = 0
    rate_hz: float | None = None
    bytes_per_message: float | None = None
    publishers: list = field(default_factory=list)
    subscribers: list = field(default_factory=list)


def _write(folder, name, lines):
    (folder / f"{name}.1.trace").write_text("\n".join(lines) + "\n")


@pytest.fixture
def traces(tmp_path):
    """cam publishes /image every 10 ms; trk handles each image (2 ms CPU) and publishes /point
    from a 20 ms timer; cmd receives /point. Times in ns from 1 s."""
    t0 = 1000 * MS
    cam = ["N /cam", "T pub camera_thread", "O /image camera_thread.out"]
    trk = ["N /trk", "T work tracker", "T send sender", "O /point sender.out"]
    cmd = ["N /cmd", "T recv receiver"]
    for k in range(10):
        release = t0 + k * 10 * MS
        cam.append(f"D pub {release} {release + MS // 10} {release + MS} {MS}")
        cam.append(f"P /image {k + 1} {release + MS} {release}")
        trk.append(f"R /image {k + 1} {release + MS} {release + 2 * MS}")
        trk.append(f"D work {release + 2 * MS} {release + 2 * MS} {release + 4 * MS} {2 * MS}")
    for j in range(5):
        release = t0 + j * 20 * MS + 5 * MS
        trk.append(f"D send {release} {release} {release + MS} {MS // 2}")
        trk.append(f"P /point {j + 1} {release + MS} {release}")
        cmd.append(f"R /point {j + 1} {release + MS} {release + 3 * MS}")
    cmd.append("D recv 5 6")  # a line cut short by a killed node
    _write(tmp_path, "cam", cam)
    _write(tmp_path, "trk", trk)
    _write(tmp_path, "cmd", cmd)
    return tmp_path


NODES = [
    Node("cam", "top_Instance.sw.cam", [("pub.deadline", 0.0005)]),
    Node("trk", "top_Instance.sw.trk"),
    Node("cmd", "top_Instance.sw.cmd"),
]
TOPICS = [
    Topic("/image", "sensor_msgs/msg/Image", 10, 100.0, 64.0, ["/cam"], ["/trk"]),
    Topic("/point", "geometry_msgs/msg/Point", 5, 50.0, 24.0, ["/trk"], ["/cmd"]),
]


def test_a_trace_is_read_and_a_cut_line_counted(traces) -> None:
    trace = read_trace(traces / "cmd.1.trace")
    assert trace.node == "/cmd" and trace.bad_lines == 1
    assert len(trace.received["/point"]) == 5


def test_chains_follow_the_latest_input_before_each_publishing_dispatch(traces) -> None:
    chain = chain_plans(
        NODES,
        TOPICS,
        [
            (
                "sw.flow",
                [
                    "top_Instance.sw.cam.camera_thread",
                    "top_Instance.sw.trk.tracker",
                    "top_Instance.sw.cmd.receiver",
                ],
            )
        ],
    )
    assert chain == [ChainPlan("sw.flow", (("/image", "/cam", "/trk"), ("/point", "/trk", "/cmd")))]
    latencies = chain_latencies(read_traces(traces), chain[0])
    # /point j is sent by a dispatch starting at 20j + 5 ms: the latest image received then is
    # the one published at 20j + 1 ms (received 20j + 2 ms); /point j arrives at 20j + 8 ms
    assert latencies == [7000.0] * 5


def test_the_document_validates_and_holds_threads_processes_topics_chains(traces) -> None:
    chains = chain_plans(
        NODES, TOPICS, [("sw.flow", ["top_Instance.sw.cam.camera_thread", "top_Instance.sw.cmd.receiver"])]
    )
    assert chains == []  # cam publishes nothing /cmd subscribes to
    chains = [ChainPlan("sw.flow", (("/image", "/cam", "/trk"), ("/point", "/trk", "/cmd")))]
    document = measurements_document(
        nodes=NODES,
        traces=read_traces(traces),
        cpu_load={"/cam": 12.5, "/trk": 30.0},
        cores={"/cam": 0, "/trk": None},
        topics=TOPICS,
        chains=chains,
        run={"duration_s": 0.1, "emulate": True, "host_cores": 2},
        root="pkg::top.impl",
    )
    read = parse_measurements(json.dumps(document))
    camera = next(t for t in read.threads if t.path == "top_Instance.sw.cam.camera_thread")
    assert camera.dispatches == 10
    assert camera.period_mean_us == 10000.0 and camera.period_jitter_us == 0.0
    assert camera.execution_time_us.mean == 1000.0
    assert camera.response_time_us.max == 1000.0
    assert camera.deadline_misses == 10  # 1 ms response, 0.5 ms deadline
    assert [p.path for p in read.processes] == ["top_Instance.sw.cam", "top_Instance.sw.trk"]
    assert read.topics[0].port == "top_Instance.sw.cam.camera_thread.out"
    assert read.topics[0].bandwidth_bytes_per_s == 6400.0
    assert read.chains[0].samples == 5 and read.chains[0].latency_us.mean == 7000.0


def test_a_window_keeps_only_the_dispatches_inside_it(traces) -> None:
    trace = read_trace(traces / "cam.1.trace", (1000 * MS, 1040 * MS + MS // 2))
    assert len(trace.dispatches["pub"]) == 4


def test_proc_gives_this_process_s_cpu_time_and_affinity() -> None:
    assert process_cpu_seconds(os.getpid()) >= 0
    assert process_cpu_seconds(2**22 + 12345) is None
    cores = os.sched_getaffinity(0)
    assert process_core(os.getpid()) == (next(iter(cores)) if len(cores) == 1 else None)

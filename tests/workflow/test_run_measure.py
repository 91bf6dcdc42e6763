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
    idle_dispatch_latencies,
    measurements_document,
    process_core,
    process_cpu_seconds,
    read_trace,
    read_traces,
    single_cpu,
)
from rosaadl.workflow.run.measured_window import whole_periods
from rosaadl.workflow.run.plan import NodeLaunch

MS = 1_000_000  # ns


@dataclass
class Node:
    name: str
    path: str
    parameters: list = field(default_factory=list)
    timers: list | None = None  # the plan's threads on a periodic timer (None: an older plan)

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
    """cam publishes /image every 10 ms; trk handles each image (2 ms CPU, of which its
    workload twin held 1.8 ms, or 1 ms every other image) and publishes /point from a 20 ms
    timer; cmd receives /point. Times in ns from 1 s."""
    t0 = 1000 * MS
    cam = ["N /cam", "T pub camera_thread", "O /image camera_thread.out"]
    trk = ["N /trk", "T work tracker", "T send sender", "O /point sender.out"]
    cmd = ["N /cmd", "T recv receiver"]
    for k in range(10):
        release = t0 + k * 10 * MS
        cam.append(f"D pub {release} {release + MS // 10} {release + MS} {MS}")
        cam.append(f"P /image {k + 1} {release + MS} {release}")
        trk.append(f"R /image {k + 1} {release + MS} {release + 2 * MS}")
        trk.append(
            f"D work {release + 2 * MS} {release + 2 * MS} {release + 4 * MS} {2 * MS} "
            + (f"{9 * MS // 5}" if k % 2 else f"{MS}")
        )
    for j in range(5):
        release = t0 + j * 20 * MS + 5 * MS
        trk.append(f"D send {release} {release} {release + MS} {MS // 2}")
        trk.append(f"P /point {j + 1} {release + MS} {release}")
        cmd.append(f"R /point {j + 1} {release + MS} {release + 3 * MS}")
    cmd.append("D recv 5 6")  # a line cut short by a killed node
    cmd.append(f"D recv {t0} {t0} {t0 + MS} {MS} {MS} 600")  # too many fields
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
    assert trace.node == "/cmd" and trace.bad_lines == 2
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
        cpu_speeds={"/trk": 301.5, "/cmd": 290.0},  # /cmd: measured no CPU load, no process row
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
    assert document["version"] == 4
    # the workload twin of trk's work thread held 1.8 and 1 ms of its dispatches: 1.4 on the mean
    work = next(t for t in read.threads if t.path == "top_Instance.sw.trk.tracker")
    assert work.twin_execution_time_us == 1400.0
    assert camera.twin_execution_time_us is None and "twin_execution_time_us" not in document["threads"][0]
    # the CPU speed of each node as the run gauged it
    assert [p.cpu_speed for p in read.processes] == [None, 301.5]
    # a plan that does not say which threads run on a timer: no dispatch latency is claimed
    assert all("dispatch_latency_us" not in row for row in document["threads"])


def test_a_window_keeps_only_the_dispatches_inside_it(traces) -> None:
    trace = read_trace(traces / "cam.1.trace", (1000 * MS, 1040 * MS + MS // 2))
    assert len(trace.dispatches["pub"]) == 4


def test_proc_gives_this_process_s_cpu_time_and_affinity() -> None:
    assert process_cpu_seconds(os.getpid()) >= 0
    assert process_cpu_seconds(2**22 + 12345) is None
    cores = os.sched_getaffinity(0)
    assert process_core(os.getpid()) == (next(iter(cores)) if len(cores) == 1 else None)
    assert process_core(2**22 + 12345) is None  # gone
    assert (single_cpu({3}), single_cpu({0, 1}), single_cpu(set())) == (3, None, None)


US = 1000  # ns


@pytest.fixture
def executor_trace(tmp_path):
    """One process: ``tick`` on a 10 ms timer, ``sub`` dispatched by messages (its recorded
    release is read after its start, as the generated code does). Times in ns from 1 s."""
    t0 = 1000 * MS
    lines = ["N /exe", "T tick ticker", "T sub listener"]
    tick = [
        (0, 800 * US),  # idle: 800 us
        (10 * MS, 10 * MS + 600 * US),  # sub runs from 9.5 to 10.5 ms: not idle
        (20 * MS, 20 * MS + 500 * US),  # sub starts at 20.1 ms, before this start: not idle
        (30 * MS, 31 * MS + 500 * US),  # idle: 1500 us
        (40 * MS, 40 * MS + 300 * US),  # sub runs from 39 to 40 ms, to the release: not idle
    ]
    for release, start in tick:
        lines.append(f"D tick {t0 + release} {t0 + start} {t0 + start + 2 * MS} {2 * MS}")
    listener = [
        (9 * MS + 500 * US, 10 * MS + 500 * US),
        (20 * MS + 100 * US, 20 * MS + 300 * US),
        (39 * MS, 40 * MS),
    ]
    for start, end in listener:
        lines.append(f"D sub {t0 + start + 5 * US} {t0 + start} {t0 + end} {end - start}")
    _write(tmp_path, "exe", lines)
    return tmp_path


def _exe_rows(folder, timers, window=None):
    document = measurements_document(
        nodes=[Node("exe", "top_Instance.sw.exe", [("tick.period", 0.01)], timers)],
        traces=read_traces(folder, window),
        cpu_load={},
        cores={},
        topics=[],
        chains=[],
        run={},
    )
    parse_measurements(json.dumps(document))  # it validates
    return {row["path"].rpartition(".")[2]: row for row in document["threads"]}


def test_a_timer_thread_s_dispatch_latency_counts_only_releases_of_an_idle_executor(executor_trace) -> None:
    rows = _exe_rows(executor_trace, ["tick"])
    assert rows["ticker"]["dispatch_latency_us"] == {"min": 800.0, "mean": 1150.0, "max": 1500.0}
    # a subscription's recorded release is its start: it has no dispatch latency
    assert "dispatch_latency_us" not in rows["listener"]


def test_a_release_during_another_dispatch_or_before_another_start_is_not_idle() -> None:
    spans = [(100, 200), (300, 400), (1000, 1100)]
    dispatches = [
        (150, 250, 260, 1),  # released while (100, 200) runs
        (260, 350, 360, 1),  # (300, 400) started between the release and this start
        (200, 240, 250, 1),  # released at the very end of (100, 200): still running
        (500, 900, 950, 1),  # idle
        (1200, 1200, 1300, 5),  # released at its start (a message's entry): none
        (1210, 1205, 1300, 5),  # released after its start (a subscription): none
    ]
    spans += [(start, end) for _release, start, end, _cpu in dispatches]
    assert idle_dispatch_latencies(dispatches, spans) == [0.4]


def test_a_timer_thread_never_released_idle_has_a_null_latency(executor_trace) -> None:
    rows = _exe_rows(executor_trace, ["tick", "sub"])  # even a "timer" whose releases follow its starts
    assert rows["listener"]["dispatch_latency_us"] is None


def test_a_dispatch_left_out_of_the_window_still_keeps_the_executor_busy(executor_trace) -> None:
    # the window starts at 1009.6 ms: sub's dispatch from 9.5 ms is left out (released before),
    # but it runs at tick's release at 10 ms
    rows = _exe_rows(executor_trace, ["tick"], (1009 * MS + 600 * US, 2000 * MS))
    assert rows["ticker"]["dispatch_latency_us"] == {"min": 1500.0, "mean": 1500.0, "max": 1500.0}


def test_the_measured_window_holds_whole_periods_of_every_timer() -> None:
    """``--measure`` rounds the S seconds up to a whole number of the longest timer period (a
    10 s window held 33 or 34 releases of a 300 ms timer, as its phase fell: 3 % of that thread's
    CPU time); a sporadic thread's period, a period longer than S, or a plan without its timers
    changes nothing."""

    def node(timers, **periods):
        parameters = [(f"{thread}.period", value) for thread, value in periods.items()]
        return NodeLaunch("n", "", "p", "n", "s.n", parameters=parameters, timers=timers)

    scaled = [node(["cmd"], cmd=0.3, point=0.3), node(["camera"], camera=0.099999)]
    assert whole_periods(10.0, scaled) == pytest.approx(10.2)
    assert whole_periods(9.9, scaled) == pytest.approx(9.9)
    assert whole_periods(10.0, [node(["cmd"], cmd=0.3, sporadic=0.7)]) == pytest.approx(10.2)
    assert whole_periods(10.0, [node([], point=0.3)]) == 10.0
    assert whole_periods(10.0, [node(None, cmd=0.3)]) == 10.0
    assert whole_periods(0.2, [node(["cmd"], cmd=0.3)]) == 0.2

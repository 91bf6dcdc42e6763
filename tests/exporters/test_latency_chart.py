"""The report's latency chart: stacked min and max bars, one segment per contributor."""

from __future__ import annotations

import re

from rosaadl.exporters.report.latency_chart import latency_chart


def _chain(mode: str = "async") -> dict:
    hop = {"kind": "processing", "label": "thread a", "best_us": 1000, "worst_us": 3000, "depth": 0}
    bus = {"kind": "transmission", "label": "bus b", "best_us": 500, "worst_us": 500, "depth": 1}
    conn = {
        "kind": "connection",
        "label": "connection a.o -> b.i",
        "best_us": 700,
        "worst_us": 500,
        "depth": 0,
    }
    sampling = {"kind": "sampling", "label": "thread b", "best_us": 0, "worst_us": 10000, "depth": 0}
    return {
        "name": "flow",
        "mode": mode,
        "best_us": 2200,
        "worst_us": 13500,
        "expected_us": 12000,
        "hops": [hop, bus, conn, sampling],
    }


def _segments(svg: str) -> list[str]:
    return re.findall(r"<title>((?:min|max): [^<]*)</title>", svg)


def test_one_segment_per_contributor_for_min_and_max():
    svg = latency_chart([_chain(), _chain("sync")])
    assert 'class="chart chart-latency"' in svg
    segments = _segments(svg)
    # the bus under the connection is a segment of its own; the connection keeps what it adds
    assert segments[:6] == [
        "min: thread a, processing 1 ms",
        "min: bus b, transmission 0.5 ms",
        "min: connection a.o -&gt; b.i, connection 0.2 ms",
        "max: thread a, processing 3 ms",
        "max: bus b, transmission 0.5 ms",
        "max: thread b, sampling 10 ms",
    ]
    assert len(segments) == 12 and "flow (sync)" in svg and "Latency 12000 us" in svg


def test_no_flow_is_said():
    assert "No end-to-end flow" in latency_chart([])

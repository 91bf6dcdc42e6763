"""The report's end-to-end latency chart: one stacked bar per flow and system kind, for its
minimum and for its maximum, one segment per contributor (sampling, processing, queuing,
transmission, partition), in the order the flow meets them.

It draws the JSON-ready chains of the latency analysis (``analyses.latency.chains`` of the
report's view); a bus or protocol under a connection is a segment of its own, and the
connection's own segment keeps only what the connection adds itself.
"""

from __future__ import annotations

from typing import Any

from rosaadl.exporters.report.canvas import (
    INK,
    MUTED,
    TRACK,
    WIDTH,
    Svg,
    empty_chart,
    fit,
    legend,
    ms_axis,
    nice_step,
    num,
)

__all__ = ["latency_chart"]

#: one colour per kind of contributor
KIND_COLOURS = {
    "sampling": "#f28e2b",
    "processing": "#4e79a7",
    "queuing": "#e15759",
    "connection": "#76b7b2",
    "transmission": "#59a14f",
    "partition": "#b07aa1",
    "partition output": "#9c755f",
}


def _segments(chain: dict[str, Any], key: str) -> list[tuple[str, str, float]]:
    """(kind, label, value) of each contributor that adds to the chain's ``key`` (best or worst);
    a connection's row holds the rows under it, which are drawn on their own."""
    out: list[tuple[str, str, float]] = []
    under = 0.0
    for hop in chain["hops"]:
        value = float(hop[key] or 0)
        if hop.get("depth", 0):
            under += value
            out.append((hop["kind"], hop["label"], value))
            continue
        if hop["kind"] == "connection":
            value -= under
        under = 0.0
        out.append((hop["kind"], hop["label"], value))
    return [s for s in out if s[2] > 0]


def latency_chart(chains: list[dict[str, Any]]) -> str:
    """Stacked min and max bars of every flow (microseconds on the axis, shown in ms)."""
    label = "End-to-end latency of every flow, by contributor"
    if not chains:
        return empty_chart(label, "No end-to-end flow or chain of threads", "chart chart-latency")
    longest = max(max(float(c["worst_us"] or 0), float(c["best_us"] or 0)) for c in chains) or 1.0
    step = nice_step(longest / 1000, 6) * 1000
    axis = step * max(1, -(-longest // step))
    left, right = 260.0, 40.0
    x0, x1 = left, WIDTH - right
    scale = (x1 - x0) / axis
    bar_h, gap, top = 14.0, 10.0, 34.0
    row_h = 2 * bar_h + 4 + gap
    height = top + row_h * len(chains) + 70
    svg = Svg(WIDTH, height, label, "chart chart-latency")
    ms_axis(svg, x0, scale, axis, step, top, top + row_h * len(chains), TRACK)
    for i, chain in enumerate(chains):
        y = top + i * row_h
        name = f"{chain['name']} ({chain['mode']})"
        svg.text(left - 10, y + bar_h + 4, fit(name, left - 20, 12), 12, anchor="end", tip=name)
        for j, (key, word) in enumerate((("best_us", "min"), ("worst_us", "max"))):
            by = y + j * (bar_h + 4)
            x = x0
            for kind, text, value in _segments(chain, key):
                width = value * scale
                tip = f"{word}: {text}, {kind} {num(value / 1000)} ms"
                svg.rect(x, by, width, bar_h, fill=KIND_COLOURS.get(kind, MUTED), stroke="#fff", tip=tip)
                x += width
            total = float(chain[key] or 0)
            svg.text(x + 6, by + bar_h - 3, f"{word} {num(total / 1000)} ms", 10.5, fill=INK)
        expected = chain.get("expected_us")
        if expected:
            ex = x0 + min(float(expected), axis) * scale
            svg.line(
                ex, y - 3, ex, y + 2 * bar_h + 7, stroke="#000", stroke_width=2, tip=f"Latency {expected} us"
            )
    legend(
        svg,
        [("swatch", colour, kind) for kind, colour in KIND_COLOURS.items()]
        + [("line", "#000", "specified Latency")],
        x0,
        top + row_h * len(chains) + 20,
        x1 - x0,
    )
    return svg.render()

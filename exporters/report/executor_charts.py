"""The executor section of the HTML report: chain latency bars and the executors' Gantt chart.

:func:`executor_section` turns the result of the ``executor`` analysis
(:mod:`rosaadl.analysis.executor_analysis`) into what the page shows: one bar per cause-effect
chain (its reaction time, which is also its data age) against its deadline (the end-to-end flow's
``Latency``) where it has one, and, per executor, the simulated dispatch of its callbacks from a
synchronous release (one row per callback; a multi-threaded executor's slices carry their thread
number). Charts are inline SVG drawn with :mod:`rosaadl.exporters.report.canvas`.
"""

from __future__ import annotations

from typing import Any

from rosaadl.exporters.report.canvas import (
    GRID,
    INK,
    MUTED,
    STATUS,
    TRACK,
    WIDTH,
    Svg,
    empty_chart,
    fit,
    ms_axis,
    nice_step,
)
from rosaadl.exporters.report.view import short_path

__all__ = ["executor_section", "chain_chart", "executor_gantt"]

_PALETTE = ("#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#76b7b2", "#edc948", "#b07aa1", "#9c755f")
_MAX_EXECUTORS = 12


def _number(value: Any) -> float | None:
    return None if value is None else float(value)


def executor_section(report: Any) -> dict[str, Any]:
    """The data of the section (``available`` false when the executor analysis did not run or
    found no executor)."""
    result = report.result("executor") if hasattr(report, "result") else None
    if result is None:
        return {"available": False, "chains": [], "executors": [], "more": 0}
    chains = [
        {
            "name": c.name,
            "reaction_time": _number(c.reaction_time),
            "deadline": _number(c.deadline),
            "met": c.met,
        }
        for c in result.chains
    ]
    executors = []
    for executor in result.executors[:_MAX_EXECUTORS]:
        window, intervals = result.gantt.get(executor.path, (0, ()))
        executors.append(
            {
                "path": executor.path,
                "label": executor.label,
                "window": float(window),
                "callbacks": [c.path for c in executor.callbacks],
                "intervals": [(p, t, float(s), float(e)) for p, t, s, e in intervals],
            }
        )
    more = max(0, len(result.executors) - _MAX_EXECUTORS)
    return {"available": True, "chains": chains, "executors": executors, "more": more}


def chain_chart(section: dict[str, Any]) -> str:
    """Horizontal bars: each chain's reaction time (= data age), its deadline as a dashed mark."""
    label = "Reaction time and data age of every cause-effect chain against its deadline"
    chains = section["chains"]
    if not chains:
        return empty_chart(label, "No cause-effect chain", "chart chart-chains")
    top, row_h, bar_h, left, right = 30.0, 30.0, 18.0, 330.0, 150.0
    longest = max(max(c["reaction_time"] or 0, c["deadline"] or 0) for c in chains) or 1000.0
    step = nice_step(longest)
    axis = step * -(-longest // step)
    scale = (WIDTH - left - right) / axis
    svg = Svg(WIDTH, max(top + row_h * len(chains) + 30, 90), label, "chart chart-chains")
    ms_axis(svg, left, scale, axis, step, top, top + row_h * len(chains), GRID)
    for i, chain in enumerate(chains):
        y = top + i * row_h + (row_h - bar_h) / 2
        svg.text(
            left - 10,
            y + bar_h / 2 + 4,
            fit(chain["name"], left - 20, 12),
            12,
            anchor="end",
            tip=chain["name"],
        )
        svg.rect(left, y, axis * scale, bar_h, fill=TRACK, rx=3)
        value = chain["reaction_time"]
        if value is None:
            svg.text(left + 8, y + bar_h / 2 + 4, "no bound: an executor on the chain is overloaded", 12,
                     bold=True, fill=STATUS["error"])  # fmt: skip
            continue
        colour = STATUS["error"] if chain["met"] is False else (STATUS["ok"] if chain["met"] else "#4e79a7")
        svg.rect(left, y, value * scale, bar_h, fill=colour, tip=f"reaction time = data age {value:g} us")
        text = f"{value / 1000:.1f} ms"
        if chain["deadline"] is not None:
            x = left + chain["deadline"] * scale
            svg.line(x, y - 3, x, y + bar_h + 3, stroke=INK, stroke_width=2, stroke_dasharray="4 3")
            text += f" / {chain['deadline'] / 1000:.1f} ms"
        svg.text(left + axis * scale + 8, y + bar_h / 2 + 4, text, 12, bold=True, fill=colour)
    return svg.render()


def executor_gantt(section: dict[str, Any]) -> str:
    """One block per executor, one row per callback, the simulated jobs as bars."""
    label = "Simulated dispatch of the callbacks by their executors"
    executors = [e for e in section["executors"] if e["intervals"]]
    if not executors:
        return empty_chart(label, "No executor with timed callbacks", "chart chart-executors")
    left, right, row_h, head = 260.0, 30.0, 20.0, 26.0
    height = sum(head + row_h * len(e["callbacks"]) + 10 for e in executors) + 10
    svg = Svg(WIDTH, height, label, "chart chart-executors")
    y = 10.0
    for executor in executors:
        span = max(executor["window"], *(end for _, _, _, end in executor["intervals"])) or 1.0
        scale = (WIDTH - left - right) / span
        svg.text(10, y + 16, f"{short_path(executor['path'])} — {executor['label']}", 12.5, bold=True)
        svg.text(WIDTH - right, y + 16, f"{span / 1000:g} ms", 10.5, anchor="end", fill=MUTED)
        y += head
        rows = {path: k for k, path in enumerate(executor["callbacks"])}
        for k, path in enumerate(executor["callbacks"]):
            svg.text(
                left - 10, y + k * row_h + 14, fit(short_path(path), left - 20, 11.5), 11.5, anchor="end"
            )
            svg.rect(left, y + k * row_h + 3, span * scale, row_h - 6, fill=TRACK)
        for path, thread, start, end in executor["intervals"]:
            k = rows.get(path, 0)
            svg.rect(
                left + start * scale,
                y + k * row_h + 3,
                max((end - start) * scale, 0.8),
                row_h - 6,
                fill=_PALETTE[k % len(_PALETTE)],
                tip=f"{short_path(path)} (thread {thread}): {start:g} .. {end:g} us",
            )
        y += row_h * len(executor["callbacks"]) + 10
    return svg.render()

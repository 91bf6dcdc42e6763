"""The report's charts as hand-written SVG: CPU and bus load bars, the Gantt chart of the
scheduling simulation; the architecture diagram is :mod:`.architecture`, the drawing kit (and
why SVG by hand) :mod:`.canvas`.

Every function takes the JSON-ready data of :mod:`rosaadl.exporters.report.view` and returns one
``<svg>`` element as a string; every text is escaped, every number is written with at most two
decimals, so the output is deterministic.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rosaadl.analysis.rendering import as_float
from rosaadl.exporters.report.architecture import architecture_diagram
from rosaadl.exporters.report.canvas import (
    FONT,
    GRID,
    INK,
    MUTED,
    STATUS,
    TRACK,
    WIDTH,
    Svg,
    distinct_labels,
    empty_chart,
    fit,
    hatch,
    legend,
    legend_height,
    mips,
    nice_step,
    num,
    percent_scale,
    rate,
    text_width,
)

__all__ = [
    "FONT",
    "STATUS",
    "cpu_chart",
    "bus_chart",
    "gantt_chart",
    "architecture_diagram",
    "text_width",
]


# =============================================================================== load bars


def cpu_chart(rows: list[dict[str, Any]]) -> str:
    """Per-processor load bars against capacity: stacked by thread in the node's colour, a
    dashed 100 % line, the part beyond capacity hatched red."""
    label = "CPU load of every processor and core against its capacity"
    if not rows:
        return empty_chart(label, "No processor in the model", "chart chart-cpu")
    axis_max, step = percent_scale(r["load_percent"] for r in rows)
    left, right = 200.0, 230.0
    x0, x1 = left, WIDTH - right
    scale = (x1 - x0) / axis_max
    row_h, bar_h, top = 34.0, 20.0, 40.0
    legend_items = _series_legend([s for r in rows for s in r["segments"]], "thread")
    legend_items.append(("hatch", "url(#cpu-over)", "over capacity"))
    height = top + row_h * len(rows) + 58 + legend_height(legend_items, x1 - x0 + right - 20)
    svg = Svg(WIDTH, height, label, "chart chart-cpu")
    hatch(svg, "cpu-over", STATUS["error"])
    _axis_percent(svg, x0, scale, axis_max, step, top, top + row_h * len(rows))
    labels = distinct_labels([r["label"] + (f" {r['mode']}" if r["mode"] else "") for r in rows])
    for i, (r, text) in enumerate(zip(rows, labels, strict=True)):
        y = top + i * row_h + (row_h - bar_h) / 2
        bold = bool(r["cores"])
        svg.text(
            left - 10,
            y + bar_h / 2 + 4,
            fit(text, left - 20, 12.5, bold),
            12.5,
            anchor="end",
            bold=bold,
            tip=r["path"],
        )
        svg.rect(x0, y, 100 * scale, bar_h, fill=TRACK, rx=3)
        load = r["load_percent"]
        if r["capacity_mips"] in (0, None) and load is None:
            svg.text(x0 + 8, y + bar_h / 2 + 4, "no MIPS capacity", 11.5, fill=MUTED)
            continue
        x = x0
        for s in r["segments"]:
            w = min(s["percent"], axis_max) * scale
            tip = f"{s['thread']}: {s['percent']:.2f} % ({s['mips']:.2f} MIPS)"
            svg.rect(x, y, w, bar_h, fill=s["colour"], tip=tip)
            x += w
        load = load or 0.0
        if r["overloaded"] or load > 100:
            over_w = (min(load, axis_max) - 100) * scale
            svg.rect(
                x0 + 100 * scale,
                y,
                over_w,
                bar_h,
                fill="url(#cpu-over)",
                stroke=STATUS["error"],
                stroke_width=1.5,
                tip=f"{load - 100:.2f} % over capacity",
            )
        colour = STATUS["error"] if r["overloaded"] else (STATUS["warning"] if load > 90 else INK)
        value = f"{load:.1f} %"
        detail = (
            f"{mips(r['demand_mips'])} of {mips(r['capacity_mips'])} MIPS"
            if r["capacity_mips"]
            else "CET / period"
        )
        if r["overloaded"]:
            detail += " — overloaded"
        vx = x0 + min(max(load, 100.0), axis_max) * scale + 8
        svg.text(vx, y + bar_h / 2 + 4, value, 12.5, bold=True, fill=colour)
        svg.text(
            vx + text_width(value, 12.5, True) + 8,
            y + bar_h / 2 + 4,
            detail,
            11.5,
            fill=colour if r["overloaded"] else MUTED,
        )
    legend(svg, legend_items, x0, top + row_h * len(rows) + 48, x1 - x0 + right - 20)
    return svg.render()


#: Up to this many threads, the legend names threads; beyond, it names their nodes.
_LEGEND_THREADS = 12
_LEGEND_NODES = 30


def _series_legend(entries: list[dict[str, Any]], key: str) -> list[tuple[str, str, str]]:
    """Legend items for threads (``entries`` with ``key``, ``colour``, ``node_label`` and
    ``node_colour``): one per thread when there are few, else one per node."""
    threads: dict[str, str] = {}
    nodes: dict[str, str] = {}
    for entry in entries:
        threads.setdefault(entry[key], entry["colour"])
        nodes.setdefault(entry["node_label"] or entry[key], entry["node_colour"])
    if len(threads) <= _LEGEND_THREADS:
        return [("swatch", colour, _short_thread(name)) for name, colour in threads.items()]
    items = [("swatch", colour, name) for name, colour in list(nodes.items())[:_LEGEND_NODES]]
    if len(nodes) > _LEGEND_NODES:
        items.append(("text", "", f"… and {len(nodes) - _LEGEND_NODES} more nodes (see the tables)"))
    return items


def _short_thread(path: str) -> str:
    parts = path.split(".")
    return ".".join(parts[-2:]) if len(parts) >= 2 else path


def _axis_percent(
    svg: Svg, x0: float, scale: float, axis_max: float, step: float, y_top: float, y_bottom: float
) -> None:
    value = 0.0
    while value <= axis_max + 1e-9:
        x = x0 + value * scale
        if abs(value - 100) > 1e-9:
            svg.line(x, y_top - 6, x, y_bottom, stroke=GRID, stroke_width=1)
        svg.text(x, y_top - 12, f"{value:g} %", 11, anchor="middle", fill=MUTED)
        value += step
    x = x0 + 100 * scale
    svg.line(x, y_top - 6, x, y_bottom + 4, stroke=INK, stroke_width=1.5, stroke_dasharray="5 4")
    svg.text(x, y_bottom + 17, "capacity", 11, anchor="middle", fill=INK, bold=True)


def _percent_of(part: float, whole: float) -> float:
    """``100 * part / whole``, exactly and saturating: the view's numbers may be integers beyond
    the float range (a capacity of 1e308 GByte/s in KByte/s)."""
    return as_float(100 * Fraction(part) / Fraction(whole))


def bus_chart(rows: list[dict[str, Any]]) -> str:
    """Per-bus load bars: actual bandwidth against capacity (100 %), with the budget and the
    required budget (sum of what is bound) as markers."""
    label = "Bandwidth of every bus and virtual bus against its capacity"
    if not rows:
        return empty_chart(label, "No bus in the model", "chart chart-bus")
    loads = [r["load_percent"] for r in rows]
    for r in rows:
        cap = r["capacity_kbps"] or 0
        if cap > 0:
            loads += [_percent_of(r["budget_kbps"] or 0, cap), _percent_of(r["required_kbps"] or 0, cap)]
    axis_max, step = percent_scale(loads)
    left, right = 200.0, 250.0
    x0, x1 = left, WIDTH - right
    scale = (x1 - x0) / axis_max
    row_h, bar_h, top = 34.0, 20.0, 40.0
    height = top + row_h * len(rows) + 30 + 28
    svg = Svg(WIDTH, height, label, "chart chart-bus")
    hatch(svg, "bus-over", STATUS["error"])
    _axis_percent(svg, x0, scale, axis_max, step, top, top + row_h * len(rows))
    labels = distinct_labels([r["label"] for r in rows])
    for i, (r, text) in enumerate(zip(rows, labels, strict=True)):
        y = top + i * row_h + (row_h - bar_h) / 2
        indent = 14 * r["depth"]
        kind = "virtual bus" if r["virtual"] else "bus"
        svg.text(
            left - 10,
            y + bar_h / 2 + 4,
            fit(text, left - 20 - indent, 12.5),
            12.5,
            anchor="end",
            tip=f"{kind} {r['path']}",
        )
        svg.rect(x0, y, 100 * scale, bar_h, fill=TRACK, rx=3)
        cap = r["capacity_kbps"] or 0
        actual = r["actual_kbps"] or 0
        if cap <= 0:
            svg.text(
                x0 + 8, y + bar_h / 2 + 4, f"no bandwidth capacity; actual {rate(actual)}", 11.5, fill=MUTED
            )
            continue
        load = _percent_of(actual, cap)
        colour = "#4e79a7" if not r["virtual"] else "#76b7b2"
        svg.rect(
            x0, y, min(load, 100) * scale, bar_h, fill=colour, tip=f"actual {rate(actual)} ({load:.2f} %)"
        )
        if load > 100:
            svg.rect(
                x0 + 100 * scale,
                y,
                (min(load, axis_max) - 100) * scale,
                bar_h,
                fill="url(#bus-over)",
                stroke=STATUS["error"],
                stroke_width=1.5,
            )
        for key, name, mark in (
            ("budget_kbps", "budget", "#6a3d9a"),
            ("required_kbps", "required budget", "#b26a00"),
        ):
            v = r[key] or 0
            if v > 0:
                mx = x0 + min(_percent_of(v, cap), axis_max) * scale
                svg.line(mx, y - 4, mx, y + bar_h + 4, stroke=mark, stroke_width=3, tip=f"{name} {rate(v)}")
        text_colour = STATUS["error"] if r["overloaded"] else INK
        value = f"{load:.1f} %"
        vx = x0 + min(max(load, 100.0), axis_max) * scale + 8
        svg.text(vx, y + bar_h / 2 + 4, value, 12.5, bold=True, fill=text_colour)
        svg.text(
            vx + text_width(value, 12.5, True) + 8,
            y + bar_h / 2 + 4,
            f"{rate(actual)} of {rate(cap)}",
            11.5,
            fill=MUTED,
        )
    legend(
        svg,
        [
            ("swatch", "#4e79a7", "actual (bus)"),
            ("swatch", "#76b7b2", "actual (virtual bus)"),
            ("line", "#6a3d9a", "budget"),
            ("line", "#b26a00", "required budget"),
            ("hatch", "url(#bus-over)", "over capacity"),
        ],
        x0,
        top + row_h * len(rows) + 48,
        x1 - x0 + right - 20,
    )
    return svg.render()


# =============================================================================== Gantt chart


_UNIT_SECONDS = {"ps": 1e-12, "ns": 1e-9, "us": 1e-6, "ms": 1e-3, "sec": 1.0, "s": 1.0}


def _display_unit(horizon: float, unit: str) -> tuple[str, float]:
    """(unit to print, factor from the task set's unit) for an axis of length ``horizon``."""
    seconds = _UNIT_SECONDS.get(unit)
    if seconds is None:
        return unit, 1.0
    span = horizon * seconds
    for name, size in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)):
        if span >= 2 * size:
            return name, seconds / size
    return "ns", seconds / 1e-9


def gantt_chart(schedule: dict[str, Any]) -> str:
    """The simulated schedule: one row per core, the jobs as bars in their node's colour,
    releases as ticks, missed deadlines as red markers, the unsimulated end of a row hatched."""
    label = "Simulated schedule (Gantt chart) over one hyperperiod"
    if not schedule.get("available") or not schedule["rows"]:
        return empty_chart(label, schedule.get("reason") or "No schedule to show", "chart chart-gantt")
    rows = schedule["rows"]
    tasks = {t["name"]: t for t in schedule["tasks"]}
    horizon = float(schedule["horizon"]) or 1.0
    unit, factor = _display_unit(horizon, schedule["time_unit"])
    left, right = 200.0, 24.0
    x0, x1 = left, WIDTH - right
    scale = (x1 - x0) / horizon
    row_h, bar_h, top = 46.0, 22.0, 34.0
    legend_items = _series_legend(schedule["tasks"], "label")
    legend_items += [("tick", MUTED, "job release"), ("miss", STATUS["error"], "missed deadline")]
    plot_bottom = top + row_h * len(rows)
    height = plot_bottom + 72 + legend_height(legend_items, x1 - x0)
    svg = Svg(WIDTH, height, label, "chart chart-gantt")
    hatch(svg, "gantt-idle", MUTED)
    # time axis and grid
    step = nice_step(horizon * factor, 10) / factor
    t = 0.0
    while t <= horizon * (1 + 1e-9):
        x = x0 + t * scale
        svg.line(x, top - 4, x, plot_bottom, stroke=GRID, stroke_width=1)
        svg.text(x, plot_bottom + 16, f"{t * factor:g}", 11, anchor="middle", fill=MUTED)
        t += step
    svg.text((x0 + x1) / 2, plot_bottom + 34, f"time ({unit})", 12, anchor="middle", fill=INK, bold=True)
    row_index = {}
    for i, row in enumerate(rows):
        y = top + i * row_h
        row_index[(row["processor"], row["core"])] = i
        if i % 2 == 0:
            svg.rect(x0, y, x1 - x0, row_h, fill="#f7f9fb")
        svg.text(
            left - 10,
            y + row_h / 2 + 2,
            fit(row["label"].split(".")[-1], left - 20, 12.5, True),
            12.5,
            anchor="end",
            bold=True,
            tip=f"{row['label']} ({row['scheduler']})",
        )
        svg.text(
            left - 10,
            y + row_h / 2 + 16,
            fit(f"{len(row['tasks'])} task{'s' if len(row['tasks']) != 1 else ''}", left - 20, 10.5),
            10.5,
            anchor="end",
            fill=MUTED,
        )
        row_horizon = float(row["horizon"] or horizon)
        if row_horizon < horizon:
            svg.rect(
                x0 + row_horizon * scale,
                y + 4,
                (horizon - row_horizon) * scale,
                row_h - 8,
                fill="url(#gantt-idle)",
                tip="not simulated",
            )
    domain_of = {}
    for row in rows:
        for name in row["tasks"]:
            domain_of[name] = (row["processor"], row["core"])
    for start, end, task_name, job, processor, core in schedule["intervals"]:
        i = row_index.get((processor, core))
        if i is None:
            continue
        task = tasks.get(task_name, {"colour": "#888888", "label": task_name})
        y = top + i * row_h + (row_h - bar_h) / 2 - 4
        x = x0 + float(start) * scale
        w = max((float(end) - float(start)) * scale, 1.0)
        tip = f"{task['label']} job {job}: {float(start) * factor:g}–{float(end) * factor:g} {unit}"
        svg.rect(x, y, w, bar_h, fill=task["colour"], stroke="#ffffff", stroke_width=0.6, tip=tip)
        name = _short_thread(task["label"])
        if w > text_width(name, 10.5) + 8:
            svg.text(x + 4, y + bar_h / 2 + 4, name, 10.5, fill="#ffffff" if _dark(task["colour"]) else INK)
    for task_name, release in schedule["releases"]:
        i = row_index.get(domain_of.get(task_name, ("", "")))
        if i is None:
            continue
        x = x0 + float(release) * scale
        y = top + i * row_h + (row_h - bar_h) / 2 - 4 + bar_h
        svg.line(x, y + 1, x, y + 8, stroke=tasks.get(task_name, {}).get("colour", MUTED), stroke_width=1.5)
    for miss in schedule["misses"]:
        i = row_index.get(domain_of.get(miss["task"], ("", "")))
        if i is None or miss["deadline"] is None:
            continue
        x = x0 + float(miss["deadline"]) * scale
        y = top + i * row_h
        label_text = tasks.get(miss["task"], {}).get("label", miss["task"])
        done = (
            "unfinished"
            if miss["completion"] is None
            else f"done at {float(miss['completion']) * factor:g} {unit}"
        )
        when = f"{float(miss['deadline']) * factor:g} {unit}"
        tip = f"{label_text} job {miss['job']} missed its deadline at {when} ({done})"
        svg.line(x, y + 2, x, y + row_h - 2, stroke=STATUS["error"], stroke_width=2.5, tip=tip)
        svg.el("path", tip=tip, d=f"M{num(x - 6)} {num(y + 1)}h12l-6 9z", fill=STATUS["error"])
    svg.line(x0, top - 4, x0, plot_bottom, stroke=INK, stroke_width=1)
    svg.line(x0, plot_bottom, x1, plot_bottom, stroke=INK, stroke_width=1)
    legend(svg, legend_items, x0, plot_bottom + 62, x1 - x0)
    return svg.render()


def _dark(colour: str) -> bool:
    r, g, b = (int(colour[i : i + 2], 16) for i in (1, 3, 5))
    return 0.299 * r + 0.587 * g + 0.114 * b < 150

"""The report's charts as hand-written SVG.

Why hand-written SVG and not matplotlib: the page must be static, self-contained and
byte-for-byte reproducible. Four chart kinds (horizontal load bars, a Gantt chart, an
architecture diagram) are a few hundred lines of plain SVG, scale to any screen, keep their text
selectable and searchable, carry tooltips (``<title>``) without JavaScript, and need nothing
beyond the standard library. matplotlib would be a large new dependency (with numpy and a font
cache), embeds its own fonts or rasters, stamps dates and random ids into its SVG unless tamed,
and draws neither a hardware/software architecture nor a Gantt chart out of the box.

Every function takes the JSON-ready data of :mod:`rosaadl.exporters.report.view` and returns one
``<svg>`` element as a string; every text is escaped, every number is written with at most two
decimals, so the output is deterministic.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from fractions import Fraction
from typing import Any

from markupsafe import escape

from rosaadl.analysis.rendering import as_float

__all__ = [
    "FONT",
    "STATUS",
    "cpu_chart",
    "bus_chart",
    "gantt_chart",
    "architecture_diagram",
    "text_width",
]

FONT = "'DejaVu Sans', 'Liberation Sans', Arial, Helvetica, sans-serif"
#: Colours of the verdicts, used for the same meaning everywhere on the page.
STATUS = {"ok": "#2e7d32", "warning": "#b26a00", "error": "#c62828"}
_INK = "#1f2933"
_MUTED = "#5f6b7a"
_GRID = "#d9dee5"
_TRACK = "#eef1f5"
_WIDTH = 1120


# =============================================================================== SVG writing


def _n(value: float) -> str:
    """A coordinate with at most two decimals and no trailing zeros."""
    if not math.isfinite(value):
        value = 0.0
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def text_width(text: str, size: float, bold: bool = False) -> float:
    """An estimate of the rendered width of ``text`` (DejaVu Sans is about 0.6 em per glyph)."""
    return len(text) * size * (0.64 if bold else 0.58)


def _fit(text: str, width: float, size: float, bold: bool = False) -> str:
    """``text`` shortened with an ellipsis to fit ``width``."""
    if text_width(text, size, bold) <= width:
        return text
    keep = max(1, int(width / (size * (0.64 if bold else 0.58))) - 1)
    return text[:keep] + "…"


class _Svg:
    def __init__(self, width: float, height: float, label: str, css_class: str) -> None:
        self.width = width
        self.height = height
        self.label = label
        self.css_class = css_class
        self.parts: list[str] = []

    @staticmethod
    def _attrs(attrs: dict[str, Any]) -> str:
        out = []
        for key, value in attrs.items():
            if value is None:
                continue
            name = key.rstrip("_").replace("_", "-")
            text = _n(value) if isinstance(value, float) else str(value)
            out.append(f' {name}="{escape(text)}"')
        return "".join(out)

    def raw(self, text: str) -> None:
        self.parts.append(text)

    def el(self, tag: str, text: str | None = None, tip: str | None = None, **attrs: Any) -> None:
        inner = ""
        if text is not None:
            inner += str(escape(text))
        if tip:
            inner += f"<title>{escape(tip)}</title>"
        if inner:
            self.parts.append(f"<{tag}{self._attrs(attrs)}>{inner}</{tag}>")
        else:
            self.parts.append(f"<{tag}{self._attrs(attrs)}/>")

    def rect(self, x: float, y: float, w: float, h: float, **attrs: Any) -> None:
        self.el("rect", x=float(x), y=float(y), width=float(max(w, 0.0)), height=float(max(h, 0.0)), **attrs)

    def line(self, x1: float, y1: float, x2: float, y2: float, **attrs: Any) -> None:
        self.el("line", x1=float(x1), y1=float(y1), x2=float(x2), y2=float(y2), **attrs)

    def text(
        self,
        x: float,
        y: float,
        text: str,
        size: float = 12,
        *,
        anchor: str = "start",
        bold: bool = False,
        fill: str = _INK,
        tip: str | None = None,
        **attrs: Any,
    ) -> None:
        self.el(
            "text",
            text,
            tip=tip,
            x=float(x),
            y=float(y),
            font_size=float(size),
            text_anchor=anchor if anchor != "start" else None,
            font_weight="bold" if bold else None,
            fill=fill,
            **attrs,
        )

    def open(self, tag: str, **attrs: Any) -> None:
        self.parts.append(f"<{tag}{self._attrs(attrs)}>")

    def close(self, tag: str) -> None:
        self.parts.append(f"</{tag}>")

    def render(self) -> str:
        head = (
            f'<svg class="{escape(self.css_class)}" role="img" '
            f'viewBox="0 0 {_n(self.width)} {_n(self.height)}" width="{_n(self.width)}" '
            f'height="{_n(self.height)}" font-family="{escape(FONT)}" aria-label="{escape(self.label)}">'
            f"<title>{escape(self.label)}</title>"
        )
        return head + "".join(self.parts) + "</svg>"


def _hatch(svg: _Svg, pattern_id: str, colour: str) -> None:
    svg.raw(
        f'<defs><pattern id="{pattern_id}" width="6" height="6" patternUnits="userSpaceOnUse" '
        f'patternTransform="rotate(45)"><rect width="6" height="6" fill="{colour}" fill-opacity="0.18"/>'
        f'<line x1="0" y1="0" x2="0" y2="6" stroke="{colour}" stroke-width="3"/></pattern></defs>'
    )


def _nice_step(span: float, target: int = 8) -> float:
    """A 1-2-5 step giving about ``target`` ticks over ``span``."""
    if span <= 0:
        return 1.0
    raw = span / target
    power = 10 ** math.floor(math.log10(raw))
    for factor in (1, 2, 2.5, 5, 10):
        if raw <= factor * power:
            return factor * power
    return 10 * power


def _percent_scale(loads: Iterable[float | None]) -> tuple[float, float]:
    """(axis maximum, tick step) in %: at least 100, with room for the largest load."""
    top = max([100.0, *[v for v in loads if v is not None]])
    step = 25.0 if top <= 200 else _nice_step(top, 8)
    if top <= 100:
        return 100.0, step
    return math.ceil(top * 1.04 / step) * step, step


def _distinct_labels(paths: Sequence[str]) -> list[str]:
    """The shortest trailing part of each dotted path that still tells it from the others."""
    labels = []
    for path in paths:
        parts = path.split(".")
        for keep in range(1, len(parts) + 1):
            tail = ".".join(parts[-keep:])
            clash = any(other != path and (other == tail or other.endswith("." + tail)) for other in paths)
            if not clash:
                labels.append(tail)
                break
        else:
            labels.append(path)
    return labels


def _rate(kbps: float | None) -> str:
    """KB/s (1000 bytes per second, as OSATE prints them) in a readable unit."""
    if kbps is None:
        return "-"
    if kbps >= 1000:
        return f"{kbps / 1000:.1f} MB/s"
    if kbps >= 1:
        return f"{kbps:.1f} KB/s"
    return f"{kbps * 1000:.0f} B/s"


def _legend_height(items: list[tuple[str, str, str]], width: float) -> float:
    """The height :func:`_legend` takes for ``items`` wrapped to ``width``."""
    x, lines = 0.0, 1
    for _kind, _colour, label in items:
        w = 22 + text_width(label, 11.5) + 18
        if x + w > width and x > 0:
            x = 0.0
            lines += 1
        x += w
    return 20.0 * lines


def _legend(svg: _Svg, items: list[tuple[str, str, str]], x0: float, y0: float, width: float) -> float:
    """Swatch legend, wrapped to ``width``; items are (kind, colour, label). Returns the height."""
    x, y = x0, y0
    for kind, colour, label in items:
        w = 22 + text_width(label, 11.5) + 18
        if x + w > x0 + width and x > x0:
            x = x0
            y += 20
        if kind == "swatch":
            svg.rect(x, y - 10, 14, 12, fill=colour, rx=2)
        elif kind == "hatch":
            svg.rect(x, y - 10, 14, 12, fill=colour, stroke=STATUS["error"], stroke_width=1)
        elif kind == "dash":
            svg.line(x, y - 4, x + 16, y - 4, stroke=colour, stroke_width=2, stroke_dasharray="4 3")
        elif kind == "miss":
            svg.el("path", d=f"M{_n(x + 1)} {_n(y - 11)}h12l-6 10z", fill=STATUS["error"])
        elif kind == "tick":
            svg.line(x + 7, y - 11, x + 7, y + 1, stroke=colour, stroke_width=1.5)
        elif kind == "line":
            svg.line(x, y - 4, x + 16, y - 4, stroke=colour, stroke_width=2)
        svg.text(x + 22, y, label, 11.5, fill=_INK)
        x += w
    return y - y0 + 20


def _empty(label: str, message: str, css_class: str) -> str:
    svg = _Svg(_WIDTH, 60, label, css_class)
    svg.rect(0.5, 0.5, _WIDTH - 1, 59, fill="#f7f9fb", stroke=_GRID, rx=6)
    svg.text(_WIDTH / 2, 35, message, 13, anchor="middle", fill=_MUTED)
    return svg.render()


# =============================================================================== load bars


def cpu_chart(rows: list[dict[str, Any]]) -> str:
    """Per-processor load bars against capacity: stacked by thread in the node's colour, a
    dashed 100 % line, the part beyond capacity hatched red."""
    label = "CPU load of every processor and core against its capacity"
    if not rows:
        return _empty(label, "No processor in the model", "chart chart-cpu")
    axis_max, step = _percent_scale(r["load_percent"] for r in rows)
    left, right = 200.0, 230.0
    x0, x1 = left, _WIDTH - right
    scale = (x1 - x0) / axis_max
    row_h, bar_h, top = 34.0, 20.0, 40.0
    legend_items = _series_legend([s for r in rows for s in r["segments"]], "thread")
    legend_items.append(("hatch", "url(#cpu-over)", "over capacity"))
    height = top + row_h * len(rows) + 58 + _legend_height(legend_items, x1 - x0 + right - 20)
    svg = _Svg(_WIDTH, height, label, "chart chart-cpu")
    _hatch(svg, "cpu-over", STATUS["error"])
    _axis_percent(svg, x0, scale, axis_max, step, top, top + row_h * len(rows))
    labels = _distinct_labels([r["label"] + (f" {r['mode']}" if r["mode"] else "") for r in rows])
    for i, (r, text) in enumerate(zip(rows, labels, strict=True)):
        y = top + i * row_h + (row_h - bar_h) / 2
        bold = bool(r["cores"])
        svg.text(
            left - 10,
            y + bar_h / 2 + 4,
            _fit(text, left - 20, 12.5, bold),
            12.5,
            anchor="end",
            bold=bold,
            tip=r["path"],
        )
        svg.rect(x0, y, 100 * scale, bar_h, fill=_TRACK, rx=3)
        load = r["load_percent"]
        if r["capacity_mips"] in (0, None) and load is None:
            svg.text(x0 + 8, y + bar_h / 2 + 4, "no MIPS capacity", 11.5, fill=_MUTED)
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
        colour = STATUS["error"] if r["overloaded"] else (STATUS["warning"] if load > 90 else _INK)
        value = f"{load:.1f} %"
        detail = (
            f"{_mips(r['demand_mips'])} of {_mips(r['capacity_mips'])} MIPS"
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
            fill=colour if r["overloaded"] else _MUTED,
        )
    _legend(svg, legend_items, x0, top + row_h * len(rows) + 48, x1 - x0 + right - 20)
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


def _mips(value: float | None) -> str:
    if value is None:
        return "-"
    if value == 0:
        return "0"
    return f"{value:.0f}" if abs(value) >= 100 else f"{value:.2f}"


def _short_thread(path: str) -> str:
    parts = path.split(".")
    return ".".join(parts[-2:]) if len(parts) >= 2 else path


def _axis_percent(
    svg: _Svg, x0: float, scale: float, axis_max: float, step: float, y_top: float, y_bottom: float
) -> None:
    value = 0.0
    while value <= axis_max + 1e-9:
        x = x0 + value * scale
        if abs(value - 100) > 1e-9:
            svg.line(x, y_top - 6, x, y_bottom, stroke=_GRID, stroke_width=1)
        svg.text(x, y_top - 12, f"{value:g} %", 11, anchor="middle", fill=_MUTED)
        value += step
    x = x0 + 100 * scale
    svg.line(x, y_top - 6, x, y_bottom + 4, stroke=_INK, stroke_width=1.5, stroke_dasharray="5 4")
    svg.text(x, y_bottom + 17, "capacity", 11, anchor="middle", fill=_INK, bold=True)


def _percent_of(part: float, whole: float) -> float:
    """``100 * part / whole``, exactly and saturating: the view's numbers may be integers beyond
    the float range (a capacity of 1e308 GByte/s in KByte/s)."""
    return as_float(100 * Fraction(part) / Fraction(whole))


def bus_chart(rows: list[dict[str, Any]]) -> str:
    """Per-bus load bars: actual bandwidth against capacity (100 %), with the budget and the
    required budget (sum of what is bound) as markers."""
    label = "Bandwidth of every bus and virtual bus against its capacity"
    if not rows:
        return _empty(label, "No bus in the model", "chart chart-bus")
    loads = [r["load_percent"] for r in rows]
    for r in rows:
        cap = r["capacity_kbps"] or 0
        if cap > 0:
            loads += [_percent_of(r["budget_kbps"] or 0, cap), _percent_of(r["required_kbps"] or 0, cap)]
    axis_max, step = _percent_scale(loads)
    left, right = 200.0, 250.0
    x0, x1 = left, _WIDTH - right
    scale = (x1 - x0) / axis_max
    row_h, bar_h, top = 34.0, 20.0, 40.0
    height = top + row_h * len(rows) + 30 + 28
    svg = _Svg(_WIDTH, height, label, "chart chart-bus")
    _hatch(svg, "bus-over", STATUS["error"])
    _axis_percent(svg, x0, scale, axis_max, step, top, top + row_h * len(rows))
    labels = _distinct_labels([r["label"] for r in rows])
    for i, (r, text) in enumerate(zip(rows, labels, strict=True)):
        y = top + i * row_h + (row_h - bar_h) / 2
        indent = 14 * r["depth"]
        kind = "virtual bus" if r["virtual"] else "bus"
        svg.text(
            left - 10,
            y + bar_h / 2 + 4,
            _fit(text, left - 20 - indent, 12.5),
            12.5,
            anchor="end",
            tip=f"{kind} {r['path']}",
        )
        svg.rect(x0, y, 100 * scale, bar_h, fill=_TRACK, rx=3)
        cap = r["capacity_kbps"] or 0
        actual = r["actual_kbps"] or 0
        if cap <= 0:
            svg.text(
                x0 + 8, y + bar_h / 2 + 4, f"no bandwidth capacity; actual {_rate(actual)}", 11.5, fill=_MUTED
            )
            continue
        load = _percent_of(actual, cap)
        colour = "#4e79a7" if not r["virtual"] else "#76b7b2"
        svg.rect(
            x0, y, min(load, 100) * scale, bar_h, fill=colour, tip=f"actual {_rate(actual)} ({load:.2f} %)"
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
                svg.line(mx, y - 4, mx, y + bar_h + 4, stroke=mark, stroke_width=3, tip=f"{name} {_rate(v)}")
        text_colour = STATUS["error"] if r["overloaded"] else _INK
        value = f"{load:.1f} %"
        vx = x0 + min(max(load, 100.0), axis_max) * scale + 8
        svg.text(vx, y + bar_h / 2 + 4, value, 12.5, bold=True, fill=text_colour)
        svg.text(
            vx + text_width(value, 12.5, True) + 8,
            y + bar_h / 2 + 4,
            f"{_rate(actual)} of {_rate(cap)}",
            11.5,
            fill=_MUTED,
        )
    _legend(
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
        return _empty(label, schedule.get("reason") or "No schedule to show", "chart chart-gantt")
    rows = schedule["rows"]
    tasks = {t["name"]: t for t in schedule["tasks"]}
    horizon = float(schedule["horizon"]) or 1.0
    unit, factor = _display_unit(horizon, schedule["time_unit"])
    left, right = 200.0, 24.0
    x0, x1 = left, _WIDTH - right
    scale = (x1 - x0) / horizon
    row_h, bar_h, top = 46.0, 22.0, 34.0
    legend_items = _series_legend(schedule["tasks"], "label")
    legend_items += [("tick", _MUTED, "job release"), ("miss", STATUS["error"], "missed deadline")]
    plot_bottom = top + row_h * len(rows)
    height = plot_bottom + 72 + _legend_height(legend_items, x1 - x0)
    svg = _Svg(_WIDTH, height, label, "chart chart-gantt")
    _hatch(svg, "gantt-idle", _MUTED)
    # time axis and grid
    step = _nice_step(horizon * factor, 10) / factor
    t = 0.0
    while t <= horizon * (1 + 1e-9):
        x = x0 + t * scale
        svg.line(x, top - 4, x, plot_bottom, stroke=_GRID, stroke_width=1)
        svg.text(x, plot_bottom + 16, f"{t * factor:g}", 11, anchor="middle", fill=_MUTED)
        t += step
    svg.text((x0 + x1) / 2, plot_bottom + 34, f"time ({unit})", 12, anchor="middle", fill=_INK, bold=True)
    row_index = {}
    for i, row in enumerate(rows):
        y = top + i * row_h
        row_index[(row["processor"], row["core"])] = i
        if i % 2 == 0:
            svg.rect(x0, y, x1 - x0, row_h, fill="#f7f9fb")
        svg.text(
            left - 10,
            y + row_h / 2 + 2,
            _fit(row["label"].split(".")[-1], left - 20, 12.5, True),
            12.5,
            anchor="end",
            bold=True,
            tip=f"{row['label']} ({row['scheduler']})",
        )
        svg.text(
            left - 10,
            y + row_h / 2 + 16,
            _fit(f"{len(row['tasks'])} task{'s' if len(row['tasks']) != 1 else ''}", left - 20, 10.5),
            10.5,
            anchor="end",
            fill=_MUTED,
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
            svg.text(x + 4, y + bar_h / 2 + 4, name, 10.5, fill="#ffffff" if _dark(task["colour"]) else _INK)
    for task_name, release in schedule["releases"]:
        i = row_index.get(domain_of.get(task_name, ("", "")))
        if i is None:
            continue
        x = x0 + float(release) * scale
        y = top + i * row_h + (row_h - bar_h) / 2 - 4 + bar_h
        svg.line(x, y + 1, x, y + 8, stroke=tasks.get(task_name, {}).get("colour", _MUTED), stroke_width=1.5)
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
        svg.el("path", tip=tip, d=f"M{_n(x - 6)} {_n(y + 1)}h12l-6 9z", fill=STATUS["error"])
    svg.line(x0, top - 4, x0, plot_bottom, stroke=_INK, stroke_width=1)
    svg.line(x0, plot_bottom, x1, plot_bottom, stroke=_INK, stroke_width=1)
    _legend(svg, legend_items, x0, plot_bottom + 62, x1 - x0)
    return svg.render()


def _dark(colour: str) -> bool:
    r, g, b = (int(colour[i : i + 2], 16) for i in (1, 3, 5))
    return 0.299 * r + 0.587 * g + 0.114 * b < 150


# =============================================================================== architecture


_NODE_W, _NODE_H = 170.0, 74.0
_NODE_MIN_W = 136.0
_ROW_GAP = 64.0  # between stacked nodes: room for the labels of the topics above a row
_CORE_W, _CORE_H, _CORE_GAP = 118.0, 66.0, 10.0
_PAD, _HEAD = 12.0, 24.0


def _ranks(keys: list[str], edges: list[tuple[str, str]]) -> dict[str, int]:
    """Longest-path layers of the topic graph (edges that close a cycle are ignored)."""
    succ: dict[str, list[str]] = {k: [] for k in keys}
    for a, b in edges:
        if a in succ and b in succ and b not in succ[a]:
            succ[a].append(b)
    order: list[str] = []
    state: dict[str, int] = {}
    back: set[tuple[str, str]] = set()
    for start in keys:
        if start in state:
            continue
        stack = [(start, iter(succ[start]))]
        state[start] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                state[node] = 2
                order.append(node)
                stack.pop()
            elif state.get(nxt) == 1:
                back.add((node, nxt))
            elif nxt not in state:
                state[nxt] = 1
                stack.append((nxt, iter(succ[nxt])))
    rank = dict.fromkeys(keys, 0)
    for node in reversed(order):
        for nxt in succ[node]:
            if (node, nxt) not in back:
                rank[nxt] = max(rank[nxt], rank[node] + 1)
    return rank


def _box_size(box: dict[str, Any]) -> tuple[float, float]:
    widths, heights = [], []
    if box["cores"]:
        n = len(box["cores"])
        widths.append(n * _CORE_W + (n - 1) * _CORE_GAP)
        heights.append(_CORE_H)
    for child in box["children"]:
        w, h = _box_size(child)
        widths.append(w)
        heights.append(h)
    inner_w = sum(widths) + _CORE_GAP * 2 * max(len(widths) - 1, 0)
    inner_w = max(inner_w, text_width(box["name"], 12.5, True) + 8)
    return inner_w + 2 * _PAD, max(heights, default=0) + _HEAD + _PAD + (4 if box["children"] else 0)


def _place_box(
    svg: _Svg,
    box: dict[str, Any],
    x: float,
    y: float,
    depth: int,
    cores: dict[str, tuple[float, float]],
    loads: dict[str, dict[str, Any]],
) -> float:
    w, h = _box_size(box)
    fills = ("#f4f6f9", "#e9edf2", "#dfe5ec", "#d5dce5")
    svg.rect(
        x,
        y,
        w,
        h,
        fill=fills[min(depth, 3)],
        stroke="#9aa5b1",
        stroke_width=1,
        rx=8,
        tip=f"{box['path']} ({box['classifier']})" if box["classifier"] else box["path"],
    )
    svg.text(
        x + _PAD,
        y + 17,
        _fit(box["name"], w - 2 * _PAD, 12.5, True),
        12.5,
        bold=True,
        fill=_INK,
        tip=box["classifier"] or None,
    )
    cx = x + _PAD
    cy = y + _HEAD
    if box["cores"]:
        for core in box["cores"]:
            _core_box(svg, core, cx, cy, loads.get(core["path"]))
            cores[core["path"]] = (cx + _CORE_W / 2, cy)
            cx += _CORE_W + _CORE_GAP
        cx += _CORE_GAP
    for child in box["children"]:
        cw = _place_box(svg, child, cx, cy, depth + 1, cores, loads)
        cores[child["path"]] = (cx + cw / 2, cy)
        cx += cw + 2 * _CORE_GAP
    return w


def _core_box(svg: _Svg, core: dict[str, Any], x: float, y: float, load: dict[str, Any] | None) -> None:
    percent = load["load_percent"] if load else None
    over = bool(load and load["overloaded"])
    stroke = STATUS["error"] if over else "#7b8794"
    svg.rect(
        x,
        y,
        _CORE_W,
        _CORE_H,
        fill="#ffffff",
        stroke=stroke,
        stroke_width=2.5 if over else 1.2,
        rx=5,
        tip=f"{core['path']} ({core['classifier']})",
    )
    svg.text(
        x + _CORE_W / 2, y + 17, _fit(core["name"], _CORE_W - 8, 12, True), 12, anchor="middle", bold=True
    )
    capacity = load["capacity_mips"] if load else None
    svg.text(
        x + _CORE_W / 2,
        y + 32,
        f"{_mips(capacity)} MIPS" if capacity else "no capacity",
        10.5,
        anchor="middle",
        fill=_MUTED,
    )
    bx, by, bw, bh = x + 8, y + 42, _CORE_W - 16, 8
    svg.rect(bx, by, bw, bh, fill=_TRACK, rx=2)
    if percent is not None:
        colour = STATUS["error"] if over else (STATUS["warning"] if percent > 90 else STATUS["ok"])
        svg.rect(bx, by, bw * min(percent, 100) / 100, bh, fill=colour, rx=2)
        svg.text(
            x + _CORE_W / 2,
            y + 62,
            f"{percent:.1f} %",
            10.5,
            anchor="middle",
            bold=over,
            fill=colour if over else _INK,
        )


def architecture_diagram(arch: dict[str, Any], cpu: list[dict[str, Any]]) -> str:
    """ROS nodes and devices with their topics (top), the hardware tree down to the cores with
    their loads (bottom), and the bindings of nodes to cores (dashed, in the node's colour).

    Nodes are placed in columns by their position along the topic graph (sources left); more
    columns than fit the width wrap into further bands, as text does."""
    label = "Architecture: ROS nodes, topics, boards, cores and bindings"
    nodes = arch["nodes"]
    if not nodes and not arch["hardware"]:
        return _empty(label, "No node and no processor in the model", "chart chart-architecture")
    keys = [n["key"] for n in nodes]
    by_key = {n["key"]: n for n in nodes}
    edges = [
        (t["source"], t["target"]) for t in arch["topics"] if t["source"] in by_key and t["target"] in by_key
    ]
    rank = _ranks(keys, edges)
    linked = {k for e in edges for k in e}
    columns: dict[int, list[str]] = {}
    for key in keys:
        if key in linked:
            columns.setdefault(rank[key], []).append(key)
    loose = [k for k in keys if k not in linked]
    next_col = max(columns, default=-1) + 1
    for i in range(0, len(loose), 4):
        columns[next_col] = loose[i : i + 4]
        next_col += 1
    ordered = [columns[c] for c in sorted(columns)]
    # a topic's label sits above the row, centred on the gap it crosses: it may be as wide as a
    # node and a gap together
    label_w = [
        max(text_width(line, 11, i == 0) for i, line in enumerate(_edge_label(t))) for t in arch["topics"]
    ]
    widest = max(label_w, default=0)
    gap = min(max(widest - _NODE_W + 24, 64.0), 240.0)
    # narrower boxes (down to _NODE_MIN_W) rather than a second band
    room = _WIDTH - 40
    node_w = _NODE_W
    if ordered:
        node_w = min(_NODE_W, max(_NODE_MIN_W, (room - (len(ordered) - 1) * gap) / len(ordered)))
        gap = min(max(widest - node_w + 24, 64.0), 240.0)
    per_band = max(1, int((room + gap) / (node_w + gap) + 1e-6))
    bands = [ordered[i : i + per_band] for i in range(0, len(ordered), per_band)]
    band_cols = max((len(b) for b in bands), default=0)
    sw_width = band_cols * node_w + max(band_cols - 1, 0) * gap
    hw_sizes = [_box_size(b) for b in arch["hardware"]]
    hw_width = sum(w for w, _ in hw_sizes) + 24 * max(len(hw_sizes) - 1, 0)
    hw_height = max((h for _, h in hw_sizes), default=0)
    width = max(_WIDTH, sw_width + 40, hw_width + 40)
    pos: dict[str, tuple[float, float]] = {}
    band_of: dict[str, int] = {}
    sx = (width - sw_width) / 2
    y = 96.0
    for b, band in enumerate(bands):
        tallest = max(len(col) for col in band)
        for c, col in enumerate(band):
            for r, key in enumerate(col):
                pos[key] = (sx + c * (node_w + gap), y + r * (_NODE_H + _ROW_GAP))
                band_of[key] = b
        y += tallest * (_NODE_H + _ROW_GAP) - _ROW_GAP + 96
    hw_top = y + 14 if nodes else 60.0
    height = hw_top + hw_height + 70
    svg = _Svg(width, height, label, "chart chart-architecture")
    svg.raw(
        '<defs><marker id="arch-arrow" viewBox="0 0 10 10" refX="9" refY="5" '
        'markerWidth="7" markerHeight="7" '
        f'orient="auto-start-reverse"><path d="M0 0L10 5L0 10z" fill="{_INK}"/></marker>'
        '<marker id="arch-bind" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="6" markerHeight="6" '
        f'orient="auto-start-reverse"><path d="M0 0L10 5L0 10z" fill="{_MUTED}"/></marker></defs>'
    )
    if nodes:
        svg.text(20, 28, "ROS nodes and topics", 14, bold=True)
    # hardware
    core_pos: dict[str, tuple[float, float]] = {}
    loads = {r["path"]: r for r in cpu}
    hx = (width - hw_width) / 2
    for box, (bw, _bh) in zip(arch["hardware"], hw_sizes, strict=True):
        _place_box(svg, box, hx, hw_top, 0, core_pos, loads)
        core_pos.setdefault(box["path"], (hx + bw / 2, hw_top))
        hx += bw + 24
    # bindings, under the nodes; drawn when the nodes fit in one band (else they would cross the
    # other bands: each node box names its core instead)
    per_target: dict[str, int] = {}
    bound_to: dict[str, list[str]] = {}
    for b in arch["bindings"]:
        bound_to.setdefault(b["node"], []).append(b["processor"].rpartition(".")[2])
    for b in arch["bindings"] if len(bands) == 1 else []:
        if b["node"] not in pos or b["processor"] not in core_pos:
            continue
        nx, ny = pos[b["node"]]
        tx, ty = core_pos[b["processor"]]
        k = per_target.get(b["processor"], 0)
        per_target[b["processor"]] = k + 1
        tx += ((k + 1) // 2) * 10 * (1 if k % 2 else -1)
        ax, ay = nx + node_w / 2, ny + _NODE_H
        mid = (ay + ty) / 2
        colour = by_key[b["node"]]["colour"]
        curve = f"M{_n(ax)} {_n(ay)}C{_n(ax)} {_n(mid)} {_n(tx)} {_n(mid)} {_n(tx)} {_n(ty - 2)}"
        svg.el("path", d=curve, fill="none", stroke="#ffffff", stroke_width=6, stroke_opacity=0.85)
        svg.el(
            "path",
            tip=f"{b['node']} is bound to {b['processor']}",
            d=curve,
            fill="none",
            stroke=colour,
            stroke_width=2.2,
            stroke_dasharray="6 4",
            marker_end="url(#arch-bind)",
        )
    # topics
    for t in arch["topics"]:
        if t["source"] not in pos or t["target"] not in pos:
            continue
        _topic(svg, t, pos[t["source"]], pos[t["target"]], band_of[t["source"]], band_of[t["target"]], node_w)
    # node boxes on top
    for key, (x, y) in pos.items():
        _node_box(svg, by_key[key], x, y, node_w, bound_to.get(key, []))
    _legend(
        svg,
        [
            ("line", _INK, "topic (port connection), with its data type and rate"),
            ("dash", _MUTED, "binding of a node to a core (Actual_Processor_Binding)"),
            ("swatch", STATUS["ok"], "core load"),
            ("swatch", STATUS["error"], "core over capacity"),
        ],
        20,
        height - 22,
        width - 40,
    )
    if arch["hardware"]:  # drawn last, with a white halo: binding lines cross this row
        svg.text(
            width - 20,
            hw_top - 14,
            "Hardware: robots, boards, SoCs, cores and their CPU load",
            14,
            anchor="end",
            bold=True,
            stroke="#ffffff",
            stroke_width=5,
            paint_order="stroke",
        )
    return svg.render()


def _topic(
    svg: _Svg,
    t: dict[str, Any],
    source: tuple[float, float],
    target: tuple[float, float],
    source_band: int,
    target_band: int,
    node_w: float,
) -> None:
    (ax, ay), (bx, by) = source, target
    lines = _edge_label(t)
    boxed = True
    if source_band != target_band:
        # to another band: leave from the bottom (or top) and enter from the top (or bottom)
        down = target_band > source_band
        x1, y1 = ax + node_w / 2, ay + (_NODE_H if down else 0)
        x2, y2 = bx + node_w / 2, by - 2 if down else by + _NODE_H + 2
        mid = (y1 + y2) / 2
        d = f"M{_n(x1)} {_n(y1)}C{_n(x1)} {_n(mid)} {_n(x2)} {_n(mid)} {_n(x2)} {_n(y2)}"
        lx, ly = (x1 + x2) / 2, mid - 13 * (len(lines) - 1) / 2
    elif bx > ax + 1:
        x1, y1 = ax + node_w, ay + _NODE_H / 2
        x2, y2 = bx - 2, by + _NODE_H / 2
        dx = (x2 - x1) / 2
        d = f"M{_n(x1)} {_n(y1)}C{_n(x1 + dx)} {_n(y1)} {_n(x2 - dx)} {_n(y2)} {_n(x2)} {_n(y2)}"
        lx = (x1 + x2) / 2
        if abs(ay - by) < 1:
            ly = ay - 8 - 13 * (len(lines) - 1)  # above the row, over the gap it crosses
            boxed = False
        else:
            ly = (y1 + y2) / 2 - 13 * (len(lines) - 1) / 2
    else:
        # backwards or within a column: an arc over the row
        x1, y1 = ax + node_w / 2, ay
        x2, y2 = bx + node_w / 2 + 10, by - 2
        lift = min(ay, by) - 50
        d = f"M{_n(x1)} {_n(y1)}C{_n(x1)} {_n(lift)} {_n(x2)} {_n(lift)} {_n(x2)} {_n(y2)}"
        lx, ly = (x1 + x2) / 2, lift - 13 * len(lines)
    tip = f"{t['label']} ({t['data_type']}) from {t['source']} to {t['target']}"
    svg.el("path", tip=tip, d=d, fill="none", stroke=_INK, stroke_width=1.8, marker_end="url(#arch-arrow)")
    if boxed:
        w = max(text_width(line, 11, i == 0) for i, line in enumerate(lines)) + 10
        svg.rect(lx - w / 2, ly - 12, w, 13 * len(lines) + 4, fill="#ffffff", fill_opacity=0.9, rx=3)
    for i, line in enumerate(lines):
        svg.text(
            lx,
            ly + 13 * i,
            line,
            11 if i == 0 else 10.5,
            anchor="middle",
            bold=i == 0,
            fill=_INK if i == 0 else _MUTED,
            tip=tip if i == 0 else None,
        )


def _node_box(svg: _Svg, n: dict[str, Any], x: float, y: float, node_w: float, cores: list[str]) -> None:
    device = n["kind"] == "device"
    svg.rect(
        x,
        y,
        node_w,
        _NODE_H,
        fill="#ffffff",
        stroke=n["colour"],
        stroke_width=2.5,
        stroke_dasharray="5 3" if device else None,
        rx=8,
        tip=f"{n['kind']} {n['key']} ({n['classifier']})",
    )
    if not device:
        svg.rect(x, y, 8, _NODE_H, fill=n["colour"], rx=3)
    inner = node_w - 24
    svg.text(x + 16, y + 20, _fit(n["name"], inner, 13, True), 13, bold=True, tip=n["key"])
    sub = n["classifier"].rpartition("::")[2] or n["kind"]
    svg.text(x + 16, y + 36, _fit(sub, inner, 10.5), 10.5, fill=_MUTED, tip=n["classifier"] or None)
    if device:
        svg.text(x + 16, y + 51, "device", 10.5, fill=_MUTED)
        return
    count = len(n["threads"])
    svg.text(x + 16, y + 51, f"ROS node · {count} thread{'s' if count != 1 else ''}", 10.5, fill=_MUTED)
    where = "on " + ", ".join(cores) if cores else "not bound"
    svg.text(
        x + 16,
        y + 66,
        _fit(where, inner, 10.5, True),
        10.5,
        bold=True,
        fill=_INK if cores else STATUS["error"],
    )


def _edge_label(topic: dict[str, Any]) -> list[str]:
    """The lines of a topic's label: its name (else its data type), then data type and rate,
    then the buses it is bound to."""
    first = topic["topic"] or topic["data_type"] or topic["label"]
    lines = [first]
    parts = []
    if topic["topic"] and topic["data_type"]:
        parts.append(topic["data_type"])
    if topic["kbps"]:
        parts.append(_rate(topic["kbps"]))
    if parts:
        lines.append(" · ".join(parts))
    if topic["buses"]:
        lines.append("via " + ", ".join(b.rpartition(".")[2] for b in topic["buses"]))
    return lines

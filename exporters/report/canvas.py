"""The drawing kit of the report's charts: an SVG writer, the page's colours and font, text
widths, axis steps, legends and the value formats the charts share.

Why hand-written SVG and not matplotlib: the page must be static, self-contained and
byte-for-byte reproducible. Four chart kinds (horizontal load bars, a Gantt chart, an
architecture diagram) are a few hundred lines of plain SVG, scale to any screen, keep their text
selectable and searchable, carry tooltips (``<title>``) without JavaScript, and need nothing
beyond the standard library. matplotlib would be a large new dependency (with numpy and a font
cache), embeds its own fonts or rasters, stamps dates and random ids into its SVG unless tamed,
and draws neither a hardware/software architecture nor a Gantt chart out of the box.

Every text is escaped and every number written with at most two decimals (:func:`num`), so
the output is deterministic.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

from markupsafe import escape

__all__ = [
    "FONT",
    "STATUS",
    "INK",
    "MUTED",
    "GRID",
    "TRACK",
    "WIDTH",
    "Svg",
    "num",
    "text_width",
    "fit",
    "hatch",
    "nice_step",
    "ms_axis",
    "percent_scale",
    "distinct_labels",
    "rate",
    "mips",
    "legend_height",
    "legend",
    "empty_chart",
]


FONT = "'DejaVu Sans', 'Liberation Sans', Arial, Helvetica, sans-serif"
#: Colours of the verdicts, used for the same meaning everywhere on the page.
STATUS = {"ok": "#2e7d32", "warning": "#b26a00", "error": "#c62828"}
INK = "#1f2933"
MUTED = "#5f6b7a"
GRID = "#d9dee5"
TRACK = "#eef1f5"
WIDTH = 1120


# =============================================================================== SVG writing


def num(value: float) -> str:
    """A coordinate with at most two decimals and no trailing zeros."""
    if not math.isfinite(value):
        value = 0.0
    text = f"{value:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def text_width(text: str, size: float, bold: bool = False) -> float:
    """An estimate of the rendered width of ``text`` (DejaVu Sans is about 0.6 em per glyph)."""
    return len(text) * size * (0.64 if bold else 0.58)


def fit(text: str, width: float, size: float, bold: bool = False) -> str:
    """``text`` shortened with an ellipsis to fit ``width``."""
    if text_width(text, size, bold) <= width:
        return text
    keep = max(1, int(width / (size * (0.64 if bold else 0.58))) - 1)
    return text[:keep] + "…"


class Svg:
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
            text = num(value) if isinstance(value, float) else str(value)
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
        fill: str = INK,
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
            f'viewBox="0 0 {num(self.width)} {num(self.height)}" width="{num(self.width)}" '
            f'height="{num(self.height)}" font-family="{escape(FONT)}" aria-label="{escape(self.label)}">'
            f"<title>{escape(self.label)}</title>"
        )
        return head + "".join(self.parts) + "</svg>"


def hatch(svg: Svg, pattern_id: str, colour: str) -> None:
    svg.raw(
        f'<defs><pattern id="{pattern_id}" width="6" height="6" patternUnits="userSpaceOnUse" '
        f'patternTransform="rotate(45)"><rect width="6" height="6" fill="{colour}" fill-opacity="0.18"/>'
        f'<line x1="0" y1="0" x2="0" y2="6" stroke="{colour}" stroke-width="3"/></pattern></defs>'
    )


def nice_step(span: float, target: int = 8) -> float:
    """A 1-2-5 step giving about ``target`` ticks over ``span``."""
    if span <= 0:
        return 1.0
    raw = span / target
    power = 10 ** math.floor(math.log10(raw))
    for factor in (1, 2, 2.5, 5, 10):
        if raw <= factor * power:
            return factor * power
    return 10 * power


def ms_axis(
    svg: Svg, x0: float, scale: float, axis: float, step: float, top: float, bottom: float, stroke: str
) -> None:
    """Vertical grid lines every ``step`` microseconds from 0 to ``axis`` (``scale`` pixels per
    µs from ``x0``, from ``top - 6`` to ``bottom``), labelled in milliseconds above ``top``."""
    tick = 0.0
    while tick <= axis + 1e-9:
        x = x0 + tick * scale
        svg.line(x, top - 6, x, bottom, stroke=stroke)
        svg.text(x, top - 10, f"{num(tick / 1000)} ms", 10.5, anchor="middle", fill=MUTED)
        tick += step


def percent_scale(loads: Iterable[float | None]) -> tuple[float, float]:
    """(axis maximum, tick step) in %: at least 100, with room for the largest load."""
    top = max([100.0, *[v for v in loads if v is not None]])
    step = 25.0 if top <= 200 else nice_step(top, 8)
    if top <= 100:
        return 100.0, step
    return math.ceil(top * 1.04 / step) * step, step


def distinct_labels(paths: Sequence[str]) -> list[str]:
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


def rate(kbps: float | None) -> str:
    """KB/s (1000 bytes per second, as OSATE prints them) in a readable unit."""
    if kbps is None:
        return "-"
    if kbps >= 1000:
        return f"{kbps / 1000:.1f} MB/s"
    if kbps >= 1:
        return f"{kbps:.1f} KB/s"
    return f"{kbps * 1000:.0f} B/s"


def legend_height(items: list[tuple[str, str, str]], width: float) -> float:
    """The height :func:`legend` takes for ``items`` wrapped to ``width``."""
    x, lines = 0.0, 1
    for _kind, _colour, label in items:
        w = 22 + text_width(label, 11.5) + 18
        if x + w > width and x > 0:
            x = 0.0
            lines += 1
        x += w
    return 20.0 * lines


def legend(svg: Svg, items: list[tuple[str, str, str]], x0: float, y0: float, width: float) -> float:
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
            svg.el("path", d=f"M{num(x + 1)} {num(y - 11)}h12l-6 10z", fill=STATUS["error"])
        elif kind == "tick":
            svg.line(x + 7, y - 11, x + 7, y + 1, stroke=colour, stroke_width=1.5)
        elif kind == "line":
            svg.line(x, y - 4, x + 16, y - 4, stroke=colour, stroke_width=2)
        svg.text(x + 22, y, label, 11.5, fill=INK)
        x += w
    return y - y0 + 20


def empty_chart(label: str, message: str, css_class: str) -> str:
    svg = Svg(WIDTH, 60, label, css_class)
    svg.rect(0.5, 0.5, WIDTH - 1, 59, fill="#f7f9fb", stroke=GRID, rx=6)
    svg.text(WIDTH / 2, 35, message, 13, anchor="middle", fill=MUTED)
    return svg.render()


def mips(value: float | None) -> str:
    if value is None:
        return "-"
    if value == 0:
        return "0"
    return f"{value:.0f}" if abs(value) >= 100 else f"{value:.2f}"

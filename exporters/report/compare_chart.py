"""The report's predicted-vs-measured chart: one bar pair per compared item (the analyses'
prediction above, the measurement below), the error in % beside it, a violated bound in the
error colour with the bound marked.

It draws ``analyses.compare.items`` of the report's view (the ``compare`` analysis, present when
``rosaadl analyze --compare`` ran); each item has its own unit, so each pair is scaled to its
own largest value and labelled with both numbers.
"""

from __future__ import annotations

from typing import Any

from rosaadl.exporters.report.canvas import INK, MUTED, STATUS, TRACK, WIDTH, Svg, fit, legend, num

__all__ = ["compare_chart"]

PREDICTED = "#4e79a7"
MEASURED = "#f28e2b"


def _error_text(item: dict[str, Any]) -> str:
    error = item.get("error_percent")
    text = "no prediction" if error is None else f"{error:+.1f} %"
    text += ", violated" if item.get("violated") else ""
    if item.get("bound") and item.get("measured") and not item["quantity"].endswith("_min_us"):
        text += f", bound ÷ measured {item['bound'] / item['measured']:.2f}"
    return text


def _label(item: dict[str, Any], root: str) -> str:
    head, dot, rest = item["path"].partition(".")
    path = rest if dot and head == root else item["path"]
    return f"{path} {item['quantity']}"


def compare_chart(items: list[dict[str, Any]], root: str = "") -> str:
    """Bar pairs of every compared item (empty string when there is no comparison)."""
    if not items:
        return ""
    label = "Predicted vs measured, one bar pair per item"
    left, right = 420.0, 200.0
    x0, x1 = left, WIDTH - right
    bar_h, gap, top = 11.0, 10.0, 16.0
    row_h = 2 * bar_h + 2 + gap
    svg = Svg(WIDTH, top + row_h * len(items) + 50, label, "chart chart-compare")
    for i, item in enumerate(items):
        y = top + i * row_h
        values = [
            float(v) for v in (item.get("predicted"), item["measured"], item.get("bound")) if v is not None
        ]
        scale = (x1 - x0) / (max(values) or 1.0)
        name = _label(item, root)
        svg.text(left - 10, y + bar_h + 3, fit(name, left - 20, 11.5), 11.5, anchor="end", tip=name)
        svg.rect(x0, y, x1 - x0, 2 * bar_h + 2, fill=TRACK)
        for j, (key, colour) in enumerate((("predicted", PREDICTED), ("measured", MEASURED))):
            value = item.get(key)
            if value is None:
                continue
            by = y + j * (bar_h + 2)
            svg.rect(x0, by, float(value) * scale, bar_h, fill=colour, tip=f"{key}: {num(float(value))}")
            svg.text(x0 + float(value) * scale + 4, by + bar_h - 2, num(float(value)), 10, fill=MUTED)
        if item.get("bound") is not None:
            bx = x0 + float(item["bound"]) * scale
            svg.line(
                bx, y - 2, bx, y + 2 * bar_h + 4, stroke="#000", stroke_width=2, tip=f"bound {item['bound']}"
            )
        colour = STATUS["error"] if item.get("violated") else INK
        svg.text(
            x1 + 62, y + bar_h + 3, _error_text(item), 11.5, fill=colour, bold=bool(item.get("violated"))
        )
    legend(
        svg,
        [
            ("swatch", PREDICTED, "predicted"),
            ("swatch", MEASURED, "measured"),
            ("line", "#000", "claimed bound"),
        ],
        x0,
        top + row_h * len(items) + 12,
        x1 - x0,
    )
    return svg.render()

"""The report's architecture diagram: hosts, their cores and the nodes bound to them, the
topics between nodes (one SVG, drawn with :mod:`.canvas`)."""

from __future__ import annotations

from typing import Any

from rosaadl.exporters.report.canvas import (
    INK,
    MUTED,
    STATUS,
    TRACK,
    WIDTH,
    Svg,
    empty_chart,
    fit,
    legend,
    mips,
    num,
    rate,
    text_width,
)

__all__ = ["architecture_diagram"]


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
    svg: Svg,
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
        fit(box["name"], w - 2 * _PAD, 12.5, True),
        12.5,
        bold=True,
        fill=INK,
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


def _core_box(svg: Svg, core: dict[str, Any], x: float, y: float, load: dict[str, Any] | None) -> None:
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
        x + _CORE_W / 2, y + 17, fit(core["name"], _CORE_W - 8, 12, True), 12, anchor="middle", bold=True
    )
    capacity = load["capacity_mips"] if load else None
    svg.text(
        x + _CORE_W / 2,
        y + 32,
        f"{mips(capacity)} MIPS" if capacity else "no capacity",
        10.5,
        anchor="middle",
        fill=MUTED,
    )
    bx, by, bw, bh = x + 8, y + 42, _CORE_W - 16, 8
    svg.rect(bx, by, bw, bh, fill=TRACK, rx=2)
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
            fill=colour if over else INK,
        )


def architecture_diagram(arch: dict[str, Any], cpu: list[dict[str, Any]]) -> str:
    """ROS nodes and devices with their topics (top), the hardware tree down to the cores with
    their loads (bottom), and the bindings of nodes to cores (dashed, in the node's colour).

    Nodes are placed in columns by their position along the topic graph (sources left); more
    columns than fit the width wrap into further bands, as text does."""
    label = "Architecture: ROS nodes, topics, boards, cores and bindings"
    nodes = arch["nodes"]
    if not nodes and not arch["hardware"]:
        return empty_chart(label, "No node and no processor in the model", "chart chart-architecture")
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
    room = WIDTH - 40
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
    width = max(WIDTH, sw_width + 40, hw_width + 40)
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
    svg = Svg(width, height, label, "chart chart-architecture")
    svg.raw(
        '<defs><marker id="arch-arrow" viewBox="0 0 10 10" refX="9" refY="5" '
        'markerWidth="7" markerHeight="7" '
        f'orient="auto-start-reverse"><path d="M0 0L10 5L0 10z" fill="{INK}"/></marker>'
        '<marker id="arch-bind" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="6" markerHeight="6" '
        f'orient="auto-start-reverse"><path d="M0 0L10 5L0 10z" fill="{MUTED}"/></marker></defs>'
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
        curve = f"M{num(ax)} {num(ay)}C{num(ax)} {num(mid)} {num(tx)} {num(mid)} {num(tx)} {num(ty - 2)}"
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
    legend(
        svg,
        [
            ("line", INK, "topic (port connection), with its data type and rate"),
            ("dash", MUTED, "binding of a node to a core (Actual_Processor_Binding)"),
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
    svg: Svg,
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
        d = f"M{num(x1)} {num(y1)}C{num(x1)} {num(mid)} {num(x2)} {num(mid)} {num(x2)} {num(y2)}"
        lx, ly = (x1 + x2) / 2, mid - 13 * (len(lines) - 1) / 2
    elif bx > ax + 1:
        x1, y1 = ax + node_w, ay + _NODE_H / 2
        x2, y2 = bx - 2, by + _NODE_H / 2
        dx = (x2 - x1) / 2
        d = f"M{num(x1)} {num(y1)}C{num(x1 + dx)} {num(y1)} {num(x2 - dx)} {num(y2)} {num(x2)} {num(y2)}"
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
        d = f"M{num(x1)} {num(y1)}C{num(x1)} {num(lift)} {num(x2)} {num(lift)} {num(x2)} {num(y2)}"
        lx, ly = (x1 + x2) / 2, lift - 13 * len(lines)
    tip = f"{t['label']} ({t['data_type']}) from {t['source']} to {t['target']}"
    svg.el("path", tip=tip, d=d, fill="none", stroke=INK, stroke_width=1.8, marker_end="url(#arch-arrow)")
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
            fill=INK if i == 0 else MUTED,
            tip=tip if i == 0 else None,
        )


def _node_box(svg: Svg, n: dict[str, Any], x: float, y: float, node_w: float, cores: list[str]) -> None:
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
    svg.text(x + 16, y + 20, fit(n["name"], inner, 13, True), 13, bold=True, tip=n["key"])
    sub = n["classifier"].rpartition("::")[2] or n["kind"]
    svg.text(x + 16, y + 36, fit(sub, inner, 10.5), 10.5, fill=MUTED, tip=n["classifier"] or None)
    if device:
        svg.text(x + 16, y + 51, "device", 10.5, fill=MUTED)
        return
    count = len(n["threads"])
    svg.text(x + 16, y + 51, f"ROS node · {count} thread{'s' if count != 1 else ''}", 10.5, fill=MUTED)
    where = "on " + ", ".join(cores) if cores else "not bound"
    svg.text(
        x + 16,
        y + 66,
        fit(where, inner, 10.5, True),
        10.5,
        bold=True,
        fill=INK if cores else STATUS["error"],
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
        parts.append(rate(topic["kbps"]))
    if parts:
        lines.append(" · ".join(parts))
    if topic["buses"]:
        lines.append("via " + ", ".join(b.rpartition(".")[2] for b in topic["buses"]))
    return lines

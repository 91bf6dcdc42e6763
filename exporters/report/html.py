"""The analysis report as one static HTML page (and its data as ``report.json``).

:func:`write_report` writes ``report.html`` and ``report.json`` into a folder. The page needs no
network and no JavaScript: the style sheet is inline, the charts are inline SVG
(:mod:`rosaadl.exporters.report.svg`), tooltips are SVG ``<title>`` elements. It shows, in this
order: the findings (verdict, headline figures, errors, warnings), the architecture (nodes,
topics, boards, cores, bindings), the CPU load of every core against its capacity, the bus
loads, the simulated schedule over one hyperperiod with its deadline misses, and the tables
behind the charts. ``report.json`` holds the same data (:func:`~rosaadl.exporters.report.view.build_view`).

The output is deterministic: the same instance and report give byte-identical files (no date,
no random identifier, fixed number formats); both files are written atomically, inside the
given folder only.
"""

from __future__ import annotations

import json
import logging
import os
from collections.abc import Sequence
from fractions import Fraction
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

import jinja2
from markupsafe import Markup, escape

from rosaadl.errors import ExportError
from rosaadl.exporters.report import svg as charts
from rosaadl.exporters.report.compare_chart import compare_chart
from rosaadl.exporters.report.executor_charts import chain_chart, executor_gantt, executor_section
from rosaadl.exporters.report.latency_chart import latency_chart
from rosaadl.exporters.report.view import build_view, short_path

__all__ = ["REPORT_HTML", "REPORT_JSON", "render_report", "write_report"]

log = logging.getLogger(__name__)

REPORT_HTML = "report.html"
REPORT_JSON = "report.json"


# =============================================================================== templates


def _template_text(name: str) -> str:
    return resources.files("rosaadl.exporters.report").joinpath("templates", name).read_text(encoding="utf-8")


@lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.FunctionLoader(_template_text),
        autoescape=True,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
    )
    env.filters["breakable"] = _breakable
    return env


def _breakable(text: str) -> Markup:
    """An instance path that may wrap after its dots (``<wbr>``), escaped."""
    return Markup(".<wbr>").join(escape(part) for part in str(text).split("."))


def _version() -> str:
    try:
        from importlib.metadata import version

        return version("rosaadl")
    except Exception:  # noqa: BLE001 - not installed: an unknown version, not a failure
        return "unknown"


# =============================================================================== tables


def _wcrt(row: Any) -> Any:
    """A task's WCRT as shown: ``>=X`` when it is a lower bound (the analysis passed its work bound)."""
    return row.wcrt if getattr(row, "wcrt_exact", True) else f">={_cell(row.wcrt)}"


def _cell(value: Any, digits: int = 2) -> str:
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, Fraction):
        value = value.numerator if value.denominator == 1 else float(value)
    if isinstance(value, int):
        return f"{value:,}".replace(",", " ")
    if isinstance(value, float):
        return f"{value:,.{digits}f}".replace(",", " ")
    return str(value)


def _table(
    table_id: str,
    title: str,
    headers: Sequence[str],
    rows: list[dict[str, Any]],
    *,
    numeric: Sequence[int] = (),
    paths: Sequence[int] = (),
    empty: str = "Nothing to show.",
) -> dict[str, Any]:
    return {
        "id": table_id,
        "title": title,
        "headers": list(headers),
        "rows": rows,
        "numeric": list(numeric),
        "paths": list(paths),
        "empty": empty,
    }


def _row(cells: Sequence[Any], cls: str = "") -> dict[str, Any]:
    return {"cells": [_cell(c) for c in cells], "cls": cls, "group": ""}


def _group(text: str) -> dict[str, Any]:
    return {"cells": [], "cls": "", "group": text}


def _tables(view: dict[str, Any], report: Any) -> list[dict[str, Any]]:
    tables = []
    # findings of the architecture first: what runs where
    arch = view["architecture"]
    bound: dict[str, list[str]] = {}
    for b in arch["bindings"]:
        bound.setdefault(b["node"], []).append(short_path(b["processor"]))
    rows = [
        _row(
            [
                n["label"],
                n["kind"],
                n["classifier"],
                len(n["threads"]),
                ", ".join(bound.get(n["key"], [])) or ("–" if n["kind"] == "device" else "not bound"),
            ]
        )
        for n in arch["nodes"]
    ]
    tables.append(
        _table(
            "nodes",
            "Nodes and bindings",
            ["Node", "Kind", "Classifier", "Threads", "Bound to"],
            rows,
            paths=[0, 2, 4],
            numeric=[3],
            empty="No process or device in the model.",
        )
    )
    rows = [
        _row(
            [
                t["topic"] or t["label"],
                t["data_type"],
                short_path(t["source"]),
                short_path(t["target"]),
                t["kbps"],
                ", ".join(t["buses"]) or "not bound",
            ]
        )
        for t in arch["topics"]
    ]
    tables.append(
        _table(
            "topics",
            "Topics",
            ["Topic", "Data type", "From", "To", "Rate (KB/s)", "Bound to"],
            rows,
            paths=[2, 3],
            numeric=[4],
            empty="No port connection between nodes.",
        )
    )
    if report.cpu is not None:
        rows = []
        for p in report.cpu.processors:
            bad = "bad" if p.overloaded else ""
            name = short_path(p.path) + (f" {p.mode}" if p.mode else "")
            rows.append(
                _row([name, p.capacity_mips, p.demand_mips, p.load_percent, p.utilization * 100], bad)
            )
            for t in p.threads:
                rows.append(_row([short_path(t.path), "", t.mips, t.load_percent, ""], f"sub {bad}".strip()))
        tables.append(
            _table(
                "cpu",
                "CPU load (bound resources)",
                ["Processor / thread", "Capacity (MIPS)", "Demand (MIPS)", "Load (%)", "CET / period (%)"],
                rows,
                paths=[0],
                numeric=[1, 2, 3, 4],
                empty="No processor.",
            )
        )
        if report.cpu.memories:
            rows = [
                _row([short_path(m.path) + f" ({m.kind})", m.capacity_kbyte, m.demand_kbyte, m.load_percent])
                for m in report.cpu.memories
            ]
            tables.append(
                _table(
                    "memory",
                    "Memory",
                    ["Memory", "Capacity (KByte)", "Demand (KByte)", "Load (%)"],
                    rows,
                    paths=[0],
                    numeric=[1, 2, 3],
                )
            )
    if report.budget is not None:
        rows = []
        for total in report.budget.totals:
            unit = "MIPS" if total.kind == "MIPS" else "KByte"
            rows.append(
                _group(
                    f"{total.kind}: capacity {_cell(total.capacity)} {unit}, "
                    f"budget {_cell(total.budget)} {unit}" + (f" {total.mode}" if total.mode else "")
                )
            )
            for r in total.rows:
                bad = "bad" if "exceeds" in r.note else ""
                rows.append(
                    _row(
                        ["\u2003" * r.depth + short_path(r.path), r.category, r.budget, r.actual, r.note], bad
                    )
                )
        tables.append(
            _table(
                "budgets",
                "Resource budgets (not bound)",
                ["Component", "Category", "Budget", "Actual", "Note"],
                rows,
                paths=[0],
                numeric=[2, 3],
                empty="No budget.",
            )
        )
    if report.bus is not None:
        rows = []
        for r in view["bus"]:
            rows.append(
                _row(
                    [
                        "\u2003" * r["depth"] + r["label"] + (" (virtual)" if r["virtual"] else ""),
                        r["capacity_kbps"],
                        r["budget_kbps"],
                        r["required_kbps"],
                        r["actual_kbps"],
                        r["load_percent"],
                    ],
                    "bad" if r["overloaded"] else "",
                )
            )
            for c in r["connections"]:
                rows.append(_row([c["name"], "", c["budget_kbps"], "", c["actual_kbps"], ""], "sub"))
        tables.append(
            _table(
                "bus",
                "Bus load (KB/s)",
                ["Bus / virtual bus / connection", "Capacity", "Budget", "Required", "Actual", "Load (%)"],
                rows,
                paths=[0],
                numeric=[1, 2, 3, 4, 5],
                empty="No bus in the model.",
            )
        )
        rows = [
            _row([short_path(p.path), p.data_size_bytes, p.rate_per_second, p.kbytesps])
            for p in report.bus.ports
        ]
        tables.append(
            _table(
                "ports",
                "Bandwidth of outgoing ports",
                ["Port", "Data_Size (bytes)", "Rate (1/s)", "KB/s"],
                rows,
                paths=[0],
                numeric=[1, 2, 3],
                empty="No outgoing data port.",
            )
        )
    if report.schedulability is not None:
        rows = []
        unit = report.schedulability.time_unit
        for dom in report.schedulability.domains:
            where = short_path(dom.path) + (f".{dom.core}" if dom.core else "")
            verdict = {True: "schedulable", False: "NOT schedulable", None: "no verdict"}[dom.schedulable]
            interval = dom.feasibility_interval.length if dom.feasibility_interval else None
            rows.append(
                _group(
                    f"{where} — {dom.scheduler.value}, utilization {float(dom.utilization):.4f} "
                    f"(bound {dom.bound:.4f}), feasibility interval {_cell(interval)} {unit}: {verdict}"
                )
            )
            for t in dom.tasks:
                rows.append(
                    _row(
                        [short_path(t.path), t.priority, t.period, t.capacity, t.deadline, _wcrt(t), t.met],
                        "bad" if t.met is False else "",
                    )
                )
        tables.append(
            _table(
                "schedulability",
                "Schedulability (feasibility tests and worst-case response times)",
                ["Task", "Priority", "Period", "Capacity", "Deadline", "WCRT", "Met"],
                rows,
                paths=[0],
                numeric=[1, 2, 3, 4, 5],
                empty="No scheduling domain.",
            )
        )
    if report.simulation is not None:
        rows = [
            _row(
                [
                    short_path(t.path),
                    t.released,
                    t.completed,
                    t.worst_response,
                    t.average_response,
                    t.deadline_misses,
                    t.preemptions,
                ],
                "bad" if t.deadline_misses else "",
            )
            for t in report.simulation.tasks
        ]
        tables.append(
            _table(
                "simulation",
                "Simulation over each core's feasibility interval",
                [
                    "Task",
                    "Released",
                    "Completed",
                    "Worst response",
                    "Average response",
                    "Misses",
                    "Preemptions",
                ],
                rows,
                paths=[0],
                numeric=[1, 2, 3, 4, 5, 6],
                empty="No task simulated.",
            )
        )
    schedule = view["schedule"]
    if schedule["available"]:
        labels = {t["name"]: t["label"] for t in schedule["tasks"]}
        rows = [
            _row(
                [labels.get(m["task"], m["task"]), m["job"], m["release"], m["deadline"], m["completion"]],
                "bad",
            )
            for m in schedule["misses"]
        ]
        tables.append(
            _table(
                "misses",
                f"Deadline misses in the Gantt chart's window ({schedule['horizon_text']})",
                ["Task", "Job", "Release", "Deadline", "Completion"],
                rows,
                paths=[0],
                numeric=[1, 2, 3, 4],
                empty="No deadline missed.",
            )
        )
    if report.latency is not None:
        rows = []
        for chain in report.latency.chains:
            rows.append(
                _group(
                    f"{chain.name} ({chain.mode}): best {_cell(chain.best_us)} us, "
                    f"worst {_cell(chain.worst_us)} us"
                    + (f", expected {_cell(chain.expected_us)} us" if chain.expected_us is not None else "")
                )
            )
            for hop in chain.hops:
                rows.append(_row([short_path(hop.path), hop.kind, hop.best_us, hop.worst_us, hop.note]))
        tables.append(
            _table(
                "latency",
                "End-to-end latency (us)",
                ["Element", "Kind", "Best", "Worst", "Note"],
                rows,
                paths=[0],
                numeric=[2, 3],
                empty="No chain of threads.",
            )
        )
    if report.deployment is not None:
        dep = report.deployment
        rows = [_row([short_path(p.process), short_path(p.processor), p.load * 100]) for p in dep.placements]
        rows += [_row([u, "not placed", None], "bad") for u in dep.unplaced]
        tables.append(
            _table(
                "deployment",
                f"Proposed deployment ({dep.method}, {'feasible' if dep.feasible else 'not feasible'})",
                ["Process", "Core", "Load of the core (%)"],
                rows,
                paths=[0, 1],
                numeric=[2],
                empty="No process to place.",
            )
        )
    return tables


def _executor_tables(report: Any) -> list[dict[str, Any]]:
    """The executor analysis's tables: each callback's bound under its executor beside its
    preemptive-thread WCRT, and each chain's reaction time and data age."""
    result = report.result("executor") if hasattr(report, "result") else None
    if result is None:
        return []
    rows = [
        _row(
            [short_path(c.path), short_path(c.executor), c.kind, c.wcrt, c.thread_wcrt, c.deadline],
            "bad" if c.met is False else "",
        )
        for c in result.callbacks
    ]
    chains = [
        _row([c.name, c.reaction_time, c.data_age, c.deadline], "bad" if c.met is False else "")
        for c in result.chains
    ]
    return [
        _table(
            "executor-callbacks",
            "Callback response times under their executors (us)",
            ["Callback", "Executor", "Kind", "WCRT (executor)", "WCRT (preemptive thread)", "Deadline"],
            rows,
            paths=[0, 1],
            numeric=[3, 4, 5],
            empty="No callback.",
        ),
        _table(
            "executor-chains",
            "Cause-effect chains (us)",
            ["Chain", "Reaction time", "Data age", "Deadline"],
            chains,
            numeric=[1, 2, 3],
            empty="No cause-effect chain.",
        ),
    ]


# =============================================================================== rendering


def render_report(
    instance: Any, report: Any, *, simulation: Any = None, title: str | None = None
) -> tuple[str, str]:
    """``(report.html, report.json)`` as text for an instance and its analysis report."""
    view = build_view(instance, report, simulation=simulation, title=title)
    svgs = {
        "architecture": charts.architecture_diagram(view["architecture"], view["cpu"]),
        "cpu": charts.cpu_chart(view["cpu"]),
        "bus": charts.bus_chart(view["bus"]),
        "gantt": charts.gantt_chart(view["schedule"]),
        "latency": latency_chart((view["analyses"].get("latency") or {}).get("chains") or []),
        "compare": compare_chart(
            (view["analyses"].get("compare") or {}).get("items") or [], view["instance"]
        ),
    }
    executors = executor_section(report)
    svgs["chains"] = chain_chart(executors)
    svgs["executors"] = executor_gantt(executors)
    template = _environment().get_template("report.html.j2")
    html = template.render(
        view=view,
        svgs={k: Markup(v) for k, v in svgs.items()},
        tables=_tables(view, report) + _executor_tables(report),
        executors=executors,
        css=Markup(_template_text("report.css")),
        version=_version(),
    )
    data = json.dumps(view, indent=2, ensure_ascii=False, allow_nan=False) + "\n"
    return html, data


def write_report(
    instance: Any,
    report: Any,
    out_dir: str | os.PathLike[str],
    *,
    simulation: Any = None,
    title: str | None = None,
) -> list[Path]:
    """Write ``report.html`` and ``report.json`` into ``out_dir`` (created if needed).

    ``simulation`` is a :class:`~rosaadl.analysis.simulation.SimulationResult` recorded with its
    schedule, drawn as it is; without it, the instance is simulated over one hyperperiod (or as
    much of it as :data:`~rosaadl.exporters.report.view.MAX_GANTT_JOBS` jobs allow). Both files
    are rendered before either is written, and each is written atomically.
    """
    from rosaadl.fileio import atomic_write_text, existing, safe_join

    folder = Path(out_dir)
    if existing(folder, ExportError) and not folder.is_dir():
        raise ExportError(f"cannot write the report into {str(folder)!r}: it is a file, not a folder")
    html, data = render_report(instance, report, simulation=simulation, title=title)
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ExportError(f"cannot create the report folder {str(folder)!r}: {exc.strerror}") from None
    written = []
    for name, text in ((REPORT_JSON, data), (REPORT_HTML, html)):
        target = safe_join(folder, name)
        try:
            atomic_write_text(target, text)
        except OSError as exc:
            raise ExportError(f"cannot write {str(target)!r}: {exc.strerror}") from None
        written.append(target)
    log.info("wrote %s and %s into %s", REPORT_HTML, REPORT_JSON, folder)
    return [written[1], written[0]]

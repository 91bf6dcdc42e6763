"""One result object for every analysis of an instance, and its renderings.

:func:`run_analyses` runs the selected analyses (``cpu``, ``budget``, ``bus``, ``sched``,
``sim``, ``latency``, ``deploy``) on an instance and gathers them in an :class:`AnalysisReport`:

* :meth:`AnalysisReport.as_dict` / :meth:`AnalysisReport.to_json`: the JSON document of
  ``rosaadl analyze --format json``::

      {"ok": bool,
       "analyses": {"cpu": {"processors": [{"path", "capacity_mips", "demand_mips", "load_percent",
                                            "threads": [{"path", "period_us", "cet_us",
                                                         "load_percent", "mips_demand"}]}]},
                    "budget": {...},
                    "bus": {"buses": [{"path", "capacity_kbps", "budget_kbps", "required_kbps",
                                       "actual_kbps", "connections": [...]}]},
                    "schedulability": {"processors": [{"path", "scheduler", "utilization",
                                                       "bound", "feasibility_interval",
                                                       "tasks": [{"path", "priority", "period",
                                                                  "capacity", "deadline",
                                                                  "wcrt", "met"}]}]},
                    "simulation": {...}, "latency": {...}},
       "errors": [{"message", "file", "line", "column", "path"}], "warnings": [...]}

  Bus figures are in KB/s as OSATE prints them (``_kbps`` = KBytesps, 1000 bytes per second);
  a bus row also lists its ``virtual_buses`` and ``broadcasts``; a model with modes adds
  ``"mode"`` / ``"modes"`` (the system operation mode) to processor and bus rows; a deployment
  search adds ``"deployment"``.
* :meth:`AnalysisReport.text`: plain text tables.
* :meth:`AnalysisReport.write_csv`: CSV files in a directory, among them OSATE's bus load report
  (``<instance>__BusLoad.csv``, line for line) and reports in the style of its resource budget
  analyses.

``ok`` is false when any analysis reports an error: an overload, a budget exceeded, a task set
found not schedulable, a deadline missed in simulation, a latency over its bound, no deployment.
"""

from __future__ import annotations

import csv
import io
import json
import logging
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path
from typing import Any

from rosaadl.errors import Diagnostic, Location, RosaadlError, UsageError

__all__ = ["ANALYSES", "DEFAULT_ANALYSES", "AnalysisReport", "run_analyses", "parse_only"]

log = logging.getLogger(__name__)

#: Every analysis ``run_analyses`` knows, in report order.
ANALYSES = ("cpu", "budget", "bus", "sched", "sim", "latency", "deploy")
#: What runs when nothing is selected (the deployment search proposes, it does not check).
DEFAULT_ANALYSES = ("cpu", "budget", "bus", "sched", "sim", "latency")

_JSON_KEYS = {
    "cpu": "cpu",
    "budget": "budget",
    "bus": "bus",
    "sched": "schedulability",
    "sim": "simulation",
    "latency": "latency",
    "deploy": "deployment",
}


def parse_only(text: str | Iterable[str] | None) -> tuple[str, ...]:
    """``"cpu,bus"`` (or a list) → the selected analyses in report order; a located
    :class:`UsageError` for an unknown name."""
    if text is None:
        return DEFAULT_ANALYSES
    items = text.split(",") if isinstance(text, str) else list(text)
    names = {item.strip().lower() for item in items if item.strip()}
    aliases = {"schedulability": "sched", "simulation": "sim", "deployment": "deploy", "busload": "bus"}
    names = {aliases.get(n, n) for n in names}
    unknown = sorted(n for n in names if n not in ANALYSES)
    if unknown:
        raise UsageError(f"unknown analysis {', '.join(unknown)} (expected some of: {', '.join(ANALYSES)})")
    if not names:
        raise UsageError(f"no analysis selected (expected some of: {', '.join(ANALYSES)})")
    return tuple(a for a in ANALYSES if a in names)


def _num(value: Any) -> Any:
    if isinstance(value, Fraction):
        return int(value) if value.denominator == 1 else float(value)
    return value


def _fmt(value: Any, digits: int = 2) -> str:
    """A number for a text table: integers as they are, others with ``digits`` decimals."""
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, Fraction) and value.denominator == 1:
        return str(value.numerator)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, (Fraction, float)):
        return f"{float(value):.{digits}f}"
    return str(value)


def _table(headers: Sequence[str], rows: Iterable[Sequence[Any]]) -> list[str]:
    cells = [[str(h) for h in headers]] + [
        [c if isinstance(c, str) else _fmt(c) for c in row] for row in rows
    ]
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]
    out = []
    for n, row in enumerate(cells):
        parts = []
        for i, cell in enumerate(row):
            numeric = n > 0 and i > 0 and re.fullmatch(r"-?[\d.]+|-", cell) is not None
            parts.append(cell.rjust(widths[i]) if numeric else cell.ljust(widths[i]))
        out.append("  ".join(parts).rstrip())
        if n == 0:
            out.append("  ".join("-" * w for w in widths))
    return out


def _short(path: str) -> str:
    """An instance path without its root segment (shorter table cells)."""
    return path.partition(".")[2] or path


def _safe_name(name: str) -> str:
    cleaned = re.sub(r"[^A-Za-z0-9_.-]", "_", name or "instance").strip(".")
    return cleaned or "instance"


def _diag_key(d: Diagnostic) -> tuple[str, str, str | None]:
    return (d.severity, d.message, d.location.path)


@dataclass(frozen=True)
class AnalysisReport:
    """The results of the analyses that ran on one instance (None: not run), and the errors of
    analyses that could not run."""

    instance: str
    cpu: Any = None
    budget: Any = None
    bus: Any = None
    schedulability: Any = None
    simulation: Any = None
    latency: Any = None
    deployment: Any = None
    failures: tuple[Diagnostic, ...] = ()
    verdicts: tuple[Diagnostic, ...] = ()

    def results(self) -> list[tuple[str, Any]]:
        """(key, result) of the analyses that ran, in report order."""
        pairs = [
            ("cpu", self.cpu),
            ("budget", self.budget),
            ("bus", self.bus),
            ("sched", self.schedulability),
            ("sim", self.simulation),
            ("latency", self.latency),
            ("deploy", self.deployment),
        ]
        return [(k, r) for k, r in pairs if r is not None]

    @property
    def diagnostics(self) -> tuple[Diagnostic, ...]:
        """Every diagnostic once (the scheduling analyses share the task extraction's)."""
        seen: set[tuple[str, str, str | None]] = set()
        out = []
        for _key, result in self.results():
            for diag in result.diagnostics:
                if _diag_key(diag) not in seen:
                    seen.add(_diag_key(diag))
                    out.append(diag)
        for diag in (*self.verdicts, *self.failures):
            if _diag_key(diag) not in seen:
                seen.add(_diag_key(diag))
                out.append(diag)
        return tuple(out)

    @property
    def errors(self) -> tuple[Diagnostic, ...]:
        return tuple(d for d in self.diagnostics if d.severity == "error")

    @property
    def warnings(self) -> tuple[Diagnostic, ...]:
        return tuple(d for d in self.diagnostics if d.severity == "warning")

    @property
    def ok(self) -> bool:
        return not self.errors and all(r.ok for _k, r in self.results())

    # ------------------------------------------------------------------ JSON

    def as_dict(self) -> dict[str, Any]:
        def entry(d: Diagnostic) -> dict[str, Any]:
            loc = d.location
            return {
                "message": d.message,
                "file": loc.file,
                "line": loc.line,
                "column": loc.column,
                "path": loc.path,
            }

        return {
            "ok": self.ok,
            "analyses": {_JSON_KEYS[k]: r.as_dict() for k, r in self.results()},
            "errors": [entry(d) for d in self.errors],
            "warnings": [entry(d) for d in self.warnings],
        }

    def to_json(self, indent: int | None = 2) -> str:
        return json.dumps(self.as_dict(), indent=indent, ensure_ascii=False)

    # ------------------------------------------------------------------ text

    def text(self) -> str:
        """Every result as plain text tables, then the errors and warnings."""
        lines: list[str] = [f"Analyses of {self.instance}", ""]
        if self.cpu is not None:
            lines += ["CPU (bound resources)", ""]
            rows = []
            for p in self.cpu.processors:
                name = _short(p.path) + (f" {p.mode}" if p.mode else "")
                rows.append([name, p.capacity_mips, p.demand_mips, p.load_percent, p.utilization * 100])
                for t in p.threads:
                    rows.append(["  " + _short(t.path), "", t.mips, t.load_percent, ""])
            lines += _table(["processor / thread", "capacity MIPS", "demand MIPS", "load %", "CET/T %"], rows)
            if self.cpu.memories:
                lines.append("")
                rows = [
                    [_short(m.path) + f" ({m.kind})", m.capacity_kbyte, m.demand_kbyte, m.load_percent]
                    for m in self.cpu.memories
                ]
                lines += _table(["memory", "capacity KByte", "demand KByte", "load %"], rows)
            lines.append("")
        if self.budget is not None:
            lines += ["Budgets (not bound)", ""]
            for total in self.budget.totals:
                unit = "MIPS" if total.kind == "MIPS" else "KByte"
                title = (
                    f"{total.kind} capacity {_fmt(total.capacity)} {unit}, budget {_fmt(total.budget)} {unit}"
                )
                lines.append(title + (f" {total.mode}" if total.mode else ""))
                rows = [
                    ["  " * r.depth + _short(r.path), r.category, r.budget, r.actual, r.note]
                    for r in total.rows
                ]
                lines += _table(["component", "category", f"budget {unit}", f"actual {unit}", "note"], rows)
                lines.append("")
        if self.bus is not None:
            lines += ["Bus load (KB/s)", ""]
            for som in self.bus.modes:
                if som.label:
                    lines.append(f"in modes {som.label}")
                rows = []
                for bus in som.buses:
                    self._bus_rows(rows, bus, 0)
                lines += _table(
                    ["bus / virtual bus / connection", "capacity", "budget", "required", "actual"], rows
                )
                lines.append("")
            if self.bus.ports:
                rows = [
                    [_short(p.path), p.data_size_bytes, p.rate_per_second, p.kbytesps] for p in self.bus.ports
                ]
                lines += _table(["outgoing port", "Data_Size bytes", "rate /s", "KB/s"], rows)
                lines.append("")
        if self.schedulability is not None:
            lines += ["Schedulability", ""]
            for dom in self.schedulability.domains:
                where = _short(dom.path) + (f".{dom.core}" if dom.core else "")
                interval = dom.feasibility_interval.length if dom.feasibility_interval else None
                lines.append(
                    f"{where}: {dom.scheduler.value}, utilization {_fmt(dom.utilization, 4)}, "
                    f"bound {_fmt(dom.bound, 4)}, feasibility interval {_fmt(interval)} "
                    f"{self.schedulability.time_unit}, schedulable {_fmt(dom.schedulable)}"
                )
                rows = [
                    [_short(t.path), t.priority, t.period, t.capacity, t.deadline, t.wcrt, t.met]
                    for t in dom.tasks
                ]
                lines += _table(["task", "priority", "period", "capacity", "deadline", "WCRT", "met"], rows)
                lines.append("")
        if self.simulation is not None:
            lines += [f"Simulation ({self.simulation.deadline_misses} deadline misses)", ""]
            rows = [
                [
                    _short(t.path),
                    t.released,
                    t.completed,
                    t.worst_response,
                    t.average_response,
                    t.deadline_misses,
                    t.preemptions,
                ]
                for t in self.simulation.tasks
            ]
            lines += _table(
                ["task", "released", "completed", "worst RT", "average RT", "misses", "preemptions"], rows
            )
            lines.append("")
        if self.latency is not None:
            lines += ["End-to-end latency (us)", ""]
            rows = [[c.name, c.best_us, c.worst_us, c.expected_us, c.met] for c in self.latency.chains]
            lines += _table(["chain", "best", "worst", "expected", "met"], rows)
            lines.append("")
        if self.deployment is not None:
            dep = self.deployment
            lines += [
                f"Deployment search ({dep.method}{', optimal' if dep.optimal else ''}, "
                f"max load {_fmt(dep.max_load * 100)} %, {'feasible' if dep.feasible else 'not feasible'})",
                "",
            ]
            rows = [
                [
                    _short(c.path),
                    c.capacity_mips,
                    c.load_percent,
                    c.schedulable,
                    ", ".join(_short(p) for p in c.processes),
                ]
                for c in dep.cores
            ]
            lines += _table(["processor", "capacity MIPS", "load %", "schedulable", "processes"], rows)
            lines.append("")
            lines += dep.associations()
            lines.append("")
        for title, group in (("Errors", self.errors), ("Warnings", self.warnings)):
            if group:
                lines.append(f"{title} ({len(group)})")
                lines += [f"  {d}" for d in group]
                lines.append("")
        lines.append("OK" if self.ok else "FAILED")
        return "\n".join(lines) + "\n"

    @staticmethod
    def _bus_rows(rows: list[list[Any]], bus: Any, depth: int) -> None:
        indent = "  " * depth
        rows.append(
            [
                indent + _short(bus.path),
                bus.capacity_kbps,
                bus.budget_kbps,
                bus.required_kbps,
                bus.actual_kbps,
            ]
        )
        for vb in bus.virtual_buses:
            AnalysisReport._bus_rows(rows, vb, depth + 1)
        for conn in bus.connections:
            rows.append([indent + "  " + conn.name, "", conn.budget_kbps, "", conn.actual_kbps])
        for group in bus.broadcasts:
            rows.append([indent + "  " + group.label, "", group.budget_kbps, "", group.actual_kbps])

    # ------------------------------------------------------------------ CSV

    def csv_files(self) -> dict[str, str]:
        """File name → content of every CSV report (OSATE's names: ``<instance>__<Report>.csv``)."""
        base = _safe_name(self.instance)
        files: dict[str, str] = {}
        if self.bus is not None:
            files[f"{base}__BusLoad.csv"] = self.bus.csv_text()
        if self.cpu is not None:
            files[f"{base}__BoundResourceAnalysis.csv"] = _bound_csv(self.cpu)
        if self.budget is not None:
            files[f"{base}__ResourceBudgets.csv"] = _budget_csv(self.budget)
        if self.schedulability is not None:
            rows = [
                [
                    "Processor",
                    "Scheduler",
                    "Task",
                    "Priority",
                    "Period",
                    "Capacity",
                    "Deadline",
                    "WCRT",
                    "Met",
                ]
            ]
            for dom in self.schedulability.domains:
                where = dom.path + (f".{dom.core}" if dom.core else "")
                for t in dom.tasks:
                    rows.append(
                        [
                            where,
                            dom.scheduler.value,
                            t.path,
                            t.priority,
                            t.period,
                            t.capacity,
                            t.deadline,
                            t.wcrt,
                            t.met,
                        ]
                    )
            files[f"{base}__Schedulability.csv"] = _csv(rows)
        if self.simulation is not None:
            rows = [
                [
                    "Task",
                    "Released",
                    "Completed",
                    "First response",
                    "Worst response",
                    "Average response",
                    "Deadline misses",
                    "Preemptions",
                ]
            ]
            for t in self.simulation.tasks:
                rows.append(
                    [
                        t.path,
                        t.released,
                        t.completed,
                        t.first_response,
                        t.worst_response,
                        t.average_response,
                        t.deadline_misses,
                        t.preemptions,
                    ]
                )
            files[f"{base}__Simulation.csv"] = _csv(rows)
        if self.latency is not None:
            rows = [["Chain", "Element", "Kind", "Best (us)", "Worst (us)", "Note"]]
            for chain in self.latency.chains:
                for hop in chain.hops:
                    rows.append([chain.name, hop.path, hop.kind, hop.best_us, hop.worst_us, hop.note])
                rows.append(
                    [
                        chain.name,
                        "Total",
                        "",
                        chain.best_us,
                        chain.worst_us,
                        f"expected {_fmt(chain.expected_us)}",
                    ]
                )
            files[f"{base}__Latency.csv"] = _csv(rows)
        if self.deployment is not None:
            rows = [["Process", "Processor", "Load (%)"]]
            for p in self.deployment.placements:
                rows.append([p.process, p.processor, p.load * 100])
            files[f"{base}__Deployment.csv"] = _csv(rows)
        return files

    def write_csv(self, directory: str | Path) -> list[Path]:
        """Write :meth:`csv_files` into ``directory`` (created if needed), atomically."""
        from rosaadl.fileio import atomic_write_text, safe_join

        folder = Path(directory)
        folder.mkdir(parents=True, exist_ok=True)
        written = []
        for name, content in self.csv_files().items():
            target = safe_join(folder, name)
            atomic_write_text(target, content)
            written.append(target)
        return written


def _csv_value(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, Fraction):
        return str(value.numerator) if value.denominator == 1 else repr(float(value))
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _csv(rows: list[list[Any]]) -> str:
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    for row in rows:
        writer.writerow([_csv_value(v) for v in row])
    return buffer.getvalue()


def _f3(value: Fraction | None) -> str:
    return f"{float(value or 0):.3f}"


def _bound_csv(result: Any) -> str:
    """In the style of OSATE's bound resource analysis report."""
    lines = [f"Bound resource analysis of {result.instance}", ""]
    modes = sorted({p.mode for p in result.processors}) or [""]
    for mode in modes:
        lines += [f"Processor Summary Report: {mode}".rstrip(), ""]
        for p in (p for p in result.processors if p.mode == mode):
            kind = "Virtual Processor" if p.category == "virtualProcessor" else "Processor"
            lines += [
                _squeeze(
                    f"Detailed Workload Report: {mode} for {kind} {_short(p.path)} "
                    f"with Capacity {_f3(p.capacity_mips)} MIPS"
                ),
                "",
                "Component,Budget,Actual,Notes",
            ]
            for row in p.components:
                lines.append(
                    f"{'  ' * row.depth}{_category(row.category)} {_short(row.path)},{_f3(row.budget)} MIPS,"
                    f"{_f3(row.actual)} MIPS,{row.note}"
                )
            load = f",{float(p.load_percent):.2f} %" if p.load_percent is not None else ","
            lines += [f"Total,,{_f3(p.demand_mips)} MIPS{load}", ""]
    for m in result.memories:
        lines += [
            _squeeze(
                f"Detailed Workload Report: {m.mode} for memory {_short(m.path)} ({m.kind}) "
                f"with Capacity {_f3(m.capacity_kbyte)} KByte"
            ),
            "",
            "Component,Budget,Actual,Notes",
        ]
        for row in m.components:
            lines.append(
                f"{_category(row.category)} {_short(row.path)},{_f3(row.budget)} KByte,"
                f"{_f3(row.actual)} KByte,{row.note}"
            )
        lines += [f"Total,,{_f3(m.demand_kbyte)} KByte", ""]
    return "\n".join(lines) + "\n"


def _budget_csv(result: Any) -> str:
    """In the style of OSATE's not-bound resource budget report."""
    lines = [f"Resource budget analysis of {result.instance}", ""]
    for total in result.totals:
        unit = "MIPS" if total.kind == "MIPS" else "KByte"
        lines += [
            f"Detailed {total.kind} Budget Report {total.mode}".rstrip(),
            "",
            "Component,Budget,Actual,Notes",
        ]
        for row in total.rows:
            lines.append(
                f"{'  ' * row.depth}{_category(row.category)} {_short(row.path)},{_f3(row.budget)} {unit},"
                f"{_f3(row.actual)} {unit},{row.note}"
            )
        lines += [
            f"Total,,{_f3(total.budget)} {unit}",
            "",
            f"{total.kind} capacity {_f3(total.capacity)} {unit} : "
            f"{total.kind} budget {_f3(total.budget)} {unit}",
            f"{total.resources_with_capacity} out of {total.resources} with {total.kind} capacity",
            f"{total.budgeted_components} out of {total.components} with {total.kind} budget",
            "",
        ]
    return "\n".join(lines) + "\n"


def _squeeze(text: str) -> str:
    return re.sub(" +", " ", text)


def _category(name: str) -> str:
    return {"threadGroup": "thread group", "virtualProcessor": "virtual processor"}.get(name, name)


# =============================================================================== running


def run_analyses(
    source: Any,
    only: str | Iterable[str] | None = None,
    *,
    latency_chains: Iterable[Any] | None = None,
    deployment: dict[str, Any] | None = None,
    simulation_horizon: Any = None,
) -> AnalysisReport:
    """Run the selected analyses (default :data:`DEFAULT_ANALYSES`) on an instance.

    An analysis that cannot run on the model (a :class:`~rosaadl.errors.RosaadlError`) becomes an
    error of the report; the others still run. ``deployment`` passes keyword arguments to
    :func:`~rosaadl.analysis.deployment.search_deployment`.
    """
    from rosaadl.analysis.busload import analyze_bus_load
    from rosaadl.analysis.deployment import search_deployment
    from rosaadl.analysis.latency import analyze_latency
    from rosaadl.analysis.resources import analyze_budgets, analyze_resources, instance_root
    from rosaadl.analysis.schedulability import analyze_schedulability
    from rosaadl.analysis.simulation import simulate
    from rosaadl.analysis.tasks import taskset_from_instance

    selected = parse_only(only)
    root = instance_root(source)
    results: dict[str, Any] = {}
    failures: list[Diagnostic] = []
    verdicts: list[Diagnostic] = []
    taskset = None

    def attempt(name: str, run: Any) -> None:
        try:
            results[name] = run()
        except RosaadlError as exc:
            log.debug("analysis %s failed: %s", name, exc)
            failures.append(Diagnostic("error", f"{name} analysis: {exc.message}", exc.location))

    if "cpu" in selected:
        attempt("cpu", lambda: analyze_resources(root))
    if "budget" in selected:
        attempt("budget", lambda: analyze_budgets(root))
    if "bus" in selected:
        attempt("bus", lambda: analyze_bus_load(root))
    if {"sched", "sim", "latency"} & set(selected):
        try:
            taskset = taskset_from_instance(root)
        except RosaadlError as exc:
            failures.append(Diagnostic("error", f"task extraction: {exc.message}", exc.location))
    if taskset is not None and ("sched" in selected or "latency" in selected):
        attempt("sched", lambda: analyze_schedulability(taskset))
        sched = results.get("sched")
        if sched is not None and "sched" in selected:
            for dom in sched.domains:
                if dom.schedulable is False:
                    where = dom.path + (f".{dom.core}" if dom.core else "")
                    verdicts.append(
                        Diagnostic(
                            "error",
                            f"not schedulable under {dom.scheduler.value} "
                            f"(utilization {float(dom.utilization):.4f}, bound {dom.bound:.4f})",
                            Location(path=where),
                        )
                    )
    if taskset is not None and "sim" in selected:
        attempt("sim", lambda: simulate(taskset, horizon=simulation_horizon, record_schedule=False))
        sim = results.get("sim")
        if sim is not None:
            for stats in sim.tasks:
                if stats.deadline_misses:
                    verdicts.append(
                        Diagnostic(
                            "error",
                            f"missed {stats.deadline_misses} deadlines in simulation",
                            Location(path=stats.path),
                        )
                    )
    if "latency" in selected:
        attempt("latency", lambda: analyze_latency(root, latency_chains, schedulability=results.get("sched")))
    if "deploy" in selected:
        attempt("deploy", lambda: search_deployment(root, **(deployment or {})))
    return AnalysisReport(
        root.name or "",
        cpu=results.get("cpu"),
        budget=results.get("budget"),
        bus=results.get("bus"),
        schedulability=results.get("sched") if "sched" in selected else None,
        simulation=results.get("sim"),
        latency=results.get("latency"),
        deployment=results.get("deploy"),
        failures=tuple(failures),
        verdicts=tuple(verdicts),
    )

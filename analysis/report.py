"""One result object for every analysis of an instance, and its renderings.

:func:`run_analyses` runs the selected analyses (those of :mod:`rosaadl.analysis.registry`:
``cpu``, ``budget``, ``bus``, ``sched``, ``sim``, ``latency``, ``executor``, ``deploy``,
``compare``, and any other registered) on an instance and gathers them in an
:class:`AnalysisReport`:

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
* :meth:`AnalysisReport.text`: plain text tables, one section per analysis (each analysis
  renders its own).
* :meth:`AnalysisReport.write_csv`: CSV files in a directory, those each analysis writes, among
  them OSATE's bus load report (``<instance>__BusLoad.csv``, line for line) and reports in the
  style of its resource budget analyses.

``ok`` is false when any analysis reports an error: an overload, a budget exceeded, a task set
found not schedulable, a deadline missed in simulation, a latency over its bound, no deployment;
and when the run is ``inconclusive``: a simulation horizon cut by the job cap before any miss,
with no feasibility test deciding every domain (a cut horizon is never a pass).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from rosaadl.analysis.registry import Analysis, AnalysisContext, analyses, analysis, parse_only
from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic

__all__ = ["ANALYSES", "DEFAULT_ANALYSES", "AnalysisReport", "run_analyses", "parse_only"]

#: The analyses rosaadl ships, in report order (others may be registered).
ANALYSES = ("cpu", "budget", "bus", "sched", "sim", "latency", "executor", "deploy", "compare")
#: What runs when nothing is selected (the deployment search proposes, it does not check).
DEFAULT_ANALYSES = ("cpu", "budget", "bus", "sched", "sim", "latency", "executor")


def _safe_name(name: str) -> str:
    cleaned = re.sub(r"[^A-Za-z0-9_.-]", "_", name or "instance").strip(".")
    return cleaned or "instance"


def _diag_key(d: Diagnostic) -> tuple[str, str, str | None]:
    return (d.severity, d.message, d.location.path)


@dataclass(frozen=True)
class AnalysisReport:
    """The results of the analyses that ran on one instance, in report order, and the errors of
    analyses that could not run. ``taskset``: the task set the scheduling analyses extracted
    (None when none ran), for renderings that draw the schedule."""

    instance: str
    outcomes: tuple[tuple[Analysis, Any], ...] = ()
    failures: tuple[Diagnostic, ...] = ()
    verdicts: tuple[Diagnostic, ...] = ()
    taskset: Any = None

    def results(self) -> list[tuple[str, Any]]:
        """(name, result) of the analyses that ran, in report order."""
        return [(item.name, result) for item, result in self.outcomes]

    def result(self, name: str) -> Any:
        """The result of the analysis ``name`` (or an alias), None when it did not run."""
        wanted = name.strip().lower()
        for item, result in self.outcomes:
            if wanted == item.name or wanted in item.aliases:
                return result
        analysis(name)  # an analysis no one registered is a usage error, not "did not run"
        return None

    def with_result(self, name: str, result: Any) -> AnalysisReport:
        """This report with ``result`` as the result of the analysis ``name`` (added in report
        order, or in place of the one it had), e.g. a deployment search run on its own."""
        item = analysis(name)
        kept = [(i, r) for i, r in self.outcomes if i.name != item.name]
        order = {a.name: n for n, a in enumerate(analyses())}
        outcomes = sorted([*kept, (item, result)], key=lambda pair: order.get(pair[0].name, len(order)))
        return replace(self, outcomes=tuple(outcomes))

    # the analyses rosaadl ships, by the names their results have always had here
    cpu = property(lambda self: self.result("cpu"))
    budget = property(lambda self: self.result("budget"))
    bus = property(lambda self: self.result("bus"))
    schedulability = property(lambda self: self.result("sched"))
    simulation = property(lambda self: self.result("sim"))
    latency = property(lambda self: self.result("latency"))
    deployment = property(lambda self: self.result("deploy"))

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
    def inconclusive(self) -> bool:
        """An analysis could not decide (``inconclusive``: a simulation whose horizon the job cap
        cut before any miss) and no other analysis of the run decided (``decided``: the
        feasibility tests gave every domain a verdict)."""
        results = [r for _k, r in self.results()]
        return any(getattr(r, "inconclusive", False) for r in results) and not any(
            getattr(r, "decided", False) for r in results
        )

    @property
    def ok(self) -> bool:
        return not self.errors and all(r.ok for _k, r in self.results()) and not self.inconclusive

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
            **({"inconclusive": True} if self.inconclusive else {}),
            "analyses": {item.json_key: result.as_dict() for item, result in self.outcomes},
            "errors": [entry(d) for d in self.errors],
            "warnings": [entry(d) for d in self.warnings],
        }

    def to_json(self, indent: int | None = 2) -> str:
        return json.dumps(self.as_dict(), indent=indent, ensure_ascii=False)

    # ------------------------------------------------------------------ text

    def text(self) -> str:
        """Every result as plain text tables, then the errors and warnings."""
        lines: list[str] = [f"Analyses of {self.instance}", ""]
        for item, result in self.outcomes:
            lines += item.text(result)
        for title, group in (("Errors", self.errors), ("Warnings", self.warnings)):
            if group:
                lines.append(f"{title} ({len(group)})")
                lines += [f"  {d}" for d in group]
                lines.append("")
        if self.inconclusive and not self.errors:
            lines.append("INCONCLUSIVE (a simulation horizon was cut and no other analysis decided)")
        else:
            lines.append("OK" if self.ok else "FAILED")
        return "\n".join(lines) + "\n"

    # ------------------------------------------------------------------ CSV

    def csv_files(self) -> dict[str, str]:
        """File name → content of every CSV report (OSATE's names: ``<instance>__<Report>.csv``)."""
        base = _safe_name(self.instance)
        files: dict[str, str] = {}
        for item, result in self.outcomes:
            files.update(item.csv(result, base))
        return files

    def write_csv(self, directory: str | Path) -> list[Path]:
        """Write :meth:`csv_files` into ``directory`` (created if needed), atomically."""
        from rosaadl.fileio import atomic_write_text, cannot_write, safe_join

        folder = Path(directory)
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise cannot_write(folder, exc) from None
        written = []
        for name, content in self.csv_files().items():
            target = safe_join(folder, name)
            atomic_write_text(target, content)
            written.append(target)
        return written


# =============================================================================== running


@checked
def run_analyses(
    source: Any,
    only: str | Iterable[str] | None = None,
    *,
    latency_chains: Iterable[Any] | None = None,
    deployment: dict[str, Any] | None = None,
    simulation_horizon: Any = None,
    latency_preferences: Any = None,
    measurements: Any = None,
) -> AnalysisReport:
    """Run the selected analyses (default: every registered analysis that runs by default) on an
    instance, in report order.

    An analysis that cannot run on the model (a :class:`~rosaadl.errors.RosaadlError`) becomes an
    error of the report; the others still run. ``deployment`` passes keyword arguments to
    :func:`~rosaadl.analysis.deployment.search_deployment`, ``latency_chains`` the chains to
    :func:`~rosaadl.analysis.latency.analyze_latency` (and ``latency_preferences``, OSATE's
    preferences), ``simulation_horizon`` the horizon to
    :func:`~rosaadl.analysis.simulation.simulate`, ``measurements`` (a measured run,
    :class:`~rosaadl.importers.measurements.Measurements`) the ``compare`` analysis.
    """
    from rosaadl.analysis.instance_values import instance_root

    selected = parse_only(only)
    root = instance_root(source)
    context = AnalysisContext(
        root,
        {
            "latency_chains": latency_chains,
            "latency_preferences": latency_preferences,
            "deployment": deployment,
            "simulation_horizon": simulation_horizon,
            "measurements": measurements,
        },
    )
    outcomes = []
    verdicts: list[Diagnostic] = []
    for item in analyses():
        if item.name not in selected:
            continue
        result = context.result(item.name)
        if result is not None:
            outcomes.append((item, result))
            verdicts += item.verdicts(result)
    return AnalysisReport(
        root.name or "",
        tuple(outcomes),
        failures=tuple(context.failures),
        verdicts=tuple(verdicts),
        taskset=context.taskset_if_extracted,
    )

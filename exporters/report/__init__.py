"""The analysis report: a static HTML page with plots, and its data as JSON.

``write_report(instance, report, out_dir)`` writes ``report.html`` (findings, architecture
diagram, CPU and bus load bars, Gantt chart of the simulated schedule, tables; inline CSS and
SVG, no network, no JavaScript) and ``report.json`` (the same data). See
:mod:`rosaadl.exporters.report.html`, :mod:`~rosaadl.exporters.report.view` (the data),
:mod:`~rosaadl.exporters.report.svg` (the charts), :mod:`~rosaadl.exporters.report.architecture`
(the architecture diagram) and :mod:`~rosaadl.exporters.report.canvas` (the drawing kit, and
why it is hand-written SVG).
"""

from __future__ import annotations

from rosaadl.exporters.report.html import REPORT_HTML, REPORT_JSON, render_report, write_report
from rosaadl.exporters.report.view import MAX_GANTT_JOBS, build_view

__all__ = ["REPORT_HTML", "REPORT_JSON", "MAX_GANTT_JOBS", "build_view", "render_report", "write_report"]

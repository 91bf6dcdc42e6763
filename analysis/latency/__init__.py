"""End-to-end flow latency as OSATE's flow latency analysis computes it.

The package follows ``org.osate.analysis.flows`` of OSATE (read for its rules; the code is our
own), one idea per module:

* :mod:`.model`: contributors, chains (one per flow and system kind), OSATE's preferences;
* :mod:`.contributors`: what each flow element contributes (sampling, processing, queuing,
  connections, partitions);
* :mod:`.transmission`: buses and protocols under a connection (transmission, periodic
  protocols, queuing on shared buses, required protocols);
* :mod:`.declarative`: what the declarative model answers (assigned values, required protocol
  classifiers, the modes of end-to-end flows);
* :mod:`.totals`: the end-to-end totals of an asynchronous and a synchronous system;
* :mod:`.chains`: flows derived from topic chains (threads over port connections);
* :mod:`.flows`: the analysis of an instance (:func:`analyze_latency`);
* :mod:`.report`: the text section, the CSV table and OSATE's latency CSV report.
"""

from __future__ import annotations

from rosaadl.analysis.latency.chains import thread_chains
from rosaadl.analysis.latency.flows import analyze_latency
from rosaadl.analysis.latency.model import (
    Contributor,
    LatencyChain,
    LatencyHop,
    LatencyPreferences,
    LatencyResult,
)
from rosaadl.analysis.latency.report import latency_csv, latency_text, osate_latency_csv
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.errors import ModelError, UsageError

__all__ = [
    "Contributor",
    "LatencyChain",
    "LatencyHop",
    "LatencyPreferences",
    "LatencyResult",
    "analyze_latency",
    "latency_preferences",
    "latency_csv",
    "latency_text",
    "osate_latency_csv",
    "thread_chains",
]


def latency_preferences(code: str) -> LatencyPreferences:
    """The preferences an ``AS-MF-ET-EQ`` code names (a :class:`UsageError` for another form)."""
    try:
        return LatencyPreferences.from_code(code)[0]
    except ModelError as exc:
        raise UsageError(exc.message) from None


def _run(context: AnalysisContext) -> LatencyResult:
    chains = context.options.get("latency_chains")
    preferences = context.options.get("latency_preferences")
    return analyze_latency(
        context.root, chains, schedulability=context.result("sched"), preferences=preferences
    )


register(
    Analysis(
        name="latency",
        json_key="latency",
        order=60,
        run=_run,
        text=latency_text,
        csv=latency_csv,
        description="end-to-end flow latency as OSATE computes it, asynchronous and synchronous",
    )
)

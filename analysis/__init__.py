"""Analyses of AADL instance models, with the semantics of the tools users would otherwise run.

* :mod:`~rosaadl.analysis.tasks`: the task model and its extraction from an instance;
* :mod:`~rosaadl.analysis.schedulability`: Cheddar's feasibility tests and response times;
* :mod:`~rosaadl.analysis.simulation`: event-driven scheduling simulation;
* :mod:`~rosaadl.analysis.resources`: OSATE's bound resource allocation (CPU/MIPS, memory) and
  not-bound budgets;
* :mod:`~rosaadl.analysis.busload`: OSATE's bus load analysis and its CSV report;
* :mod:`~rosaadl.analysis.latency`: end-to-end latency of thread chains;
* :mod:`~rosaadl.analysis.deployment`: deployment search (bindings of processes to cores);
* :mod:`~rosaadl.analysis.report`: every analysis in one result, as JSON, text and CSV.

Each analysis is a pure function from an instance (or a task set) to a typed result with rows
and located diagnostics; none prints.
"""

from __future__ import annotations

from rosaadl.analysis import busload as _busload
from rosaadl.analysis import deployment as _deployment
from rosaadl.analysis import latency as _latency
from rosaadl.analysis import report as _report
from rosaadl.analysis import resources as _resources
from rosaadl.analysis import schedulability as _schedulability
from rosaadl.analysis import simulation as _simulation
from rosaadl.analysis import tasks as _tasks
from rosaadl.analysis.busload import *  # noqa: F403
from rosaadl.analysis.deployment import *  # noqa: F403
from rosaadl.analysis.latency import *  # noqa: F403
from rosaadl.analysis.report import *  # noqa: F403
from rosaadl.analysis.resources import *  # noqa: F403
from rosaadl.analysis.schedulability import *  # noqa: F403
from rosaadl.analysis.simulation import *  # noqa: F403
from rosaadl.analysis.tasks import *  # noqa: F403

__all__ = [
    *_tasks.__all__,
    *_schedulability.__all__,
    *_simulation.__all__,
    *_resources.__all__,
    *_busload.__all__,
    *_latency.__all__,
    *_deployment.__all__,
    *_report.__all__,
]

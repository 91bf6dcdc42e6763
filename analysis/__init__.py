"""Analyses of AADL instance models, with the semantics of the tools users would otherwise run.

* :mod:`~rosaadl.analysis.tasks`: the task model and its extraction from an instance;
* :mod:`~rosaadl.analysis.instance_values`: system modes, exact property values and processor
  bindings of an instance, as every analysis reads them;
* :mod:`~rosaadl.analysis.resources`: OSATE's bound resource allocation (CPU/MIPS, memory);
* :mod:`~rosaadl.analysis.budgets`: OSATE's not-bound resource budgets (both built on
  :mod:`~rosaadl.analysis.demand`, OSATE's ``sumBudgets``);
* :mod:`~rosaadl.analysis.busload`: OSATE's bus load analysis and its CSV report;
* :mod:`~rosaadl.analysis.schedulability`: Cheddar's feasibility tests and response times
  (:mod:`~rosaadl.analysis.edf_response`: Spuri's response times under EDF;
  :mod:`~rosaadl.analysis.partitioning`: tasks onto cores, as Cheddar partitions them);
* :mod:`~rosaadl.analysis.simulation`: event-driven scheduling simulation (its engine in
  :mod:`~rosaadl.analysis.simulation_engine`);
* :mod:`~rosaadl.analysis.latency`: end-to-end latency of thread chains;
* :mod:`~rosaadl.analysis.deployment`: deployment search (bindings of processes to cores; the
  exact branch and bound); the constraint solver behind ``rosaadl deploy`` beside it, imported
  on use: :mod:`~rosaadl.analysis.deployment_problem` (units, cores, boards, loads, memory,
  traffic), :mod:`~rosaadl.analysis.deployment_solver` (the CP-SAT model),
  :mod:`~rosaadl.analysis.deployment_baselines` (first/best/worst-fit decreasing),
  :mod:`~rosaadl.analysis.deployment_infeasibility` (why no binding exists) and
  :mod:`~rosaadl.analysis.deployment_proposal` (all of them together);
* :mod:`~rosaadl.analysis.registry`: the analyses by name; each module above that is an analysis
  registers itself there with its runner, JSON key and text/CSV renderings
  (:mod:`~rosaadl.analysis.rendering`);
* :mod:`~rosaadl.analysis.report`: every selected analysis in one result, as JSON, text and CSV.

Each analysis is a pure function from an instance (or a task set) to a typed result with rows
and located diagnostics; none prints.
"""

from __future__ import annotations

from rosaadl.analysis import budgets as _budgets
from rosaadl.analysis import busload as _busload
from rosaadl.analysis import deployment as _deployment
from rosaadl.analysis import edf_response as _edf_response
from rosaadl.analysis import instance_values as _instance_values
from rosaadl.analysis import latency as _latency
from rosaadl.analysis import partitioning as _partitioning
from rosaadl.analysis import registry as _registry
from rosaadl.analysis import report as _report
from rosaadl.analysis import resources as _resources
from rosaadl.analysis import schedulability as _schedulability
from rosaadl.analysis import simulation as _simulation
from rosaadl.analysis import tasks as _tasks
from rosaadl.analysis.budgets import *  # noqa: F403
from rosaadl.analysis.busload import *  # noqa: F403
from rosaadl.analysis.deployment import *  # noqa: F403
from rosaadl.analysis.edf_response import *  # noqa: F403
from rosaadl.analysis.instance_values import *  # noqa: F403
from rosaadl.analysis.latency import *  # noqa: F403
from rosaadl.analysis.partitioning import *  # noqa: F403
from rosaadl.analysis.registry import *  # noqa: F403
from rosaadl.analysis.report import *  # noqa: F403
from rosaadl.analysis.resources import *  # noqa: F403
from rosaadl.analysis.schedulability import *  # noqa: F403
from rosaadl.analysis.simulation import *  # noqa: F403
from rosaadl.analysis.tasks import *  # noqa: F403

__all__ = list(
    dict.fromkeys(
        [
            *_tasks.__all__,
            *_instance_values.__all__,
            *_schedulability.__all__,
            *_edf_response.__all__,
            *_partitioning.__all__,
            *_simulation.__all__,
            *_resources.__all__,
            *_budgets.__all__,
            *_busload.__all__,
            *_latency.__all__,
            *_deployment.__all__,
            *_registry.__all__,
            *_report.__all__,
        ]
    )
)

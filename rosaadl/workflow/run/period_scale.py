"""``rosaadl run … --period-scale F``: every period of the generated nodes multiplied by ``F``.

A machine with fewer or slower cores than the model's target cannot run the application at its
modelled rates: an overloaded node drops messages and runs at another rate than modelled, and
nothing measured can be compared with the model. Scaled, every timer of the nodes fires ``F``
times less often (so every publish rate and every event rate downstream follows) while every
dispatch does the same work: the node parameters ``<thread>.period``, ``<thread>.deadline`` and
``<thread>.offset`` (Dispatch_Offset; seconds, read by the generated node at start-up:
``period_of``, ``check_deadline``, ``start_timers``) are given multiplied by ``F`` on the
node's command line; execution times (``<thread>.cet_min``, ``cet_max``) are left alone. The
run folder's packages are not regenerated: a run folder runs at any scale. The model of such a
run is the model with its periods scaled (:func:`rosaadl.transforms.time_scale.scale_periods`);
``measurements.json`` records ``F`` (``run.period_scale``) so that ``analyze --compare``
compares against that model.

``--period-scale auto`` takes the smallest ``F`` (rounded up to a tenth, at least 1) such that
the predicted load of every CPU of this machine is at most :data:`AUTO_TARGET_PERCENT`: a node's
predicted load is Σ ``cet_max / period`` of its threads (the model's CET / Period, the work the
workload twin burns), spread evenly over the CPUs it is bound to here (the model's cores mapped
as :mod:`~rosaadl.workflow.run.cores` maps them; a node bound to none, over all of them). The
rest of each CPU is left to what the model does not hold: the executor, serialization and DDS
of every node, the run's topic monitor and whatever else the machine runs.
"""

from __future__ import annotations

import math
from dataclasses import replace

from rosaadl.workflow.run.cores import Machine, map_cpus
from rosaadl.workflow.run.plan import NodeLaunch, RunError, RunPlan

__all__ = [
    "AUTO_TARGET_PERCENT",
    "SCALED_PARAMETERS",
    "parse_period_scale",
    "scaled_plan",
    "predicted_cpu_loads",
    "auto_period_scale",
]

#: ``--period-scale auto`` keeps every CPU's predicted load at most this (% of one CPU).
AUTO_TARGET_PERCENT = 60.0
#: The node parameters (suffixes of ``<thread>.``) a period scale multiplies.
SCALED_PARAMETERS = (".period", ".deadline", ".offset")


def parse_period_scale(text: str) -> float | None:
    """``--period-scale``'s value: a number > 0, or None for ``auto``; a :class:`RunError` else."""
    if text.strip().lower() == "auto":
        return None
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or value <= 0:
        raise RunError(f"--period-scale is a number greater than 0 or auto, not {text!r}")
    return value


def _is_number(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _scaled_parameters(node: NodeLaunch, factor: float) -> list[tuple[str, object]]:
    return [
        (name, float(value) * factor)
        if name.endswith(SCALED_PARAMETERS) and _is_number(value) and value > 0
        else (name, value)
        for name, value in node.parameters
    ]


def scaled_plan(plan: RunPlan, factor: float) -> RunPlan:
    """``plan`` with every node's periods and deadlines multiplied by ``factor`` and every
    topic's modelled rate divided by it (the plan itself is left as it is)."""
    if factor == 1:
        return plan
    return replace(
        plan,
        nodes=[replace(node, parameters=_scaled_parameters(node, factor)) for node in plan.nodes],
        topics=[
            replace(
                topic, model_rate_hz=None if topic.model_rate_hz is None else topic.model_rate_hz / factor
            )
            for topic in plan.topics
        ],
    )


def _node_load(node: NodeLaunch) -> float:
    """Σ cet_max / period of the node's threads, in % of one CPU."""
    values = dict(node.parameters)
    load = 0.0
    for name, cet in values.items():
        if not name.endswith(".cet_max") or not _is_number(cet):
            continue
        period = values.get(name[: -len(".cet_max")] + ".period")
        if _is_number(period) and period > 0:
            load += float(cet) / float(period) * 100
    return load


def predicted_cpu_loads(nodes: list[NodeLaunch], here: Machine) -> dict[int, float]:
    """Per CPU of this machine: the predicted load of the nodes on it, in % (unscaled)."""
    loads = dict.fromkeys(here.cpus, 0.0)
    for node in nodes:
        cpus = map_cpus(node.cpus, here.cpus)[0] if node.cpus else list(here.cpus)
        for cpu in cpus:
            loads[cpu] = loads.get(cpu, 0.0) + _node_load(node) / len(cpus)
    return loads


def auto_period_scale(nodes: list[NodeLaunch], here: Machine, target: float = AUTO_TARGET_PERCENT) -> float:
    """The smallest factor, in tenths and at least 1, that brings every CPU's predicted load to
    ``target`` % or less (see the module docstring)."""
    highest = max(predicted_cpu_loads(nodes, here).values(), default=0.0)
    return max(1.0, math.ceil(round(highest / target * 10, 9)) / 10)

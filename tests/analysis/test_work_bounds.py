"""Every analysis of a scheduling case ends in bounded work with a stated result: response-time
iterations stop at their work bound, a period below the time resolution is an error, and a
simulation cut by its job cap never passes."""

from __future__ import annotations

import random
import time
from fractions import Fraction

import pytest
from time_limit import within_seconds

from rosaadl import model
from rosaadl.analysis.edf_response import bounded_edf_response_times
from rosaadl.analysis.report import run_analyses
from rosaadl.analysis.schedulability import (
    analyze_schedulability,
    bounded_response_times,
    response_times,
    utilization,
    utilization_test,
)
from rosaadl.analysis.simulation import simulate, simulation_text
from rosaadl.analysis.tasks import Processor, Scheduler, Task, TaskSet, taskset_from_instance
from rosaadl.analysis.work_bounds import RTA_STEP_LIMIT
from rosaadl.exporters.report import render_report

LIMIT_S = 10
# Utilisation exactly 1, co-prime periods: the busy period is the hyperperiod (~10⁹ jobs).
COPRIME = (1009, 1013, 1019, 1021)


_ten_seconds = pytest.fixture(autouse=True, name="ten_seconds")(within_seconds(LIMIT_S))


def _full_load(scheduler: Scheduler, preemptive: bool = True) -> TaskSet:
    tasks = tuple(Task(f"t{p}", 4 * p, p, processor="cpu") for p in COPRIME)
    return TaskSet(tasks, (Processor("cpu", scheduler, preemptive=preemptive),))


def test_fixed_priority_full_load_stops_at_the_work_bound_with_a_miss():
    start = time.process_time()
    result = analyze_schedulability(_full_load(Scheduler.RATE_MONOTONIC))
    assert time.process_time() - start < LIMIT_S
    domain = result.domain("cpu")
    assert domain.schedulable is False
    row = {r.name: r for r in domain.tasks}["t1021"]
    assert row.met is False and not row.wcrt_exact and row.wcrt > row.deadline
    assert row.as_dict()["wcrt_at_least"] is True
    assert any("at least" in d.message and "work bound" in d.message for d in result.diagnostics)
    # the tasks whose busy windows end are exact, as before
    assert {r.name: r.wcrt for r in domain.tasks if r.wcrt_exact} == {
        "t1009": 1009,
        "t1013": 2022,
        "t1019": 3041,
    }


def test_the_html_report_shows_a_lower_bound_as_such():
    threads = [(f"t{p}", (4 * p, "us"), (p, "us")) for p in (1009, 1013, 1019, 1021)]
    root = _instance(threads, protocol="RMS")
    report = run_analyses(root, only="sched")
    html, _ = render_report(root, report)
    row = {r.name.rsplit(".", 1)[-1]: r for r in report.schedulability.domains[0].tasks}["t1021"]
    assert not row.wcrt_exact
    assert f"&gt;={row.wcrt:,}".replace(",", " ") in html


def test_public_response_times_leave_a_cut_task_undecided():
    tasks = _full_load(Scheduler.RATE_MONOTONIC).tasks
    tasks = tuple(Task(t.name, t.period, t.capacity, priority=-t.period) for t in tasks)
    values, cut = bounded_response_times(tasks)
    assert set(cut) == {"t1021"} and values["t1021"] == cut["t1021"]
    assert response_times(tasks)["t1021"] is None
    assert response_times(tasks, step_limit=10 * RTA_STEP_LIMIT)["t1019"] == 3041


def test_non_preemptive_full_load_ends_with_a_verdict():
    result = analyze_schedulability(_full_load(Scheduler.RATE_MONOTONIC, preemptive=False))
    assert result.domain("cpu").schedulable is False
    assert any("not decided" in d.message for d in result.diagnostics)


def test_edf_full_load_is_cut_and_the_utilisation_test_decides():
    values, cut = bounded_edf_response_times(_full_load(Scheduler.EARLIEST_DEADLINE_FIRST).tasks)
    assert set(cut) == {f"t{p}" for p in COPRIME}
    assert all(values[name] == cut[name] for name in cut)
    result = analyze_schedulability(_full_load(Scheduler.EARLIEST_DEADLINE_FIRST))
    domain = result.domain("cpu")
    assert domain.rta_schedulable is None and domain.schedulable is True
    assert all(r.wcrt is None and r.met is None and r.wcrt_exact for r in domain.tasks)
    assert "wcrt_at_least" not in domain.tasks[0].as_dict()
    assert sum("cut after" in d.message for d in result.diagnostics) == len(COPRIME)


# =============================================================================== simulation


def _late_overload() -> TaskSet:
    # U = 0.5 + 50002/100003 > 1 under EDF; the first miss is at 300 000, past a cap of 2 000 jobs.
    tasks = (Task("a", 10, 5, processor="cpu"), Task("b", 100003, 50002, processor="cpu"))
    return TaskSet(tasks, (Processor("cpu", Scheduler.EARLIEST_DEADLINE_FIRST),))


def test_a_simulation_cut_before_the_first_miss_is_inconclusive():
    result = simulate(_late_overload(), max_jobs=2000, record_schedule=False)
    assert result.deadline_misses == 0 and result.inconclusive
    assert result.as_dict()["inconclusive"] is True
    assert "inconclusive" in simulation_text(result)[0]
    whole = simulate(_late_overload(), max_jobs=200_000, record_schedule=False)
    assert whole.deadline_misses and not whole.inconclusive


def test_a_given_horizon_is_not_a_cut():
    result = simulate(_late_overload(), horizon=1000, record_schedule=False)
    assert not result.inconclusive and "inconclusive" not in result.as_dict()


def test_a_sub_resolution_period_never_raises_the_horizon_past_the_job_cap():
    # the feasibility interval, 1 us, holds 10⁹ jobs; the cap once rounded the horizon up to it
    fast = Task("fast", Fraction(1, 10**9), Fraction(1, 10**10), processor="cpu")
    tasks = (fast, Task("slow", 1, Fraction(1, 2), processor="cpu"))
    result = simulate(TaskSet(tasks, (Processor("cpu", Scheduler.RATE_MONOTONIC),)), max_jobs=1000)
    assert result.task("fast").released <= 1000 and result.inconclusive


# =============================================================================== instance models


def _set(obj, prop, value):
    obj.ownedPropertyAssociations.append(
        model.new(
            "PropertyAssociation", property=prop, ownedValues=[model.new("ModalPropertyValue", value=value)]
        )
    )


def _number(value, unit):
    kind = "RealValue" if isinstance(value, float) else "IntegerValue"
    return model.new(kind, value=value, unit=unit)


def _instance(threads: list[tuple[str, object, object]], protocol: str = "EDF"):
    root = model.new("SystemInstance", name="robot_impl_Instance", category="system")
    cpu = model.new("ComponentInstance", name="cpu", category="processor")
    root.componentInstances.append(cpu)
    _set(
        cpu,
        "Deployment_Properties::Scheduling_Protocol",
        model.new("ListValue", ownedItems=[model.new("NamedValue", name=protocol)]),
    )
    process = model.new("ComponentInstance", name="node", category="process")
    root.componentInstances.append(process)
    for name, period, cost in threads:
        thread = model.new("ComponentInstance", name=name, category="thread")
        process.componentInstances.append(thread)
        _set(thread, "Timing_Properties::Period", _number(*period))
        _set(thread, "Timing_Properties::Compute_Execution_Time", _number(*cost))
        _set(thread, "Thread_Properties::Dispatch_Protocol", model.new("NamedValue", name="Periodic"))
        binding = model.new("InstanceReferenceValue", referencedInstanceObject=cpu)
        _set(
            thread,
            "Deployment_Properties::Actual_Processor_Binding",
            model.new("ListValue", ownedItems=[binding]),
        )
    return root


def test_a_period_below_the_time_resolution_is_a_located_error():
    root = _instance([("fast", (0.001, "ps"), (0.0001, "ps")), ("slow", (10, "ms"), (1, "ms"))])
    taskset = taskset_from_instance(root)
    assert [t.name.rsplit(".", 1)[-1] for t in taskset.tasks] == ["slow"]
    errors = [d for d in taskset.diagnostics if d.severity == "error"]
    assert len(errors) == 1 and "below the time resolution 1 ps" in errors[0].message
    assert errors[0].location.path.endswith("fast")
    ok = taskset_from_instance(_instance([("fine", (1, "ps"), (0.5, "ps"))]))
    assert [t.name.rsplit(".", 1)[-1] for t in ok.tasks] == ["fine"]


def test_a_cut_simulation_alone_is_inconclusive_and_fails_the_run():
    # U > 1 under EDF, first miss near 3.3·10⁹ us; the job cap (10⁶) cuts the horizon near 10⁷ us
    root = _instance([("a", (10, "us"), (5, "us")), ("b", (10000003, "us"), (5000002, "us"))])
    report = run_analyses(root, only="sim", simulation_horizon=None)
    assert report.inconclusive and not report.ok
    assert report.as_dict()["inconclusive"] is True
    assert "INCONCLUSIVE" in report.text().splitlines()[-1]
    # the feasibility tests decide (utilisation above 1: not schedulable), so the run is decided
    both = run_analyses(root, only="sched,sim")
    assert not both.inconclusive and not both.ok and "FAILED" in both.text()


def _jeffay_by_every_length(tasks: list[Task]) -> bool:
    ordered = sorted(tasks, key=lambda t: t.period)
    if utilization(ordered) > 1:
        return False
    for i in range(1, len(ordered)):
        for length in range(ordered[0].period + 1, ordered[i].period):
            demand = ordered[i].capacity + sum(
                (length - 1) // ordered[j].period * ordered[j].capacity for j in range(i)
            )
            if demand > length:
                return False
    return True


def test_jeffay_condition_checks_the_demand_steps_only():
    rng = random.Random(21)
    for _ in range(300):
        tasks = [Task(f"t{k}", rng.randint(2, 60), 1, processor="cpu") for k in range(rng.randint(2, 4))]
        tasks = [Task(t.name, t.period, rng.randint(1, max(1, t.period // 3))) for t in tasks]
        expected = _jeffay_by_every_length(tasks)
        assert utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, False, tasks) is expected


def test_jeffay_condition_on_far_apart_periods_ends():
    # every length in (2, 10⁹) was tried: 10⁹ steps
    tasks = [Task("fast", 2, 1), Task("slow", 10**9, 1)]
    assert utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, False, tasks) is None
    tasks = [Task("fast", 2, 1), Task("slow", 2 * 10**5, 1)]
    assert utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, False, tasks) is True

"""Event-driven scheduling simulation: schedules checked by hand, resource protocols,
multi-core, LLF, properties against the response-time analysis (hypothesis), and a side by
side with SimSo when it is installed."""

from __future__ import annotations

import contextlib
import io
import random
from dataclasses import replace
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from benchmarks.generators.tasks import simso_model, simso_response_times
from rosaadl.analysis.schedulability import (
    analyze_schedulability,
    blocking_times,
    response_times,
    utilization,
)
from rosaadl.analysis.simulation import simulate
from rosaadl.analysis.tasks import (
    CriticalSection,
    Dispatch,
    Processor,
    Protocol,
    Resource,
    Scheduler,
    Task,
    TaskSet,
)
from rosaadl.errors import ModelError


def _gantt(result, core: str = "") -> list[tuple]:
    return [(i.start, i.end, i.task) for i in result.schedule if i.core == core]


def _completions(result) -> dict[str, list]:
    return {t.name: [j.completion for j in result.jobs_of(t.name)] for t in result.tasks}


# =============================================================================== basic schedules


def test_edf_schedule_and_deadline_ties():
    tasks = [Task("a", 4, 2), Task("b", 6, 3)]
    result = simulate(TaskSet.uniprocessor(tasks, Scheduler.EARLIEST_DEADLINE_FIRST))
    # at 8, a's third job and b's second share deadline 12: the one activated first runs first
    assert _gantt(result) == [(0, 2, "a"), (2, 5, "b"), (5, 7, "a"), (7, 10, "b"), (10, 12, "a")]
    assert [j.response_time for j in result.jobs_of("a")] == [2, 3, 4]
    assert result.task("b").worst_response == 5 and result.ok
    assert result.horizons == {("cpu", ""): 12}


def test_preemptive_and_non_preemptive_fixed_priority():
    tasks = [Task("high", 5, 1, priority=2, offset=1), Task("low", 10, 4, priority=1)]
    preemptive = simulate(TaskSet.uniprocessor(tasks))
    assert preemptive.task("high").first_response == 1
    assert preemptive.task("low").preemptions == 2  # once per job, over 2 * 10 + 1
    assert _gantt(preemptive)[:3] == [(0, 1, "low"), (1, 2, "high"), (2, 5, "low")]
    blocking = simulate(TaskSet.uniprocessor(tasks, preemptive=False))
    assert blocking.task("high").first_response == 4  # waits for low (started at 0) until 4, ends at 5
    assert blocking.task("low").preemptions == 0


def test_rate_monotonic_priorities_are_assigned_before_simulating():
    tasks = [Task("slow", 20, 5), Task("fast", 5, 1)]
    result = simulate(TaskSet.uniprocessor(tasks, Scheduler.RATE_MONOTONIC))
    assert {t.name: t.priority for t in result.tasks} == {"slow": 1, "fast": 2}
    assert result.task("fast").worst_response == 1


def test_a_task_runs_one_job_at_a_time():
    result = simulate(TaskSet.uniprocessor([Task("t", 2, 3)]), horizon=7)
    jobs = result.jobs_of("t")
    assert [(j.release, j.start, j.completion) for j in jobs] == [
        (0, 0, 3),
        (2, 3, 6),
        (4, 6, None),
        (6, None, None),
    ]
    assert [j.missed for j in jobs] == [True, True, None, None]
    # unfinished jobs whose deadline passed count as misses too
    assert result.task("t").deadline_misses == 3 and not result.ok


def test_aperiodic_task_and_fractional_times():
    tasks = [
        Task("p", Fraction(1, 2), Fraction(1, 4), priority=2),
        Task(
            "once",
            None,
            Fraction(1, 3),
            deadline=2,
            offset=Fraction(1, 3),
            priority=1,
            dispatch=Dispatch.APERIODIC,
        ),
    ]
    result = simulate(TaskSet.uniprocessor(tasks))
    # the interval of the periodic task, stretched to the aperiodic job's deadline
    assert result.horizons[("cpu", "")] == Fraction(1, 3) + 2
    once = result.jobs_of("once")
    assert len(once) == 1 and once[0].release == Fraction(1, 3)
    assert once[0].completion == Fraction(11, 12)  # preempted by p at 1/2 after 1/6 of work
    assert all(isinstance(i.start, int | Fraction) for i in result.schedule)


def test_horizon_and_job_limit():
    tasks = [Task("a", 3, 1), Task("b", 7, 2)]
    assert simulate(TaskSet.uniprocessor(tasks), horizon=10).horizons[("cpu", "")] == 10
    limited = simulate(TaskSet.uniprocessor(tasks), max_jobs=5)
    assert limited.horizons[("cpu", "")] < 21
    assert any("simulated up to" in d.message for d in limited.diagnostics)
    with pytest.raises(ModelError):
        simulate(TaskSet.uniprocessor(tasks), horizon=0)
    with pytest.raises(ModelError):
        simulate(TaskSet.uniprocessor(tasks), horizon=2.5)


def test_result_serialises():
    result = simulate(TaskSet.uniprocessor([Task("a", 4, 1, path="sys.a")]))
    data = result.as_dict()
    assert data["deadline_misses"] == 0
    assert data["tasks"][0]["path"] == "sys.a" and data["tasks"][0]["worst_response"] == 1


# =============================================================================== resources


def _inversion(protocol: Protocol, m_uses_other: bool = False) -> TaskSet:
    """low locks r from t=0 for 3 units; mid arrives at 1; high, needing r at once, at 2."""
    tasks = [
        Task("high", 20, 2, priority=3, offset=2, critical_sections=(CriticalSection("r", 0, 1),)),
        Task(
            "mid",
            20,
            3,
            priority=2,
            offset=1,
            critical_sections=(CriticalSection("s", 0, 1),) if m_uses_other else (),
        ),
        Task("low", 20, 4, priority=1, critical_sections=(CriticalSection("r", 0, 3),)),
    ]
    resources = [Resource("r", protocol), Resource("s", protocol)]
    return TaskSet.uniprocessor(tasks, resources=resources)


def test_no_protocol_lets_the_middle_task_delay_the_high_one():
    result = simulate(_inversion(Protocol.NONE), horizon=20)
    assert _completions(result) == {"high": [8], "mid": [4], "low": [9]}
    assert result.task("high").first_response == 6


def test_priority_inheritance():
    result = simulate(_inversion(Protocol.PIP), horizon=20)
    assert _completions(result) == {"high": [6], "mid": [8], "low": [9]}
    assert _gantt(result) == [
        (0, 1, "low"),
        (1, 2, "mid"),
        (2, 4, "low"),
        (4, 6, "high"),
        (6, 8, "mid"),
        (8, 9, "low"),
    ]


def test_priority_ceiling_blocks_on_the_system_ceiling():
    # under PCP mid may not lock s while low holds r (ceiling 3 >= 2): low keeps running
    pcp = simulate(_inversion(Protocol.PCP, m_uses_other=True), horizon=20)
    assert _completions(pcp) == {"high": [5], "mid": [8], "low": [9]}
    pip = simulate(_inversion(Protocol.PIP, m_uses_other=True), horizon=20)
    assert _completions(pip) == {"high": [6], "mid": [8], "low": [9]}


def test_immediate_ceiling():
    result = simulate(_inversion(Protocol.IPCP), horizon=20)
    assert _gantt(result) == [(0, 3, "low"), (3, 5, "high"), (5, 8, "mid"), (8, 9, "low")]
    assert result.task("high").first_response == 3 and result.task("mid").preemptions == 0


def test_deadlock_is_reported():
    tasks = [
        Task(
            "a",
            20,
            3,
            priority=2,
            offset=1,
            critical_sections=(CriticalSection("r1", 0, 3), CriticalSection("r2", 1, 2)),
        ),
        Task(
            "b",
            20,
            3,
            priority=1,
            critical_sections=(CriticalSection("r2", 0, 3), CriticalSection("r1", 2, 3)),
        ),
    ]
    taskset = TaskSet.uniprocessor(
        tasks, resources=[Resource("r1", Protocol.PIP), Resource("r2", Protocol.PIP)]
    )
    result = simulate(taskset)
    assert any(d.severity == "error" and "deadlock" in d.message for d in result.diagnostics)
    assert result.task("a").completed == 0 and not result.ok


def test_edf_with_priority_inheritance_of_deadlines():
    tasks = [
        Task("urgent", 10, 1, deadline=3, offset=1, critical_sections=(CriticalSection("r", 0, 1),)),
        Task("other", 10, 2, deadline=6, offset=1),
        Task("holder", 10, 3, deadline=10, critical_sections=(CriticalSection("r", 0, 2),)),
    ]
    taskset = TaskSet.uniprocessor(
        tasks, Scheduler.EARLIEST_DEADLINE_FIRST, resources=[Resource("r", Protocol.PCP)]
    )
    result = simulate(taskset)
    assert any("simulated as priority inheritance" in d.message for d in result.diagnostics)
    # holder inherits urgent's deadline and finishes its section before other runs
    assert _completions(result)["urgent"][0] == 3
    assert result.task("urgent").deadline_misses == 0


# =============================================================================== multi-core, LLF


def test_partitioned_cores_run_in_parallel():
    soc = Processor("soc", Scheduler.RATE_MONOTONIC, cores=("c0", "c1"))
    tasks = [
        Task("a", 4, 2, processor="soc", core="c0"),
        Task("b", 8, 3, processor="soc", core="c0"),
        Task("c", 5, 5, processor="soc", core="c1"),
    ]
    result = simulate(TaskSet(tasks, (soc,)))
    assert _gantt(result, "c1") == [(0, 5, "c")]
    assert _gantt(result, "c0") == [(0, 2, "a"), (2, 4, "b"), (4, 6, "a"), (6, 7, "b")]
    assert result.horizons == {("soc", "c0"): 8, ("soc", "c1"): 5}


def test_resource_shared_across_cores():
    soc = Processor("soc", cores=("c0", "c1"))
    tasks = [
        Task("holder", 10, 4, processor="soc", core="c0", critical_sections=(CriticalSection("r", 0, 3),)),
        Task(
            "waiter",
            10,
            2,
            offset=1,
            processor="soc",
            core="c1",
            critical_sections=(CriticalSection("r", 0, 1),),
        ),
    ]
    result = simulate(TaskSet(tasks, (soc,), (Resource("r", Protocol.PIP),)))
    assert result.jobs_of("holder")[0].completion == 4
    assert result.jobs_of("waiter")[0].completion == 5  # waits on c1 for c0's section to end at 3
    assert result.horizons[("soc", "c0")] == result.horizons[("soc", "c1")] == 21


def test_least_laxity_first():
    equal = simulate(TaskSet.uniprocessor([Task("a", 4, 2), Task("b", 4, 2)], Scheduler.LEAST_LAXITY_FIRST))
    assert _gantt(equal) == [(0, 1, "a"), (1, 3, "b"), (3, 4, "a")]
    tasks = [Task("s1", 2, 1), Task("s2", 5, 1), Task("s3", 7, 2)]
    result = simulate(TaskSet.uniprocessor(tasks, Scheduler.LEAST_LAXITY_FIRST))
    assert result.ok and result.horizons[("cpu", "")] == 70
    assert sum(i.end - i.start for i in result.schedule) == 70 * utilization(tasks)


# =============================================================================== properties (hypothesis)

_PERIODS = [2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 24, 30]


@st.composite
def _task_sets(draw, *, deadlines: bool = True, offsets: bool = False, resources: bool = False):
    n = draw(st.integers(1, 6))
    order = draw(st.permutations(range(n)))
    tasks = []
    for i in range(n):
        period = draw(st.sampled_from(_PERIODS))
        capacity = draw(st.integers(1, period))
        deadline = draw(st.integers(capacity, period)) if deadlines else period
        sections = ()
        if resources and capacity >= 2 and draw(st.booleans()):
            start = draw(st.integers(0, capacity - 1))
            end = draw(st.integers(start + 1, capacity))
            sections = (CriticalSection(draw(st.sampled_from(["r1", "r2"])), start, end),)
        tasks.append(
            Task(
                f"t{i}",
                period,
                capacity,
                deadline=deadline,
                priority=order[i] + 1,
                offset=draw(st.integers(0, period)) if offsets else 0,
                critical_sections=sections,
            )
        )
    return tasks


_SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@_SETTINGS
@given(_task_sets(offsets=True))
def test_simulation_never_exceeds_the_rta_bound(tasks):
    bounds = response_times(tasks)
    result = simulate(TaskSet.uniprocessor(tasks), record_schedule=False)
    for stats in result.tasks:
        bound = bounds[stats.name]
        if bound is not None and stats.worst_response is not None:
            assert stats.worst_response <= bound


@_SETTINGS
@given(_task_sets(resources=True), st.sampled_from([Protocol.PIP, Protocol.PCP, Protocol.IPCP]))
def test_simulation_with_resources_never_exceeds_the_rta_bound(tasks, protocol):
    taskset = TaskSet.uniprocessor(tasks, resources=[Resource("r1", protocol), Resource("r2", protocol)])
    blocking = blocking_times(taskset.tasks, taskset)
    bounded = [
        Task(t.name, t.period, t.capacity, t.deadline, t.priority, blocking=blocking[t.name]) for t in tasks
    ]
    bounds = response_times(bounded)
    result = simulate(taskset, record_schedule=False)
    for stats in result.tasks:
        bound = bounds[stats.name]
        if bound is not None and stats.worst_response is not None:
            assert stats.worst_response <= bound, (stats.name, stats.worst_response, bound)


@_SETTINGS
@given(_task_sets())
def test_rta_verdict_equals_simulation_for_synchronous_constrained_tasks(tasks):
    taskset = TaskSet.uniprocessor(tasks)
    verdict = analyze_schedulability(taskset).domains[0].rta_schedulable
    result = simulate(taskset, record_schedule=False)
    assert verdict is (result.deadline_misses == 0)
    if verdict:  # the synchronous release is the critical instant: first jobs reach the bound
        bounds = response_times(tasks)
        assert {t.name: t.first_response for t in result.tasks} == bounds


@_SETTINGS
@given(_task_sets(deadlines=False))
def test_edf_meets_every_deadline_exactly_when_utilisation_is_at_most_one(tasks):
    result = simulate(TaskSet.uniprocessor(tasks, Scheduler.EARLIEST_DEADLINE_FIRST), record_schedule=False)
    assert (result.deadline_misses == 0) is (utilization(tasks) <= 1)


@_SETTINGS
@given(_task_sets())
def test_non_preemptive_simulation_never_exceeds_the_rta_bound(tasks):
    bounds = response_times(tasks, preemptive=False)
    result = simulate(TaskSet.uniprocessor(tasks, preemptive=False), record_schedule=False)
    for stats in result.tasks:
        bound = bounds[stats.name]
        if bound is not None and stats.worst_response is not None:
            assert stats.worst_response <= bound


@_SETTINGS
@given(_task_sets(offsets=True), st.sampled_from(list(Scheduler)), st.booleans())
def test_fast_path_and_general_engine_agree(tasks, scheduler, preemptive):
    assume(scheduler is not Scheduler.LEAST_LAXITY_FIRST)  # LLF always takes the general engine
    plain = simulate(TaskSet.uniprocessor(tasks, scheduler, preemptive=preemptive))
    horizon = plain.horizons[("cpu", "")]
    # a critical section on a resource nobody else uses changes nothing but the engine
    first = tasks[0]
    marked = [replace(first, critical_sections=(CriticalSection("solo", 0, first.capacity),)), *tasks[1:]]
    general = simulate(
        TaskSet.uniprocessor(marked, scheduler, preemptive=preemptive, resources=[Resource("solo")]),
        horizon=horizon,
    )
    assert plain.jobs == general.jobs
    assert plain.schedule == general.schedule
    assert [(t.preemptions, t.deadline_misses) for t in plain.tasks] == [
        (t.preemptions, t.deadline_misses) for t in general.tasks
    ]


# =============================================================================== side by side with SimSo


def _simso_responses(tasks: list[Task], scheduler: str, horizon: int) -> dict[str, list]:
    simulation = simso_model(tasks, scheduler, horizon)
    with contextlib.redirect_stdout(io.StringIO()):
        simulation.run_model()
    return simso_response_times(simulation)


def _random_sets(seed: int, count: int) -> list[list[Task]]:
    rng = random.Random(seed)
    sets = []
    for _ in range(count):
        n = rng.randint(2, 7)
        priorities = rng.sample(range(1, n + 1), n)
        tasks = []
        for i in range(n):
            period = rng.choice(_PERIODS + [40, 60])
            capacity = rng.randint(1, max(1, period // 2))
            tasks.append(
                Task(
                    f"T{i}",
                    period,
                    capacity,
                    deadline=rng.randint(capacity, period),
                    priority=priorities[i],
                    offset=rng.choice([0, 0, 1, 3]),
                )
            )
        sets.append(tasks)
    return sets


@pytest.mark.parametrize("scheduler", [Scheduler.FIXED_PRIORITY, Scheduler.EARLIEST_DEADLINE_FIRST])
def test_identical_per_job_response_times_as_simso(scheduler):
    pytest.importorskip(
        "simso.core", reason="SimSo (PyPI simso 0.8.5, SimPy 2.3.1; Python < 3.12) is not available"
    )
    simso_class = (
        "simso.schedulers.FP" if scheduler is Scheduler.FIXED_PRIORITY else "simso.schedulers.EDF_mono"
    )
    compared = 0
    for tasks in _random_sets(2024 if scheduler.fixed_priority else 2025, 40):
        ours = simulate(TaskSet.uniprocessor(tasks, scheduler), record_schedule=False)
        horizon = ours.horizons[("cpu", "")]
        theirs = _simso_responses(tasks, simso_class, horizon)
        for task in tasks:
            mine = [job.response_time for job in ours.jobs_of(task.name)]
            for number, (a, b) in enumerate(zip(mine, theirs[task.name], strict=False), start=1):
                if a is not None and b is not None:
                    assert a == b, (task.name, number, a, b, tasks)
                    compared += 1
    assert compared > 500

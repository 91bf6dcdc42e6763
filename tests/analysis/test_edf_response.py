"""EDF response times (Spuri's deadline busy periods; George, Rivierre and Spuri's
non-preemptive case): a three-task set computed by hand, the cases where Cheddar's code and the
papers part, jitter, blocking through shared resources, the feasibility tests that use them,
and properties against the simulator (hypothesis)."""

from __future__ import annotations

import random
import time
from fractions import Fraction
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rosaadl.analysis.edf_response import (
    deadline_busy_period,
    edf_blocking_times,
    edf_response_times,
    release_offsets,
    synchronous_busy_period,
)
from rosaadl.analysis.schedulability import analyze_schedulability, utilization_test
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
    taskset_from_instance,
)
from rosaadl.errors import ModelError
from rosaadl.importers.cheddar import load_cheddar

EDF = Scheduler.EARLIEST_DEADLINE_FIRST

# (C, T, D): t1 has its deadline after its period
THREE = [Task("t1", 8, 2, deadline=9), Task("t2", 10, 3, deadline=8), Task("t3", 8, 1, deadline=3)]


def _edf(tasks, preemptive: bool = True, resources=()) -> TaskSet:
    return TaskSet.uniprocessor(tasks, EDF, preemptive=preemptive, resources=resources)


def _worst(taskset: TaskSet) -> dict:
    return {t.name: t.worst_response for t in simulate(taskset, record_schedule=False).tasks}


# =============================================================================== by hand


def test_three_tasks_by_hand_preemptive():
    """(C, T, D): t1 = (2, 8, 9), t2 = (3, 10, 8), t3 = (1, 8, 3); U = 0.675.

    Busy period: L = ⌈L/8⌉ 2 + ⌈L/10⌉ 3 + ⌈L/8⌉ 1, from ΣC = 6: 2 + 3 + 1 = 6, so L = 6.

    t1 (D = 9): a = 8k (0), 10k + 8 − 9 (−1, 9: none in [0, 6]), 8k + 3 − 9 (2): A = {0, 2}.
      a = 0, deadline 9: t2 counts 1 + ⌊(9 − 8)/10⌋ = 1 job, t3 1 + ⌊(9 − 3)/8⌋ = 1;
      L(0) = 2 + min(⌈t/10⌉, 1) 3 + min(⌈t/8⌉, 1) 1 = 6, r = 6.
      a = 2: L − a = 4 <= 6, nothing later can beat it.  R1 = 6.
    t2 (D = 8): a = 8k + 9 − 8 (1), 10k (0), 8k + 3 − 8 (3): A = {0, 1, 3}.
      a = 0, deadline 8: t1 counts 1 + ⌊(8 − 9)/8⌋ = 0, t3 1 + ⌊5/8⌋ = 1; L(0) = 3 + 1 = 4, r = 4.
      a = 1, deadline 9: t1 counts 1 + ⌊0/8⌋ = 1, t3 1 + ⌊6/8⌋ = 1; L(1) = 3 + 2 + 1 = 6, r = 5.
      a = 3: L − a = 3 <= 5.  R2 = 5 (t2 released 1 after the others).
    t3 (D = 3): A = {0, 5, 6}. a = 0, deadline 3: t1 and t2 count no job (1 + ⌊−6/8⌋,
      1 + ⌊−5/10⌋), L(0) = 1, r = 1; a = 5: L − a = 1 <= 1.  R3 = 1.
    """
    assert synchronous_busy_period(THREE) == 6
    t1, t2, t3 = THREE
    assert release_offsets(t1, THREE, 6) == [0, 2]
    assert release_offsets(t2, THREE, 6) == [0, 1, 3]
    assert release_offsets(t3, THREE, 6) == [0, 5, 6]
    assert [deadline_busy_period(t2, THREE, a) for a in (0, 1, 3)] == [4, 6, 6]
    assert deadline_busy_period(t1, THREE, 0) == 6 and deadline_busy_period(t3, THREE, 0) == 1
    assert edf_response_times(THREE) == {"t1": 6, "t2": 5, "t3": 1}


def test_three_tasks_by_hand_non_preemptive():
    """The same tasks, non-preemptive: a job with a later deadline may have started one unit
    before the busy period (C_j − 1), the job under analysis starts at L_i(a) and ends C_i later.

    t1: blocking for the busy period max(3 − 1, 1 − 1) = 2; L = 2 + ⌈L/8⌉ 2 + ⌈L/10⌉ 3 + ⌈L/8⌉ 1
      = 8; A = {0, 2, 8}.
      a = 0: no deadline after 9, blocking 0; t2 1 job, t3 1 job (1 + ⌊t/·⌋ capped at 1):
      L(0) = 3 + 1 = 4, r = 4 + 2 − 0 = 6.  a = 2: t3 counts 1 + ⌊8/8⌋ = 2 but only
      1 + ⌊4/8⌋ = 1 is released by the start: L(2) = 3 + 1 = 4, r = 4.  a = 8: one earlier
      job of t1 (2), L(8) = 2 + 3 + 1 = 6, r = 0.  R1 = 6.
    t2: busy-period blocking max(2 − 1, 1 − 1) = 1, L = 7, A = {0, 1, 3}.
      a = 0: t1's deadline 9 > 8 blocks 2 − 1 = 1; t3 1 job; L(0) = 1 + 1 = 2, r = 2 + 3 = 5.
      a = 1: no later deadline; t1 1 job, t3 1 job; L(1) = 3, r = 3 + 3 − 1 = 5.
      a = 3: t3 counts up to 2 jobs but 1 + ⌊3/8⌋ = 1 by the start: L(3) = 3, r = 3.  R2 = 5.
    t3: busy-period blocking 2, L = 8, A = {0, 5, 6, 8}.
      a = 0: t1 (9) and t2 (8) have later deadlines: blocking max(1, 2) = 2, L(0) = 2, r = 3.
      a = 5: blocking 1 (t1), t2 1 job: L(5) = 4, r = 0; a = 6: L(6) = 5, r = 0;
      a = 8: L(8) = 1 + 2 + 3 = 6, r = −1.  R3 = 3.
    """
    t1, t2, t3 = THREE
    assert synchronous_busy_period(THREE, 2) == 8 and synchronous_busy_period(THREE, 1) == 7
    assert release_offsets(t1, THREE, 8) == [0, 2, 8]
    assert release_offsets(t3, THREE, 8) == [0, 5, 6, 8]
    assert [deadline_busy_period(t1, THREE, a, preemptive=False) for a in (0, 2, 8)] == [4, 4, 6]
    assert [deadline_busy_period(t2, THREE, a, preemptive=False) for a in (0, 1, 3)] == [2, 3, 3]
    assert [deadline_busy_period(t3, THREE, a, preemptive=False) for a in (0, 5, 6, 8)] == [2, 4, 5, 6]
    assert edf_response_times(THREE, preemptive=False) == {"t1": 6, "t2": 5, "t3": 3}


def test_the_hand_computed_bounds_are_reached():
    """Each bound is a response the simulator shows for some first releases (offsets)."""
    assert _worst(_edf(THREE)) == {"t1": 6, "t2": 4, "t3": 1}  # all released at 0
    shifted = [THREE[0], Task("t2", 10, 3, deadline=8, offset=1), THREE[2]]
    assert _worst(_edf(shifted))["t2"] == 5
    late = [THREE[0], THREE[1], Task("t3", 8, 1, deadline=3, offset=1)]
    assert _worst(_edf(late, preemptive=False))["t3"] == 3
    assert _worst(_edf(THREE, preemptive=False))["t1"] == 6


# =============================================================================== where Cheddar's code differs


def test_negative_arrivals_are_not_tried():
    """Cheddar tries a = 2 − 10 = −8 for the second task, where its iteration stays at
    L(a) = 0 and gives a response of 8; the papers start at a = 0: 2, as simulated."""
    tasks = [Task("a", 2, 1), Task("b", 10, 1)]
    assert release_offsets(tasks[1], tasks, 10) == [0, 2, 4, 6, 8, 10]
    assert edf_response_times(tasks) == {"a": 1, "b": 2}
    assert _worst(_edf(tasks)) == {"a": 1, "b": 2}


def test_every_arrival_up_to_the_busy_period_is_tried():
    """Cheddar stops t1's arrivals at a = 4, where L(4) = 3 <= a, and reports 2; a = 7 (its
    deadline 12 with t2's third job) gives L(7) = 10, so 3, which the simulation reaches
    when t1 starts at 2."""
    tasks = [
        Task("t0", 4, 1, deadline=3),
        Task("t1", 5, 1, deadline=5),
        Task("t2", 3, 1, deadline=6),
        Task("t3", 15, 2, deadline=11),
    ]
    assert deadline_busy_period(tasks[1], tasks, 4) == 3
    assert deadline_busy_period(tasks[1], tasks, 7) == 10
    assert edf_response_times(tasks)["t1"] == 3
    shifted = [tasks[0], Task("t1", 5, 1, deadline=5, offset=2), tasks[2], tasks[3]]
    assert _worst(_edf(shifted))["t1"] == 3


# =============================================================================== jitter, limits, exactness


def test_release_jitter_by_hand():
    """a = (1, 4, 4) with jitter 3, b = (2, 8, 8). For b at a = 0 (deadline 8), a's jobs
    arriving at −3 (released at 0) and 1 both count: 1 + ⌊(8 − 4 + 3)/4⌋ = 2, and
    ⌈(t + 3)/4⌉ = 2 from t = 2: L(0) = 2 + 2 = 4 instead of 3 without jitter. For a, the
    arrivals start at −J = −3: L(−3) = 1, r = 4 = C + J."""
    jittery = [Task("a", 4, 1, jitter=3), Task("b", 8, 2)]
    plain = [Task("a", 4, 1), Task("b", 8, 2)]
    assert synchronous_busy_period(jittery) == 4
    assert release_offsets(jittery[0], jittery, 4) == [-3, 1, 4]
    assert deadline_busy_period(jittery[1], jittery, 0) == 4
    assert edf_response_times(jittery) == {"a": 4, "b": 4}
    assert edf_response_times(plain) == {"a": 1, "b": 3}
    with pytest.raises(ModelError, match="before -J_i"):
        deadline_busy_period(jittery[0], jittery, -4)


def test_overload_is_unbounded_and_full_load_is_not():
    """a = (2, 4), b = (3, 6), U = 1. Non-preemptive, the busy period never ends (blocking 2 at
    U = 1) but one hyperperiod (12) of arrivals bounds the responses:
    a: A = {0, 2, 4, 8}; a = 0: b's later deadline blocks 2, r = 2 + 2 = 4; a = 2: b's job
       (deadline 6) counts, r = 3 + 2 − 2 = 3; a = 4: r = 2 + 3 + 2 − 4 = 3; a = 8: one more
       job of b, L = 4 + 6 = 10, r = 4.  R = 4.
    b: A = {0, 2, 6, 10}; a = 0: a's job (deadline 4), r = 2 + 3 = 5; a = 2: r = 3;
       a = 6: L = 3 + 4 = 7, r = 4; a = 10: r = 0.  R = 5.
    With jitter 1 on a (preemptive): b at a = 1 and a = 6 waits for two then three jobs of a:
    r = 7 − 1 = 6 and 12 − 6 = 6; a at a = 3 and a = 8: r = 4."""
    assert edf_response_times([Task("a", 4, 3), Task("b", 5, 2)]) == {"a": None, "b": None}
    full = [Task("a", 4, 2), Task("b", 6, 3)]
    assert edf_response_times(full) == {"a": 4, "b": 6}
    assert synchronous_busy_period(full, 2) is None
    assert edf_response_times(full, preemptive=False) == {"a": 4, "b": 5}
    assert edf_response_times([Task("a", 4, 2, jitter=1), Task("b", 6, 3)]) == {"a": 4, "b": 6}


def test_fractions_stay_exact():
    tasks = [Task("a", Fraction(1, 2), Fraction(1, 8)), Task("b", Fraction(3, 4), Fraction(1, 4))]
    assert edf_response_times(tasks) == {"a": Fraction(1, 8), "b": Fraction(3, 8)}
    assert synchronous_busy_period(tasks, Fraction(1, 16)) == Fraction(7, 16)


def test_tasks_without_period_are_left_out():
    tasks = [Task("a", 4, 1), Task("once", None, 2, dispatch=Dispatch.APERIODIC)]
    assert edf_response_times(tasks) == {"a": 1}
    with pytest.raises(ModelError, match="no period"):
        deadline_busy_period(tasks[1], tasks, 0)


def test_edf_response_times_of_a_hundred_tasks_are_fast():
    rng = random.Random(7)
    tasks = []
    for i in range(100):
        period = rng.randrange(10_000, 1_000_000)
        tasks.append(Task(f"t{i}", period, max(1, period * 85 // 10_000)))  # U ≈ 0.85
    start = time.process_time()
    edf_response_times(tasks)
    edf_response_times(tasks, preemptive=False)
    spent = time.process_time() - start
    assert spent < 5, f"EDF response times of 100 tasks took {spent:.2f} s"


# =============================================================================== blocking


def _sharing(protocol: Protocol) -> TaskSet:
    tasks = [
        Task("urgent", 10, 1, deadline=3, critical_sections=(CriticalSection("r", 0, 1),)),
        Task("other", 10, 2, deadline=6),
        Task("holder", 10, 3, deadline=10, critical_sections=(CriticalSection("r", 0, 2),)),
    ]
    return _edf(tasks, resources=[Resource("r", protocol)])


@pytest.mark.parametrize("protocol", [Protocol.PIP, Protocol.PCP, Protocol.IPCP])
def test_blocking_by_a_job_with_a_later_deadline(protocol):
    """holder (deadline 10) may hold r for 2 units when urgent (3) and other (6) arrive."""
    taskset = _sharing(protocol)
    assert edf_blocking_times(taskset.tasks, taskset) == {"urgent": 2, "other": 2, "holder": 0}
    rows = {r.name: r for r in analyze_schedulability(taskset).domains[0].tasks}
    assert (rows["urgent"].blocking, rows["urgent"].wcrt, rows["urgent"].met) == (2, 3, True)
    assert rows["other"].wcrt == 2 + 1 + 2 and rows["holder"].wcrt == 6


def test_no_protocol_with_a_third_task_is_unbounded():
    taskset = _sharing(Protocol.NONE)
    assert edf_blocking_times(taskset.tasks, taskset) == {"urgent": None, "other": None, "holder": 0}
    result = analyze_schedulability(taskset)
    rows = {r.name: r for r in result.domains[0].tasks}
    assert rows["urgent"].wcrt is None and rows["urgent"].met is None
    assert rows["holder"].wcrt == 6
    assert result.domains[0].rta_schedulable is None
    assert any(d.location.path == "urgent" and "later deadline" in d.message for d in result.diagnostics)


# =============================================================================== the feasibility tests


def test_edf_domains_get_response_times():
    result = analyze_schedulability(_edf(THREE))
    domain = result.domains[0]
    assert {r.name: r.wcrt for r in domain.tasks} == {"t1": 6, "t2": 5, "t3": 1}
    assert all(r.met for r in domain.tasks) and domain.rta_schedulable is True
    assert [t["wcrt"] for t in result.as_dict()["processors"][0]["tasks"]] == [6, 5, 1]
    assert result.ok


def test_response_times_decide_where_the_deadline_utilisation_cannot():
    """Σ C/D = 2/9 + 3/8 + 1/3 + 3/4 > 1 fails Cheddar's EDF utilisation test, yet every
    deadline is met, t4 = (3, 24, 4) just: at a = 0 only t3's first job (deadline 3) comes
    first, L = 3 + 1 = 4; at a = 5 (deadline 9 with t1), L = 3 + 3 + 1 + 2 = 9, r = 4."""
    tasks = [*THREE, Task("t4", 24, 3, deadline=4)]
    domain = analyze_schedulability(_edf(tasks)).domains[0]
    assert domain.utilization_test is False
    assert {r.name: r.wcrt for r in domain.tasks} == {"t1": 9, "t2": 8, "t3": 3, "t4": 4}
    assert domain.rta_schedulable is True and domain.schedulable is True
    assert simulate(_edf(tasks), record_schedule=False).deadline_misses == 0


def test_missed_deadlines_and_overload_are_errors():
    late = analyze_schedulability(_edf([Task("a", 4, 2, deadline=2), Task("b", 4, 1, deadline=2)]))
    rows = {r.name: r for r in late.domains[0].tasks}
    assert rows["a"].wcrt == 3 and rows["a"].met is False and not late.ok
    overloaded = analyze_schedulability(_edf([Task("a", 4, 3), Task("b", 5, 2)]))
    assert [r.wcrt for r in overloaded.domains[0].tasks] == [None, None]
    assert any("overloaded" in d.message for d in overloaded.diagnostics)
    assert not overloaded.ok


def test_llf_gets_no_response_time():
    tasks = [Task("s1", 2, 1), Task("s2", 5, 1), Task("s3", 7, 2)]
    domain = analyze_schedulability(TaskSet.uniprocessor(tasks, Scheduler.LEAST_LAXITY_FIRST)).domains[0]
    assert [r.wcrt for r in domain.tasks] == [None, None, None] and domain.rta_schedulable is None


@pytest.mark.corpus
def test_cheddar_edf_file_with_priority_inheritance(corpus: Path):
    """Cheddar 2 file (EDF, PIP): T1 (1, 10, 10) and T2 (5, 10, 10) share R1; equal deadlines,
    so neither blocks the other and each may wait for the other's whole job: 6 and 6."""
    taskset = taskset_from_instance(load_cheddar(corpus / "cheddar" / "edf_pip_resource_v2.xml"))
    domain = analyze_schedulability(taskset).domains[0]
    assert domain.scheduler is EDF
    wcrt = {r.name.rsplit(".", 1)[-1]: r.wcrt for r in domain.tasks}
    assert wcrt == {"T1": 6, "T2": 6}
    simulated = _worst(taskset)
    assert all(simulated[r.name] <= r.wcrt for r in domain.tasks)


# =============================================================================== properties (hypothesis)

_PERIODS = [2, 3, 4, 5, 6, 8, 10, 12, 15, 20]


@st.composite
def _edf_task_sets(draw, *, arbitrary: bool = True, offsets: bool = True, resources: bool = False):
    """1 to 5 tasks of utilisation at most 1/n each, deadlines up to 2T (``arbitrary``) or T."""
    n = draw(st.integers(1, 5))
    tasks = []
    for i in range(n):
        period = draw(st.sampled_from(_PERIODS))
        capacity = draw(st.integers(1, max(1, period // n)))
        deadline = draw(st.integers(capacity, 2 * period if arbitrary else period))
        sections = ()
        if resources and capacity >= 2 and draw(st.booleans()):
            begin = draw(st.integers(0, capacity - 1))
            sections = (CriticalSection(draw(st.sampled_from(["r1", "r2"])), begin, capacity),)
        offset = draw(st.integers(0, period)) if offsets else 0
        tasks.append(Task(f"t{i}", period, capacity, deadline, offset=offset, critical_sections=sections))
    return tasks


_SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@_SETTINGS
@given(_edf_task_sets(), st.booleans())
def test_simulated_responses_never_exceed_the_bound(tasks, preemptive):
    bounds = edf_response_times(tasks, preemptive=preemptive)
    for name, worst in _worst(_edf(tasks, preemptive)).items():
        if bounds[name] is not None and worst is not None:
            assert worst <= bounds[name], (name, worst, bounds[name])


@_SETTINGS
@given(_edf_task_sets(resources=True), st.sampled_from([Protocol.PIP, Protocol.PCP, Protocol.IPCP]))
def test_simulated_responses_with_resources_never_exceed_the_bound(tasks, protocol):
    taskset = _edf(tasks, resources=[Resource("r1", protocol), Resource("r2", protocol)])
    blocking = edf_blocking_times(taskset.tasks, taskset)
    bounds = edf_response_times(taskset.tasks, blocking=blocking)  # no None: every protocol bounds it
    for name, worst in _worst(taskset).items():
        if bounds[name] is not None and worst is not None:
            assert worst <= bounds[name], (name, worst, bounds[name], blocking)


@_SETTINGS
@given(_edf_task_sets(arbitrary=False, offsets=False))
def test_the_verdict_equals_the_synchronous_simulation(tasks):
    """Spuri's bound is exact for sporadic tasks, and under preemptive EDF the synchronous
    release is the worst pattern: deadlines are all met exactly when the simulation meets them."""
    taskset = _edf(tasks)
    verdict = analyze_schedulability(taskset).domains[0].rta_schedulable
    assert verdict is (simulate(taskset, record_schedule=False).deadline_misses == 0)


@_SETTINGS
@given(_edf_task_sets(arbitrary=False, offsets=False))
def test_non_preemptive_verdict_equals_jeffays_condition_when_deadlines_are_periods(tasks):
    implicit = [Task(t.name, t.period, t.capacity) for t in tasks]
    bounds = edf_response_times(implicit, preemptive=False)
    verdict = all(bounds[t.name] is not None and bounds[t.name] <= t.deadline for t in implicit)
    assert verdict is utilization_test(EDF, False, implicit)


def test_processor_with_cores_is_analysed_per_core():
    soc = Processor("soc", EDF, cores=("c0", "c1"))
    tasks = [
        Task("a", 4, 2, processor="soc", core="c0"),
        Task("b", 6, 3, processor="soc", core="c0"),
        Task("c", 5, 5, processor="soc", core="c1"),
    ]
    result = analyze_schedulability(TaskSet(tasks, (soc,)))
    assert {d.core: {r.name: r.wcrt for r in d.tasks} for d in result.domains} == {
        "c0": {"a": 4, "b": 6},
        "c1": {"c": 5},
    }

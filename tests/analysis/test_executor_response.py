"""Executor response-time bounds against the executor-faithful simulation and the Prosa-verified
analyses of ``response-time-analysis`` (rosaadl.analysis.executor_response)."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosaadl.analysis.executor_response import (
    CallbackTiming,
    fifo_response_time,
    np_edf_response_time,
    np_fixed_priority_response_time,
    polling_response_time,
    work_conserving_response_time,
)
from rosaadl.analysis.executor_simulation import POLICIES, periodic_releases, simulate_executor

prosa = pytest.importorskip("response_time_analysis")
from response_time_analysis import edf, fifo, fp  # noqa: E402
from response_time_analysis.model import (  # noqa: E402
    WCET,
    Deadline,
    FullyNonPreemptive,
    IdealProcessor,
    Priority,
    Sporadic,
    Task,
    taskset,
)

HORIZON = 10**6
EXAMPLES = 2000  # generated task sets per executor model


@st.composite
def callback_sets(draw, most=5, distinct=False):
    n = draw(st.integers(1, most))
    priorities = draw(st.permutations(range(n))) if distinct else [draw(st.integers(0, 3)) for _ in range(n)]
    items = []
    for i in range(n):
        period = draw(st.integers(4, 40))
        wcet = draw(st.integers(1, max(1, period // n)))
        deadline = draw(st.integers(wcet, 2 * period))
        items.append(CallbackTiming(f"c{i}", period, wcet, deadline, priorities[i], draw(st.integers(0, 9))))
    return items


@st.composite
def runs(draw):
    """A callback set, sporadic releases (offsets, extra gaps), execution times up to the WCET and
    the multi-threaded executor's threads, time slice and callback groups. Everything past the
    callback set comes from one drawn random generator (cheap to draw, so that thousands of sets
    per executor model stay fast)."""
    items = draw(callback_sets())
    rng = draw(st.randoms(use_true_random=False))
    span = min(math.lcm(*(c.period for c in items)), 600) + max(c.period for c in items)
    offsets = [rng.randint(0, c.period) if rng.random() < 0.5 else 0 for c in items]
    gaps = [[rng.choice((0, 0, 1, 3)) for _ in range(rng.randint(1, 4))] for _ in items]
    executions = [[rng.randint(1, c.wcet) for _ in range(rng.randint(1, 3))] for c in items]
    threads, quantum = rng.randint(1, 3), rng.randint(1, 6)
    groups = [rng.choice(("a", "b", None)) for _ in items]
    return items, periodic_releases(items, span, offsets, gaps), executions, threads, quantum, groups


def _bound(policy, items, index):
    if policy == "fifo":
        return fifo_response_time(items, horizon=HORIZON)
    if policy == "pfifo":
        return np_fixed_priority_response_time(items, index, horizon=HORIZON)
    if policy == "edf":
        return np_edf_response_time(items, index, horizon=HORIZON)
    if policy == "polling":
        return polling_response_time(items, index, horizon=HORIZON)
    return work_conserving_response_time(items, horizon=HORIZON)


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None)
@given(runs())
def test_simulated_response_never_exceeds_the_bound(run):
    """Every executor model on the same generated sets: the simulated worst response of each
    callback never exceeds its bound, and a set of utilisation below 1 always has a bound."""
    items, releases, executions, threads, quantum, groups = run
    underloaded = sum(c.wcet / period for c in items for period in (c.period, *c.streams)) < 1
    for policy in POLICIES:
        result = simulate_executor(
            items, policy, releases, executions=executions, threads=threads, groups=groups, quantum=quantum
        )
        for index, worst in enumerate(result.worst):
            bound = _bound(policy, items, index)
            if worst is not None and bound is not None:
                assert worst <= bound, (policy, items, index)
            if underloaded:
                assert bound is not None, (policy, items, index)


@st.composite
def runs_with_streams(draw):
    """As :func:`runs`, with callbacks released by one to three independent streams (a
    subscription fed over several topics), each with its own phase, sporadic gaps and release
    jitter (each job released up to ``J`` after its nominal time)."""
    items = draw(callback_sets(most=4))
    rng = draw(st.randoms(use_true_random=False))
    for k, c in enumerate(items):
        streams = tuple(rng.randint(4, 40) for _ in range(rng.choice((0, 1, 1, 2))))
        jitters = tuple(rng.choice((0, 0, rng.randint(0, 2 * p))) for p in (c.period, *streams))
        items[k] = c._replace(streams=streams, jitters=jitters)
    span = 400 + max(c.period for c in items)
    releases = []
    for c in items:
        times = []
        for period, jitter in zip((c.period, *c.streams), c.jitters, strict=True):
            nominal = rng.randint(0, period)
            while nominal < span:
                times.append(nominal + rng.choice((0, jitter, rng.randint(0, jitter))))
                nominal += period + rng.choice((0, 0, 1, 3))
        releases.append(sorted(times))
    executions = [[rng.randint(1, c.wcet) for _ in range(rng.randint(1, 3))] for c in items]
    groups = [rng.choice(("a", "b", None)) for _ in items]
    return items, releases, executions, rng.randint(1, 3), rng.randint(1, 6), groups


@settings(max_examples=EXAMPLES // 8, deadline=None, derandomize=True, database=None)
@given(runs_with_streams())
def test_callbacks_of_several_release_streams_stay_within_the_bound(run):
    """A callback released by several independent streams with release jitter requests their
    sum: under every executor model the simulated worst response never exceeds the bound."""
    test_simulated_response_never_exceeds_the_bound.hypothesis.inner_test(run)


def _prosa(items):
    tasks = [
        Task(Sporadic(c.period), FullyNonPreemptive(WCET(c.wcet)), Deadline(c.deadline), Priority(c.priority))
        for c in items
    ]
    return tasks, taskset(*tasks)


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None)
@given(callback_sets(distinct=True))
def test_component_executor_bounds_are_the_classical_non_preemptive_ones(items):
    """FIFO and non-preemptive FP (distinct priorities) equal Prosa's verified analyses; the
    George et al. NP-EDF bound is never below Prosa's aRTA EDF bound (which is at least as tight)."""
    tasks, all_tasks = _prosa(items)
    assert (
        fifo_response_time(items, horizon=HORIZON)
        == fifo.rta(all_tasks, IdealProcessor(), horizon=HORIZON).response_time_bound
    )
    for index, task in enumerate(tasks):
        ours = np_fixed_priority_response_time(items, index, horizon=HORIZON)
        assert ours == fp.rta(all_tasks, task, IdealProcessor(), horizon=HORIZON).response_time_bound
        ours = np_edf_response_time(items, index, horizon=HORIZON)
        theirs = edf.rta(all_tasks, task, IdealProcessor(), horizon=HORIZON).response_time_bound
        assert (ours is None) == (theirs is None)
        assert ours is None or ours >= theirs


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None)
@given(callback_sets(most=1))
def test_single_callback_executors_give_the_classical_result(items):
    """One callback per executor: every executor model gives the non-preemptive result, C."""
    (only,) = items
    tasks, all_tasks = _prosa(items)
    classical = fp.rta(all_tasks, tasks[0], IdealProcessor(), horizon=HORIZON).response_time_bound
    assert classical == only.wcet
    for policy in ("fifo", "pfifo", "edf", "polling", "multi"):
        assert _bound(policy, items, 0) == classical


def test_worked_example_polling_two_rounds():
    """Hand-checked: t (timer, T=10, C=2) and s (subscription, T=20, C=3) on one single-threaded
    rclpy executor (timers before subscriptions). Casini eq. (6) for s: A=0, F = 3 + rbf_t(F-2)
    -> F=5 (t released in [0, 3]: one job, 2) ; the two-round bound is C_t + 0 + C_s = 5 too.
    For t: F = 2 + rbf_s(F-1) = 5, two rounds: C_s + 0 + C_t = 5."""
    t = CallbackTiming("t", 10, 2, 10, 0, 1)
    s = CallbackTiming("s", 20, 3, 20, 0, 2)
    assert polling_response_time([t, s], 0) == 5
    assert polling_response_time([t, s], 1) == 5
    # preempted by a thread of higher OS priority (T=7, C=1): 5 + ceil(R/7) -> 6
    assert polling_response_time([t, s], 1, [(7, 1)]) == 6


def test_worked_example_rosmod_queues():
    """Hand-checked: a ROSMOD component with a (T=10, C=4, D=10, P=2) and b (T=15, C=5, D=8, P=1).
    FIFO: both released at 0, the second served ends at 4 + 5 = 9. PFIFO: a is blocked by a job of
    b started just before (5 - 1 = 4), then runs: 8; b waits for a's job released with it: 4 + 5
    = 9. EDF: b's absolute deadline 8 is earlier, so b is blocked only by a job of a started just
    before (4 - 1 = 3): 3 + 5 = 8; a waits for b: 5 + 4 = 9."""
    a = CallbackTiming("a", 10, 4, 10, 2, 0)
    b = CallbackTiming("b", 15, 5, 8, 1, 1)
    assert fifo_response_time([a, b]) == 9
    assert np_fixed_priority_response_time([a, b], 0) == 8
    assert np_fixed_priority_response_time([a, b], 1) == 9
    assert np_edf_response_time([a, b], 0) == 9
    assert np_edf_response_time([a, b], 1) == 8

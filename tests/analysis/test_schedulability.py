"""Feasibility tests: utilisation, bounds, feasibility interval, priorities, response times,
blocking, partitioning, and the extraction of task sets from instance models."""

from __future__ import annotations

import random
import time
from fractions import Fraction

import pytest

from rosaadl import model
from rosaadl.analysis.partitioning import partition, partition_taskset
from rosaadl.analysis.schedulability import (
    analyze_schedulability,
    blocking_times,
    feasibility_interval,
    is_harmonic,
    liu_layland_bound,
    rate_monotonic_priorities,
    response_times,
    unused_units,
    utilization,
    utilization_by_deadline,
    utilization_test,
    within_liu_layland,
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
    exact_time,
    taskset_from_instance,
)
from rosaadl.errors import ModelError

# =============================================================================== task model


def test_times_are_exact_and_floats_are_refused():
    task = Task("t", Fraction(1, 2), "0.25")
    assert task.period == Fraction(1, 2) and task.capacity == Fraction(1, 4)
    assert task.deadline == Fraction(1, 2)
    assert exact_time(Fraction(6, 3)) == 2 and type(exact_time(Fraction(6, 3))) is int
    with pytest.raises(ModelError, match="float"):
        Task("t", 0.5, 1)
    with pytest.raises(ModelError, match="period must be positive"):
        Task("t", 0, 1)
    with pytest.raises(ModelError, match="needs a period"):
        Task("t", None, 1)
    with pytest.raises(ModelError, match="overlap"):
        Task(
            "t",
            10,
            5,
            critical_sections=(CriticalSection("a", 0, 3), CriticalSection("b", 2, 4)),
        )
    with pytest.raises(ModelError, match="after the capacity"):
        Task("t", 10, 2, critical_sections=(CriticalSection("a", 1, 3),))


def test_taskset_checks_its_references():
    with pytest.raises(ModelError, match="unknown processor"):
        TaskSet((Task("t", 10, 1, processor="nowhere"),), (Processor("cpu"),))
    with pytest.raises(ModelError, match="needs one"):
        TaskSet((Task("t", 10, 1, processor="soc"),), (Processor("soc", cores=("c0", "c1")),))
    with pytest.raises(ModelError, match="unknown resource"):
        TaskSet.uniprocessor([Task("t", 10, 2, critical_sections=(CriticalSection("r", 0, 1),))])
    with pytest.raises(ModelError, match="duplicate task"):
        TaskSet.uniprocessor([Task("t", 10, 1), Task("t", 20, 1)])


# =============================================================================== utilisation and bounds


def test_utilization_is_exact():
    tasks = [Task("a", 3, 1), Task("b", 7, 2, deadline=5)]
    assert utilization(tasks) == Fraction(1, 3) + Fraction(2, 7)
    assert utilization_by_deadline(tasks) == Fraction(1, 3) + Fraction(2, 5)


def test_harmonic_periods():
    assert is_harmonic([2, 4, 8, 8])
    assert is_harmonic([3, 6, 12])
    assert is_harmonic([Fraction(1, 2), 1, 3])
    assert not is_harmonic([4, 6])
    assert not is_harmonic([2, 4, 6])


def test_liu_layland_bound_is_decided_exactly():
    assert liu_layland_bound(1) == 1.0
    assert abs(liu_layland_bound(2) - 0.8284271) < 1e-7
    assert within_liu_layland(Fraction(8284, 10000), 2)
    assert not within_liu_layland(Fraction(8285, 10000), 2)
    assert within_liu_layland(Fraction(7797, 10000), 3)
    assert not within_liu_layland(Fraction(7798, 10000), 3)


def test_harmonic_sets_get_bound_one():
    tasks = [Task("a", 2, 1), Task("b", 4, 1), Task("c", 8, 2)]  # U = 1
    result = analyze_schedulability(TaskSet.uniprocessor(tasks, Scheduler.RATE_MONOTONIC)).domains[0]
    assert result.harmonic and result.bound == 1.0
    assert result.utilization == 1 and result.utilization_test is True
    assert result.rta_schedulable is True


def test_utilization_tests_per_scheduler():
    tasks = [Task("a", 10, 4, deadline=5), Task("b", 15, 4)]
    assert utilization_test(Scheduler.RATE_MONOTONIC, True, tasks) is True  # 0.667 <= 0.828
    assert utilization_test(Scheduler.DEADLINE_MONOTONIC, True, tasks) is False  # by deadline 1.067
    assert utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, True, tasks) is False
    assert utilization_test(Scheduler.FIXED_PRIORITY, True, tasks) is None
    # non-preemptive EDF, D = T: Jeffay's condition
    assert (
        utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, False, [Task("a", 4, 1), Task("b", 6, 2)]) is True
    )
    assert (
        utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, False, [Task("a", 4, 1), Task("b", 8, 5)])
        is False
    )
    assert utilization_test(Scheduler.EARLIEST_DEADLINE_FIRST, False, tasks) is None  # needs D = T


# =============================================================================== feasibility interval


def test_feasibility_interval_is_the_hyperperiod_or_twice_it_plus_the_offset():
    synchronous = [Task("a", 4, 1), Task("b", 6, 2)]
    interval = feasibility_interval(synchronous, Scheduler.RATE_MONOTONIC)
    assert interval.length == 12 and interval.validated
    with_offset = [Task("a", 4, 1), Task("b", 6, 2, offset=3)]
    assert feasibility_interval(with_offset, Scheduler.RATE_MONOTONIC).length == 2 * 12 + 3
    assert unused_units(with_offset, 27) == 27 - (7 * 1 + 4 * 2)
    fractions = [Task("a", Fraction(1, 2), Fraction(1, 10)), Task("b", Fraction(1, 3), Fraction(1, 10))]
    assert feasibility_interval(fractions).length == 1


def test_feasibility_interval_for_edf_and_unproven_cases():
    tasks = [Task("a", 4, 1, offset=1), Task("b", 6, 2)]
    interval = feasibility_interval(tasks, Scheduler.EARLIEST_DEADLINE_FIRST)
    # Goossens and Devillers: S1 = 1, S2 = 0 + ceil((1 - 0) / 6) * 6 = 6; S2 + lcm = 18
    assert interval.length == 18 and interval.validated
    arbitrary = [Task("a", 4, 1, deadline=6), Task("b", 6, 2)]
    assert feasibility_interval(arbitrary, Scheduler.RATE_MONOTONIC).validated is False
    assert feasibility_interval(tasks, Scheduler.RATE_MONOTONIC, independent=False).validated
    assert feasibility_interval([Task("a", None, 1, dispatch=Dispatch.APERIODIC)]) is None


# =============================================================================== priorities


def test_rate_monotonic_ties_keep_task_order():
    tasks = [Task("a", 10, 1), Task("b", 10, 1), Task("c", 5, 1), Task("d", 20, 1)]
    assert rate_monotonic_priorities(tasks) == {"c": 4, "a": 3, "b": 2, "d": 1}


# =============================================================================== response times


def test_response_times_textbook_example():
    tasks = [Task("t1", 4, 1, priority=3), Task("t2", 6, 2, priority=2), Task("t3", 13, 3, priority=1)]
    assert response_times(tasks) == {"t1": 1, "t2": 3, "t3": 10}
    # the synchronous release is the critical instant: the first jobs reach the bound
    result = simulate(TaskSet.uniprocessor(tasks))
    assert {t.name: t.first_response for t in result.tasks} == {"t1": 1, "t2": 3, "t3": 10}


def test_response_times_with_arbitrary_deadlines_match_the_busy_period():
    # Lehoczky's example: the second job of t2 has the longest response.
    tasks = [Task("t1", 70, 26, priority=2), Task("t2", 100, 62, deadline=200, priority=1)]
    bound = response_times(tasks)
    worst = simulate(TaskSet.uniprocessor(tasks)).task("t2")
    assert bound["t2"] == worst.worst_response == 118
    assert worst.first_response < worst.worst_response


def test_response_times_with_jitter_and_blocking():
    tasks = [Task("t1", 4, 1, jitter=2, priority=2), Task("t2", 10, 2, blocking=1, priority=1)]
    # R1 = C1 + J1 = 3; w2 = 2 + 1 + ceil((w2 + 2) / 4) * 1 = 5, R2 = 5
    assert response_times(tasks) == {"t1": 3, "t2": 5}


def test_response_times_in_fractions():
    tasks = [
        Task("t1", Fraction(1, 2), Fraction(1, 10), priority=2),
        Task("t2", 1, Fraction(3, 10), priority=1),
    ]
    assert response_times(tasks) == {"t1": Fraction(1, 10), "t2": Fraction(2, 5)}


def test_unbounded_response_time_is_reported_on_the_task():
    tasks = [Task("a", 4, 3), Task("b", 5, 3)]
    result = analyze_schedulability(TaskSet.uniprocessor(tasks, Scheduler.RATE_MONOTONIC))
    rows = {row.name: row for row in result.domains[0].tasks}
    assert rows["a"].wcrt == 3 and rows["a"].met
    assert rows["b"].wcrt is None and rows["b"].met is False
    assert not result.ok
    errors = [d for d in result.diagnostics if d.severity == "error"]
    assert [d.location.path for d in errors] == ["b"]


def test_equal_priorities_interfere_with_each_other():
    tasks = [Task("a", 10, 2, priority=1), Task("b", 10, 3, priority=1)]
    assert response_times(tasks) == {"a": 5, "b": 5}
    result = analyze_schedulability(TaskSet.uniprocessor(tasks))
    assert any("share a priority" in d.message for d in result.diagnostics)


def test_rta_of_a_thousand_tasks_is_fast():
    rng = random.Random(7)
    tasks = []
    for i in range(1000):
        period = rng.randrange(10_000, 1_000_000)
        tasks.append(Task(f"t{i}", period, max(1, period * 85 // 100_000)))
    priorities = rate_monotonic_priorities(tasks)
    tasks = [Task(t.name, t.period, t.capacity, priority=priorities[t.name]) for t in tasks]
    best = min(_timed(response_times, tasks) for _ in range(3))
    assert best < 0.5, f"RTA of 1000 tasks took {best:.3f} s"


def _timed(func, *args):
    start = time.process_time()  # CPU time: other work on the machine does not count
    func(*args)
    return time.process_time() - start


# =============================================================================== blocking


def _resource_set(protocol: Protocol) -> TaskSet:
    tasks = [
        Task("high", 10, 2, priority=3, critical_sections=(CriticalSection("r", 0, 1),)),
        Task("mid", 20, 2, priority=2),
        Task("low", 40, 5, priority=1, critical_sections=(CriticalSection("r", 1, 4),)),
    ]
    return TaskSet.uniprocessor(tasks, resources=[Resource("r", protocol)])


@pytest.mark.parametrize("protocol", [Protocol.PIP, Protocol.PCP, Protocol.IPCP])
def test_blocking_through_a_shared_resource(protocol):
    taskset = _resource_set(protocol)
    assert blocking_times(taskset.tasks, taskset) == {"high": 3, "mid": 3, "low": 0}
    rows = {r.name: r for r in analyze_schedulability(taskset).domains[0].tasks}
    assert rows["high"].blocking == 3 and rows["high"].wcrt == 5
    assert rows["mid"].wcrt == 2 + 2 + 3


def test_no_protocol_with_an_intermediate_task_is_unbounded():
    taskset = _resource_set(Protocol.NONE)
    assert blocking_times(taskset.tasks, taskset)["high"] is None
    result = analyze_schedulability(taskset)
    rows = {r.name: r for r in result.domains[0].tasks}
    assert rows["high"].wcrt is None and rows["high"].met is None
    assert rows["low"].wcrt is not None
    assert result.domains[0].rta_schedulable is None
    assert any(d.location.path == "high" and "unbounded" in d.message for d in result.diagnostics)


# =============================================================================== multi-core and partitioning


def test_partitioned_multicore_is_analysed_per_core():
    tasks = [
        Task("a", 4, 2, processor="soc", core="c0"),
        Task("b", 6, 2, processor="soc", core="c0"),
        Task("c", 5, 4, processor="soc", core="c1"),
    ]
    soc = Processor("soc", Scheduler.RATE_MONOTONIC, cores=("c0", "c1"))
    result = analyze_schedulability(TaskSet(tasks, (soc,)))
    assert [(d.processor, d.core) for d in result.domains] == [("soc", "c0"), ("soc", "c1")]
    c0, c1 = result.domains
    assert c0.utilization == Fraction(5, 6) and c0.priorities == {"a": 2, "b": 1}
    assert {r.name: r.wcrt for r in c0.tasks} == {"a": 2, "b": 4}
    assert c1.feasibility_interval.length == 5 and c1.unused_units == 1
    assert c0.as_dict()["path"] == "soc.c0"


def test_first_and_next_fit():
    tasks = [Task("t1", 4, 1), Task("t2", 5, 1), Task("t3", 10, 2), Task("t4", 12, 3), Task("t5", 20, 2)]
    first = partition(tasks, ["p1", "p2"], "first_fit")
    assert first.assignment == {"t1": "p1", "t2": "p1", "t3": "p1", "t4": "p2", "t5": "p1"}
    nxt = partition(tasks, ["p1", "p2"], "next_fit")
    assert nxt.assignment == {"t1": "p1", "t2": "p1", "t3": "p1", "t4": "p2", "t5": "p2"}
    crowded = partition([Task("a", 2, 2), Task("b", 2, 2)], ["p1"], "best_fit")
    assert crowded.assignment == {"a": "p1"} and crowded.unplaced == ("b",) and not crowded.ok
    with pytest.raises(ModelError, match="unknown partitioning"):
        partition(tasks, ["p1"], "worst_fit")


def test_partition_onto_cores():
    soc = Processor("soc", Scheduler.RATE_MONOTONIC, cores=("c0", "c1"))
    tasks = [Task(f"t{i}", 10, 4, processor="soc", core="c0") for i in range(4)]
    moved, result = partition_taskset(TaskSet(tasks, (soc,)))
    assert result.ok
    assert sorted(t.core for t in moved.tasks) == ["c0", "c0", "c1", "c1"]
    assert analyze_schedulability(moved).ok


# =============================================================================== instance models


def _value(value, unit=None):
    if isinstance(value, tuple):
        return model.new("RangeValue", minimum=_value(value[0], unit), maximum=_value(value[1], unit))
    if isinstance(value, float):
        return model.new("RealValue", value=value, unit=unit)
    if isinstance(value, int):
        return model.new("IntegerValue", value=value, unit=unit)
    if isinstance(value, str):
        return model.new("NamedValue", name=value)
    if isinstance(value, list):
        return model.new("ListValue", ownedItems=[_value(v) for v in value])
    return model.new("InstanceReferenceValue", referencedInstanceObject=value)


def _set(obj, prop, value, unit=None):
    obj.ownedPropertyAssociations.append(
        model.new(
            "PropertyAssociation",
            property=prop,
            ownedValues=[model.new("ModalPropertyValue", value=_value(value, unit))],
        )
    )


def _component(parent, name, category):
    child = model.new("ComponentInstance", name=name, category=category)
    parent.componentInstances.append(child)
    return child


def _thread(process, name, binding=None, **props):
    thread = _component(process, name, "thread")
    for prop, value in props.items():
        if isinstance(value, tuple):
            _set(thread, prop, *value)
        else:
            _set(thread, prop, value)
    if binding is not None:
        _set(thread, "Deployment_Properties::Actual_Processor_Binding", [binding])
    return thread


@pytest.fixture()
def instance():
    root = model.new("SystemInstance", name="robot_impl_Instance", category="system")
    cpu = _component(root, "cpu", "processor")
    _set(cpu, "Deployment_Properties::Scheduling_Protocol", ["RMS"])
    vp = _component(cpu, "partition", "virtualProcessor")
    soc = _component(root, "soc", "processor")
    _set(soc, "Deployment_Properties::Scheduling_Protocol", ["EDF"])
    _component(soc, "core0", "processor")
    core1 = _component(soc, "core1", "processor")
    mem = _component(root, "ram", "memory")
    process = _component(root, "node", "process")
    lock = _component(process, "queue", "data")
    _set(lock, "Thread_Properties::Concurrency_Control_Protocol", "Priority_Ceiling")
    _set(lock, "Thread_Properties::Priority", 7)
    _thread(
        process,
        "camera",
        cpu,
        **{
            "Timing_Properties::Period": (10, "ms"),
            "Timing_Properties::Compute_Execution_Time": ((1, 2), "ms"),
            "Timing_Properties::Deadline": (8, "ms"),
            "Timing_Properties::Dispatch_Offset": (500, "us"),
            "Thread_Properties::Priority": 5,
            "Thread_Properties::Dispatch_Protocol": "Periodic",
        },
    )
    _thread(
        process,
        "filter",
        vp,
        **{
            "Timing_Properties::Period": (20, "ms"),
            "Timing_Properties::Compute_Execution_Time": ((33.3, 33.3), "us"),
        },
    )
    _thread(
        process,
        "planner",
        core1,
        **{
            "Timing_Properties::Period": (5, "ms"),
            "Timing_Properties::Compute_Execution_Time": (1, "ms"),
            "Thread_Properties::Dispatch_Protocol": "Sporadic",
        },
    )
    _thread(process, "no_period", cpu, **{"Timing_Properties::Compute_Execution_Time": (1, "ms")})
    _thread(process, "no_cet", cpu, **{"Timing_Properties::Period": (10, "ms")})
    _thread(
        process,
        "zero",
        cpu,
        **{"Timing_Properties::Period": (0, "ms"), "Timing_Properties::Compute_Execution_Time": (1, "ms")},
    )
    _thread(
        process,
        "on_memory",
        mem,
        **{"Timing_Properties::Period": (10, "ms"), "Timing_Properties::Compute_Execution_Time": (1, "ms")},
    )
    _thread(
        process,
        "on_soc",
        soc,
        **{"Timing_Properties::Period": (10, "ms"), "Timing_Properties::Compute_Execution_Time": (1, "ms")},
    )
    _thread(
        process,
        "unbound",
        None,
        **{"Timing_Properties::Period": (10, "ms"), "Timing_Properties::Compute_Execution_Time": (1, "ms")},
    )
    _thread(
        process,
        "no_unit",
        cpu,
        **{"Timing_Properties::Period": 10, "Timing_Properties::Compute_Execution_Time": (1, "ms")},
    )
    _thread(
        process,
        "event",
        cpu,
        **{
            "Timing_Properties::Compute_Execution_Time": (1, "ms"),
            "Timing_Properties::Deadline": (50, "ms"),
            "Thread_Properties::Dispatch_Protocol": "Aperiodic",
        },
    )
    return root


def test_taskset_from_instance(instance):
    taskset = taskset_from_instance(instance)
    tasks = {t.name.rsplit(".", 1)[-1]: t for t in taskset.tasks}
    assert sorted(tasks) == ["camera", "event", "filter", "planner"]
    camera = tasks["camera"]
    assert (camera.period, camera.capacity, camera.deadline, camera.offset, camera.priority) == (
        10_000,
        2_000,
        8_000,
        500,
        5,
    )
    assert camera.path == "robot_impl_Instance.node.camera" and camera.processor == "robot_impl_Instance.cpu"
    assert camera.address_space == "robot_impl_Instance.node"
    assert (
        tasks["filter"].capacity == Fraction(333, 10)
        and tasks["filter"].processor == "robot_impl_Instance.cpu"
    )
    planner = tasks["planner"]
    assert (planner.processor, planner.core, planner.dispatch) == (
        "robot_impl_Instance.soc",
        "core1",
        Dispatch.SPORADIC,
    )
    assert tasks["event"].period is None and tasks["event"].deadline == 50_000
    processors = {p.name: p for p in taskset.processors}
    assert processors["robot_impl_Instance.cpu"].scheduler is Scheduler.RATE_MONOTONIC
    assert processors["robot_impl_Instance.soc"].scheduler is Scheduler.EARLIEST_DEADLINE_FIRST
    assert processors["robot_impl_Instance.soc"].cores == ("core0", "core1")
    (queue,) = taskset.resources
    assert (queue.protocol, queue.ceiling, queue.path) == (Protocol.PCP, 7, "robot_impl_Instance.node.queue")


def test_bad_threads_become_located_diagnostics(instance):
    taskset = taskset_from_instance(instance)
    found = {(d.location.path.rsplit(".", 1)[-1], d.severity) for d in taskset.diagnostics}
    for name in ("no_period", "zero", "on_memory", "on_soc", "no_unit"):
        assert (name, "error") in found, name
    # a thread with no execution time is not a task (a ROS spinner nobody measured): a warning
    assert ("no_cet", "warning") in found
    assert ("unbound", "warning") in found
    messages = {d.location.path.rsplit(".", 1)[-1]: d.message for d in taskset.diagnostics}
    assert "no Period" in messages["no_period"]
    assert "Compute_Execution_Time" in messages["no_cet"]
    assert "positive" in messages["zero"]
    assert "not a processor" in messages["on_memory"] and "ram" in messages["on_memory"]
    assert all(d.location.path.startswith("robot_impl_Instance") for d in taskset.diagnostics)


def test_instance_times_convert_exactly_to_other_units(instance):
    taskset = taskset_from_instance(instance, time_unit="ms")
    camera = next(t for t in taskset.tasks if t.name.endswith("camera"))
    assert camera.offset == Fraction(1, 2) and camera.period == 10
    assert next(t for t in taskset.tasks if t.name.endswith("filter")).capacity == Fraction(333, 10_000)
    with pytest.raises(ModelError, match="unknown time unit"):
        taskset_from_instance(instance, time_unit="parsec")


def test_analyses_run_on_an_instance(instance):
    holder = model.new("AadlModel", name="ws")
    holder.instances.append(instance)
    result = analyze_schedulability(holder)
    assert not result.ok  # the bad threads are errors
    cpu = result.domain("robot_impl_Instance.cpu")
    assert cpu.scheduler is Scheduler.RATE_MONOTONIC
    assert {r.path.rsplit(".", 1)[-1]: r.met for r in cpu.tasks} == {
        "camera": True,
        "filter": True,
        "event": None,
    }
    row = cpu.as_dict()
    assert set(row) == {"path", "scheduler", "utilization", "bound", "feasibility_interval", "tasks"}
    assert set(row["tasks"][0]) == {"path", "priority", "period", "capacity", "deadline", "wcrt", "met"}
    simulated = simulate(instance)
    assert simulated.task("robot_impl_Instance.node.camera").worst_response == 2_000
    # 2 * lcm + offset = 40 500 us, stretched to the aperiodic event's deadline at 50 ms
    assert simulated.horizons[("robot_impl_Instance.cpu", "")] == 50_000


def test_instance_with_strange_values_does_not_crash():
    root = model.new("SystemInstance", name="s", category="system")
    cpu = _component(root, "cpu", "processor")
    _set(cpu, "Deployment_Properties::Scheduling_Protocol", ["ARINC653"])
    thread = _component(root, "t", "thread")
    _set(thread, "Timing_Properties::Period", "Ten")
    _set(thread, "Timing_Properties::Compute_Execution_Time", (1, "ms"))
    _set(thread, "Deployment_Properties::Actual_Processor_Binding", [cpu])
    other = _component(root, "u", "thread")
    _set(other, "Timing_Properties::Period", (10, "KByte"))
    _set(other, "Timing_Properties::Compute_Execution_Time", (1, "ms"))
    _set(other, "Thread_Properties::Priority", "High")
    _set(other, "Deployment_Properties::Actual_Processor_Binding", [cpu])
    taskset = taskset_from_instance(root)
    assert taskset.tasks == ()
    paths = {d.location.path for d in taskset.diagnostics if d.severity == "error"}
    assert paths == {"s.t", "s.u"}
    assert any("ARINC653" in d.message for d in taskset.diagnostics)
    with pytest.raises(ModelError):
        taskset_from_instance("not a model")

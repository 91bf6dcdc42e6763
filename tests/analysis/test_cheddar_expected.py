"""Our analyses against real Cheddar outputs (``corpus/cheddar/expected/``).

The expected values are read from the expected files themselves and the task parameters
from the Cheddar XML files (a small reader below), so nothing of Cheddar's output is
copied here. A second set of tests goes the user's way: the Cheddar importer → instance
model → :func:`taskset_from_instance` → the same results.
"""

from __future__ import annotations

import re
from fractions import Fraction
from pathlib import Path

import pytest

from rosaadl.analysis.partitioning import partition, partition_taskset
from rosaadl.analysis.schedulability import (
    analyze_schedulability,
    deadline_monotonic_priorities,
    non_preemptive_rm_failures,
    rate_monotonic_priorities,
)
from rosaadl.analysis.simulation import simulate
from rosaadl.analysis.tasks import Processor, Scheduler, Task, TaskSet, taskset_from_instance
from rosaadl.fileio import parse_xml_bytes
from rosaadl.importers.cheddar import load_cheddar

pytestmark = pytest.mark.corpus


# --------------------------------------------------------------------------- Cheddar XML reader


def _text(element, tag: str, default: str | None = None) -> str | None:
    child = element.find(tag)
    return child.text.strip() if child is not None and child.text is not None else default


def read_cheddar_tasks(path: Path) -> TaskSet:
    """The task set of a Cheddar 3 file: periodic tasks (capacity, period, deadline, start_time
    as offset, priority, jitter, blocking_time) on mono-core processors with their core's
    scheduler. Activation offsets (``<offsets>``) are left out, as the expected outputs did."""
    root = parse_xml_bytes(path.read_bytes(), str(path)).getroot()
    cores = {}
    for core in root.iter("core_unit"):
        params = core.find("scheduling/scheduling_parameters")
        cores[core.get("id")] = (
            Scheduler(_text(params, "scheduler_type")),
            _text(params, "preemptive_type") == "PREEMPTIVE",
        )
    processors = []
    for cpu in root.iter("mono_core_processor"):
        scheduler, preemptive = cores[cpu.find("core").get("ref")]
        processors.append(Processor(_text(cpu, "name"), scheduler, preemptive))
    tasks = []
    for element in root.iter("periodic_task"):
        tasks.append(
            Task(
                name=_text(element, "name"),
                period=int(_text(element, "period")),
                capacity=int(_text(element, "capacity")),
                deadline=int(_text(element, "deadline")),
                priority=int(_text(element, "priority")),
                offset=int(_text(element, "start_time", "0")),
                jitter=int(_text(element, "jitter", "0")),
                blocking=int(_text(element, "blocking_time", "0")),
                processor=_text(element, "cpu_name"),
            )
        )
    return TaskSet(tuple(tasks), tuple(processors))


# --------------------------------------------------------------------------- expected files


def _blocks(text: str) -> list[str]:
    return re.findall(r"```\n(.*?)```", text, flags=re.S)


def _arrows(block: str) -> dict[str, str]:
    """``name => value`` lines of a Cheddar report block."""
    return {m.group(1): m.group(2).strip() for m in re.finditer(r"^\s*(\S+)\s*=>\s*(.+?)\s*$", block, re.M)}


def _expected(corpus: Path, name: str) -> str:
    path = corpus / "cheddar" / "expected" / f"{name}.expected.md"
    if not path.is_file():
        pytest.skip(f"{path} not in the corpus")
    return path.read_text(encoding="utf-8")


def _last(name: str) -> str:
    return name.rsplit(".", 1)[-1]


def _rm_expectations(text: str) -> dict:
    priorities_block, basics_block, non_preemptive_block = _blocks(text)[:3]
    facts = {"priorities": {k: int(v) for k, v in _arrows(priorities_block).items()}}
    facts["interval"] = Fraction(re.search(r"feasibility interval is ([\d.]+)", basics_block).group(1))
    facts["unused"] = int(re.search(r"(\d+) units of time are unused", basics_block).group(1))
    facts["u_deadline"] = re.search(r"factor with deadline is ([\d.]+)", basics_block).group(1)
    facts["u_period"] = re.search(r"factor with period is ([\d.]+)", basics_block).group(1)
    verdict = re.search(
        r"with RM, the task set is (\w+) because .*? ([\d.]+) is equal or less than ([\d.]+)", basics_block
    )
    facts["verdict"], facts["u_test"], facts["bound"] = verdict.group(1), verdict.group(2), verdict.group(3)
    wcrt_part = basics_block.split("Worst case task response time")[1]
    facts["wcrt"] = {k: int(v) for k, v in _arrows(wcrt_part).items()}
    facts["all_met"] = "All task deadlines will be met" in basics_block
    np_part = non_preemptive_block.split("Worst case thread component response time")[1]
    facts["np_wcrt"] = {_last(k): int(re.match(r"(\d+)", v).group(1)) for k, v in _arrows(np_part).items()}
    facts["np_missed"] = {_last(k) for k, v in _arrows(np_part).items() if "missed" in v}
    concerned = re.search(r"List of concerned thread components :(.*)", non_preemptive_block).group(1)
    facts["np_concerned"] = {_last(name) for name in concerned.split()}
    return facts


# --------------------------------------------------------------------------- rate monotonic


@pytest.fixture(scope="module")
def rm_case(corpus):
    facts = _rm_expectations(_expected(corpus, "rm_test_case_3tasks"))
    taskset = read_cheddar_tasks(corpus / "cheddar" / "rm_test_case_3tasks.xml")
    return facts, taskset


def test_rm_priorities(rm_case):
    facts, taskset = rm_case
    assert rate_monotonic_priorities(taskset.tasks) == facts["priorities"]
    assert analyze_schedulability(taskset).domains[0].priorities == facts["priorities"]


def test_rm_feasibility_basics(rm_case):
    facts, taskset = rm_case
    domain = analyze_schedulability(taskset).domains[0]
    assert domain.feasibility_interval.length == facts["interval"]
    assert domain.feasibility_interval.validated
    assert domain.unused_units == facts["unused"]
    assert f"{float(domain.utilization_by_deadline):.5f}" == facts["u_deadline"]
    assert f"{float(domain.utilization):.5f}" == facts["u_period"] == facts["u_test"]
    assert f"{domain.bound:.5f}" == facts["bound"]
    assert domain.utilization_test is (facts["verdict"] == "schedulable")


def test_rm_worst_case_response_times(rm_case):
    facts, taskset = rm_case
    result = analyze_schedulability(taskset)
    domain = result.domains[0]
    assert {row.name: row.wcrt for row in domain.tasks} == facts["wcrt"]
    assert domain.rta_schedulable is facts["all_met"]
    assert result.ok


def test_rm_non_preemptive(rm_case):
    facts, taskset = rm_case
    cpu = taskset.processors[0]
    non_preemptive = TaskSet(taskset.tasks, (Processor(cpu.name, cpu.scheduler, False),))
    domain = analyze_schedulability(non_preemptive).domains[0]
    rows = {row.name.lower(): row for row in domain.tasks}
    assert {name: row.wcrt for name, row in rows.items()} == facts["np_wcrt"]
    assert {name for name, row in rows.items() if not row.met} == facts["np_missed"]
    # Cheddar's non-preemptive utilisation test cannot prove it, for the same tasks.
    assert domain.utilization_test is False
    assert {name.lower() for name in non_preemptive_rm_failures(taskset.tasks)} == facts["np_concerned"]


# --------------------------------------------------------------------------- deadline monotonic


def test_dm_priorities(corpus):
    block = _blocks(_expected(corpus, "dm_test_case_3tasks"))[0]
    expected = {k: int(v) for k, v in _arrows(block).items()}
    taskset = read_cheddar_tasks(corpus / "cheddar" / "dm_test_case_3tasks.xml")
    assert deadline_monotonic_priorities(taskset.tasks) == expected
    dm = TaskSet(taskset.tasks, (Processor("cpu", Scheduler.DEADLINE_MONOTONIC),))
    assert analyze_schedulability(dm).domains[0].priorities == expected


# --------------------------------------------------------------------------- simulation event table


def _event_facts(text: str) -> dict:
    priorities = dict(re.findall(r"(T\d) \(id_\d+\)=(\d+)", text))
    ends = {}
    line = re.search(r"END_OF_TASK_CAPACITY: (.*)", text).group(1)
    for name, times in re.findall(r"(T\d) at ([\d,]+)", line):
        ends[name] = [int(t) for t in times.split(",")]
    first_job = re.search(r"(T\d) first job at (\d+)", line)
    first_responses = dict(re.findall(r"(T\d)=(\d+)", text.split("first jobs:")[1]))
    return {
        "priorities": {k: int(v) for k, v in priorities.items()},
        "ends": ends,
        "first_job_end": (first_job.group(1), int(first_job.group(2))),
        "first_responses": {k: int(v) for k, v in first_responses.items()},
    }


def test_event_table_first_jobs(corpus):
    facts = _event_facts(_expected(corpus, "schedule_with_offset_test_case"))
    taskset = read_cheddar_tasks(corpus / "cheddar" / "schedule_with_offset_test_case.xml")
    result = simulate(taskset)
    assert {t.name: t.priority for t in result.tasks} == facts["priorities"]
    assert {t.name: t.first_response for t in result.tasks} == facts["first_responses"]
    for name, ends in facts["ends"].items():
        completions = [j.completion for j in result.jobs_of(name)]
        assert completions[: len(ends)] == ends
    name, end = facts["first_job_end"]
    assert result.jobs_of(name)[0].completion == end
    assert result.ok


# --------------------------------------------------------------------------- best fit


def test_best_fit_partition(corpus):
    block = _blocks(_expected(corpus, "best_fit_test_case_2cpu"))[0]
    expected = {m.group(1): m.group(2) for m in re.finditer(r"^\s*(\S+)\s*=>\s*(\S+)\s*$", block, re.M)}
    taskset = read_cheddar_tasks(corpus / "cheddar" / "best_fit_test_case_2cpu.xml")
    result = partition(taskset.tasks, [p.name for p in taskset.processors], "best_fit")
    assert result.assignment == expected
    assert result.ok
    moved, _ = partition_taskset(taskset, "best_fit")
    assert {t.name: t.processor for t in moved.tasks} == expected
    assert analyze_schedulability(moved).ok


# --------------------------------------------------------------------------- through the importer


def _import(corpus: Path, name: str) -> TaskSet:
    return taskset_from_instance(load_cheddar(corpus / "cheddar" / name))


def test_importer_rm_case(corpus, rm_case):
    facts, _ = rm_case
    taskset = _import(corpus, "rm_test_case_3tasks.xml")
    domain = analyze_schedulability(taskset).domains[0]
    assert {_last(k): v for k, v in domain.priorities.items()} == facts["priorities"]
    assert {_last(row.name): row.wcrt for row in domain.tasks} == facts["wcrt"]
    assert domain.feasibility_interval.length == facts["interval"]
    assert domain.unused_units == facts["unused"]
    assert f"{float(domain.utilization):.5f}" == facts["u_period"]
    assert f"{domain.bound:.5f}" == facts["bound"]


def test_importer_dm_case(corpus):
    block = _blocks(_expected(corpus, "dm_test_case_3tasks"))[0]
    expected = {k: int(v) for k, v in _arrows(block).items()}
    taskset = _import(corpus, "dm_test_case_3tasks.xml")
    assert {_last(k): v for k, v in deadline_monotonic_priorities(taskset.tasks).items()} == expected


def test_importer_event_table(corpus):
    facts = _event_facts(_expected(corpus, "schedule_with_offset_test_case"))
    result = simulate(_import(corpus, "schedule_with_offset_test_case.xml"))
    assert {_last(t.name): t.first_response for t in result.tasks} == facts["first_responses"]
    assert {_last(t.name): t.priority for t in result.tasks} == facts["priorities"]


def test_importer_best_fit(corpus):
    block = _blocks(_expected(corpus, "best_fit_test_case_2cpu"))[0]
    expected = {m.group(1): m.group(2) for m in re.finditer(r"^\s*(\S+)\s*=>\s*(\S+)\s*$", block, re.M)}
    taskset = _import(corpus, "best_fit_test_case_2cpu.xml")
    _, result = partition_taskset(taskset, "best_fit")
    assert {_last(k): _last(v) for k, v in result.assignment.items()} == expected

"""The benchmark harness (best of N, alternating blocks, rows, the one table) and the shapes of the
model generators that benchmarks and tests share (``benchmarks/``)."""

from __future__ import annotations

import json
import types

import pytest

from benchmarks import harness
from benchmarks.generators.aadl_text import aadl_package_text
from benchmarks.generators.declarative import chained_system, time_units
from benchmarks.generators.rosmod import rosmod_project
from benchmarks.generators.tasks import random_rta_tasks, random_simulation_sets
from benchmarks.harness import Goal, Report, Row, alternate, best_of, format_table, read_rows
from rosaadl import model
from rosaadl.analysis.tasks import Scheduler
from rosaadl.importers.aadl_syntax import parse


@pytest.fixture
def no_collection(monkeypatch):
    # the full collection before each call is not what is tested here (and slow in a test process)
    monkeypatch.setattr(harness, "gc", types.SimpleNamespace(collect=lambda: None))


# --------------------------------------------------------------------------- timing


def test_best_of_keeps_the_lowest_of_each_clock_and_the_last_result(no_collection) -> None:
    calls = []

    def action(size: int) -> int:
        calls.append(size)
        return sum(range(size))

    sizes = iter([20_000, 2_000, 200_000])
    timing = best_of(action, 3, setup=lambda: next(sizes))
    assert calls == [20_000, 2_000, 200_000] and timing.calls == 3
    assert timing.cpu == min(timing.cpu_calls) and timing.cpu <= max(timing.cpu_calls)
    assert timing.wall >= 0 and timing.result == sum(range(200_000))
    assert best_of(lambda: None, 0).calls == 1  # at least one round
    # a timing kept in a row lets its result go: it would stay on the heap every later gc traverses
    assert best_of(lambda: [0] * 10, 2, keep=False).result is None


def test_best_of_measures_the_memory_a_round_holds_at_its_peak(no_collection) -> None:
    if harness.reset_peak() is None:
        pytest.skip("the kernel offers no reset of the resident high-water mark")
    timing = best_of(lambda: len(bytearray(64 * 1024 * 1024)), 2)
    assert timing.peak_mib is not None and 50 <= timing.peak_mib < 200
    assert best_of(lambda: None, 1, memory=False).peak_mib is None


def test_alternate_gives_every_action_as_many_calls_as_the_first_in_each_round(no_collection) -> None:
    # the bests are minima: a side given more calls would have more draws at a low time
    calls = {"floor": 0, "ours": 0}

    def floor() -> None:
        calls["floor"] += 1
        sum(range(2_000))

    def ours() -> None:  # ten times the floor: a time budget per block would give it fewer calls
        calls["ours"] += 1
        sum(range(20_000))

    best = alternate({"floor": floor, "ours": ours}, 4, min_calls=5, min_seconds=0.002)
    assert calls["floor"] > 4 * 5 and calls["ours"] == calls["floor"]
    assert 0 < best["floor"].cpu < best["ours"].cpu
    assert best["ours"].calls == calls["ours"] and best["ours"].settled_cpu >= best["ours"].cpu


# --------------------------------------------------------------------------- rows and the table


def test_goals_judge_the_figure_or_the_ratio() -> None:
    fast = Row("parse", 0.2, reference=0.1, goal=Goal(5, on="ratio"))
    assert fast.ratio == pytest.approx(2.0) and fast.verdict == "ok"
    slow = Row("import", 3.0, goal=Goal(2.0))
    assert slow.verdict == "MISSED" and slow.ratio is None
    rate = Row("read", 0.8, "MB/s", goal=Goal(1.0, at_most=False))
    assert rate.verdict == "MISSED" and rate.goal.text("MB/s") == ">= 1.00 MB/s"
    faster = Goal(1 / 20, on="ratio", says="20x faster")
    assert Row("sim", 1.0, reference=None, goal=faster).verdict == "n/a"
    assert faster.text("s") == "<= 0.05x (20x faster)"
    assert Row("plain", 1.0).verdict == ""


def test_one_table_of_every_row() -> None:
    rows = [
        Row(
            "import x", 0.0123, reference=0.00246, against="lxml parse", goal=Goal(5, on="ratio"), module="m"
        ),
        Row("RTA", 1.5, wall=2.25, goal=Goal(0.5), peak_mib=12.0, module="s", note="1000 tasks"),
        Row("jobs per second", 415178.0, "jobs/s", module="s"),
    ]
    lines = format_table(rows, modules=True).splitlines()
    assert lines[0].split() == [
        "measure",
        "ours",
        "wall",
        "reference",
        "ratio",
        "goal",
        "met",
        "peak",
        "MiB",
        "note",
    ]
    assert set(lines[1]) <= {"-", " "} and len(lines) == 5
    assert lines[2].startswith("m: import x") and "12 ms" in lines[2] and "2.46 ms lxml parse" in lines[2]
    assert "5.00x" in lines[2] and "<= 5x" in lines[2] and lines[2].split()[-1] == "ok"
    assert "1.50 s" in lines[3] and "2.25 s" in lines[3] and "MISSED" in lines[3] and "1000 tasks" in lines[3]
    assert "415,178 jobs/s" in lines[4]


def test_report_hands_its_rows_back_as_json(tmp_path, monkeypatch, capsys) -> None:
    target = tmp_path / "rows.json"
    monkeypatch.setenv(harness.ROWS_ENV, str(target))
    report = Report("demo")
    report.add("count", 3, "", goal=Goal(0))
    report.growth("import", [(100, 0.1), (1000, 1.0)])
    assert report.finish() == 1  # a goal is missed
    assert "count" in capsys.readouterr().out
    rows = read_rows(target)
    assert [r.measure for r in rows] == ["count", "import growth 100 -> 1000: exponent k"]
    assert rows[0].goal == Goal(0) and rows[0].module == "demo" and rows[0].verdict == "MISSED"
    assert rows[1].ours == pytest.approx(1.0)
    assert json.loads(target.read_text())[0]["measure"] == "count"
    assert read_rows(tmp_path / "absent.json") == []


# --------------------------------------------------------------------------- shared generators


def test_chained_system_has_the_size_asked() -> None:
    ws = chained_system(processes=3, threads=4)
    package = ws.units[-1]
    node = next(c for c in package.classifiers if c.name == "node.impl")
    top = next(c for c in package.classifiers if c.name == "top.impl")
    assert len(node.subcomponents) == 4 and len(node.connections) == 5  # in, 3 between, out
    assert len(top.subcomponents) == 4 and len(top.connections) == 2  # 3 processes and the cpu
    assert [u.name for u in ws.units[:-1]] == [
        "AADL_Project",
        "Timing_Properties",
        "Thread_Properties",
        "Memory_Properties",
        "Deployment_Properties",
    ]


def test_time_units_are_consecutive_literals_of_the_standard_chain() -> None:
    units = time_units("ns", "us", "ms")
    assert [(u.name, u.baseUnit, u.factor.value if u.factor else None) for u in units.ownedLiterals] == [
        ("ns", None, None),
        ("us", "ns", 1000),
        ("ms", "us", 1000),
    ]
    with pytest.raises(ValueError):
        time_units("us", "sec")


def test_generated_package_text_parses_with_one_type_and_implementation_per_component() -> None:
    tree = parse(aadl_package_text(300), "<generated>")
    assert len(list(tree.find_data("component_type"))) == 300
    assert len(list(tree.find_data("component_implementation"))) == 300


def test_random_task_sets_are_reproducible() -> None:
    sets = random_simulation_sets(6)
    assert sets == random_simulation_sets(6)
    assert [s for s, _ in sets[:2]] == [Scheduler.EARLIEST_DEADLINE_FIRST, Scheduler.FIXED_PRIORITY]
    assert all(5 <= len(tasks) <= 15 for _, tasks in sets)
    tasks = random_rta_tasks(50, 0.9)
    assert len(tasks) == 50 and sum(t.capacity / t.period for t in tasks) == pytest.approx(0.9, abs=0.01)
    assert len({t.priority for t in tasks}) == 50


def test_generated_rosmod_project_has_a_node_per_instance() -> None:
    project = rosmod_project(10)
    (deployment,) = project.deployments
    assert len(deployment.nodes) == 10 and len(project.software.packages[0].components) == 5
    assert model.is_a(deployment.nodes[0].componentInstances[0], "rosmod.ComponentInstance")

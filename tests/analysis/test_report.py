"""The combined report (rosaadl.analysis.report): JSON document, text tables, CSV files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from instance_builders import num, pa, ref

from rosaadl import model
from rosaadl.analysis import ANALYSES, DEFAULT_ANALYSES, AnalysisReport, parse_only, run_analyses
from rosaadl.errors import UsageError

new = model.new


def thread(name, period, cet, priority, ports=()):
    ci = new("ComponentInstance", name=name, category="thread")
    ci.ownedPropertyAssociations.extend(
        [
            pa("Timing_Properties::Period", num(period, "us")),
            pa(
                "Timing_Properties::Compute_Execution_Time",
                new("RangeValue", minimum=num(cet, "us"), maximum=num(cet, "us")),
            ),
            pa("Thread_Properties::Priority", new("IntegerValue", value=priority)),
        ]
    )
    ci.featureInstances.extend(ports)
    return ci


def port(name, direction):
    fi = new("FeatureInstance", name=name, feature=name, category="event data port", direction=direction)
    fi.ownedPropertyAssociations.append(pa("Memory_Properties::Data_Size", num(100, "Bytes")))
    return fi


def robot(overload=False):
    root = new("SystemInstance", name="robot_i_Instance", category="system")
    cpu = new("ComponentInstance", name="cpu", category="processor")
    cpu.ownedPropertyAssociations.extend(
        [
            pa("SEI::MIPSCapacity", num(1000.0, "MIPS")),
            pa(
                "Deployment_Properties::Scheduling_Protocol",
                new("NamedValue", name="RATE_MONOTONIC_PROTOCOL"),
            ),
        ]
    )
    net = new("ComponentInstance", name="net", category="bus")
    net.ownedPropertyAssociations.extend(
        [
            pa("SEI::BandWidthCapacity", num(100.0, "KBytesps")),
            pa("SEI::BandWidthBudget", num(50.0, "KBytesps")),
        ]
    )
    a = thread("a", 10_000, 8000 if overload else 2000, 2, [port("o", "out")])
    b = thread("b", 20_000, 5000, 1, [port("i", "in")])
    node = new("ComponentInstance", name="node", category="process")
    node.componentInstances.extend([a, b])
    for t in (a, b):
        t.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Processor_Binding", ref(cpu)))
    root.componentInstances.extend([cpu, net, node])
    conn = new(
        "ConnectionInstance",
        name="node.a.o -> node.b.i",
        kind="portConnection",
        source=a.featureInstances[0],
        destination=b.featureInstances[0],
    )
    conn.ownedPropertyAssociations.extend(
        [
            pa("Deployment_Properties::Actual_Connection_Binding", ref(net)),
            pa("SEI::BandWidthBudget", num(20.0, "KBytesps")),
        ]
    )
    root.connectionInstances.append(conn)
    return root


def test_json_document_shape():
    report = run_analyses(robot())
    data = json.loads(report.to_json())
    assert list(data) == ["ok", "analyses", "errors", "warnings"]
    assert list(data["analyses"]) == [
        "cpu",
        "budget",
        "bus",
        "schedulability",
        "simulation",
        "latency",
        "executor",
    ]
    (proc,) = data["analyses"]["cpu"]["processors"]
    assert list(proc) == ["path", "capacity_mips", "demand_mips", "load_percent", "threads"]
    assert proc == {
        "path": "robot_i_Instance.cpu",
        "capacity_mips": 1000,
        "demand_mips": 450,
        "load_percent": 45,
        "threads": [
            {
                "path": "robot_i_Instance.node.a",
                "period_us": 10000,
                "cet_us": 2000,
                "load_percent": 20,
                "mips_demand": 200,
            },
            {
                "path": "robot_i_Instance.node.b",
                "period_us": 20000,
                "cet_us": 5000,
                "load_percent": 25,
                "mips_demand": 250,
            },
        ],
    }
    (bus,) = data["analyses"]["bus"]["buses"]
    assert {k: bus[k] for k in ("path", "capacity_kbps", "budget_kbps", "required_kbps", "actual_kbps")} == {
        "path": "robot_i_Instance.net",
        "capacity_kbps": 100,
        "budget_kbps": 50,
        "required_kbps": 20,
        "actual_kbps": 10,
    }
    assert bus["connections"] == [
        {"path": "robot_i_Instance.node.a.o -> node.b.i", "budget_kbps": 20, "actual_kbps": 10}
    ]
    (dom,) = data["analyses"]["schedulability"]["processors"]
    assert list(dom) == ["path", "scheduler", "utilization", "bound", "feasibility_interval", "tasks"]
    assert list(dom["tasks"][0]) == ["path", "priority", "period", "capacity", "deadline", "wcrt", "met"]
    assert [t["wcrt"] for t in dom["tasks"]] == [2000, 7000]
    assert data["analyses"]["simulation"]["deadline_misses"] == 0
    chain, sync = data["analyses"]["latency"]["chains"]  # one entry per system kind
    assert (chain["mode"], sync["mode"]) == ("async", "sync")
    assert chain["threads"] == sync["threads"] == ["robot_i_Instance.node.a", "robot_i_Instance.node.b"]
    assert {"best_us", "worst_us", "expected_us", "met", "hops"} <= set(chain)
    assert data["ok"] is True and data["errors"] == []
    for warning in data["warnings"]:
        assert list(warning) == ["message", "file", "line", "column", "path"]


def test_overload_fails_the_report():
    report = run_analyses(robot(overload=True))
    assert not report.ok
    errors = {(d.location.path, d.message.split(":")[0]) for d in report.errors}
    assert ("robot_i_Instance.cpu", "Processor robot_i_Instance.cpu") in errors
    assert any(
        d.location.path == "robot_i_Instance.cpu" and "not schedulable" in d.message for d in report.errors
    )
    assert any("missed" in d.message for d in report.errors)
    assert json.loads(report.to_json())["ok"] is False


def test_text_tables():
    text = run_analyses(robot()).text()
    for heading in (
        "CPU (bound resources)",
        "Bus load (KB/s)",
        "Schedulability",
        "Simulation",
        "End-to-end latency",
    ):
        assert heading in text
    assert "node.a" in text and text.rstrip().endswith("OK")


def test_csv_files(tmp_path: Path):
    report = run_analyses(robot(), "cpu,budget,bus,sched,sim,latency,deploy")
    files = report.write_csv(tmp_path / "out")
    names = sorted(f.name for f in files)
    assert names == sorted(
        f"robot_i_Instance__{n}.csv"
        for n in (
            "BusLoad",
            "BoundResourceAnalysis",
            "ResourceBudgets",
            "Schedulability",
            "Simulation",
            "Latency",
            "Deployment",
            "latency_AS-MF-ET-EQ",  # OSATE's latency report, per system kind
            "latency_SS-MF-ET-EQ",
        )
    )
    bound = (tmp_path / "out" / "robot_i_Instance__BoundResourceAnalysis.csv").read_text(encoding="utf-8")
    assert "Detailed Workload Report: for Processor cpu with Capacity 1000.000 MIPS" in bound
    assert "Total,,450.000 MIPS,45.00 %" in bound
    sched = (
        (tmp_path / "out" / "robot_i_Instance__Schedulability.csv").read_text(encoding="utf-8").splitlines()
    )
    assert sched[0] == "Processor,Scheduler,Task,Priority,Period,Capacity,Deadline,WCRT,Met"
    assert sched[2].endswith(",7000,true")
    # deterministic: the same input gives the same bytes
    again = run_analyses(robot(), "cpu,budget,bus,sched,sim,latency,deploy")
    assert again.csv_files() == report.csv_files() and again.to_json() == report.to_json()


def test_an_analysis_that_cannot_run_becomes_an_error():
    root = robot()
    root.componentInstances.remove(root.componentInstances[0])  # no processor: nothing to deploy on
    report = run_analyses(root, ["deploy", "bus"])
    assert report.deployment is None and report.bus is not None
    assert any(d.message.startswith("deploy analysis:") for d in report.errors) and not report.ok


def test_selection():
    assert parse_only(None) == DEFAULT_ANALYSES
    assert parse_only("latency, cpu,bus") == ("cpu", "bus", "latency")
    assert parse_only(["schedulability", "simulation"]) == ("sched", "sim")
    assert set(parse_only(",".join(ANALYSES))) == set(ANALYSES)
    with pytest.raises(UsageError, match="unknown analysis gpu"):
        parse_only("cpu,gpu")
    with pytest.raises(UsageError):
        parse_only(" , ")


def test_empty_report_is_ok():
    report = AnalysisReport("x")
    assert report.ok and report.as_dict() == {"ok": True, "analyses": {}, "errors": [], "warnings": []}
    assert report.csv_files() == {}


def test_bad_input_never_crashes_any_analysis():
    """Missing Period or Compute_Execution_Time, a zero period, a binding to a non-processor:
    every analysis runs, and the problems are diagnostics naming the thread's instance path."""
    root = robot()
    cpu, net, node = root.componentInstances
    no_period = thread("no_period", 10_000, 100, 0)
    no_period.ownedPropertyAssociations.pop(0)
    no_cet = thread("no_cet", 10_000, 100, 0)
    no_cet.ownedPropertyAssociations.pop(1)
    zero = thread("zero", 10_000, 100, 0)
    zero.ownedPropertyAssociations[0].ownedValues[0].value = num(0, "us")
    on_bus = thread("on_bus", 10_000, 100, 0)
    for t in (no_period, no_cet, zero):
        t.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Processor_Binding", ref(cpu)))
    on_bus.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Processor_Binding", ref(net)))
    node.componentInstances.extend([no_period, no_cet, zero, on_bus])
    report = run_analyses(root, ",".join(ANALYSES))
    assert all(r is not None for r in (report.cpu, report.bus, report.schedulability, report.deployment))
    paths = {d.location.path for d in report.diagnostics}
    for name in ("no_period", "no_cet", "zero", "on_bus"):
        assert f"robot_i_Instance.node.{name}" in paths, name
    assert not report.ok
    json.loads(report.to_json())
    assert "robot_i_Instance.node.on_bus" in report.text()

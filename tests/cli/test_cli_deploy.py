"""``rosaadl deploy``: the solver's binding written as ``<package>_proposed.aadl`` and re-analysed,
the JSON of the issue, infeasible models explained with exit 1, and the demo's failing deployment
(its proposed binding instantiated and passing every analysis that depends on the binding)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from rosaadl.cli import main
from rosaadl.exporters.aadl_text import write_model
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.rosmod_text import read_project
from rosaadl.transforms.instantiate import instantiate
from rosaadl.workflow.binding import bind_project, read_bindings
from rosaadl.workflow.deploy import DeployRun, check_proposed, deploy_instance

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "tracking"

RIG = """package rig
public
  with SEI;
  processor cpu
  properties
    Scheduling_Protocol => (RATE_MONOTONIC_PROTOCOL);
    SEI::MIPSCapacity => 1000.0 MIPS;
  end cpu;
  thread worker
  properties
    Dispatch_Protocol => Periodic;
    Period => 100 ms;
  end worker;
  thread implementation worker.light
  properties
    Compute_Execution_Time => 30 ms .. 30 ms;
  end worker.light;
  thread implementation worker.heavy
  properties
    Compute_Execution_Time => 111 ms .. 111 ms;
  end worker.heavy;
  process node
  properties
    SEI::MIPSBudget => 400.0 MIPS;
  end node;
  process implementation node.light
  subcomponents
    t : thread worker.light;
  end node.light;
  process implementation node.heavy
  subcomponents
    t : thread worker.heavy;
  end node.heavy;
  system robot
  end robot;
  system implementation robot.impl
  subcomponents
    c0 : processor cpu;
    c1 : processor cpu;
    a : process node.light;
    b : process node.light;
    c : process node.light;
  properties
    Actual_Processor_Binding => (reference (c0)) applies to a, b, c;
  end robot.impl;
  system implementation robot.overloaded extends robot.impl
  subcomponents
    h : process node.heavy;
  properties
    Actual_Processor_Binding => (reference (c1)) applies to h;
  end robot.overloaded;
end rig;
"""


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture
def rig(tmp_path: Path) -> Path:
    path = tmp_path / "rig.aadl"
    path.write_text(RIG)
    return path


def test_deploy_writes_the_best_binding_with_the_fewest_moves(rig, tmp_path, capsys):
    out = tmp_path / "out"
    code, stdout, err = run(
        [
            "--format",
            "json",
            "deploy",
            str(rig),
            "--root",
            "rig::robot.impl",
            "-o",
            str(out),
            "--deterministic",
        ],
        capsys,
    )
    assert code == 0, err
    data = json.loads(stdout)
    assert data["ok"] is True and data["feasible"] is True
    assert [o["name"] for o in data["objectives"]] == [
        "max_core_load",
        "bus_load",
        "longest_chain_latency",
        "moves",
    ]
    top, bus, latency, moves = data["objectives"]
    assert top == {"name": "max_core_load", "value": 60, "bound": 60, "gap_percent": 0.0, "unit": "percent"}
    assert bus["value"] == 0 and latency["value"] is None
    assert moves["value"] == 1  # two of a, b, c stay on c0, one moves to c1
    assert set(data["baseline"]) == {"first_fit", "best_fit", "worst_fit"}
    assert data["baseline"]["first_fit"]["max_load_percent"] == 90
    assert data["current"]["max_load_percent"] == 90
    assert sorted(b["processor"] for b in data["binding"]).count("robot_impl_Instance.c0") == 2
    written = Path(data["output"])
    assert written == out / "rig_proposed.aadl" and data["root"] == "rig_proposed::robot.impl"
    text = written.read_text()
    assert "applies to a, b, c" not in text  # the root's own association for them is replaced
    assert all(f"applies to {unit};" in text for unit in ("a", "b", "c", "h"))
    # the proposed package reads back with the model and passes the analyses
    instance = instantiate(read_files([rig, written]), "rig_proposed::robot.impl")
    from rosaadl.analysis.report import run_analyses

    report = run_analyses(instance)
    assert report.ok and max(p.load_percent for p in report.cpu.processors) == 60
    # text output: the objectives, the baselines beside the current binding, the moves
    code, stdout, _err = run(["deploy", str(rig), "--root", "rig::robot.impl", "-o", str(out)], capsys)
    assert code == 0
    assert "max_core_load" in stdout and "current" in stdout and "proposed binding: rig_proposed" in stdout


def test_an_infeasible_model_is_explained_and_exits_1(rig, tmp_path, capsys):
    out = tmp_path / "out"
    code, stdout, err = run(
        ["--format", "json", "deploy", str(rig), "--root", "rig::robot.overloaded", "-o", str(out)], capsys
    )
    assert code == 1
    data = json.loads(stdout)
    assert data["ok"] is False and data["feasible"] is False and data["output"] is None
    (reason,) = data["explanation"]
    assert reason["constraint"] == "cpu" and reason["path"].endswith(".h")
    assert reason["message"].startswith("h at 10 Hz needs 111.0 % of any")
    assert not out.exists()  # nothing written
    code, _stdout, err = run(["deploy", str(rig), "--root", "rig::robot.overloaded", "-o", str(out)], capsys)
    assert code == 1 and "needs 111.0 % of any" in err


@pytest.mark.parametrize(
    ("options", "message"),
    [(["--keep", "0"], "--keep"), (["--time-limit", "0"], "--time-limit")],
)
def test_bad_options_are_usage_errors(rig, capsys, options, message):
    code, _out, err = run(["deploy", str(rig), "--root", "rig::robot.impl", *options], capsys)
    assert code == 2 and message in err


def test_the_demos_failing_deployment_gets_a_binding_that_passes(tmp_path, capsys):
    library = read_files([], include_library=True)
    bound = bind_project(read_project(EXAMPLE), read_bindings(EXAMPLE / "bindings.json"), library)
    pioneer = bound["pioneer_3dx"]
    (path,) = write_model([pioneer.package], tmp_path)
    instance = instantiate(read_files([path]), pioneer.root)
    run_: DeployRun = deploy_instance(instance, tmp_path / "out", time_limit=5, deterministic=True)
    assert run_.proposal.current is not None and not run_.proposal.current.feasible  # 118 % today
    assert run_.output is not None and run_.root == "pioneer_3dx_bound_proposed::tracking.impl"
    proposed, report = check_proposed([path], run_)
    assert not any(p.overloaded for p in report.cpu.processors)
    assert report.schedulability.ok and report.bus.ok and report.latency.ok and not report.failures
    assert all(t.deadline_misses == 0 for t in report.simulation.tasks)
    # the only finding left is a node's MIPS budget, a property of the library node that the
    # current binding has as well: no binding can change it
    from rosaadl.analysis.report import run_analyses

    before = run_analyses(instance)
    left = {d.message for d in report.diagnostics if d.severity == "error"}
    assert left and left <= {d.message for d in before.diagnostics if d.severity == "error"}
    assert all("SEI::MIPSBudget" in message for message in left)


HOSTILE = """package hostile
public
  thread sampled
  properties
    Dispatch_Protocol => Periodic;
    Compute_Execution_Time => 1 ms .. 2 ms;
  end sampled;
  process node
  end node;
  process implementation node.sampled
  subcomponents
    t : thread sampled;
  end node.sampled;
  processor cpu
  end cpu;
  processor implementation cpu.impl
  end cpu.impl;
  virtual processor part
  end part;
  system robot
  end robot;
  system implementation robot.shells
  subcomponents
    c0 : processor cpu;
    a : process node;
    b : process node;
  end robot.shells;
  system implementation robot.unperiodic
  subcomponents
    c0 : processor cpu;
    a : process node.sampled;
  end robot.unperiodic;
  system implementation robot.modal
  subcomponents
    c0 : processor cpu;
    c1 : processor cpu in modes (full);
    a : process node.sampled;
    b : process node.sampled in modes (full);
  modes
    safe : initial mode;
    full : mode;
  end robot.modal;
  system implementation robot.nowhere
  subcomponents
    c0 : processor cpu;
    loose : virtual processor part;
    a : process node.sampled;
  properties
    Allowed_Processor_Binding => (reference (loose)) applies to a;
  end robot.nowhere;
end hostile;
"""


def deploy(model: Path, root: str, out: Path, *options: str) -> list[str]:
    return [*options, "deploy", str(model), "--root", root, "-o", str(out)]


@pytest.mark.parametrize(
    ("root", "message"),
    [
        ("hostile::cpu.impl", "is a processor, not a system"),
        ("hostile::node.sampled", "is a process, not a system"),
        ("hostile::robot.shells", "has no process to bind"),
    ],
)
def test_what_cannot_be_deployed_is_a_located_error_and_writes_nothing(tmp_path, capsys, root, message):
    model = tmp_path / "hostile.aadl"
    model.write_text(HOSTILE)
    out = tmp_path / "out"
    code, _stdout, err = run(deploy(model, root, out), capsys)
    assert code == 1 and message in err and "Traceback" not in err
    assert re.search(r"error: \w+_Instance: ", err)  # located at the instance
    assert not out.exists()


def test_what_the_problem_cannot_read_is_warned_beside_the_proposal(tmp_path, capsys):
    model = tmp_path / "hostile.aadl"
    model.write_text(HOSTILE)
    json_out = ("--format", "json")
    code, stdout, err = run(deploy(model, "hostile::robot.unperiodic", tmp_path, *json_out), capsys)
    assert code == 0, err
    data = json.loads(stdout)
    assert any("has no Period" in w["message"] and w["path"].endswith("a.t") for w in data["warnings"])
    # what exists only in other modes is left as it is, and said
    code, stdout, err = run(deploy(model, "hostile::robot.modal", tmp_path, *json_out), capsys)
    assert code == 0, err
    data = json.loads(stdout)
    assert [b["path"] for b in data["binding"]] == ["robot_modal_Instance.a"]
    assert any(
        "first system mode (safe)" in w["message"] and "(b, c1)" in w["message"] for w in data["warnings"]
    )
    # a virtual processor bound nowhere leaves its unit no core, and the reason says which
    code, _stdout, err = run(deploy(model, "hostile::robot.nowhere", tmp_path), capsys)
    assert code == 1 and "Allowed_Processor_Binding (loose) names no candidate processor" in err
    assert "demands MIPS" not in err  # no core to take is not a core without MIPS


THREADS_BOUND = """package threads_bound
public
  thread worker
  properties
    Dispatch_Protocol => Periodic;
    Period => 10 ms;
    Compute_Execution_Time => 4 ms .. 4 ms;
  end worker;
  process node
  end node;
  process implementation node.impl
  subcomponents
    t1 : thread worker;
    t2 : thread worker;
  end node.impl;
  processor cpu
  properties
    Scheduling_Protocol => (RATE_MONOTONIC_PROTOCOL);
  end cpu;
  virtual processor part
  end part;
  processor implementation cpu.partitioned
  subcomponents
    part1 : virtual processor part;
    part2 : virtual processor part;
  end cpu.partitioned;
  system robot
  end robot;
  system implementation robot.threads
  subcomponents
    c0 : processor cpu;
    c1 : processor cpu;
    a : process node.impl;
    b : process node.impl;
    spare : virtual processor part;
  properties
    Actual_Processor_Binding => (reference (c0)) applies to a.t1, a.t2, b.t1, b.t2, spare;
  end robot.threads;
  system implementation robot.partitions
  subcomponents
    m0 : processor cpu.partitioned;
    m1 : processor cpu.partitioned;
    a : process node.impl;
    b : process node.impl;
  properties
    Actual_Processor_Binding => (reference (m0.part1)) applies to a;
    Actual_Processor_Binding => (reference (m0.part2)) applies to b;
  end robot.partitions;
end threads_bound;
"""


def test_the_proposal_holds_where_the_model_binds_threads_and_partitions(tmp_path):
    """A model binding the threads (not the process) has them where they are as the current
    binding, and the proposal restates the threads' bindings (a thread's own binding beats
    the one it inherits); a root association that also binds something else keeps that; a
    unit bound to a partition that stays on its processor keeps the partition."""
    from rosaadl.analysis.instance_values import bound_processor
    from rosaadl.model import component_instances

    path = tmp_path / "threads_bound.aadl"
    path.write_text(THREADS_BOUND)
    model = read_files([path])
    run_ = deploy_instance(
        instantiate(model, "threads_bound::robot.threads"), tmp_path / "t", deterministic=True
    )
    problem = run_.proposal.problem
    assert [len(c) for c in problem.current] == [1, 1]  # on c0, through their threads
    assert run_.proposal.outcome.best is not None
    proposed = dict(run_.proposal.binding())
    assert len(set(proposed.values())) == 2  # 80 % each: one moves
    assert run_.output is not None and run_.root is not None
    instance = instantiate(read_files([path, run_.output]), run_.root)
    for ci in component_instances(instance):
        if ci.name in ("t1", "t2"):
            unit = f"{problem.root}.{ci.eContainer().name}"
            assert bound_processor(ci).name == proposed[unit].rpartition(".")[2]
        if ci.name == "spare":
            assert bound_processor(ci).name == "c0"
    run_ = deploy_instance(
        instantiate(model, "threads_bound::robot.partitions"), tmp_path / "p", deterministic=True
    )
    binding = {u.rpartition(".")[2]: c.partition(".")[2] for u, c in run_.proposal.binding()}
    stays = [u for u, c in binding.items() if c.startswith("m0")]
    assert len(stays) == 1 and binding[stays[0]] == {"a": "m0.part1", "b": "m0.part2"}[stays[0]]

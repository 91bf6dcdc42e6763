"""What a unit may be bound to, as AADL models write it beyond ``Allowed_Processor_Binding`` to a
processor or a system: ``Allowed_Processor_Binding_Class`` (a processor, virtual processor or
system classifier, extensions included), virtual processors (partitions, or the cores of a
multi-core processor) named by ``Allowed_Processor_Binding`` and ``Actual_Processor_Binding``, and
processes budgeted with ``SEI::MIPSBudget`` before their threads are modelled."""

from __future__ import annotations

from pathlib import Path

import pytest

from rosaadl.analysis.deployment_problem import deployment_problem
from rosaadl.analysis.deployment_proposal import propose_deployment
from rosaadl.importers.aadl_text import read_files
from rosaadl.transforms.instantiate import instantiate

MODEL = """package targets
public
  with SEI;
  thread worker
  properties
    Dispatch_Protocol => Periodic;
    Period => 10 ms;
    Compute_Execution_Time => 2 ms .. 2 ms;
  end worker;
  process node
  end node;
  process implementation node.impl
  subcomponents
    w : thread worker;
  end node.impl;
  process budgeted
  properties
    SEI::MIPSBudget => 80.0 MIPS;
  end budgeted;
  process empty
  end empty;
  process stored
  properties
    SEI::RAMBudget => 80.0 KByte;
  end stored;
  memory ram
  properties
    Memory_Size => 100.0 KByte;
  end ram;
  system shelf
  end shelf;
  system implementation shelf.impl
  subcomponents
    cpu : processor cpu.impl;
    mem : memory ram;
  end shelf.impl;
  processor cpu
  properties
    Scheduling_Protocol => (RATE_MONOTONIC_PROTOCOL);
    SEI::MIPSCapacity => 100.0 MIPS;
  end cpu;
  processor implementation cpu.impl
  end cpu.impl;
  processor implementation cpu.fast extends cpu.impl
  end cpu.fast;
  processor other
  properties
    Scheduling_Protocol => (RATE_MONOTONIC_PROTOCOL);
    SEI::MIPSCapacity => 100.0 MIPS;
  end other;
  virtual processor part
  end part;
  processor soc
  properties
    Scheduling_Protocol => (RATE_MONOTONIC_PROTOCOL);
    SEI::MIPSCapacity => 100.0 MIPS;
  end soc;
  processor implementation soc.dual
  subcomponents
    v0 : virtual processor part;
    v1 : virtual processor part;
  end soc.dual;
  system board
  end board;
  system implementation board.impl
  subcomponents
    cpu : processor other;
  end board.impl;
  system robot
  end robot;
  system implementation robot.classes
  subcomponents
    c0 : processor other;
    c1 : processor cpu.fast;
    b : system board.impl;
    p : process node.impl;
    q : process node.impl;
    r : process node.impl;
  properties
    Allowed_Processor_Binding_Class => (classifier (targets::cpu)) applies to p;
    Allowed_Processor_Binding_Class => (classifier (targets::board.impl)) applies to q;
    Allowed_Processor_Binding_Class => (classifier (targets::cpu.fast)) applies to r;
  end robot.classes;
  system implementation robot.partitions
  subcomponents
    c0 : processor cpu.impl;
    c1 : processor cpu.impl;
    s : processor soc.dual;
    part1 : virtual processor part;
    p : process node.impl;
    q : process node.impl;
    r : process node.impl;
  properties
    Actual_Processor_Binding => (reference (c1)) applies to part1;
    Allowed_Processor_Binding => (reference (part1)) applies to p;
    Actual_Processor_Binding => (reference (part1)) applies to p;
    Allowed_Processor_Binding => (reference (s.v1)) applies to q;
  end robot.partitions;
  system implementation robot.threads
  subcomponents
    c0 : processor other;
    c1 : processor cpu.impl;
    p : process node.impl;
    q : process node.impl;
  properties
    Allowed_Processor_Binding => (reference (c1)) applies to p.w;
    Allowed_Processor_Binding_Class => (classifier (targets::other)) applies to q.w;
  end robot.threads;
  system implementation robot.memory
  subcomponents
    left : system shelf.impl;
    right : system shelf.impl;
    m : process stored;
    n : process stored;
  end robot.memory;
  system implementation robot.budgets
  subcomponents
    c0 : processor cpu.impl;
    c1 : processor cpu.impl;
    a : process budgeted;
    b : process budgeted;
    e : process empty;
  end robot.budgets;
end targets;
"""


@pytest.fixture(scope="module")
def model(tmp_path_factory: pytest.TempPathFactory):
    path: Path = tmp_path_factory.mktemp("targets") / "targets.aadl"
    path.write_text(MODEL)
    return read_files([path])


def _binding(model, root: str) -> dict[str, str]:
    proposal = propose_deployment(instantiate(model, root), time_limit=5, deterministic=True)
    assert proposal.feasible
    prefix = proposal.problem.root + "."
    return {u.removeprefix(prefix): c.removeprefix(prefix) for u, c in proposal.binding()}


def test_allowed_processor_binding_class_restricts_the_cores(model):
    """A type admits its implementations and their extensions; a system classifier the cores
    inside the systems of that classifier (OSATE's binding check: same or extends)."""
    problem = deployment_problem(instantiate(model, "targets::robot.classes"))
    cores = [c.path.partition(".")[2] for c in problem.cores]
    allowed = {
        u.path.partition(".")[2]: [cores[k] for k in problem.allowed[i]] for i, u in enumerate(problem.units)
    }
    assert allowed == {"p": ["c1"], "q": ["b.cpu"], "r": ["c1"]}
    assert {pin.reason for pin in problem.pins} == {"Allowed_Processor_Binding_Class"}
    assert _binding(model, "targets::robot.classes") == {"p": "c1", "q": "b.cpu", "r": "c1"}


def test_a_virtual_processor_is_bound_to_where_it_runs(model):
    """``Allowed_Processor_Binding`` naming a virtual processor: the unit runs on the processor
    that hosts it (its ``Actual_Processor_Binding``, else the processor containing it) and the
    binding names the virtual processor; a current binding to it counts as that core."""
    problem = deployment_problem(instantiate(model, "targets::robot.partitions"))
    cores = [c.path.partition(".")[2] for c in problem.cores]
    assert cores == ["c0", "c1", "s"]
    assert [cores[k] for k in problem.allowed[0]] == ["c1"] and [cores[k] for k in problem.allowed[1]] == [
        "s"
    ]
    assert [cores[k] for k in problem.current[0]] == ["c1"]
    binding = _binding(model, "targets::robot.partitions")
    assert binding["p"] == "part1" and binding["q"] == "s.v1" and binding["r"] in cores


def test_a_process_budgeted_before_its_threads_is_bound(model):
    """A process without threads but with an ``SEI::MIPSBudget`` is a unit of its budget (two
    of 80 % cannot share a core); one with neither is left as it is."""
    problem = deployment_problem(instantiate(model, "targets::robot.budgets"))
    assert [u.path.partition(".")[2] for u in problem.units] == ["a", "b"]
    binding = _binding(model, "targets::robot.budgets")
    assert sorted(binding.values()) == ["c0", "c1"]


def test_a_threads_restriction_holds_for_its_process(model):
    """OSATE checks the bindings of threads: a process is bound with its threads, so their own
    ``Allowed_Processor_Binding`` and ``Allowed_Processor_Binding_Class`` restrict it."""
    problem = deployment_problem(instantiate(model, "targets::robot.threads"))
    cores = [c.path.partition(".")[2] for c in problem.cores]
    assert [[cores[k] for k in allowed] for allowed in problem.allowed] == [["c1"], ["c0"]]
    assert [pin.reason for pin in problem.pins] == [
        "Allowed_Processor_Binding of p.w",
        "Allowed_Processor_Binding_Class of q.w",
    ]
    assert _binding(model, "targets::robot.threads") == {"p": "c1", "q": "c0"}


def test_a_process_with_only_a_ram_budget_takes_memory(model):
    """A process without threads whose demand is an ``SEI::RAMBudget``: two of 80 KByte do not
    fit one board of 100 KByte."""
    problem = deployment_problem(instantiate(model, "targets::robot.memory"))
    assert [(u.path.partition(".")[2], u.memory_kbyte) for u in problem.units] == [("m", 80), ("n", 80)]
    binding = _binding(model, "targets::robot.memory")
    assert sorted(binding.values()) == ["left.cpu", "right.cpu"]

"""Deployment search (rosaadl.analysis.deployment): optimality on small problems against brute
force, the heuristic's quality bound on larger ones, load and schedulability constraints."""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import pytest
from instance_builders import num, pa

from rosaadl import model
from rosaadl.analysis.deployment import search_deployment
from rosaadl.errors import ModelError

new = model.new


def thread(name, period, cet, props=()):
    ci = new("ComponentInstance", name=name, category="thread")
    ci.ownedPropertyAssociations.extend(
        [
            pa("Timing_Properties::Period", num(period, "us")),
            pa(
                "Timing_Properties::Compute_Execution_Time",
                new("RangeValue", minimum=num(cet, "us"), maximum=num(cet, "us")),
            ),
            *props,
        ]
    )
    return ci


def process(name, *threads, budget=None):
    ci = new("ComponentInstance", name=name, category="process")
    ci.componentInstances.extend(threads)
    if budget is not None:
        ci.ownedPropertyAssociations.append(pa("SEI::MIPSBudget", num(float(budget), "MIPS")))
    return ci


def core(name, mips=None, scheduler=None):
    ci = new("ComponentInstance", name=name, category="processor")
    if mips is not None:
        ci.ownedPropertyAssociations.append(pa("SEI::MIPSCapacity", num(float(mips), "MIPS")))
    if scheduler is not None:
        ci.ownedPropertyAssociations.append(
            pa("Deployment_Properties::Scheduling_Protocol", new("NamedValue", name=scheduler))
        )
    return ci


def system(cores, processes):
    root = new("SystemInstance", name="d_i_Instance", category="system")
    board = new("ComponentInstance", name="board", category="system")
    board.componentInstances.extend(cores)
    root.componentInstances.append(board)
    root.componentInstances.extend(processes)
    return root


def random_problem(rng, n, m):
    """n processes of one or two threads with harmonic periods on m identical cores; returns the
    instance and each process's load (Σ CET / Period)."""
    periods = [1000, 2000, 4000, 8000]
    processes, loads = [], []
    for i in range(n):
        threads, load = [], Fraction(0)
        for j in range(rng.randint(1, 2)):
            period = rng.choice(periods)
            cet = rng.randint(1, period * 35 // 100)
            threads.append(thread(f"t{j}", period, cet))
            load += Fraction(cet, period)
        processes.append(process(f"p{i}", *threads))
        loads.append(load)
    return system([core(f"c{k}") for k in range(m)], processes), loads


def brute_force(result_loads, n, m):
    """The least maximum load over every assignment whose cores stay within 100 %."""
    best = None
    for assignment in itertools.product(range(m), repeat=n):
        loads = [Fraction(0)] * m
        for p, c in enumerate(assignment):
            loads[c] += result_loads[p]
        if max(loads) <= 1 and (best is None or max(loads) < best):
            best = max(loads)
    return best


@pytest.mark.parametrize("seed", range(12))
def test_exact_search_is_optimal_on_small_problems(seed):
    rng = random.Random(seed)
    n, m = rng.randint(2, 6), rng.randint(2, 3)
    root, loads = random_problem(rng, n, m)
    # harmonic periods: rate monotonic schedules any load up to 100 %, so the load check is
    # the only constraint and brute force over the loads gives the optimum
    result = search_deployment(root)
    optimum = brute_force(loads, n, m)
    if optimum is None:
        assert not result.feasible and result.method == "exact" and not result.optimal
        return
    assert result.method == "exact" and result.optimal and result.feasible
    assert result.max_load == optimum
    assert {p.process: p.load for p in result.placements} == {
        f"d_i_Instance.p{i}": x for i, x in enumerate(loads)
    }


@pytest.mark.parametrize("seed", range(4))
def test_heuristic_beyond_the_node_limit(seed):
    rng = random.Random(100 + seed)
    n, m = 40, 6
    processes = [process(f"p{i}", thread("t", 1000, rng.randint(10, 250))) for i in range(n)]
    root = system([core(f"c{k}") for k in range(m)], processes)
    result = search_deployment(root, node_limit=500)
    assert result.method == "heuristic" and not result.optimal
    loads = [p.load for p in result.placements]
    assert len(loads) == n and result.feasible
    lower = max(sum(loads) / m, max(loads))
    assert result.max_load <= Fraction(4, 3) * lower  # LPT's guarantee, kept by the local search
    assert all(c.load <= 1 for c in result.cores)


def test_schedulability_rejects_what_the_load_accepts():
    # U = 2/5 + 4/7 = 0.97 fits one core, but rate monotonic misses: R2 = 4 + 2 x 2 = 8 > 7
    root = system([core("only")], [process("a", thread("t", 5, 2)), process("b", thread("t", 7, 4))])
    assert search_deployment(root, schedulability=False).feasible
    result = search_deployment(root)
    assert not result.feasible and not result.ok
    assert any("no candidate processor" in d.message for d in result.diagnostics)
    # EDF schedules it
    root = system(
        [core("only", scheduler="EDF")], [process("a", thread("t", 5, 2)), process("b", thread("t", 7, 4))]
    )
    edf = search_deployment(root)
    assert edf.feasible and edf.cores[0].schedulable is True


def test_mips_scaling_and_budgets():
    ws = new("AadlModel", name="ws")
    big = new(
        "ComponentType",
        name="Big",
        category="processor",
        ownedPropertyAssociations=[pa("SEI::MIPSCapacity", num(2000.0, "MIPS"))],
    )
    ws.units.append(new("AadlPackage", name="Hw", classifiers=[big]))
    measured = thread(
        "work",
        10_000,
        5_000,
        props=[pa("Timing_Properties::Reference_Processor", new("ClassifierValue", classifier="Hw::Big"))],
    )
    root = system(
        [core("little", 1000), core("large", 2000)],
        [process("node", measured), process("budgeted", thread("idle", 10_000, 1), budget=100)],
    )
    root.componentInstances[2].componentInstances[0].ownedPropertyAssociations.pop(1)  # no CET
    ws.instances.append(root)
    result = search_deployment(ws, schedulability=False)
    # measured at 50 % of 2000 MIPS: 1000 MIPS, 100 % of the little core, 50 % of the large one
    assert result.binding("d_i_Instance.node") == "d_i_Instance.board.large"
    assert result.binding("d_i_Instance.budgeted") == "d_i_Instance.board.little"
    loads = {c.path.rpartition(".")[2]: c.load for c in result.cores}
    assert loads == {"little": Fraction(1, 10), "large": Fraction(1, 2)}


def test_allowed_cores_and_associations():
    root = system(
        [core("c1"), core("c2"), core("c3")],
        [process("a", thread("t", 100, 10)), process("b", thread("t", 100, 10))],
    )
    result = search_deployment(root, allowed={"a": ["board.c3"], "d_i_Instance.b": ["board.c3"]})
    assert {p.processor for p in result.placements} == {"d_i_Instance.board.c3"}
    assert result.associations() == [
        "Actual_Processor_Binding => (reference (board.c3)) applies to a;",
        "Actual_Processor_Binding => (reference (board.c3)) applies to b;",
    ]
    data = result.as_dict()
    assert data["max_load_percent"] == 20 and data["bindings"][0]["process"] == "d_i_Instance.a"


def test_nothing_fits():
    root = system([core("c1"), core("c2")], [process("heavy", thread("t", 100, 150))])
    result = search_deployment(root)
    assert not result.feasible and result.unplaced == ("d_i_Instance.heavy",)
    assert any(d.location.path == "d_i_Instance.heavy" for d in result.diagnostics)


def test_bad_arguments():
    root = system([core("c1")], [process("a", thread("t", 100, 10))])
    with pytest.raises(ModelError):
        search_deployment(root, processes=["board.c1"])
    with pytest.raises(ModelError):
        search_deployment(root, processors=["nothing"])
    with pytest.raises(ModelError):
        search_deployment(root, allowed={"a": ["board.c9"]})
    empty = system([], [process("a", thread("t", 100, 10))])
    with pytest.raises(ModelError, match="no processor"):
        search_deployment(empty)

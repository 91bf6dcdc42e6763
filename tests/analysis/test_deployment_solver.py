"""The deployment constraint solver (rosaadl.analysis.deployment_solver and its neighbours): its
optimum equals the exact search's on every small instance of test_deployment, the lazy
schedulability cuts, the baselines, keeping N bindings, determinism, the explanations of
infeasible models, and a scale model."""

from __future__ import annotations

import random
from fractions import Fraction

import pytest
from instance_builders import num, pa, ref
from test_deployment import core, process, random_problem, system, thread

from rosaadl import model
from rosaadl.analysis.deployment import search_deployment
from rosaadl.analysis.deployment_baselines import (
    best_fit_decreasing,
    first_fit_decreasing,
    worst_fit_decreasing,
)
from rosaadl.analysis.deployment_infeasibility import explain_infeasibility
from rosaadl.analysis.deployment_problem import deployment_problem
from rosaadl.analysis.deployment_proposal import propose_deployment
from rosaadl.analysis.deployment_solver import solve_deployment

new = model.new


def solved(root, **options):
    problem = deployment_problem(root, **{k: v for k, v in options.items() if k != "deterministic"})
    return problem, solve_deployment(problem, time_limit=5, deterministic=True)


def compare_with_exact(root, **options):
    """The solver's highest core load equals the exact search's (or both find no binding)."""
    exact = search_deployment(root, **options)
    assert exact.method == "exact"
    problem, outcome = solved(root, **options)
    assert outcome.exact_scale  # the loads scaled by the LCM of their denominators: no rounding
    if not exact.feasible:
        assert outcome.status == "infeasible" and not outcome.bindings
        return problem, outcome
    assert outcome.status == "optimal"
    best = outcome.best
    assert best.evaluation.feasible
    assert best.evaluation.max_load == exact.max_load
    assert best.objectives[0].value == exact.max_load * 100 == best.objectives[0].bound
    return problem, outcome


@pytest.mark.parametrize("seed", range(12))
def test_solver_optimum_equals_the_exact_search_on_test_deployments_instances(seed):
    rng = random.Random(seed)  # the instances of test_exact_search_is_optimal_on_small_problems
    n, m = rng.randint(2, 6), rng.randint(2, 3)
    root, _loads = random_problem(rng, n, m)
    compare_with_exact(root)


@pytest.mark.parametrize("seed", range(500, 510))
def test_solver_optimum_equals_the_exact_search_with_response_time_cuts(seed):
    # non-harmonic periods: rate monotonic refuses some loads under 100 %, which only the lazy
    # response-time cuts see (seed 502 is infeasible by them alone, after 60 cuts)
    rng = random.Random(seed)
    n, m = rng.randint(6, 9), rng.randint(2, 3)
    processes = []
    for i in range(n):
        period = rng.choice([5, 7, 11, 13]) * 100
        processes.append(process(f"p{i}", thread("t", period, rng.randint(period // 10, period * 3 // 10))))
    root = system([core(f"c{k}") for k in range(m)], processes)
    problem, outcome = compare_with_exact(root)
    if outcome.best is not None:
        members = problem.members(outcome.best.assignment)
        assert all(problem.schedulable(c, inside) for c, inside in enumerate(members))
    else:
        assert outcome.cuts > 0


def test_solver_on_the_other_instances_of_test_deployment():
    # test_schedulability_rejects_what_the_load_accepts: the cut makes it infeasible
    root = system([core("only")], [process("a", thread("t", 5, 2)), process("b", thread("t", 7, 4))])
    problem, outcome = compare_with_exact(root)
    assert outcome.cuts >= 1
    compare_with_exact(root, schedulability=False)
    # test_allowed_cores_and_associations
    root = system(
        [core("c1"), core("c2"), core("c3")],
        [process("a", thread("t", 100, 10)), process("b", thread("t", 100, 10))],
    )
    compare_with_exact(root, allowed={"a": ["board.c3"], "d_i_Instance.b": ["board.c3"]})
    # test_nothing_fits
    compare_with_exact(system([core("c1"), core("c2")], [process("heavy", thread("t", 100, 150))]))


def test_a_resolution_of_a_millionth_when_the_exact_scale_is_too_large():
    # periods of large coprime values: the LCM of the denominators exceeds 10^9
    primes = [100_003, 100_019, 100_043, 100_049]
    root = system(
        [core("c0"), core("c1")], [process(f"p{i}", thread("t", p, p // 4)) for i, p in enumerate(primes)]
    )
    problem, outcome = solved(root)
    assert not outcome.exact_scale and outcome.scale == 10**6
    exact = search_deployment(root)
    # the rounded model's optimum is within the rounding (fewer than one millionth of a core per
    # unit) of the exact optimum; the bound, rounded down, stays a true lower bound
    rounding = Fraction(len(primes), 10**6)
    assert exact.max_load <= outcome.best.evaluation.max_load <= exact.max_load + rounding
    bound = outcome.best.objectives[0].bound / 100
    assert exact.max_load - rounding <= bound <= exact.max_load


def test_baselines_first_fit_and_best_fit_decreasing():
    loads = [50, 40, 30, 30, 20]  # percent of a core
    root = system(
        [core("c0"), core("c1"), core("c2")],
        [process(f"p{i}", thread("t", 1000, 10 * x)) for i, x in enumerate(loads)],
    )
    problem = deployment_problem(root, schedulability=False)
    first = first_fit_decreasing(problem)
    best = best_fit_decreasing(problem)
    worst = worst_fit_decreasing(problem)
    # FFD and BFD: 50+40 on c0 (30 would make it 120), 30+30+20 on c1, nothing on c2
    assert [float(x) for x in first.evaluation.loads] == [0.9, 0.8, 0.0]
    assert best.evaluation.loads == first.evaluation.loads
    # WFD: 50 | 40+20 | 30+30; the optimum is the same 60 %
    assert [float(x) for x in worst.evaluation.loads] == [0.5, 0.6, 0.6]
    outcome = solve_deployment(problem, deterministic=True, time_limit=5)
    assert outcome.best.evaluation.max_load == Fraction(3, 5) and outcome.status == "optimal"


def test_keep_n_distinct_bindings_and_determinism():
    rng = random.Random(7)
    root, _ = random_problem(rng, 6, 3)
    problem = deployment_problem(root)
    first = solve_deployment(problem, keep=3, time_limit=6, deterministic=True)
    again = solve_deployment(deployment_problem(root), keep=3, time_limit=6, deterministic=True)
    assert len(first.bindings) == 3
    assert len({b.assignment for b in first.bindings}) == 3
    keys = [(b.evaluation.max_load, b.evaluation.bus_kbyteps, b.evaluation.moves) for b in first.bindings]
    assert keys[0] == min(keys)
    assert [b.assignment for b in first.bindings] == [b.assignment for b in again.bindings]


def _board(name, cores, memory_mbyte=None):
    board = new("ComponentInstance", name=name, category="system")
    board.componentInstances.extend(cores)
    if memory_mbyte is not None:
        ram = new("ComponentInstance", name="ram", category="memory")
        ram.ownedPropertyAssociations.append(pa("Memory_Properties::Memory_Size", num(memory_mbyte, "MByte")))
        board.componentInstances.append(ram)
    return board


def _boards_system(boards, processes, bus_kbyteps=None):
    root = new("SystemInstance", name="r_i_Instance", category="system")
    root.componentInstances.extend(boards)
    root.componentInstances.extend(processes)
    if bus_kbyteps is not None:
        bus = new("ComponentInstance", name="net", category="bus")
        bus.ownedPropertyAssociations.append(
            pa("SEI::BandWidthCapacity", num(float(bus_kbyteps), "KBytesps"))
        )
        root.componentInstances.append(bus)
    return root


def _topic(root, src, dst, kbyte):
    ports = []
    for owner, direction in ((src, "out"), (dst, "in")):
        port = new(
            "FeatureInstance", name=direction, feature=direction, category="data port", direction=direction
        )
        port.ownedPropertyAssociations.append(pa("Memory_Properties::Data_Size", num(kbyte, "KByte")))
        owner.componentInstances[0].featureInstances.append(port)
        ports.append(port)
    root.connectionInstances.append(
        new(
            "ConnectionInstance",
            name=f"{src.name}->{dst.name}",
            kind="portConnection",
            source=ports[0],
            destination=ports[1],
        )
    )


def test_bus_load_is_minimised_then_moves():
    # two talking nodes fit together on either board: the solver keeps them on one board
    a = process("a", thread("t", 1000, 300))
    b = process("b", thread("t", 1000, 300))
    c = process("c", thread("t", 1000, 300))
    boards = [_board("left", [core("c0"), core("c1")]), _board("right", [core("c0"), core("c1")])]
    root = _boards_system(boards, [a, b, c], bus_kbyteps=10_000)
    _topic(root, a, b, 10)  # 10 KByte at 1 kHz: 10 000 KByte/s
    a.ownedPropertyAssociations.append(
        pa("Deployment_Properties::Actual_Processor_Binding", ref(boards[1].componentInstances[0]))
    )
    problem = deployment_problem(root)
    assert problem.traffic == [(0, 1, Fraction(10_000))] and problem.bus_capacity == 10_000
    outcome = solve_deployment(problem, deterministic=True, time_limit=5)
    best = outcome.best
    assert best.evaluation.max_load == Fraction(3, 10) and best.evaluation.bus_kbyteps == 0
    assert best.evaluation.moves == 0  # a stays where it is bound
    assert outcome.status == "optimal"
    names = [o.name for o in best.objectives]
    assert names == ["max_core_load", "bus_load", "longest_chain_latency", "moves"]
    latency = best.objectives[2].as_dict()
    # the chain a.t -> b.t on one board: the two execution times, no transmission
    assert latency["value"] == 600 == latency["bound"] and latency["unit"] == "us"
    assert "executor analysis" in latency["note"]


def test_allowed_processor_binding_is_honoured():
    pinned = process("driver", thread("t", 1000, 100))
    boards = [_board("left", [core("c0")]), _board("right", [core("c0")])]
    pinned.ownedPropertyAssociations.append(
        pa("Deployment_Properties::Allowed_Processor_Binding", ref(boards[1]))
    )
    root = _boards_system(boards, [pinned, process("other", thread("t", 1000, 100))])
    problem = deployment_problem(root)
    assert problem.allowed[0] == [1]
    outcome = solve_deployment(problem, deterministic=True, time_limit=5)
    assert outcome.best.assignment[0] == 1


def test_thread_granularity():
    root = system([core("c0"), core("c1")], [process("a", thread("t1", 1000, 400), thread("t2", 1000, 400))])
    by_process = solve_deployment(deployment_problem(root), deterministic=True)
    assert by_process.best.evaluation.max_load == Fraction(4, 5)
    by_thread = propose_deployment(root, granularity="thread", deterministic=True, time_limit=5)
    assert [u for u, _c in by_thread.binding()] == ["d_i_Instance.a.t1", "d_i_Instance.a.t2"]
    assert by_thread.outcome.best.evaluation.max_load == Fraction(2, 5)


# ----------------------------------------------------------------------------- infeasible


def test_a_process_that_fits_no_core_is_named_with_its_rate_and_load():
    heavy = process("tracker", thread("t", 100_000, 111_100))  # 10 Hz, 111.1 ms
    cores = [core("c0"), core("c1")]
    for c in cores:
        c.classifier = "Exynos::ARM_A15"
    proposal = propose_deployment(system(cores, [heavy]), deterministic=True, time_limit=2)
    assert not proposal.feasible and proposal.outcome.status == "infeasible"
    (reason,) = proposal.explanation
    assert reason.constraint == "cpu"
    assert reason.message == "tracker at 10 Hz needs 111.1 % of any Exynos::ARM_A15 core"
    data = proposal.as_dict()
    assert data["ok"] is False and data["explanation"][0]["path"] == "d_i_Instance.tracker"


def test_pinned_units_that_overload_their_core():
    root = system(
        [core("c1"), core("c2")],
        [process("a", thread("t", 100, 60)), process("b", thread("t", 100, 60))],
    )
    problem = deployment_problem(root, allowed={"a": ["board.c1"], "b": ["board.c1"]})
    (reason,) = explain_infeasibility(problem)
    assert reason.constraint == "pinned" and reason.path == "d_i_Instance.board.c1"
    assert "a, b" in reason.message and "120.0 %" in reason.message


def test_pinned_units_not_schedulable_together():
    root = system([core("only")], [process("a", thread("t", 5, 2)), process("b", thread("t", 7, 4))])
    (reason,) = explain_infeasibility(deployment_problem(root))
    assert reason.constraint == "pinned" and "not schedulable together" in reason.message


def test_memory_and_total_capacity():
    big = process("big", thread("t", 1000, 100))
    big.ownedPropertyAssociations.append(pa("SEI::RAMBudget", num(300, "MByte")))
    root = _boards_system([_board("b0", [core("c0")], memory_mbyte=256)], [big])
    (reason,) = explain_infeasibility(deployment_problem(root))
    assert reason.constraint == "memory" and "more than the memory" in reason.message
    many = [process(f"p{i}", thread("t", 100, 70)) for i in range(3)]
    (reason,) = explain_infeasibility(deployment_problem(system([core("c0"), core("c1")], many)))
    assert reason.constraint == "cpu" and "210.0 %" in reason.message


def test_bus_capacity_between_pinned_boards():
    a = process("a", thread("t", 1000, 100))
    b = process("b", thread("t", 1000, 100))
    boards = [_board("left", [core("c0")]), _board("right", [core("c0")])]
    a.ownedPropertyAssociations.append(pa("Deployment_Properties::Allowed_Processor_Binding", ref(boards[0])))
    b.ownedPropertyAssociations.append(pa("Deployment_Properties::Allowed_Processor_Binding", ref(boards[1])))
    root = _boards_system(boards, [a, b], bus_kbyteps=5_000)
    _topic(root, a, b, 10)
    (reason,) = explain_infeasibility(deployment_problem(root))
    assert reason.constraint == "bus" and "10000 KByte/s" in reason.message


# ----------------------------------------------------------------------------- scale


def test_a_small_scale_model_against_the_baselines():
    from benchmarks.generators.deployment import robot_to_deploy

    root = robot_to_deploy(6, 24, 2, 4, seed=3)
    proposal = propose_deployment(root, granularity="thread", time_limit=1.5, deterministic=True)
    assert proposal.feasible
    best = proposal.outcome.best
    assert best.evaluation.feasible
    ffd, bfd, _wfd = proposal.baselines
    assert best.evaluation.max_load <= min(ffd.evaluation.max_load, bfd.evaluation.max_load)
    gap = best.objectives[0].gap_percent
    assert gap is not None and gap <= 5
    data = proposal.as_dict()
    assert set(data["baseline"]) == {"first_fit", "best_fit", "worst_fit"}
    assert len(data["binding"]) == 24

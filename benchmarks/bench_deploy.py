"""Deployment benchmark: the CP-SAT proposal beside first-fit and best-fit decreasing, at scale.

Side by side in one run, on each scale model of the deployment issue
(``benchmarks.generators.deployment``: 30 nodes / 300 threads on 3 boards / 16 cores, and
100 nodes / 1 000 threads on 6 boards / 48 cores, bound thread by thread):

  * the proposal: reading the problem, the worst-fit starting bindings and CP-SAT limited by its
    deterministic time (``--work``, 4 by default: the same search on any machine and load, where
    a wall-clock limit would give a loaded machine less search); goal: a feasible proposal in at
    most 10 s of CPU (the harness judges CPU time, which a shared machine does not stretch);
  * the optimality gap of its highest core load (value against the solver's lower bound); goal
    at most 1 % on the first model, 5 % on the second;
  * its highest core load against first-fit decreasing and best-fit decreasing on the same model
    (ratio proposal / baseline; a baseline that leaves units unplaced or breaks a constraint says
    so in the note);
  * the bus load and the moves from the current binding, in the notes;
  * the same model with its ring of topics left open (one cause-effect chain through every
    node, so the longest chain latency objective has work to do): the proposal's time and the
    gap of the longest chain latency.

Usage: ``python -m benchmarks.bench_deploy [--budget S] [--work W] [--only 30|100]``.
"""

from __future__ import annotations

import argparse
import time

from benchmarks.generators.deployment import SCALE_MODELS, robot_to_deploy
from benchmarks.harness import Goal, Report
from rosaadl.analysis.deployment_baselines import (
    best_fit_decreasing,
    first_fit_decreasing,
    worst_fit_decreasing,
)
from rosaadl.analysis.deployment_problem import deployment_problem
from rosaadl.analysis.deployment_solver import solve_deployment

__all__ = ["main"]

GAP_GOALS = (1.0, 5.0)


def _clocks() -> tuple[float, float]:
    return time.process_time(), time.perf_counter()


def _text(value) -> str:
    return "-" if value is None else f"{float(value):g}"


def _baseline_note(baseline, seconds: float) -> str:
    e = baseline.evaluation
    state = (
        "passes"
        if e.feasible
        else f"FAILS: {e.violations[0]}" + (f" (+{len(e.violations) - 1})" if len(e.violations) > 1 else "")
    )
    load = float(e.max_load * 100)
    return f"{baseline.name} {load:.2f} % in {seconds:.2f} s, bus {float(e.bus_kbyteps):g} KB/s; {state}"


def _solve(root, args) -> tuple:
    """(problem, outcome, CPU seconds, wall seconds, wall seconds to read and start)."""
    cpu0, wall0 = _clocks()
    problem = deployment_problem(root, granularity="thread")
    hints = [
        worst_fit_decreasing(problem, keep_boards=True).assignment,
        worst_fit_decreasing(problem).assignment,
    ]
    wall1 = time.perf_counter()
    outcome = solve_deployment(problem, time_limit=args.work, hints=hints, deterministic=True)
    cpu2, wall2 = _clocks()
    return problem, outcome, cpu2 - cpu0, wall2 - wall0, wall1 - wall0


def _proposal(report: Report, name: str, args, outcome, cpu: float, wall: float, start: float) -> None:
    best = outcome.best
    feasible = best is not None and best.evaluation.feasible
    report.add(
        f"{name}: proposal",
        cpu,
        "s",
        wall=wall,
        goal=Goal(args.budget, says=f"a feasible proposal in <= {args.budget:g} s"),
        note=(
            f"{outcome.status}, read + start {start:.2f} s, CP-SAT {wall - start:.2f} s, "
            f"{outcome.solves} solves, {outcome.cuts} cuts" + ("" if feasible else "; NO FEASIBLE BINDING")
        ),
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_deploy", description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=10.0, help="seconds for the whole proposal")
    parser.add_argument("--only", choices=["30", "100"], default=None)
    parser.add_argument(
        "--work", type=float, default=4.0, help="CP-SAT's deterministic time (its own count of work)"
    )
    args = parser.parse_args(argv)
    report = Report("deploy")
    for index, (name, (nodes, threads, boards, cores)) in enumerate(SCALE_MODELS.items()):
        if args.only is not None and not name.startswith(args.only + " "):
            continue
        problem, outcome, cpu, wall, start = _solve(robot_to_deploy(nodes, threads, boards, cores), args)
        baselines = []
        for pack in (first_fit_decreasing, best_fit_decreasing):
            began = time.perf_counter()
            baselines.append((pack(problem), time.perf_counter() - began))
        _proposal(report, name, args, outcome, cpu, wall, start)
        best = outcome.best
        if best is None:
            continue
        top = best.objectives[0]
        report.add(
            f"{name}: gap of the highest core load",
            top.gap_percent,
            "%",
            goal=Goal(GAP_GOALS[index], says=f"gap <= {GAP_GOALS[index]:g} %"),
            note=f"{float(top.value):.3f} % against the bound {float(top.bound):.3f} %"
            if top.bound is not None
            else "",
        )
        value = float(best.evaluation.max_load * 100)
        bus = next(o for o in best.objectives if o.name == "bus_load")
        moves = next(o for o in best.objectives if o.name == "moves")
        report.add(
            f"{name}: bus load, moves",
            float(bus.value),
            "KB/s",
            note=f"bus bound {_text(bus.bound)}, moves {moves.value} (bound {_text(moves.bound)}) "
            f"of {len(problem.units)} units",
            detail=True,
        )
        for baseline, seconds in baselines:
            report.add(
                f"{name}: highest core load vs {baseline.name.replace('_', '-')} decreasing",
                value,
                "%",
                reference=float(baseline.evaluation.max_load * 100),
                against=baseline.name,
                note=_baseline_note(baseline, seconds),
            )
        chained = f"{name}, one open chain"
        root = robot_to_deploy(nodes, threads, boards, cores, open_chain=True)
        problem, outcome, cpu, wall, start = _solve(root, args)
        _proposal(report, chained, args, outcome, cpu, wall, start)
        if outcome.best is not None:
            chain = next(o for o in outcome.best.objectives if o.name == "longest_chain_latency")
            report.add(
                f"{chained}: gap of the longest chain latency",
                chain.gap_percent,
                "%",
                note=f"{_text(chain.value)} us against the bound {_text(chain.bound)} us "
                f"({len(problem.chains)} chain of {len(problem.chains[0].links) + 1} callbacks)",
            )
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

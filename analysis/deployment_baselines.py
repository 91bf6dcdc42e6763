"""First-fit decreasing and best-fit decreasing: the bin-packing baselines a proposal is compared to.

OSATE's binpacker and Cheddar's partitioning tools are first-fit style heuristics with no bound on
their distance from the best binding; these two are the textbook forms over a
:class:`~rosaadl.analysis.deployment_problem.DeploymentProblem`: the units by decreasing load (the
largest load they would put on any of their cores; ties in model order), each on the first of its
cores in model order where it fits (first fit), or on the one it leaves the least room on (best
fit; ties to the first). A unit *fits* a core when the core stays at most 100 % loaded and
schedulable, and the board's memory holds it; the bus is not looked at (neither heuristic knows
about it), so a baseline may overload it, which its evaluation then says.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.deployment_problem import DeploymentProblem, Evaluation

__all__ = ["Baseline", "best_fit_decreasing", "decreasing_order", "first_fit_decreasing"]


@dataclass(frozen=True)
class Baseline:
    """A heuristic's binding (core index per unit, -1 when it fits nowhere) and its evaluation."""

    name: str
    assignment: tuple[int, ...]
    evaluation: Evaluation

    @property
    def feasible(self) -> bool:
        return self.evaluation.feasible

    def as_dict(self, problem: DeploymentProblem) -> dict[str, Any]:
        unplaced = [problem.units[u].path for u, c in enumerate(self.assignment) if c < 0]
        return {
            "feasible": self.feasible,
            "max_load_percent": float(self.evaluation.max_load * 100),
            "bus_kbyteps": float(self.evaluation.bus_kbyteps),
            "moves": self.evaluation.moves,
            "unplaced": unplaced,
        }


def decreasing_order(problem: DeploymentProblem) -> list[int]:
    """Units by decreasing largest load over their candidate cores (ties: model order)."""
    return sorted(
        range(len(problem.units)),
        key=lambda u: (
            -max((problem.load[u][c] or Fraction(0) for c in problem.candidates(u)), default=0),
            u,
        ),
    )


def _pack(problem: DeploymentProblem, best: bool) -> tuple[int, ...]:
    assignment = [-1] * len(problem.units)
    loads = [Fraction(0)] * len(problem.cores)
    members: list[list[int]] = [[] for _ in problem.cores]
    memory: dict[str, Fraction] = {}
    for u in decreasing_order(problem):
        fitting = []
        for c in problem.candidates(u):
            load = loads[c] + (problem.load[u][c] or Fraction(0))
            if load > 1:
                continue
            board = problem.cores[c].board
            capacity = problem.board_memory.get(board)
            if (
                capacity is not None
                and memory.get(board, Fraction(0)) + problem.units[u].memory_kbyte > capacity
            ):
                continue
            if not problem.schedulable(c, tuple(sorted([*members[c], u]))):
                continue
            fitting.append((load, c))
            if not best:
                break
        if not fitting:
            continue
        # best fit: the least room left, i.e. the highest load after placing (ties: the first core)
        _load, chosen = max(fitting, key=lambda item: (item[0], -item[1])) if best else fitting[0]
        assignment[u] = chosen
        loads[chosen] += problem.load[u][chosen] or Fraction(0)
        members[chosen].append(u)
        board = problem.cores[chosen].board
        memory[board] = memory.get(board, Fraction(0)) + problem.units[u].memory_kbyte
    return tuple(assignment)


def first_fit_decreasing(problem: DeploymentProblem) -> Baseline:
    """First-fit decreasing over the problem's cores in model order."""
    assignment = _pack(problem, best=False)
    return Baseline("first_fit", assignment, problem.evaluate(assignment))


def best_fit_decreasing(problem: DeploymentProblem) -> Baseline:
    """Best-fit decreasing: each unit on the fitting core it leaves the least room on."""
    assignment = _pack(problem, best=True)
    return Baseline("best_fit", assignment, problem.evaluate(assignment))

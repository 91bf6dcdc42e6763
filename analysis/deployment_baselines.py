"""First-fit decreasing and best-fit decreasing: the bin-packing baselines a proposal is compared to.

OSATE's binpacker and Cheddar's partitioning tools are first-fit style heuristics with no bound on
their distance from the best binding; these two are the textbook forms over a
:class:`~rosaadl.analysis.deployment_problem.DeploymentProblem`: the units by decreasing load (the
largest load they would put on any of their cores; ties in model order), each on the first of its
cores in model order where it fits (first fit), or on the one it leaves the least room on (best
fit; ties to the first). A unit *fits* a core when the core stays at most 100 % loaded and
schedulable, and the board's memory holds it; the bus is not looked at (neither heuristic knows
about it), so a baseline may overload it, which its evaluation then says.

Worst-fit decreasing balances the loads: the units allowed on fewer cores first, then the units
with topics in a breadth-first walk of the topic graph, then the others by decreasing load; each
on the fitting core left the least loaded, the boards of its placed neighbours first when the
bus has a capacity (which it keeps as the units are placed), and with ``keep_boards`` the board
of its current binding before all. It is the constraint solver's starting point and is reported
beside the other two.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.deployment_problem import DeploymentProblem, Evaluation

__all__ = [
    "Baseline",
    "best_fit_decreasing",
    "decreasing_order",
    "first_fit_decreasing",
    "worst_fit_decreasing",
]


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


def _pack(problem: DeploymentProblem, rule: str, keep_boards: bool = False) -> tuple[int, ...]:
    """Place the units in decreasing order by ``rule``: first, best or worst (bus-aware) fit;
    ``keep_boards``: worst fit trying the board of each unit's current binding first."""
    current = [
        {problem.cores[c].board for c in problem.current[u]} if keep_boards else set()
        for u in range(len(problem.units))
    ]
    assignment = [-1] * len(problem.units)
    loads = [Fraction(0)] * len(problem.cores)
    members: list[list[int]] = [[] for _ in problem.cores]
    memory: dict[str, Fraction] = {}
    bus = Fraction(0)
    neighbours: dict[int, list[tuple[int, Fraction]]] = {}
    for u, v, rate in problem.traffic:
        neighbours.setdefault(u, []).append((v, rate))
        neighbours.setdefault(v, []).append((u, rate))
    order = decreasing_order(problem)
    if rule == "worst":  # the units that may take fewer cores first, then those that talk
        walk = _breadth_first(neighbours, order)
        order.sort(key=lambda u: (len(problem.candidates(u)) == len(problem.cores), walk.get(u, len(walk))))
    for u in order:
        row = problem.load[u]
        candidates = problem.candidates(u)
        if rule == "worst":
            # the boards of the unit's placed neighbours first when the bus has a capacity, then
            # the least loaded
            crowded = problem.bus_capacity is not None
            candidates = sorted(
                candidates,
                key=lambda c: (
                    bool(current[u]) and problem.cores[c].board not in current[u],
                    crowded
                    and _crossing(problem, assignment, neighbours.get(u, []), problem.cores[c].board) > 0,
                    loads[c] + (row[c] or 0),
                    c,
                ),
            )
        fitting = []
        for c in candidates:
            load = loads[c] + (row[c] or Fraction(0))
            if load > 1:
                continue
            board = problem.cores[c].board
            capacity = problem.board_memory.get(board)
            if (
                capacity is not None
                and memory.get(board, Fraction(0)) + problem.units[u].memory_kbyte > capacity
            ):
                continue
            if rule == "worst" and problem.bus_capacity is not None:
                added = _crossing(problem, assignment, neighbours.get(u, []), board)
                if bus + added > problem.bus_capacity:
                    continue
            if not problem.schedulable(c, tuple(sorted([*members[c], u]))):
                continue
            fitting.append((load, c))
            if rule != "best":
                break
        if not fitting:
            continue
        # best fit: the least room left, i.e. the highest load after placing (ties: the first core)
        _load, chosen = max(fitting, key=lambda item: (item[0], -item[1])) if rule == "best" else fitting[0]
        bus += _crossing(problem, assignment, neighbours.get(u, []), problem.cores[chosen].board)
        assignment[u] = chosen
        loads[chosen] += row[chosen] or Fraction(0)
        members[chosen].append(u)
        board = problem.cores[chosen].board
        memory[board] = memory.get(board, Fraction(0)) + problem.units[u].memory_kbyte
    return tuple(assignment)


def _breadth_first(neighbours: dict[int, list[tuple[int, Fraction]]], order: list[int]) -> dict[int, int]:
    """The position of each unit with topics in a breadth-first walk of the topic graph, each
    component from its first unit in ``order``: a unit then mostly has a placed neighbour."""
    position: dict[int, int] = {}
    for start in order:
        if start in position or start not in neighbours:
            continue
        position[start] = len(position)
        queue = [start]
        while queue:
            u = queue.pop(0)
            for v, _rate in neighbours[u]:
                if v not in position:
                    position[v] = len(position)
                    queue.append(v)
    return position


def _crossing(
    problem: DeploymentProblem, assignment: list[int], neighbours: list[tuple[int, Fraction]], board: str
) -> Fraction:
    """The traffic a unit placed on ``board`` adds to the bus, with its neighbours placed so far."""
    return sum(
        (
            rate
            for v, rate in neighbours
            if assignment[v] >= 0 and problem.cores[assignment[v]].board != board
        ),
        Fraction(0),
    )


def first_fit_decreasing(problem: DeploymentProblem) -> Baseline:
    """First-fit decreasing over the problem's cores in model order."""
    assignment = _pack(problem, "first")
    return Baseline("first_fit", assignment, problem.evaluate(assignment))


def best_fit_decreasing(problem: DeploymentProblem) -> Baseline:
    """Best-fit decreasing: each unit on the fitting core it leaves the least room on."""
    assignment = _pack(problem, "best")
    return Baseline("best_fit", assignment, problem.evaluate(assignment))


def worst_fit_decreasing(problem: DeploymentProblem, keep_boards: bool = False) -> Baseline:
    """Worst-fit decreasing: each unit on the fitting core left the least loaded, keeping the bus
    within its capacity as the units are placed; with ``keep_boards``, on the board of its current
    binding when one fits there (the current binding rebalanced inside its boards)."""
    assignment = _pack(problem, "worst", keep_boards)
    return Baseline("worst_fit", assignment, problem.evaluate(assignment))

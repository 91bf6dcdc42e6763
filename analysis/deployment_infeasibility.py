"""Why a deployment problem has no binding: which constraint set cannot be met, in the model's words.

:func:`explain_infeasibility` looks, in this order, for a cause one can read off the problem:

1. a unit with no candidate core (``Allowed_Processor_Binding`` or the caller's list leaves it
   none, or it demands MIPS of cores that give none); a unit pinned to two boards (by the
   devices it talks to, or a device and ``Allowed_Processor_Binding``): "node.driver is pinned
   to left by device left.camera and to right by device right.lidar: no core is both";
2. a unit that alone overloads every core it may take: "node.tracker at 30 Hz needs 111.1 % of
   any Exynos_5422::ARM_A15 core" (per core classifier, the least load there);
3. a unit not schedulable alone on any core it fits;
4. units pinned to one core (a single candidate) that together overload it or are not
   schedulable there;
5. memory: a unit larger than every board it may go to, or the units pinned to a board larger
   than its memory;
6. the CPU capacity in all: the least load of every unit, summed, against the cores;
7. the bus: the topics between units that cannot share a board, against its capacity.

When none of them holds, the constraint sets are dropped one at a time (schedulability, memory,
bus) and the problem solved again, briefly: the sets whose removal makes a binding exist are
named ("the CPU load and schedulability constraints together: without schedulability a binding
exists").
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

from rosaadl.analysis.deployment_problem import DeploymentProblem

__all__ = ["Infeasibility", "explain_infeasibility"]


@dataclass(frozen=True)
class Infeasibility:
    """One reason: the constraint set (cpu, schedulability, pinned, memory, bus, candidates,
    combined), a sentence, and the element it is about."""

    constraint: str
    message: str
    path: str

    def as_dict(self) -> dict[str, Any]:
        return {"constraint": self.constraint, "message": self.message, "path": self.path}

    def __str__(self) -> str:
        return f"{self.path}: {self.message}"


def _percent(value: Fraction) -> str:
    return f"{float(value * 100):.1f} %"


def _short(problem: DeploymentProblem, path: str) -> str:
    return path.removeprefix(problem.root + ".")


def _rate(problem: DeploymentProblem, unit: int) -> str:
    """`` at 30 Hz`` when the unit's periodic threads share one rate, else nothing."""
    periods = {t.period_us for t in problem.units[unit].threads if t.period_us}
    if len(periods) != 1:
        return ""
    hertz = Fraction(1_000_000) / periods.pop()
    return f" at {float(hertz):g} Hz"


def _single_unit(problem: DeploymentProblem) -> list[Infeasibility]:
    out = []
    for u, unit in enumerate(problem.units):
        name = _short(problem, unit.path)
        if not problem.allowed[u]:
            pins = [p for p in problem.pins if p.unit == u]
            if any(p.device for p in pins):
                held = " and ".join(
                    f"to {_short(problem, p.board)} by "
                    + (f"device {_short(problem, p.device)}" if p.device else p.by)
                    for p in pins
                )
                out.append(Infeasibility("pinned", f"{name} is pinned {held}: no core is both", unit.path))
                continue
            held = [f"{p.by} ({_short(problem, p.board)})" for p in pins]
            why = (
                f": {held[0]} names no candidate processor"
                if len(held) == 1 and not pins[0].cores
                else f": {' and '.join(held)} leave no core in common"
                if held
                else " (Allowed_Processor_Binding or the cores given)"
            )
            out.append(Infeasibility("candidates", f"{name} may run on no candidate core{why}", unit.path))
            continue
        candidates = problem.candidates(u)
        if not candidates:
            out.append(
                Infeasibility(
                    "candidates",
                    f"{name} demands MIPS but none of its cores has SEI::MIPSCapacity",
                    unit.path,
                )
            )
            continue
        least: dict[str, Fraction] = {}
        for c in candidates:
            kind = problem.cores[c].kind or _short(problem, problem.cores[c].path)
            load = problem.load[u][c] or Fraction(0)
            least[kind] = min(load, least.get(kind, load))
        if all(load > 1 for load in least.values()):
            needs = ", ".join(f"{_percent(load)} of any {kind} core" for kind, load in sorted(least.items()))
            out.append(Infeasibility("cpu", f"{name}{_rate(problem, u)} needs {needs}", unit.path))
            continue
        fitting = [c for c in candidates if (problem.load[u][c] or 0) <= 1]
        if problem.check_schedulability and not any(problem.schedulable(c, (u,)) for c in fitting):
            out.append(
                Infeasibility(
                    "schedulability",
                    f"{name}{_rate(problem, u)} is not schedulable alone on any of its cores",
                    unit.path,
                )
            )
    return out


def _pinned(problem: DeploymentProblem) -> list[Infeasibility]:
    out = []
    on: dict[int, list[int]] = {}
    for u in range(len(problem.units)):
        candidates = problem.candidates(u)
        if len(candidates) == 1:
            on.setdefault(candidates[0], []).append(u)
    for c, units in sorted(on.items()):
        core = problem.cores[c]
        names = ", ".join(_short(problem, problem.units[u].path) for u in units)
        load = sum((problem.load[u][c] or Fraction(0) for u in units), Fraction(0))
        if load > 1:
            out.append(
                Infeasibility(
                    "pinned", f"the units pinned to it ({names}) need {_percent(load)} of it", core.path
                )
            )
        elif not problem.schedulable(c, tuple(units)):
            out.append(
                Infeasibility(
                    "pinned", f"the units pinned to it ({names}) are not schedulable together", core.path
                )
            )
    return out


def _memory(problem: DeploymentProblem) -> list[Infeasibility]:
    out = []
    if not problem.board_memory:
        return out
    pinned: dict[str, list[int]] = {}
    for u, unit in enumerate(problem.units):
        boards = {problem.cores[c].board for c in problem.candidates(u)}
        room = [problem.board_memory.get(b) for b in boards]
        if room and all(r is not None and unit.memory_kbyte > r for r in room):
            out.append(
                Infeasibility(
                    "memory",
                    f"{_short(problem, unit.path)} needs {float(unit.memory_kbyte):g} KByte, more than the "
                    "memory of any board it may run on",
                    unit.path,
                )
            )
        if len(boards) == 1:
            pinned.setdefault(boards.pop(), []).append(u)
    for board, units in sorted(pinned.items()):
        capacity = problem.board_memory.get(board)
        total = sum((problem.units[u].memory_kbyte for u in units), Fraction(0))
        if capacity is not None and total > capacity and len(units) > 1:
            out.append(
                Infeasibility(
                    "memory",
                    f"the units that may only run on it need {float(total):g} KByte of its "
                    f"{float(capacity):g} KByte",
                    board,
                )
            )
    return out


def _totals(problem: DeploymentProblem) -> list[Infeasibility]:
    out = []
    usable = {c for u in range(len(problem.units)) for c in problem.candidates(u)}
    need = sum(
        (
            min(problem.load[u][c] or Fraction(0) for c in problem.candidates(u))
            for u in range(len(problem.units))
        ),
        Fraction(0),
    )
    if usable and need > len(usable):
        out.append(
            Infeasibility(
                "cpu",
                f"the units need at least {_percent(need)} of a core in all; the {len(usable)} cores "
                f"they may take offer {len(usable) * 100} %",
                problem.root,
            )
        )
    if problem.bus_capacity is not None:
        forced = Fraction(0)
        for u, v, rate in problem.traffic:
            boards_u = {problem.cores[c].board for c in problem.candidates(u)}
            boards_v = {problem.cores[c].board for c in problem.candidates(v)}
            if not boards_u & boards_v:
                forced += rate
        if forced > problem.bus_capacity:
            out.append(
                Infeasibility(
                    "bus",
                    f"the topics between units that cannot share a board carry {float(forced):g} KByte/s, "
                    f"more than the bus capacity {float(problem.bus_capacity):g} KByte/s",
                    problem.root,
                )
            )
    return out


def _relaxed(problem: DeploymentProblem, time_limit: float) -> list[Infeasibility]:
    """Drop one constraint set at a time; name those whose removal lets a binding exist."""
    from rosaadl.analysis.deployment_solver import solve_deployment

    variants = {
        "schedulability": replace(problem, check_schedulability=False),
        "memory": replace(problem, board_memory={}),
        "bus": replace(problem, bus_capacity=None),
    }
    freed = []
    for name, variant in variants.items():
        if name == "schedulability" and not problem.check_schedulability:
            continue
        if name == "memory" and not problem.board_memory:
            continue
        if name == "bus" and problem.bus_capacity is None:
            continue
        if solve_deployment(variant, time_limit=time_limit, deterministic=True).feasible:
            freed.append(name)
    if freed:
        return [
            Infeasibility(
                "combined",
                f"the CPU load and {' / '.join(freed)} constraints together admit no binding: without "
                f"{' or without '.join(freed)} a binding exists",
                problem.root,
            )
        ]
    return [Infeasibility("combined", "no binding keeps every core at most 100 % loaded", problem.root)]


def explain_infeasibility(problem: DeploymentProblem, *, time_limit: float = 2.0) -> list[Infeasibility]:
    """The reasons ``problem`` has no binding (see the module), the simplest found first."""
    for check in (_single_unit, _pinned, _memory, _totals):
        found = check(problem)
        if found:
            return found
    return _relaxed(problem, time_limit)

"""The deployment problem as a constraint model, solved by OR-Tools CP-SAT.

One Boolean per (unit, candidate core), exactly one per unit. Constraints: each core at most
100 % loaded; each board's memory; the bus capacity against the traffic of unit pairs on
different boards; per-core schedulability. Objectives, lexicographic (each stage minimises one
with the ones before held at the values found): the highest core load, the total bus load
(KByte/s crossing boards), the longest chain latency, the number of units moved from their
current ``Actual_Processor_Binding``.

**Chain latency.** Each cause-effect chain of the executor analysis costs its fixed part (timer
periods + execution times) plus the transmission of each of its topics whose units are on
different boards (:mod:`rosaadl.analysis.deployment_links`): linear in the "on different boards"
Booleans the bus objective has (``y >= x[u,b] - x[v,b]`` per board), so ``L >= chain`` for every
chain and ``L`` minimised is the longest chain exactly. This is the executor analysis's reaction
time of the chain (crossing topics bound to the solver's bus) less the waiting of its callbacks
in their executors and on their cores, which the solver does not model. Microseconds are scaled
like the loads (exact up to 10^9, else by 1000: nanoseconds, rounded down). The stage is skipped
when no binding can change the value (no chain, one board, or no topic between units).

**Integers.** CP-SAT works on integers. Loads are exact fractions (Σ CET / Period); they are
scaled by the least common multiple of their denominators when it is at most 10^9, so the model
is *exact* (the solver's optimum is the exact optimum); otherwise by 10^6 (a resolution of one
millionth of a core, 0.0001 %), rounded down. Memory (KByte) and traffic (KByte/s) are scaled
the same way. Rounding down never cuts a binding that is feasible exactly; a binding the rounded
model accepts is then checked exactly, with the same functions the analyses use.

**Lazy cuts.** Schedulability under fixed priorities is not linear: each binding the solver
returns is checked core by core (:meth:`DeploymentProblem.schedulable`, the response-time test
where the core has priorities), as are the exact loads, memory and bus; a core that fails gets a
cut "not all of these units together on this core" (on every identical core too: adding tasks
never makes a core schedulable), the set first shrunk to one from which no unit can be dropped,
and the stage is solved again, until the binding passes.

**Determinism.** One search worker and a fixed seed: CP-SAT with several workers is not
deterministic across runs (the workers race), so one is used. A stage that ends by proving its
optimum then gives the same binding on every run. ``time_limit`` is wall-clock seconds (the
limit a user waits for); a stage cut short by it may stop at another incumbent on a busier
machine. With ``deterministic=True`` the limit is CP-SAT's deterministic time instead (its own
count of work, ``max_deterministic_time``), and the output is the same on any machine and load.
The best of the worst-fit and best-fit baselines that passes every check is the starting hint.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rosaadl.analysis.deployment_problem import DeploymentProblem, Evaluation

__all__ = [
    "EXACT_LIMIT",
    "RESOLUTION",
    "Objective",
    "SolvedBinding",
    "SolverOutcome",
    "integer_scale",
    "solve_deployment",
]

RESOLUTION = 10**6  #: the scale of a core's capacity when the exact one is larger than EXACT_LIMIT
EXACT_LIMIT = 10**9
_STAGE_SHARE = (0.8, 0.9, 0.95, 1.0)  #: stage k may use the time up to this share of the binding's budget
LATENCY_SCALE = 1000  #: the scale of a microsecond when the exact one is larger than EXACT_LIMIT
LATENCY_NOTE = (
    "timer periods + execution times + transmission of the topics that cross boards; "
    "the executor analysis adds the waiting of each callback"
)
NO_CHAIN_NOTE = "the model has no cause-effect chain"


def integer_scale(values: Iterable[Fraction]) -> tuple[int, bool]:
    """(scale, exact): the least common multiple of the denominators when at most EXACT_LIMIT,
    else (RESOLUTION, False)."""
    scale = 1
    for value in values:
        scale = math.lcm(scale, value.denominator)
        if scale > EXACT_LIMIT:
            return RESOLUTION, False
    return scale, True


def _scaled(value: Fraction, scale: int) -> int:
    return math.floor(value * scale)


@dataclass(frozen=True)
class Objective:
    """One objective of the best binding: its value, the solver's bound and the gap between."""

    name: str
    value: Fraction | int | None
    bound: Fraction | int | None
    unit: str
    note: str = ""

    @property
    def gap_percent(self) -> float | None:
        if self.value is None or self.bound is None:
            return None
        if self.value == 0:
            return 0.0
        return max(0.0, float((Fraction(self.value) - Fraction(self.bound)) / Fraction(self.value) * 100))

    def as_dict(self) -> dict[str, Any]:
        def num(x: Fraction | int | None) -> float | int | None:
            if x is None:
                return None
            return int(x) if Fraction(x).denominator == 1 else float(x)

        out: dict[str, Any] = {
            "name": self.name,
            "value": num(self.value),
            "bound": num(self.bound),
            "gap_percent": None if self.gap_percent is None else round(self.gap_percent, 4),
            "unit": self.unit,
        }
        if self.note:
            out["note"] = self.note
        return out


@dataclass(frozen=True)
class SolvedBinding:
    """A binding (core index per unit), its exact evaluation and its objectives."""

    assignment: tuple[int, ...]
    evaluation: Evaluation
    objectives: tuple[Objective, ...]
    optimal: bool


@dataclass(frozen=True)
class SolverOutcome:
    """What the solver found: the bindings, best first (empty when none), and how."""

    status: str  #: "optimal", "feasible", "infeasible" (proven) or "unknown" (no binding in time)
    bindings: tuple[SolvedBinding, ...]
    scale: int
    exact_scale: bool
    seconds: float
    cuts: int
    solves: int

    @property
    def feasible(self) -> bool:
        return bool(self.bindings)

    @property
    def best(self) -> SolvedBinding | None:
        return self.bindings[0] if self.bindings else None


@dataclass
class _Model:
    """The CP-SAT model of one problem, rebuilt for each binding kept."""

    problem: DeploymentProblem
    load_scale: int
    memory_scale: int
    traffic_scale: int
    latency_scale: int
    cuts: list[tuple[int, tuple[int, ...]]]
    excluded: list[tuple[int, ...]]
    model: Any = None
    x: dict[tuple[int, int], Any] = field(default_factory=dict)
    core_terms: list[list[tuple[int, Any]]] = field(default_factory=list)

    def build(self) -> None:
        from ortools.sat.python import cp_model

        p = self.problem
        m = cp_model.CpModel()
        self.model = m
        self.x = {}
        self.core_terms = [[] for _ in p.cores]
        for u in range(len(p.units)):
            row = []
            for c in p.candidates(u):
                load = p.load[u][c] or Fraction(0)
                if load > 1:
                    continue
                var = m.new_bool_var(f"x{u}_{c}")
                self.x[u, c] = var
                row.append(var)
                self.core_terms[c].append((_scaled(load, self.load_scale), var))
            m.add_exactly_one(row)
        weighted = cp_model.LinearExpr.weighted_sum
        top = 0
        sums = []
        for terms in self.core_terms:
            if terms:
                expression = weighted([v for _w, v in terms], [w for w, _v in terms])
                m.add(expression <= self.load_scale)
                sums.append(expression)
                top = max(top, min(self.load_scale, sum(w for w, _ in terms)))
        self.z = m.new_int_var(0, top, "max_load")
        for expression in sums:
            m.add(expression <= self.z)
        boards = p.boards()
        on: dict[tuple[int, str], list[Any]] = {}
        for (u, c), var in self.x.items():
            on.setdefault((u, p.cores[c].board), []).append(var)
        for b, capacity in p.board_memory.items():
            terms = [
                (_scaled(p.units[u].memory_kbyte, self.memory_scale), var)
                for u in range(len(p.units))
                for var in on.get((u, b), [])
            ]
            terms = [(w, v) for w, v in terms if w > 0]
            if terms:
                total = weighted([v for _w, v in terms], [w for w, _v in terms])
                m.add(total <= _scaled(capacity, self.memory_scale))
        crossing = []
        self.y: list[tuple[int, int, Any]] = []
        if len(boards) > 1:
            for u, v, rate in p.traffic:
                weight = _scaled(rate, self.traffic_scale)
                if weight <= 0:
                    continue
                y = m.new_bool_var(f"y{u}_{v}")
                self.y.append((u, v, y))
                for b in boards:
                    m.add(sum(on.get((u, b), [])) - sum(on.get((v, b), [])) <= y)
                crossing.append((weight, y))
        self.bus = (
            weighted([y for _w, y in crossing], [w for w, _y in crossing]) if crossing else m.new_constant(0)
        )
        if p.bus_capacity is not None and crossing:
            m.add(self.bus <= _scaled(p.bus_capacity, self.traffic_scale))
        self._chains(boards, on)
        moved = []
        for u in range(len(p.units)):
            if p.current[u]:
                here = [self.x[u, c] for c in p.current[u] if (u, c) in self.x]
                moved.append(1 - sum(here))
        self.moves = sum(moved) if moved else m.new_constant(0)
        for core, members in self.cuts:
            self._add_cut(core, members)
        for assignment in self.excluded:
            m.add(sum(self.x[u, c] for u, c in enumerate(assignment)) <= len(assignment) - 1)

    def _chains(self, boards: list[str], on: dict[tuple[int, str], list[Any]]) -> None:
        """The longest chain latency: at least each chain's fixed part plus the transmission of
        each of its links whose units are on different boards (one Boolean per unit pair,
        shared with the bus objective)."""
        p, m = self.problem, self.model
        self.latency_varies = False
        self.latency_low = 0
        if not p.chains:
            self.latency = m.new_constant(0)
            return
        pairs = {(min(u, v), max(u, v)): y for u, v, y in self.y}
        expressions = []
        for chain in p.chains:
            terms = []
            for u, v, us in chain.links:
                weight = _scaled(us, self.latency_scale)
                key = (min(u, v), max(u, v))
                if weight <= 0 or len(boards) < 2:
                    continue
                y = pairs.get(key)
                if y is None:
                    y = m.new_bool_var(f"y{key[0]}_{key[1]}")
                    pairs[key] = y
                    self.y.append((key[0], key[1], y))
                    for b in boards:
                        m.add(sum(on.get((key[0], b), [])) - sum(on.get((key[1], b), [])) <= y)
                terms.append((weight, y))
            expressions.append((_scaled(chain.fixed_us, self.latency_scale), terms))
        low = max(fixed for fixed, _terms in expressions)
        high = max(fixed + sum(w for w, _y in terms) for fixed, terms in expressions)
        self.latency_varies = high > low
        self.latency_low = low
        self.latency = m.new_int_var(low, high, "longest_chain")
        for fixed, terms in expressions:
            if terms:
                m.add(self.latency >= fixed + sum(w * y for w, y in terms))

    def _add_cut(self, core: int, members: tuple[int, ...]) -> None:
        variables = [self.x.get((u, core)) for u in members]
        if all(v is not None for v in variables):
            self.model.add(sum(variables) <= len(members) - 1)

    def cut(self, core: int, members: tuple[int, ...]) -> int:
        """Forbid ``members`` together on ``core`` and on every core identical to it."""
        added = 0
        for other in _identical(self.problem, core):
            self.cuts.append((other, members))
            self._add_cut(other, members)
            added += 1
        return added

    def hint(self, assignment: Sequence[int]) -> None:
        """Start from ``assignment``: every variable hinted, so that a binding that passes is
        the first solution without search."""
        self.model.clear_hints()
        for (u, c), var in self.x.items():
            self.model.add_hint(var, assignment[u] == c)
        if all(c >= 0 for c in assignment):
            cores = self.problem.cores
            for u, v, y in self.y:
                self.model.add_hint(y, cores[assignment[u]].board != cores[assignment[v]].board)
            self.model.add_hint(self.z, _stage_value(self, 0, assignment))

    def assignment(self, solver: Any) -> tuple[int, ...]:
        out = [-1] * len(self.problem.units)
        for (u, c), var in self.x.items():
            if solver.boolean_value(var):
                out[u] = c
        return tuple(out)


def _identical(problem: DeploymentProblem, core: int) -> list[int]:
    """``core`` and the cores whose tasks would be the same (same MIPS, scheduler, load column)."""
    if problem.times and any(t is not None for t in problem.times):
        return [core]
    me = problem.cores[core]

    def column(c: int) -> tuple[Any, ...]:
        return tuple(problem.load[u][c] for u in range(len(problem.units)))

    mine = column(core)
    return [
        c
        for c, other in enumerate(problem.cores)
        if c == core
        or (
            (other.capacity, other.scheduler, other.preemptive) == (me.capacity, me.scheduler, me.preemptive)
            and column(c) == mine
        )
    ]


def _cuts_for(problem: DeploymentProblem, assignment: Sequence[int], evaluation: Evaluation) -> list[Any]:
    """What to forbid of a binding the rounded model accepted but the exact checks refuse:
    (core, members) for a core over 100 % or not schedulable, else the whole binding."""
    out = []
    for c, members in enumerate(problem.members(assignment)):
        if members and evaluation.loads[c] > 1:
            out.append((c, members))
        elif members and not problem.schedulable(c, members):
            out.append((c, _minimal_unschedulable(problem, c, members)))
    return out


def _minimal_unschedulable(
    problem: DeploymentProblem, core: int, members: tuple[int, ...]
) -> tuple[int, ...]:
    """A subset of ``members`` still not schedulable on ``core`` from which no unit can be
    dropped (deletion filter, lightest units tried first): the smaller the set, the more bindings
    one cut rules out."""
    kept = list(members)
    for unit in sorted(members, key=lambda u: (problem.load[u][core] or 0, u)):
        trial = tuple(u for u in kept if u != unit)
        if trial and not problem.schedulable(core, trial):
            kept = list(trial)
    return tuple(kept)


def solve_deployment(
    problem: DeploymentProblem,
    *,
    time_limit: float = 10.0,
    keep: int = 1,
    seed: int = 0,
    hints: Sequence[Sequence[int]] = (),
    deterministic: bool = False,
) -> SolverOutcome:
    """The ``keep`` best distinct bindings of ``problem`` under the lexicographic objectives
    (see the module), within ``time_limit`` seconds in all (wall clock, or CP-SAT's deterministic
    time with ``deterministic``). ``hints``: bindings to start from (the first that passes every
    check is the incumbent)."""
    from ortools.sat.python import cp_model

    start = time.perf_counter()
    load_scale, exact_load = integer_scale(
        problem.load[u][c] or Fraction(0) for u in range(len(problem.units)) for c in problem.candidates(u)
    )
    memory_scale, exact_memory = integer_scale(
        [u.memory_kbyte for u in problem.units] + list(problem.board_memory.values())
    )
    traffic_scale, exact_traffic = integer_scale(
        [rate for _u, _v, rate in problem.traffic]
        + ([problem.bus_capacity] if problem.bus_capacity is not None else [])
    )
    latency_scale, exact_latency = integer_scale(
        [c.fixed_us for c in problem.chains] + [us for c in problem.chains for _u, _v, us in c.links]
    )
    if not exact_latency:
        latency_scale = LATENCY_SCALE
    state = _Model(problem, load_scale, memory_scale, traffic_scale, latency_scale, [], [])
    if any(not problem.candidates(u) for u in range(len(problem.units))):
        return SolverOutcome("infeasible", (), load_scale, exact_load, time.perf_counter() - start, 0, 0)
    budget = max(0.05, time_limit / max(1, keep))
    bindings: list[SolvedBinding] = []
    solves = cuts = 0
    proven_infeasible = False
    for _index in range(max(1, keep)):
        began = time.perf_counter()
        state.build()
        incumbent = _best_hint(problem, hints, state.excluded)
        stages = [
            ("max_core_load", state.z),
            ("bus_load", state.bus),
            ("longest_chain_latency", state.latency),
            ("moves", state.moves),
        ]
        values: list[tuple[int, int, bool]] = []
        used = 0.0 if deterministic else time.perf_counter() - began
        for stage, (_name, expression) in enumerate(stages):
            if stage == 2 and incumbent is not None and not state.latency_varies:
                # no binding changes it (no chain, or no link between units that may part)
                held = _stage_value(state, stage, incumbent)
                values.append((held, held, True))
                continue
            limit = budget * _STAGE_SHARE[stage] if incumbent is not None else budget
            found = None
            unproven_bound = -1.0
            while True:
                state.model.minimize(expression)
                if incumbent is not None or hints:
                    state.hint(incumbent if incumbent is not None else hints[0])
                solver = cp_model.CpSolver()
                solver.parameters.num_workers = 1
                # a light presolve: on thousands of variables, symmetry detection, probing and
                # repeated presolve take seconds of the time limit before the search starts
                solver.parameters.symmetry_level = 0
                solver.parameters.cp_model_probing_level = 0
                solver.parameters.max_presolve_iterations = 1
                solver.parameters.random_seed = seed
                if deterministic:
                    solver.parameters.max_deterministic_time = max(0.01, limit - used)
                else:
                    solver.parameters.max_time_in_seconds = max(0.01, limit - used)
                status = solver.solve(state.model)
                solves += 1
                used = used + solver.deterministic_time if deterministic else time.perf_counter() - began
                if status == cp_model.INFEASIBLE:
                    proven_infeasible = stage == 0 and incumbent is None
                    break
                if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
                    # no solution in time: the bound the search reached still holds
                    unproven_bound = solver.best_objective_bound
                    break
                assignment = state.assignment(solver)
                evaluation = problem.evaluate(assignment)
                if evaluation.feasible:
                    found = (assignment, solver.objective_value, solver.best_objective_bound, status)
                    break
                new_cuts = _cuts_for(problem, assignment, evaluation)
                if not new_cuts:  # memory or bus, rounded: forbid this binding
                    state.excluded.append(assignment)
                    state.model.add(
                        sum(state.x[u, c] for u, c in enumerate(assignment)) <= len(assignment) - 1
                    )
                    cuts += 1
                for core, members in new_cuts:
                    cuts += state.cut(core, members)
                if used >= limit:
                    break
            if found is None:
                if incumbent is None:
                    break
                # the time ran out (or cuts closed the stage): the incumbent stays, without a bound
                values.append((-1, math.floor(unproven_bound + 1e-9) if unproven_bound >= 0 else -1, False))
            else:
                incumbent = found[0]
                values.append((round(found[1]), math.floor(found[2] + 1e-9), found[3] == cp_model.OPTIMAL))
            # hold this objective at the incumbent's value for the next stages
            held = _stage_value(state, stage, incumbent)
            state.model.add(expression <= held)
        if incumbent is None:
            break
        bindings.append(_solved(problem, state, incumbent, values))
        state.excluded.append(incumbent)
    seconds = time.perf_counter() - start
    if bindings:
        status = "optimal" if bindings[0].optimal else "feasible"
    else:
        status = "infeasible" if proven_infeasible else "unknown"
    return SolverOutcome(status, tuple(bindings), load_scale, exact_load, seconds, cuts, solves)


def _best_hint(
    problem: DeploymentProblem, hints: Sequence[Sequence[int]], excluded: list[tuple[int, ...]]
) -> tuple[int, ...] | None:
    """The best of the hints that pass every check (highest load, bus, chain, moves), None if none."""
    best, key = None, None
    for hint in hints:
        if len(hint) != len(problem.units) or tuple(hint) in excluded:
            continue
        evaluation = problem.evaluate(hint)
        if evaluation.feasible:
            mine = (evaluation.max_load, evaluation.bus_kbyteps, evaluation.latency_us or 0, evaluation.moves)
            if key is None or mine < key:
                best, key = tuple(hint), mine
    return best


def _stage_value(state: _Model, stage: int, assignment: Sequence[int]) -> int:
    """The scaled value of objective ``stage`` of ``assignment`` in the model's integers."""
    p = state.problem
    if stage == 0:
        sums = [0] * len(p.cores)
        for u, c in enumerate(assignment):
            sums[c] += _scaled(p.load[u][c] or Fraction(0), state.load_scale)
        return max(sums, default=0)
    if stage == 1:
        return sum(
            _scaled(rate, state.traffic_scale)
            for u, v, rate in p.traffic
            if p.cores[assignment[u]].board != p.cores[assignment[v]].board
        )
    if stage == 2:
        if not p.chains:
            return 0

        def crossing(u: int, v: int) -> bool:
            boards = p.boards()
            return len(boards) > 1 and p.cores[assignment[u]].board != p.cores[assignment[v]].board

        return max(
            _scaled(chain.fixed_us, state.latency_scale)
            + sum(_scaled(us, state.latency_scale) for u, v, us in chain.links if crossing(u, v))
            for chain in p.chains
        )
    return p.evaluate(assignment).moves


def _solved(
    problem: DeploymentProblem,
    state: _Model,
    assignment: tuple[int, ...],
    values: list[tuple[int, int, bool]],
) -> SolvedBinding:
    evaluation = problem.evaluate(assignment)
    scales = (state.load_scale, state.traffic_scale, state.latency_scale, 1)
    exact_values: tuple[Any, ...] = (
        evaluation.max_load,
        evaluation.bus_kbyteps,
        evaluation.latency_us,
        evaluation.moves,
    )
    objectives = []
    optimal = True
    for stage, (name, unit) in enumerate(
        (
            ("max_core_load", "percent"),
            ("bus_load", "KByte/s"),
            ("longest_chain_latency", "us"),
            ("moves", "units"),
        )
    ):
        _value, bound, proven = values[stage] if stage < len(values) else (-1, -1, False)
        optimal = optimal and proven
        exact = exact_values[stage]
        if exact is None:  # no chain
            objectives.append(Objective(name, None, None, unit, NO_CHAIN_NOTE))
            continue
        if stage == 2 and state.latency_low > 0:  # no chain is shorter than its fixed part
            bound = max(bound, state.latency_low)
        if bound < 0:
            bound_value: Fraction | int | None = None
        else:
            bound_value = min(Fraction(bound, scales[stage]), Fraction(exact))
            if proven and stage and optimal:
                bound_value = Fraction(exact)
        if name == "max_core_load":
            exact = exact * 100
            bound_value = None if bound_value is None else bound_value * 100
        note = LATENCY_NOTE if name == "longest_chain_latency" else ""
        objectives.append(Objective(name, exact, bound_value, unit, note))
    return SolvedBinding(assignment, evaluation, tuple(objectives), optimal)

"""Deployment search: bind software processes to processors (cores) so that every core passes the
CPU load check and the schedulability analysis, minimising the maximum core load.

The load a process puts on a core is the CPU load its threads would have there, with OSATE's MIPS
semantics (:mod:`rosaadl.analysis.resources`): a thread's demand is ``CET / Period`` times the
MIPS of its ``Reference_Processor`` when the declarative model gives one — then its load on a core
is that demand over the core's ``SEI::MIPSCapacity`` — and its plain ``CET / Period`` otherwise
(it was measured on the core it runs on); a process whose threads demand nothing counts with its
``SEI::MIPSBudget``. A core passes when its load is at most 100 % and, with
``schedulability=True``, when the feasibility tests of :mod:`rosaadl.analysis.schedulability`
(response-time analysis where it applies) accept its periodic threads under the core's
``Scheduling_Protocol`` (rate monotonic when it has none), execution times scaled like the load.
A process measured separately on each core type (a library node with one platform-dependent
implementation per core) can be given its execution times per candidate core instead
(``execution_times``): it then runs only on those cores, with those times, unscaled.

Search: branch and bound over processes (heaviest first) and cores, cutting branches that cannot
beat the best maximum load found and trying only one of several identical empty cores; it is
exact (optimal) when it finishes within ``node_limit`` nodes. Beyond, a bin-packing heuristic
(largest process first on the least loaded core that passes, then moves and swaps that lower the
maximum load) gives the result. The best bindings come back as AADL ``Actual_Processor_Binding``
property associations.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.deployment_problem import DeploymentProblem, deployment_problem
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, fmt, short_path, table
from rosaadl.errors import Diagnostic, Location, ModelError

__all__ = [
    "Placement",
    "CoreLoad",
    "DeploymentResult",
    "search_deployment",
]

log = logging.getLogger(__name__)


def _num(value: Fraction | None) -> float | int | None:
    if value is None:
        return None
    return int(value) if value.denominator == 1 else float(value)


@dataclass(frozen=True)
class Placement:
    """A process bound to a core, and the load it puts there (a fraction: 1 = 100 %)."""

    process: str
    processor: str
    load: Fraction

    def as_dict(self) -> dict[str, Any]:
        return {"process": self.process, "processor": self.processor, "load_percent": _num(self.load * 100)}


@dataclass(frozen=True)
class CoreLoad:
    """A candidate core after the search: its load, processes and schedulability verdict."""

    path: str
    capacity_mips: Fraction
    load: Fraction
    processes: tuple[str, ...]
    schedulable: bool | None

    @property
    def load_percent(self) -> Fraction:
        return self.load * 100

    def as_dict(self) -> dict[str, Any]:
        return {
            "path": self.path,
            "capacity_mips": _num(self.capacity_mips),
            "load_percent": _num(self.load_percent),
            "processes": list(self.processes),
            "schedulable": self.schedulable,
        }


@dataclass(frozen=True)
class DeploymentResult:
    """The best deployment found (``feasible`` False: the best effort, some core fails)."""

    instance: str
    method: str
    optimal: bool
    feasible: bool
    placements: tuple[Placement, ...]
    cores: tuple[CoreLoad, ...]
    unplaced: tuple[str, ...]
    nodes: int
    diagnostics: tuple[Diagnostic, ...]

    @property
    def max_load(self) -> Fraction:
        return max((c.load for c in self.cores), default=Fraction(0))

    @property
    def ok(self) -> bool:
        return self.feasible and all(d.severity != "error" for d in self.diagnostics)

    def binding(self, process: str) -> str:
        for placement in self.placements:
            if placement.process == process:
                return placement.processor
        raise ModelError(f"process {process!r} is not placed")

    def associations(self) -> list[str]:
        """The bindings as AADL property associations for the root implementation's properties."""
        lines = []
        for placement in self.placements:
            target = placement.processor.partition(".")[2] or placement.processor
            process = placement.process.partition(".")[2] or placement.process
            lines.append(f"Actual_Processor_Binding => (reference ({target})) applies to {process};")
        return lines

    def as_dict(self) -> dict[str, Any]:
        return {
            "method": self.method,
            "optimal": self.optimal,
            "feasible": self.feasible,
            "max_load_percent": _num(self.max_load * 100),
            "bindings": [p.as_dict() for p in self.placements],
            "cores": [c.as_dict() for c in self.cores],
            "unplaced": list(self.unplaced),
            "associations": self.associations(),
        }


# =============================================================================== search


class _Search:
    """Branch and bound (exact) and a bin-packing heuristic over one problem."""

    def __init__(self, problem: DeploymentProblem, node_limit: int) -> None:
        self.p = problem
        self.node_limit = node_limit
        self.nodes = 0
        self.best: list[int] | None = None
        self.best_key: tuple[Fraction, Fraction] | None = None
        self.complete = True
        n = len(problem.units)
        # processes by decreasing heaviest load (ties: model order)
        self.order = sorted(
            range(n),
            key=lambda i: (-max((x for x in problem.load[i] if x is not None), default=Fraction(0)), i),
        )
        # identical cores (same capacity, scheduler, loads and permissions) are interchangeable
        self.signature = [
            (
                c.capacity,
                c.scheduler,
                c.preemptive,
                tuple(problem.load[q][k] for q in range(n)),
                tuple(k in problem.allowed[q] for q in range(n)),
            )
            for k, c in enumerate(problem.cores)
        ]
        self.allowed = [set(a) for a in problem.allowed]

    @staticmethod
    def key(loads: Sequence[Fraction]) -> tuple[Fraction, Fraction]:
        """Minimise the maximum load, then the sum of squares (balance), for a deterministic best."""
        return (max(loads, default=Fraction(0)), sum((x * x for x in loads), Fraction(0)))

    def fits(self, p: int, c: int, loads: Sequence[Fraction], members: Sequence[Sequence[int]]) -> bool:
        load = self.p.load[p][c]
        if load is None or c not in self.allowed[p] or loads[c] + load > 1:
            return False
        return self.p.schedulable(c, tuple(sorted([*members[c], p])))

    # ------------------------------------------------------------------ exact

    def exact(self) -> None:
        """Depth-first branch and bound; ``complete`` stays True when it ran to the end."""
        problem = self.p
        n, m = len(problem.units), len(problem.cores)
        assignment = [-1] * n
        loads = [Fraction(0)] * m
        members: list[list[int]] = [[] for _ in range(m)]

        def visit(depth: int) -> None:
            if self.nodes >= self.node_limit:
                self.complete = False
                return
            self.nodes += 1
            if depth == n:
                key = self.key(loads)
                if self.best_key is None or key < self.best_key:
                    self.best_key, self.best = key, list(assignment)
                return
            p = self.order[depth]
            row = problem.load[p]
            candidates = sorted(
                (c for c in self.allowed[p] if row[c] is not None), key=lambda c: (loads[c] + row[c], c)
            )
            tried_empty: set[Any] = set()
            for c in candidates:
                new_load = loads[c] + row[c]
                if self.best_key is not None and new_load >= self.best_key[0]:
                    break  # cannot lower the best maximum; the others are at least as loaded
                if not members[c]:
                    if self.signature[c] in tried_empty:
                        continue
                    tried_empty.add(self.signature[c])
                if not self.fits(p, c, loads, members):
                    continue
                assignment[p] = c
                loads[c] = new_load
                members[c].append(p)
                visit(depth + 1)
                members[c].pop()
                loads[c] -= row[c]
                assignment[p] = -1
                if not self.complete:
                    return

        visit(0)

    # ------------------------------------------------------------------ heuristic

    def heuristic(self) -> tuple[list[int], list[int]]:
        """Largest first on the least loaded core that passes, then moves and swaps of the
        processes of the most loaded cores while they lower (max load, balance)."""
        problem = self.p
        n, m = len(problem.units), len(problem.cores)
        assignment = [-1] * n
        loads = [Fraction(0)] * m
        members: list[list[int]] = [[] for _ in range(m)]
        unplaced = []
        for p in self.order:
            row = problem.load[p]
            chosen = None
            for c in sorted(
                (c for c in self.allowed[p] if row[c] is not None), key=lambda c: (loads[c] + row[c], c)
            ):
                if self.fits(p, c, loads, members):
                    chosen = c
                    break
            if chosen is None:
                unplaced.append(p)
                continue
            assignment[p] = chosen
            loads[chosen] += row[chosen]
            members[chosen].append(p)
        for _round in range(10 * n + 10):
            if not self._improve(assignment, loads, members):
                break
        return assignment, sorted(unplaced)

    def _improve(self, assignment: list[int], loads: list[Fraction], members: list[list[int]]) -> bool:
        """One move or swap that lowers (max load, Σ load²), applied; False when there is none.
        Candidates are scored in O(1) from the three largest loads before any feasibility test."""
        problem = self.p
        current = self.key(loads)
        top = current[0]
        biggest = sorted(range(len(loads)), key=lambda c: (-loads[c], c))[:3]

        def score(a: int, new_a: Fraction, b: int, new_b: Fraction) -> tuple[Fraction, Fraction]:
            rest = next((loads[c] for c in biggest if c != a and c != b), Fraction(0))
            squares = current[1] - loads[a] ** 2 - loads[b] ** 2 + new_a**2 + new_b**2
            return (max(rest, new_a, new_b), squares)

        hot = [c for c in range(len(loads)) if loads[c] == top]
        for src in hot:
            for p in list(members[src]):
                row = problem.load[p]
                for c in sorted(self.allowed[p]):
                    if c == src or row[c] is None:
                        continue
                    new_c = loads[c] + row[c]
                    if new_c > 1 or score(src, loads[src] - row[src], c, new_c) >= current:
                        continue
                    if not self.fits(p, c, loads, members):  # p is not on c: members[c] as it is
                        continue
                    assignment[p] = c
                    loads[src] -= row[src]
                    loads[c] = new_c
                    members[src].remove(p)
                    members[c].append(p)
                    return True
        for src in hot:
            for p in list(members[src]):
                for q in range(len(assignment)):
                    dst = assignment[q]
                    if dst < 0 or dst == src:
                        continue
                    lp, lq = problem.load[p][dst], problem.load[q][src]
                    if lp is None or lq is None or dst not in self.allowed[p] or src not in self.allowed[q]:
                        continue
                    new_src = loads[src] + lq - problem.load[p][src]
                    new_dst = loads[dst] + lp - problem.load[q][dst]
                    if new_src > 1 or new_dst > 1 or score(src, new_src, dst, new_dst) >= current:
                        continue
                    at_src = tuple(sorted([x for x in members[src] if x != p] + [q]))
                    at_dst = tuple(sorted([x for x in members[dst] if x != q] + [p]))
                    if not (problem.schedulable(src, at_src) and problem.schedulable(dst, at_dst)):
                        continue
                    assignment[p], assignment[q] = dst, src
                    loads[src], loads[dst] = new_src, new_dst
                    members[src] = list(at_src)
                    members[dst] = list(at_dst)
                    return True
        return False


# =============================================================================== entry


def search_deployment(
    source: Any,
    processes: Iterable[Any] | None = None,
    processors: Iterable[Any] | None = None,
    *,
    allowed: Mapping[str, Iterable[str]] | None = None,
    schedulability: bool = True,
    node_limit: int = 200_000,
    exact_processes: int = 16,
    execution_times: Mapping[str, Mapping[str, Mapping[str, Any]]] | None = None,
) -> DeploymentResult:
    """Propose bindings of ``processes`` (instances or paths; default: every process with threads)
    to ``processors`` (default: every processor without processor subcomponents, i.e. the cores),
    minimising the maximum core load while every core passes the load and schedulability checks.

    ``allowed`` restricts the cores of some processes (process path → core paths). Problems of
    at most ``exact_processes`` processes are searched exactly (within ``node_limit`` nodes of the
    branch and bound); larger ones by the heuristic.

    ``execution_times`` gives, for processes whose execution times depend on the core type they
    run on, process path → core path → thread path → ``Compute_Execution_Time`` in seconds
    (paths with or without the root's name; thread paths may be relative to the process). Such a
    process can run only on the cores listed for it; there its threads take the given times
    (a thread not listed takes none), unscaled, over the Periods of the instance.
    """
    problem = deployment_problem(
        source,
        processes,
        processors,
        allowed=allowed,
        schedulability=schedulability,
        execution_times=execution_times,
    )
    diagnostics = problem.diagnostics
    proc_list, core_list = problem.units, problem.cores

    search = _Search(problem, node_limit)
    small = len(proc_list) <= exact_processes
    unplaced_idx: list[int] = []
    if small:
        heuristic, unplaced_idx = _Search(problem, node_limit).heuristic()
        if not unplaced_idx:  # a good first incumbent makes the bound bite early
            search.best, search.best_key = heuristic, _key(problem, heuristic)
        search.exact()
    if small and search.complete:
        method = "exact"
        if search.best is not None:
            assignment, feasible, unplaced_idx = search.best, True, []
        else:  # proven: nothing passes; the heuristic shows the best effort
            assignment, feasible = heuristic, False
    else:
        method = "heuristic"
        if not small:
            heuristic, unplaced_idx = search.heuristic()
        if search.best is not None and (
            unplaced_idx or _key(problem, search.best) <= _key(problem, heuristic)
        ):
            assignment, unplaced_idx = search.best, []
        else:
            assignment = heuristic
        feasible = not unplaced_idx
    optimal = method == "exact" and feasible
    placements = []
    members: dict[int, list[int]] = {}
    for p, c in enumerate(assignment):
        if c < 0:
            continue
        members.setdefault(c, []).append(p)
        placements.append(Placement(proc_list[p].path, core_list[c].path, problem.load[p][c] or Fraction(0)))
    cores = []
    for c, core in enumerate(core_list):
        inside = tuple(sorted(members.get(c, [])))
        load = sum((problem.load[p][c] or Fraction(0) for p in inside), Fraction(0))
        verdict = problem.schedulable(c, inside) if schedulability and inside else (True if inside else None)
        cores.append(
            CoreLoad(core.path, core.capacity, load, tuple(proc_list[p].path for p in inside), verdict)
        )
        if load > 1 or verdict is False:
            feasible = False
    unplaced = tuple(proc_list[p].path for p in unplaced_idx)
    if unplaced:
        for path in unplaced:
            diagnostics.append(
                Diagnostic("error", "no candidate processor can take this process", Location(path=path))
            )
    elif not feasible:
        diagnostics.append(
            Diagnostic(
                "error",
                "no deployment passes the CPU load and schedulability checks",
                Location(path=problem.root),
            )
        )
    nodes = search.nodes
    log.debug(
        "deployment search: %d processes, %d cores, %d nodes, %d schedulability checks, %s",
        len(proc_list),
        len(core_list),
        nodes,
        problem.sched_calls,
        method,
    )
    return DeploymentResult(
        problem.root,
        method,
        optimal,
        feasible,
        tuple(placements),
        tuple(cores),
        unplaced,
        nodes,
        tuple(diagnostics),
    )


def _key(problem: DeploymentProblem, assignment: Sequence[int]) -> tuple[Fraction, Fraction]:
    loads = [Fraction(0)] * len(problem.cores)
    for p, c in enumerate(assignment):
        if c >= 0:
            loads[c] += problem.load[p][c] or Fraction(0)
    return (max(loads, default=Fraction(0)), sum((x * x for x in loads), Fraction(0)))


# =============================================================================== report


def deployment_text(result: DeploymentResult) -> list[str]:
    """The ``Deployment search`` section of the text report."""
    lines = [
        f"Deployment search ({result.method}{', optimal' if result.optimal else ''}, "
        f"max load {fmt(result.max_load * 100)} %, {'feasible' if result.feasible else 'not feasible'})",
        "",
    ]
    rows = [
        [
            short_path(c.path),
            c.capacity_mips,
            c.load_percent,
            c.schedulable,
            ", ".join(short_path(p) for p in c.processes),
        ]
        for c in result.cores
    ]
    lines += table(["processor", "capacity MIPS", "load %", "schedulable", "processes"], rows)
    lines.append("")
    lines += result.associations()
    lines.append("")
    return lines


def deployment_csv(result: DeploymentResult, base: str) -> dict[str, str]:
    """``<base>__Deployment.csv``: the processor proposed for every process, with its load."""
    rows: list[list[Any]] = [["Process", "Processor", "Load (%)"]]
    for p in result.placements:
        rows.append([p.process, p.processor, p.load * 100])
    return {f"{base}__Deployment.csv": csv_text(rows)}


def _run(context: AnalysisContext) -> DeploymentResult:
    return search_deployment(context.root, **(context.options.get("deployment") or {}))


register(
    Analysis(
        name="deploy",
        json_key="deployment",
        order=70,
        run=_run,
        text=deployment_text,
        csv=deployment_csv,
        aliases=("deployment",),
        default=False,
        description="a search for bindings of processes to cores that pass the analyses (proposes)",
    )
)

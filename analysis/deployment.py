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

from rosaadl.analysis.demand import ResourceDemand
from rosaadl.analysis.instance_values import (
    PropertyReader,
    category_of,
    instance_root,
    system_modes,
)
from rosaadl.analysis.registry import Analysis, AnalysisContext, register
from rosaadl.analysis.rendering import csv_text, fmt, short_path, table
from rosaadl.analysis.tasks import Dispatch, Processor, Scheduler, Task, TaskSet
from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.model import component_instances

__all__ = [
    "Placement",
    "CoreLoad",
    "DeploymentResult",
    "search_deployment",
]

log = logging.getLogger(__name__)

_US = 1_000_000


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


# =============================================================================== problem


@dataclass
class _Thread:
    path: str
    utilization: Fraction | None
    reference_mips: Fraction | None
    budget_mips: Fraction
    period_us: Fraction | None
    cet_us: Fraction | None
    deadline_us: Fraction | None
    priority: int
    dispatch: Dispatch


@dataclass
class _Process:
    path: str
    threads: list[_Thread]
    budget_mips: Fraction


@dataclass
class _Core:
    path: str
    capacity: Fraction
    scheduler: Scheduler
    preemptive: bool


class _Problem:
    def __init__(
        self,
        processes: list[_Process],
        cores: list[_Core],
        allowed: list[list[int]],
        schedulability: bool,
        reader: PropertyReader,
        times: list[dict[int, dict[str, Fraction]] | None] | None = None,
    ) -> None:
        self.processes = processes
        self.cores = cores
        self.allowed = allowed
        self.check_schedulability = schedulability
        self.reader = reader
        # times[p][c][thread path]: the execution time (us) of a thread of p on core c, when given
        self.times = times if times is not None else [None] * len(processes)
        # load[p][c]: the load process p puts on core c (None: it cannot run there)
        self.load = [
            [
                self._load(p, c) if self.times[i] is None else self._given_load(i, k)
                for k, c in enumerate(cores)
            ]
            for i, p in enumerate(processes)
        ]
        self._sched_cache: dict[tuple[int, tuple[int, ...]], bool] = {}
        self._tasks: dict[tuple[int, int], list[Task]] = {}
        self.sched_calls = 0

    def _load(self, process: _Process, core: _Core) -> Fraction | None:
        total = Fraction(0)
        demand_only = Fraction(0)
        for thread in process.threads:
            if thread.utilization is not None:
                if thread.reference_mips and core.capacity > 0:
                    total += thread.utilization * thread.reference_mips / core.capacity
                else:
                    total += thread.utilization
            elif thread.budget_mips > 0:
                demand_only += thread.budget_mips
        if total == 0 and demand_only == 0 and process.budget_mips > 0:
            demand_only = process.budget_mips
        if demand_only > 0:
            if core.capacity <= 0:
                return None
            total += demand_only / core.capacity
        return total

    def _given_load(self, process: int, core_index: int) -> Fraction | None:
        """Σ CET / Period with the execution times given for this core (None: not a candidate)."""
        given = self.times[process]
        cets = given.get(core_index) if given is not None else None
        if cets is None:
            return None
        total = Fraction(0)
        for thread in self.processes[process].threads:
            cet = cets.get(thread.path)
            if cet is not None and thread.period_us:
                total += cet / thread.period_us
        return total

    def scale(self, thread: _Thread, core: _Core) -> Fraction:
        if thread.reference_mips and core.capacity > 0:
            return thread.reference_mips / core.capacity
        return Fraction(1)

    def tasks(self, process: int, core_index: int) -> list[Task]:
        """The periodic threads of a process as tasks on a core (execution times scaled)."""
        key = (process, core_index)
        found = self._tasks.get(key)
        if found is not None:
            return found
        core = self.cores[core_index]
        given = self.times[process]
        cets = given.get(core_index, {}) if given is not None else None
        found = []
        for thread in self.processes[process].threads:
            cet = thread.cet_us if cets is None else cets.get(thread.path)
            if cet is None or thread.period_us is None or not thread.dispatch.recurrent:
                continue
            capacity = cet * (self.scale(thread, core) if cets is None else 1)
            if capacity <= 0:
                continue
            found.append(
                Task(
                    name=thread.path,
                    period=_exact(thread.period_us),
                    capacity=_exact(capacity),
                    deadline=_exact(thread.deadline_us) if thread.deadline_us is not None else None,
                    priority=thread.priority,
                    dispatch=thread.dispatch,
                    processor=core.path,
                    path=thread.path,
                )
            )
        self._tasks[key] = found
        return found

    def schedulable(self, core_index: int, members: tuple[int, ...]) -> bool:
        """Feasibility of the periodic threads of ``members`` on one core (cached): Cheddar's
        utilisation test when it accepts a preemptive core, else the full feasibility tests."""
        if not self.check_schedulability or not members:
            return True
        key = (core_index, members)
        cached = self._sched_cache.get(key)
        if cached is not None:
            return cached
        from rosaadl.analysis.schedulability import analyze_schedulability, utilization_test

        core = self.cores[core_index]
        tasks = [t for index in members for t in self.tasks(index, core_index)]
        verdict = True
        if tasks and not (core.preemptive and utilization_test(core.scheduler, True, tasks) is True):
            self.sched_calls += 1
            taskset = TaskSet(tuple(tasks), (Processor(core.path, core.scheduler, core.preemptive),))
            result = analyze_schedulability(taskset)
            verdict = all(d.schedulable is not False for d in result.domains)
        self._sched_cache[key] = verdict
        return verdict


def _exact(value: Fraction) -> int | Fraction:
    return value.numerator if value.denominator == 1 else value


# =============================================================================== search


class _Search:
    """Branch and bound (exact) and a bin-packing heuristic over one problem."""

    def __init__(self, problem: _Problem, node_limit: int) -> None:
        self.p = problem
        self.node_limit = node_limit
        self.nodes = 0
        self.best: list[int] | None = None
        self.best_key: tuple[Fraction, Fraction] | None = None
        self.complete = True
        n = len(problem.processes)
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
        n, m = len(problem.processes), len(problem.cores)
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
        n, m = len(problem.processes), len(problem.cores)
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


# =============================================================================== extraction


def _scheduler_of(reader: PropertyReader, core: Any) -> tuple[Scheduler, bool, bool]:
    """(scheduler, preemptive, given) from the core or the processor that contains it."""
    holders = [core]
    parent = core.eContainer()
    if parent is not None and category_of(parent) == "processor":
        holders.append(parent)
    for holder in holders:
        for name in ("Deployment_Properties::Scheduling_Protocol", "Cheddar_Properties::Scheduler"):
            value = reader.value(holder, name)
            items = value if isinstance(value, list) else [value] if value is not None else []
            for item in items:
                found = Scheduler.from_name(str(item))
                if found is not None:
                    preemptive = reader.value(holder, "Preemptive_Scheduler")
                    return found, preemptive if isinstance(preemptive, bool) else True, True
    return Scheduler.RATE_MONOTONIC, True, False


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
    from rosaadl import model as _model

    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = ResourceDemand(root, diagnostics)
    reader = analysis.reader
    mode = system_modes(root)[0]

    def resolve(items: Iterable[Any], what: str) -> list[Any]:
        out = []
        for item in items:
            if isinstance(item, str):
                try:
                    item = _model.find_instance(root, item)
                except ModelError as exc:
                    raise ModelError(f"{what}: {exc.message}", exc.location) from None
            if category_of(item) != what.split()[0]:
                raise ModelError(
                    f"{_model.instance_path(item)} is not a {what}", Location(path=_model.instance_path(item))
                )
            out.append(item)
        return out

    components = analysis.components()
    if processes is None:
        process_objs = [
            ci
            for ci in components
            if category_of(ci) == "process"
            and any(category_of(t) == "thread" for t in component_instances(ci, include_root=False))
            and mode.active(ci)
        ]
    else:
        process_objs = resolve(processes, "process")
    if processors is None:
        core_objs = [
            ci
            for ci in components
            if category_of(ci) == "processor"
            and not any(category_of(c) == "processor" for c in ci.componentInstances)
            and mode.active(ci)
        ]
    else:
        core_objs = resolve(processors, "processor")
    if not core_objs:
        raise ModelError("deployment search: the model has no processor to bind to", Location(path=root.name))

    proc_list = []
    for obj in process_objs:
        threads = []
        for t in component_instances(obj, include_root=False):
            if category_of(t) != "thread":
                continue
            load = analysis.thread_load(t, mode)
            dispatch = Dispatch.from_name(reader.enum(t, "Thread_Properties::Dispatch_Protocol", mode) or "")
            deadline = reader.seconds(t, "Timing_Properties::Deadline", mode)
            priority = reader.value(t, "Thread_Properties::Priority", mode)
            threads.append(
                _Thread(
                    path=load.path,
                    utilization=load.utilization,
                    reference_mips=analysis.reference_mips(t, mode),
                    budget_mips=reader.mips_budget(t, mode),
                    period_us=load.period_us,
                    cet_us=load.cet_us,
                    deadline_us=deadline * _US if deadline is not None and deadline > 0 else None,
                    priority=priority if isinstance(priority, int) and not isinstance(priority, bool) else 0,
                    dispatch=dispatch or Dispatch.PERIODIC,
                )
            )
        proc_list.append(_Process(_model.instance_path(obj), threads, reader.mips_budget(obj, mode)))
    core_list = []
    defaulted = []
    for obj in core_objs:
        scheduler, preemptive, given = _scheduler_of(reader, obj)
        if not given:
            defaulted.append(_model.instance_path(obj))
        core_list.append(
            _Core(_model.instance_path(obj), reader.mips_capacity(obj, mode), scheduler, preemptive)
        )
    if schedulability and defaulted:
        diagnostics.append(
            Diagnostic(
                "info",
                f"{len(defaulted)} candidate processors have no Scheduling_Protocol; "
                "schedulability is checked under preemptive rate monotonic scheduling",
                Location(path=defaulted[0]),
            )
        )
    index = {c.path: i for i, c in enumerate(core_list)}
    allowed_lists = []
    for proc in proc_list:
        wanted = (
            None if allowed is None else allowed.get(proc.path) or allowed.get(proc.path.partition(".")[2])
        )
        if wanted is None:
            allowed_lists.append(list(range(len(core_list))))
            continue
        chosen = []
        for path in wanted:
            key = path if path in index else f"{root.name}.{path}"
            if key not in index:
                raise ModelError(f"allowed core {path!r} of {proc.path} is not a candidate processor")
            chosen.append(index[key])
        allowed_lists.append(sorted(chosen))
    times = _given_times(root.name or "", proc_list, index, execution_times) if execution_times else None
    problem = _Problem(proc_list, core_list, allowed_lists, schedulability, reader, times)
    for p, proc in enumerate(proc_list):
        if all(problem.load[p][c] is None for c in allowed_lists[p]):
            diagnostics.append(
                Diagnostic(
                    "error",
                    "process demands MIPS (SEI::MIPSBudget) but no candidate processor has SEI::MIPSCapacity",
                    Location(path=proc.path),
                )
            )

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
                Location(path=root.name),
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
        root.name or "",
        method,
        optimal,
        feasible,
        tuple(placements),
        tuple(cores),
        unplaced,
        nodes,
        tuple(diagnostics),
    )


def _given_times(
    root: str,
    processes: list[_Process],
    cores: dict[str, int],
    given: Mapping[str, Mapping[str, Mapping[str, Any]]],
) -> list[dict[int, dict[str, Fraction]] | None]:
    """``execution_times`` as core index → thread path → CET in microseconds, per process."""

    def full(path: str, prefix: str) -> str:
        return path if path == prefix or path.startswith(prefix + ".") else f"{prefix}.{path}"

    by_path = {p.path: i for i, p in enumerate(processes)}
    out: list[dict[int, dict[str, Fraction]] | None] = [None] * len(processes)
    for process_path, per_core in given.items():
        index = by_path.get(full(process_path, root))
        if index is None:
            raise ModelError(f"execution times given for {process_path!r}, which is not a process searched")
        threads = {t.path for t in processes[index].threads}
        table: dict[int, dict[str, Fraction]] = {}
        for core_path, per_thread in per_core.items():
            core = cores.get(full(core_path, root))
            if core is None:
                raise ModelError(
                    f"execution times of {process_path!r} given for {core_path!r}, which is not a candidate "
                    "processor"
                )
            cets: dict[str, Fraction] = {}
            for thread_path, seconds in per_thread.items():
                path = full(thread_path, processes[index].path)
                if path not in threads:
                    raise ModelError(
                        f"execution time given for {thread_path!r}, not a thread of {process_path!r}"
                    )
                value = Fraction(str(seconds)) if isinstance(seconds, float) else Fraction(seconds)
                if value < 0:
                    raise ModelError(f"negative execution time for {thread_path!r} of {process_path!r}")
                cets[path] = value * _US
            table[core] = cets
        out[index] = table
    return out


def _key(problem: _Problem, assignment: Sequence[int]) -> tuple[Fraction, Fraction]:
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

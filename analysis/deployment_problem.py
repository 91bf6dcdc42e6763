"""The deployment problem read from an instance model: what may be bound where, and at what cost.

A *unit* (a process, or with ``granularity="thread"`` a thread) is to be bound to one *core* (a
processor without processor subcomponents). :func:`deployment_problem` reads, in the instance's
first system mode:

* **load** ``load[u][c]``: the CPU load unit ``u`` puts on core ``c``, exactly as the CPU load
  analysis computes it (:mod:`rosaadl.analysis.resources`, OSATE's MIPS semantics): a thread's
  ``CET / Period``, scaled by ``Reference_Processor`` MIPS over the core's ``SEI::MIPSCapacity``
  when the model gives one; a unit that only demands MIPS counts with its ``SEI::MIPSBudget``;
  execution times given per core type (a library node's PDMs) replace the scaled ones and make the
  unit a candidate of those cores only. None: the unit cannot run there.
* **schedulability** of a set of units on a core (:meth:`DeploymentProblem.schedulable`):
  Cheddar's utilisation test when it accepts, else the feasibility tests of
  :mod:`rosaadl.analysis.schedulability` (response-time analysis where the core has priorities)
  under the core's ``Scheduling_Protocol`` (preemptive rate monotonic when it has none).
* **candidates**: ``Allowed_Processor_Binding`` of the unit (or of the process holding a thread),
  a processor or system standing for the cores inside it and a virtual processor for the core it
  runs on (then named by the binding, :meth:`DeploymentProblem.target`), and
  ``Allowed_Processor_Binding_Class`` (cores whose classifier is or extends one listed, OSATE's
  binding check), intersected with the caller's
  ``allowed`` and with the board of every device the unit is connected to (the **pins**,
  :func:`~rosaadl.analysis.deployment_links.device_pins`; the ``Allowed_Processor_Binding``
  restrictions are listed as pins too); the **current binding** from ``Actual_Processor_Binding``
  (the moves objective; a process whose threads are bound, not itself, is where its threads are;
  the threads bound otherwise than their unit are kept in ``bound_inside``, for the proposal to
  restate).
* **boards**: a core's board is its nearest enclosing system below the root, else its outermost
  enclosing processor, else the core itself. Units on different boards talk over the bus.
* **memory**: a unit's RAM (Data + Heap + Stack size of its subtree, else ``SEI::RAMBudget``)
  against its board's memories (``Memory_Size``, else ``SEI::RAMCapacity``, summed).
* **traffic**: the KByte/s of the port connections between two units (``Data_Size`` × message
  rate at the source, as the bus load analysis computes a connection's actual bandwidth, without
  protocol overhead); it loads the bus when the two units are on different boards, against the
  smallest ``SEI::BandWidthCapacity`` of the model's buses (one network carries every topic).
* **chains**: the executor analysis's cause-effect chains, each as a fixed part plus the
  transmission of its topics that cross boards (:mod:`rosaadl.analysis.deployment_links`);
  :meth:`DeploymentProblem.longest_chain` gives the longest under a binding.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rosaadl.analysis.busload import data_size_kbyte, message_rate
from rosaadl.analysis.demand import ResourceDemand
from rosaadl.analysis.deployment_links import ChainCost, Pin, chain_costs, device_pins
from rosaadl.analysis.deployment_targets import (
    bound_inside,
    classes_up,
    classifier_name,
    covered_cores,
    declared_up,
    of_class,
)
from rosaadl.analysis.instance_values import (
    PropertyReader,
    category_of,
    instance_root,
    relative_path,
    system_modes,
)
from rosaadl.analysis.tasks import Dispatch, Processor, Scheduler, Task, TaskSet
from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.model import (
    component_instances,
    find_instance,
    instance_path,
    walk,
)

__all__ = [
    "CandidateCore",
    "DeploymentProblem",
    "Evaluation",
    "Unit",
    "UnitThread",
    "deployment_problem",
]

_US = 1_000_000
_LN2_BELOW = 0.6931  #: below ln 2 = 0.693147..., with room for the rounding of the float sums


@dataclass
class UnitThread:
    """A thread of a unit, with what its load and its task on a core need."""

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
class Unit:
    """What is bound: a process (or a thread), its threads, its MIPS budget and RAM (KByte)."""

    path: str
    threads: list[UnitThread]
    budget_mips: Fraction
    memory_kbyte: Fraction = Fraction(0)


@dataclass
class CandidateCore:
    """A core units may be bound to: its MIPS, scheduler, board and classifier."""

    path: str
    capacity: Fraction
    scheduler: Scheduler
    preemptive: bool
    board: str = ""
    kind: str = ""


@dataclass(frozen=True)
class Evaluation:
    """One binding measured exactly: core loads, bus traffic, moves, and what it breaks."""

    loads: tuple[Fraction, ...]
    bus_kbyteps: Fraction
    moves: int
    violations: tuple[str, ...]
    latency_us: Fraction | None = None  #: the longest chain's latency (None: the model has no chain)

    @property
    def max_load(self) -> Fraction:
        return max(self.loads, default=Fraction(0))

    @property
    def feasible(self) -> bool:
        return not self.violations


@dataclass
class DeploymentProblem:
    """Units, cores and the costs of binding one to the other (see the module)."""

    root: str
    units: list[Unit]
    cores: list[CandidateCore]
    allowed: list[list[int]]
    check_schedulability: bool = True
    times: list[dict[int, dict[str, Fraction]] | None] | None = None
    current: list[frozenset[int]] = field(default_factory=list)
    board_memory: dict[str, Fraction] = field(default_factory=dict)
    traffic: list[tuple[int, int, Fraction]] = field(default_factory=list)
    bus_capacity: Fraction | None = None
    diagnostics: list[Diagnostic] = field(default_factory=list)
    chains: list[ChainCost] = field(default_factory=list)
    pins: list[Pin] = field(default_factory=list)
    #: (unit, core) -> the virtual processor on that core the unit is bound to (its
    #: ``Allowed_Processor_Binding`` names it); by default a unit is bound to the core itself
    targets: dict[tuple[int, int], str] = field(default_factory=dict)
    #: unit -> the paths of its threads bound otherwise than the unit (their own
    #: ``Actual_Processor_Binding`` beats the one they inherit: a proposal must restate it)
    bound_inside: dict[int, tuple[str, ...]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.times is None:
            self.times = [None] * len(self.units)
        if not self.current:
            self.current = [frozenset()] * len(self.units)
        self.load: list[list[Fraction | None]] = [
            [
                _load(u, c) if self.times[i] is None else self._given_load(i, k)
                for k, c in enumerate(self.cores)
            ]
            for i, u in enumerate(self.units)
        ]
        self._float_load = [[float(x) if x is not None else 0.0 for x in row] for row in self.load]
        self._sched_cache: dict[tuple[int, tuple[int, ...]], bool] = {}
        self._tasks: dict[tuple[int, int], list[Task]] = {}
        self.sched_calls = 0

    # ------------------------------------------------------------------ loads and tasks

    def candidates(self, unit: int) -> list[int]:
        """The cores ``unit`` may go to: allowed, and with a load there."""
        return [c for c in self.allowed[unit] if self.load[unit][c] is not None]

    def target(self, unit: int, core: int) -> str:
        """The path ``Actual_Processor_Binding`` names when ``unit`` runs on ``core``: the core, or
        the virtual processor on it that the unit's ``Allowed_Processor_Binding`` names."""
        return self.targets.get((unit, core), self.cores[core].path)

    def boards(self) -> list[str]:
        """The boards, in core order."""
        return list(dict.fromkeys(c.board for c in self.cores))

    def _given_load(self, unit: int, core_index: int) -> Fraction | None:
        """Σ CET / Period with the execution times given for this core (None: not a candidate)."""
        given = self.times[unit] if self.times else None
        cets = given.get(core_index) if given is not None else None
        if cets is None:
            return None
        total = Fraction(0)
        for thread in self.units[unit].threads:
            cet = cets.get(thread.path)
            if cet is not None and thread.period_us:
                total += cet / thread.period_us
        return total

    def tasks(self, unit: int, core_index: int) -> list[Task]:
        """The periodic threads of a unit as tasks on a core (execution times scaled)."""
        key = (unit, core_index)
        found = self._tasks.get(key)
        if found is not None:
            return found
        core = self.cores[core_index]
        given = self.times[unit] if self.times else None
        cets = given.get(core_index, {}) if given is not None else None
        found = []
        for thread in self.units[unit].threads:
            cet = thread.cet_us if cets is None else cets.get(thread.path)
            if cet is None or thread.period_us is None or not thread.dispatch.recurrent:
                continue
            capacity = cet * (_scale(thread, core) if cets is None else 1)
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
        core = self.cores[core_index]
        # the load bounds the tasks' utilisation from above; at most ln 2 (below Liu and
        # Layland's bound for any number of tasks) the utilisation test accepts, as below
        if (
            core.preemptive
            and core.scheduler is Scheduler.RATE_MONOTONIC
            and sum(self._float_load[u][core_index] for u in members) <= _LN2_BELOW
        ):
            return True
        key = (core_index, members)
        cached = self._sched_cache.get(key)
        if cached is not None:
            return cached
        from rosaadl.analysis.schedulability import analyze_schedulability, utilization_test

        tasks = [t for index in members for t in self.tasks(index, core_index)]
        verdict = True
        if tasks and not (core.preemptive and utilization_test(core.scheduler, True, tasks) is True):
            self.sched_calls += 1
            taskset = TaskSet(tuple(tasks), (Processor(core.path, core.scheduler, core.preemptive),))
            result = analyze_schedulability(taskset)
            verdict = all(d.schedulable is not False for d in result.domains)
        self._sched_cache[key] = verdict
        return verdict

    # ------------------------------------------------------------------ a binding measured

    def members(self, assignment: Sequence[int]) -> list[tuple[int, ...]]:
        """The units on each core (sorted) under ``assignment`` (-1: unplaced)."""
        out: list[list[int]] = [[] for _ in self.cores]
        for u, c in enumerate(assignment):
            if c >= 0:
                out[c].append(u)
        return [tuple(m) for m in out]

    def evaluate(self, assignment: Sequence[int]) -> Evaluation:
        """Exact core loads, crossing traffic, moves and broken constraints of ``assignment``."""
        members = self.members(assignment)
        loads = tuple(
            sum((self.load[u][c] or Fraction(0) for u in inside), Fraction(0))
            for c, inside in enumerate(members)
        )
        violations = []
        for u, c in enumerate(assignment):
            if c < 0:
                violations.append(f"{self.units[u].path} is not placed")
            elif c not in self.allowed[u] or self.load[u][c] is None:
                violations.append(f"{self.units[u].path} cannot run on {self.cores[c].path}")
        for c, inside in enumerate(members):
            if loads[c] > 1:
                violations.append(f"{self.cores[c].path} is loaded {float(loads[c] * 100):.1f} %")
            elif inside and not self.schedulable(c, inside):
                violations.append(f"{self.cores[c].path} is not schedulable")
        used: dict[str, Fraction] = {}
        for u, c in enumerate(assignment):
            if c >= 0:
                board = self.cores[c].board
                used[board] = used.get(board, Fraction(0)) + self.units[u].memory_kbyte
        for board, kbyte in used.items():
            capacity = self.board_memory.get(board)
            if capacity is not None and kbyte > capacity:
                violations.append(f"{board} needs {float(kbyte):.1f} KByte of {float(capacity):.1f} KByte")
        bus = self.bus_traffic(assignment)
        if self.bus_capacity is not None and bus > self.bus_capacity:
            violations.append(
                f"the bus carries {float(bus):.1f} KByte/s of {float(self.bus_capacity):.1f} KByte/s"
            )
        moves = sum(
            1 for u, c in enumerate(assignment) if self.current[u] and c >= 0 and c not in self.current[u]
        )
        return Evaluation(loads, bus, moves, tuple(violations), self.longest_chain(assignment))

    def longest_chain(self, assignment: Sequence[int]) -> Fraction | None:
        """The latency (µs) of the longest chain under ``assignment`` (None: no chain)."""
        if not self.chains:
            return None

        def board(u: int) -> str | None:
            return self.cores[assignment[u]].board if assignment[u] >= 0 else None

        return max(chain.latency(board) for chain in self.chains)

    def bus_traffic(self, assignment: Sequence[int]) -> Fraction:
        """KByte/s of the connections between units placed on different boards."""
        total = Fraction(0)
        for u, v, rate in self.traffic:
            cu, cv = assignment[u], assignment[v]
            if cu >= 0 and cv >= 0 and self.cores[cu].board != self.cores[cv].board:
                total += rate
        return total


def _load(unit: Unit, core: CandidateCore) -> Fraction | None:
    total = Fraction(0)
    demand_only = Fraction(0)
    for thread in unit.threads:
        if thread.utilization is not None:
            if thread.reference_mips and core.capacity > 0:
                total += thread.utilization * thread.reference_mips / core.capacity
            else:
                total += thread.utilization
        elif thread.budget_mips > 0:
            demand_only += thread.budget_mips
    if total == 0 and demand_only == 0 and unit.budget_mips > 0:
        demand_only = unit.budget_mips
    if demand_only > 0:
        if core.capacity <= 0:
            return None
        total += demand_only / core.capacity
    return total


def _scale(thread: UnitThread, core: CandidateCore) -> Fraction:
    if thread.reference_mips and core.capacity > 0:
        return thread.reference_mips / core.capacity
    return Fraction(1)


def _exact(value: Fraction) -> int | Fraction:
    return value.numerator if value.denominator == 1 else value


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


def _board_of(core: Any, root: Any) -> Any:
    """The nearest enclosing system below the root, else the outermost processor, else the core."""
    outer_processor = None
    parent = core.eContainer()
    while parent is not None and parent is not root:
        kind = category_of(parent)
        if kind == "system":
            return parent
        if kind == "processor":
            outer_processor = parent
        parent = parent.eContainer()
    return outer_processor if outer_processor is not None else core


def _resolve(root: Any, items: Iterable[Any], what: str) -> list[Any]:
    out = []
    for item in items:
        if isinstance(item, str):
            try:
                item = find_instance(root, item)
            except ModelError as exc:
                raise ModelError(f"{what}: {exc.message}", exc.location) from None
        if category_of(item) != what.split()[0]:
            raise ModelError(f"{instance_path(item)} is not a {what}", Location(path=instance_path(item)))
        out.append(item)
    return out


def _has_demand(process: Any, analysis: ResourceDemand, mode: Any) -> bool:
    """Whether a process is searched: it has threads, or a MIPS or RAM budget (a process
    budgeted before its threads are modelled)."""
    return (
        any(category_of(t) == "thread" for t in component_instances(process, include_root=False))
        or analysis.reader.mips_budget(process, mode) > 0
        or analysis.memory_budget(process, "RAM", mode) > 0
    )


def deployment_problem(
    source: Any,
    processes: Iterable[Any] | None = None,
    processors: Iterable[Any] | None = None,
    *,
    allowed: Mapping[str, Iterable[str]] | None = None,
    schedulability: bool = True,
    execution_times: Mapping[str, Mapping[str, Mapping[str, Any]]] | None = None,
    granularity: str = "process",
) -> DeploymentProblem:
    """The deployment problem of an instance (see the module). ``processes`` (instances or paths;
    default: every active process with threads, or without threads but with an
    ``SEI::MIPSBudget`` or ``SEI::RAMBudget``: a process budgeted before its threads are
    modelled) and ``processors`` (default: every active core) narrow it; ``allowed`` maps unit
    paths (with or without the root's name) to the core paths it may take; ``execution_times``
    gives process path → core path → thread path → CET in seconds for units measured per core
    type (those run only on the cores listed)."""
    if granularity not in ("process", "thread"):
        raise ModelError(f"unknown granularity {granularity!r} (process, thread)")
    root = instance_root(source)
    diagnostics: list[Diagnostic] = []
    analysis = ResourceDemand(root, diagnostics)
    reader = analysis.reader
    mode = system_modes(root)[0]
    components = analysis.components()
    if processes is None:
        process_objs = [
            ci
            for ci in components
            if category_of(ci) == "process" and mode.active(ci) and _has_demand(ci, analysis, mode)
        ]
        asleep = [
            instance_path(ci)
            for ci in components
            if category_of(ci) in ("process", "processor")
            and not mode.active(ci)
            and (category_of(ci) == "processor" or _has_demand(ci, analysis, mode))
        ]
        if asleep:
            diagnostics.append(
                Diagnostic(
                    "warning",
                    f"the deployment is searched in the first system mode {mode.label or mode.name}: "
                    f"{len(asleep)} processes and processors of other modes are left as they are "
                    f"bound ({', '.join(p.partition('.')[2] for p in asleep[:5])}"
                    f"{', ...' if len(asleep) > 5 else ''})",
                    Location(path=asleep[0]),
                )
            )
    else:
        process_objs = _resolve(root, processes, "process")
    if processors is None:
        core_objs = [
            ci
            for ci in components
            if category_of(ci) == "processor"
            and not any(category_of(c) == "processor" for c in ci.componentInstances)
            and mode.active(ci)
        ]
    else:
        core_objs = _resolve(root, processors, "processor")
    if not core_objs:
        raise ModelError("deployment search: the model has no processor to bind to", Location(path=root.name))

    def thread_of(t: Any) -> UnitThread:
        load = analysis.thread_load(t, mode)
        dispatch = Dispatch.from_name(reader.enum(t, "Thread_Properties::Dispatch_Protocol", mode) or "")
        deadline = reader.seconds(t, "Timing_Properties::Deadline", mode)
        priority = reader.value(t, "Thread_Properties::Priority", mode)
        return UnitThread(
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

    def memory(obj: Any) -> Fraction:
        subtree = component_instances(obj)
        actual = sum((analysis.memory_actual(c, "RAM", mode) for c in subtree), Fraction(0))
        return actual if actual > 0 else analysis.memory_budget(obj, "RAM", mode)

    unit_objs: list[Any] = []
    unit_threads: list[list[Any]] = []  # the threads inside each unit (none for a thread unit)
    units: list[Unit] = []
    for obj in process_objs:
        threads = [t for t in component_instances(obj, include_root=False) if category_of(t) == "thread"]
        if granularity == "thread" and threads:
            for t in threads:
                unit_objs.append(t)
                unit_threads.append([])
                units.append(Unit(instance_path(t), [thread_of(t)], reader.mips_budget(t, mode), memory(t)))
        else:
            unit_objs.append(obj)
            unit_threads.append(threads)
            units.append(
                Unit(
                    instance_path(obj),
                    [thread_of(t) for t in threads],
                    reader.mips_budget(obj, mode),
                    memory(obj),
                )
            )

    cores = []
    defaulted = []
    boards: dict[str, Any] = {}
    for obj in core_objs:
        scheduler, preemptive, given = _scheduler_of(reader, obj)
        if not given:
            defaulted.append(instance_path(obj))
        board = _board_of(obj, root)
        boards[instance_path(board)] = board
        cores.append(
            CandidateCore(
                instance_path(obj),
                reader.mips_capacity(obj, mode),
                scheduler,
                preemptive,
                instance_path(board),
                classifier_name(obj) or classifier_name(obj.eContainer()),
            )
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
    index = {c.path: i for i, c in enumerate(cores)}
    bindings = analysis.bindings
    class_cover: dict[str, dict[int, str | None]] = {}  # classes named -> the cores they cover
    allowed_lists = []
    current = []
    targets: dict[tuple[int, int], str] = {}
    restated: dict[int, tuple[str, ...]] = {}
    pins = device_pins(root, unit_objs, [c.path for c in cores], mode)
    for u, (unit, obj) in enumerate(zip(units, unit_objs, strict=True)):
        chosen = set(range(len(cores)))
        declared = declared_up(reader, obj, "Allowed_Processor_Binding", mode, root)
        classes = classes_up(reader, obj, mode, root)
        restrictions = [(declared, classes, "")]
        # a thread's own restriction holds for the process it is bound with (OSATE checks threads)
        declared_paths = [instance_path(t) for t in declared]
        for thread in unit_threads[u]:
            mine = reader.targets(thread, "Allowed_Processor_Binding", mode) or []
            kinds = classes_up(reader, thread, mode, obj)
            if mine and [instance_path(t) for t in mine] != declared_paths:
                restrictions.append((mine, [], f" of {relative_path(thread)}"))
            if kinds and kinds != classes:
                restrictions.append(([], kinds, f" of {relative_path(thread)}"))
        limits = []  # (the cores they cover, with virtual processors; what names them; property)
        for targets_, classes_, holder in restrictions:
            if targets_:
                covered = covered_cores(targets_, index, bindings, mode)
                names = ", ".join(instance_path(t) for t in targets_)
                limits.append((covered, names, f"Allowed_Processor_Binding{holder}"))
            if classes_:
                names = ", ".join(str(c) for c in classes_)
                if names not in class_cover:  # the same classes for many units: one walk
                    class_cover[names] = covered_cores(of_class(root, classes_, mode), index, bindings, mode)
                limits.append((class_cover[names], names, f"Allowed_Processor_Binding_Class{holder}"))
        for covered, names, by in limits:
            chosen &= set(covered)
            for k, vp in covered.items():
                if vp is not None:
                    targets.setdefault((u, k), vp)
            pins.append(Pin(u, names, "", tuple(sorted(covered)), by))
        for pin in pins:
            if pin.unit == u and pin.device:
                chosen &= set(pin.cores)
        wanted = (
            None if allowed is None else allowed.get(unit.path) or allowed.get(unit.path.partition(".")[2])
        )
        if wanted is not None:
            given = set()
            for path in wanted:
                key = path if path in index else f"{root.name}.{path}"
                if key not in index:
                    raise ModelError(f"allowed core {path!r} of {unit.path} is not a candidate processor")
                given.add(index[key])
            chosen &= given
        allowed_lists.append(sorted(chosen))
        own = declared_up(reader, obj, "Actual_Processor_Binding", mode, root)
        actual = covered_cores(own, index, bindings, mode)
        inside = bound_inside(reader, unit_threads[u], own, mode)
        if inside:
            restated[u] = tuple(instance_path(t) for t, _targets in inside)
            if not actual:  # the threads are bound, not the process: where they are now
                for _t, found in inside:
                    for k, vp in covered_cores(found, index, bindings, mode).items():
                        actual.setdefault(k, vp)
        current.append(frozenset(actual))
        if not declared:  # a unit that stays on its core keeps its partition there
            for k, vp in actual.items():
                if vp is not None:
                    targets.setdefault((u, k), vp)
    times = None
    if execution_times:
        if granularity != "process":
            raise ModelError(
                "execution times per core type are given per process: use the process granularity"
            )
        times = _given_times(root.name or "", units, index, execution_times)
    board_memory = {}
    for path, board in boards.items():
        capacity = Fraction(0)
        for ci in component_instances(board):
            if category_of(ci) == "memory" and mode.active(ci):
                size = reader.size_kbyte(ci, "Memory_Properties::Memory_Size", mode)
                if size is None:
                    size = reader.size_kbyte(ci, "SEI::RAMCapacity", mode)
                capacity += size or Fraction(0)
        if capacity > 0:
            board_memory[path] = capacity
    problem = DeploymentProblem(
        root.name or "",
        units,
        cores,
        allowed_lists,
        schedulability,
        times,
        current,
        board_memory,
        _traffic(root, unit_objs, reader, mode),
        _bus_capacity(components, reader, mode),
        diagnostics,
        chain_costs(root, unit_objs, mode),
        sorted(pins, key=lambda p: (p.unit, p.device, p.board)),
        {key: vp for key, vp in targets.items() if key[1] in allowed_lists[key[0]]},
        restated,
    )
    for u, unit in enumerate(units):
        if allowed_lists[u] and all(problem.load[u][c] is None for c in allowed_lists[u]):
            diagnostics.append(
                Diagnostic(
                    "error",
                    "process demands MIPS (SEI::MIPSBudget) but no candidate processor has SEI::MIPSCapacity",
                    Location(path=unit.path),
                )
            )
    return problem


def _traffic(
    root: Any, unit_objs: list[Any], reader: PropertyReader, mode: Any
) -> list[tuple[int, int, Fraction]]:
    """(unit, unit, KByte/s) of the port connections between two different units."""
    owner = {id(obj): u for u, obj in enumerate(unit_objs)}

    def unit_of(feature: Any) -> int | None:
        obj = feature
        while obj is not None and obj is not root:
            found = owner.get(id(obj))
            if found is not None:
                return found
            obj = obj.eContainer()
        return None

    pairs: dict[tuple[int, int], Fraction] = {}
    for obj in walk(root):
        if type(obj).__name__ != "ConnectionInstance" or obj.source is None or obj.destination is None:
            continue
        if not mode.active(obj):
            continue
        u, v = unit_of(obj.source), unit_of(obj.destination)
        if u is None or v is None or u == v or hasattr(obj.source, "componentInstances"):
            continue
        size = data_size_kbyte(reader, obj.source, mode) or Fraction(0)
        rate = size * message_rate(reader, obj.source, mode)
        if rate > 0:
            key = (min(u, v), max(u, v))
            pairs[key] = pairs.get(key, Fraction(0)) + rate
    return [(u, v, rate) for (u, v), rate in sorted(pairs.items())]


def _bus_capacity(components: list[Any], reader: PropertyReader, mode: Any) -> Fraction | None:
    capacities = [
        reader.number(ci, "SEI::BandWidthCapacity", "KBytesps", mode)
        for ci in components
        if category_of(ci) == "bus" and mode.active(ci)
    ]
    found = [c for c in capacities if c is not None and c > 0]
    return min(found) if found else None


def _given_times(
    root: str,
    units: list[Unit],
    cores: dict[str, int],
    given: Mapping[str, Mapping[str, Mapping[str, Any]]],
) -> list[dict[int, dict[str, Fraction]] | None]:
    """``execution_times`` as core index → thread path → CET in microseconds, per unit."""

    def full(path: str, prefix: str) -> str:
        return path if path == prefix or path.startswith(prefix + ".") else f"{prefix}.{path}"

    by_path = {p.path: i for i, p in enumerate(units)}
    out: list[dict[int, dict[str, Fraction]] | None] = [None] * len(units)
    for process_path, per_core in given.items():
        index = by_path.get(full(process_path, root))
        if index is None:
            raise ModelError(f"execution times given for {process_path!r}, which is not a process searched")
        threads = {t.path for t in units[index].threads}
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
                path = full(thread_path, units[index].path)
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

"""How every benchmark measures and reports: best of N rounds, CPU and wall time, peak memory, one row.

One policy for all benchmarks of ``benchmarks/``:

* **Time.** A round calls the action once and reads both ``time.process_time`` (the CPU time of
  this process, the figure that counts on a shared machine, where other processes stretch the
  wall clock) and ``time.perf_counter`` (wall clock); the lowest of each over the rounds is
  kept, since the noise of a shared machine only ever adds time. Goals are judged on CPU time.
* **Garbage.** ``gc.collect()`` before each round, outside the measure, so that every round
  starts from the same heap: pyecore objects live in reference cycles, and only the collector
  frees the models of the rounds before. The collector stays enabled during the round: the
  collections an action triggers are part of its cost, as they are for a user, and the readers
  that pause the collector do so themselves (``rosaadl.bulk.gc_paused``), which is then what is
  measured. Pausing it here would hide a cost every user pays and make the figures incomparable
  with the ones measured before this harness.
* **Memory.** The peak resident memory of a round above the memory resident at its start, in
  MiB: Linux's ``VmHWM`` after resetting it through ``/proc/self/clear_refs``, read outside the
  measure. Not ``tracemalloc``: it sees Python's allocator only (not lxml's libxml2 trees, most
  of the memory of the XML readers and of their floor) and slows allocation-heavy code several
  times, so it could not run in the timed rounds. Not ``ru_maxrss`` alone: it is the high-water
  mark of the whole life of the process (carried across ``exec`` even), so every measure after
  the largest one would read that one's peak. Where the reset is not available, no peak.
* **Processes.** ``python -m benchmarks`` runs each benchmark module in its own process (one run
  after others would inherit their heap: every ``gc.collect()`` traverses it too).
* **Side by side.** :func:`alternate` measures a floor and ours (or two tools) in alternating
  blocks of as many calls each, so that both see the same drift of the machine's speed and have
  as many draws at a low time.

Every module reports its figures as :class:`Row` objects through a :class:`Report`, which prints
them in the one table format and, when ``python -m benchmarks`` runs the module, hands them back
as JSON (the file named by ``$ROSAADL_BENCH_ROWS``) for the table that gathers every module.
"""

from __future__ import annotations

import gc
import json
import math
import os
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

__all__ = [
    "ROWS_ENV",
    "Goal",
    "Report",
    "Row",
    "Timing",
    "alternate",
    "best_of",
    "format_table",
    "process_peak_mib",
    "read_rows",
    "reset_peak",
    "status_kib",
]

ROWS_ENV = "ROSAADL_BENCH_ROWS"
_STATUS = Path("/proc/self/status")
_CLEAR_REFS = Path("/proc/self/clear_refs")


# --------------------------------------------------------------------------- memory


def status_kib(key: str) -> int | None:
    """A field of ``/proc/self/status`` in KiB (``"VmRSS:"``, ``"VmHWM:"``); None off Linux."""
    try:
        with _STATUS.open() as status:
            for line in status:
                if line.startswith(key):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return None


def reset_peak() -> int | None:
    """Reset the resident high-water mark to the resident memory now; that memory in KiB, or None
    where the kernel offers no reset."""
    try:
        _CLEAR_REFS.write_text("5")
    except OSError:
        return None
    return status_kib("VmRSS:")


def process_peak_mib() -> float:
    """This process's peak resident memory (MiB) since it started or since the last measure.

    ``VmHWM`` belongs to the process image, so it starts afresh at ``exec``; ``ru_maxrss`` (the
    fallback off Linux) would carry the parent's high-water mark into the child."""
    peak = status_kib("VmHWM:")
    if peak is None:
        import resource

        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak / 1024


# --------------------------------------------------------------------------- timing


@dataclass
class Timing:
    """What the rounds of one action measured: the lowest CPU and wall seconds of a call, the
    CPU seconds of every call, the lowest peak memory of a call above its start (MiB, None where
    not measured), and the result of the last call."""

    cpu: float = math.inf
    wall: float = math.inf
    cpu_calls: list[float] = field(default_factory=list)
    peak_mib: float | None = None
    settled_cpu: float = math.inf
    result: Any = field(default=None, repr=False, compare=False)

    @property
    def calls(self) -> int:
        return len(self.cpu_calls)

    def _call(self, action: Callable[..., Any], args: tuple, memory: bool, keep: bool) -> float:
        self.result = None  # the previous round's result is not part of this round's heap
        gc.collect()
        start_rss = reset_peak() if memory else None
        start_wall, start_cpu = time.perf_counter(), time.process_time()
        result = action(*args)
        cpu = time.process_time() - start_cpu
        wall = time.perf_counter() - start_wall
        if keep:
            self.result = result
        del result
        if start_rss is not None:
            peak = status_kib("VmHWM:")
            if peak is not None:
                grown = max(0, peak - start_rss) / 1024
                self.peak_mib = grown if self.peak_mib is None else min(self.peak_mib, grown)
        self.cpu, self.wall = min(self.cpu, cpu), min(self.wall, wall)
        self.cpu_calls.append(cpu)
        return cpu


def best_of(
    action: Callable[..., Any],
    rounds: int = 3,
    *,
    setup: Callable[[], Any] | None = None,
    memory: bool = True,
    keep: bool = True,
) -> Timing:
    """Call ``action`` ``rounds`` times (at least once), each after ``gc.collect()``, and keep the
    best CPU and wall times and the last result (each round's result is let go before the next
    round); ``setup``, when given, is called before each round outside the
    measure and its result passed to ``action`` (what must not be timed: a fresh resource set,
    say). ``memory=False`` leaves out the peak memory; ``keep=False`` lets the last result go
    too, for timings kept in rows while the next inputs are measured (a model kept in a row would
    be traversed by every ``gc.collect()`` after it, and slow down every measure that follows)."""
    timing = Timing()
    for _ in range(max(1, rounds)):
        args = () if setup is None else (setup(),)
        timing._call(action, args, memory, keep=keep)
    return timing


def alternate(
    actions: Mapping[str, Callable[[], Any]],
    rounds: int = 4,
    *,
    min_calls: int = 1,
    min_seconds: float = 0.0,
    max_calls: int = 1000,
    memory: bool = True,
) -> dict[str, Timing]:
    """Best times of several actions measured side by side, in alternating blocks of calls.

    In each round the first action makes a block of back-to-back calls: at least ``min_calls``,
    more until its calls have taken ``min_seconds`` of CPU time (at most ``max_calls``); each of
    the others then makes as many calls. The blocks alternate, ``rounds`` times, so that all see
    the same drift of the machine's speed. The bests are minima, and a minimum over more calls is
    lower only for having had more draws: on a sub-millisecond file, whose times spread over
    2-3x on a shared machine, a floor given 3-4x the calls of ours (as a time budget per block
    gives it) came out up to 10 % lower than over as many calls as ours. Each call is collected
    before as :func:`best_of` does. ``Timing.settled_cpu`` is the best over the calls that follow
    a call of the same action (each block but its first call): for large inputs the first call
    after another action runs on memory that action left consolidated, and differs. The results
    are not kept (``Timing.result`` is None): one action's result would be on the heap the
    others' calls run on and collect.
    """
    timings = {name: Timing() for name in actions}
    for _ in range(max(1, rounds)):
        block: int | None = None  # how many calls the first action made in this round
        for name, action in actions.items():
            timing, spent, calls = timings[name], 0.0, 0
            while True:
                if block is None:
                    if calls >= min_calls and (spent >= min_seconds or calls >= max_calls):
                        break
                elif calls >= block:
                    break
                cpu = timing._call(action, (), memory, keep=False)
                if calls:
                    timing.settled_cpu = min(timing.settled_cpu, cpu)
                spent += cpu
                calls += 1
            block = calls
    return timings


# --------------------------------------------------------------------------- goals and rows


@dataclass(frozen=True)
class Goal:
    """A bound the figure (``on="ours"``) or the ratio ours / reference (``on="ratio"``) must
    keep: at most (``at_most=True``) or at least ``bound``; ``says`` is how the issue words it."""

    bound: float
    on: str = "ours"
    at_most: bool = True
    says: str = ""

    def met(self, row: Row) -> bool | None:
        value = row.ours if self.on == "ours" else row.ratio
        if value is None:
            return None
        return value <= self.bound if self.at_most else value >= self.bound

    def text(self, unit: str) -> str:
        sign = "<=" if self.at_most else ">="
        bound = _number(self.bound, unit) if self.on == "ours" else f"{self.bound:.3g}x"
        return f"{sign} {bound}" + (f" ({self.says})" if self.says else "")


@dataclass
class Row:
    """One figure of a benchmark: what is measured, ours, the reference it is set against (the
    floor, or the other tool), their ratio (ours / reference), the goal, whether it is met.

    ``unit`` is ``"s"`` for times (CPU seconds; ``wall`` the wall-clock seconds beside them), a
    rate such as ``"MB/s"``, or ``""`` for counts and pure numbers. ``detail`` rows (per corpus
    file, say) show in the module's own table only, not in the table ``make bench`` gathers."""

    measure: str
    ours: float | None
    unit: str = "s"
    reference: float | None = None
    against: str = ""
    goal: Goal | None = None
    wall: float | None = None
    peak_mib: float | None = None
    note: str = ""
    detail: bool = False
    module: str = ""

    @property
    def ratio(self) -> float | None:
        if self.ours is None or not self.reference:
            return None
        return self.ours / self.reference

    @property
    def verdict(self) -> str:
        if self.goal is None:
            return ""
        met = self.goal.met(self)
        return "n/a" if met is None else ("ok" if met else "MISSED")

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Row:
        values = dict(data)
        if values.get("goal") is not None:
            values["goal"] = Goal(**values["goal"])
        return cls(**values)


def _number(value: float | None, unit: str) -> str:
    if value is None:
        return "-"
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if unit == "s":
        if value >= 100:
            return f"{value:.0f} s"
        if value >= 1:
            return f"{value:.2f} s"
        if value >= 0.01:
            return f"{value * 1000:.0f} ms"
        return f"{value * 1000:.2f} ms"
    if unit == "":
        return f"{value:.0f}" if float(value).is_integer() else f"{value:.2f}"
    if value >= 1000:
        return f"{value:,.0f} {unit}"
    return f"{value:.2f} {unit}"


_COLUMNS = ("measure", "ours", "wall", "reference", "ratio", "goal", "met", "peak MiB", "note")


def format_table(rows: Iterable[Row], *, modules: bool = False) -> str:
    """The one table: measure, ours, wall, reference, ratio, goal, met, peak memory, note; with
    ``modules``, each row's module before its measure."""
    lines = []
    for row in rows:
        measure = f"{row.module}: {row.measure}" if modules and row.module else row.measure
        reference = ""
        if row.reference is not None or row.against:
            reference = " ".join(p for p in (_number(row.reference, row.unit), row.against) if p != "-")
        lines.append(
            (
                measure,
                _number(row.ours, row.unit),
                _number(row.wall, "s") if row.wall is not None else "",
                reference,
                f"{row.ratio:.2f}x" if row.ratio is not None else "",
                row.goal.text(row.unit) if row.goal is not None else "",
                row.verdict,
                f"{row.peak_mib:.0f}" if row.peak_mib is not None else "",
                row.note,
            )
        )
    widths = [max([len(c)] + [len(line[i]) for line in lines]) for i, c in enumerate(_COLUMNS)]
    right = {1, 2, 4, 7}

    def render(cells: tuple[str, ...]) -> str:
        out = [
            c.rjust(w) if i in right else c.ljust(w)
            for i, (c, w) in enumerate(zip(cells, widths, strict=True))
        ]
        return "  ".join(out).rstrip()

    return "\n".join([render(_COLUMNS), render(tuple("-" * w for w in widths))] + [render(x) for x in lines])


class Report:
    """The rows of one benchmark module: ``add`` or ``time`` them, ``finish`` prints the table."""

    def __init__(self, module: str) -> None:
        self.module = module
        self.rows: list[Row] = []

    def add(self, measure: str, ours: float | None, unit: str = "s", **values: Any) -> Row:
        row = Row(measure, ours, unit, module=self.module, **values)
        self.rows.append(row)
        return row

    def time(
        self,
        measure: str,
        timing: Timing,
        reference: Timing | float | None = None,
        *,
        cpu: float | None = None,
        **values: Any,
    ) -> Row:
        """A row of CPU seconds from a timing (``cpu`` overrides its best, as for a settled best),
        with its wall time and peak memory; a reference timing counts by its CPU time."""
        if isinstance(reference, Timing):
            reference = reference.cpu
        ours = timing.cpu if cpu is None else cpu
        return self.add(
            measure, ours, "s", reference=reference, wall=timing.wall, peak_mib=timing.peak_mib, **values
        )

    def rate(
        self,
        measure: str,
        timing: Timing,
        size: float,
        reference: Timing | None = None,
        *,
        unit: str = "MB/s",
        **values: Any,
    ) -> Row:
        """A row of throughput: ``size`` (in the unit's numerator, MB say) per CPU second, the
        reference's likewise, and the wall-clock rate in the note."""
        note = f"{size / timing.wall:.2f} {unit} wall" if timing.wall > 0 else ""
        if values.get("note"):
            note = f"{values.pop('note')}; {note}"
        return self.add(
            measure,
            size / timing.cpu if timing.cpu > 0 else None,
            unit,
            reference=size / reference.cpu if reference is not None and reference.cpu > 0 else None,
            peak_mib=timing.peak_mib,
            note=note,
            **values,
        )

    def growth(self, what: str, points: Iterable[tuple[int, float]], **values: Any) -> None:
        """Rows of how a time grows with the size: between each two sizes, the exponent k in
        t ∝ N^k."""
        ordered = sorted(points)
        for (n1, t1), (n2, t2) in zip(ordered, ordered[1:], strict=False):
            if t1 > 0 and t2 > 0 and n2 != n1:
                k = math.log(t2 / t1) / math.log(n2 / n1)
                note = f"x{t2 / t1:.1f} time for x{n2 / n1:.0f} size"
                self.add(f"{what} growth {n1} -> {n2}: exponent k", k, "", note=note, **values)

    def missed(self) -> list[Row]:
        return [r for r in self.rows if r.verdict == "MISSED"]

    def finish(self, status: int = 0) -> int:
        """Print the table, hand the rows to ``python -m benchmarks`` if it asked for them, and
        return 1 if a goal is missed (or ``status`` if that is not 0)."""
        print()
        print(format_table(self.rows))
        target = os.environ.get(ROWS_ENV)
        if target:
            Path(target).write_text(json.dumps([r.to_dict() for r in self.rows], indent=1))
        return status or (1 if self.missed() else 0)


def read_rows(path: Path) -> list[Row]:
    """The rows a module wrote with :meth:`Report.finish` (none if it wrote nothing)."""
    try:
        text = path.read_text()
    except OSError:
        return []
    return [Row.from_dict(item) for item in json.loads(text)] if text.strip() else []

"""``measurements.json``: what a measured run of the generated ROS 2 application saw, read and
checked against its versioned schema (``measurements.schema.json`` beside this module,
documented in ``docs/measurements.md``).

:func:`read_measurements` reads a file, :func:`parse_measurements` a text; both return a
:class:`Measurements` (per thread, process, topic and topic chain of the model) or raise a
:class:`~rosaadl.errors.ParseError` located at the file, line and JSON path of the first
problem, listing every problem in ``errors``: a truncated text, a value of the wrong type, an
unknown member (a hand edit), a statistic whose min, mean and max are out of order, a format
version this release does not know. Times are in microseconds, loads in % of one core.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any

from rosaadl.errors import Location, ParseError, RosaadlError
from rosaadl.importers.json_limits import json_value_bound
from rosaadl.importers.json_schema import schema_problems, value_lines

__all__ = [
    "FORMAT",
    "VERSION",
    "KNOWN_VERSIONS",
    "MAX_FILE_BYTES",
    "Statistics",
    "ThreadMeasurement",
    "ProcessMeasurement",
    "TopicMeasurement",
    "ChainMeasurement",
    "Measurements",
    "measurements_schema",
    "parse_measurements",
    "read_measurements",
]

FORMAT = "rosaadl-measurements"
#: The version this release writes; it reads every one of :data:`KNOWN_VERSIONS`.
VERSION = 4
KNOWN_VERSIONS = (1, 2, 3, 4)
#: What each version added, as (group, member): a file of an earlier version holding one was
#: edited by hand.
_NEW_IN: tuple[tuple[int, tuple[tuple[str, str], ...]], ...] = (
    (2, (("run", "period_scale"), ("processes", "profile"))),
    (3, (("threads", "dispatch_latency_us"),)),
    (4, (("threads", "twin_execution_time_us"), ("processes", "cpu_speed"))),
)
#: a measurements file larger than this is refused before it is read
MAX_FILE_BYTES = 64 * 1024 * 1024
_MAX_VALUES = 2_000_000


@lru_cache(maxsize=1)
def _schema_text() -> str:
    return resources.files("rosaadl.importers").joinpath("measurements.schema.json").read_text("utf-8")


def measurements_schema() -> dict[str, Any]:
    """The JSON Schema of ``measurements.json`` (a fresh copy)."""
    return json.loads(_schema_text())


@dataclass(frozen=True)
class Statistics:
    """min, mean and max of some samples."""

    min: float
    mean: float
    max: float

    @classmethod
    def of(cls, data: dict[str, Any] | None) -> Statistics | None:
        return None if data is None else cls(float(data["min"]), float(data["mean"]), float(data["max"]))

    def as_dict(self) -> dict[str, float]:
        return {"min": self.min, "mean": self.mean, "max": self.max}


@dataclass(frozen=True)
class ThreadMeasurement:
    """One thread's dispatches: release period (mean, jitter), execution time (CPU time of its
    own thread), response time (release to end), deadline misses; times in µs.
    ``dispatch_latency_us``: release to start of its timer dispatches released while its
    executor was idle (version 3; None: not a timer thread, or no such dispatch).
    ``twin_execution_time_us``: the mean CPU time of a dispatch up to the end of the workload
    twin's loop, what does not depend on the CPU's speed (version 4, None: no twin ran)."""

    path: str
    process: str | None
    dispatches: int
    period_mean_us: float | None
    period_jitter_us: float | None
    execution_time_us: Statistics | None
    response_time_us: Statistics | None
    deadline_us: float | None
    deadline_misses: int
    dispatch_latency_us: Statistics | None = None
    twin_execution_time_us: float | None = None

    @property
    def load_percent(self) -> float | None:
        """Mean execution time / mean period in % (None below two dispatches)."""
        if self.execution_time_us is None or not self.period_mean_us:
            return None
        return self.execution_time_us.mean / self.period_mean_us * 100


@dataclass(frozen=True)
class ProcessMeasurement:
    """One process (ROS node): its CPU load from ``/proc`` (all its threads: callbacks,
    executor, serialization, DDS) and the host core it ran on (None: not bound);
    ``cpu_speed``: the speed of the CPUs it may run on as the run gauged them, loops per ms of
    CPU (version 4, None: not gauged), see :mod:`rosaadl.workflow.run.cpu_speed`."""

    path: str
    node: str | None
    cpu_load_percent: float
    core: int | None
    classifier: str | None = None  #: the model's classifier of the process (``Pkg::type.impl``)
    profile: tuple[str, str] | None = None  #: (board, core) a profile of it is named after
    cpu_speed: float | None = None


@dataclass(frozen=True)
class TopicMeasurement:
    """One topic: messages seen, their rate and bandwidth; ``port``: the model's out port."""

    name: str
    type: str | None
    port: str | None
    messages: int
    rate_hz: float
    bytes_per_message: int | None
    bandwidth_bytes_per_s: float


@dataclass(frozen=True)
class ChainMeasurement:
    """One topic chain of the model (a flow by its name): end-to-end latency in µs."""

    name: str
    topics: tuple[str, ...]
    samples: int
    latency_us: Statistics | None


@dataclass(frozen=True)
class Measurements:
    """A whole ``measurements.json``."""

    threads: tuple[ThreadMeasurement, ...]
    processes: tuple[ProcessMeasurement, ...]
    topics: tuple[TopicMeasurement, ...]
    chains: tuple[ChainMeasurement, ...]
    root: str | None = None
    run: tuple[tuple[str, Any], ...] = ()
    source: str | None = None

    def run_value(self, name: str, default: Any = None) -> Any:
        return dict(self.run).get(name, default)

    @property
    def period_scale(self) -> float:
        """The factor the run multiplied every period by (``run.period_scale``; 1 when absent)."""
        return float(self.run_value("period_scale", 1.0))


def _order_problems(document: dict[str, Any]) -> list[tuple[str, str]]:
    """min ≤ mean ≤ max in every statistic, and no member of a later version in a file of an
    earlier one (a schema cannot say it)."""
    problems = []
    version = document.get("version")
    for added, members in _NEW_IN:
        if version >= added:
            continue
        why = f"a member of version {added} in a version {version} file"
        for group, member in members:
            rows = document.get(group)
            if isinstance(rows, dict) and member in rows:  # ``run``: one object
                problems.append((f"$.{group}.{member}", why))
            elif isinstance(rows, list):
                problems += [
                    (f"$.{group}[{index}].{member}", why)
                    for index, row in enumerate(rows)
                    if isinstance(row, dict) and member in row
                ]
    for group, key in (
        ("threads", "execution_time_us"),
        ("threads", "response_time_us"),
        ("threads", "dispatch_latency_us"),
        ("chains", "latency_us"),
    ):
        for index, row in enumerate(document.get(group, [])):
            stats = row.get(key)
            if stats and not stats["min"] <= stats["mean"] <= stats["max"]:
                problems.append((f"$.{group}[{index}].{key}", "min <= mean <= max does not hold"))
    return problems


def _build(document: dict[str, Any], source: str | None) -> Measurements:
    threads = tuple(
        ThreadMeasurement(
            path=t["path"],
            process=t.get("process"),
            dispatches=int(t["dispatches"]),
            period_mean_us=None if t["period_us"] is None else float(t["period_us"]["mean"]),
            period_jitter_us=None if t["period_us"] is None else float(t["period_us"]["jitter"]),
            execution_time_us=Statistics.of(t["execution_time_us"]),
            response_time_us=Statistics.of(t["response_time_us"]),
            deadline_us=t.get("deadline_us"),
            deadline_misses=int(t["deadline_misses"]),
            dispatch_latency_us=Statistics.of(t.get("dispatch_latency_us")),
            twin_execution_time_us=t.get("twin_execution_time_us"),
        )
        for t in document["threads"]
    )
    processes = tuple(
        ProcessMeasurement(
            p["path"],
            p.get("node"),
            float(p["cpu_load_percent"]),
            p.get("core"),
            p.get("classifier"),
            (p["profile"]["board"], p["profile"]["core"]) if "profile" in p else None,
            p.get("cpu_speed"),
        )
        for p in document["processes"]
    )
    topics = tuple(
        TopicMeasurement(
            t["name"],
            t.get("type"),
            t.get("port"),
            int(t["messages"]),
            float(t["rate_hz"]),
            t.get("bytes_per_message"),
            float(t["bandwidth_bytes_per_s"]),
        )
        for t in document["topics"]
    )
    chains = tuple(
        ChainMeasurement(
            c["name"], tuple(c.get("topics", ())), int(c["samples"]), Statistics.of(c["latency_us"])
        )
        for c in document["chains"]
    )
    return Measurements(
        threads,
        processes,
        topics,
        chains,
        root=document.get("model", {}).get("root"),
        run=tuple(sorted(document.get("run", {}).items())),
        source=source,
    )


def parse_measurements(text: str, file: str | None = None) -> Measurements:
    """The measurements in ``text``; a located :class:`ParseError` (file, line, JSON path) when
    it is not a valid ``measurements.json`` of this version."""
    if json_value_bound(text.encode("utf-8", "surrogatepass"), _MAX_VALUES) > _MAX_VALUES:
        raise ParseError(f"a measurements file holds at most {_MAX_VALUES} JSON values", file=file)
    try:
        document = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ParseError(
            f"malformed JSON (truncated or edited?): {exc.msg}", file=file, line=exc.lineno, column=exc.colno
        ) from None
    except (ValueError, RecursionError) as exc:
        raise ParseError(f"malformed JSON: {exc}", file=file) from None
    if (
        isinstance(document, dict)
        and document.get("format") == FORMAT
        and document.get("version") not in KNOWN_VERSIONS
    ):
        raise ParseError(
            f"measurements format version {document.get('version')!r} is not known"
            f" (this release reads {', '.join(str(v) for v in KNOWN_VERSIONS[:-1])}"
            f" and {KNOWN_VERSIONS[-1]})",
            file=file,
            path="$.version",
        )
    problems = list(schema_problems(document, measurements_schema()))
    if not problems:
        problems = _order_problems(document)
    if problems:
        lines = value_lines(text)
        errors = [
            RosaadlError(
                message, Location(file=file, line=lines.get(path) or _nearest_line(lines, path), path=path)
            )
            for path, message in problems
        ]
        first = errors[0]
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        raise ParseError(
            f"not a valid measurements file: {first.location.path}: {first.message}{more}",
            first.location,
            errors=list(errors),
        )
    return _build(document, file)


def _nearest_line(lines: dict[str, int], path: str) -> int | None:
    """The line of ``path``'s closest enclosing value (a missing member: its object's line)."""
    while path:
        if path in lines:
            return lines[path]
        cut = max(path.rfind("."), path.rfind("["))
        if cut <= 0:
            break
        path = path[:cut]
    return lines.get("$")


def read_measurements(path: str | Path) -> Measurements:
    """The measurements of the file ``path`` (see :func:`parse_measurements`)."""
    target = Path(path)
    name = str(target)
    try:
        if target.stat().st_size > MAX_FILE_BYTES:
            raise ParseError(f"a measurements file is at most {MAX_FILE_BYTES} bytes", file=name)
        data = target.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the measurements: {exc.strerror or exc}", file=name) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ParseError(f"not UTF-8 text (byte {exc.start})", file=name) from None
    return parse_measurements(text, name)

"""What the flow latency analysis computes: contributors, one entry per flow and mode, the result.

Follows OSATE's ``org.osate.analysis.flows.model`` (``LatencyContributor``,
``LatencyReportEntry``): a contributor is one row of OSATE's report (a component's sampling,
processing or queuing, a connection, a bus or protocol under it, a partition), with a minimum
and a maximum value, the method that gave each (OSATE's words: ``first sampling``,
``processing time``, ``transmission time`` ...), the values specified by ``Latency`` on the flow
element, and comments. Times are exact microseconds (:class:`~fractions.Fraction`); OSATE's
reports print milliseconds.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rosaadl.errors import Diagnostic, ModelError

__all__ = [
    "METHOD_WORDS",
    "REVISIONS",
    "method_word",
    "LatencyPreferences",
    "Contributor",
    "LatencyChain",
    "LatencyHop",
    "LatencyResult",
    "number",
]

#: OSATE's words for each contributor method (``LatencyContributor.mapMethodToString``) today;
#: see :func:`method_word` for the words of earlier releases.
METHOD_WORDS = {
    "deadline": "deadline",
    "response": "response time",
    "processing": "processing time",
    "delayed": "delayed sampling",
    "specified": "specified",
    "sampled": "sampling",
    "first": "first sampling",
    "queued": "queued",
    "partition_frame": "partition major frame",
    "partition_schedule": "partition offset",
    "transmission": "transmission time",
    "partition_output": "partition output",
    "sampled_protocol": "sampling protocol/bus",
    "unknown": "no sampling/queuing latency",
    "none": "no latency",
}

#: revisions of OSATE's rules: ``current`` (since July 2019), ``2018`` (the same rules, with the
#: words of OSATE 2.2-2.4), ``2014`` and ``2014-early`` (September 2014)
REVISIONS = ("current", "2018", "2014", "2014-early")


def method_word(method: str, revision: str = "current", major_frame: bool = True) -> str:
    """OSATE's word for a contributor method in a revision of its rules: an unknown method was
    ``no latency`` until July 2019, a partition window ``partition schedule`` in 2014; a
    partition output names the preference that placed it (``LatencyContributor
    .mapMethodToString``: ``partition output (MF)`` at the major frame, ``(PE)`` at the
    partition end, since September 2014)."""
    if method == "unknown" and revision != "current":
        return "no latency"
    if method == "partition_schedule" and revision.startswith("2014"):
        return "partition schedule"
    if method == "partition_output":
        return f"{METHOD_WORDS[method]} ({'MF' if major_frame else 'PE'})"
    return METHOD_WORDS[method]


def number(value: Fraction | None) -> float | int | None:
    """An exact time as JSON gives it: an integer when whole, else a float."""
    if value is None:
        return None
    return int(value) if value.denominator == 1 else float(value)


@dataclass(frozen=True)
class LatencyPreferences:
    """OSATE's flow latency preferences, which its report names spell as four letter pairs.

    * ``AS``/``SS``: asynchronous or synchronous system. rosaadl computes both and reports
      them side by side (``mode``); the preference only names OSATE's report.
    * ``MF``/``PE``: a partition's output leaves at the major frame, or at the end of the
      partition window.
    * ``ET``/``DL``: the worst-case processing time is the maximum ``Compute_Execution_Time``,
      or the thread's ``Deadline`` when one is assigned.
    * ``EQ``/``FQ``: the best-case queuing delay assumes an empty queue, or a full one.

    ``revision`` selects OSATE's rules of a release (:data:`REVISIONS`): ``"current"`` (the
    default), ``"2018"`` (the same rules with OSATE 2.2-2.4's words), ``"2014"`` and
    ``"2014-early"`` (the September 2014 rules that wrote the flow latency examples of
    ``osate/examples``: a sampling delay counts in the minimum too, a synchronous system rounds
    the minimum up as well, a row shows the sampling period rather than what was added).
    """

    major_frame: bool = True
    worst_case_deadline: bool = False
    best_case_empty_queue: bool = True
    revision: str = "current"

    def __post_init__(self) -> None:
        if self.revision not in REVISIONS:
            known = ", ".join(REVISIONS)
            raise ModelError(
                f"unknown revision {self.revision!r} of OSATE's latency rules (expected {known})"
            )

    def code(self, synchronous: bool) -> str:
        """OSATE's report suffix, ``AS-MF-ET-EQ``."""
        return "-".join(
            (
                "SS" if synchronous else "AS",
                "MF" if self.major_frame else "PE",
                "DL" if self.worst_case_deadline else "ET",
                "EQ" if self.best_case_empty_queue else "FQ",
            )
        )

    def description(self, synchronous: bool) -> str:
        """OSATE's report header words for the preferences."""
        return "/".join(
            (
                "synchronous system" if synchronous else "asynchronous system",
                "major frame" if self.major_frame else "partition end",
                "worst case as deadline"
                if self.worst_case_deadline
                else "worst case as max compute execution time",
                "best case as empty queue min compute execution time"
                if self.best_case_empty_queue
                else "best case as full queue min compute execution time",
            )
        )

    @classmethod
    def from_code(cls, code: str, revision: str = "current") -> tuple[LatencyPreferences, bool]:
        """``"SS-MF-DL-EQ"`` → (preferences, synchronous); a :class:`ModelError` for another form."""
        parts = code.upper().split("-")
        if len(parts) != 4 or parts[0] not in ("AS", "SS") or parts[1] not in ("MF", "PE"):
            raise ModelError(f"latency preferences {code!r}: expected e.g. AS-MF-ET-EQ")
        if parts[2] not in ("ET", "DL") or parts[3] not in ("EQ", "FQ"):
            raise ModelError(f"latency preferences {code!r}: expected e.g. AS-MF-ET-EQ")
        prefs = cls(parts[1] == "MF", parts[2] == "DL", parts[3] == "EQ", revision)
        return prefs, parts[0] == "SS"


@dataclass
class Contributor:
    """One row of OSATE's latency report (``LatencyContributor``).

    ``element``: the instance object (component, flow specification's component, connection,
    bus, virtual bus); ``kind``: ``sampling``, ``processing``, ``queuing``, ``connection``,
    ``transmission``, ``partition`` or ``partition output``; ``best``/``worst``: OSATE's min and
    max values; ``best_method``/``worst_method``: keys of :data:`METHOD_WORDS`;
    ``specified_*``: the element's ``Latency``; ``period``: the sampling period when it samples.
    """

    element: Any
    label: str
    kind: str
    best: Fraction = Fraction(0)
    worst: Fraction = Fraction(0)
    best_method: str = "unknown"
    worst_method: str = "unknown"
    specified_best: Fraction = Fraction(0)
    specified_worst: Fraction = Fraction(0)
    period: Fraction = Fraction(0)
    partition_offset: Fraction = Fraction(-1)
    partition_duration: Fraction = Fraction(0)
    immediate_deadline: Fraction = Fraction(0)
    sync: str = "unknown"  #: connections: synchronous, asynchronous or unknown
    timing: str = ""  #: connections: sampled, immediate or delayed
    comments: list[str] = field(default_factory=list)
    subs: list[Contributor] = field(default_factory=list)

    def total(self, worst: bool) -> Fraction:
        own = self.worst if worst else self.best
        return own + sum((s.total(worst) for s in self.subs), Fraction(0))

    def specified_total(self, worst: bool) -> Fraction:
        """OSATE's ``getTotalM..Specified``: a connection's own Latency unless protocols under it
        specify some; other rows add their own to their sub-rows'."""
        own = self.specified_worst if worst else self.specified_best
        subs = sum((s.specified_total(worst) for s in self.subs), Fraction(0))
        if self.kind == "connection":
            return own if subs == 0 else subs
        return own + subs

    def method(self, worst: bool) -> str:
        return self.worst_method if worst else self.best_method

    @property
    def is_partition(self) -> bool:
        return self.worst_method in ("partition_frame", "partition_schedule")

    def shown(self, worst: bool) -> Fraction:
        """The value the report row shows: its own and its sub-rows' (a sampling row shows what
        the totals added, under the 2014 rules its period)."""
        return self.total(worst)

    def comment(self, text: str) -> None:
        if text not in self.comments:
            self.comments.append(text)


@dataclass(frozen=True)
class LatencyHop:
    """One contribution to a chain's latency, as the JSON and the CSV list it."""

    kind: str
    path: str
    best_us: Fraction
    worst_us: Fraction
    note: str = ""
    label: str = ""
    best_method: str = ""
    worst_method: str = ""
    depth: int = 0  #: 1 for a bus or protocol under a connection
    specified_best_us: Fraction = Fraction(0)
    specified_worst_us: Fraction = Fraction(0)

    def as_dict(self) -> dict[str, Any]:
        return {
            "kind": self.kind,
            "path": self.path,
            "label": self.label,
            "best_us": number(self.best_us),
            "worst_us": number(self.worst_us),
            "best_method": self.best_method,
            "worst_method": self.worst_method,
            "depth": self.depth,
            "note": self.note,
        }


@dataclass(frozen=True)
class LatencyChain:
    """One end-to-end flow (or chain of threads) in one system mode (``async`` or ``sync``)."""

    name: str
    threads: tuple[str, ...]
    hops: tuple[LatencyHop, ...]
    best_us: Fraction
    worst_us: Fraction
    expected_us: Fraction | None = None
    mode: str = "async"
    expected_best_us: Fraction | None = None
    specified_best_us: Fraction = Fraction(0)
    specified_worst_us: Fraction = Fraction(0)
    issues: tuple[tuple[str, str], ...] = ()  #: OSATE's summary lines (severity, message)
    system_mode: str = ""
    flow_path: str = ""

    @property
    def met(self) -> bool | None:
        """Whether the worst case stays within the expected latency (None: no expectation)."""
        return None if not self.expected_us else self.worst_us <= self.expected_us

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "mode": self.mode,
            "threads": list(self.threads),
            "best_us": number(self.best_us),
            "worst_us": number(self.worst_us),
            "expected_us": number(self.expected_us),
            "met": self.met,
            "hops": [h.as_dict() for h in self.hops],
        }


@dataclass(frozen=True)
class LatencyResult:
    chains: tuple[LatencyChain, ...]
    diagnostics: tuple[Diagnostic, ...]
    preferences: LatencyPreferences = LatencyPreferences()
    system: str = ""

    @property
    def ok(self) -> bool:
        return all(d.severity != "error" for d in self.diagnostics)

    def chain(self, name: str, mode: str = "async") -> LatencyChain:
        for chain in self.chains:
            if chain.name == name and chain.mode == mode:
                return chain
        raise ModelError(f"no latency chain {name!r} in mode {mode}")

    def as_dict(self) -> dict[str, Any]:
        return {"chains": [c.as_dict() for c in self.chains]}

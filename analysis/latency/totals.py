"""End-to-end totals of a flow's contributors, for an asynchronous or a synchronous system.

OSATE's ``LatencyReportEntry.getActualLatency``, walked once for the minimum and once for the
maximum. Sampling rows do not simply add up:

* the *first sampling* row adds nothing and marks where sampling starts;
* a *sampling* row right after a partition adds what its period exceeds the partition's;
  otherwise, in a synchronous system (or over a connection within one processor), it rounds
  the latency accumulated since the last sampling up to its period: the worst case adds the
  difference, the best case nothing; in an asynchronous system it adds its period to the worst
  case only;
* a *delayed sampling* row does the same round-up for both cases, or adds its period to both;
* a *partition* row (after the first) rounds up (synchronous, to the major frame or to its
  window offset) or adds its period to the worst case; a *partition output* row waits for the
  next major frame (``MF``) or the end of its window (``PE``);
* a connection's periodic protocol rows round up (synchronous) or add their period (worst
  case); every other row adds its value and those of the rows under it.

The 2014 rules (``revision="2014"``, ``"2014-early"``): a sampling or partition row adds its
period to the best case too and rounds the best case up as well; rows that sample are left out
of the accumulated latency; the early rules round up in a synchronous system whatever the
connection, the later ones only when the row right before is a connection of unknown or shared
clock.
"""

from __future__ import annotations

from fractions import Fraction

from rosaadl.analysis.latency.model import Contributor

__all__ = ["actual_latency", "round_up", "round_up_diff"]


def round_up(value: Fraction, period: Fraction) -> Fraction:
    """``value`` up to a whole number of periods (one period for 0): ``FlowLatencyUtil.roundUp``."""
    if period <= 0:
        return value
    frames = value // period
    if value % period > 0:
        frames += 1
    elif value == 0:
        frames = 1
    return frames * period


def round_up_diff(value: Fraction, period: Fraction, target: Fraction | None = None) -> Fraction:
    """What ``value`` needs to reach the next multiple of ``period`` (``roundUpDiff``); with a
    ``target`` window length, what it needs to reach the end of the window it falls in."""
    if target is not None:
        if target <= 0:
            return Fraction(0)
        return target - value % target + (value // target) * period
    if period <= 0:
        return Fraction(0)
    rest = value % period
    if rest > 0:
        return period - rest
    return period if value == 0 else Fraction(0)


class _Walk:
    def __init__(self, rows: list[Contributor], synchronous: bool, major_frame: bool, revision: str) -> None:
        self.rows = rows
        self.sync = synchronous
        self.major_frame = major_frame
        self.legacy = revision.startswith("2014")
        self.early = revision == "2014-early"
        self.last: int | None = None

    def cumulative(self, index: int, worst: bool) -> Fraction:
        if self.last is None:
            return Fraction(0)
        total = Fraction(0)
        for row in self.rows[self.last + 1 : index]:
            if self.legacy and (row.kind == "sampling" or row.is_partition):
                continue
            total += row.total(worst)
        return total

    def previous_connection(self, index: int) -> Contributor | None:
        if self.legacy:
            before = self.rows[index - 1] if index > 0 else None
            return before if before is not None and before.kind == "connection" else None
        for row in reversed(self.rows[:index]):
            if row.kind == "connection":
                return row
        return None

    def rounds_up(self, index: int) -> bool:
        """Whether a sampling row is a round-up rather than a full period."""
        if self.last is None:
            return False
        if self.early:
            return self.sync
        conn = self.previous_connection(index)
        if conn is None:
            return False
        return (self.sync and conn.sync == "unknown") or conn.sync == "synchronous"

    def set(self, row: Contributor, worst: bool, value: Fraction) -> Fraction:
        if not self.legacy:  # the 2014 rows keep showing their period
            if worst:
                row.worst = value
            else:
                row.best = value
        return value

    def total(self, worst: bool) -> Fraction:
        res = Fraction(0)
        tag = "Max: " if worst else "Min: "
        for index, row in enumerate(self.rows):
            method = row.method(worst)
            if row.immediate_deadline > 0:
                cum = self.cumulative(index, worst) + row.total(worst)
                if cum > row.immediate_deadline:
                    row.comment(
                        f"{tag}immediate latency sequence exceeds deadline {_ms(row.immediate_deadline)}ms"
                    )
            if method == "first":
                self.last = index
            elif method in ("sampled", "delayed"):
                before = self.rows[index - 1] if index > 0 else None
                if before is not None and before.is_partition:
                    if row.period > before.period:
                        res += self.set(row, worst, row.period - before.period)
                        row.comment(
                            f"{tag}Added {_ms(row.period - before.period)}ms"
                            if self.legacy
                            else f"Sampling period {_ms(row.period)}ms"
                        )
                    elif 0 < row.period < before.period:
                        row.comment("Task period smaller than partition period")
                    else:
                        self.set(row, worst, Fraction(0))
                elif self.rounds_up(index):
                    cum = self.cumulative(index, worst)
                    if method == "delayed" or worst or self.legacy:
                        diff = round_up_diff(cum, row.period)
                    else:
                        diff = Fraction(0)
                    res += self.set(row, worst, diff)
                    if self.legacy:
                        row.comment(f"{tag}Sync added {_ms(diff)}ms")
                    elif method == "sampled":
                        row.comment(
                            f"{tag}Worst case: Round up sampling delay to period {_ms(row.period)}ms"
                            if worst
                            else f"{tag}Best case: 0 ms sampling delay"
                        )
                elif method == "delayed" or worst or self.legacy:
                    res += self.set(row, worst, row.period)
                else:
                    self.set(row, worst, Fraction(0))
                self.last = index
            elif row.is_partition:
                if index > 0:
                    if self.rounds_up(index):
                        cum = self.cumulative(index, worst)
                        if row.worst_method == "partition_frame" or row.partition_offset < 0:
                            diff = round_up_diff(cum, row.period)
                        else:
                            previous = self._previous_offset(index)
                            if previous < 0:
                                diff = round_up_diff(cum, row.period)
                            else:
                                mine = row.partition_offset
                                while mine - (previous + cum) < 0 and row.period > 0:
                                    mine += row.period
                                diff = mine - (previous + cum)
                        res += self.set(row, worst, diff)
                    elif worst or self.legacy:
                        res += self.set(row, worst, row.period)
                    else:
                        self.set(row, worst, Fraction(0))
                elif not self.legacy:
                    row.comment(f"Initial {_ms(row.period)}ms partition latency not added")
                self.last = index
            elif row.kind == "partition output":
                cum = self.cumulative(index, worst)
                if self.major_frame:
                    diff = round_up_diff(cum + row.partition_offset, row.period)
                    row.comment(f"Output at {_ms(row.period)}ms major frame")
                else:
                    diff = round_up_diff(cum, row.period, row.partition_duration)
                    row.comment(f"Output at {_ms(row.partition_duration)}ms partition end")
                res += self.set(row, worst, diff)
            else:
                if row.kind == "connection":
                    self._protocols(row, index, worst, None)
                res += row.total(worst)
        return res

    def _previous_offset(self, index: int) -> Fraction:
        for row in reversed(self.rows[:index]):
            if row.worst_method == "partition_schedule":
                return row.partition_offset
        return Fraction(-1)

    def _protocols(self, row: Contributor, index: int, worst: bool, enclosing: Contributor | None) -> None:
        """Periodic protocols and buses under a connection (``doSampledProtocol``)."""
        for sub in row.subs:
            periodic = sub.worst_method == "sampled_protocol" and sub.period > 0
            if periodic and (enclosing is None or sub.period > enclosing.period):
                if enclosing is not None:
                    self.set(enclosing, worst, Fraction(0))
                if self.sync and self.last is not None:
                    self.set(sub, worst, round_up_diff(self.cumulative(index, worst), sub.period))
                elif worst:
                    self.set(sub, worst, sub.period)
                else:
                    self.set(sub, worst, Fraction(0))
                enclosing = sub
            self._protocols(sub, index, worst, enclosing)


def actual_latency(
    rows: list[Contributor], synchronous: bool, major_frame: bool, revision: str
) -> tuple[Fraction, Fraction]:
    """(best, worst) end-to-end latency of ``rows``, in one system kind; today's sampling rows
    then show what they added."""
    best = _Walk(rows, synchronous, major_frame, revision).total(False)
    worst = _Walk(rows, synchronous, major_frame, revision).total(True)
    return best, worst


def _ms(value: Fraction) -> str:
    from rosaadl.analysis.busload import java_double

    return java_double(value / 1000)

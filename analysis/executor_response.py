"""Response-time bounds of callbacks run by one executor, in integer time.

An executor runs the callbacks of a ROS node (ROS 2) or of a ROSMOD component instance one at a
time per executor thread, to completion: scheduling inside it is non-preemptive. Each function
here bounds the response time (release to completion) of every job of one callback, given the
callbacks of its executor as :class:`CallbackTiming` (integer minimum inter-arrival time ``period``,
worst-case execution time ``wcet``, relative ``deadline``, ``priority`` where a larger number is
more urgent, ``rank``: its place in the executor's dispatch order) and ``interference``: the
``(period, wcet)`` of the threads of the same core that may preempt the executor's thread (other
executors of higher or equal OS priority), which take processor time as in the classical
preemptive analysis (their request-bound function is added to every demand below).

Time is discrete (Prosa's model, which ``response-time-analysis`` implements): a job released at
time ``a`` may start at ``a``, and a job that started before ``a`` blocks a more urgent job for at
most ``wcet - 1``. :func:`rbf` is the request-bound function, the work of the jobs of a callback
released in any half-open window of length ``delta``: ``ceil(delta / T) * C``, or
``ceil((delta + J) / T) * C`` for a release jitter ``J`` (a subscription released by a callback
whose response time varies); a callback with further release ``streams`` (a subscription fed
over several topics, each publisher releasing it independently) requests the sum over its
streams, and every ``rbf_j`` below is that sum. The offsets ``A`` searched are then the steps of
the jittered functions, ``k * T - J``.

Each bound follows the busy-window principle (Bozhko & Brandenburg, ECRTS 2020): a bound ``L`` on
the busy window, then, for every relevant offset ``A < L`` of the job under analysis in it, the
least completion time ``F`` solving the per-offset equation; the bound is ``max(F - A)``. A bound
is ``None`` when the busy window does not close below ``horizon`` (the executor is overloaded).

The functions are cross-checked, in the tests, against the Prosa-verified analyses of PyPI
``response-time-analysis`` (FIFO, fixed priority and EDF with fully non-preemptive jobs): on an
executor that no other thread preempts they give the same numbers.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import NamedTuple

__all__ = [
    "CallbackTiming",
    "rbf",
    "busy_window",
    "fifo_response_time",
    "np_fixed_priority_response_time",
    "np_edf_response_time",
    "polling_response_time",
    "work_conserving_response_time",
    "DEFAULT_HORIZON",
]

#: The default limit of every fixed-point search, in time units (beyond it: no bound).
DEFAULT_HORIZON = 10**12


class CallbackTiming(NamedTuple):
    """One callback of an executor in integer time units."""

    name: str
    period: int  #: minimum inter-arrival time (the timer period, the topic's minimum gap)
    wcet: int
    deadline: int
    priority: int = 0
    rank: int = 0  #: place in the executor's dispatch order (kind order, then registration)
    #: minimum inter-arrival times of further independent release streams (a subscription fed
    #: over several topics: one stream per topic), whose jobs add to those of ``period``
    streams: tuple[int, ...] = ()
    #: release jitter of each stream, ``period`` first (missing: 0): a stream of period ``T`` and
    #: jitter ``J`` releases ``ceil((t + J) / T)`` jobs in a window ``t``
    jitters: tuple[int, ...] = ()


#: ``(period, wcet)`` or ``(period, wcet, jitter)`` of each preempting thread or callback
Interference = Sequence[tuple[int, ...]]


def rbf(period: int, wcet: int, delta: int, jitter: int = 0) -> int:
    """The request-bound function: work of the jobs released in a half-open window of ``delta``
    by a stream of minimum inter-arrival time ``period`` and release jitter ``jitter``."""
    if delta <= 0 or wcet <= 0:
        return 0
    return -(-(delta + jitter) // period) * wcet


def _streams(callback: CallbackTiming) -> list[tuple[int, int]]:
    """``(period, jitter)`` of each release stream of the callback."""
    periods = (callback.period, *callback.streams)
    return [(p, callback.jitters[k] if k < len(callback.jitters) else 0) for k, p in enumerate(periods)]


def _requests(callback: CallbackTiming, delta: int) -> int:
    """The callback's request-bound function: the sum of :func:`rbf` over its release streams."""
    return sum(rbf(period, callback.wcet, delta, jitter) for period, jitter in _streams(callback))


def _preemption(interference: Interference, delta: int) -> int:
    return sum(rbf(t[0], t[1], delta, t[2] if len(t) > 2 else 0) for t in interference)


def _fixed_point(rhs: Callable[[int], int], start: int, horizon: int, least: int = 0) -> int | None:
    """The least ``x >= start`` with ``rhs(x) <= x`` reached by iteration (None past ``horizon``)."""
    x = max(start, least)
    while True:
        value = rhs(x)
        if value <= x:
            return x
        if value > horizon:
            return None
        x = value


def busy_window(
    callbacks: Iterable[CallbackTiming],
    interference: Interference = (),
    blocking: int = 0,
    horizon: int = DEFAULT_HORIZON,
) -> int | None:
    """The longest busy window: the least ``L > 0`` with ``blocking + sum rbf(L) + I(L) <= L``
    (Casini et al., ECRTS 2019, Lemma 6; the classical level-i busy period)."""
    items = list(callbacks)
    return _fixed_point(
        lambda x: blocking + sum(_requests(c, x) for c in items) + _preemption(interference, x),
        1,
        horizon,
        least=1,
    )


def _least(*values: int | None) -> int | None:
    known = [v for v in values if v is not None]
    return min(known) if known else None


def _offsets(steps: Iterable[tuple[int, int]], limit: int) -> list[int]:
    """0 and every ``k * period + shift`` (``k >= 0``) in ``[0, limit)`` for each ``(period, shift)``."""
    points: set[int] = {0}
    for period, shift in steps:
        k = 0 if shift >= 0 else -(shift // period)
        value = k * period + shift
        while value < limit:
            points.add(value)
            value += period
    return sorted(points)


def _worst_response(
    offsets: Iterable[int], demand: Callable[[int, int], int], first: Callable[[int], int], horizon: int
) -> int | None:
    """``max_A (F(A) - A)`` over ``offsets``, where ``F(A)`` is the least ``F >= first(A)`` with
    ``demand(A, F) <= F`` (None when one of them passes ``horizon``)."""
    worst = 0
    for offset in offsets:
        finish = _fixed_point(lambda x, a=offset: demand(a, x), first(offset), horizon)
        if finish is None:
            return None
        worst = max(worst, finish - offset)
    return worst


def fifo_response_time(
    callbacks: Sequence[CallbackTiming],
    interference: Interference = (),
    horizon: int = DEFAULT_HORIZON,
) -> int | None:
    """Response-time bound of every callback of a FIFO executor (ROSMOD's ``FIFO`` message queue,
    the ROSMOD paper, section II.A: one executor thread, callbacks run to completion in arrival
    order).

    FIFO RTA (Prosa's, as ``response_time_analysis.fifo``): for every offset ``A`` at a step of the
    total request-bound function below the busy window ``L``, the job completes by the least ``F``
    with ``F >= sum_j rbf_j(A + 1) + I(F)`` (all the work released up to ``A`` inclusive goes first);
    the bound is ``max_A (F - A)``, the same for every callback of the queue.
    """
    window = busy_window(callbacks, interference, 0, horizon)
    if window is None:
        return None

    def released(offset: int) -> int:
        return sum(_requests(c, offset + 1) for c in callbacks)

    return _worst_response(
        _offsets(((p, -j) for c in callbacks for p, j in _streams(c)), window),
        lambda offset, x: released(offset) + _preemption(interference, x),
        released,
        horizon,
    )


def np_fixed_priority_response_time(
    callbacks: Sequence[CallbackTiming],
    index: int,
    interference: Interference = (),
    horizon: int = DEFAULT_HORIZON,
) -> int | None:
    """Response-time bound of ``callbacks[index]`` under non-preemptive fixed priorities (ROSMOD's
    ``PFIFO`` queue: the most urgent callback first, FIFO among equals, run to completion).

    The classical non-preemptive fixed-priority analysis (Davis, Burns, Bril & Lukkien, Real-Time
    Systems 35(3), 2007, its non-preemptive response-time analysis, in Prosa's discrete form):
    blocking ``B = max(C_lp) - 1`` by one job of a less urgent callback; level-i busy window
    ``L = B + sum_hep rbf(L) + I(L)`` (or the processor's busy window ``sum rbf(L) + I(L)``
    that holds it, when shorter); for each offset ``A = q * T_i < L`` the least ``F`` with
    ``F >= B + rbf_i(A + 1) + sum_{j != i, P_j >= P_i} rbf_j(F - C_i + 1) + I(F)``; bound
    ``max_A (F - A)``. Callbacks of equal priority count as more urgent (FIFO among equals
    orders them by arrival, which this bounds).
    """
    me = callbacks[index]
    hep = [c for k, c in enumerate(callbacks) if k != index and c.priority >= me.priority]
    blocking = max((c.wcet - 1 for c in callbacks if c.priority < me.priority), default=0)
    window = _least(
        busy_window([me, *hep], interference, blocking, horizon),
        busy_window(callbacks, interference, 0, horizon),
    )
    if window is None:
        return None

    def own(offset: int) -> int:
        return blocking + _requests(me, offset + 1)

    def demand(offset: int, x: int) -> int:
        start = x - me.wcet + 1
        return own(offset) + sum(_requests(c, start) for c in hep) + _preemption(interference, x)

    return _worst_response(_offsets([(p, -j) for p, j in _streams(me)], window), demand, own, horizon)


def np_edf_response_time(
    callbacks: Sequence[CallbackTiming],
    index: int,
    interference: Interference = (),
    horizon: int = DEFAULT_HORIZON,
) -> int | None:
    """Response-time bound of ``callbacks[index]`` under non-preemptive EDF (ROSMOD's ``EDF``
    queue: the earliest absolute deadline first, run to completion).

    George, Rivierre & Spuri (INRIA RR-2966, 1996), the non-preemptive EDF response time, in
    discrete time: for a job of
    ``i`` released at ``A`` (absolute deadline ``A + D_i``) the least ``F`` with
    ``F >= B(A) + rbf_i(A + 1) + sum_{j != i, D_j <= A + D_i} min(rbf_j(F - C_i + 1),
    rbf_j(A + D_i - D_j + 1)) + I(F)``, where ``B(A) = max(C_j - 1 | D_j > A + D_i)`` is the
    blocking by one job of later deadline; ``A`` ranges over ``k * T_j + D_j - D_i`` and
    ``k * T_i`` below the busy window ``L = sum rbf(L) + I(L)`` (the processor's, which the
    blocking job belongs to); bound
    ``max_A (F - A)``. Jobs of equal absolute deadline count as interfering.
    """
    me = callbacks[index]
    others = [c for k, c in enumerate(callbacks) if k != index]
    window = busy_window(callbacks, interference, 0, horizon)
    if window is None:
        return None
    steps = [(p, -j) for p, j in _streams(me)]
    steps += [(p, c.deadline - me.deadline - j) for c in others for p, j in _streams(c)]

    def own(offset: int) -> int:
        due = offset + me.deadline
        blocking = max((c.wcet - 1 for c in others if c.deadline > due), default=0)
        return blocking + _requests(me, offset + 1)

    def demand(offset: int, x: int) -> int:
        due, start = offset + me.deadline, x - me.wcet + 1
        work = sum(
            min(_requests(c, start), _requests(c, due - c.deadline + 1)) for c in others if c.deadline <= due
        )
        return own(offset) + work + _preemption(interference, x)

    return _worst_response(_offsets(steps, window), demand, own, horizon)


def polling_response_time(
    callbacks: Sequence[CallbackTiming],
    index: int,
    interference: Interference = (),
    horizon: int = DEFAULT_HORIZON,
) -> int | None:
    """Response-time bound of ``callbacks[index]`` under the ROS 2 single-threaded executor.

    The executor waits for work, takes a snapshot of the ready callbacks at that *polling point*
    and runs each callback of the snapshot at most once, in a fixed order (kind, then registration:
    ``rank``), non-preemptively; it polls again only when the snapshot is used up. Two bounds hold,
    and the smaller is returned:

    * Casini, Blaß, Lütkebohle & Brandenburg, ECRTS 2019, Lemmas 4-5 and eq. (6) (a polling-point
      callback): for every offset ``A = q * T_i`` below the busy window (Lemma 6), the least ``F``
      with ``F >= rbf_i(A + 1) + sum_{j != i} rbf_j(F - C_i + 1) + I(F)``;
    * the starvation freedom of the polling rounds (Blaß, Casini, Bozhko & Brandenburg, RTSS 2021,
      their round-robin argument: every callback ready at a polling point runs once in that
      round): when the first bound is at most ``T_i``, no older job of ``i`` is pending when a
      job is released, so the job runs in the round after the one under way at its release.
      That round's remainder holds at most one job of every other callback, the next one at
      most one job of every callback ordered before ``i``; and a callback ``j`` runs in the window
      only jobs released less than its own bound ``R_j`` (the first bound) before the window
      opens, so at most ``ceil((R + R_j) / T_j)`` of them (the arrival-curve cap of Blaß et al.'s
      round-robin analysis, as the ``ros2::rr`` module of the ``response-time-analysis`` crate
      implements it, summed over its release streams); a callback of equal rank counts as
      ordered before ``i``:
      ``R = C_i + sum_{j != i} C_j * min(1 + [rank_j <= rank_i], ceil((R + R_j) / T_j)) + I(R)``.

    A callback of several release streams (whose jobs may arrive together, so one may be pending
    when the next arrives) keeps the first bound, and so does one whose first bound exceeds its
    period less its release jitter (the least gap between its jobs).
    """
    me = callbacks[index]
    worst = _casini_bound(callbacks, index, interference, horizon)
    if worst is None or me.streams or worst > me.period - sum(me.jitters):
        return worst
    caps = []
    for k, other in enumerate(callbacks):
        if k == index:
            continue
        bound = _casini_bound(callbacks, k, interference, horizon)
        if bound is None:
            return worst
        caps.append((other, 2 if other.rank <= me.rank else 1, bound))

    def rounds(x: int) -> int:
        work = sum(c.wcet * min(jobs, _arrivals(c, x + lag)) for c, jobs, lag in caps)
        return me.wcet + work + _preemption(interference, x)

    two_rounds = _fixed_point(rounds, me.wcet, horizon)
    return worst if two_rounds is None else min(worst, two_rounds)


def _arrivals(callback: CallbackTiming, delta: int) -> int:
    """Jobs a callback releases in a half-open window of ``delta > 0``."""
    return sum(-(-(delta + jitter) // period) for period, jitter in _streams(callback))


def _casini_bound(
    callbacks: Sequence[CallbackTiming], index: int, interference: Interference, horizon: int
) -> int | None:
    """Casini et al.'s polling-point bound (eq. (6)) of ``callbacks[index]``: the non-preemptive
    fixed-priority equation with every other callback as urgent and no blocking."""
    level = [c._replace(priority=0) for c in callbacks]
    return np_fixed_priority_response_time(level, index, interference, horizon)


def work_conserving_response_time(
    callbacks: Sequence[CallbackTiming],
    interference: Interference = (),
    horizon: int = DEFAULT_HORIZON,
) -> int | None:
    """Response-time bound of every callback of an executor that keeps its processor busy while
    any callback is ready but follows no order: the length of the busy window (Casini et al.,
    ECRTS 2019, Lemma 6: no job completes later than the end of the busy window it is released
    in, which is at most ``L`` after its release).

    This is the bound of a multi-threaded executor whose threads share one core, and of a rclpy
    ``MultiThreadedExecutor`` on any number of cores: Python callbacks of one process hold the
    GIL to compute, which the interpreter hands between threads every 5 ms (its switch interval)
    in no priority order, so the process computes like one processor time-sliced among its ready
    callbacks. Mutually exclusive callback groups only restrict which callbacks run together; as
    long as the executor has a thread per group, some ready callback always computes.
    """
    return busy_window(callbacks, interference, 0, horizon)

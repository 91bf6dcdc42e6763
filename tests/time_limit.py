"""A time limit for tests of bounded work: a hang fails the test instead of hanging the suite.

Test modules import it as ``time_limit`` (the ``tests`` folder is on pytest's import path)::

    from time_limit import within_seconds
    _limit = pytest.fixture(autouse=True)(within_seconds(10))

The limit is CPU time of the test process (``ITIMER_PROF``): bounded work is what is asserted,
and CPU time does not stretch when other processes load the machine. A wall-clock alarm at six
times the limit (at least 60 s) still ends a test that blocks without computing.
"""

from __future__ import annotations

import signal
from collections.abc import Callable, Iterator

__all__ = ["within_seconds"]


def within_seconds(limit: int) -> Callable[[], Iterator[None]]:
    """A generator fixture body raising :class:`TimeoutError` in the test after ``limit`` seconds
    of CPU time (``SIGPROF``), or six times that of wall-clock time (``SIGALRM``; the main
    thread, POSIX)."""

    def limited() -> Iterator[None]:
        def cpu_expired(signum: int, frame: object) -> None:
            raise TimeoutError(f"used more than {limit} s of CPU time")

        def wall_expired(signum: int, frame: object) -> None:
            raise TimeoutError(f"ran past {max(60, 6 * limit)} s")

        previous_prof = signal.signal(signal.SIGPROF, cpu_expired)
        previous_alarm = signal.signal(signal.SIGALRM, wall_expired)
        signal.setitimer(signal.ITIMER_PROF, limit)
        signal.alarm(max(60, 6 * limit))
        try:
            yield
        finally:
            signal.setitimer(signal.ITIMER_PROF, 0)
            signal.alarm(0)
            signal.signal(signal.SIGPROF, previous_prof)
            signal.signal(signal.SIGALRM, previous_alarm)

    return limited

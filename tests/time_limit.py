"""A time limit for tests of bounded work: a hang fails the test instead of hanging the suite.

Test modules import it as ``time_limit`` (the ``tests`` folder is on pytest's import path)::

    from time_limit import within_seconds
    _limit = pytest.fixture(autouse=True)(within_seconds(10))
"""

from __future__ import annotations

import signal
from collections.abc import Callable, Iterator

__all__ = ["within_seconds"]


def within_seconds(limit: int) -> Callable[[], Iterator[None]]:
    """A generator fixture body raising :class:`TimeoutError` in the test after ``limit`` seconds
    (``SIGALRM``: the main thread, POSIX)."""

    def limited() -> Iterator[None]:
        def expired(signum: int, frame: object) -> None:
            raise TimeoutError(f"ran past {limit} s")

        previous = signal.signal(signal.SIGALRM, expired)
        signal.alarm(limit)
        try:
            yield
        finally:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, previous)

    return limited

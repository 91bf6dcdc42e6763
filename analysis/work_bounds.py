"""The work bound of the response-time analyses: how many fixed-point steps one task may take.

Busy-window iterations end when the busy period ends; with a level utilisation of exactly 1
and co-prime periods that is the hyperperiod, which can hold ~10⁹ jobs (four tasks with
C = p, T = 4p, p ∈ {1009, 1013, 1019, 1021}). Each analysis therefore spends at most
:data:`RTA_STEP_LIMIT` steps per task (one step: one evaluation of the right-hand side of a
fixed-point equation, or one candidate release tried); the work of a domain is bounded by
``RTA_STEP_LIMIT × n`` steps of ``O(n)`` each. Past the bound the analysis stops with
:class:`WorkCut`, carrying the largest response time found so far (a lower bound of the
worst case): above the deadline it decides a miss, otherwise the task is left undecided
and a warning says what was cut.

The simulation releases at most :data:`SIMULATION_JOB_LIMIT` jobs per group of processors; a
horizon cut to fit is reported, and a cut horizon without a miss is inconclusive.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["RTA_STEP_LIMIT", "SIMULATION_JOB_LIMIT", "StepBudget", "WorkCut"]

#: Fixed-point steps (or candidate releases) one task's response-time analysis may take.
RTA_STEP_LIMIT = 100_000
#: Jobs one simulation group may release; a longer feasibility interval is cut to fit, and the
#: simulation is then inconclusive unless it saw a miss (~10 µs of work and ~200 bytes per job).
SIMULATION_JOB_LIMIT = 200_000


class WorkCut(Exception):
    """The step budget ran out; ``at_least`` is the largest response time found so far (scaled
    to the analysis' integer time base), ``steps`` the budget spent."""

    def __init__(self, at_least: int, steps: int) -> None:
        super().__init__(f"cut after {steps} steps (response time at least {at_least})")
        self.at_least = at_least
        self.steps = steps


@dataclass
class StepBudget:
    """Steps left for one task's analysis; :meth:`spend` raises :class:`WorkCut` past the limit."""

    limit: int = RTA_STEP_LIMIT
    spent: int = 0
    worst: int = 0  #: the largest response time found so far (kept by the analysis)

    def spend(self, steps: int = 1) -> None:
        self.spent += steps
        if self.spent > self.limit:
            raise WorkCut(self.worst, self.limit)

    def found(self, response: int) -> None:
        """Record a response time reached (the lower bound reported when the budget runs out)."""
        if response > self.worst:
            self.worst = response

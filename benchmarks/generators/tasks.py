"""Random task sets for the scheduling analyses, and the same sets as SimSo models.

UUniFast utilisations (Bini and Buttazzo), periods in microseconds or from a menu that keeps the
hyperperiod small, rate-monotonic priorities; SimSo (PyPI ``simso``, optional) set up for one
processor, fixed priority or EDF, as ``bench_scheduling`` and the simulation tests compare it.
"""

from __future__ import annotations

import random
from fractions import Fraction
from typing import Any

from rosaadl.analysis.schedulability import rate_monotonic_priorities
from rosaadl.analysis.tasks import Scheduler, Task

__all__ = [
    "PERIODS",
    "SIMSO_SCHEDULERS",
    "long_run_tasks",
    "random_rta_tasks",
    "random_simulation_sets",
    "simso_model",
    "simso_response_times",
    "uunifast",
]

PERIODS = [10, 20, 25, 40, 50, 100, 125, 200, 250, 500, 1000]
SIMSO_SCHEDULERS = {
    Scheduler.FIXED_PRIORITY: "simso.schedulers.FP",
    Scheduler.EARLIEST_DEADLINE_FIRST: "simso.schedulers.EDF_mono",
}


def uunifast(rng: random.Random, n: int, total: float) -> list[float]:
    """``n`` utilisations summing to ``total``, uniformly distributed (UUniFast)."""
    shares, left = [], total
    for i in range(1, n):
        nxt = left * rng.random() ** (1 / (n - i))
        shares.append(left - nxt)
        left = nxt
    shares.append(left)
    return shares


def _with_rm_priorities(tasks: list[Task]) -> list[Task]:
    priorities = rate_monotonic_priorities(tasks)
    return [Task(t.name, t.period, t.capacity, priority=priorities[t.name]) for t in tasks]


def random_rta_tasks(n: int, utilization: float, seed: int = 1) -> list[Task]:
    """``n`` tasks (periods 10 ms .. 1 s in us, UUniFast utilisations) with RM priorities."""
    rng = random.Random(seed)
    tasks = []
    for i, u in enumerate(uunifast(rng, n, utilization)):
        period = int(10 ** rng.uniform(4, 6))
        tasks.append(Task(f"t{i}", period, max(1, round(u * period))))
    return _with_rm_priorities(tasks)


def random_simulation_sets(count: int, seed: int = 11) -> list[tuple[Scheduler, list[Task]]]:
    """Single-core sets of 5..15 tasks, U = 0.6 .. 0.95, alternately fixed priority (RM order)
    and EDF; periods from a menu so that the hyperperiod stays at most 1 000."""
    rng = random.Random(seed)
    sets = []
    for k in range(count):
        n = rng.randint(5, 15)
        tasks = []
        for i, u in enumerate(uunifast(rng, n, rng.uniform(0.6, 0.95))):
            period = rng.choice(PERIODS)
            tasks.append(Task(f"T{i}", period, max(1, round(u * period))))
        tasks = _with_rm_priorities(tasks)
        sets.append((Scheduler.FIXED_PRIORITY if k % 2 else Scheduler.EARLIEST_DEADLINE_FIRST, tasks))
    return sets


def long_run_tasks(seed: int = 5) -> list[Task]:
    """20 tasks at U = 0.9 with periods 100 .. 5 000 (no priorities: the scheduler gives them)."""
    rng = random.Random(seed)
    tasks = []
    for i, u in enumerate(uunifast(rng, 20, 0.9)):
        period = rng.choice([100, 200, 250, 400, 500, 1000, 1250, 2000, 2500, 5000])
        tasks.append(Task(f"L{i}", period, max(1, round(u * period))))
    return tasks


def simso_model(tasks: list[Task], scheduler_class: str, horizon: int) -> Any:
    """SimSo's model of ``tasks`` on one processor ``cpu`` over ``horizon`` ms, not run yet;
    ``scheduler_class`` names SimSo's scheduler (see ``SIMSO_SCHEDULERS``)."""
    from simso.configuration import Configuration
    from simso.core import Model

    configuration = Configuration()
    configuration.duration = horizon * configuration.cycles_per_ms
    for number, task in enumerate(tasks, start=1):
        configuration.add_task(
            name=task.name,
            identifier=number,
            period=task.period,
            activation_date=task.offset,
            wcet=task.capacity,
            deadline=task.deadline,
            abort_on_miss=False,
            data={"priority": task.priority},
        )
    configuration.add_processor(name="cpu", identifier=1)
    configuration.scheduler_info.clas = scheduler_class
    configuration.check_all()
    return Model(configuration)


def simso_response_times(simulation: Any) -> dict[str, list[Fraction | None]]:
    """The response time of every job of each task of a SimSo model that has run (exact, in
    ms), None for a job it did not complete."""
    cycles = simulation.cycles_per_ms
    return {
        task.name: [
            None if job.end_date is None else Fraction(job.end_date, cycles) - Fraction(job.activation_date)
            for job in task.jobs
        ]
        for task in simulation.results.tasks
    }

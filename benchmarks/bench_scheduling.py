"""Scheduling benchmark: response-time analysis at scale, and our simulator beside SimSo.

Side by side in one run:
  * RTA (preemptive fixed priority, RM priorities) on 1 000 random tasks; floor: under 0.5 s;
  * our event-driven simulator and SimSo (PyPI ``simso``, if installed) on the same random
    single-core task sets, fixed priority and EDF, preemptive, over each set's feasibility
    interval; the per-job response times are compared, and ours must be at least 20x faster;
  * a long simulation (many jobs) for throughput.

Times are CPU seconds of this process (time.process_time), so that other work on the machine
does not blur them; each simulator runs in its own phase (garbage collected in between) so that
neither pays for the other's garbage, and the best of a few alternating rounds is kept.
Usage: ``python -m benchmarks.bench_scheduling [--tasks N] [--sets S] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import io
import random
import time
from fractions import Fraction

from rosaadl.analysis.schedulability import rate_monotonic_priorities, response_times
from rosaadl.analysis.simulation import simulate
from rosaadl.analysis.tasks import Scheduler, Task, TaskSet

__all__ = ["main", "random_rta_tasks", "random_simulation_sets"]

RTA_FLOOR_SECONDS = 0.5
SIMSO_FACTOR_FLOOR = 20.0
_PERIODS = [10, 20, 25, 40, 50, 100, 125, 200, 250, 500, 1000]


def _uunifast(rng: random.Random, n: int, total: float) -> list[float]:
    shares, left = [], total
    for i in range(1, n):
        nxt = left * rng.random() ** (1 / (n - i))
        shares.append(left - nxt)
        left = nxt
    shares.append(left)
    return shares


def random_rta_tasks(n: int, utilization: float, seed: int = 1) -> list[Task]:
    """``n`` tasks (periods 10 ms .. 1 s in us, UUniFast utilisations) with RM priorities."""
    rng = random.Random(seed)
    tasks = []
    for i, u in enumerate(_uunifast(rng, n, utilization)):
        period = int(10 ** rng.uniform(4, 6))
        tasks.append(Task(f"t{i}", period, max(1, round(u * period))))
    priorities = rate_monotonic_priorities(tasks)
    return [Task(t.name, t.period, t.capacity, priority=priorities[t.name]) for t in tasks]


def random_simulation_sets(count: int, seed: int = 11) -> list[tuple[Scheduler, list[Task]]]:
    """Single-core sets of 5..15 tasks, U = 0.6 .. 0.95, alternately fixed priority (RM order)
    and EDF; periods from a menu so that the hyperperiod stays at most 1 000."""
    rng = random.Random(seed)
    sets = []
    for k in range(count):
        n = rng.randint(5, 15)
        tasks = []
        for i, u in enumerate(_uunifast(rng, n, rng.uniform(0.6, 0.95))):
            period = rng.choice(_PERIODS)
            tasks.append(Task(f"T{i}", period, max(1, round(u * period))))
        priorities = rate_monotonic_priorities(tasks)
        tasks = [Task(t.name, t.period, t.capacity, priority=priorities[t.name]) for t in tasks]
        sets.append((Scheduler.FIXED_PRIORITY if k % 2 else Scheduler.EARLIEST_DEADLINE_FIRST, tasks))
    return sets


def _simso_model(tasks: list[Task], scheduler: Scheduler, horizon: int):
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
    configuration.scheduler_info.clas = (
        "simso.schedulers.EDF_mono"
        if scheduler is Scheduler.EARLIEST_DEADLINE_FIRST
        else "simso.schedulers.FP"
    )
    configuration.check_all()
    return Model(configuration)


def _bench_rta(n: int) -> tuple[float, int, float]:
    tasks = random_rta_tasks(n, 0.9)
    runs = []
    bounds: dict = {}
    for _ in range(3):
        start = time.process_time()
        bounds = response_times(tasks)
        runs.append(time.process_time() - start)
    met = sum(1 for t in tasks if bounds[t.name] is not None and bounds[t.name] <= t.deadline)
    return min(runs), met, sorted(runs)[1]


def _run_ours(sets: list[tuple[Scheduler, list[Task]]]) -> tuple[float, list]:
    gc.collect()
    start = time.process_time()
    results = [
        simulate(TaskSet.uniprocessor(tasks, scheduler), record_schedule=False) for scheduler, tasks in sets
    ]
    return time.process_time() - start, results


def _run_simso(sets: list[tuple[Scheduler, list[Task]]], ours: list) -> tuple[float, list]:
    gc.collect()
    models = []
    start = time.process_time()
    with contextlib.redirect_stdout(io.StringIO()):
        for (scheduler, tasks), mine in zip(sets, ours, strict=True):
            model = _simso_model(tasks, scheduler, mine.horizons[("cpu", "")])
            model.run_model()
            models.append(model)
    return time.process_time() - start, models


def _bench_simso(count: int, rounds: int) -> dict:
    """Best of ``rounds`` alternating rounds of each simulator (CPU time of this process)."""
    sets = random_simulation_sets(count)
    try:
        import simso.core  # noqa: F401  (imports the removed ``imp`` module on Python >= 3.12)

        available = True
    except ImportError:
        available = False
    our_times, simso_times = [], []
    ours: list = []
    models: list = []
    for _ in range(rounds if available else 1):
        seconds, ours = _run_ours(sets)
        our_times.append(seconds)
        if available:
            seconds, models = _run_simso(sets, ours)
            simso_times.append(seconds)
            models_last = models
    result = {
        "sets": len(sets),
        "jobs": sum(len(r.jobs) for r in ours),
        "ours": min(our_times),
        "simso": min(simso_times) if available else None,
    }
    if not available:
        return result
    compared = differences = 0
    for model, mine in zip(models_last, ours, strict=True):
        cycles = model.cycles_per_ms
        for task in model.results.tasks:
            for job, record in zip(task.jobs, mine.jobs_of(task.name), strict=False):
                if job.end_date is None or record.completion is None:
                    continue
                compared += 1
                theirs = Fraction(job.end_date, cycles) - Fraction(job.activation_date)
                differences += theirs != record.response_time
    result["compared"], result["differences"] = compared, differences
    return result


def _bench_long() -> tuple[int, float]:
    rng = random.Random(5)
    tasks = []
    for i, u in enumerate(_uunifast(rng, 20, 0.9)):
        period = rng.choice([100, 200, 250, 400, 500, 1000, 1250, 2000, 2500, 5000])
        tasks.append(Task(f"L{i}", period, max(1, round(u * period))))
    taskset = TaskSet.uniprocessor(tasks, Scheduler.RATE_MONOTONIC)
    gc.collect()
    start = time.process_time()
    result = simulate(taskset, horizon=200_000, record_schedule=True)
    return len(result.jobs), time.process_time() - start


def _row(label: str, value: str, floor: str = "", verdict: str = "") -> None:
    print(f"{label:36} {value:>12} {floor:>10} {verdict:>5}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--tasks", type=int, default=1000, help="tasks for the RTA run")
    parser.add_argument("--sets", type=int, default=40, help="random task sets simulated by both")
    parser.add_argument("--rounds", type=int, default=3, help="alternating rounds (best one kept)")
    args = parser.parse_args(argv)
    failed = False

    best, met, median = _bench_rta(args.tasks)
    ok = best < RTA_FLOOR_SECONDS
    failed |= not ok
    _row("measure", "value", "floor", "")
    _row(
        f"RTA, {args.tasks} tasks (CPU, best of 3)",
        f"{best:.3f} s",
        f"{RTA_FLOOR_SECONDS} s",
        "ok" if ok else "FAIL",
    )
    _row("RTA, median of 3", f"{median:.3f} s")
    _row("RTA, tasks meeting their deadline", str(met))

    sim = _bench_simso(args.sets, args.rounds)
    sets, jobs = sim["sets"], sim["jobs"]
    _row(f"ours: {sets} sets, {jobs} jobs", f"{sim['ours']:.3f} s")
    _row("ours: jobs per second", f"{jobs / sim['ours']:.0f}")
    if sim["simso"] is None:
        _row("SimSo: same sets", "not installed", "", "skip")
        print("  (SimSo runs on Python < 3.12: pip install simso==0.8.5, which pulls SimPy 2.3.1)")
    else:
        factor = sim["simso"] / sim["ours"]
        ok = factor >= SIMSO_FACTOR_FLOOR
        failed |= not ok or sim["differences"] != 0
        _row("SimSo: same sets", f"{sim['simso']:.3f} s")
        _row(
            "ours faster than SimSo by",
            f"{factor:.1f}x",
            f"{SIMSO_FACTOR_FLOOR:.0f}x",
            "ok" if ok else "FAIL",
        )
        _row("per-job response times compared", str(sim["compared"]))
        _row(
            "... of which different", str(sim["differences"]), "0", "ok" if not sim["differences"] else "FAIL"
        )

    jobs, seconds = _bench_long()
    _row(f"long run: {jobs} jobs, with schedule", f"{seconds:.3f} s")
    _row("long run: jobs per second", f"{jobs / seconds:.0f}")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())

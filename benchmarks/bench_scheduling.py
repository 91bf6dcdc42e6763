"""Scheduling benchmark: response-time analysis at scale, and our simulator beside SimSo.

Side by side in one run:
  * RTA (preemptive fixed priority, RM priorities) on 1 000 random tasks; floor: under 0.5 s;
  * our event-driven simulator and SimSo (PyPI ``simso``, if installed) on the same random
    single-core task sets, fixed priority and EDF, preemptive, over each set's feasibility
    interval; the per-job response times are compared, and ours must be at least 20x faster;
  * a long simulation (many jobs) for throughput.

Times are CPU seconds of this process (``benchmarks.harness``); each simulator runs in its own
block (garbage collected before each call) so that neither pays for the other's garbage, and
the best of a few alternating rounds is kept. The task sets come from ``benchmarks.generators``.
Usage: ``python -m benchmarks.bench_scheduling [--tasks N] [--sets S] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import statistics

from benchmarks.generators.tasks import (
    SIMSO_SCHEDULERS,
    long_run_tasks,
    random_rta_tasks,
    random_simulation_sets,
    simso_model,
    simso_response_times,
)
from benchmarks.harness import Goal, Report, alternate, best_of
from rosaadl.analysis.schedulability import response_times
from rosaadl.analysis.simulation import simulate
from rosaadl.analysis.tasks import Scheduler, Task, TaskSet

__all__ = ["main"]

RTA_FLOOR_SECONDS = 0.5
SIMSO_FACTOR_FLOOR = 20.0


def _simso_available() -> bool:
    try:
        import simso.core  # noqa: F401  (imports the removed ``imp`` module on Python >= 3.12)
    except ImportError:
        return False
    return True


def _run_simso(sets: list[tuple[Scheduler, list[Task]]], horizons: list[int]) -> list:
    models = []
    with contextlib.redirect_stdout(io.StringIO()):
        for (scheduler, tasks), horizon in zip(sets, horizons, strict=True):
            model = simso_model(tasks, SIMSO_SCHEDULERS[scheduler], horizon)
            model.run_model()
            models.append(model)
    return models


def _differences(models: list, ours: list) -> tuple[int, int]:
    """How many per-job response times both simulators give, and how many of them differ."""
    compared = differences = 0
    for model, mine in zip(models, ours, strict=True):
        for name, theirs in simso_response_times(model).items():
            for response, record in zip(theirs, mine.jobs_of(name), strict=False):
                if response is None or record.completion is None:
                    continue
                compared += 1
                differences += response != record.response_time
    return compared, differences


def _simulators(report: Report, count: int, rounds: int) -> None:
    sets = random_simulation_sets(count)

    def ours() -> list:
        return [
            simulate(TaskSet.uniprocessor(tasks, scheduler), record_schedule=False)
            for scheduler, tasks in sets
        ]

    models: list = []  # SimSo's last run, kept for the comparison (as the results of ours)

    def simso() -> None:
        models[:] = []  # let the last run go first
        models.extend(_run_simso(sets, horizons))

    if not _simso_available():
        timing = best_of(ours, 1)
        results, simso_timing = timing.result, None
    else:
        results = ours()
        horizons = [r.horizons[("cpu", "")] for r in results]
        timings = alternate({"ours": ours, "simso": simso}, rounds)
        timing, simso_timing = timings["ours"], timings["simso"]
    jobs = sum(len(r.jobs) for r in results)
    if simso_timing is None:
        report.time(
            "simulation: random sets", timing, against="SimSo (not installed)", note=f"{len(sets)} sets"
        )
        print("  (SimSo runs on Python < 3.12: pip install simso==0.8.5, which pulls SimPy 2.3.1)")
    else:
        report.time(
            "simulation: random sets",
            timing,
            simso_timing,
            against="SimSo",
            goal=Goal(1 / SIMSO_FACTOR_FLOOR, on="ratio", says=f"{SIMSO_FACTOR_FLOOR:.0f}x faster"),
            note=f"{len(sets)} sets, {jobs} jobs, {simso_timing.cpu / timing.cpu:.1f}x faster",
        )
        compared, differences = _differences(models, results)
        report.add(
            "simulation: per-job responses unlike SimSo's",
            differences,
            "",
            goal=Goal(0),
            note=f"of {compared} compared",
        )
    report.add("simulation: jobs per second", jobs / timing.cpu, "jobs/s", detail=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--tasks", type=int, default=1000, help="tasks for the RTA run")
    parser.add_argument("--sets", type=int, default=40, help="random task sets simulated by both")
    parser.add_argument("--rounds", type=int, default=3, help="alternating rounds (best one kept)")
    args = parser.parse_args(argv)
    report = Report("scheduling")

    tasks = random_rta_tasks(args.tasks, 0.9)
    rta = best_of(lambda: response_times(tasks), 3)
    bounds = rta.result
    met = sum(1 for t in tasks if bounds[t.name] is not None and bounds[t.name] <= t.deadline)
    report.time(
        f"RTA, {args.tasks} tasks",
        rta,
        goal=Goal(RTA_FLOOR_SECONDS),
        note=f"median of 3 {statistics.median(rta.cpu_calls):.3f} s; {met} tasks meet their deadline",
    )

    _simulators(report, args.sets, args.rounds)

    taskset = TaskSet.uniprocessor(long_run_tasks(), Scheduler.RATE_MONOTONIC)
    long = best_of(lambda: simulate(taskset, horizon=200_000, record_schedule=True), 1)
    jobs = len(long.result.jobs)
    report.time("simulation: long run, with schedule", long, note=f"{jobs} jobs")
    report.add("simulation: long run, jobs per second", jobs / long.cpu, "jobs/s")
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

"""The CPU speed gauges of a measured run: how fast each CPU the nodes run on ran interpreted
code while they were measured.

A measured process's CPU time depends on the CPU's speed, which is not a constant: a virtual
machine's CPU runs slower while its host is busy (on a 2-core virtual machine, up to a third
from one run to the next), a robot's board while it is thermally throttled. The emulated
execution times do not (the workload twin burns CPU time); the executor, serialization, DDS and
user code do. So each run measures the speed beside the load, and a profile keeps the speed it
was measured at (``docs/measurements.md``, version 4).

One gauge process per CPU (``python .../cpu_speed.py CPU OUT``: this file alone, it loads
nothing of rosaadl), pinned to it, at the idle scheduling class (``SCHED_IDLE``: it runs only
when the CPU has nothing else to do, so that it does not delay the nodes), samples the CPU
evenly over the measured window: every :data:`INTERVAL` seconds it runs :func:`gauge_work` for
:data:`SAMPLE_NS` of its own CPU time (about 1 % of an idle CPU), counting the iterations. On
SIGTERM or SIGINT it writes ``OUT`` (``{"loops", "cpu_ns", "samples"}``, atomically). The speed
is loops per ms of CPU time (:func:`speed_of`); a process's is the mean over the CPUs it may run
on. Evenly sampled, it follows the middleware of the tracking example's small processes from run
to run within about ±6 %, where the workload twin's own loop, which samples a CPU only while a
twin burns, followed it within ±8 % (14 runs).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

__all__ = [
    "INTERVAL",
    "SAMPLE_NS",
    "MAX_CPUS",
    "gauge_work",
    "speed_of",
    "CpuSpeedGauges",
    "main",
]

#: Seconds between two samples, and the CPU time (ns) of one sample.
INTERVAL = 0.05
SAMPLE_NS = 500_000
#: At most this many CPUs are gauged (the lowest numbered of those the nodes may run on).
MAX_CPUS = 16
_STOP_SECONDS = 5.0


def gauge_work() -> list[int]:
    """One iteration of the gauge: a few µs of Python object work (allocation, hashing,
    sorting: what an executor's wait loop does)."""
    return sorted(dict.fromkeys([i * 2 for i in range(24)]), reverse=True)


def speed_of(result: dict) -> float | None:
    """Loops per ms of CPU time of one gauge's output (None without a sample)."""
    loops, cpu_ns = result.get("loops", 0), result.get("cpu_ns", 0)
    if not isinstance(loops, int) or not isinstance(cpu_ns, int) or loops <= 0 or cpu_ns <= 0:
        return None
    return round(loops / cpu_ns * 1e6, 3)


class CpuSpeedGauges:
    """The gauges of one measured window: :meth:`start` on the CPUs, :meth:`stop` for the
    speed of each (CPUs whose gauge wrote nothing are left out)."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        self.running: dict[int, tuple[subprocess.Popen, Path]] = {}

    def start(self, cpus: set[int]) -> None:
        self.folder.mkdir(parents=True, exist_ok=True)
        for cpu in sorted(cpus)[:MAX_CPUS]:
            out = self.folder / f"cpu_speed.{cpu}.json"
            out.unlink(missing_ok=True)
            process = subprocess.Popen(
                [sys.executable, str(Path(__file__).resolve()), str(cpu), str(out)],
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,
            )
            self.running[cpu] = (process, out)

    def stop(self) -> dict[int, float]:
        for process, _out in self.running.values():
            if process.poll() is None:
                process.terminate()
        speeds = {}
        for cpu, (process, out) in sorted(self.running.items()):
            try:
                process.wait(timeout=_STOP_SECONDS)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
            try:
                speed = speed_of(json.loads(out.read_text(encoding="utf-8")))
            except (OSError, ValueError, AttributeError):
                speed = None
            if speed is not None:
                speeds[cpu] = speed
        self.running = {}
        return speeds


def main(argv: list[str]) -> int:
    """Gauge CPU ``argv[0]`` until SIGTERM or SIGINT, then write ``argv[1]``."""
    cpu, out = int(argv[0]), Path(argv[1])
    os.sched_setaffinity(0, {cpu})
    try:
        os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))
    except (AttributeError, OSError):
        os.nice(19)
    stopped = []
    signal.signal(signal.SIGTERM, lambda *_: stopped.append(True))
    signal.signal(signal.SIGINT, lambda *_: stopped.append(True))
    loops = cpu_ns = samples = 0
    while not stopped:
        began = time.thread_time_ns()
        count = 0
        while time.thread_time_ns() - began < SAMPLE_NS:
            gauge_work()
            count += 1
        loops += count
        cpu_ns += time.thread_time_ns() - began
        samples += 1
        time.sleep(INTERVAL)
    part = out.with_name(out.name + ".part")
    part.write_text(json.dumps({"loops": loops, "cpu_ns": cpu_ns, "samples": samples}), encoding="utf-8")
    os.replace(part, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

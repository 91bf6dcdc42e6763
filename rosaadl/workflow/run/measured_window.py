"""The measured window of a ``rosaadl run … --measure``: the trace folder the nodes write into,
``/proc`` sampled when the S seconds begin and end, the speed of the nodes' CPUs gauged over them
(:mod:`~rosaadl.workflow.run.cpu_speed`), and ``measurements.json`` written at the end (see
:mod:`~rosaadl.workflow.run.measure`)."""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path
from typing import Any

from rosaadl.fileio import atomic_write_text
from rosaadl.workflow.run.cpu_speed import CpuSpeedGauges
from rosaadl.workflow.run.measure import (
    MEASUREMENTS_FILE,
    TRACE_FOLDER,
    TRACE_PARAMETERS,
    cpu_seconds_between,
    measurements_document,
    process_cpu_seconds,
    process_cpus,
    read_traces,
    single_cpu,
    thread_cpu_ns,
)
from rosaadl.workflow.run.profiles import run_profile

__all__ = ["MeasuredWindow", "whole_periods"]


def whole_periods(duration: float, nodes: list[Any]) -> float:
    """The measured window for ``duration`` seconds of ``nodes`` (the run plan's, periods as
    scaled): ``duration`` rounded up to a whole number of the longest period of their timers,
    where that period is at most ``duration``. Every periodic thread is then released as many
    times in the window whatever phase the window starts at (a 10 s window holds 33 or 34
    releases of a 300 ms timer: its CPU load measured 3 % apart from one run to the next), and a
    thread whose period divides the longest one (the usual harmonic periods) exactly so."""
    longest = max((p for node in nodes for p in node.timer_periods().values()), default=0.0)
    if not 0 < longest <= duration:
        return duration
    return round(math.ceil(duration / longest - 1e-9) * longest, 6)


class MeasuredWindow:
    """One measured run: ``parameters()`` for the nodes, ``begin()`` and ``end()`` around the
    S seconds, ``write()`` once the nodes have stopped (and flushed their traces)."""

    def __init__(self, folder: Path, processes: list[Any]) -> None:
        self.folder = folder
        self.traces = (folder / TRACE_FOLDER).resolve()
        self.processes = processes  # filled as the nodes start
        self.traces.mkdir(parents=True, exist_ok=True)
        for old in self.traces.glob("*.trace"):  # the traces of an earlier run of the folder
            old.unlink()
        self.started_ns = self.ended_ns = 0
        self.cpu_before: dict[str, float | None] = {}
        self.cpu_after: dict[str, float | None] = {}
        self.threads_before: dict[str, dict[int, int] | None] = {}
        self.threads_after: dict[str, dict[int, int] | None] = {}
        self.gauges = CpuSpeedGauges(folder / TRACE_FOLDER)
        self.allowed: dict[str, set[int]] = {}  # node -> the CPUs it may run on
        self.cpu_speeds: dict[int, float] = {}

    def parameters(self) -> list[tuple[str, object]]:
        return TRACE_PARAMETERS(self.traces)

    def _sample(self) -> dict[str, float | None]:
        return {
            p.node.full_name: process_cpu_seconds(p.process.pid) if p.process is not None else None
            for p in self.processes
        }

    def _sample_threads(self) -> dict[str, dict[int, int] | None]:
        return {
            p.node.full_name: thread_cpu_ns(p.process.pid) if p.process is not None else None
            for p in self.processes
        }

    def begin(self) -> None:
        self.threads_before = self._sample_threads()
        self.cpu_before = self._sample()
        self.allowed = {
            p.node.full_name: process_cpus(p.process.pid) for p in self.processes if p.process is not None
        }
        self.gauges.start(set().union(*self.allowed.values()))
        self.started_ns = time.monotonic_ns()

    def end(self) -> None:
        self.ended_ns = time.monotonic_ns()
        self.cpu_after = self._sample()
        self.threads_after = self._sample_threads()
        self.cpu_speeds = self.gauges.stop()

    def stop_gauges(self) -> None:
        """Stop the CPU speed gauges of a run that ended early (nothing once stopped)."""
        self.gauges.stop()

    def process_speeds(self) -> dict[str, float]:
        """Per node: the mean speed of the gauged CPUs it may run on."""
        out = {}
        for name, cpus in self.allowed.items():
            speeds = [self.cpu_speeds[cpu] for cpu in sorted(cpus) if cpu in self.cpu_speeds]
            if speeds:
                out[name] = round(sum(speeds) / len(speeds), 3)
        return out

    def write(self, plan: Any, result: Any, options: Any) -> Path:
        """Aggregate the traces and the samples into ``measurements.json`` (checked against its
        schema, written atomically); its path."""
        from rosaadl.importers.measurements import parse_measurements

        seconds = max(1e-9, (self.ended_ns - self.started_ns) / 1e9)
        cpu_load = {
            name: (self.cpu_after[name] - before) / seconds * 100
            for name, before in self.cpu_before.items()
            if before is not None and self.cpu_after.get(name) is not None
        }
        for name, before in self.threads_before.items():  # to the ns where the kernel counts so
            after = self.threads_after.get(name)
            if before is not None and after is not None:
                cpu_load[name] = cpu_seconds_between(before, after) / seconds * 100
        document = measurements_document(
            nodes=plan.nodes,
            traces=read_traces(self.traces, (self.started_ns, self.ended_ns)),
            cpu_load=cpu_load,
            cores={name: single_cpu(cpus) for name, cpus in self.allowed.items()},
            topics=result.topics,
            chains=options.chains,
            run={
                "duration_s": round(seconds, 3),
                "emulate": bool(options.emulate),
                "host_cores": os.cpu_count() or 1,
                "period_scale": float(getattr(result, "period_scale", 1.0)),
            },
            root=options.root,
            profiles={n.full_name: run_profile(n.profile, emulate=options.emulate) for n in plan.nodes},
            cpu_speeds=self.process_speeds(),
        )
        text = json.dumps(document, indent=2) + "\n"
        target = self.folder / MEASUREMENTS_FILE
        parse_measurements(text, str(target))  # what is written reads back
        atomic_write_text(target, text)
        return target

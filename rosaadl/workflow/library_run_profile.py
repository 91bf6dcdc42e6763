"""A measured run (``measurements.json``) as the rows ``rosaadl library add-profile`` turns into
platform-dependent implementations, for the board and core the run was bound to.

:func:`run_measurement_rows` gives one :class:`~rosaadl.workflow.library_measurements.Measurement`
per measured thread with a dispatch:

* the node: its process's classifier without the implementation (``processes[].classifier``,
  ``nd_usb_cam::usb_cam_nd``), else its ROS node name (``processes[].node``, the model's
  ``ROS_Properties::Node_Name``), else the process's instance name;
* the thread: the last segment of its instance path;
* the PDM ``<board>_<core>``: the process's ``processes[].profile`` (what ``rosaadl run`` writes:
  the PDM it emulated, else this machine, see :mod:`rosaadl.workflow.run.profiles`), else the
  run's ``run.board`` and ``run.core`` (then required);
* the execution time: the thread's mean CPU time per dispatch, plus its process's CPU time per
  dispatch beyond its callbacks (executor, serialization, DDS), the same for every dispatch of
  the process (:func:`middleware_per_dispatch`: rclpy's executor spends about the same on each
  dispatch, waking up, making a wait set, taking and handing over), so that the PDM's
  Σ CET / Period is the node's measured CPU load, as a profile of a whole node measures it, and
  each callback's execution time carries the executor work its own dispatches cause, as the
  executor analysis's busy windows need;
* the Period: the PIM's; nothing is written. A run with scaled periods (``run.period_scale``)
  gives the same profile as an unscaled one: the CPU time of a dispatch and the middleware's
  CPU time per dispatch (both measured at the scaled rates) do not depend on the scale;
* ``Data_Size``: the bytes per message of the one topic the thread publishes, when measured;
* ``ROS_Properties::Dispatch_Latency``: the max of the thread's ``dispatch_latency_us`` (a
  timer thread's latency from its release to its start while its executor was idle, version 3),
  rounded up to a whole µs, when measured;
* ``ROS_Properties::Twin_Execution_Time`` and ``ROS_Properties::Profiled_CPU_Speed``, for every
  thread of a process whose CPUs the run gauged (``cpu_speed``, version 4): what of the
  execution time the workload twin held whatever the CPU's speed (its
  ``twin_execution_time_us``; 0 where no twin ran: user code) and the speed of the process's
  CPUs: ``analyze --compare`` rescales the rest of the execution time to the speed a later run
  measures;
* no ``Raw_MIPS``, ``IPC`` or ``MIPSBudget``: a run without hardware counters measures no
  instruction rate, and the library leaves out what was not measured.

Rows are numbered after ``$.threads`` (row 1 is ``$.threads[0]``) and located at its line.
"""

from __future__ import annotations

import math
import re

from rosaadl.errors import Diagnostic, Location, ParseError, RosaadlError
from rosaadl.importers.json_schema import value_lines
from rosaadl.importers.measurements import Measurements, parse_measurements
from rosaadl.workflow.library_measurements import Measurement, MeasurementError

__all__ = ["run_measurement_rows", "middleware_per_dispatch"]

_PART = re.compile(r"[A-Za-z0-9](?:_?[A-Za-z0-9])*\Z")
#: a dispatch latency or twin time above this (µs, about 31 years) is refused: the model's times
#: are 64-bit ns
_MAX_TIME_US = 10**15


def middleware_per_dispatch(measurements: Measurements) -> dict[str, float]:
    """Per thread path: the CPU time (µs) its process spends per dispatch beyond its callbacks
    (executor, serialization, DDS): the process's measured load less its threads' loads, divided
    evenly among the dispatches of all its threads with a period (rclpy's executor spends about
    the same on each: waking up, making a wait set, taking the timer or message, handing it
    over); 0 where the process is not measured or spent no more than its callbacks."""
    loads: dict[str, float] = {}
    rates: dict[str, float] = {}
    for thread in measurements.threads:
        if thread.load_percent is not None and thread.period_mean_us:
            key = thread.process or thread.path.rpartition(".")[0]
            loads[key] = loads.get(key, 0.0) + thread.load_percent
            rates[key] = rates.get(key, 0.0) + 1e6 / thread.period_mean_us  # dispatches per second
    cost: dict[str, float] = {}
    for process in measurements.processes:
        beyond = process.cpu_load_percent - loads.get(process.path, 0.0)
        if beyond > 0 and rates.get(process.path):
            cost[process.path] = beyond / 100 * 1e6 / rates[process.path]  # µs of CPU per dispatch
    return {t.path: cost.get(t.process or t.path.rpartition(".")[0], 0.0) for t in measurements.threads}


def _twin(thread, speed: float | None) -> dict[str, object]:
    """The speed values of a profile row where the run gauged its process's CPUs: the thread's
    speed-independent CPU time per dispatch (ns; 0 without a twin) and the CPUs' speed."""
    if speed is None:
        return {}
    return {"twin_execution_time_ns": round((thread.twin_execution_time_us or 0) * 1000), "cpu_speed": speed}


def run_measurement_rows(
    data: bytes, file: str
) -> tuple[list[Measurement], list[RosaadlError], list[Diagnostic]]:
    """The rows of the measured run in ``data`` (the bytes of a ``measurements.json``), the
    problems (located) and warnings; a file that is not a valid ``measurements.json`` raises a
    located :class:`~rosaadl.errors.ParseError`."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ParseError(f"not UTF-8 text (byte {exc.start})", file=file) from None
    measurements = parse_measurements(text, file)
    lines = value_lines(text)
    errors: list[RosaadlError] = []
    notes: list[Diagnostic] = []
    named = {p.path: p.profile for p in measurements.processes if p.profile is not None}
    places = {p.path: f"$.processes[{i}].profile" for i, p in enumerate(measurements.processes)}
    needed = {t.process or t.path.rpartition(".")[0] for t in measurements.threads}
    board, core = measurements.run_value("board"), measurements.run_value("core")
    checks = [(f"$.run.{n}", f"run.{n}", v) for n, v in (("board", board), ("core", core))]
    if needed <= set(named):  # every process names its own: run.board and run.core are not needed
        checks = []
    for path, pair in named.items():
        checks += [
            (f"{places[path]}.{n}", f"{places[path][2:]}.{n}", v)
            for n, v in zip(("board", "core"), pair, strict=True)
        ]
    for where, name, value in checks:
        if value is None or not _PART.match(value):
            shown = "none" if value is None else repr(value)
            errors.append(
                MeasurementError(
                    f"{name}: the board and core the run was bound to name the profile "
                    f"(<board>_<core>, letters, digits and single underscores); found {shown}",
                    Location(
                        file=file,
                        line=lines.get(where, lines.get(where.rpartition(".")[0], 1)),
                        path=where,
                    ),
                )
            )
    if errors:
        return [], errors, notes
    nodes = {
        p.path: (p.classifier.partition(".")[0] if p.classifier else None)
        or p.node
        or p.path.rpartition(".")[2]
        for p in measurements.processes
    }
    middleware = middleware_per_dispatch(measurements)
    speeds = {p.path: p.cpu_speed for p in measurements.processes}
    sizes: dict[str, list[int | None]] = {}
    for topic in measurements.topics:
        if topic.port:
            sizes.setdefault(topic.port.rpartition(".")[0], []).append(topic.bytes_per_message)
    rows = []
    for index, thread in enumerate(measurements.threads):
        where = f"$.threads[{index}]"
        if thread.execution_time_us is None or thread.execution_time_us.mean <= 0:
            notes.append(
                Diagnostic(
                    "warning",
                    f"{where}: thread {thread.path} has no dispatch with CPU time; it gets no profile",
                    Location(file=file, line=lines.get(where), path=where),
                )
            )
            continue
        latency = thread.dispatch_latency_us
        burned = thread.twin_execution_time_us
        too_long = [
            (f"{where}.{member}", value)
            for member, value in (
                ("dispatch_latency_us.max", None if latency is None else latency.max),
                ("twin_execution_time_us", burned),
            )
            if value is not None and value > _MAX_TIME_US
        ]
        if too_long:
            errors += [
                MeasurementError(
                    f"{at[2:]}: {value:g} us is out of range (at most {_MAX_TIME_US} us)",
                    Location(file=file, line=lines.get(at, lines.get(where, 1)), path=at),
                )
                for at, value in too_long
            ]
            continue
        process = thread.process or thread.path.rpartition(".")[0]
        if burned is not None and speeds.get(process) is None:
            notes.append(
                Diagnostic(
                    "warning",
                    f"{where}: thread {thread.path} ran the workload twin, but the run gauged no "
                    "CPU of its process (no cpu_speed); its profile keeps no speed",
                    Location(file=file, line=lines.get(where), path=where),
                )
            )
        inside = thread.path[len(process) + 1 :] if thread.path.startswith(f"{process}.") else None
        published = sizes.get(thread.path, [])
        rows.append(
            Measurement(
                file=file,
                row=index + 1,
                line=lines.get(where, 1),
                node=nodes.get(process, process.rpartition(".")[2]),
                thread=inside or thread.path.rpartition(".")[2],  # in thread groups: dotted
                board=named.get(process, (board, core))[0],
                core=named.get(process, (board, core))[1],
                period_ns=None,
                cet_ns=max(1, round((thread.execution_time_us.mean + middleware[thread.path]) * 1000)),
                mips_raw=None,
                ipc=None,
                data_size=published[0] if len(published) == 1 else None,
                processor=None,
                dispatch_latency_ns=None if latency is None else math.ceil(latency.max) * 1000,
                **_twin(thread, speeds.get(process)),
            )
        )
    return ([] if errors else rows), errors, notes

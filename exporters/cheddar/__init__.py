"""AADL instances as Cheddar XML: Cheddar 3 ADL (``.xmlv3``) or Cheddar 2 (``cheddar_format=2``);
by default the format a model read from Cheddar came in, else Cheddar 3.

What becomes what (the inverse of :mod:`rosaadl.importers.cheddar`, plus the AADL
conventions Ocarina and OSATE's Cheddar plugin use):

* top-level ``processor`` instances → processors; one with ``processor`` subcomponents (an
  SoC with cores, possibly in clusters) → ``multi_cores_processor`` whose core units are
  its innermost processors; a plain processor → ``mono_core_processor`` with one core unit;
  ``Scheduling_Protocol`` → the core's scheduler (RMS / Rate_Monotonic_Protocol →
  RATE_MONOTONIC_PROTOCOL, EDF → EARLIEST_DEADLINE_FIRST_PROTOCOL, ...);
* ``process`` instances → address spaces (threads outside any process get one per processor);
* ``thread`` instances → tasks by ``Dispatch_Protocol`` (periodic, sporadic, aperiodic, ...),
  ``Actual_Processor_Binding`` → ``cpu_name`` (and ``core_name`` when bound to a core),
  the upper bound of ``Compute_Execution_Time`` → capacity, ``Dispatch_Offset`` →
  start_time, ``Dispatch_Jitter`` → jitter, ``Priority`` (or Ocarina's
  ``Cheddar_Properties::Fixed_Priority``) → priority;
* ``data`` with ``Concurrency_Control_Protocol`` → a resource whose critical sections are
  the whole execution of the threads that access it (so Cheddar serialises them — the
  ROSMOD callback queue of a component); ``Priority_Inheritance`` → pip_resource,
  ``Priority_Ceiling`` → pcp_resource, ``Protected_Access``/``Maximum_Priority`` → ipcp;
* port connections between threads → a buffer per receiving port with QUEUEING_BUFFER
  dependencies (event ports: PRECEDENCE dependencies); connections bound to a bus
  (``Actual_Connection_Binding``) or between processors → a message per sending port with
  ASYNCHRONOUS_COMMUNICATION dependencies, and the buses → networks;
* entities imported from Cheddar (they carry ``Cheddar_Properties::Cheddar_Name``) are
  written back exactly as they were read: same names, ids, fields and order.

Names are ``Cheddar_Name`` or the dotted instance path below the root. Times are written in
``time_unit`` (``us`` by default, or ``ms``); a time that is not a whole number of that
unit is an :class:`ExportError` listing every such value, never a silent rounding.

The package: :mod:`~.context` (the export's state and how values become text),
:mod:`~.system` (the intermediate Cheddar system), :mod:`~.collect` with :mod:`~.hardware`,
:mod:`~.software` and :mod:`~.communication` (reading the instance into it), :mod:`~.fields`,
:mod:`~.v3` and :mod:`~.v2` (writing XML), :mod:`~.structure` (what Cheddar's reader would
reject), :mod:`~.export` (the entry points). The vocabulary it shares with the reader is
:mod:`rosaadl.importers.cheddar.vocabulary`.
"""

from rosaadl.exporters.cheddar.export import dumps_cheddar, write_cheddar
from rosaadl.exporters.cheddar.structure import structure_problems
from rosaadl.importers.cheddar.vocabulary import EXPORT_SECTIONS_V3

__all__ = ["dumps_cheddar", "write_cheddar", "structure_problems", "EXPORT_SECTIONS_V3"]

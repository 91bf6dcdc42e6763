"""Cheddar XML models (Cheddar 3.x ADL ``.xmlv3`` and Cheddar 2.x DTD-style ``.xml``) as AADL instances.

The result is an ``AadlModel`` holding one ``SystemInstance`` named after the file, laid out
as ``docs/instance-model.md`` ("Cheddar-imported instances") says:

* processors → ``processor`` instances; a mono-core processor is one instance that also
  carries its core unit's facts (``Cheddar_Properties::Core_Name``/``Core_Id`` and the
  scheduler); a multi-core processor has one ``processor`` subcomponent per core unit;
* address spaces → ``process`` instances bound with ``Actual_Processor_Binding``;
* tasks → ``thread`` instances inside their address space's process (directly under the
  root when they have none), bound to their processor, or to their core when the task has
  a core affinity on a multi-core processor; timing in the standard properties
  (``Period``, ``Deadline``, ``Compute_Execution_Time`` as ``c .. c``, ``Dispatch_Offset``
  for ``start_time``, ``Dispatch_Jitter``, ``Priority``, ``Dispatch_Protocol``,
  ``POSIX_Scheduling_Policy``) in the file's time unit (``us`` unless told ``ms``);
* resources, buffers and messages → ``data`` instances (``Cheddar_Properties::Data_Role``),
  resources with ``Concurrency_Control_Protocol`` and ``Cheddar_Properties::Critical_Sections``;
* networks → ``bus`` instances; dependencies → connection instances between the threads'
  features and the data components (``Cheddar_Properties::Dependency_Type``);
* the scheduler of a core → ``Scheduling_Protocol`` when AADL has a literal for it,
  otherwise ``Cheddar_Properties::Scheduler``; everything else Cheddar has goes into the
  ``Cheddar_Properties`` property set (``library/properties/Cheddar_Properties.aadl``).

Nothing is dropped: names and ids (``Cheddar_Name``, ``Cheddar_Id``), the order of the
file (``Section_Index``, ``Section_Order``), and the sections and fields rosaadl does not
model (kept verbatim in ``Unmodelled_Elements`` / ``Unmodelled_Fields``), so that
import → export → import gives an equal model.

Cheddar's own rules are followed for bad input: Cheddar 3's reader checks that a task's,
resource's or buffer's processor and address space exist and agree, that ids are unique and
that every ``ref`` resolves; those are located errors here. Cheddar 2's reader checks none
of the location names, and real Cheddar 2 files rely on it (a task on an undeclared
processor): such names are kept as unresolved references with a warning, and are errors
with ``strict=True``. Tags are matched case-insensitively and enumeration values in any
case, as Cheddar's reader does, and scheduler fields are read with or without Cheddar's
``<scheduling_parameters>`` wrapper (OSATE plug-ins leave it out; see :mod:`~.scheduling`).
Hostile XML (entity declarations, external DTDs) is refused.

The package: :mod:`~.vocabulary` (the field tables and enumerations the reader and the writer
share), :mod:`~.document` (the XML document and its two styles), :mod:`~.values` (the model
values made), :mod:`~.state` (the reader's state and primitive steps), :mod:`~.entities`,
:mod:`~.records`, :mod:`~.scheduling` and :mod:`~.connections` (what becomes what),
:mod:`~.v3` and :mod:`~.v2` (what only one file style has), :mod:`~.reader` (the entry points).
"""

from rosaadl.importers.cheddar.document import canonical_xml, cheddar_format_of, strip_internal_subset
from rosaadl.importers.cheddar.reader import load_cheddar, loads_cheddar
from rosaadl.importers.cheddar.values import aadl_identifier
from rosaadl.importers.cheddar.vocabulary import (
    AADL_TO_RESOURCE_PROTOCOL,
    AADL_TO_SCHEDULER,
    ADDRESS_SPACE_FIELDS,
    BUFFER_FIELDS,
    CORE_FIELDS,
    CP,
    DEPENDENCY_ENDS,
    DISPATCH_TO_TASK_TYPE,
    ENUMERATIONS,
    MESSAGE_FIELDS,
    MESSAGE_TAGS,
    NETWORK_FIELDS,
    NETWORK_TAGS,
    PROCESSOR_FIELDS,
    RESOURCE_FIELDS,
    RESOURCE_PROTOCOL_TO_AADL,
    RESOURCE_TAGS,
    SCHEDULER_TO_AADL,
    SCHEDULING_FIELDS,
    SECTIONS_V2,
    SECTIONS_V3,
    TASK_FIELDS,
    TASK_TYPE_TAGS,
    TASK_TYPE_TO_DISPATCH,
    TIME_UNITS,
    V2_ADDRESS_SPACE_FIELDS,
    V2_BUFFER_FIELDS,
    V2_MESSAGE_FIELDS,
    V2_NETWORK_FIELDS,
    V2_RESOURCE_FIELDS,
    V2_TASK_FIELDS,
    Field,
)

__all__ = [
    "CP",
    "TIME_UNITS",
    "Field",
    "load_cheddar",
    "loads_cheddar",
    "cheddar_format_of",
    "strip_internal_subset",
    "aadl_identifier",
    "canonical_xml",
    "SCHEDULER_TO_AADL",
    "AADL_TO_SCHEDULER",
    "RESOURCE_PROTOCOL_TO_AADL",
    "AADL_TO_RESOURCE_PROTOCOL",
    "TASK_TYPE_TO_DISPATCH",
    "DISPATCH_TO_TASK_TYPE",
    "TASK_TYPE_TAGS",
    "RESOURCE_TAGS",
    "NETWORK_TAGS",
    "MESSAGE_TAGS",
    "DEPENDENCY_ENDS",
    "SCHEDULING_FIELDS",
    "CORE_FIELDS",
    "PROCESSOR_FIELDS",
    "ADDRESS_SPACE_FIELDS",
    "TASK_FIELDS",
    "RESOURCE_FIELDS",
    "BUFFER_FIELDS",
    "MESSAGE_FIELDS",
    "NETWORK_FIELDS",
    "V2_TASK_FIELDS",
    "V2_ADDRESS_SPACE_FIELDS",
    "V2_RESOURCE_FIELDS",
    "V2_BUFFER_FIELDS",
    "V2_MESSAGE_FIELDS",
    "V2_NETWORK_FIELDS",
    "ENUMERATIONS",
    "SECTIONS_V3",
    "SECTIONS_V2",
]

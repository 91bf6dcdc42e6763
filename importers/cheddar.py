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
case, as Cheddar's reader does. Hostile XML (entity declarations, external DTDs) is refused.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Callable, Iterable
from copy import deepcopy
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NoReturn

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.bulk import gc_paused
from rosaadl.errors import Diagnostic, ImportFormatError, Location, RosaadlError, UsageError
from rosaadl.fileio import element_path, parse_xml_bytes

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

log = logging.getLogger(__name__)

CP = "Cheddar_Properties::"
TIME_UNITS = ("us", "ms")

# Standard properties used for Cheddar facts.
PERIOD = "Timing_Properties::Period"
DEADLINE = "Timing_Properties::Deadline"
CET = "Timing_Properties::Compute_Execution_Time"
OFFSET = "Timing_Properties::Dispatch_Offset"
JITTER = "Timing_Properties::Dispatch_Jitter"
PRIORITY = "Thread_Properties::Priority"
DISPATCH = "Thread_Properties::Dispatch_Protocol"
POLICY = "Thread_Properties::POSIX_Scheduling_Policy"
CCP = "Thread_Properties::Concurrency_Control_Protocol"
BINDING = "Deployment_Properties::Actual_Processor_Binding"
SCHEDULING = "Deployment_Properties::Scheduling_Protocol"
PREEMPTIVE_SCHEDULER = "Deployment_Properties::Preemptive_Scheduler"

# --------------------------------------------------------------------------- vocabulary

SCHEDULERS = [
    "RATE_MONOTONIC_PROTOCOL",
    "DEADLINE_MONOTONIC_PROTOCOL",
    "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL",
    "EARLIEST_DEADLINE_FIRST_PROTOCOL",
    "EARLIEST_DEADLINE_FIRST_ENERGY_TO_TIME_PROTOCOL",
    "EARLIEST_DEADLINE_FIRST_ENERGY_HARVESTING_PROTOCOL",
    "LEAST_LAXITY_FIRST_PROTOCOL",
    "LEAST_RUNTIME_LAXITY_FIRST_PROTOCOL",
    "ROUND_ROBIN_PROTOCOL",
    "MAXIMUM_URGENCY_FIRST_BASED_ON_DEADLINE_PROTOCOL",
    "MAXIMUM_URGENCY_FIRST_BASED_ON_LAXITY_PROTOCOL",
    "TIME_SHARING_BASED_ON_WAIT_TIME_PROTOCOL",
    "TIME_SHARING_BASED_ON_CPU_USAGE_PROTOCOL",
    "D_OVER_PROTOCOL",
    "PIPELINE_USER_DEFINED_PROTOCOL",
    "AUTOMATA_USER_DEFINED_PROTOCOL",
    "COMPILED_USER_DEFINED_PROTOCOL",
    "USER_DEFINED_PROTOCOL",
    "HIERARCHICAL_CYCLIC_PROTOCOL",
    "HIERARCHICAL_OFFLINE_PROTOCOL",
    "HIERARCHICAL_ROUND_ROBIN_PROTOCOL",
    "HIERARCHICAL_FIXED_PRIORITY_PROTOCOL",
    "HIERARCHICAL_POLLING_APERIODIC_SERVER_PROTOCOL",
    "HIERARCHICAL_DEFERRABLE_APERIODIC_SERVER_PROTOCOL",
    "HIERARCHICAL_PRIORITY_EXCHANGE_APERIODIC_SERVER_PROTOCOL",
    "HIERARCHICAL_SPORADIC_APERIODIC_SERVER_PROTOCOL",
    "DAG_HIGHEST_LEVEL_FIRST_ESTIMATED_TIMES_PROTOCOL",
    "MIXED_CRITICALITY_SMC_PROTOCOL",
    "MIXED_CRITICALITY_AMC_PROTOCOL",
    "MIXED_CRITICALITY_RECURRENT_QUALITY_AMC_PROTOCOL",
    "MIXED_CRITICALITY_QUALITY_AMC_PROTOCOL",
    "MIXED_CRITICALITY_EDF_VD_PROTOCOL",
    "PROPORTIONATE_FAIR_PF_PROTOCOL",
    "PROPORTIONATE_FAIR_PD_PROTOCOL",
    "PROPORTIONATE_FAIR_PD2_PROTOCOL",
    "REDUCTION_TO_UNIPROCESSOR_PROTOCOL",
    "EARLIEST_DEADLINE_ZERO_LAXITY_PROTOCOL",
    "LARGEST_LOCAL_REMAINING_EXECUTION_FIRST_PROTOCOL",
    "NO_SCHEDULING_PROTOCOL",
]

#: Enumeration types of Cheddar fields stored as AADL enumeration literals (NamedValue).
ENUMERATIONS: dict[str, tuple[str, ...]] = {
    "scheduler": tuple(SCHEDULERS),
    "task_type": (
        "PERIODIC_TYPE",
        "APERIODIC_TYPE",
        "SPORADIC_TYPE",
        "POISSON_TYPE",
        "TIMED_TYPE",
        "PARAMETRIC_TYPE",
        "SCHEDULING_TASK_TYPE",
        "FRAME_TASK_TYPE",
        "SPORADIC_INNER_PERIODIC_TYPE",
        "PERIODIC_INNER_PERIODIC_TYPE",
    ),
    "policy": ("SCHED_FIFO", "SCHED_RR", "SCHED_OTHERS"),
    "resource_protocol": (
        "NO_PROTOCOL",
        "PRIORITY_CEILING_PROTOCOL",
        "POOL_BASED_PRIORITY_CEILING_PROTOCOL",
        "PRIORITY_INHERITANCE_PROTOCOL",
        "IMMEDIATE_PRIORITY_CEILING_PROTOCOL",
    ),
    "priority_assignment": ("AUTOMATIC_ASSIGNMENT", "MANUAL_ASSIGNMENT"),
    "synchronization": ("MUTEX", "WAIT", "POST"),
    "buffer_role": (
        "QUEUING_PRODUCER",
        "QUEUING_CONSUMER",
        "SAMPLING_WRITER",
        "SAMPLING_READER",
        "UCSDF_PRODUCER",
        "UCSDF_CONSUMER",
        "ICQ_PRODUCER",
        "ICQ_CONSUMER",
    ),
    "message_type": ("PERIODIC_TYPE", "APERIODIC_TYPE"),
    "preemptive": ("PREEMPTIVE", "NOT_PREEMPTIVE"),
    "dependency_type": (
        "PRECEDENCE_DEPENDENCY",
        "QUEUEING_BUFFER_DEPENDENCY",
        "TDMA_COMMUNICATION_DEPENDENCY",
        "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY",
        "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY",
        "RESOURCE_DEPENDENCY",
        "REMOTE_PROCEDURE_CALL_DEPENDENCY",
        "BLACK_BOARD_BUFFER_DEPENDENCY",
    ),
    "orientation": ("FROM_OBJECT_TO_TASK", "FROM_TASK_TO_OBJECT"),
    "async_protocol": ("FIRST_MESSAGE", "ALL_MESSAGES"),
    "tt_timing": ("SAMPLED_TIMING", "IMMEDIATE_TIMING", "DELAYED_TIMING"),
    "bool": ("TRUE", "FALSE"),
}

#: Cheddar scheduler → literal of ``AADL_Project::Supported_Scheduling_Protocols`` (the others
#: go to ``Cheddar_Properties::Scheduler``).
SCHEDULER_TO_AADL = {
    "RATE_MONOTONIC_PROTOCOL": "Rate_Monotonic_Protocol",
    "DEADLINE_MONOTONIC_PROTOCOL": "Deadline_Monotonic_Protocol",
    "EARLIEST_DEADLINE_FIRST_PROTOCOL": "Earliest_Deadline_First_Protocol",
    "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL": "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL",
    "ROUND_ROBIN_PROTOCOL": "Round_Robin_Protocol",
}
#: AADL scheduling protocol literal (lower case) → Cheddar scheduler.
AADL_TO_SCHEDULER = {v.lower(): k for k, v in SCHEDULER_TO_AADL.items()} | {
    "rms": "RATE_MONOTONIC_PROTOCOL",
    "dms": "DEADLINE_MONOTONIC_PROTOCOL",
    "edf": "EARLIEST_DEADLINE_FIRST_PROTOCOL",
}

#: Cheddar resource protocol → ``Concurrency_Control_Protocol`` literal.
RESOURCE_PROTOCOL_TO_AADL = {
    "NO_PROTOCOL": "None_Specified",
    "PRIORITY_CEILING_PROTOCOL": "Priority_Ceiling",
    "POOL_BASED_PRIORITY_CEILING_PROTOCOL": "Priority_Ceiling",
    "PRIORITY_INHERITANCE_PROTOCOL": "Priority_Inheritance",
    "IMMEDIATE_PRIORITY_CEILING_PROTOCOL": "Priority_Ceiling",
}
#: ``Concurrency_Control_Protocol`` literal (lower case) → Cheddar resource protocol.
AADL_TO_RESOURCE_PROTOCOL = {
    "none_specified": "NO_PROTOCOL",
    "semaphore": "NO_PROTOCOL",
    "spin_lock": "NO_PROTOCOL",
    "priority_inheritance": "PRIORITY_INHERITANCE_PROTOCOL",
    "priority_ceiling": "PRIORITY_CEILING_PROTOCOL",
    "protected_access": "IMMEDIATE_PRIORITY_CEILING_PROTOCOL",
    "maximum_priority": "IMMEDIATE_PRIORITY_CEILING_PROTOCOL",
    "interrupt_masking": "IMMEDIATE_PRIORITY_CEILING_PROTOCOL",
}
RESOURCE_TAGS = {
    "NO_PROTOCOL": "np_resource",
    "PRIORITY_CEILING_PROTOCOL": "pcp_resource",
    "POOL_BASED_PRIORITY_CEILING_PROTOCOL": "ppcp_resource",
    "PRIORITY_INHERITANCE_PROTOCOL": "pip_resource",
    "IMMEDIATE_PRIORITY_CEILING_PROTOCOL": "ipcp_resource",
}

#: Cheddar task kind → AADL ``Dispatch_Protocol``.
TASK_TYPE_TO_DISPATCH = {
    "PERIODIC_TYPE": "Periodic",
    "APERIODIC_TYPE": "Aperiodic",
    "SPORADIC_TYPE": "Sporadic",
    "POISSON_TYPE": "Aperiodic",
    "TIMED_TYPE": "Timed",
    "PARAMETRIC_TYPE": "Aperiodic",
    "SCHEDULING_TASK_TYPE": "Periodic",
    "FRAME_TASK_TYPE": "Periodic",
    "SPORADIC_INNER_PERIODIC_TYPE": "Sporadic",
    "PERIODIC_INNER_PERIODIC_TYPE": "Periodic",
}
#: AADL ``Dispatch_Protocol`` (lower case) → the usual Cheddar task kind.
DISPATCH_TO_TASK_TYPE = {
    "periodic": "PERIODIC_TYPE",
    "sporadic": "SPORADIC_TYPE",
    "aperiodic": "APERIODIC_TYPE",
    "timed": "TIMED_TYPE",
    "hybrid": "PERIODIC_TYPE",
    "background": "APERIODIC_TYPE",
}
#: Cheddar task kind → element tag of Cheddar 3 (the reader's list of task tags).
TASK_TYPE_TAGS = {
    "PERIODIC_TYPE": "periodic_task",
    "APERIODIC_TYPE": "aperiodic_task",
    "SPORADIC_TYPE": "sporadic_task",
    "POISSON_TYPE": "poisson_task",
    "TIMED_TYPE": "periodic_task",
    "PARAMETRIC_TYPE": "parametric_task",
    "SCHEDULING_TASK_TYPE": "scheduling_task",
    "FRAME_TASK_TYPE": "frame_task",
    "SPORADIC_INNER_PERIODIC_TYPE": "sporadic_inner_periodic_task",
    "PERIODIC_INNER_PERIODIC_TYPE": "periodic_inner_periodic_task",
}
_TAG_TASK_TYPES = {tag: kind for kind, tag in TASK_TYPE_TAGS.items() if kind != "TIMED_TYPE"}
NETWORK_TAGS = ("generic_network", "noc_network", "spacewire_network", "bus_network")
MESSAGE_TAGS = {"PERIODIC_TYPE": "periodic_message", "APERIODIC_TYPE": "aperiodic_message"}

#: Dependency kind → (first end tag, its kind, orientation tag or None, second end tag, its
#: kind, extra fields as (tag, property, enumeration)). Kinds: task, buffer, message, resource.
DEPENDENCY_ENDS: dict[str, tuple[str, str, str | None, str, str, tuple[tuple[str, str, str], ...]]] = {
    "PRECEDENCE_DEPENDENCY": ("precedence_sink", "task", None, "precedence_source", "task", ()),
    "QUEUEING_BUFFER_DEPENDENCY": (
        "buffer_dependent_task",
        "task",
        "buffer_orientation",
        "buffer_dependency_object",
        "buffer",
        (),
    ),
    "TDMA_COMMUNICATION_DEPENDENCY": (
        "tdma_communication_dependent_task",
        "task",
        "tdma_communication_orientation",
        "tdma_communication_dependency_object",
        "message",
        (),
    ),
    "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY": (
        "asynchronous_communication_dependent_task",
        "task",
        "asynchronous_communication_orientation",
        "asynchronous_communication_dependency_object",
        "message",
        (
            (
                "asynchronous_communication_protocol_property",
                CP + "Asynchronous_Communication_Protocol_Property",
                "async_protocol",
            ),
        ),
    ),
    "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY": (
        "time_triggered_communication_sink",
        "task",
        None,
        "time_triggered_communication_source",
        "task",
        (("time_triggered_timing_property", CP + "Time_Triggered_Timing_Property", "tt_timing"),),
    ),
    "RESOURCE_DEPENDENCY": (
        "resource_dependency_resource",
        "resource",
        None,
        "resource_dependency_task",
        "task",
        (),
    ),
    "REMOTE_PROCEDURE_CALL_DEPENDENCY": (
        "remote_procedure_call_client",
        "task",
        None,
        "remote_procedure_call_server",
        "task",
        (),
    ),
    "BLACK_BOARD_BUFFER_DEPENDENCY": (
        "black_board_dependent_task",
        "task",
        "black_board_orientation",
        "black_board_dependency_object",
        "buffer",
        (),
    ),
}

SECTIONS_V3 = (
    "core_units",
    "processors",
    "networks",
    "address_spaces",
    "tasks",
    "resources",
    "buffers",
    "messages",
    "dependencies",
)
SECTIONS_V2 = (
    "processors",
    "address_spaces",
    "tasks",
    "networks",
    "buffers",
    "resources",
    "messages",
    "dependencies",
)


@dataclass(frozen=True)
class Field:
    """One simple Cheddar field: its tag, the property that holds it, and how its text reads.

    ``kind`` is ``int`` (a natural number), ``time`` (a natural number of time units),
    ``real``, ``bool`` (TRUE/FALSE), ``str`` (text, also for Cheddar enumerations whose
    literals rosaadl does not fix), ``enum:<name>`` (a literal of :data:`ENUMERATIONS`) or
    ``preemptive`` (PREEMPTIVE/NOT_PREEMPTIVE as a boolean).
    """

    tag: str
    prop: str
    kind: str


def _f(tag: str, name: str, kind: str) -> Field:
    return Field(tag, name if "::" in name else CP + name, kind)


# Field tables, in the order Cheddar's writer puts the fields. Tags not listed here but
# handled by the entity readers: name, object_type, id, cpu_name, address_space_name,
# core_name, task_type, capacity, scheduling, core, cores, protocol, critical_sections,
# roles, offsets, message_type.
SCHEDULING_FIELDS = (
    _f("quantum", "Scheduler_Quantum", "time"),
    _f("capacity", "Scheduler_Capacity", "time"),
    _f("period", "Scheduler_Period", "time"),
    _f("threshold", "Scheduler_Threshold", "int"),
    _f("priority", "Scheduler_Priority", "int"),
    _f("start_time", "Scheduler_Start_Time", "time"),
    _f("user_defined_scheduler_source_file_name", "User_Defined_Scheduler_File", "str"),
    _f("user_defined_scheduler_protocol_name", "User_Defined_Scheduler_Protocol", "str"),
    _f("automaton_name", "Automaton_Name", "str"),
)
CORE_FIELDS = (
    _f("speed", "Speed", "real"),
    _f("l1_cache_system_name", "L1_Cache_System_Name", "str"),
    _f(
        "worstcase_perequest_intrabank_memory_interference",
        "Worstcase_Perequest_Intrabank_Memory_Interference",
        "int",
    ),
    _f(
        "worstcase_perequest_interbank_memory_interference",
        "Worstcase_Perequest_Interbank_Memory_Interference",
        "int",
    ),
    _f("isa", "ISA", "str"),
)
PROCESSOR_FIELDS = (
    _f("processor_type", "Processor_Type", "str"),
    _f("migration_type", "Migration_Type", "str"),
)
ADDRESS_SPACE_FIELDS = (
    _f("text_memory_size", "Text_Memory_Size", "int"),
    _f("stack_memory_size", "Stack_Memory_Size", "int"),
    _f("data_memory_size", "Data_Memory_Size", "int"),
    _f("heap_memory_size", "Heap_Memory_Size", "int"),
    _f("mils_confidentiality_level", "MILS_Confidentiality_Level", "str"),
    _f("mils_integrity_level", "MILS_Integrity_Level", "str"),
    _f("mils_component", "MILS_Component", "str"),
    _f("mils_partition", "MILS_Partition", "str"),
    _f("mils_compliant", "MILS_Compliant", "bool"),
)
# "capacity" and "offsets" are special (range and record list); listed to fix their place.
TASK_FIELDS = (
    _f("capacity_model", "Capacity_Model", "str"),
    Field("capacity", CET, "capacity"),
    _f("energy_consumption", "Energy_Consumption", "int"),
    Field("deadline", DEADLINE, "time"),
    Field("start_time", OFFSET, "time"),
    Field("priority", PRIORITY, "int"),
    _f("blocking_time", "Bound_On_Data_Blocking_Time", "time"),
    Field("policy", POLICY, "enum:policy"),
    _f("offsets", "Offsets", "offsets"),
    _f("text_memory_size", "Text_Memory_Size", "int"),
    _f("text_memory_start_address", "Text_Memory_Start_Address", "int"),
    _f("stack_memory_size", "Stack_Memory_Size", "int"),
    _f("criticality", "Criticality", "int"),
    _f("context_switch_overhead", "Context_Switch_Overhead", "time"),
    _f("cfg_name", "Cfg_Name", "str"),
    _f("cfg_relocatable", "Cfg_Relocatable", "bool"),
    _f("cache_access_profile_name", "Cache_Access_Profile_Name", "str"),
    _f("mils_confidentiality_level", "MILS_Confidentiality_Level", "str"),
    _f("mils_integrity_level", "MILS_Integrity_Level", "str"),
    _f("mils_component", "MILS_Component", "str"),
    _f("mils_task", "MILS_Task", "str"),
    _f("mils_compliant", "MILS_Compliant", "bool"),
    _f("access_memory_number", "Access_Memory_Number", "int"),
    _f("maximum_number_of_memory_request_per_job", "Maximum_Number_Of_Memory_Request_Per_Job", "int"),
    _f("seed", "Dispatch_Seed_Value", "int"),
    _f("predictable", "Dispatch_Seed_Is_Predictable", "bool"),
    Field("period", PERIOD, "time"),
    Field("jitter", JITTER, "time"),
    _f("every", "Every", "int"),
    _f("completion_time", "Completion_Time", "time"),
    _f("activation_rule", "Activation_Rule", "str"),
    _f("outer_period", "Outer_Period", "time"),
    _f("outer_duration", "Outer_Duration", "time"),
    _f("interarrival", "Interarrival", "time"),
)
RESOURCE_FIELDS = (
    _f("state", "Data_Concurrency_State", "int"),
    _f("size", "Resource_Size", "int"),
    _f("address", "Resource_Address", "int"),
    Field("priority", PRIORITY, "int"),
    _f("priority_assignment", "Priority_Assignment", "enum:priority_assignment"),
)
BUFFER_FIELDS = (
    _f("queueing_system_type", "Queueing_System_Type", "str"),
    _f("buffer_size", "Buffer_Size", "int"),
    _f("buffer_initial_data_size", "Buffer_Initial_Data_Size", "int"),
)
MESSAGE_FIELDS = (
    _f("preemptive_type", "Preemptive", "preemptive"),
    _f("deadline", "Message_Deadline", "time"),
    _f("size", "Message_Size", "int"),
    _f("response_time", "Response_Time", "time"),
    _f("communication_time", "Communication_Time", "time"),
    _f("mils_confidentiality_level", "MILS_Confidentiality_Level", "str"),
    _f("mils_integrity_level", "MILS_Integrity_Level", "str"),
    _f("period", "Message_Period", "time"),
    _f("jitter", "Message_Jitter", "time"),
)
NETWORK_FIELDS = (
    _f("network_type", "Network_Type", "str"),
    _f("network_delay", "Network_Delay", "str"),
    _f("network_architecture_type", "Network_Architecture_Type", "str"),
    _f("network_arbitration", "Network_Arbitration", "str"),
    _f("topology", "Topology", "str"),
    _f("number_of_processor", "Number_Of_Processor", "int"),
    _f("link_delay", "Link_Delay", "time"),
    _f("dimension", "Dimension", "int"),
    _f("number_of_virtual_channel", "Number_Of_Virtual_Channel", "int"),
    _f("routing_protocol", "Routing_Protocol", "str"),
    _f("switching_protocol", "Switching_Protocol", "str"),
    _f("xdimension", "Xdimension", "int"),
    _f("ydimension", "Ydimension", "int"),
    _f("tdma_synchronization_frame", "TDMA_Synchronization_Frame", "str"),
    _f("memory_word_access_time", "Memory_Word_Access_Time", "int"),
    _f(
        "maximum_interbank_interferences_memory_delay",
        "Maximum_Interbank_Interferences_Memory_Delay",
        "int",
    ),
)

# Cheddar 2 tables (the order Cheddar 2's writer uses).
V2_TASK_FIELDS = (
    Field("capacity", CET, "capacity"),
    Field("start_time", OFFSET, "time"),
    Field("policy", POLICY, "enum:policy"),
    Field("deadline", DEADLINE, "time"),
    _f("criticality", "Criticality", "int"),
    _f("context_switch_overhead", "Context_Switch_Overhead", "time"),
    _f("blocking_time", "Bound_On_Data_Blocking_Time", "time"),
    Field("priority", PRIORITY, "int"),
    _f("text_memory_size", "Text_Memory_Size", "int"),
    _f("stack_memory_size", "Stack_Memory_Size", "int"),
    Field("period", PERIOD, "time"),
    Field("jitter", JITTER, "time"),
    _f("offsets", "Offsets", "offsets"),
    _f("every", "Every", "int"),
    _f("seed", "Dispatch_Seed_Value", "int"),
    _f("predictable_seed", "Dispatch_Seed_Is_Predictable", "bool"),
    _f("activation_rule", "Activation_Rule", "str"),
)
V2_ADDRESS_SPACE_FIELDS = ADDRESS_SPACE_FIELDS[:4]
V2_RESOURCE_FIELDS = RESOURCE_FIELDS  # Cheddar 2 resources have the same fields
V2_BUFFER_FIELDS = (
    _f("qs", "Queueing_System_Type", "str"),
    _f("size", "Buffer_Size", "int"),
)
V2_MESSAGE_FIELDS = (
    _f("size", "Message_Size", "int"),
    _f("period", "Message_Period", "time"),
    _f("deadline", "Message_Deadline", "time"),
    _f("jitter", "Message_Jitter", "time"),
    _f("response_time", "Response_Time", "time"),
    _f("communication_time", "Communication_Time", "time"),
)
V2_NETWORK_FIELDS = (_f("type", "Network_Type", "str"),)

_MAX_INT = 2**63 - 1
_INT_RE = re.compile(r"^[+]?[0-9]+$")
_NEG_RE = re.compile(r"^-[0-9]+$")

# --------------------------------------------------------------------------- small helpers


def aadl_identifier(name: str) -> str:
    """A valid AADL identifier close to ``name`` (``DAG1-Kernel1`` → ``DAG1_Kernel1``)."""
    text = re.sub(r"[^A-Za-z0-9]+", "_", name.strip())
    text = re.sub(r"_+", "_", text).strip("_")
    if not text:
        return "unnamed"
    if not text[0].isalpha():
        text = "n_" + text
    return text


def canonical_xml(element: etree._Element) -> str:
    """An element as XML text without insignificant whitespace (the form kept in the model)."""
    copy = deepcopy(element)
    for node in copy.iter():
        if node.text is not None and not node.text.strip() and len(node):
            node.text = None
        if node.tail is not None and not node.tail.strip():
            node.tail = None
        elif node.tail is not None:
            node.tail = node.tail.strip()
        if len(node) == 0 and node.text is not None:
            node.text = node.text.strip()
    copy.tail = None
    return etree.tostring(copy, encoding="unicode")


def strip_internal_subset(data: bytes, filename: str) -> bytes:
    """Blank out a DOCTYPE declaration after checking it is harmless.

    Cheddar 2 files carry an inline DTD that libxml2 refuses (it declares
    ``context_switch_overhead`` twice) and that Cheddar's own SAX reader does not use. A
    DOCTYPE that refers to an external DTD, declares entities or uses parameter entities is
    refused with a located error; a harmless one is replaced by spaces (line ends kept, so
    that line numbers stay right) before the document is parsed.
    """
    start = _doctype_start(data)
    if start < 0:
        return data
    line = data.count(b"\n", 0, start) + 1
    pos = start + len(b"<!DOCTYPE")
    end_name = pos
    while end_name < len(data) and data[end_name : end_name + 1] not in (b"[", b">"):
        end_name += 1
    header = data[pos:end_name].split()
    if len(header) > 1 and header[1].upper() in (b"SYSTEM", b"PUBLIC"):
        raise ImportFormatError(
            "the DOCTYPE refers to an external DTD; external DTDs are refused (expected a plain "
            "Cheddar XML document or an inline DTD)",
            file=filename,
            line=line,
        )
    if end_name >= len(data):
        raise ImportFormatError("the DOCTYPE declaration is not closed", file=filename, line=line)
    end = end_name
    if data[end : end + 1] == b"[":
        end = _internal_subset_end(data, end + 1, filename, line)
        while end < len(data) and data[end : end + 1] in b" \t\r\n":
            end += 1
        if data[end : end + 1] != b">":
            raise ImportFormatError("the DOCTYPE declaration is not closed", file=filename, line=line)
    blank = bytes(c if c in (0x0A, 0x0D) else 0x20 for c in data[start : end + 1])
    return data[:start] + blank + data[end + 1 :]


def _doctype_start(data: bytes) -> int:
    """Offset of ``<!DOCTYPE`` in the prolog (before the root element), or -1."""
    pos = 3 if data.startswith(b"\xef\xbb\xbf") else 0
    n = len(data)
    while pos < n:
        ch = data[pos : pos + 1]
        if ch in b" \t\r\n" and ch:
            pos += 1
            continue
        if data.startswith(b"<?", pos):
            close = data.find(b"?>", pos + 2)
            if close < 0:
                return -1
            pos = close + 2
            continue
        if data.startswith(b"<!--", pos):
            close = data.find(b"-->", pos + 4)
            if close < 0:
                return -1
            pos = close + 3
            continue
        if data.startswith(b"<!DOCTYPE", pos):
            return pos
        return -1
    return -1


def _internal_subset_end(data: bytes, pos: int, filename: str, line: int) -> int:
    """Offset just after the ``]`` closing an internal subset; refuses entity declarations."""
    n = len(data)
    while pos < n:
        if data.startswith(b"<!--", pos):
            close = data.find(b"-->", pos + 4)
            if close < 0:
                break
            pos = close + 3
            continue
        if data.startswith(b"<!ENTITY", pos):
            raise ImportFormatError(
                "the DOCTYPE declares entities; DTD entities are refused (entity expansion and "
                "external entities are not allowed in Cheddar files)",
                file=filename,
                line=data.count(b"\n", 0, pos) + 1,
            )
        ch = data[pos : pos + 1]
        if ch == b"%":
            raise ImportFormatError(
                "the DOCTYPE uses parameter entities; they are refused",
                file=filename,
                line=data.count(b"\n", 0, pos) + 1,
            )
        if ch in (b'"', b"'"):
            close = data.find(ch, pos + 1)
            if close < 0:
                break
            pos = close + 1
            continue
        if ch == b"]":
            return pos + 1
        pos += 1
    raise ImportFormatError("the DOCTYPE's internal subset is not closed", file=filename, line=line)


def _local(element: etree._Element) -> str:
    return etree.QName(element).localname.lower()


def _children(element: etree._Element) -> list[etree._Element]:
    return [c for c in element if isinstance(c.tag, str)]


def cheddar_format_of(root: etree._Element) -> int:
    """2 for a Cheddar 2 document, 3 for a Cheddar 3 one (by the shape of its sections)."""
    v2_tags = {"processor", "task", "resource", "message", "network"}
    for section in _children(root):
        if _local(section) == "core_units":
            return 3
        for item in _children(section):
            tag = _local(item)
            if item.get("id") is not None or tag.endswith(
                ("_task", "_resource", "_network", "_message", "_processor")
            ):
                return 3
            if tag in v2_tags:
                return 2
    return 3


# --------------------------------------------------------------------------- model values

_CLASSES: dict[str, Any] = {}


def _cls(name: str) -> Any:
    cls = _CLASSES.get(name)
    if cls is None:
        cls = _CLASSES[name] = model.eclass_of(name).python_class
    return cls


def _int_value(value: int, unit: str | None = None) -> EObject:
    obj = _cls("IntegerValue")()
    obj.value = value
    if unit:
        obj.unit = unit
    return obj


def _real_value(value: float) -> EObject:
    obj = _cls("RealValue")()
    obj.value = value
    return obj


def _bool_value(value: bool) -> EObject:
    obj = _cls("BooleanValue")()
    obj.value = value
    return obj


def _str_value(value: str) -> EObject:
    obj = _cls("StringValue")()
    obj.value = value
    return obj


def _named_value(name: str) -> EObject:
    obj = _cls("NamedValue")()
    obj.name = name
    return obj


def _range_value(low: EObject, high: EObject) -> EObject:
    obj = _cls("RangeValue")()
    obj.minimum = low
    obj.maximum = high
    return obj


def _list_value(items: Iterable[EObject]) -> EObject:
    obj = _cls("ListValue")()
    obj.ownedItems.extend(items)
    return obj


def _record_value(fields: Iterable[tuple[str, EObject]]) -> EObject:
    obj = _cls("RecordValue")()
    for name, value in fields:
        item = _cls("FieldValue")()
        item.name = name
        item.value = value
        obj.ownedFields.append(item)
    return obj


def _reference_value(target: EObject | str) -> EObject:
    if isinstance(target, str):
        obj = _cls("ReferenceValue")()
        obj.path = target
        return obj
    obj = _cls("InstanceReferenceValue")()
    obj.referencedInstanceObject = target
    return obj


def _associate(owner: EObject, prop: str, value: EObject) -> None:
    assoc = _cls("PropertyAssociation")()
    assoc.property = prop
    modal = _cls("ModalPropertyValue")()
    modal.value = value
    assoc.ownedValues.append(modal)
    owner.ownedPropertyAssociations.append(assoc)


# --------------------------------------------------------------------------- the reader


@dataclass
class _Entity:
    """What the reader knows about one Cheddar entity while building the model."""

    kind: str
    name: str
    element: etree._Element
    instance: EObject | None = None
    cheddar_id: str | None = None
    cpu: EObject | str | None = None  # processor instance (or unresolved name)


class _Reader:
    def __init__(
        self, filename: str, time_unit: str, strict: bool, diagnostics: list[Diagnostic] | None
    ) -> None:
        if time_unit not in TIME_UNITS:
            raise UsageError(f"time_unit must be one of {', '.join(TIME_UNITS)}, not {time_unit!r}")
        self.filename = filename
        self.unit = time_unit
        self.strict = strict
        self.diagnostics = diagnostics if diagnostics is not None else []
        self.version = 3
        self.ids: dict[str, tuple[str, etree._Element]] = {}
        self.cores: dict[str, etree._Element] = {}  # id -> core_unit element
        self.used_cores: set[str] = set()
        self.processors: dict[str, _Entity] = {}
        self.address_spaces: dict[str, _Entity] = {}
        self.tasks: dict[str, _Entity] = {}
        self.resources: dict[str, _Entity] = {}
        self.buffers: dict[str, _Entity] = {}
        self.messages: dict[str, _Entity] = {}
        self.networks: dict[str, _Entity] = {}
        self.by_id: dict[str, _Entity] = {}
        self.unknown: dict[tuple[str, str], list] = {}
        self.kept: list[tuple[str, str]] = []
        self.names: dict[int, set[str]] = {}
        self.features: dict[tuple, EObject] = {}
        self.kept_fields: dict[int, tuple[EObject, list[EObject]]] = {}
        self.pending: list[tuple[EObject, EObject]] = []
        self.root: EObject | None = None

    # ------------------------------------------------------------------ diagnostics

    def where(self, element: etree._Element) -> Location:
        return Location(file=self.filename, line=element.sourceline, path=element_path(element))

    def fail(self, element: etree._Element, message: str) -> NoReturn:
        raise ImportFormatError(message, self.where(element))

    def warn(self, element: etree._Element, message: str) -> None:
        diagnostic = Diagnostic("warning", message, self.where(element))
        self.diagnostics.append(diagnostic)
        log.warning("%s", diagnostic)

    def lenient(self, element: etree._Element, message: str) -> None:
        """A problem Cheddar's own reader tolerates: a warning, or an error when strict."""
        if self.strict:
            self.fail(element, message)
        self.warn(element, message)

    # ------------------------------------------------------------------ text values

    def text(self, element: etree._Element) -> str:
        if _children(element):
            self.fail(element, f"<{_local(element)}> must hold a value, not elements")
        text = element.text or ""
        return " ".join(text.split()) if self.version == 2 else text.strip()

    def natural(self, element: etree._Element, text: str | None = None) -> int:
        raw = self.text(element) if text is None else text
        if _NEG_RE.match(raw):
            self.fail(element, f"<{_local(element)}> is {raw}; expected a natural number (0 or more)")
        if not _INT_RE.match(raw):
            self.fail(element, f"<{_local(element)}> is {raw!r}; expected a whole number")
        value = int(raw)
        if value > _MAX_INT:
            self.fail(element, f"<{_local(element)}> is {raw}; the number is too large")
        return value

    def value(self, element: etree._Element, kind: str, text: str | None = None) -> EObject:
        """The property value for one field's text."""
        raw = self.text(element) if text is None else text
        if kind == "int":
            return _int_value(self.natural(element, raw))
        if kind == "time":
            return _int_value(self.natural(element, raw), self.unit)
        if kind == "real":
            try:
                number = float(raw)
            except ValueError:
                self.fail(element, f"<{_local(element)}> is {raw!r}; expected a number")
            if number != number or number in (float("inf"), float("-inf")) or number < 0:
                self.fail(element, f"<{_local(element)}> is {raw!r}; expected a finite number, 0 or more")
            return _real_value(number)
        if kind == "bool":
            upper = raw.upper()
            if upper not in ("TRUE", "FALSE"):
                self.fail(element, f"<{_local(element)}> is {raw!r}; expected TRUE or FALSE")
            return _bool_value(upper == "TRUE")
        if kind == "preemptive":
            upper = raw.upper()
            if upper not in ENUMERATIONS["preemptive"]:
                self.fail(element, f"<{_local(element)}> is {raw!r}; expected PREEMPTIVE or NOT_PREEMPTIVE")
            return _bool_value(upper == "PREEMPTIVE")
        if kind.startswith("enum:"):
            return _named_value(self.literal(element, kind[5:], raw))
        return _str_value(raw)

    def literal(self, element: etree._Element, enumeration: str, raw: str | None = None) -> str:
        text = (self.text(element) if raw is None else raw).upper()
        known = ENUMERATIONS[enumeration]
        if not text:
            self.fail(element, f"<{_local(element)}> is empty; expected one of {', '.join(known)}")
        if text not in known:
            self.lenient(
                element, f"<{_local(element)}> is {text}, not a value Cheddar knows ({', '.join(known)})"
            )
        return text

    # ------------------------------------------------------------------ model helpers

    def instance(self, parent: EObject, name: str, category: str) -> EObject:
        """A new component instance for ``parent``, with a name unique among its siblings.

        It is attached to ``parent`` when the next one is made (or the section ends): filling
        a detached object is much cheaper in pyecore (every change notifies up the containers).
        """
        self.attach()
        taken = self.names.get(id(parent))
        if taken is None:
            taken = self.names[id(parent)] = {c.name.lower() for c in parent.componentInstances}
        base = aadl_identifier(name)
        candidate, n = base, 1
        while candidate.lower() in taken:
            n += 1
            candidate = f"{base}_{n}"
        taken.add(candidate.lower())
        obj = model.new("ComponentInstance", name=candidate, category=category)
        self.pending.append((parent, obj))
        return obj

    def attach(self) -> None:
        for parent, obj in self.pending:
            parent.componentInstances.append(obj)
        self.pending.clear()

    def fields(
        self,
        owner: EObject,
        element: etree._Element,
        table: Iterable[Field],
        present: dict[str, etree._Element],
        consumed: set[str],
        special: Callable[[Field, etree._Element], None] | None = None,
    ) -> None:
        """Store the fields of ``table`` found in ``present`` on ``owner``, in table order."""
        for spec in table:
            child = present.get(spec.tag)
            if child is None:
                continue
            consumed.add(spec.tag)
            if spec.kind in ("capacity", "offsets"):
                if special is None:
                    self.fail(child, f"internal: no reader for <{spec.tag}>")
                special(spec, child)
                continue
            _associate(owner, spec.prop, self.value(child, spec.kind))

    def index_children(
        self, element: etree._Element, repeatable: Iterable[str] = ()
    ) -> dict[str, etree._Element]:
        """The element's children by lower-case tag; a repeated simple field is an error."""
        found: dict[str, etree._Element] = {}
        allowed = set(repeatable)
        for child in _children(element):
            tag = _local(child)
            if tag in found and tag not in allowed:
                self.fail(child, f"<{tag}> is given twice in <{_local(element)}>")
            found.setdefault(tag, child)
        return found

    def leftovers(
        self,
        owner: EObject,
        element: etree._Element,
        kind: str,
        present: dict[str, etree._Element],
        consumed: set[str],
    ) -> None:
        """Fields nobody read: kept verbatim on ``owner`` (Unmodelled_Fields), with a warning.

        Each is kept with the element it belongs to (``kind``: ``task``, ``core_unit``,
        ``scheduling_parameters``, ``processor``, ...), since a mono-core processor instance
        holds the fields of three Cheddar elements.
        """
        for child in _children(element):
            tag = _local(child)
            if tag in consumed:
                continue
            if self.strict:
                self.fail(child, f"<{kind}> field <{tag}> is not modelled by rosaadl")
            record = self.unknown.setdefault((kind, tag), [child, 0])
            record[1] += 1
            kept = self.kept_fields.setdefault(id(owner), (owner, []))[1]
            kept.append(
                _record_value([("Section", _str_value(kind)), ("Xml", _str_value(canonical_xml(child)))])
            )

    def identity(self, owner: EObject, entity: _Entity, index: int | None = None) -> None:
        _associate(owner, CP + "Cheddar_Name", _str_value(entity.name))
        if entity.cheddar_id is not None:
            _associate(owner, CP + "Cheddar_Id", _str_value(entity.cheddar_id))
        if index is not None:
            _associate(owner, CP + "Section_Index", _int_value(index))

    def register(self, table: dict[str, _Entity], entity: _Entity, what: str) -> None:
        if not entity.name:
            self.fail(entity.element, f"the {what} has no <name>")
        key = entity.name
        if key in table:
            self.fail(entity.element, f"{what} name {entity.name!r} is used twice")
        table[key] = entity
        if entity.cheddar_id is not None:
            self.by_id[entity.cheddar_id] = entity

    def name_of(self, element: etree._Element, present: dict[str, etree._Element], what: str) -> str:
        child = present.get("name")
        if child is None:
            self.fail(element, f"the {what} has no <name>")
        name = self.text(child)
        if not name:
            self.fail(child, f"the {what}'s <name> is empty")
        return name

    # ------------------------------------------------------------------ document

    def read(self, data: bytes) -> EObject:
        data = strip_internal_subset(data, self.filename)
        tree = parse_xml_bytes(data, self.filename, allow_doctype=True)
        root_element = tree.getroot()
        if _local(root_element) != "cheddar":
            self.fail(root_element, f"the root element is <{_local(root_element)}>; expected <cheddar>")
        self.version = cheddar_format_of(root_element)
        stem = Path(self.filename).stem or "cheddar"
        aadl_model = model.new("AadlModel", name=aadl_identifier(stem))
        root = model.new("SystemInstance", name=aadl_identifier(stem), category="system")
        self.root = root
        self.names[id(root)] = set()

        sections: dict[str, list[etree._Element]] = {}
        order: list[str] = []
        for section in _children(root_element):
            name = _local(section)
            order.append(name)
            sections.setdefault(name, []).append(section)
        if self.version == 3:
            self.collect_ids(sections)
        known = SECTIONS_V3 if self.version == 3 else SECTIONS_V2
        for name in order:
            if name not in known:
                for section in sections[name]:
                    self.keep_section(section)
        readers = self.v3_readers() if self.version == 3 else self.v2_readers()
        for name in known:
            for section in sections.get(name, []):
                self.attach()
                readers[name](section)
        self.attach()
        if self.version == 3:
            self.keep_unreferenced_cores(sections.get("core_units", []))
        for owner, kept in self.kept_fields.values():
            _associate(owner, CP + "Unmodelled_Fields", _list_value(kept))
        _associate(root, CP + "Section_Order", _list_value(_str_value(s) for s in order))
        if self.kept:
            _associate(
                root,
                CP + "Unmodelled_Elements",
                _list_value(
                    _record_value([("Section", _str_value(s)), ("Xml", _str_value(x))]) for s, x in self.kept
                ),
            )
        aadl_model.instances.append(root)
        for (kind, tag), (element, count) in self.unknown.items():
            times = f" ({count} times)" if count > 1 else ""
            self.warn(element, f"<{kind}> field <{tag}> is not modelled by rosaadl; kept as it is{times}")
        return aadl_model

    def keep_section(self, section: etree._Element) -> None:
        name = _local(section)
        items = _children(section)
        if self.strict:
            self.fail(section, f"section <{name}> is not modelled by rosaadl")
        self.warn(section, f"section <{name}> is not modelled by rosaadl; kept as it is")
        if not items:
            return
        for item in items:
            self.kept.append((name, canonical_xml(item)))

    def collect_ids(self, sections: dict[str, list[etree._Element]]) -> None:
        for name, elements in sections.items():
            for section in elements:
                for item in _children(section):
                    identifier = item.get("id")
                    if identifier is None:
                        continue
                    identifier = identifier.strip()
                    if not identifier:
                        self.fail(item, "the id attribute is empty")
                    if identifier in self.ids:
                        first = self.ids[identifier][1]
                        self.fail(item, f"id {identifier!r} is used twice (first at line {first.sourceline})")
                    self.ids[identifier] = (name, item)

    def ref(self, element: etree._Element, kind: str, table: dict[str, _Entity] | None = None) -> Any:
        """The target of a ``ref`` attribute (an entity of ``table``, or a core unit element)."""
        target = element.get("ref")
        if target is None or not target.strip():
            self.fail(element, f"<{_local(element)}> has no ref attribute")
        target = target.strip()
        if kind == "core":
            if target not in self.cores:
                if target in self.ids:
                    self.fail(element, f"ref {target!r} is not a core unit")
                self.fail(element, f"ref {target!r} does not resolve to any id of the file")
            return target
        entity = self.by_id.get(target)
        if entity is None or entity.kind != kind:
            if target in self.ids:
                self.fail(element, f"ref {target!r} is a {self.ids[target][0]} entry, expected a {kind}")
            self.fail(element, f"ref {target!r} does not resolve to any id of the file")
        return entity

    def keep_unreferenced_cores(self, sections: list[etree._Element]) -> None:
        for section in sections:
            for item in _children(section):
                identifier = (item.get("id") or "").strip()
                if _local(item) == "core_unit" and identifier in self.used_cores:
                    continue
                self.warn(item, f"<{_local(item)}> {identifier!r} belongs to no processor; kept as it is")
                self.kept.append(("core_units", canonical_xml(item)))

    # ------------------------------------------------------------------ Cheddar 3

    def v3_readers(self) -> dict[str, Callable[[etree._Element], None]]:
        return {
            "core_units": self.v3_core_units,
            "processors": self.v3_processors,
            "networks": self.v3_networks,
            "address_spaces": self.v3_address_spaces,
            "tasks": self.v3_tasks,
            "resources": self.v3_resources,
            "buffers": self.v3_buffers,
            "messages": self.v3_messages,
            "dependencies": self.v3_dependencies,
        }

    def items(self, section: etree._Element, tags: Iterable[str], what: str) -> Iterable[etree._Element]:
        allowed = set(tags)
        for item in _children(section):
            if _local(item) in allowed:
                yield item
            else:
                self.lenient(item, f"<{_local(item)}> is not a {what}; kept as it is")
                self.kept.append((_local(section), canonical_xml(item)))

    def v3_core_units(self, section: etree._Element) -> None:
        for item in _children(section):
            if _local(item) != "core_unit":
                continue  # memories and other entries: kept with the unreferenced cores
            identifier = (item.get("id") or "").strip()
            if not identifier:
                self.fail(item, "the core unit has no id attribute")
            self.cores[identifier] = item

    def core_facts(self, owner: EObject, identifier: str, as_processor_core: bool) -> None:
        """Store a core unit's facts on ``owner`` (a mono-core processor or a core instance)."""
        element = self.cores[identifier]
        present = self.index_children(element)
        name = self.name_of(element, present, "core unit")
        consumed = {"name", "object_type"}
        if as_processor_core:
            _associate(owner, CP + "Core_Name", _str_value(name))
            _associate(owner, CP + "Core_Id", _str_value(identifier))
        else:
            _associate(owner, CP + "Cheddar_Name", _str_value(name))
            _associate(owner, CP + "Cheddar_Id", _str_value(identifier))
        scheduling = present.get("scheduling")
        if scheduling is not None:
            consumed.add("scheduling")
            self.scheduling(owner, scheduling, processor=True)
        self.fields(owner, element, CORE_FIELDS, present, consumed)
        self.leftovers(owner, element, "core_unit", present, consumed)

    def scheduling(self, owner: EObject, element: etree._Element, *, processor: bool) -> None:
        """``<scheduling><scheduling_parameters>…`` of a core unit or an address space."""
        present_outer = self.index_children(element)
        params = present_outer.get("scheduling_parameters")
        if params is None or len(present_outer) != 1:
            self.fail(element, "<scheduling> must hold one <scheduling_parameters>")
        present = self.index_children(params)
        consumed = {"scheduler_type", "preemptive_type"}
        kind = present.get("scheduler_type")
        if kind is not None:
            literal = self.literal(kind, "scheduler")
            if processor and literal in SCHEDULER_TO_AADL:
                _associate(owner, SCHEDULING, _list_value([_named_value(SCHEDULER_TO_AADL[literal])]))
            else:
                _associate(owner, CP + "Scheduler", _named_value(literal))
        preemptive = present.get("preemptive_type")
        if preemptive is not None:
            prop = PREEMPTIVE_SCHEDULER if processor else CP + "Preemptive"
            _associate(owner, prop, self.value(preemptive, "preemptive"))
        self.fields(owner, params, SCHEDULING_FIELDS, present, consumed)
        self.leftovers(owner, params, "scheduling_parameters", present, consumed)

    def v3_processors(self, section: etree._Element) -> None:
        for item in self.items(section, ("mono_core_processor", "multi_cores_processor"), "processor"):
            tag = _local(item)
            present = self.index_children(item)
            entity = _Entity("processor", self.name_of(item, present, "processor"), item)
            entity.cheddar_id = (item.get("id") or "").strip() or None
            self.register(self.processors, entity, "processor")
            instance = self.instance(self.root, entity.name, "processor")
            entity.instance = instance
            self.identity(instance, entity)
            consumed = {"name", "object_type"}
            self.fields(instance, item, PROCESSOR_FIELDS, present, consumed)
            if tag == "mono_core_processor":
                core = present.get("core")
                if core is None:
                    self.fail(item, "the mono-core processor has no <core ref=...>")
                consumed.add("core")
                identifier = self.ref(core, "core")
                self.used_cores.add(identifier)
                self.core_facts(instance, identifier, as_processor_core=True)
            else:
                cores = present.get("cores")
                if cores is None:
                    self.fail(item, "the multi-core processor has no <cores>")
                consumed.add("cores")
                refs = _children(cores)
                if not refs:
                    self.fail(cores, "the multi-core processor has no core unit")
                for ref in refs:
                    if _local(ref) != "core_unit":
                        self.fail(ref, f"<{_local(ref)}> in <cores>; expected <core_unit ref=...>")
                    identifier = self.ref(ref, "core")
                    self.used_cores.add(identifier)
                    core_name = self.name_of(
                        self.cores[identifier], self.index_children(self.cores[identifier]), "core unit"
                    )
                    core = self.instance(instance, core_name, "processor")
                    self.core_facts(core, identifier, as_processor_core=False)
            self.leftovers(instance, item, "processor", present, consumed)

    def processor_of(self, element: etree._Element, name: str) -> EObject | str:
        """The processor instance called ``name``; unknown names follow the format's rule."""
        entity = self.processors.get(name)
        if entity is not None:
            return entity.instance
        if self.version == 3:
            self.fail(
                element,
                f"processor {name!r} is not declared (expected one of: {self.known(self.processors)})",
            )
        self.lenient(element, f"processor {name!r} is not declared; kept as an unresolved reference")
        return name

    @staticmethod
    def known(table: dict[str, _Entity]) -> str:
        names = list(table)
        return ", ".join(names[:10]) + (", ..." if len(names) > 10 else "") if names else "none"

    def bind(self, owner: EObject, target: EObject | str) -> None:
        _associate(owner, BINDING, _list_value([_reference_value(target)]))

    def v3_address_spaces(self, section: etree._Element) -> None:
        for item in self.items(section, ("address_space",), "address space"):
            self.address_space(item, ADDRESS_SPACE_FIELDS)

    def address_space(self, item: etree._Element, table: tuple[Field, ...]) -> None:
        present = self.index_children(item)
        entity = _Entity("address_space", self.name_of(item, present, "address space"), item)
        entity.cheddar_id = (item.get("id") or "").strip() or None
        self.register(self.address_spaces, entity, "address space")
        instance = self.instance(self.root, entity.name, "process")
        entity.instance = instance
        self.identity(instance, entity)
        consumed = {"name", "object_type", "cpu_name"}
        cpu = present.get("cpu_name")
        if cpu is None or not self.text(cpu):
            self.fail(item, "the address space has no <cpu_name>")
        entity.cpu = self.processor_of(cpu, self.text(cpu))
        self.bind(instance, entity.cpu)
        self.fields(instance, item, table, present, consumed)
        scheduling = present.get("scheduling")
        if scheduling is not None and self.version == 3:
            consumed.add("scheduling")
            self.scheduling(instance, scheduling, processor=False)
        scheduler = present.get("scheduler")
        if scheduler is not None and self.version == 2:
            consumed.add("scheduler")
            self.v2_scheduler(instance, scheduler, processor=False)
        self.leftovers(instance, item, "address_space", present, consumed)

    def location(
        self, item: etree._Element, present: dict[str, etree._Element], what: str
    ) -> tuple[EObject, EObject | str, str | None]:
        """Where an entity goes: (parent instance, processor, unresolved address-space name)."""
        cpu_element = present.get("cpu_name")
        if cpu_element is None or not self.text(cpu_element):
            self.fail(item, f"the {what} has no <cpu_name> (every {what} must name its processor)")
        cpu = self.processor_of(cpu_element, self.text(cpu_element))
        space_element = present.get("address_space_name")
        space_name = self.text(space_element) if space_element is not None else ""
        if not space_name:
            if self.version == 3:
                self.fail(item, f"the {what} has no <address_space_name> (Cheddar 3 needs one)")
            return self.root, cpu, None
        space = self.address_spaces.get(space_name)
        if space is None:
            if self.version == 3:
                self.fail(
                    space_element,
                    f"address space {space_name!r} is not declared "
                    f"(expected one of: {self.known(self.address_spaces)})",
                )
            self.lenient(
                space_element,
                f"address space {space_name!r} is not declared; the {what} goes under the system",
            )
            return self.root, cpu, space_name
        if self.version == 3 and not _same(space.cpu, cpu):
            self.fail(
                cpu_element,
                f"the {what} is on processor {self.text(cpu_element)!r} but its address space "
                f"{space_name!r} is on {space.cpu.name if isinstance(space.cpu, EObject) else space.cpu!r}",
            )
        return space.instance, cpu, None

    def v3_tasks(self, section: etree._Element) -> None:
        tags = tuple(_TAG_TASK_TYPES)
        for index, item in enumerate(self.items(section, tags, "task")):
            self.task(item, index, TASK_FIELDS, _TAG_TASK_TYPES[_local(item)])

    def task(self, item: etree._Element, index: int, table: tuple[Field, ...], default_type: str) -> None:
        present = self.index_children(item)
        entity = _Entity("task", self.name_of(item, present, "task"), item)
        entity.cheddar_id = (item.get("id") or "").strip() or None
        self.register(self.tasks, entity, "task")
        parent, cpu, lost_space = self.location(item, present, "task")
        instance = self.instance(parent, entity.name, "thread")
        entity.instance = instance
        entity.cpu = cpu
        self.identity(instance, entity, index)
        consumed = {"name", "object_type", "cpu_name", "address_space_name", "task_type", "core_name"}
        kind_element = present.get("task_type")
        task_type = default_type
        if kind_element is not None:
            task_type = self.literal(kind_element, "task_type")
        elif self.version == 2 and item.get("task_type") is not None:
            task_type = self.literal(item, "task_type", item.get("task_type"))
        dispatch = TASK_TYPE_TO_DISPATCH.get(task_type, "Aperiodic")
        _associate(instance, DISPATCH, _named_value(dispatch))
        if DISPATCH_TO_TASK_TYPE[dispatch.lower()] != task_type:
            _associate(instance, CP + "Task_Type", _named_value(task_type))
        target = cpu
        core_element = present.get("core_name")
        core_name = self.text(core_element) if core_element is not None else None
        if core_name and isinstance(cpu, EObject) and cpu.componentInstances:
            core = next(
                (c for c in cpu.componentInstances if _own_string(c, CP + "Cheddar_Name") == core_name), None
            )
            if core is None:
                self.fail(core_element, f"core {core_name!r} is not a core of processor {cpu.name!r}")
            target = core
            core_name = None
        self.bind(instance, target)
        if core_name is not None:
            if (
                core_name
                and isinstance(cpu, EObject)
                and _own_string(cpu, CP + "Core_Name") not in (None, core_name)
            ):
                self.fail(core_element, f"core {core_name!r} is not the core of processor {cpu.name!r}")
            _associate(instance, CP + "Core_Name", _str_value(core_name))
        if lost_space is not None:
            _associate(instance, CP + "Address_Space_Name", _str_value(lost_space))
        self.fields(instance, item, table, present, consumed, self.task_special(instance))
        if self.version == 2:
            self.positions(instance, item)
        if (
            task_type in ("PERIODIC_TYPE", "SPORADIC_TYPE")
            and "period" in present
            and self.natural(present["period"]) == 0
        ):
            self.fail(present["period"], "the period of a periodic or sporadic task must be greater than 0")
        self.leftovers(instance, item, "task", present, consumed)

    def task_special(self, instance: EObject) -> Callable[[Field, etree._Element], None]:
        def special(spec: Field, element: etree._Element) -> None:
            if spec.kind == "capacity":
                value = self.natural(element)
                _associate(
                    instance, CET, _range_value(_int_value(value, self.unit), _int_value(value, self.unit))
                )
            elif spec.kind == "offsets":
                _associate(instance, spec.prop, _list_value(self.offsets(element)))

        return special

    def offsets(self, element: etree._Element) -> list[EObject]:
        records = []
        for item in _children(element):
            tag = _local(item)
            if self.version == 3:
                if tag != "offset_type":
                    self.fail(item, f"<{tag}> in <offsets>; expected <offset_type>")
                present = self.index_children(item)
                if set(present) - {"offset_value", "activation"} or len(present) != 2:
                    self.fail(item, "<offset_type> must hold <offset_value> and <activation>")
                activation = self.natural(present["activation"])
                value = self.natural(present["offset_value"])
            else:
                if tag != "offset":
                    self.fail(item, f"<{tag}> in <offsets>; expected <offset>")
                words = self.text(item).split()
                if len(words) != 2:
                    self.fail(item, "<offset> must hold two numbers: activation and offset value")
                activation = self.natural(item, words[0])
                value = self.natural(item, words[1])
            records.append(
                _record_value(
                    [("Activation", _int_value(activation)), ("Offset_Value", _int_value(value, self.unit))]
                )
            )
        return records

    def task_reference(self, element: etree._Element, name: str) -> EObject | str:
        entity = self.tasks.get(name)
        if entity is not None:
            return entity.instance
        if self.version == 3:
            self.fail(element, f"task {name!r} is not declared (expected one of: {self.known(self.tasks)})")
        self.lenient(element, f"task {name!r} is not declared; kept as an unresolved reference")
        return name

    def v3_resources(self, section: etree._Element) -> None:
        tags = tuple(RESOURCE_TAGS.values())
        for index, item in enumerate(self.items(section, tags, "resource")):
            self.resource(item, index, RESOURCE_FIELDS)

    def shared_object(
        self, item: etree._Element, index: int, kind: str, table: dict[str, _Entity], role: str
    ) -> tuple[_Entity, EObject, dict[str, etree._Element], set[str]]:
        """Common part of resources and buffers: name, id, location, Data_Role."""
        present = self.index_children(item, ("task_name",))
        entity = _Entity(kind, self.name_of(item, present, kind), item)
        entity.cheddar_id = (item.get("id") or "").strip() or None
        self.register(table, entity, kind)
        parent, cpu, lost_space = self.location(item, present, kind)
        instance = self.instance(parent, entity.name, "data")
        entity.instance = instance
        entity.cpu = cpu
        self.identity(instance, entity, index)
        _associate(instance, CP + "Data_Role", _named_value(role))
        space_cpu = None
        if parent is not self.root:
            space_cpu = next(s.cpu for s in self.address_spaces.values() if s.instance is parent)
        if not _same(space_cpu, cpu):
            cpu_name = cpu if isinstance(cpu, str) else _own_string(cpu, CP + "Cheddar_Name") or cpu.name
            _associate(instance, CP + "Cpu_Name", _str_value(cpu_name))
        if lost_space is not None:
            _associate(instance, CP + "Address_Space_Name", _str_value(lost_space))
        consumed = {"name", "object_type", "cpu_name", "address_space_name"}
        return entity, instance, present, consumed

    def resource(self, item: etree._Element, index: int, table: tuple[Field, ...]) -> None:
        entity, instance, present, consumed = self.shared_object(
            item, index, "resource", self.resources, "Resource"
        )
        protocol_element = present.get("protocol")
        protocol = "NO_PROTOCOL"
        if protocol_element is not None:
            consumed.add("protocol")
            protocol = self.literal(protocol_element, "resource_protocol")
        elif self.version == 3:
            for literal, tag in RESOURCE_TAGS.items():
                if tag == _local(item):
                    protocol = literal
        aadl = RESOURCE_PROTOCOL_TO_AADL.get(protocol, "None_Specified")
        _associate(instance, CCP, _named_value(aadl))
        if AADL_TO_RESOURCE_PROTOCOL[aadl.lower()] != protocol:
            _associate(instance, CP + "Resource_Protocol", _named_value(protocol))
        self.fields(instance, item, table, present, consumed)
        sections = present.get("critical_sections" if self.version == 3 else "resource_used_by")
        if sections is not None:
            consumed.add(_local(sections))
            _associate(instance, CP + "Critical_Sections", _list_value(self.critical_sections(sections)))
        self.leftovers(instance, item, "resource", present, consumed)

    def critical_sections(self, element: etree._Element) -> list[EObject]:
        records = []
        if self.version == 2:
            for item in _children(element):
                if _local(item) != "resource_user":
                    self.fail(item, f"<{_local(item)}> in <resource_used_by>; expected <resource_user>")
                words = self.text(item).split()
                if len(words) != 3:
                    self.fail(item, "<resource_user> must hold a task name, a begin and an end")
                task = self.task_reference(item, words[0])
                begin, end = self.natural(item, words[1]), self.natural(item, words[2])
                records.append(self.critical_section(item, task, begin, end, None))
            return records
        for task_element, data in self.pairs(element, "critical_section"):
            present = self.index_children(data)
            unknown = set(present) - {"task_begin", "task_end", "task_synchronization"}
            if unknown:
                self.fail(data, f"<critical_section> has unknown field <{sorted(unknown)[0]}>")
            for needed in ("task_begin", "task_end"):
                if needed not in present:
                    self.fail(data, f"<critical_section> has no <{needed}>")
            task = self.task_reference(task_element, self.text(task_element))
            sync = present.get("task_synchronization")
            records.append(
                self.critical_section(
                    data,
                    task,
                    self.natural(present["task_begin"]),
                    self.natural(present["task_end"]),
                    self.literal(sync, "synchronization") if sync is not None else None,
                )
            )
        return records

    def critical_section(
        self, element: etree._Element, task: EObject | str, begin: int, end: int, sync: str | None
    ) -> EObject:
        if begin > end:
            self.fail(element, f"the critical section begins ({begin}) after it ends ({end})")
        fields = [
            ("Task", _reference_value(task)),
            ("Task_Begin", _int_value(begin, self.unit)),
            ("Task_End", _int_value(end, self.unit)),
        ]
        if sync is not None:
            fields.append(("Synchronization", _named_value(sync)))
        return _record_value(fields)

    def pairs(self, element: etree._Element, record_tag: str) -> list[tuple[etree._Element, etree._Element]]:
        """``<task_name>t</task_name><record>…</record>`` pairs of Cheddar's indexed tables."""
        items = _children(element)
        result = []
        i = 0
        while i < len(items):
            first = items[i]
            if _local(first) != "task_name":
                self.fail(first, f"<{_local(first)}> in <{_local(element)}>; expected <task_name>")
            if i + 1 >= len(items) or _local(items[i + 1]) != record_tag:
                self.fail(first, f"<task_name> in <{_local(element)}> must be followed by <{record_tag}>")
            result.append((first, items[i + 1]))
            i += 2
        return result

    def v3_buffers(self, section: etree._Element) -> None:
        for index, item in enumerate(self.items(section, ("buffer",), "buffer")):
            self.buffer(item, index, BUFFER_FIELDS)

    def buffer(self, item: etree._Element, index: int, table: tuple[Field, ...]) -> None:
        entity, instance, present, consumed = self.shared_object(
            item, index, "buffer", self.buffers, "Buffer"
        )
        self.fields(instance, item, table, present, consumed)
        roles = present.get("roles" if self.version == 3 else "buffer_used_by")
        if roles is not None:
            consumed.add(_local(roles))
            _associate(instance, CP + "Buffer_Roles", _list_value(self.roles(roles)))
        if self.version == 2:
            self.positions(instance, item)
        self.leftovers(instance, item, "buffer", present, consumed)

    def roles(self, element: etree._Element) -> list[EObject]:
        records = []
        if self.version == 2:
            for item in _children(element):
                if _local(item) != "buffer_user":
                    self.fail(item, f"<{_local(item)}> in <buffer_used_by>; expected <buffer_user>")
                words = self.text(item).split()
                if len(words) != 3:
                    self.fail(item, "<buffer_user> must hold a task name, a size and a time")
                role_text = (item.get("buffer_role") or "producer").strip().lower()
                if role_text not in ("producer", "consumer"):
                    self.fail(item, f"buffer_role is {role_text!r}; expected producer or consumer")
                fields = [
                    ("Task", _reference_value(self.task_reference(item, words[0]))),
                    ("Role", _named_value("QUEUING_" + role_text.upper())),
                    ("Size", _int_value(self.natural(item, words[1]))),
                    ("Time", _int_value(self.natural(item, words[2]), self.unit)),
                ]
                records.append(_record_value(fields))
            return records
        for task_element, data in self.pairs(element, "buffer_role"):
            present = self.index_children(data)
            unknown = set(present) - {"the_role", "size", "time", "timeout", "amplitude_function"}
            if unknown:
                self.fail(data, f"<buffer_role> has unknown field <{sorted(unknown)[0]}>")
            if "the_role" not in present:
                self.fail(data, "<buffer_role> has no <the_role>")
            fields = [
                ("Task", _reference_value(self.task_reference(task_element, self.text(task_element)))),
                ("Role", _named_value(self.literal(present["the_role"], "buffer_role"))),
            ]
            if "size" in present:
                fields.append(("Size", _int_value(self.natural(present["size"]))))
            for tag, name in (("time", "Time"), ("timeout", "Timeout")):
                if tag in present:
                    fields.append((name, _int_value(self.natural(present[tag]), self.unit)))
            if "amplitude_function" in present:
                fields.append(("Amplitude_Function", _str_value(self.text(present["amplitude_function"]))))
            records.append(_record_value(fields))
        return records

    def v3_messages(self, section: etree._Element) -> None:
        for item in self.items(section, tuple(MESSAGE_TAGS.values()), "message"):
            self.message(item, MESSAGE_FIELDS)

    def message(self, item: etree._Element, table: tuple[Field, ...]) -> None:
        present = self.index_children(item)
        entity = _Entity("message", self.name_of(item, present, "message"), item)
        entity.cheddar_id = (item.get("id") or "").strip() or None
        self.register(self.messages, entity, "message")
        instance = self.instance(self.root, entity.name, "data")
        entity.instance = instance
        self.identity(instance, entity)
        _associate(instance, CP + "Data_Role", _named_value("Message"))
        consumed = {"name", "object_type", "message_type"}
        kind_element = present.get("message_type")
        if kind_element is not None:
            message_type = self.literal(kind_element, "message_type")
        elif self.version == 3:
            message_type = "PERIODIC_TYPE" if _local(item) == "periodic_message" else "APERIODIC_TYPE"
        else:
            message_type = "PERIODIC_TYPE" if "period" in present else "APERIODIC_TYPE"
        _associate(instance, CP + "Message_Type", _named_value(message_type))
        self.fields(instance, item, table, present, consumed)
        if self.version == 2:
            self.positions(instance, item)
        self.leftovers(instance, item, "message", present, consumed)

    def v3_networks(self, section: etree._Element) -> None:
        for item in self.items(section, NETWORK_TAGS, "network"):
            self.network(item, NETWORK_FIELDS, _local(item))

    def network(self, item: etree._Element, table: tuple[Field, ...], tag: str) -> None:
        present = self.index_children(item)
        entity = _Entity("network", self.name_of(item, present, "network"), item)
        entity.cheddar_id = (item.get("id") or "").strip() or None
        self.register(self.networks, entity, "network")
        instance = self.instance(self.root, entity.name, "bus")
        entity.instance = instance
        self.identity(instance, entity)
        if tag != "generic_network":
            _associate(instance, CP + "Network_Kind", _named_value(tag.upper()))
        consumed = {"name", "object_type"}
        self.fields(instance, item, table, present, consumed)
        self.leftovers(instance, item, "network", present, consumed)

    def v3_dependencies(self, section: etree._Element) -> None:
        for index, item in enumerate(self.items(section, ("dependency",), "dependency")):
            present = self.index_children(item)
            kind_element = present.get("type_of_dependency")
            if kind_element is None:
                self.fail(item, "the dependency has no <type_of_dependency>")
            kind = self.literal(kind_element, "dependency_type")
            if kind not in DEPENDENCY_ENDS:
                self.fail(kind_element, f"unknown dependency type {kind}")
            first_tag, first_kind, orient_tag, second_tag, second_kind, extras = DEPENDENCY_ENDS[kind]
            allowed = {"type_of_dependency", first_tag, second_tag} | {e[0] for e in extras}
            if orient_tag:
                allowed.add(orient_tag)
            for tag, child in present.items():
                if tag not in allowed:
                    self.fail(child, f"<{tag}> does not belong to a {kind}")
            ends = []
            for tag, end_kind in ((first_tag, first_kind), (second_tag, second_kind)):
                if tag not in present:
                    self.fail(item, f"the {kind} has no <{tag} ref=...>")
                ends.append(self.ref(present[tag], end_kind))
            orientation = None
            if orient_tag:
                if orient_tag not in present:
                    self.fail(item, f"the {kind} has no <{orient_tag}>")
                orientation = self.literal(present[orient_tag], "orientation")
            extra_values = [
                (prop, _named_value(self.literal(present[tag], enum)))
                for tag, prop, enum in extras
                if tag in present
            ]
            self.dependency(item, index, kind, ends[0], ends[1], orientation, extra_values)

    # ------------------------------------------------------------------ dependencies as connections

    def dependency(
        self,
        element: etree._Element,
        index: int,
        kind: str,
        first: _Entity,
        second: _Entity,
        orientation: str | None,
        extras: list[tuple[str, EObject]],
    ) -> None:
        """A Cheddar dependency as a connection instance (see Cheddar_Properties::Dependency_Type)."""
        bidirectional = False
        if first.kind == "task" and second.kind == "task":
            # precedence: sink first in the record; the connection goes source -> sink
            if kind in ("PRECEDENCE_DEPENDENCY", "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY"):
                source_task, sink_task = second, first
            else:  # remote procedure call: client -> server
                source_task, sink_task = first, second
            stem = {
                "PRECEDENCE_DEPENDENCY": "precedence",
                "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY": "time_triggered",
            }.get(kind, "rpc")
            source = self.feature(
                source_task.instance, (stem, "out"), f"{stem}_out", "event port", direction="out"
            )
            destination = self.feature(
                sink_task.instance, (stem, "in"), f"{stem}_in", "event port", direction="in"
            )
            connection_kind = "portConnection"
            ends = (source_task.instance, sink_task.instance)
        else:
            task, thing = (first, second) if first.kind == "task" else (second, first)
            feature = self.feature(
                task.instance,
                ("access", id(thing.instance)),
                thing.instance.name,
                "data access",
                access="requires",
            )
            if orientation == "FROM_OBJECT_TO_TASK":
                source, destination = thing.instance, feature
            else:
                source, destination = feature, thing.instance
            bidirectional = orientation is None
            connection_kind = "accessConnection"
            ends = (task.instance, thing.instance)
        owner = _common_owner(*ends)
        arrow = " <-> " if bidirectional else " -> "
        name = _relative_path(source, owner) + arrow + _relative_path(destination, owner)
        connection = model.new(
            "ConnectionInstance",
            name=name,
            kind=connection_kind,
            complete=True,
            bidirectional=bidirectional,
            source=source,
            destination=destination,
        )
        owner.connectionInstances.append(connection)
        _associate(connection, CP + "Section_Index", _int_value(index))
        _associate(connection, CP + "Dependency_Type", _named_value(kind))
        for prop, value in extras:
            _associate(connection, prop, value)

    def feature(
        self,
        thread: EObject,
        key: tuple,
        name: str,
        category: str,
        *,
        direction: str | None = None,
        access: str | None = None,
    ) -> EObject:
        """The thread's feature for ``key`` (made on first use, with a name unique on the thread)."""
        found = self.features.get((id(thread), key))
        if found is not None:
            return found
        taken = {f.name.lower() for f in thread.featureInstances}
        candidate, n = name, 1
        while candidate.lower() in taken:
            n += 1
            candidate = f"{name}_{n}"
        feature = model.new(
            "FeatureInstance",
            name=candidate,
            feature=candidate,
            category=category,
            direction=direction,
            access=access,
        )
        thread.featureInstances.append(feature)
        self.features[(id(thread), key)] = feature
        return feature

    # ------------------------------------------------------------------ Cheddar 2

    def v2_readers(self) -> dict[str, Callable[[etree._Element], None]]:
        return {
            "processors": self.v2_processors,
            "networks": lambda s: [
                self.network(i, V2_NETWORK_FIELDS, "generic_network")
                for i in self.items(s, ("network",), "network")
            ],
            "address_spaces": lambda s: [
                self.address_space(i, V2_ADDRESS_SPACE_FIELDS)
                for i in self.items(s, ("address_space",), "address space")
            ],
            "tasks": lambda s: [
                self.task(i, n, V2_TASK_FIELDS, "APERIODIC_TYPE")
                for n, i in enumerate(self.items(s, ("task",), "task"))
            ],
            "resources": lambda s: [
                self.resource(i, n, V2_RESOURCE_FIELDS)
                for n, i in enumerate(self.items(s, ("resource",), "resource"))
            ],
            "buffers": lambda s: [
                self.buffer(i, n, V2_BUFFER_FIELDS)
                for n, i in enumerate(self.items(s, ("buffer",), "buffer"))
            ],
            "messages": lambda s: [
                self.message(i, V2_MESSAGE_FIELDS) for i in self.items(s, ("message",), "message")
            ],
            "dependencies": self.v2_dependencies,
        }

    def positions(self, instance: EObject, item: etree._Element) -> None:
        for attribute, prop in (("x", "X_Position"), ("y", "Y_Position")):
            if item.get(attribute) is not None:
                _associate(instance, CP + prop, _int_value(self.natural(item, item.get(attribute).strip())))

    def v2_processors(self, section: etree._Element) -> None:
        for item in self.items(section, ("processor",), "processor"):
            present = self.index_children(item)
            entity = _Entity("processor", self.name_of(item, present, "processor"), item)
            self.register(self.processors, entity, "processor")
            instance = self.instance(self.root, entity.name, "processor")
            entity.instance = instance
            self.identity(instance, entity)
            consumed = {"name"}
            scheduler = present.get("scheduler")
            if scheduler is not None:
                consumed.add("scheduler")
                self.v2_scheduler(instance, scheduler, processor=True)
            link = present.get("network_link")
            if link is not None:
                consumed.add("network_link")
                _associate(instance, CP + "Network_Link", _str_value(self.text(link)))
            self.leftovers(instance, item, "processor", present, consumed)

    def v2_scheduler(self, owner: EObject, element: etree._Element, *, processor: bool) -> None:
        literal = self.literal(element, "scheduler")
        if processor and literal in SCHEDULER_TO_AADL:
            _associate(owner, SCHEDULING, _list_value([_named_value(SCHEDULER_TO_AADL[literal])]))
        else:
            _associate(owner, CP + "Scheduler", _named_value(literal))
        attributes = {k.lower(): v for k, v in element.attrib.items()}
        if "is_preemptive" in attributes:
            prop = PREEMPTIVE_SCHEDULER if processor else CP + "Preemptive"
            _associate(owner, prop, self.value(element, "preemptive", attributes["is_preemptive"].strip()))
        for attribute, prop, kind in (
            ("quantum", "Scheduler_Quantum", "time"),
            ("parametric_file_name", "User_Defined_Scheduler_File", "str"),
            ("automaton_name", "Automaton_Name", "str"),
        ):
            if attribute in attributes:
                _associate(owner, CP + prop, self.value(element, kind, attributes[attribute].strip()))
        unknown = set(attributes) - {"is_preemptive", "quantum", "parametric_file_name", "automaton_name"}
        if unknown:
            self.lenient(element, f"<scheduler> attribute {sorted(unknown)[0]!r} is not known; ignored")

    def v2_dependencies(self, section: etree._Element) -> None:
        for index, item in enumerate(self.items(section, ("dependency",), "dependency")):
            from_type = (item.get("from_type") or "task").strip().lower()
            to_type = (item.get("to_type") or "task").strip().lower()
            for kind in (from_type, to_type):
                if kind not in ("task", "buffer", "message"):
                    self.fail(item, f"dependency end type {kind!r}; expected task, buffer or message")
            words = self.text(item).split()
            if len(words) != 2:
                self.fail(item, "<dependency> must hold two names: from and to")
            tables = {"task": self.tasks, "buffer": self.buffers, "message": self.messages}
            ends = []
            for word, kind in zip(words, (from_type, to_type), strict=True):
                entity = tables[kind].get(word)
                if entity is None:
                    self.fail(
                        item, f"{kind} {word!r} is not declared (expected one of: {self.known(tables[kind])})"
                    )
                ends.append(entity)
            if from_type == "task" and to_type == "task":
                self.dependency(item, index, "PRECEDENCE_DEPENDENCY", ends[1], ends[0], None, [])
                continue
            if "task" not in (from_type, to_type):
                self.fail(item, "a dependency must have a task at one end")
            kind = (
                "QUEUEING_BUFFER_DEPENDENCY"
                if "buffer" in (from_type, to_type)
                else "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY"
            )
            if from_type == "task":
                self.dependency(item, index, kind, ends[0], ends[1], "FROM_TASK_TO_OBJECT", [])
            else:
                self.dependency(item, index, kind, ends[1], ends[0], "FROM_OBJECT_TO_TASK", [])

    # v2 sections share the Cheddar 3 entity readers (task, resource, buffer, ...).


def _same(a: object, b: object) -> bool:
    return a is b or (isinstance(a, str) and a == b)


def _own_string(obj: EObject, prop: str) -> str | None:
    for assoc in obj.ownedPropertyAssociations:
        if assoc.property == prop and assoc.ownedValues:
            value = assoc.ownedValues[0].value
            return getattr(value, "value", None)
    return None


def _common_owner(a: EObject, b: EObject) -> EObject:
    chain = []
    current = a.eContainer()
    while current is not None:
        chain.append(current)
        current = current.eContainer()
    current = b.eContainer()
    while current is not None:
        if current in chain:
            return current
        current = current.eContainer()
    return chain[-1]


def _relative_path(obj: EObject, owner: EObject) -> str:
    parts = []
    current = obj
    while current is not None and current is not owner:
        parts.append(current.name)
        current = current.eContainer()
    return ".".join(reversed(parts))


# --------------------------------------------------------------------------- public API


def loads_cheddar(
    data: bytes | str,
    filename: str = "<cheddar>",
    *,
    time_unit: str = "us",
    strict: bool = False,
    diagnostics: list[Diagnostic] | None = None,
) -> EObject:
    """Read a Cheddar 2 or 3 XML document into an ``AadlModel`` holding one ``SystemInstance``.

    ``time_unit`` says what Cheddar's plain integer times are (``us`` or ``ms``);
    ``strict`` turns what Cheddar's reader tolerates (undeclared names in Cheddar 2 files,
    unknown fields and sections, unknown enumeration values) into errors. Warnings are
    appended to ``diagnostics`` when given (and logged). Problems raise a located
    :class:`ImportFormatError` (file, line and element path).
    """
    if isinstance(data, str):
        data = data.encode("utf-8")
    reader = _Reader(filename, time_unit, strict, diagnostics)
    try:
        with gc_paused():
            return reader.read(data)
    except RosaadlError:
        raise
    except RecursionError:
        raise ImportFormatError("the document is nested too deeply", file=filename) from None


def load_cheddar(
    path: str | Path,
    *,
    time_unit: str = "us",
    strict: bool = False,
    diagnostics: list[Diagnostic] | None = None,
) -> EObject:
    """Read a Cheddar file (``.xmlv3`` / ``.xml``); see :func:`loads_cheddar`."""
    source = Path(path)
    try:
        data = source.read_bytes()
    except OSError as exc:
        raise ImportFormatError(f"cannot read the file: {exc.strerror}", file=str(path)) from None
    return loads_cheddar(data, str(path), time_unit=time_unit, strict=strict, diagnostics=diagnostics)

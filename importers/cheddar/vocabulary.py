"""The Cheddar vocabulary that the reader and the writer share (a data table).

Everything both directions must agree on lives here, once: the standard AADL properties that
hold Cheddar facts, Cheddar's enumerations, the mapping of schedulers, resource protocols and
task kinds to AADL literals and back, the element tags of Cheddar 3, the ends of each kind of
dependency, the order of the sections, and the field tables (tag, property, kind of value) of
each entity, for Cheddar 3 ADL and for Cheddar 2, in the order Cheddar's own writers use.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "CP",
    "TIME_UNITS",
    "PERIOD",
    "DEADLINE",
    "CET",
    "OFFSET",
    "JITTER",
    "PRIORITY",
    "DISPATCH",
    "POLICY",
    "CCP",
    "BINDING",
    "CONNECTION_BINDING",
    "SCHEDULING",
    "PREEMPTIVE_SCHEDULER",
    "QUEUE_SIZE",
    "DATA_SIZE",
    "SCHEDULERS",
    "ENUMERATIONS",
    "SCHEDULER_TO_AADL",
    "AADL_TO_SCHEDULER",
    "RESOURCE_PROTOCOL_TO_AADL",
    "AADL_TO_RESOURCE_PROTOCOL",
    "RESOURCE_TAGS",
    "TASK_TYPE_TO_DISPATCH",
    "DISPATCH_TO_TASK_TYPE",
    "TASK_TYPE_TAGS",
    "TASK_TAG_TYPES",
    "NETWORK_TAGS",
    "MESSAGE_TAGS",
    "DEPENDENCY_ENDS",
    "SECTIONS_V3",
    "SECTIONS_V2",
    "EXPORT_SECTIONS_V3",
    "Field",
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
]

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
CONNECTION_BINDING = "Deployment_Properties::Actual_Connection_Binding"
QUEUE_SIZE = "Communication_Properties::Queue_Size"
DATA_SIZE = "Memory_Properties::Data_Size"

# --------------------------------------------------------------------------- enumerations and mappings

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
#: Cheddar 3 task tag → its task kind (TIMED_TYPE tasks are written as periodic_task).
TASK_TAG_TYPES = {tag: kind for kind, tag in TASK_TYPE_TAGS.items() if kind != "TIMED_TYPE"}
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

# --------------------------------------------------------------------------- sections and fields

#: Section order of Cheddar 3 files as the reader takes them (entities before their users).
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
#: Section order of Cheddar 2 files (Cheddar 2's writer order).
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
#: Section order of a Cheddar 3 file written from scratch (Cheddar 3's writer order).
EXPORT_SECTIONS_V3 = (
    "core_units",
    "networks",
    "processors",
    "address_spaces",
    "tasks",
    "resources",
    "buffers",
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


def _pick(table: tuple[Field, ...], *tags: str) -> tuple[Field, ...]:
    """The fields of ``table`` with ``tags``, in the order of ``tags``."""
    by_tag = {spec.tag: spec for spec in table}
    return tuple(by_tag[tag] for tag in tags)


# Cheddar 2 tables (the order Cheddar 2's writer uses): the Cheddar 3 fields Cheddar 2 has,
# and the few whose tag differs.
V2_TASK_FIELDS = (
    *_pick(
        TASK_FIELDS,
        "capacity",
        "start_time",
        "policy",
        "deadline",
        "criticality",
        "context_switch_overhead",
        "blocking_time",
        "priority",
        "text_memory_size",
        "stack_memory_size",
        "period",
        "jitter",
        "offsets",
        "every",
        "seed",
    ),
    _f("predictable_seed", "Dispatch_Seed_Is_Predictable", "bool"),
    *_pick(TASK_FIELDS, "activation_rule"),
)
V2_ADDRESS_SPACE_FIELDS = ADDRESS_SPACE_FIELDS[:4]
V2_RESOURCE_FIELDS = RESOURCE_FIELDS  # Cheddar 2 resources have the same fields
V2_BUFFER_FIELDS = (
    _f("qs", "Queueing_System_Type", "str"),
    _f("size", "Buffer_Size", "int"),
)
V2_MESSAGE_FIELDS = _pick(
    MESSAGE_FIELDS, "size", "period", "deadline", "jitter", "response_time", "communication_time"
)
V2_NETWORK_FIELDS = (_f("type", "Network_Type", "str"),)

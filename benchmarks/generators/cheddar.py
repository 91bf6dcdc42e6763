"""Cheddar XML generated at scale: a Cheddar 3 document of N tasks (``bench_cheddar``)."""

from __future__ import annotations

__all__ = ["cheddar_document"]


def cheddar_document(tasks: int, processors: int = 8) -> bytes:
    """A Cheddar 3 document with ``tasks`` periodic tasks on ``processors`` mono-core processors,
    with one shared resource and one buffer per 100 tasks and the buffers' dependencies."""
    parts = ['<?xml version="1.0" encoding="utf-8"?>\n<cheddar>\n <core_units>']
    for p in range(processors):
        parts.append(
            f' <core_unit id="c{p}"><object_type>CORE_OBJECT_TYPE</object_type><name>core{p}</name>'
            "<scheduling><scheduling_parameters><scheduler_type>RATE_MONOTONIC_PROTOCOL</scheduler_type>"
            "<quantum>0</quantum><preemptive_type>PREEMPTIVE</preemptive_type><capacity>0</capacity>"
            "<period>0</period><priority>0</priority><start_time>0</start_time></scheduling_parameters>"
            "</scheduling><speed>1</speed></core_unit>"
        )
    parts.append(" </core_units>\n <processors>")
    for p in range(processors):
        parts.append(
            f' <mono_core_processor id="p{p}"><object_type>PROCESSOR_OBJECT_TYPE</object_type>'
            f"<name>cpu{p}</name><processor_type>MONOCORE_TYPE</processor_type>"
            f'<migration_type>NO_MIGRATION_TYPE</migration_type><core ref="c{p}"/></mono_core_processor>'
        )
    parts.append(" </processors>\n <address_spaces>")
    for p in range(processors):
        parts.append(
            f' <address_space id="a{p}"><object_type>ADDRESS_SPACE_OBJECT_TYPE</object_type>'
            f"<name>as{p}</name><cpu_name>cpu{p}</cpu_name><text_memory_size>0</text_memory_size>"
            "<stack_memory_size>0</stack_memory_size><data_memory_size>0</data_memory_size>"
            "<heap_memory_size>0</heap_memory_size></address_space>"
        )
    parts.append(" </address_spaces>\n <tasks>")
    for t in range(tasks):
        p = t % processors
        period = 1000 * (1 + t % 50)
        parts.append(
            f' <periodic_task id="t{t}"><object_type>TASK_OBJECT_TYPE</object_type><name>task{t}</name>'
            f"<task_type>PERIODIC_TYPE</task_type><cpu_name>cpu{p}</cpu_name>"
            f"<address_space_name>as{p}</address_space_name><capacity>{1 + t % 7}</capacity>"
            f"<deadline>{period}</deadline><start_time>0</start_time><priority>{1 + t % 99}</priority>"
            "<blocking_time>0</blocking_time><policy>SCHED_FIFO</policy><text_memory_size>0</text_memory_size>"
            "<stack_memory_size>0</stack_memory_size><criticality>0</criticality>"
            f"<context_switch_overhead>0</context_switch_overhead><period>{period}</period><jitter>0</jitter>"
            "</periodic_task>"
        )
    parts.append(" </tasks>\n <resources>")
    groups = range(0, tasks - processors, 100)
    for g in groups:
        p = g % processors
        users = "".join(
            f"<task_name>task{g + k * processors}</task_name><critical_section><task_begin>1</task_begin>"
            "<task_end>1</task_end></critical_section>"
            for k in range(2)
        )
        parts.append(
            f' <pip_resource id="r{g}"><object_type>RESOURCE_OBJECT_TYPE</object_type><name>res{g}</name>'
            f"<state>1</state><protocol>PRIORITY_INHERITANCE_PROTOCOL</protocol><critical_sections>{users}"
            f"</critical_sections><cpu_name>cpu{p}</cpu_name><address_space_name>as{p}</address_space_name>"
            "</pip_resource>"
        )
    parts.append(" </resources>\n <buffers>")
    for g in groups:
        p = g % processors
        parts.append(
            f' <buffer id="b{g}"><object_type>BUFFER_OBJECT_TYPE</object_type><name>buf{g}</name>'
            f"<cpu_name>cpu{p}</cpu_name><address_space_name>as{p}</address_space_name>"
            "<queueing_system_type>QS_PP1</queueing_system_type><buffer_size>10</buffer_size>"
            f"<roles><task_name>task{g}</task_name><buffer_role><the_role>QUEUING_PRODUCER</the_role>"
            "<size>1</size><time>1</time><timeout>0</timeout></buffer_role></roles></buffer>"
        )
    parts.append(" </buffers>\n <dependencies>")
    for g in groups:
        parts.append(
            "  <dependency><type_of_dependency>QUEUEING_BUFFER_DEPENDENCY</type_of_dependency>"
            f'<buffer_dependent_task ref="t{g}"/><buffer_orientation>FROM_TASK_TO_OBJECT</buffer_orientation>'
            f'<buffer_dependency_object ref="b{g}"/></dependency>'
        )
    parts.append(" </dependencies>\n</cheddar>\n")
    return "\n".join(parts).encode("utf-8")

"""Cheddar XML benchmark: import and export of the corpus files and of a generated large model.

Side by side in one run, per file:
  * the raw lxml parse of the file (the floor an importer cannot beat);
  * ``loads_cheddar`` (parse + checks + instance model);
  * ``dumps_cheddar`` of that model in the same format;
  * the comparison of the round trip (import of the export vs the first import, with
    ``rosaadl.model.model_differences``; for the generated file only with ``--compare``).

The generated file has ``--tasks`` tasks (10 000 by default) on 8 mono-core processors, with
one shared resource and one buffer per 100 tasks and the buffers' dependencies.
Usage: ``python -m benchmarks.bench_cheddar [--tasks N] [--repeat R] [--no-corpus]``.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable
from pathlib import Path

from lxml import etree

from rosaadl import model
from rosaadl.exporters.cheddar import dumps_cheddar
from rosaadl.fileio import safe_xml_parser
from rosaadl.importers.cheddar import cheddar_format_of, loads_cheddar, strip_internal_subset

__all__ = ["main", "generated_model"]


def _corpus() -> Path:
    env = os.environ.get("ROSAADL_CORPUS")
    base = Path(env) if env else Path(__file__).resolve().parent.parent.parent / "shared" / "corpus"
    return base / "cheddar"


def generated_model(tasks: int, processors: int = 8) -> bytes:
    """A Cheddar 3 document with ``tasks`` periodic tasks (and resources, buffers, dependencies)."""
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


def _time(action: Callable[[], object], repeat: int) -> tuple[float, object]:
    """Best wall time of ``repeat`` runs (seconds) and the last result."""
    best = float("inf")
    result = None
    for _ in range(repeat):
        start = time.perf_counter()
        result = action()
        best = min(best, time.perf_counter() - start)
    return best, result


def _row(name: str, data: bytes, repeat: int, compare: bool = True) -> tuple:
    stripped = strip_internal_subset(data, name)
    parse, tree = _time(lambda: etree.fromstring(stripped, safe_xml_parser()), repeat)
    fmt = cheddar_format_of(tree)
    load, first = _time(lambda: loads_cheddar(data, name), repeat)
    dump, exported = _time(lambda: dumps_cheddar(first, cheddar_format=fmt), repeat)
    if not compare:
        return (name, len(data) / 1024, _task_count(tree), fmt, parse, load, dump, None, "not compared")
    second = loads_cheddar(exported, name)
    took, differences = _time(lambda: model.model_differences(first, second), 1)
    verdict = "equal" if not differences else "DIFFERS"
    return (name, len(data) / 1024, _task_count(tree), fmt, parse, load, dump, took, verdict)


def _task_count(tree: etree._Element) -> int:
    section = next((s for s in tree if isinstance(s.tag, str) and s.tag.lower() == "tasks"), None)
    return sum(1 for t in section if isinstance(t.tag, str)) if section is not None else 0


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_cheddar", description=__doc__.splitlines()[0])
    parser.add_argument("--tasks", type=int, default=10_000, help="tasks of the generated file")
    parser.add_argument("--repeat", type=int, default=3, help="runs per corpus measurement (best is shown)")
    parser.add_argument("--no-corpus", action="store_true", help="only the generated file")
    parser.add_argument(
        "--compare",
        action="store_true",
        help="also compare the generated model's round trip (slow: about a minute)",
    )
    options = parser.parse_args(argv)
    rows = []
    folder = _corpus()
    if not options.no_corpus and folder.is_dir():
        for path in sorted(folder.glob("*.xml*")):
            rows.append(_row(path.name, path.read_bytes(), options.repeat))
    elif not options.no_corpus:
        print(f"(corpus not found at {folder}; only the generated file is measured)")
    rows.append(_row(f"generated {options.tasks} tasks", generated_model(options.tasks), 1, options.compare))
    header = ("file", "KiB", "tasks", "fmt", "lxml parse", "import", "export", "compare", "round trip")
    print(
        f"{header[0]:<38} {header[1]:>7} {header[2]:>6} {header[3]:>3} "
        f"{header[4]:>11} {header[5]:>10} {header[6]:>10} {header[7]:>10}  {header[8]}"
    )
    for name, size, tasks, fmt, parse, load, dump, compare, verdict in rows:
        took = f"{compare * 1000:8.1f}ms" if compare is not None else f"{'-':>10}"
        print(
            f"{name:<38} {size:7.1f} {tasks:6d} {fmt:>3} {parse * 1000:9.2f}ms {load * 1000:8.1f}ms "
            f"{dump * 1000:8.1f}ms {took}  {verdict}"
        )
    if len(rows) > 1:
        corpus_rows = rows[:-1]
        ratio = statistics.median(r[5] / r[4] for r in corpus_rows if r[4] > 0)
        print(f"median import / raw parse over the corpus: {ratio:.0f}x")
    return 0 if all(r[-1] != "DIFFERS" for r in rows) else 1


if __name__ == "__main__":
    import sys

    raise SystemExit(main(sys.argv[1:]))

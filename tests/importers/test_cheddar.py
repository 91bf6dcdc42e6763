"""Cheddar XML import: the shared corpus (counts and task timing checked against INDEX.md and
the files themselves, read independently with lxml), the mapping rules, and bad input."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from conftest import corpus_dir
from lxml import etree

from rosaadl import model
from rosaadl.errors import Diagnostic, ImportFormatError
from rosaadl.importers.cheddar import (
    aadl_identifier,
    cheddar_format_of,
    load_cheddar,
    loads_cheddar,
    strip_internal_subset,
)
from rosaadl.properties import EnumLiteral, Range, own_property
from rosaadl.units import Quantity

CP = "Cheddar_Properties::"


# --------------------------------------------------------------------------- corpus index


def _index_rows() -> list:
    """The rows of corpus/cheddar/INDEX.md: (file, format, counts c/p/as/t/r/b/m/n/d)."""
    index = corpus_dir() / "cheddar" / "INDEX.md"
    if not index.is_file():
        return [pytest.param(None, None, None, id="corpus-absent")]
    rows = []
    for line in index.read_text(encoding="utf-8").splitlines():
        match = re.match(r"\|\s*([\w.-]+\.xml\w*)\s*\|[^|]*\|\s*(v[23])\s*\|\s*([-\d/]+)\s*\|", line)
        if match:
            rows.append(pytest.param(match.group(1), match.group(2), match.group(3), id=match.group(1)))
    return rows


ROWS = _index_rows()


def _counts(text: str) -> dict[str, int]:
    keys = (
        "cores",
        "processors",
        "address_spaces",
        "tasks",
        "resources",
        "buffers",
        "messages",
        "networks",
        "dependencies",
    )
    values = [0 if part == "-" else int(part) for part in text.split("/")]
    return dict(zip(keys, values, strict=True))


def _category(obj) -> str:
    return obj.category.name if obj.category is not None else ""


def _all_components(root) -> list:
    """Component instances below ``root`` in document order (faster than a full model walk)."""
    out, stack = [], [root]
    while stack:
        current = stack.pop()
        out.append(current)
        stack.extend(reversed(current.componentInstances))
    return out


def _components(root, category: str) -> list:
    return [o for o in _all_components(root) if _category(o) == category]


def _connections(root) -> list:
    return [c for o in _all_components(root) for c in o.connectionInstances]


def _model_counts(root) -> dict[str, int]:
    processors = [p for p in root.componentInstances if _category(p) == "processor"]
    cores = 0
    for processor in processors:
        inner = [c for c in processor.componentInstances if _category(c) == "processor"]
        cores += len(inner) if inner else (1 if own_property(processor, CP + "Core_Name") is not None else 0)
    datas = _components(root, "data")

    def role(name: str) -> int:
        return sum(1 for d in datas if own_property(d, CP + "Data_Role") == name)

    connections = _connections(root)
    return {
        "cores": cores,
        "processors": len(processors),
        "address_spaces": len(_components(root, "process")),
        "tasks": len(_components(root, "thread")),
        "resources": role("Resource"),
        "buffers": role("Buffer"),
        "messages": role("Message"),
        "networks": len(_components(root, "bus")),
        "dependencies": sum(1 for c in connections if own_property(c, CP + "Dependency_Type") is not None),
    }


def _raw_tree(path: Path) -> etree._Element:
    """The file read with plain lxml; the inline DTD of Cheddar 2 files cut out first."""
    data = path.read_bytes()
    data = re.sub(rb"<!DOCTYPE.*?\]\s*>", b"", data, flags=re.S)
    return etree.fromstring(data)


def _thread_by_name(root, name: str):
    found = [t for t in _components(root, "thread") if own_property(t, CP + "Cheddar_Name") == name]
    assert len(found) == 1, f"{len(found)} threads imported for task {name!r}"
    return found[0]


def _number(element: etree._Element, tag: str) -> int | None:
    child = element.find(tag)
    return int(child.text.strip()) if child is not None else None


# --------------------------------------------------------------------------- corpus tests


@pytest.mark.corpus
@pytest.mark.parametrize(("name", "fmt", "counts"), ROWS)
def test_corpus_file_imports_with_index_counts(corpus: Path, name: str, fmt: str, counts: str) -> None:
    path = corpus / "cheddar" / name
    diagnostics: list[Diagnostic] = []
    aadl_model = load_cheddar(path, diagnostics=diagnostics)
    assert all(d.severity == "warning" for d in diagnostics)
    (root,) = aadl_model.instances
    assert root.name == aadl_identifier(path.stem)
    assert _model_counts(root) == _counts(counts)
    assert cheddar_format_of(_raw_tree(path)) == int(fmt[1])


@pytest.mark.corpus
@pytest.mark.parametrize(("name", "fmt", "counts"), ROWS)
@pytest.mark.parametrize("unit", ["us", "ms"])
def test_corpus_task_timing_matches_the_file(
    corpus: Path, name: str, fmt: str, counts: str, unit: str
) -> None:
    path = corpus / "cheddar" / name
    root = load_cheddar(path, time_unit=unit).instances[0]
    raw = _raw_tree(path)
    tasks = [t for t in raw.find("tasks") if isinstance(t.tag, str)]
    assert len(tasks) == len(_components(root, "thread"))
    for position, task in enumerate(tasks):
        task_name = " ".join(task.findtext("name").split())
        thread = _thread_by_name(root, task_name)
        assert own_property(thread, CP + "Section_Index") == position
        capacity = _number(task, "capacity")
        assert own_property(thread, "Timing_Properties::Compute_Execution_Time") == Range(
            Quantity(capacity, unit), Quantity(capacity, unit)
        )
        for tag, prop in (
            ("period", "Timing_Properties::Period"),
            ("deadline", "Timing_Properties::Deadline"),
            ("start_time", "Timing_Properties::Dispatch_Offset"),
            ("jitter", "Timing_Properties::Dispatch_Jitter"),
        ):
            value = _number(task, tag)
            expected = Quantity(value, unit) if value is not None else None
            assert own_property(thread, prop) == expected, (task_name, tag)
        assert own_property(thread, "Thread_Properties::Priority") == _number(task, "priority")
        kind = (task.findtext("task_type") or task.get("task_type") or "").strip()
        dispatch = {"PERIODIC_TYPE": "Periodic", "APERIODIC_TYPE": "Aperiodic"}[kind]
        assert own_property(thread, "Thread_Properties::Dispatch_Protocol") == EnumLiteral(dispatch)
        # bound to the processor the task names (or its undeclared name, kept as a reference)
        binding = own_property(thread, "Deployment_Properties::Actual_Processor_Binding")[0]
        cpu = " ".join(task.findtext("cpu_name").split())
        bound_name = binding.path if hasattr(binding, "path") else own_property(binding, CP + "Cheddar_Name")
        assert bound_name == cpu


@pytest.mark.corpus
def test_cheddar2_inline_dtd_declares_no_entity_but_libxml2_refuses_it(corpus: Path) -> None:
    """Why the importer blanks the internal subset: no entity, but a redefined element."""
    for name in ("edf_pip_resource_v2.xml", "ocarina_issue288_test_cheddar_v2.xml"):
        data = (corpus / "cheddar" / name).read_bytes()
        subset = re.search(rb"<!DOCTYPE.*?\]\s*>", data, flags=re.S).group(0)
        assert b"<!ENTITY" not in subset and b"%" not in subset
        assert subset.count(b"<!ELEMENT context_switch_overhead ") == 2
        with pytest.raises(etree.XMLSyntaxError, match="Redefinition"):
            etree.fromstring(data, etree.XMLParser(resolve_entities=False, load_dtd=False, no_network=True))
        blanked = strip_internal_subset(data, name)
        assert len(blanked) == len(data) and blanked.count(b"\n") == data.count(b"\n")


@pytest.mark.corpus
def test_multicore_processor_has_one_processor_per_core(corpus: Path) -> None:
    root = load_cheddar(corpus / "cheddar" / "cheddar_adl_test4_multicore.xmlv3").instances[0]
    (processor,) = [p for p in root.componentInstances if _category(p) == "processor"]
    cores = processor.componentInstances
    assert [own_property(c, CP + "Cheddar_Name") for c in cores] == ["core1", "core2"]
    assert [own_property(c, CP + "Cheddar_Id") for c in cores] == ["id_9", "id_10"]
    assert own_property(processor, CP + "Migration_Type") == "TIME_UNIT_MIGRATION_TYPE"
    for core in cores:
        assert own_property(core, "Deployment_Properties::Scheduling_Protocol") == [
            EnumLiteral("POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL")
        ]
        assert own_property(core, CP + "Scheduler_Quantum") == Quantity(100, "us")
    for thread in _components(root, "thread"):
        assert own_property(thread, "Deployment_Properties::Actual_Processor_Binding") == [processor]


@pytest.mark.corpus
def test_resources_become_shared_data_with_protocol_and_critical_sections(corpus: Path) -> None:
    root = load_cheddar(corpus / "cheddar" / "manual_ceiling_priority_ipcp.xmlv3").instances[0]
    (resource,) = [d for d in _components(root, "data")]
    assert resource.eContainer().category.name == "process"
    assert own_property(resource, "Thread_Properties::Concurrency_Control_Protocol") == EnumLiteral(
        "Priority_Ceiling"
    )
    assert own_property(resource, CP + "Resource_Protocol") == EnumLiteral(
        "IMMEDIATE_PRIORITY_CEILING_PROTOCOL"
    )
    assert own_property(resource, "Thread_Properties::Priority") == 20
    assert own_property(resource, CP + "Priority_Assignment") == EnumLiteral("MANUAL_ASSIGNMENT")
    (section,) = own_property(resource, CP + "Critical_Sections")
    assert section["Task"] is _thread_by_name(root, "T1")
    assert (section["Task_Begin"], section["Task_End"]) == (Quantity(1, "us"), Quantity(2, "us"))

    root = load_cheddar(corpus / "cheddar" / "ravenscar_pip_resource.xmlv3").instances[0]
    (resource,) = _components(root, "data")
    assert own_property(resource, "Thread_Properties::Concurrency_Control_Protocol") == EnumLiteral(
        "Priority_Inheritance"
    )
    assert own_property(resource, CP + "Resource_Protocol") is None


@pytest.mark.corpus
def test_cheddar2_resource_users_and_undeclared_processor(corpus: Path) -> None:
    path = corpus / "cheddar" / "edf_pip_resource_v2.xml"
    diagnostics: list[Diagnostic] = []
    root = load_cheddar(path, diagnostics=diagnostics).instances[0]
    (warning,) = [d for d in diagnostics if "not declared" in d.message]
    assert warning.location.path == "/cheddar/tasks/task[3]/cpu_name" and warning.location.line is not None
    (resource,) = _components(root, "data")
    sections = own_property(resource, CP + "Critical_Sections")
    assert [(s["Task"].name, s["Task_Begin"].value, s["Task_End"].value) for s in sections] == [
        ("T1", 1, 1),
        ("T2", 2, 4),
        ("T2", 1, 1),
    ]
    (processor,) = [p for p in root.componentInstances if _category(p) == "processor"]
    assert own_property(processor, "Deployment_Properties::Scheduling_Protocol") == [
        EnumLiteral("Earliest_Deadline_First_Protocol")
    ]
    with pytest.raises(ImportFormatError) as caught:
        load_cheddar(path, strict=True)
    assert caught.value.location.path == "/cheddar/tasks/task[3]/cpu_name"


@pytest.mark.corpus
def test_buffers_and_dependencies_become_access_connections(corpus: Path) -> None:
    root = load_cheddar(corpus / "cheddar" / "buffer_sched_case_study_01.xmlv3").instances[0]
    (space,) = _components(root, "process")
    connections = list(space.connectionInstances)
    assert [c.name for c in connections] == [
        "Task_1.Buffer_01 -> Buffer_01",
        "Buffer_01 -> Task_2.Buffer_01",
        "Task_2.Buffer_02 -> Buffer_02",
    ]
    assert all(c.kind.name == "accessConnection" for c in connections)
    buffer = [d for d in _components(root, "data") if d.name == "Buffer_01"][0]
    roles = own_property(buffer, CP + "Buffer_Roles")
    assert [(r["Task"].name, r["Role"].name, r["Time"].value) for r in roles] == [
        ("Task_1", "QUEUING_PRODUCER", 6),
        ("Task_2", "QUEUING_CONSUMER", 1),
    ]


@pytest.mark.corpus
def test_messages_and_asynchronous_dependencies(corpus: Path) -> None:
    root = load_cheddar(corpus / "cheddar" / "gpu_analysis_model_1.xmlv3").instances[0]
    messages = [d for d in _components(root, "data") if own_property(d, CP + "Data_Role") == "Message"]
    assert [own_property(m, CP + "Cheddar_Name") for m in messages][
        0
    ] == "message:DAG1-Kernel1_to_Kernel2::Prev1-Block1"
    assert messages[0].name == "message_DAG1_Kernel1_to_Kernel2_Prev1_Block1"
    connections = _connections(root)
    assert sorted(own_property(c, CP + "Section_Index") for c in connections) == list(range(10))
    first = min(connections, key=lambda c: own_property(c, CP + "Section_Index"))
    assert first.source is messages[0]  # FROM_OBJECT_TO_TASK: the message is the source
    assert own_property(first, CP + "Asynchronous_Communication_Protocol_Property") == EnumLiteral(
        "FIRST_MESSAGE"
    )


# --------------------------------------------------------------------------- own fixtures

_CORE = (
    '<core_unit id="c1"><object_type>CORE_OBJECT_TYPE</object_type><name>core</name>'
    "<scheduling><scheduling_parameters><scheduler_type>RATE_MONOTONIC_PROTOCOL</scheduler_type>"
    "<quantum>0</quantum><preemptive_type>PREEMPTIVE</preemptive_type></scheduling_parameters>"
    "</scheduling></core_unit>"
)


def _task(name: str = "a", ident: str = "t1", cpu: str = "cpu", period: str = "10", extra: str = "") -> str:
    cpu_part = f"<cpu_name>{cpu}</cpu_name>" if cpu is not None else ""
    return (
        f'<periodic_task id="{ident}"><name>{name}</name><task_type>PERIODIC_TYPE</task_type>{cpu_part}'
        f"<address_space_name>as</address_space_name><capacity>2</capacity><deadline>10</deadline>"
        f"<priority>1</priority><period>{period}</period>{extra}</periodic_task>"
    )


def _document(tasks: str | None = None, more: str = "", core: str = _CORE, processor_ref: str = "c1") -> str:
    tasks = _task() if tasks is None else tasks
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n<cheddar>\n'
        f"<core_units>{core}</core_units>\n"
        f'<processors><mono_core_processor id="p1"><name>cpu</name><core ref="{processor_ref}"/>'
        "</mono_core_processor></processors>\n"
        '<address_spaces><address_space id="s1"><name>as</name><cpu_name>cpu</cpu_name></address_space>'
        "</address_spaces>\n"
        f"<tasks>\n{tasks}\n</tasks>\n{more}</cheddar>\n"
    )


def _error(text: str | bytes, **options) -> ImportFormatError:
    data = text.encode("utf-8") if isinstance(text, str) else text
    with pytest.raises(ImportFormatError) as caught:
        loads_cheddar(data, "bad.xmlv3", **options)
    error = caught.value
    assert error.location.file == "bad.xmlv3"
    return error


def test_own_fixture_imports() -> None:
    root = loads_cheddar(_document().encode(), "mini.xmlv3").instances[0]
    (thread,) = _components(root, "thread")
    assert model.instance_path(thread) == "mini.as.a"
    assert own_property(thread, "Timing_Properties::Period") == Quantity(10, "us")


def test_bom_and_crlf_are_handled_and_lines_stay_right() -> None:
    text = _document().replace("\n", "\r\n")
    root = loads_cheddar(b"\xef\xbb\xbf" + text.encode(), "crlf.xmlv3").instances[0]
    assert len(_components(root, "thread")) == 1
    bad = _document(_task(period="-1")).replace("\n", "\r\n")
    error = _error(b"\xef\xbb\xbf" + bad.encode())
    assert error.location.line == 7
    assert error.location.path == "/cheddar/tasks/periodic_task/period"


def test_missing_cpu_is_a_located_error() -> None:
    error = _error(_document(_task(cpu=None)))
    assert error.location.path == "/cheddar/tasks/periodic_task" and "cpu_name" in error.message


def test_task_on_unknown_processor_is_a_located_error() -> None:
    error = _error(_document(_task(cpu="gpu")))
    assert error.location.path == "/cheddar/tasks/periodic_task/cpu_name"
    assert "'gpu' is not declared" in error.message


def test_duplicate_ids_are_an_error() -> None:
    error = _error(_document(_task() + _task(name="b", ident="t1")))
    assert (
        error.location.path == "/cheddar/tasks/periodic_task[2]" and "id 't1' is used twice" in error.message
    )


def test_dangling_ref_is_an_error() -> None:
    error = _error(_document(processor_ref="c9"))
    assert error.location.path == "/cheddar/processors/mono_core_processor/core" and "c9" in error.message
    dependency = (
        "<dependencies><dependency><type_of_dependency>PRECEDENCE_DEPENDENCY</type_of_dependency>"
        '<precedence_sink ref="t1"/><precedence_source ref="p1"/></dependency></dependencies>'
    )
    error = _error(_document(more=dependency))
    assert error.location.path == "/cheddar/dependencies/dependency/precedence_source"
    assert "expected a task" in error.message


def test_negative_and_malformed_numbers_are_errors() -> None:
    error = _error(_document(_task(period="-40")))
    assert error.location.path == "/cheddar/tasks/periodic_task/period" and "natural" in error.message
    error = _error(_document(_task(period="4e1")))
    assert "whole number" in error.message
    error = _error(_document(_task(period="0")))
    assert "greater than 0" in error.message
    error = _error(_document(_task(period="99999999999999999999999")))
    assert "too large" in error.message


def test_entity_bomb_and_external_dtd_are_refused() -> None:
    bomb = (
        '<?xml version="1.0"?>\n<!DOCTYPE cheddar [\n <!ENTITY a "aaaaaaaaaa">\n'
        ' <!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">\n <!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;">\n]>\n'
        "<cheddar>&c;</cheddar>"
    )
    error = _error(bomb)
    assert "entities" in error.message and error.location.line == 3
    error = _error(
        '<?xml version="1.0"?>\n<!DOCTYPE cheddar SYSTEM "http://example.org/cheddar.dtd">\n<cheddar/>'
    )
    assert "external DTD" in error.message
    error = _error('<!DOCTYPE cheddar [<!ENTITY x SYSTEM "file:///etc/passwd">]><cheddar>&x;</cheddar>')
    assert "entities" in error.message
    error = _error("<!DOCTYPE cheddar [<!ELEMENT cheddar ANY> %p;]><cheddar/>")
    assert "parameter entities" in error.message
    # an undeclared entity reference without any DTD is malformed XML
    error = _error("<cheddar>&x;</cheddar>")
    assert "malformed XML" in error.message


def test_truncated_empty_and_foreign_documents_are_located_errors() -> None:
    text = _document()
    error = _error(text[: len(text) // 2])
    assert "malformed XML" in error.message and error.location.line is not None
    assert "empty" in _error(b"").message
    assert "expected <cheddar>" in _error("<system><tasks/></system>").message
    assert "malformed" in _error(b"\xff\xfe\x00<\x00c\x00" * 3).message


def test_deep_nesting_is_refused_without_a_traceback() -> None:
    deep = "<cheddar>" + "<x>" * 100_000 + "</x>" * 100_000 + "</cheddar>"
    error = _error(deep)
    assert error.location.file == "bad.xmlv3"


def test_reference_rules_follow_cheddar3() -> None:
    space_on_other_cpu = _document(_task()).replace(
        "</processors>",
        '<mono_core_processor id="p2"><name>cpu2</name><core ref="c1"/></mono_core_processor></processors>',
    )
    moved = "<cpu_name>cpu2</cpu_name><address_space_name>"
    error = _error(space_on_other_cpu.replace("<cpu_name>cpu</cpu_name><address_space_name>", moved))
    assert error.location.path == "/cheddar/tasks/periodic_task/cpu_name"
    assert "on processor 'cpu2' but its address space 'as' is on 'cpu'" in error.message
    no_space = _document(_task().replace("<address_space_name>as</address_space_name>", ""))
    assert "address_space_name" in _error(no_space).message
    twice = _document(_task() + _task(ident="t2"))
    assert "name 'a' is used twice" in _error(twice).message
    resource = (
        '<resources><pcp_resource id="r1"><name>r</name><protocol>PRIORITY_CEILING_PROTOCOL</protocol>'
        "<critical_sections><task_name>ghost</task_name><critical_section><task_begin>1</task_begin>"
        "<task_end>2</task_end></critical_section></critical_sections><cpu_name>cpu</cpu_name>"
        "<address_space_name>as</address_space_name></pcp_resource></resources>"
    )
    error = _error(_document(more=resource))
    assert "task 'ghost' is not declared" in error.message and error.location.path.endswith("task_name")


def test_unknown_values_fields_and_sections_warn_or_fail_when_strict() -> None:
    text = (
        _document(_task(extra="<policy>sched_fifo</policy><colour>blue</colour>"))
        .replace(
            "</cheddar>",
            "<event_analyzers><event_analyzer><name>e</name></event_analyzer></event_analyzers></cheddar>",
        )
        .replace("RATE_MONOTONIC_PROTOCOL", "QUANTUM_SCHEDULING_PROTOCOL")
    )
    diagnostics: list[Diagnostic] = []
    root = loads_cheddar(text.encode(), "lenient.xmlv3", diagnostics=diagnostics).instances[0]
    messages = " | ".join(d.message for d in diagnostics)
    assert (
        "QUANTUM_SCHEDULING_PROTOCOL" in messages and "<colour>" in messages and "event_analyzers" in messages
    )
    (thread,) = _components(root, "thread")
    assert own_property(thread, "Thread_Properties::POSIX_Scheduling_Policy") == EnumLiteral("SCHED_FIFO")
    assert own_property(thread, CP + "Unmodelled_Fields") == [
        {"Section": "task", "Xml": "<colour>blue</colour>"}
    ]
    assert own_property(root, CP + "Unmodelled_Elements") == [
        {"Section": "event_analyzers", "Xml": "<event_analyzer><name>e</name></event_analyzer>"}
    ]
    with pytest.raises(ImportFormatError):
        loads_cheddar(text.encode(), "strict.xmlv3", strict=True)


def test_hostile_names_become_identifiers_and_are_kept() -> None:
    names = ["../../etc/passwd", "a b\tc", "<&>", "1st", "T1", "t1"]
    tasks = "".join(
        _task(name=n.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;"), ident=f"t{i}")
        for i, n in enumerate(names)
    )
    root = loads_cheddar(_document(tasks).encode(), "names.xmlv3").instances[0]
    threads = _components(root, "thread")
    assert [own_property(t, CP + "Cheddar_Name") for t in threads] == names
    instance_names = [t.name for t in threads]
    assert instance_names == ["etc_passwd", "a_b_c", "unnamed", "n_1st", "T1", "t1_2"]
    assert all(re.fullmatch(r"[A-Za-z][A-Za-z0-9]*(_[A-Za-z0-9]+)*", n) for n in instance_names)


def test_milliseconds_option_and_bad_unit() -> None:
    root = loads_cheddar(_document().encode(), "ms.xmlv3", time_unit="ms").instances[0]
    (thread,) = _components(root, "thread")
    assert own_property(thread, "Timing_Properties::Period") == Quantity(10, "ms")
    with pytest.raises(Exception, match="time_unit"):
        loads_cheddar(_document().encode(), "x.xmlv3", time_unit="s")


def test_cheddar2_dependencies_and_buffers() -> None:
    text = """<?xml version="1.0"?>
<cheddar>
 <processors><processor><name> cpu </name><scheduler quantum="2" is_preemptive="NOT_PREEMPTIVE">
   Rate_Monotonic_Protocol </scheduler></processor></processors>
 <address_spaces><address_space><name>as</name><cpu_name>cpu</cpu_name></address_space></address_spaces>
 <tasks>
  <task task_type="PERIODIC_TYPE" x="3" y="4"><name>a</name><cpu_name>cpu</cpu_name>
   <address_space_name>as</address_space_name><capacity> 1 </capacity><period>5</period>
   <offsets><offset> 1 2 </offset></offsets></task>
  <task><name>b</name><cpu_name>cpu</cpu_name><address_space_name>as</address_space_name>
   <capacity>1</capacity></task>
 </tasks>
 <buffers><buffer><cpu_name>cpu</cpu_name><address_space_name>as</address_space_name><name>q</name>
  <qs>QS_PP1</qs><size>4</size><buffer_used_by><buffer_user buffer_role="producer"> a 1 1 </buffer_user>
  <buffer_user buffer_role="consumer">b 1 1</buffer_user></buffer_used_by></buffer></buffers>
 <dependencies>
  <dependency from_type="task" to_type="task">a b</dependency>
  <dependency from_type="task" to_type="buffer">a q</dependency>
  <dependency from_type="buffer" to_type="task">q b</dependency>
 </dependencies>
</cheddar>"""
    root = loads_cheddar(text.encode(), "v2.xml").instances[0]
    (processor,) = [p for p in root.componentInstances if _category(p) == "processor"]
    assert own_property(processor, "Deployment_Properties::Preemptive_Scheduler") is False
    assert own_property(processor, CP + "Scheduler_Quantum") == Quantity(2, "us")
    a, b = _components(root, "thread")
    assert own_property(b, "Thread_Properties::Dispatch_Protocol") == EnumLiteral("Aperiodic")
    assert own_property(a, CP + "Offsets") == [{"Activation": 1, "Offset_Value": Quantity(2, "us")}]
    assert own_property(a, CP + "X_Position") == 3
    kinds = [own_property(c, CP + "Dependency_Type").name for c in a.eContainer().connectionInstances]
    assert kinds == ["PRECEDENCE_DEPENDENCY", "QUEUEING_BUFFER_DEPENDENCY", "QUEUEING_BUFFER_DEPENDENCY"]
    precedence = a.eContainer().connectionInstances[0]
    assert precedence.source.eContainer() is a and precedence.destination.eContainer() is b
    error = _error(text.replace("a q</dependency>", "a nowhere</dependency>"))
    assert error.location.path == "/cheddar/dependencies/dependency[2]" and "'nowhere'" in error.message


def test_large_generated_file_imports() -> None:
    count = 1500
    tasks = "\n".join(_task(name=f"t{i}", ident=f"t{i}") for i in range(count))
    root = loads_cheddar(_document(tasks).encode(), "big.xmlv3").instances[0]
    threads = _components(root, "thread")
    assert len(threads) == count and threads[-1].name == f"t{count - 1}"

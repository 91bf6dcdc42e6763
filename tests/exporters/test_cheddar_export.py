"""Cheddar XML export: corpus round trips, conformance of every exported file to the Cheddar
vocabulary collected from the corpus (tests/data/cheddar_vocabulary.json) and to Cheddar's
structure rules, and instance models shaped like the AADL instantiator's."""

from __future__ import annotations

import json
import re
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import pytest
from conftest import corpus_dir
from lxml import etree

from rosaadl import model
from rosaadl.errors import Diagnostic, ExportError
from rosaadl.exporters.cheddar import dumps_cheddar, structure_problems, write_cheddar
from rosaadl.importers.aaxl2 import read_aaxl2
from rosaadl.importers.cheddar import cheddar_format_of, loads_cheddar
from rosaadl.properties import Range, own_property
from rosaadl.units import Quantity

CP = "Cheddar_Properties::"
VOCABULARY = json.loads(
    (Path(__file__).resolve().parent.parent / "data" / "cheddar_vocabulary.json").read_text()
)


def _corpus_files() -> list:
    folder = corpus_dir() / "cheddar"
    if not folder.is_dir():
        return [pytest.param(None, id="corpus-absent")]
    return [pytest.param(p.name, id=p.name) for p in sorted(folder.glob("*.xml*"))]


FILES = _corpus_files()


def _strip_dtd(data: bytes) -> bytes:
    return re.sub(rb"<!DOCTYPE.*?\]\s*>", b"", data, flags=re.S)


# --------------------------------------------------------------------------- the conformance oracle


def _local(element: etree._Element) -> str:
    return etree.QName(element).localname.lower()


def conformance_problems(data: bytes, fmt: int) -> list[str]:
    """Everything in an exported file that is outside the vocabulary or breaks the structure rules."""
    key = f"v{fmt}"
    corpus = VOCABULARY["corpus"][key]
    extra = VOCABULARY["reader_additions"][key]
    elements = set(corpus["elements"]) | set(extra["elements"])
    attributes = set(corpus["attributes"]) | set(extra["attributes"])
    values: dict[str, set[str]] = {k: {v.upper() for v in vs} for k, vs in corpus["values"].items()}
    for name, entry in extra["values"].items():
        values.setdefault(name, set()).update(v.upper() for v in entry["values"])
    enumerations = set(VOCABULARY["enumeration_elements"])
    problems: list[str] = []
    root = etree.fromstring(data)
    tree = root.getroottree()
    if b"<!DOCTYPE" in data or b"<!ENTITY" in data:
        problems.append("the export has a DOCTYPE")
    for element in root.iter():
        if not isinstance(element.tag, str):
            continue
        tag = _local(element)
        where = tree.getpath(element)
        if tag not in elements:
            problems.append(f"{where}: element <{tag}> is not in the vocabulary")
        for attribute, value in element.attrib.items():
            if attribute.lower() not in attributes:
                problems.append(f"{where}: attribute {attribute} is not in the vocabulary")
            allowed = values.get("@" + attribute.lower())
            if allowed is not None and value.strip().upper() not in allowed:
                problems.append(f"{where}: {attribute}={value!r} is not a known value")
        if tag in enumerations and len(element) == 0:
            text = " ".join((element.text or "").split()).upper()
            if text not in values.get(tag, set()):
                problems.append(f"{where}: <{tag}>{text}</{tag}> is not a known value")
    sections = {_local(s): s for s in root if isinstance(s.tag, str)}

    def named(section: str) -> dict[str, etree._Element]:
        found: dict[str, etree._Element] = {}
        for item in sections.get(section, []):
            if isinstance(item.tag, str):
                name = " ".join((item.findtext("name") or "").split())
                if name in found:
                    problems.append(f"{tree.getpath(item)}: {section} name {name!r} twice")
                found[name] = item
        return found

    processors, spaces, tasks = named("processors"), named("address_spaces"), named("tasks")
    if fmt == 3:
        ids: dict[str, etree._Element] = {}
        for element in root.iter():
            if isinstance(element.tag, str) and "id" in element.attrib:
                if element.get("id") in ids:
                    problems.append(f"{tree.getpath(element)}: id {element.get('id')} twice")
                ids[element.get("id")] = element
        ref_kinds = {"core": "core_unit", "core_unit": "core_unit"}
        for element in root.iter():
            if not isinstance(element.tag, str) or "ref" not in element.attrib:
                continue
            target = ids.get(element.get("ref"))
            if target is None:
                problems.append(f"{tree.getpath(element)}: ref {element.get('ref')} does not resolve")
                continue
            tag, target_tag = _local(element), _local(target)
            expected = ref_kinds.get(tag)
            if expected is None:
                if (
                    tag.endswith("_task")
                    or tag in ("precedence_sink", "precedence_source")
                    or tag.endswith(("_client", "_server", "_sink", "_source"))
                ):
                    expected = "_task"
                elif tag.endswith("_object"):
                    expected = "buffer" if tag.startswith(("buffer", "black_board")) else "_message"
                elif tag == "resource_dependency_resource":
                    expected = "_resource"
            if expected is None or not target_tag.endswith(expected):
                problems.append(f"{tree.getpath(element)}: ref {element.get('ref')} is a <{target_tag}>")
        core_names = {
            name: {
                (ids[r.get("ref")].findtext("name") or "").strip() for r in p.iter() if r.get("ref") in ids
            }
            for name, p in processors.items()
        }
        for space in spaces.values():
            if space.findtext("cpu_name") not in processors:
                problems.append(f"{tree.getpath(space)}: cpu_name does not resolve")
        for section in ("tasks", "resources", "buffers"):
            for item in sections.get(section, []):
                if not isinstance(item.tag, str):
                    continue
                cpu, space = item.findtext("cpu_name"), item.findtext("address_space_name")
                if cpu not in processors:
                    problems.append(f"{tree.getpath(item)}: cpu_name {cpu!r} does not resolve")
                if space not in spaces:
                    problems.append(f"{tree.getpath(item)}: address_space_name {space!r} does not resolve")
                elif spaces[space].findtext("cpu_name") != cpu:
                    problems.append(f"{tree.getpath(item)}: address space on another processor")
                core = item.findtext("core_name")
                if core and core not in core_names.get(cpu, set()):
                    problems.append(f"{tree.getpath(item)}: core_name {core!r} is not a core of {cpu!r}")
                for name_element in item.iter("task_name"):
                    if name_element.text not in tasks:
                        problems.append(
                            f"{tree.getpath(name_element)}: task {name_element.text!r} does not resolve"
                        )
    else:
        tables = {"task": tasks, "buffer": named("buffers"), "message": named("messages")}
        for user in root.iter("resource_user", "buffer_user"):
            if (user.text or "").split()[0] not in tasks:
                problems.append(f"{tree.getpath(user)}: task does not resolve")
        for dependency in sections.get("dependencies", []):
            if not isinstance(dependency.tag, str):
                continue
            words = (dependency.text or "").split()
            for word, kind in zip(
                words, (dependency.get("from_type"), dependency.get("to_type")), strict=True
            ):
                if word not in tables[kind]:
                    problems.append(f"{tree.getpath(dependency)}: {kind} {word!r} does not resolve")
    return problems


def _check(data: bytes, fmt: int) -> None:
    problems = conformance_problems(data, fmt)
    assert not problems, "\n".join(problems[:20])
    assert not structure_problems(data, fmt)


# --------------------------------------------------------------------------- corpus round trips


def _format_of(data: bytes) -> int:
    return cheddar_format_of(etree.fromstring(_strip_dtd(data)))


@pytest.mark.corpus
@pytest.mark.parametrize("name", FILES)
def test_corpus_round_trip_is_equal_and_conformant(corpus: Path, name: str) -> None:
    data = (corpus / "cheddar" / name).read_bytes()
    fmt = _format_of(data)
    first = loads_cheddar(data, name)
    exported = dumps_cheddar(first, cheddar_format=fmt)
    _check(exported, fmt)
    second = loads_cheddar(exported, name)
    assert model.model_differences(first, second) == []
    assert dumps_cheddar(second, cheddar_format=fmt) == exported  # a fixed point, byte for byte


def _leaves(root: etree._Element) -> Counter:
    """Every element as (path of tags, attributes, normalised text): order-free file content."""
    out: Counter = Counter()

    def visit(element: etree._Element, path: str) -> None:
        tag = _local(element)
        here = f"{path}/{tag}"
        children = [c for c in element if isinstance(c.tag, str)]
        text = "" if children else " ".join((element.text or "").split())
        if re.fullmatch(r"[0-9]+\.[0-9]+", text) and float(text).is_integer():
            text = str(int(float(text)))
        attributes = tuple(sorted(element.attrib.items())) if tag in ("task", "scheduler") else ()
        out[(here, attributes, text.upper())] += 1
        for child in children:
            visit(child, here)

    visit(root, "")
    return out


@pytest.mark.corpus
@pytest.mark.parametrize("name", FILES)
def test_export_of_an_import_has_the_content_of_the_original(corpus: Path, name: str) -> None:
    data = (corpus / "cheddar" / name).read_bytes()
    fmt = _format_of(data)
    exported = dumps_cheddar(loads_cheddar(data, name), cheddar_format=fmt)
    original = _leaves(etree.fromstring(_strip_dtd(data)))
    written = _leaves(etree.fromstring(exported))
    assert original - written == Counter() and written - original == Counter()


@pytest.mark.corpus
def test_model_survives_xmi_persistence_before_export(corpus: Path) -> None:
    for name in (
        "gpu_analysis_model_1.xmlv3",
        "edf_pip_resource_v2.xml",
        "cheddar_adl_test4_multicore.xmlv3",
    ):
        data = (corpus / "cheddar" / name).read_bytes()
        fmt = _format_of(data)
        imported = loads_cheddar(data, name)
        direct = dumps_cheddar(imported, cheddar_format=fmt)
        reloaded = model.loads_xmi(model.dumps_xmi(imported), name + ".xmi")
        assert dumps_cheddar(reloaded, cheddar_format=fmt) == direct


@pytest.mark.corpus
def test_cheddar2_files_in_cheddar3(corpus: Path) -> None:
    data = (corpus / "cheddar" / "ocarina_issue288_test_cheddar_v2.xml").read_bytes()
    exported = dumps_cheddar(loads_cheddar(data, "o.xml"), cheddar_format=3)
    _check(exported, 3)
    tasks = {t.findtext("name"): t for t in etree.fromstring(exported).find("tasks")}
    assert tasks["p1_t1"].findtext("period") == "20000" and tasks["p1_t2"].findtext("capacity") == "15000"
    assert etree.fromstring(exported).find("core_units/core_unit/name").text == "core_unit_cpu"
    # a Cheddar 2 task on an undeclared processor cannot be written for Cheddar 3's reader
    edf = loads_cheddar((corpus / "cheddar" / "edf_pip_resource_v2.xml").read_bytes(), "edf.xml")
    with pytest.raises(ExportError, match="cpu_name 'cpu' is not a processor"):
        dumps_cheddar(edf, cheddar_format=3)


@pytest.mark.corpus
def test_vocabulary_covers_the_corpus(corpus: Path) -> None:
    """The vocabulary file holds every element, attribute and enumeration value of the corpus."""
    enumerations = set(VOCABULARY["enumeration_elements"])
    for path in sorted((corpus / "cheddar").glob("*.xml*")):
        data = path.read_bytes()
        key = f"v{_format_of(data)}"
        known = VOCABULARY["corpus"][key]
        for element in etree.fromstring(_strip_dtd(data)).iter():
            if not isinstance(element.tag, str):
                continue
            tag = _local(element)
            assert tag in known["elements"], (path.name, tag)
            assert {a.lower() for a in element.attrib} <= set(known["attributes"]), (path.name, tag)
            if tag in enumerations and len(element) == 0 and (element.text or "").strip():
                assert " ".join(element.text.split()).upper() in known["values"][tag], (path.name, tag)


def test_conformance_oracle_catches_problems() -> None:
    good = (
        b'<cheddar><core_units><core_unit id="c"><name>k</name></core_unit></core_units>'
        b'<processors><mono_core_processor id="p"><name>cpu</name><core ref="c"/></mono_core_processor>'
        b'</processors><address_spaces><address_space id="s"><name>as</name><cpu_name>cpu</cpu_name>'
        b'</address_space></address_spaces><tasks><periodic_task id="t"><name>t</name>'
        b"<task_type>PERIODIC_TYPE</task_type><cpu_name>cpu</cpu_name>"
        b"<address_space_name>as</address_space_name></periodic_task></tasks></cheddar>"
    )
    assert conformance_problems(good, 3) == []
    assert conformance_problems(good.replace(b"PERIODIC_TYPE<", b"WEEKLY_TYPE<"), 3)
    assert conformance_problems(good.replace(b'ref="c"', b'ref="t"'), 3)
    assert conformance_problems(good.replace(b'id="s"', b'id="p"'), 3)
    assert conformance_problems(
        good.replace(b"<cpu_name>cpu</cpu_name><address", b"<cpu_name>gpu</cpu_name><address"), 3
    )
    assert conformance_problems(good.replace(b"<name>t</name>", b"<name>t</name><colour>red</colour>"), 3)


# --------------------------------------------------------------------------- instantiator-like instances


def _prop(obj, name: str, value) -> None:
    association = model.new("PropertyAssociation", property=name)
    association.ownedValues.append(model.new("ModalPropertyValue", value=value))
    obj.ownedPropertyAssociations.append(association)


def _int(value: int, unit: str | None = None):
    return model.new("IntegerValue", value=value, unit=unit)


def _refs(*targets):
    return model.new(
        "ListValue",
        ownedItems=[model.new("InstanceReferenceValue", referencedInstanceObject=t) for t in targets],
    )


def _component(parent, name: str, category: str, **values):
    child = model.new("ComponentInstance", name=name, category=category, subcomponent=name, **values)
    parent.componentInstances.append(child)
    return child


def _feature(component, name: str, category: str, direction: str):
    feature = model.new("FeatureInstance", name=name, feature=name, category=category, direction=direction)
    component.featureInstances.append(feature)
    return feature


def _thread(
    process, name: str, period, cet: tuple, *, dispatch: str = "Periodic", priority: int | None = None
):
    thread = _component(process, name, "thread", classifier=f"nodes::{name}.impl")
    _prop(thread, "Thread_Properties::Dispatch_Protocol", model.new("NamedValue", name=dispatch))
    if period is not None:
        _prop(thread, "Timing_Properties::Period", _int(*period))
    low, high, unit = cet
    _prop(
        thread,
        "Timing_Properties::Compute_Execution_Time",
        model.new("RangeValue", minimum=_int(low, unit), maximum=_int(high, unit)),
    )
    if priority is not None:
        _prop(thread, "Thread_Properties::Priority", _int(priority))
    return thread


def _deployment(*, multicore: bool = True):
    """An instance as the AADL instantiator makes it: hardware and software subsystems, processes
    bound to processors (threads inherit the binding), periods in ms and us, a callback queue
    with Priority_Inheritance shared by a component's threads, port connections."""
    workspace = model.new("AadlModel", name="robot")
    root = model.new(
        "SystemInstance", name="robot_impl_Instance", category="system", classifier="robot::robot.impl"
    )
    workspace.instances.append(root)
    hardware = _component(root, "hw", "system")
    board = _component(hardware, "soc", "processor", classifier="hw::exynos5422.impl")
    _prop(
        board,
        "Deployment_Properties::Scheduling_Protocol",
        model.new("ListValue", ownedItems=[model.new("NamedValue", name="RMS")]),
    )
    cores = [_component(board, "a15", "processor", index=[i]) for i in (1, 2)] if multicore else []
    pc = _component(hardware, "pc", "processor")
    _prop(
        pc,
        "Deployment_Properties::Scheduling_Protocol",
        model.new("ListValue", ownedItems=[model.new("NamedValue", name="EDF")]),
    )
    _prop(pc, "Deployment_Properties::Preemptive_Scheduler", model.new("BooleanValue", value=False))
    ethernet = _component(hardware, "eth", "bus")
    software = _component(root, "sw", "system")
    camera = _component(software, "cam", "process", classifier="nodes::usb_cam_nd.impl")
    _prop(camera, "Deployment_Properties::Actual_Processor_Binding", _refs(board))
    capture = _thread(camera, "capture", (33, "ms"), (2, 5, "ms"), priority=20)
    publish = _thread(camera, "publish", (100000, "us"), (500, 1500, "us"), priority=10)
    queue = _component(camera, "callback_queue", "data")
    _prop(
        queue,
        "Thread_Properties::Concurrency_Control_Protocol",
        model.new("NamedValue", name="Priority_Inheritance"),
    )
    for thread, core in zip((capture, publish), cores or (board, board), strict=True):
        _prop(thread, "Deployment_Properties::Actual_Processor_Binding", _refs(core))
    tracker = _component(software, "tracker", "process")
    _prop(tracker, "Deployment_Properties::Actual_Processor_Binding", _refs(pc))
    track = _thread(tracker, "track", (50, "ms"), (1, 4, "ms"), dispatch="Sporadic")
    _prop(track, "Deployment_Properties::Actual_Processor_Binding", _refs(pc))
    log = _thread(tracker, "log", None, (1, 1, "ms"), dispatch="Aperiodic", priority=1)
    _prop(log, "Deployment_Properties::Actual_Processor_Binding", _refs(pc))
    image_out = _feature(capture, "image_out", "event data port", "out")
    image_in = _feature(publish, "image_in", "event data port", "in")
    _prop(image_in, "Communication_Properties::Queue_Size", _int(4))
    objects_out = _feature(publish, "objects_out", "event data port", "out")
    objects_in = _feature(track, "objects_in", "event data port", "in")
    _prop(objects_out, "Memory_Properties::Data_Size", _int(24, "Bytes"))
    tick_out = _feature(track, "done", "event port", "out")
    tick_in = _feature(log, "trigger", "event port", "in")
    local = model.new(
        "ConnectionInstance",
        name="capture.image_out -> publish.image_in",
        kind="portConnection",
        complete=True,
        source=image_out,
        destination=image_in,
    )
    camera.connectionInstances.append(local)
    remote = model.new(
        "ConnectionInstance",
        name="cam.publish.objects_out -> tracker.track.objects_in",
        kind="portConnection",
        complete=True,
        source=objects_out,
        destination=objects_in,
    )
    _prop(remote, "Deployment_Properties::Actual_Connection_Binding", _refs(ethernet))
    software.connectionInstances.append(remote)
    event = model.new(
        "ConnectionInstance",
        name="track.done -> log.trigger",
        kind="portConnection",
        complete=True,
        source=tick_out,
        destination=tick_in,
    )
    tracker.connectionInstances.append(event)
    return workspace, {"capture": capture, "publish": publish, "track": track, "log": log, "queue": queue}


def _us(value: int | None) -> Quantity | None:
    return Quantity(value, "us") if value is not None else None


def _entities(document: etree._Element, section: str) -> dict[str, etree._Element]:
    return {e.findtext("name"): e for e in document.find(section)}


def test_instantiator_model_exports_to_cheddar3() -> None:
    workspace, _ = _deployment()
    diagnostics: list[Diagnostic] = []
    data = dumps_cheddar(workspace, diagnostics=diagnostics)
    _check(data, 3)
    assert data == dumps_cheddar(workspace)  # deterministic
    document = etree.fromstring(data)
    (soc,) = document.findall("processors/multi_cores_processor")
    assert soc.findtext("name") == "hw.soc" and len(soc.findall("cores/core_unit")) == 2
    assert soc.findtext("migration_type") == "NO_MIGRATION_TYPE"  # threads have a core affinity
    tasks = _entities(document, "tasks")
    assert {n: t.tag for n, t in tasks.items()} == {
        "sw.cam.capture": "periodic_task",
        "sw.cam.publish": "periodic_task",
        "sw.tracker.track": "sporadic_task",
        "sw.tracker.log": "aperiodic_task",
    }
    capture = tasks["sw.cam.capture"]
    assert [capture.findtext(t) for t in ("cpu_name", "core_name", "address_space_name")] == [
        "hw.soc",
        "hw.soc.a15[1]",
        "sw.cam",
    ]
    # ms and us periods in one model, written in us; capacity is the upper bound
    assert [capture.findtext(t) for t in ("period", "capacity", "deadline", "priority")] == [
        "33000",
        "5000",
        "33000",
        "20",
    ]
    publish = tasks["sw.cam.publish"]
    assert [publish.findtext(t) for t in ("period", "capacity")] == ["100000", "1500"]
    assert tasks["sw.tracker.log"].find("period") is None
    cores = _entities(document, "core_units")
    assert (
        cores["hw.soc.a15[1]"].findtext("scheduling/scheduling_parameters/scheduler_type")
        == "RATE_MONOTONIC_PROTOCOL"
    )
    pc_core = cores["core_unit_hw.pc"].find("scheduling/scheduling_parameters")
    assert pc_core.findtext("scheduler_type") == "EARLIEST_DEADLINE_FIRST_PROTOCOL"
    assert pc_core.findtext("preemptive_type") == "NOT_PREEMPTIVE"
    # the callback queue serialises the component's threads: whole-capacity critical sections
    (resource,) = document.find("resources")
    assert resource.tag == "pip_resource" and resource.findtext("protocol") == "PRIORITY_INHERITANCE_PROTOCOL"
    sections = [
        (n.text, s.findtext("task_begin"), s.findtext("task_end"))
        for n, s in zip(
            resource.findall("critical_sections/task_name"),
            resource.findall("critical_sections/critical_section"),
            strict=True,
        )
    ]
    assert sections == [("sw.cam.capture", "1", "5000"), ("sw.cam.publish", "1", "1500")]
    # local port connection -> buffer at the receiving port; bus-bound one -> message on a network
    (buffer,) = document.find("buffers")
    assert buffer.findtext("name") == "sw.cam.publish.image_in" and buffer.findtext("buffer_size") == "4"
    assert [r.findtext("the_role") for r in buffer.findall("roles/buffer_role")] == [
        "QUEUING_PRODUCER",
        "QUEUING_CONSUMER",
    ]
    (message,) = document.find("messages")
    assert message.tag == "periodic_message" and message.findtext("size") == "24"
    assert message.findtext("period") == "100000"
    assert [n.findtext("name") for n in document.find("networks")] == ["hw.eth"]
    kinds = Counter(d.findtext("type_of_dependency") for d in document.find("dependencies"))
    assert kinds == Counter(
        {
            "QUEUEING_BUFFER_DEPENDENCY": 2,
            "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY": 2,
            "PRECEDENCE_DEPENDENCY": 1,
        }
    )


def test_export_then_import_preserves_timing_priorities_and_bindings() -> None:
    workspace, threads = _deployment()
    reimported = loads_cheddar(dumps_cheddar(workspace), "robot.xmlv3").instances[0]
    by_name = {}
    stack = [reimported]
    while stack:
        current = stack.pop()
        stack.extend(current.componentInstances)
        if current.category.name == "thread":
            by_name[own_property(current, CP + "Cheddar_Name")] = current
    expected = {
        "sw.cam.capture": (33000, 5000, 33000, 20, ("hw.soc", "hw.soc.a15[1]")),
        "sw.cam.publish": (100000, 1500, 100000, 10, ("hw.soc", "hw.soc.a15[2]")),
        "sw.tracker.track": (50000, 4000, 50000, 1, ("hw.pc", None)),
        "sw.tracker.log": (None, 1000, None, 1, ("hw.pc", None)),
    }
    for name, (period, capacity, deadline, priority, (cpu, core)) in expected.items():
        thread = by_name[name]
        assert own_property(thread, "Timing_Properties::Period") == _us(period)
        assert own_property(thread, "Timing_Properties::Compute_Execution_Time") == Range(
            _us(capacity), _us(capacity)
        )
        assert own_property(thread, "Timing_Properties::Deadline") == _us(deadline)
        assert own_property(thread, "Thread_Properties::Priority") == priority
        (target,) = own_property(thread, "Deployment_Properties::Actual_Processor_Binding")
        if core is None:
            assert own_property(target, CP + "Cheddar_Name") == cpu
        else:
            assert own_property(target, CP + "Cheddar_Name") == core
            assert own_property(target.eContainer(), CP + "Cheddar_Name") == cpu


def test_milliseconds_and_times_that_are_not_whole() -> None:
    workspace, _ = _deployment()
    with pytest.raises(ExportError) as caught:
        dumps_cheddar(workspace, time_unit="ms")
    message = caught.value.message
    # every offending value is listed with its instance path, nothing is rounded
    assert (
        "robot_impl_Instance.sw.cam.publish: Timing_Properties::Compute_Execution_Time = 1500 us" in message
    )
    assert "(1.5 ms)" in message
    assert caught.value.location.path == "robot_impl_Instance"
    workspace, threads = _deployment()
    for association in threads["publish"].ownedPropertyAssociations:
        if association.property.endswith("Compute_Execution_Time"):
            association.ownedValues[0].value = model.new(
                "RangeValue", minimum=_int(1, "ms"), maximum=_int(2, "ms")
            )
    data = dumps_cheddar(workspace, time_unit="ms")
    _check(data, 3)
    tasks = _entities(etree.fromstring(data), "tasks")
    assert [tasks["sw.cam.publish"].findtext(t) for t in ("period", "capacity")] == ["100", "2"]
    assert tasks["sw.cam.capture"].findtext("period") == "33"


def test_cheddar2_export_of_an_instance() -> None:
    workspace, _ = _deployment(multicore=False)
    data = dumps_cheddar(workspace, cheddar_format=2)
    _check(data, 2)
    document = etree.fromstring(data)
    assert [t.get("task_type") for t in document.find("tasks")] == [
        "PERIODIC_TYPE",
        "PERIODIC_TYPE",
        "SPORADIC_TYPE",
        "APERIODIC_TYPE",
    ]
    users = [u.text for u in document.iter("resource_user")]
    assert users == ["sw.cam.capture 1 5000", "sw.cam.publish 1 1500"]
    reimported = loads_cheddar(data, "robot.xml")
    assert len(reimported.instances[0].componentInstances) >= 4
    workspace, _ = _deployment(multicore=True)
    with pytest.raises(ExportError, match="Cheddar 2 has no multi-core processors"):
        dumps_cheddar(workspace, cheddar_format=2)


def test_unbound_threads_are_errors_and_threads_without_capacity_are_left_out() -> None:
    workspace, threads = _deployment()
    for association in list(threads["log"].ownedPropertyAssociations):
        if association.property.endswith("Actual_Processor_Binding"):
            threads["log"].ownedPropertyAssociations.remove(association)
    threads["log"].eContainer().ownedPropertyAssociations.clear()  # its process is unbound too
    for association in list(threads["track"].ownedPropertyAssociations):
        if association.property.endswith("Compute_Execution_Time"):
            threads["track"].ownedPropertyAssociations.remove(association)
    with pytest.raises(ExportError) as caught:
        dumps_cheddar(workspace)
    message = caught.value.message
    assert "robot_impl_Instance.sw.tracker.log: the thread is bound to no processor" in message
    assert "tracker.track" not in message
    # bound again, the export succeeds; the thread with no execution time is left out, with a warning
    workspace, threads = _deployment()
    for association in list(threads["track"].ownedPropertyAssociations):
        if association.property.endswith("Compute_Execution_Time"):
            threads["track"].ownedPropertyAssociations.remove(association)
    notes: list = []
    document = dumps_cheddar(workspace, diagnostics=notes)
    assert b"tracker.track" not in document and b"tracker.log" in document
    (note,) = [n for n in notes if "Compute_Execution_Time" in n.message]
    assert note.severity == "warning" and note.location.path == "robot_impl_Instance.sw.tracker.track"


def test_write_is_atomic_and_root_is_chosen(tmp_path: Path) -> None:
    workspace, _ = _deployment()
    target = tmp_path / "out" / "robot.xmlv3"
    with pytest.raises(ExportError):
        write_cheddar(workspace, target, time_unit="ms")
    assert not target.exists() and (not target.parent.exists() or not list(target.parent.iterdir()))
    assert write_cheddar(workspace, target) == target
    _check(target.read_bytes(), 3)
    other = model.new("SystemInstance", name="other_Instance", category="system")
    workspace.instances.append(other)
    with pytest.raises(ExportError, match="several system instances"):
        dumps_cheddar(workspace)
    assert dumps_cheddar(workspace, root="robot_impl_Instance") == target.read_bytes()
    with pytest.raises(ExportError, match="cheddar_format"):
        dumps_cheddar(workspace, root="robot_impl_Instance", cheddar_format=4)


# --------------------------------------------------------------------------- own Cheddar fixtures

_SCHED = (
    "<scheduling><scheduling_parameters><scheduler_type>POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL"
    "</scheduler_type><quantum>0</quantum><preemptive_type>PREEMPTIVE</preemptive_type>"
    "</scheduling_parameters></scheduling>"
)


def _fixture(dependencies: str = "", extra_cores: str = "", tasks: str | None = None) -> bytes:
    cores = "".join(
        f'<core_unit id="k{i}"><object_type>CORE_OBJECT_TYPE</object_type><name>k{i}</name>'
        f"{_SCHED}</core_unit>"
        for i in (1, 2, 3)
    )
    if tasks is None:
        tasks = (
            '<periodic_task id="ta"><name>a</name><task_type>PERIODIC_TYPE</task_type>'
            "<cpu_name>multi</cpu_name><address_space_name>as</address_space_name><core_name>k2</core_name>"
            "<capacity>2</capacity><period>10</period></periodic_task>"
            '<periodic_task id="tb"><name>b</name><task_type>PERIODIC_TYPE</task_type>'
            "<cpu_name>multi</cpu_name><address_space_name>as</address_space_name><capacity>3</capacity>"
            "<period>20</period></periodic_task>"
        )
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n<cheddar>'
        f"<core_units>{cores}{extra_cores}</core_units>"
        '<processors><multi_cores_processor id="pm"><name>multi</name>'
        "<processor_type>IDENTICAL_MULTICORES_TYPE</processor_type>"
        "<migration_type>NO_MIGRATION_TYPE</migration_type><cores>"
        '<core_unit ref="k1"/><core_unit ref="k2"/></cores></multi_cores_processor>'
        '<mono_core_processor id="p1"><name>one</name><core ref="k3"/></mono_core_processor>'
        '<mono_core_processor id="p2"><name>two</name><core ref="k3"/></mono_core_processor></processors>'
        '<address_spaces><address_space id="s"><name>as</name><cpu_name>multi</cpu_name></address_space>'
        "</address_spaces>"
        f"<tasks>{tasks}</tasks>"
        '<resources><np_resource id="r"><name>r</name><protocol>NO_PROTOCOL</protocol><critical_sections>'
        "<task_name>b</task_name><critical_section><task_synchronization>WAIT</task_synchronization>"
        "<task_begin>1</task_begin><task_end>1</task_end></critical_section></critical_sections>"
        "<cpu_name>multi</cpu_name><address_space_name>as</address_space_name></np_resource></resources>"
        '<buffers><buffer id="q"><name>q</name><cpu_name>multi</cpu_name><address_space_name>as'
        "</address_space_name><roles><task_name>a</task_name><buffer_role><the_role>SAMPLING_WRITER</the_role>"
        "<amplitude_function>f</amplitude_function></buffer_role></roles></buffer></buffers>"
        '<messages><periodic_message id="m"><name>m</name><period>5</period><size>8</size></periodic_message>'
        "</messages>"
        f"<dependencies>{dependencies}</dependencies></cheddar>\n"
    ).encode()


def _dependency(kind: str, *parts: str) -> str:
    return f"<dependency><type_of_dependency>{kind}</type_of_dependency>{''.join(parts)}</dependency>"


ALL_DEPENDENCIES = "".join(
    (
        _dependency("PRECEDENCE_DEPENDENCY", '<precedence_sink ref="ta"/>', '<precedence_source ref="tb"/>'),
        _dependency(
            "QUEUEING_BUFFER_DEPENDENCY",
            '<buffer_dependent_task ref="ta"/>',
            "<buffer_orientation>FROM_TASK_TO_OBJECT</buffer_orientation>",
            '<buffer_dependency_object ref="q"/>',
        ),
        _dependency(
            "TDMA_COMMUNICATION_DEPENDENCY",
            '<tdma_communication_dependent_task ref="ta"/>',
            "<tdma_communication_orientation>FROM_OBJECT_TO_TASK</tdma_communication_orientation>",
            '<tdma_communication_dependency_object ref="m"/>',
        ),
        _dependency(
            "ASYNCHRONOUS_COMMUNICATION_DEPENDENCY",
            '<asynchronous_communication_dependent_task ref="tb"/>',
            "<asynchronous_communication_orientation>FROM_TASK_TO_OBJECT</asynchronous_communication_orientation>",
            '<asynchronous_communication_dependency_object ref="m"/>',
            "<asynchronous_communication_protocol_property>ALL_MESSAGES</asynchronous_communication_protocol_property>",
        ),
        _dependency(
            "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY",
            '<time_triggered_communication_sink ref="ta"/>',
            '<time_triggered_communication_source ref="tb"/>',
            "<time_triggered_timing_property>DELAYED_TIMING</time_triggered_timing_property>",
        ),
        _dependency(
            "RESOURCE_DEPENDENCY",
            '<resource_dependency_resource ref="r"/>',
            '<resource_dependency_task ref="tb"/>',
        ),
        _dependency(
            "REMOTE_PROCEDURE_CALL_DEPENDENCY",
            '<remote_procedure_call_client ref="ta"/>',
            '<remote_procedure_call_server ref="tb"/>',
        ),
        _dependency(
            "BLACK_BOARD_BUFFER_DEPENDENCY",
            '<black_board_dependent_task ref="tb"/>',
            "<black_board_orientation>FROM_OBJECT_TO_TASK</black_board_orientation>",
            '<black_board_dependency_object ref="q"/>',
        ),
    )
)


def test_every_dependency_kind_cores_and_records_round_trip() -> None:
    spare = f'<core_unit id="k9"><object_type>CORE_OBJECT_TYPE</object_type><name>spare</name>{_SCHED}'
    spare += "</core_unit>"
    diagnostics: list[Diagnostic] = []
    first = loads_cheddar(_fixture(ALL_DEPENDENCIES, spare), "all.xmlv3", diagnostics=diagnostics)
    assert any("'k9' belongs to no processor" in d.message for d in diagnostics)
    exported = dumps_cheddar(first)
    _check(exported, 3)
    second = loads_cheddar(exported, "all.xmlv3")
    assert model.model_differences(first, second) == []
    document = etree.fromstring(exported)
    # the core shared by two mono-core processors is written once, the unused one is kept
    assert [c.get("id") for c in document.find("core_units")] == ["k1", "k2", "k3", "k9"]
    assert [d.findtext("type_of_dependency") for d in document.find("dependencies")] == [
        re.search(r"<type_of_dependency>(\w+)<", part).group(1)
        for part in ALL_DEPENDENCIES.split("</dependency>")[:-1]
    ]
    root = first.instances[0]
    (multi,) = [p for p in root.componentInstances if p.name == "multi"]
    (task_a,) = [t for p in root.componentInstances for t in p.componentInstances if t.name == "a"]
    assert own_property(task_a, "Deployment_Properties::Actual_Processor_Binding") == [
        multi.componentInstances[1]
    ]
    assert _entities(document, "tasks")["a"].findtext("core_name") == "k2"
    assert _entities(document, "messages")["m"].findtext("period") == "5"
    assert (
        _entities(document, "resources")["r"].findtext(
            "critical_sections/critical_section/task_synchronization"
        )
        == "WAIT"
    )


def test_an_edited_import_exports_the_edit() -> None:
    first = loads_cheddar(_fixture(), "edit.xmlv3")
    root = first.instances[0]
    (space,) = [p for p in root.componentInstances if p.category.name == "process"]
    task_b = [t for t in space.componentInstances if t.name == "b"][0]
    for association in task_b.ownedPropertyAssociations:
        if association.property == "Timing_Properties::Period":
            association.ownedValues[0].value = _int(40, "ms")
    added = _component(space, "added", "thread")
    _prop(added, "Thread_Properties::Dispatch_Protocol", model.new("NamedValue", name="Periodic"))
    _prop(added, "Timing_Properties::Period", _int(7, "us"))
    _prop(
        added,
        "Timing_Properties::Compute_Execution_Time",
        model.new("RangeValue", minimum=_int(1, "us"), maximum=_int(1, "us")),
    )
    _prop(added, "Deployment_Properties::Actual_Processor_Binding", _refs(root.componentInstances[0]))
    exported = dumps_cheddar(first)
    _check(exported, 3)
    tasks = _entities(etree.fromstring(exported), "tasks")
    assert tasks["b"].findtext("period") == "40000"
    # a new thread gets a dotted name, a fresh id and Cheddar's usual fields
    assert (
        tasks["as.added"].get("id") not in ("ta", "tb")
        and tasks["as.added"].findtext("policy") == "SCHED_FIFO"
    )
    assert tasks["as.added"].findtext("address_space_name") == "as"


@dataclass(frozen=True)
class Exports:
    """The file exports: the reader finds ``threads`` threads and ``tasks`` of them are written
    (those with a Compute_Execution_Time; each other one is left out with a warning)."""

    threads: int
    tasks: int
    why: str = ""


@dataclass(frozen=True)
class Refused:
    """The export is refused with an ExportError matching ``match``, for the reason ``why``;
    ``threads`` is how many threads the reader finds (each named in the refusal when it is
    the threads that cannot be written)."""

    match: str
    why: str
    threads: int = 0


_UNBOUND = "the thread is bound to no processor"
_NO_INSTANCE = "the model holds no system instance"

#: Every OSATE instance file of the corpus, by file name: what its export gives. A corpus file
#: without a row fails test_every_osate_instance_file_has_a_row.
OSATE_EXPORTS: dict[str, Exports | Refused] = {
    "test_event_data_port_periodic_domains_top_impl_Instance.aaxl2": Exports(2, 2),
    "CarSystem_MyCar_CruiseControlFunction_Instance.aaxl2": Exports(0, 0, "systems and devices only"),
    "CrossDomainExample_CrossDomain_basic_Instance.aaxl2": Exports(0, 0, "systems, devices, data, a bus"),
    "test2.aaxl2": Refused(_NO_INSTANCE, "a declarative package: no instance to export"),
    "testfgmodel_TestSystem_base_Instance.aaxl2": Exports(0, 0, "two processors, no software"),
    "ps411.aaxl2": Refused(_NO_INSTANCE, "a declarative property set: no instance to export"),
    "test_queuing_root_impl_Instance.aaxl2": Exports(2, 2, "bound through virtual processors"),
    "LargeExample_Dependable_System_Notional_Instance.aaxl2": Exports(0, 0, "systems only"),
    "latency-distributed_latencytest_nobus_Instance.aaxl2": Exports(2, 2),
    "latency-distributed_latencytest_normal_Instance.aaxl2": Exports(2, 2),
    "latency-distributed_latencytest_partitioned_distributed_Instance.aaxl2": Exports(4, 4),
    "latency-distributed_latencytest_unbound_Instance.aaxl2": Exports(2, 2),
    "MissionAircraft_Generic_missionAircraft_generic_Instance.aaxl2": Exports(
        0, 0, "systems, devices, a bus"
    ),
    "pullprotocols_stub_i_Instance.aaxl2": Refused(_UNBOUND, "no processor in the model", threads=2),
    "SimpleThreadLatency_s_i_Instance.aaxl2": Refused(_UNBOUND, "no processor in the model", threads=18),
    "UAV_UAV_Impl_Instance.aaxl2": Exports(7, 0, "no thread has a Compute_Execution_Time"),
    "IntegrationTestsModel_MySystem_Tier0_Instance.aaxl2": Exports(0, 0, "processes without threads"),
    "platform_ZCU102_Impl_Instance.aaxl2": Exports(3, 3),
    "down_path_three_level_test_s_i_Instance.aaxl2": Refused(
        _UNBOUND, "no processor in the model", threads=1
    ),
    "BiDirPeerToPeer_LtoR_same_toplevel_i_Instance.aaxl2": Refused(
        _UNBOUND, "no processor in the model", threads=1
    ),
    "P_S1_i_Instance.aaxl2": Exports(0, 0, "one system, feature groups only"),
    "PulseOx_Forwarding_System_PulseOx_Forwarding_System_imp_Instance.aaxl2": Refused(
        _UNBOUND, "no processor in the model", threads=3
    ),
    "SimpleControlSystem_SCS_tier1_Instance.aaxl2": Exports(0, 0, "processes without threads"),
    "Geofence.aaxl2": Refused(_NO_INSTANCE, "a declarative package: no instance to export"),
}


def _osate_file(corpus: Path, name: str) -> Path:
    (path,) = (corpus / "osate" / "aaxl2").rglob(name)
    return path


@pytest.mark.corpus
def test_every_osate_instance_file_has_a_row(corpus: Path) -> None:
    files = {p.name for p in (corpus / "osate" / "aaxl2").rglob("*.aaxl2")}
    assert files == set(OSATE_EXPORTS)


@pytest.mark.corpus
@pytest.mark.parametrize("name", sorted(OSATE_EXPORTS))
def test_osate_instance_files_export_their_tasks_or_are_refused(corpus: Path, name: str) -> None:
    """Real OSATE instance models (read by the .aaxl2 importer) export with every thread that
    has an execution time as a task, or are refused for the reason their row names."""
    expected = OSATE_EXPORTS[name]
    aadl_model = read_aaxl2(_osate_file(corpus, name)).model
    threads = [
        t
        for root in aadl_model.instances
        for t in model.component_instances(root)
        if t.category is not None and t.category.name == "thread"
    ]
    assert len(threads) == expected.threads
    if isinstance(expected, Refused):
        with pytest.raises(ExportError, match=expected.match) as refusal:
            dumps_cheddar(aadl_model)
        if expected.match == _UNBOUND:
            assert refusal.value.message.count(_UNBOUND) == len(threads)
            assert re.search(r"_Instance\.\S+: ", refusal.value.message), refusal.value.message
        return
    timed = [t for t in threads if own_property(t, "Timing_Properties::Compute_Execution_Time") is not None]
    assert len(timed) == expected.tasks
    diagnostics: list[Diagnostic] = []
    data = dumps_cheddar(aadl_model, diagnostics=diagnostics)
    _check(data, 3)
    (root,) = aadl_model.instances
    below = model.instance_path(root) + "."
    tasks = etree.fromstring(data).findall("tasks/*")
    assert sorted(t.findtext("name") for t in tasks) == sorted(
        model.instance_path(t).removeprefix(below) for t in timed
    )
    left_out = [d for d in diagnostics if d.message.startswith("not exported as a task")]
    assert len(left_out) == len(threads) - len(timed)
    again = loads_cheddar(data, name.replace(".aaxl2", ".xmlv3")).instances[0]
    assert sum(1 for t in model.component_instances(again) if t.category.name == "thread") == len(tasks)


def test_values_the_format_cannot_carry_are_export_errors() -> None:
    first = loads_cheddar(_fixture(), "odd.xmlv3")
    root = first.instances[0]
    task_b = [t for p in root.componentInstances for t in p.componentInstances if t.name == "b"][0]
    for association in task_b.ownedPropertyAssociations:
        if association.property == CP + "Cheddar_Name":
            association.ownedValues[0].value = model.new("StringValue", value="b\x01")
    with pytest.raises(ExportError, match="XML cannot carry"):
        dumps_cheddar(first)
    spaced = _fixture().replace(b"<name>b</name>", b"<name>task b</name>")
    second = loads_cheddar(spaced.replace(b"<task_name>b<", b"<task_name>task b<"), "spaces.xmlv3")
    _check(dumps_cheddar(second), 3)
    with pytest.raises(ExportError, match="splits values at spaces"):
        dumps_cheddar(second, cheddar_format=2)


def test_soc_systems_of_the_library_become_multicore_processors() -> None:
    """The library models an SoC as a system of processors (Exynos: clusters of cores)."""
    workspace = model.new("AadlModel", name="robot")
    root = model.new("SystemInstance", name="sys_impl_Instance", category="system")
    workspace.instances.append(root)
    board = _component(root, "OdroidXU4", "system")
    _component(board, "ram", "memory")
    _component(board, "usb", "bus")
    soc = _component(board, "Exynos_SOC", "system", classifier="Exynos_5422::Exynos_5422.impl")
    _prop(
        soc,
        "Deployment_Properties::Scheduling_Protocol",
        model.new("ListValue", ownedItems=[model.new("NamedValue", name="RMS")]),
    )
    big = _component(soc, "big_procs_cluster", "system")
    little = _component(soc, "little_procs_cluster", "system")
    cores = [
        _component(big, f"big_proc{i}", "processor", classifier="Exynos_5422::ARM_A15.impl") for i in (1, 2)
    ]
    cores += [
        _component(little, f"little_proc{i}", "processor", classifier="Exynos_5422::ARM_A7.impl")
        for i in (1, 2)
    ]
    pair = _component(root, "pair", "system")  # two separate computers joined by a bus: not an SoC
    left, right = _component(pair, "left", "processor"), _component(pair, "right", "processor")
    _component(pair, "can", "bus")
    node = _component(root, "node", "process")
    threads = []
    for i, target in enumerate((cores[0], cores[3], big, left)):
        thread = _thread(node, f"t{i}", (10, "ms"), (1, 1, "ms"))
        _prop(thread, "Deployment_Properties::Actual_Processor_Binding", _refs(target))
        threads.append(thread)
    _prop(
        right,
        "Deployment_Properties::Scheduling_Protocol",
        model.new("ListValue", ownedItems=[model.new("NamedValue", name="EDF")]),
    )
    diagnostics: list[Diagnostic] = []
    data = dumps_cheddar(workspace, diagnostics=diagnostics)
    _check(data, 3)
    document = etree.fromstring(data)
    processors = {p.findtext("name"): p for p in document.find("processors")}
    assert set(processors) == {"OdroidXU4.Exynos_SOC", "pair.left", "pair.right"}
    soc_element = processors["OdroidXU4.Exynos_SOC"]
    assert soc_element.tag == "multi_cores_processor" and len(soc_element.findall("cores/core_unit")) == 4
    assert soc_element.findtext("processor_type") == "UNRELATED_MULTICORES_TYPE"
    core_units = _entities(document, "core_units")
    assert (
        core_units["OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc2"].findtext(
            "scheduling/scheduling_parameters/scheduler_type"
        )
        == "RATE_MONOTONIC_PROTOCOL"
    )
    tasks = _entities(document, "tasks")
    assert [
        (tasks[f"node.t{i}"].findtext("cpu_name"), tasks[f"node.t{i}"].findtext("core_name"))
        for i in range(4)
    ] == [
        ("OdroidXU4.Exynos_SOC", "OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc1"),
        ("OdroidXU4.Exynos_SOC", "OdroidXU4.Exynos_SOC.little_procs_cluster.little_proc2"),
        ("OdroidXU4.Exynos_SOC", None),  # bound to a cluster: the SoC, no single core
        ("pair.left", None),
    ]
    # the node's threads run on two processors: one address space per processor
    assert sorted(s.findtext("name") for s in document.find("address_spaces")) == [
        "node",
        "node_on_pair.left",
    ]
    assert any("pair.left" in d.location.path and "Scheduling_Protocol" in d.message for d in diagnostics)

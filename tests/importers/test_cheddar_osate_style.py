"""Cheddar 3 files in the style of the OSATE plug-ins' Cheddar exporters: the scheduler fields
directly under ``<scheduling>`` (no ``<scheduling_parameters>``), numeric ids, enumeration
values in mixed case. Cheddar's reader takes these fields by their tag wherever they sit in a
core unit or an address space, so both styles must give the same model; the fixture is our own,
of that shape."""

from __future__ import annotations

import pytest
from lxml import etree

from rosaadl import model
from rosaadl.errors import Diagnostic, ImportFormatError
from rosaadl.exporters.cheddar import dumps_cheddar, structure_problems
from rosaadl.importers.cheddar import cheddar_format_of, loads_cheddar
from rosaadl.properties import EnumLiteral, own_property
from rosaadl.units import Quantity

CP = "Cheddar_Properties::"

_CORE_SCHEDULING = (
    "<scheduling>\n"
    "    <scheduler_type>Posix_1003_Highest_Priority_First_Protocol</scheduler_type>\n"
    "    <quantum>2</quantum>\n"
    "    <preemptive_type>Not_Preemptive</preemptive_type>\n"
    "    <capacity>0</capacity>\n"
    "    <period>0</period>\n"
    "    <priority>0</priority>\n"
    "    <start_time>0</start_time>\n"
    "   </scheduling>"
)
_SPACE_SCHEDULING = (
    "<scheduling>\n"
    "    <scheduler_type>No_Scheduling_Protocol</scheduler_type>\n"
    "    <quantum>0</quantum>\n"
    "    <preemptive_type>Preemptive</preemptive_type>\n"
    "   </scheduling>"
)


def _task(ident: int, name: str, *, capacity: int, period: int, start: int, priority: int) -> str:
    fields = {
        "object_type": "TASK_OBJECT_TYPE",
        "name": name,
        "task_type": "Periodic_Type",
        "cpu_name": "board",
        "address_space_name": "control",
        "capacity": capacity,
        "deadline": period,
        "start_time": start,
        "priority": priority,
        "policy": "Sched_Fifo",
        "period": period,
    }
    body = "".join(f"\n   <{tag}>{value}</{tag}>" for tag, value in fields.items())
    return f'  <periodic_task id="{ident}">{body}\n  </periodic_task>'


def _osate_style(core_scheduling: str = _CORE_SCHEDULING, space_scheduling: str = _SPACE_SCHEDULING) -> str:
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<cheddar>
 <core_units>
  <core_unit id="1">
   <object_type>CORE_OBJECT_TYPE</object_type>
   <name>board_core</name>
   {core_scheduling}
   <speed>1</speed>
  </core_unit>
 </core_units>
 <processors>
  <mono_core_processor id="2"><object_type>PROCESSOR_OBJECT_TYPE</object_type><name>board</name>
   <core ref="1"/></mono_core_processor>
 </processors>
 <address_spaces>
  <address_space id="3">
   <object_type>ADDRESS_SPACE_OBJECT_TYPE</object_type>
   <name>control</name>
   <cpu_name>board</cpu_name>
   {space_scheduling}
  </address_space>
 </address_spaces>
 <tasks>
{_task(4, "sensor", capacity=2, period=10, start=0, priority=5)}
{_task(5, "actuator", capacity=3, period=20, start=1, priority=3)}
 </tasks>
</cheddar>
"""


def _wrapped(text: str) -> str:
    """The same document in Cheddar's own style (the fields inside <scheduling_parameters>)."""
    text = text.replace("<scheduling>", "<scheduling><scheduling_parameters>")
    return text.replace("</scheduling>", "</scheduling_parameters></scheduling>")


def _error(text: str) -> ImportFormatError:
    with pytest.raises(ImportFormatError) as caught:
        loads_cheddar(text.encode(), "osate.xmlv3")
    assert caught.value.location.file == "osate.xmlv3"
    return caught.value


def test_osate_exporter_style_reads_like_cheddars_own() -> None:
    diagnostics: list[Diagnostic] = []
    root = loads_cheddar(_osate_style().encode(), "osate.xmlv3", diagnostics=diagnostics).instances[0]
    assert diagnostics == []
    (board,) = [c for c in root.componentInstances if c.category.name == "processor"]
    assert own_property(board, "Deployment_Properties::Scheduling_Protocol") == [
        EnumLiteral("POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL")
    ]
    assert own_property(board, "Deployment_Properties::Preemptive_Scheduler") is False
    assert own_property(board, CP + "Scheduler_Quantum") == Quantity(2, "us")
    assert own_property(board, CP + "Core_Id") == "1"
    (space,) = [c for c in root.componentInstances if c.category.name == "process"]
    assert own_property(space, CP + "Scheduler") == EnumLiteral("NO_SCHEDULING_PROTOCOL")
    assert own_property(space, CP + "Preemptive") is True
    sensor, actuator = space.componentInstances
    assert own_property(sensor, CP + "Cheddar_Id") == "4"
    assert own_property(sensor, "Thread_Properties::Dispatch_Protocol") == EnumLiteral("Periodic")
    assert own_property(sensor, "Thread_Properties::POSIX_Scheduling_Policy") == EnumLiteral("SCHED_FIFO")
    assert own_property(actuator, "Timing_Properties::Dispatch_Offset") == Quantity(1, "us")
    # the same facts as the file in Cheddar's own style
    wrapped = loads_cheddar(_wrapped(_osate_style()).encode(), "osate.xmlv3")
    assert model.model_differences(loads_cheddar(_osate_style().encode(), "osate.xmlv3"), wrapped) == []


def test_osate_exporter_style_round_trips_through_cheddars_own_style() -> None:
    first = loads_cheddar(_osate_style().encode(), "osate.xmlv3")
    exported = dumps_cheddar(first)
    document = etree.fromstring(exported)
    assert cheddar_format_of(document) == 3 and structure_problems(exported, 3) == []
    # written as Cheddar writes it, ids kept, enumerations in Cheddar's spelling
    assert document.findtext("core_units/core_unit/scheduling/scheduling_parameters/scheduler_type") == (
        "POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL"
    )
    assert document.findtext("address_spaces/address_space/scheduling/scheduling_parameters/quantum") == "0"
    assert [t.get("id") for t in document.find("tasks")] == ["4", "5"]
    second = loads_cheddar(exported, "osate.xmlv3")
    assert model.model_differences(first, second) == []
    assert dumps_cheddar(second) == exported


def test_unknown_scheduling_fields_of_either_style_are_kept_and_written_back() -> None:
    text = _osate_style(_CORE_SCHEDULING.replace("<quantum>", "<budget>7</budget><quantum>"))
    diagnostics: list[Diagnostic] = []
    first = loads_cheddar(text.encode(), "osate.xmlv3", diagnostics=diagnostics)
    (warning,) = diagnostics
    assert "<scheduling_parameters> field <budget>" in warning.message
    assert warning.location.path == "/cheddar/core_units/core_unit/scheduling/budget"
    (board,) = [c for c in first.instances[0].componentInstances if c.category.name == "processor"]
    assert own_property(board, CP + "Unmodelled_Fields") == [
        {"Section": "scheduling_parameters", "Xml": "<budget>7</budget>"}
    ]
    second = loads_cheddar(dumps_cheddar(first), "osate.xmlv3")
    assert model.model_differences(first, second) == []
    assert model.model_differences(first, loads_cheddar(_wrapped(text).encode(), "osate.xmlv3")) == []


def test_bad_osate_style_scheduling_is_a_located_error() -> None:
    mixed = _CORE_SCHEDULING.replace("<scheduling>", "<scheduling><scheduling_parameters/>")
    error = _error(_osate_style(mixed))
    assert error.location.path == "/cheddar/core_units/core_unit/scheduling/scheduler_type"
    assert "beside <scheduling_parameters>" in error.message and error.location.line == 8
    twice = _CORE_SCHEDULING.replace("<quantum>2</quantum>", "<quantum>2</quantum><quantum>3</quantum>")
    error = _error(_osate_style(twice))
    assert error.location.path == "/cheddar/core_units/core_unit/scheduling/quantum[2]"
    assert "given twice" in error.message
    error = _error(_osate_style(_CORE_SCHEDULING.replace("<quantum>2<", "<quantum>-2<")))
    assert error.location.path == "/cheddar/core_units/core_unit/scheduling/quantum"
    error = _error(_osate_style(_CORE_SCHEDULING.replace("Not_Preemptive", "Sometimes")))
    assert error.location.path == "/cheddar/core_units/core_unit/scheduling/preemptive_type"
    nested = _SPACE_SCHEDULING.replace("<quantum>0</quantum>", "<quantum><x/></quantum>")
    error = _error(_osate_style(space_scheduling=nested))
    assert error.location.path == "/cheddar/address_spaces/address_space/scheduling/quantum"
    text = _osate_style()
    cut = text.index("<preemptive_type>")
    error = _error(text[:cut])
    assert "malformed XML" in error.message and error.location.line is not None


def test_an_empty_scheduling_says_nothing_and_round_trips() -> None:
    first = loads_cheddar(_osate_style(space_scheduling="<scheduling/>").encode(), "osate.xmlv3")
    (space,) = [c for c in first.instances[0].componentInstances if c.category.name == "process"]
    assert own_property(space, CP + "Scheduler") is None
    second = loads_cheddar(dumps_cheddar(first), "osate.xmlv3")
    assert model.model_differences(first, second) == []

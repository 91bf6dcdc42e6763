"""OSATE .aaxl2 import: the 24 corpus files, decoded values per OSATE era, bad input, fast construction."""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest
from corpus_cases import OSATE_DECLARATIVE_DIRS, OSATE_INSTANCE_DIRS
from lxml import etree

from benchmarks.generators.aaxl2 import write_aaxl2_instance
from rosaadl import metamodels, model
from rosaadl.errors import ImportFormatError, RosaadlError
from rosaadl.importers import osate_eras
from rosaadl.importers.aaxl2 import ImportResult, loads_aaxl2, read_aaxl2
from rosaadl.properties import EnumLiteral, Range, own_property
from rosaadl.units import Quantity

# ----------------------------------------------------------------------------- corpus helpers

DECLARATIVE = OSATE_DECLARATIVE_DIRS
INSTANCE_DIRS = OSATE_INSTANCE_DIRS

# featureInstance elements (at any depth) per file: INDEX.md's table has no feature column,
# so these were counted in the files with an XPath, independently of the importer.
FEATURES = {
    "case-hamr-edp-domains": 4,
    "ex-carsystem": 20,
    "ex-crossdomain-security": 30,
    "ex-issue228-featuregroups": 14,
    "ex-issue440-arinc653": 4,
    "ex-large-modes": 20,
    "ex-latency-nobus": 6,
    "ex-latency-normal": 6,
    "ex-latency-partitioned-distributed": 10,
    "ex-latency-unbound": 6,
    "ex-mission-aircraft": 34,
    "ex-pullprotocols": 16,
    "ex-simple-thread-latency": 24,
    "fmw-uav-v3": 71,
    "gtse-atsv-tier0": 11,
    "inspecta-firewall-platform": 16,
    "osate2-emv2-annex-instance": 3,
    "osate2-issue2318-bidir": 3,
    "osate2-issue2780-featuregroups": 24,
    "osate2-pulseox": 18,
    "osate2-simple-control-modes": 31,
}

ERA_OF = {
    "case-hamr-edp-domains": "2017-2020",
    "ex-carsystem": "2014",
    "ex-crossdomain-security": "2017-2020",
    "ex-issue440-arinc653": "2014",
    "ex-latency-nobus": "2014",
    "ex-latency-normal": "2014",
    "ex-latency-partitioned-distributed": "2014",
    "ex-latency-unbound": "2014",
    "ex-pullprotocols": "2014",
    "ex-simple-thread-latency": "2014",
    "fmw-uav-v3": "2017-2020",
    "inspecta-firewall-platform": "current",
    "osate2-pulseox": "current",
    "osate2-simple-control-modes": "2017-2020",
}


def _file(corpus: Path, short: str) -> Path:
    found = sorted((corpus / "osate" / "aaxl2" / short).rglob("*.aaxl2"))
    assert len(found) == 1, found
    return found[0]


def _index_counts(corpus: Path) -> dict[str, tuple[int, int, int]]:
    """(comps, conns, PAs) per short name, read from the counts table of the corpus INDEX.md."""
    counts = {}
    for line in (corpus / "osate" / "INDEX.md").read_text(encoding="utf-8").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 11 and cells[0].isdigit():
            counts[cells[1].strip("`")] = (int(cells[7]), int(cells[8]), int(cells[9]))
    return counts


_CACHE: dict[Path, ImportResult] = {}


def _read(corpus: Path, short: str) -> ImportResult:
    path = _file(corpus, short)
    if path not in _CACHE:
        _CACHE[path] = read_aaxl2(path)
    return _CACHE[path]


def _everything(result: ImportResult):
    for root in list(result.model.instances) + list(result.model.componentInstances):
        yield from model.walk(root)


def _find(result: ImportResult, path: str):
    return model.find_instance(result.root, path)


def _value(obj, prop: str):
    return own_property(obj, prop)


# ----------------------------------------------------------------------------- corpus: counts


@pytest.mark.corpus
def test_corpus_has_the_indexed_files(corpus: Path) -> None:
    counts = _index_counts(corpus)
    assert set(counts) == set(INSTANCE_DIRS) | set(DECLARATIVE)


@pytest.mark.corpus
@pytest.mark.parametrize("short", INSTANCE_DIRS)
def test_corpus_instance_counts(corpus: Path, short: str) -> None:
    result = _read(corpus, short)
    assert result.kind == "instance"
    comps, conns, pas = _index_counts(corpus)[short]
    kinds: dict[str, int] = {}
    for obj in _everything(result):
        name = obj.eClass.name
        kinds[name] = kinds.get(name, 0) + 1
    assert kinds.get("ComponentInstance", 0) + kinds.get("SystemInstance", 0) == comps
    assert kinds.get("FeatureInstance", 0) == FEATURES[short]
    assert kinds.get("ConnectionInstance", 0) == conns
    assert kinds.get("PropertyAssociation", 0) == pas
    assert result.era == ERA_OF.get(short)


@pytest.mark.corpus
@pytest.mark.parametrize("short", INSTANCE_DIRS + DECLARATIVE)
def test_corpus_round_trips_through_save_and_load(corpus: Path, short: str, tmp_path: Path) -> None:
    result = _read(corpus, short)
    for suffix in (".xmi", ".json"):
        target = tmp_path / f"model{suffix}"
        model.save(result.model, target)
        again = model.load(target)
        assert model.model_differences(result.model, again) == []


@pytest.mark.corpus
def test_every_predeclared_href_of_the_corpus_decodes(corpus: Path) -> None:
    """The era tables against the real files: each positional reference into a predeclared set
    decodes in the era chosen for its set; the only exception is the 2013 declarative file."""
    undecoded = {}
    for short in INSTANCE_DIRS + DECLARATIVE:
        result = _read(corpus, short)
        messages = [w.message for w in result.warnings if "do not decode" in w.message]
        if messages:
            undecoded[short] = messages
    assert list(undecoded) == ["ex-issue168-declarative-package"]
    assert "Data_Rate_Units" in undecoded["ex-issue168-declarative-package"][0]


# ----------------------------------------------------------------------------- corpus: structure and values


@pytest.mark.corpus
def test_2014_latency_file(corpus: Path) -> None:
    result = _read(corpus, "ex-latency-normal")
    root = result.root
    assert root.name == "latencytest_normal_Instance"
    assert root.classifier == "latency_distributed::latencytest.normal"  # from systemImplementation
    assert model.is_a(root, "SystemInstance") and root.category.name == "system"
    task = _find(result, "s.task1")
    assert task.category.name == "thread" and task.subcomponent == "task1" and list(task.index) == []
    assert _value(task, "Timing_Properties::Period") == Quantity(50, "ms")
    assert _value(task, "Period").unit == "ms"
    assert _value(task, "Dispatch_Protocol") == EnumLiteral("Periodic")
    assert _value(task, "Compute_Execution_Time") == Range(Quantity(3, "ms"), Quantity(7, "ms"))
    outp = _find(result, "s.task1.outp")
    assert outp.category.name == "dataPort" and outp.direction.name == "out" and outp.feature == "outp"
    assert _value(outp, "Memory_Properties::Data_Size") == Quantity(1, "Bytes")
    assert _value(outp, "Data_Model::Data_Representation") == EnumLiteral("Integer")
    assert _value(_find(result, "r.inp"), "Data_Model::Number_Representation") == EnumLiteral("Signed")
    assert _find(result, "r.inp").direction.name == "in"  # EMF omits the default
    # xmi:id references: a binding to the processor instance
    assert _value(_find(result, "s"), "Actual_Processor_Binding") == [_find(result, "scpu")]
    assert _value(_find(result, "r.task1"), "Actual_Processor_Binding") == [_find(result, "rcpu")]
    bus_time = _value(_find(result, "b"), "Communication_Properties::Transmission_Time")
    assert bus_time == {
        "Fixed": Range(Quantity(10, "ms"), Quantity(30, "ms")),
        "PerByte": Range(Quantity(1, "us"), Quantity(10, "us")),
    }
    (conn,) = [c for c in root.connectionInstances if c.kind.name == "portConnection"]
    assert conn.name == "s.task1.outp -> r.task1.inp" and conn.complete
    assert conn.source is _find(result, "s.task1.outp") and conn.destination is _find(result, "r.task1.inp")
    assert _value(conn, "Actual_Connection_Binding") == [_find(result, "b")]
    contexts = [model.instance_path(ref.context) for ref in conn.connectionReferences]
    assert contexts == ["latencytest_normal_Instance.s", root.name, "latencytest_normal_Instance.r"]
    assert conn.connectionReferences[0].connection.endswith("@ownedClassifier.4/@ownedPortConnection.0")
    access = [c for c in root.connectionInstances if c.kind.name == "accessConnection"]
    assert len(access) == 2 and all(c.bidirectional for c in access)
    assert access[0].destination is _find(result, "b")  # a component instance as connection end
    fsource = _find(result, "s.task1").flowSpecifications[0]
    assert fsource.kind.name == "source" and fsource.destination is _find(result, "s.task1.outp")
    (flow,) = root.endToEndFlows
    assert flow.flow == "etef0" and flow.flowElements[1] is conn
    assert _value(flow, "Latency") == Range(Quantity(5, "ms"), Quantity(10, "ms"))
    assert [m.name for m in root.systemOperationModes] == ["No Modes"]


@pytest.mark.corpus
def test_2014_file_with_newer_arinc653(corpus: Path) -> None:
    """A 2014 file whose ARINC653 set already had the 2017 layout: decoded per property set."""
    result = _read(corpus, "ex-issue440-arinc653")
    assert result.era == "2014" and result.property_set_eras == {"ARINC653": "2017-2020"}
    cpu = _find(result, "the_cpu")
    levels = _value(cpu, "ARINC653::HM_Error_ID_Levels")
    assert levels[0] == {
        "ErrorIdentifier": 1,
        "Description": "Numeric error",
        "ErrorLevel": EnumLiteral("Module_Level"),
        "ErrorCode": EnumLiteral("Numeric_Error"),
    }
    assert _value(cpu, "ARINC653::Module_Major_Frame") == Quantity(4000, "ms")
    schedule = _value(cpu, "ARINC653::Module_Schedule")
    assert schedule[0]["Partition"] is _find(result, "the_cpu.the_part1")
    assert (
        schedule[0]["Duration"] == Quantity(2000, "ms") and schedule[0]["Periodic_Processing_Start"] is True
    )
    sender = _find(result, "the_proc1.the_sender")
    assert _value(sender, "Memory_Properties::Data_Size") == Quantity(40000, "Bytes")
    assert _value(_find(result, "the_proc1"), "Actual_Memory_Binding") == [_find(result, "the_mem.part1_mem")]
    assert _value(_find(result, "the_mem.part1_mem"), "Memory_Protocol") == EnumLiteral("read_write")
    # a user property set without its source: positions kept as written, reported once
    scheduler = _value(cpu, "POK::Scheduler")
    assert str(scheduler).startswith("../properties/pok_properties.aadl2#//@ownedPropertyType.0/")
    assert any("pok_properties.aadl2" in w.message for w in result.warnings)


@pytest.mark.corpus
def test_2017_era_file(corpus: Path) -> None:
    result = _read(corpus, "osate2-simple-control-modes")
    sensor = _find(result, "sensor1")
    assert sensor.classifier and "::" in sensor.classifier
    assert _value(sensor, "Period") == Quantity(25, "ms")
    assert _value(_find(result, "sensor1.sensorSignal"), "Data_Size") == Quantity(2, "KByte")
    assert _value(_find(result, "dcs.hw"), "SEI::MIPSCapacity") == Quantity(2.4, "MIPS")
    assert _value(_find(result, "dcs.app"), "SEI::MIPSBudget") == Quantity(2.0, "MIPS")
    assert _value(_find(result, "sensor1.power"), "SEI::PowerBudget") == Quantity(0.45, "W")
    assert _value(result.root, "SEI::WeightLimit") == Quantity(1.2, "kg")
    assert _value(result.root, "ACVIP::Aliases") == ["SCS", "Simple Controller"]
    assert [m.name for m in result.root.modeInstances] == ["operational", "standby"]
    assert result.root.modeInstances[0].initial and not result.root.modeInstances[1].initial


@pytest.mark.corpus
def test_relative_plugin_uris_and_memory_bindings(corpus: Path) -> None:
    result = _read(corpus, "fmw-uav-v3")
    assert result.era == "2017-2020"  # from ../../../plugin/org.osate.workspace/… URIs
    proc_sw = _find(result, "MCMP.PROC_SW")
    assert _value(proc_sw, "Actual_Processor_Binding") == [_find(result, "MCMP.PROC_HW")]
    assert _value(proc_sw, "Actual_Memory_Binding") == [_find(result, "MCMP.MEM_HW")]
    port = _find(result, "MCMP.PROC_SW.FPLN.request_nofly_zones")
    assert _value(port, "Data_Model::Data_Representation") == EnumLiteral("Array")
    assert _value(port, "Data_Model::Base_Type") == ["SW::Coordinate.Impl"]  # classifier value
    bindings = [c for c in result.root.connectionInstances if own_property(c, "Actual_Connection_Binding")]
    assert bindings and all(
        model.is_a(b, "ComponentInstance") for c in bindings for b in _value(c, "Actual_Connection_Binding")
    )


@pytest.mark.corpus
def test_current_era_xmi_file_with_two_roots(corpus: Path) -> None:
    result = _read(corpus, "inspecta-firewall-platform")
    assert result.era == "current"
    assert [r.name for r in result.model.instances] == ["ZCU102_Impl_Instance"]
    (data_root,) = result.model.componentInstances
    assert data_root.name == "SW::StructuredEthernetMessage.i" and data_root.category.name == "data"
    thread = _find(result, "seL4.ArduPilot.ArduPilot")
    assert thread.classifier == "SW::ArduPilot.Impl"
    assert _value(thread, "Period") == Quantity(1000, "ms")
    assert _value(thread, "Memory_Properties::Stack_Size") == Quantity(1048576, "Bytes")
    assert _value(thread, "Actual_Processor_Binding") == [_find(result, "proc")]
    assert _value(_find(result, "proc"), "Timing_Properties::Frame_Period") == Quantity(1000, "ms")
    rx = _find(result, "seL4.ArduPilot.EthernetFramesRx")
    assert rx.category.name == "eventDataPort" and rx.type is data_root  # "/1": the second root
    enumerators = own_property(data_root.componentInstances[1], "Data_Model::Enumerators")
    assert enumerators == ["IPV4", "IPV6"]
    assert result.sidecars["../SW.aadl"][1] is True and result.sidecars["../platform.aadl"][1] is False


@pytest.mark.corpus
def test_modes_feature_groups_bidirectional_and_annexes(corpus: Path) -> None:
    modes = _read(corpus, "ex-large-modes").root
    s1 = modes.componentInstances[0]
    assert list(s1.inModes) == ["S123", "S124", "S134"]
    transition = modes.modeTransitionInstances[0]
    assert (transition.source.name, transition.destination.name) == ("S123", "S234")
    som = modes.systemOperationModes[0]
    assert [m.name for m in som.currentModes] == ["S123", "Powered", "Powered", "Powered"]
    assert len(modes.connectionInstances[0].inSystemOperationModes) == 8
    # a list of references written again is resolved once, but each object gets its own list
    connections = list(modes.connectionInstances)
    first = list(connections[0].inSystemOperationModes)
    same = [c for c in connections if list(c.inSystemOperationModes) == first]
    assert len(same) > 1
    same[0].inSystemOperationModes.append("elsewhere")
    assert list(same[1].inSystemOperationModes) == first
    for each in modes.systemOperationModes:  # every object refers on its own (delete() follows these)
        assert all((each, type(each).currentModes) in mode._inverse_rels for mode in each.currentModes)

    groups = _read(corpus, "osate2-issue2780-featuregroups").root
    fl = groups.componentInstances[0].featureInstances[0]
    assert (fl.category.name, fl.direction.name) == ("featureGroup", "inOut")
    inner = fl.featureInstances[0]
    assert [(f.name, f.direction.name) for f in inner.featureInstances] == [("fi", "out"), ("fo", "in")]
    assert groups.componentInstances[0].category.name == "abstract"  # EMF omits the default

    emv2 = _read(corpus, "osate2-emv2-annex-instance").root
    annex = emv2.annexInstances[0]
    assert annex.name == "EMV2" and "FeaturePropagation" in annex.text
    assert etree.fromstring(annex.text.encode()).get("name") == "EMV2"
    assert emv2.connectionInstances[0].kind.name == "featureConnection"  # no kind written


@pytest.mark.corpus
def test_user_property_sets_stay_opaque_and_are_reported(corpus: Path) -> None:
    result = _read(corpus, "ex-mission-aircraft")
    assert result.era is None
    messages = [w.message for w in result.warnings]
    assert any("SecurityEnforcementProperties.aadl" in m and "kept as uri#fragment" in m for m in messages)


@pytest.mark.corpus
def test_declarative_package(corpus: Path) -> None:
    result = _read(corpus, "smaccm-geofence-declarative")
    assert result.kind == "package" and result.root is None
    (pkg,) = result.model.units
    assert pkg.name == "Geofence" and list(pkg.withs) == ["Base_Types", "Data_Model"]
    names = [c.name for c in pkg.classifiers]
    assert names[:4] == ["route", "route.i", "coord", "coord.i"] and len(names) == 12
    coord = model.find_classifier(result.model, "Geofence::coord.i")
    assert coord.type == "Geofence::coord" and coord.category.name == "data"
    assert [(s.name, s.classifier) for s in coord.subcomponents] == [
        ("x", "Base_Types::Float"),
        ("y", "Base_Types::Float"),
    ]
    route = model.find_classifier(result.model, "Geofence::route.i")
    assert own_property(route, "Data_Model::Data_Representation") == EnumLiteral("Array")
    vehicle_i = model.find_classifier(result.model, "Geofence::vehicle.i")
    assert ("conn_fence", "fence", "planner.fence") in [
        (c.name, c.source, c.destination) for c in vehicle_i.connections
    ]
    vehicle = model.find_classifier(result.model, "Geofence::vehicle")
    assert [(f.name, f.category.name, f.classifier) for f in vehicle.features][0] == (
        "loc",
        "dataPort",
        "Geofence::coord.i",
    )
    assert vehicle.annexSubclauses[0].name == "agree" and "cur_fence" in vehicle.annexSubclauses[0].text


@pytest.mark.corpus
def test_a_subcomponent_of_no_known_category_is_an_unknown_element(corpus: Path) -> None:
    path = _file(corpus, "smaccm-geofence-declarative")
    text = path.read_text(encoding="ascii")
    data = text.replace('<ownedDataSubcomponent name="x"', '<ownedBogusSubcomponent name="x"', 1)
    assert data != text
    result = loads_aaxl2(data.encode("ascii"), str(path))
    coord = model.find_classifier(result.model, "Geofence::coord.i")
    assert [s.name for s in coord.subcomponents] == ["y"]
    assert any("ownedBogusSubcomponent" in w.message for w in result.warnings)
    with pytest.raises(ImportFormatError, match="ownedBogusSubcomponent"):
        loads_aaxl2(data.encode("ascii"), str(path), strict=True)


@pytest.mark.corpus
def test_declarative_2013_package_and_property_set(corpus: Path) -> None:
    package = _read(corpus, "ex-issue168-declarative-package")
    (pkg,) = package.model.units
    s1 = model.find_classifier(package.model, "test2::s1")
    assert [(f.name, f.category.name, f.direction.name) for f in s1.features] == [("f", "eventPort", "out")]
    assert own_property(s1, "SEI::SecurityLevel") == 1  # a positional property reference, decoded
    impl = model.find_classifier(package.model, "test2::s.i")
    assert impl.type == "test2::s" and [c.source for c in impl.connections] == ["s1.f"]
    pset = _read(corpus, "ex-issue411-declarative-propertyset")
    (unit,) = pset.model.units
    assert model.is_a(unit, "PropertySet") and unit.name == "JMRMIS"
    (ptype,) = unit.ownedPropertyTypes
    literals = [(lit.name, lit.baseUnit) for lit in ptype.ownedUnitsType.ownedLiterals]
    assert literals == [("m", None), ("km", "m"), ("NM", "m")]
    (prop,) = unit.ownedProperties
    assert (prop.name, prop.type, list(prop.appliesTo)) == (
        "ObservationRadius",
        "JMRMIS::NauticalDistance",
        ["all"],
    )


# ----------------------------------------------------------------------------- era tables


@pytest.mark.parametrize("era", osate_eras.ERAS)
def test_era_tables_decode_and_encode_both_ways(era: str) -> None:
    table = osate_eras.table(era)
    checked = 0
    for set_name in table.property_sets():
        facts = table._sets[set_name.lower()]
        for container in facts.containers.values():
            for name, _units in container.entries:
                path = table.literal_path(set_name, container.type_name, name)
                literal = table.literal(set_name, path)
                assert literal is not None and literal.name.lower() == name.lower()
                checked += 1
    assert checked > 200


def test_known_positions_per_era() -> None:
    ms_2014 = osate_eras.table("2014").literal("AADL_Project", "@ownedPropertyType.12/@ownedLiteral.3")
    ms_now = osate_eras.table("current").literal("AADL_Project", "@ownedPropertyType.16/@ownedLiteral.3")
    assert (
        (ms_2014.type_name, ms_2014.name)
        == (ms_now.type_name, ms_now.name)
        == ("AADL_Project::Time_Units", "ms")
    )
    assert (
        osate_eras.table("2017-2020").literal("AADL_Project", "@ownedPropertyType.15/@ownedLiteral.1").name
        == "Bytes"
    )
    assert (
        osate_eras.table("current").literal("AADL_Project", "@ownedPropertyType.17/@ownedLiteral.1").name
        == "kbps"
    )
    assert (
        osate_eras.table("2017-2020").literal("AADL_Project", "@ownedPropertyType.17/@ownedLiteral.1").name
        == "Bytesps"
    )
    assert osate_eras.table("current").literal_path("AADL_Project", "Time_Units", "ms") == (
        "@ownedPropertyType.16/@ownedLiteral.3"
    )
    assert (
        osate_eras.fragment("current", "@ownedPropertyType.16/@ownedLiteral.3")
        == "/0/@ownedPropertyType.16/@ownedLiteral.3"
    )
    assert osate_eras.predeclared_uri("current", "Timing_Properties") == (
        "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/Timing_Properties.aadl"
    )
    assert osate_eras.predeclared_uri("current", "SEI").startswith(
        "platform:/plugin/org.osate.contribution.sei/"
    )
    assert (
        osate_eras.table("current").property_units("Timing_Properties::Period") == "AADL_Project::Time_Units"
    )
    assert (
        osate_eras.table("2014").property_name("Communication_Properties", 14)
        == "Communication_Properties::Transmission_Time"
    )


@pytest.mark.parametrize(
    ("uri", "expected"),
    [
        ("../../../Plugin_Resources/AADL_Project.aadl", ("AADL_Project", ("2014",))),
        (
            "platform:/plugin/org.osate.workspace/resources/properties/Predeclared_Property_Sets/Timing_Properties.aadl",
            ("Timing_Properties", ("2017-2020",)),
        ),
        (
            "../../../plugin/org.osate.workspace/resources/properties/Predeclared_Property_Sets/Deployment_Properties.aadl",
            ("Deployment_Properties", ("2017-2020",)),
        ),
        (
            "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/AADL_Project.aadl",
            ("AADL_Project", ("current",)),
        ),
        (
            "platform:/plugin/org.osate.contribution.sei/resources/properties/SEI.aadl",
            ("SEI", ("2017-2020", "current")),
        ),
        ("../../Properties/Physical.aadl", None),
        ("platform:/plugin/org.sireum.aadl.osate.hamr/resources/HAMR.aadl", None),
    ],
)
def test_uri_forms(uri: str, expected) -> None:
    found = osate_eras.classify_uri(uri)
    assert (None if found is None else (found.property_set, found.eras)) == expected


def test_choose_era_checks_units_against_the_property() -> None:
    plugin = "../../Plugin_Resources/"
    period = osate_eras.HrefUse(
        plugin + "AADL_Project.aadl",
        "//@ownedPropertyType.12/@ownedLiteral.3",
        "unit",
        "Timing_Properties::Period",
    )
    assert osate_eras.choose_era([period]).era == "2014" and not osate_eras.choose_era([period]).problems
    wrong = osate_eras.HrefUse(
        plugin + "AADL_Project.aadl",
        "//@ownedPropertyType.11/@ownedLiteral.1",
        "unit",
        "Timing_Properties::Period",
    )
    choice = osate_eras.choose_era([wrong])
    assert choice.era == "2014" and "Size_Units" in choice.problems[0][1]
    # without a URI form that names the era, the table that decodes everything wins
    sei = "platform:/plugin/org.osate.contribution.sei/resources/properties/SEI.aadl"
    use = osate_eras.HrefUse(sei, "/0/@ownedPropertyType.4/@ownedLiteral.1", "unit", "SEI::MIPSCapacity")
    assert osate_eras.choose_era([use]).era == "current"
    enum = osate_eras.HrefUse(sei, "/0/@ownedPropertyType.4/@ownedLiteral.1", "enum", "SEI::MIPSCapacity")
    assert osate_eras.choose_era([enum]).problems  # a units type is not an enumeration


# ----------------------------------------------------------------------------- small own fixtures

NS = (
    'xmlns:xmi="http://www.omg.org/XMI" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
    'xmlns:aadl2="http://aadl.info/AADL/2.0" xmlns:instance="http://aadl.info/AADL/2.0/instance"'
)
PS = "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/"


def _instance(body: str, root_attrs: str = 'name="top_i_Instance" category="system"') -> bytes:
    return (
        '<?xml version="1.0" encoding="ASCII"?>\n'
        f'<instance:SystemInstance xmi:version="2.0" {NS} {root_attrs}>\n'
        f"{body}\n"
        '  <componentImplementation xsi:type="aadl2:SystemImplementation" href="../m.aadl#m.top.i"/>\n'
        "</instance:SystemInstance>\n"
    ).encode("ascii")


D = "../m.aadl#/0/@ownedPublicSection/@ownedClassifier."
F0, F1 = "//@componentInstance.1/@featureInstance.0", "//@componentInstance.1/@featureInstance.1"
GOOD = _instance(
    f"""  <componentInstance name="cpu" category="processor">
    <subcomponent xsi:type="aadl2:ProcessorSubcomponent" href="{D}1/@ownedProcessorSubcomponent.0"/>
    <index>0</index>
  </componentInstance>
  <componentInstance name="t" category="thread group">
    <ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">
      <property href="{PS}Deployment_Properties.aadl#Deployment_Properties.Actual_Processor_Binding"/>
      <ownedValue><ownedValue xsi:type="aadl2:ListValue">
        <ownedListElement xsi:type="instance:InstanceReferenceValue"
          referencedInstanceObject="//@componentInstance.0"/>
      </ownedValue></ownedValue>
    </ownedPropertyAssociation>
    <ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">
      <property href="{PS}Timing_Properties.aadl#Timing_Properties.Period"/>
      <ownedValue><ownedValue xsi:type="aadl2:IntegerLiteral" value="20">
        <unit href="{PS}AADL_Project.aadl#/0/@ownedPropertyType.16/@ownedLiteral.2"/>
      </ownedValue></ownedValue>
    </ownedPropertyAssociation>
    <featureInstance name="p" category="eventDataPort" direction="in out">
      <feature xsi:type="aadl2:EventDataPort" href="{D}0/@ownedEventDataPort.0"/>
    </featureInstance>
    <featureInstance name="q">
      <feature xsi:type="aadl2:DataPort" href="{D}0/@ownedDataPort.0"/>
    </featureInstance>
    <index>2</index>
    <classifier xsi:type="aadl2:ThreadGroupImplementation" href="../m.aadl#m.tg.i"/>
  </componentInstance>
  <connectionInstance name="t.p -> t.q" destination="{F1}" source="{F0}">
    <connectionReference context="/" source="{F0}" destination="{F1}">
      <connection xsi:type="aadl2:FeatureConnection" href="{D}2/@ownedFeatureConnection.0"/>
    </connectionReference>
  </connectionInstance>"""
)


def test_own_fixture_reads_with_defaults_and_java_literals() -> None:
    result = loads_aaxl2(GOOD, "good.aaxl2")
    root = result.root
    assert result.era == "current" and result.warnings == []
    t = root.componentInstances[1]
    assert t.category.name == "threadGroup" and list(t.index) == [2] and t.classifier == "m::tg.i"
    assert own_property(t, "Period") == Quantity(20, "us")
    assert own_property(t, "Actual_Processor_Binding") == [root.componentInstances[0]]
    p, q = t.featureInstances
    assert (p.category.name, p.direction.name) == ("eventDataPort", "inOut")
    assert (q.category.name, q.direction.name) == ("dataPort", "in")
    conn = root.connectionInstances[0]
    assert conn.kind.name == "featureConnection" and not conn.complete and not conn.bidirectional
    assert conn.source is p and conn.destination is q and conn.connectionReferences[0].context is root


def _replace(data: bytes, old: str, new: str) -> bytes:
    assert old.encode() in data
    return data.replace(old.encode(), new.encode(), 1)


BOMB = b"""<?xml version="1.0"?>
<!DOCTYPE lolz [<!ENTITY lol "lol"><!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
<!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">]>
<instance:SystemInstance xmlns:instance="http://aadl.info/AADL/2.0/instance" name="&lol2;"/>"""
EXTERNAL = b"""<?xml version="1.0"?>
<!DOCTYPE r [<!ENTITY x SYSTEM "file:///etc/passwd">]>
<instance:SystemInstance xmlns:instance="http://aadl.info/AADL/2.0/instance" name="&x;"/>"""
EXTERNAL_NET = b"""<?xml version="1.0"?>
<!DOCTYPE r SYSTEM "http://127.0.0.1:9/r.dtd">
<instance:SystemInstance xmlns:instance="http://aadl.info/AADL/2.0/instance" name="x"/>"""

BAD_INPUTS = {
    "truncated": (GOOD[: len(GOOD) // 2], "malformed XML", True),
    "empty": (b"", "empty", True),
    "wrong-root": (
        b'<?xml version="1.0"?>\n<project name="x"/>\n',
        "unexpected root element <project>",
        True,
    ),
    "wrong-aadl2-root": (
        b'<aadl2:Classifier xmlns:aadl2="http://aadl.info/AADL/2.0" name="x"/>',
        "unexpected root element",
        True,
    ),
    "dangling-ref": (
        _replace(
            GOOD,
            'referencedInstanceObject="//@componentInstance.0"',
            'referencedInstanceObject="//@componentInstance.7"',
        ),
        "referencedInstanceObject refers to '//@componentInstance.7'",
        True,
    ),
    "dangling-root": (
        _replace(GOOD, 'context="/"', 'context="/3"'),
        "context refers to '/3'",
        True,
    ),
    "wrong-target-class": (
        _replace(GOOD, 'context="/"', f'context="{F0}"'),
        "context refers to a FeatureInstance, expected a ComponentInstance",
        True,
    ),
    "unknown-xsi-type": (
        _replace(GOOD, 'xsi:type="aadl2:IntegerLiteral"', 'xsi:type="aadl2:ImaginaryLiteral"'),
        "unknown property value type",
        True,
    ),
    "unknown-feature-type": (
        _replace(GOOD, 'xsi:type="aadl2:DataPort"', 'xsi:type="aadl2:WormholePort"'),
        "unknown xsi:type 'aadl2:WormholePort'",
        True,
    ),
    "undeclared-prefix": (
        _replace(GOOD, 'xsi:type="aadl2:IntegerLiteral"', 'xsi:type="nowhere:IntegerLiteral"'),
        "undeclared namespace prefix",
        True,
    ),
    "bad-category": (_replace(GOOD, 'category="thread group"', 'category="spaceship"'), "spaceship", True),
    "bad-number": (_replace(GOOD, 'value="20"', 'value="twenty"'), "not a number", True),
    "bad-index": (_replace(GOOD, "<index>2</index>", "<index>two</index>"), "not an integer", True),
    "no-source": (
        _replace(GOOD, ' source="//@componentInstance.1/@featureInstance.0">', ">"),
        "has no source",
        True,
    ),
    "entity-bomb": (BOMB, "entit", False),
    "external-entity": (EXTERNAL, "entity", False),
    "external-dtd-on-the-network": (EXTERNAL_NET, "DOCTYPE", False),
    "deeply-nested": (
        _instance('<componentInstance name="a">' * 300 + "</componentInstance>" * 300),
        "malformed XML",
        True,
    ),
}


@pytest.mark.parametrize("case", list(BAD_INPUTS))
def test_bad_input_is_a_located_error(case: str, tmp_path: Path) -> None:
    data, message, has_line = BAD_INPUTS[case]
    path = tmp_path / "bad_Instance.aaxl2"
    path.write_bytes(data)
    before = sorted(p.name for p in tmp_path.iterdir())
    with pytest.raises(ImportFormatError) as info:
        read_aaxl2(path)
    assert message in info.value.message
    assert info.value.location.file == str(path)
    if has_line:
        assert info.value.location.line is not None or info.value.location.path is not None
    assert "passwd" not in str(info.value) or case != "external-entity"
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # nothing written


def test_located_errors_name_the_element() -> None:
    data = BAD_INPUTS["dangling-ref"][0]
    with pytest.raises(ImportFormatError) as info:
        loads_aaxl2(data, "x.aaxl2")
    location = info.value.location
    assert location.line == data[: data.index(b"componentInstance.7")].count(b"\n") + 1
    assert location.path.endswith("ownedListElement/@referencedInstanceObject")


def test_huge_file_is_refused_before_reading(tmp_path: Path) -> None:
    path = tmp_path / "huge_Instance.aaxl2"
    with path.open("wb") as handle:  # sparse: takes no disk space
        handle.truncate(600 * 1024 * 1024)
    with pytest.raises(ImportFormatError, match="more than the .*-byte limit"):
        read_aaxl2(path)
    small = tmp_path / "small_Instance.aaxl2"
    small.write_bytes(GOOD)
    with pytest.raises(ImportFormatError, match="limit"):
        read_aaxl2(small, max_bytes=100)


def test_unknown_elements_are_warned_or_refused_when_strict() -> None:
    data = _replace(GOOD, "<index>2</index>", "<index>2</index><futureThing a='1'/>")
    result = loads_aaxl2(data, "x.aaxl2")
    assert any("futureThing" in w.message and w.location.line for w in result.warnings)
    with pytest.raises(ImportFormatError, match="futureThing"):
        loads_aaxl2(data, "x.aaxl2", strict=True)


def test_names_with_path_tricks_are_plain_names(tmp_path: Path) -> None:
    data = _replace(GOOD, 'name="cpu"', 'name="../../etc/passwd"')
    data = _replace(data, 'href="../m.aadl#m.tg.i"', 'href="../../../../../../etc/passwd#m.tg.i"')
    result = loads_aaxl2(data, str(tmp_path / "x_Instance.aaxl2"))
    assert result.root.componentInstances[0].name == "../../etc/passwd"
    resolved, _present = result.sidecars["../../../../../../etc/passwd"]
    assert Path(resolved).is_absolute()  # reported, never read


def test_sidecars_are_looked_up_when_asked_for_not_during_the_import(tmp_path: Path) -> None:
    (tmp_path / "instances").mkdir()
    result = loads_aaxl2(GOOD, str(tmp_path / "instances" / "x_Instance.aaxl2"))
    (tmp_path / "m.aadl").write_text("package m\npublic\nend m;\n")
    resolved, present = result.sidecars["../m.aadl"]
    assert Path(resolved) == tmp_path / "m.aadl" and present
    assert loads_aaxl2(GOOD, "<memory>").sidecars["../m.aadl"] == ("../m.aadl", False)


@pytest.mark.corpus
def test_mutated_corpus_files_fail_cleanly(corpus: Path) -> None:
    """Random damage to real files: every outcome is a model or a RosaadlError, never a crash."""
    rng = random.Random(20240521)
    sources = [
        _file(corpus, s).read_bytes()
        for s in ("ex-latency-normal", "osate2-simple-control-modes", "ex-large-modes")
    ]
    outcomes = {"ok": 0, "error": 0}
    for _ in range(150):
        data = bytearray(rng.choice(sources))
        action = rng.randrange(4)
        if action == 0:  # truncate
            data = data[: rng.randrange(len(data))]
        elif action == 1:  # damage an attribute value
            values = [m.span(1) for m in re.finditer(rb'="([^"]*)"', data)]
            start, end = rng.choice(values)
            data[start:end] = rng.choice(
                [b"", b"//@componentInstance.99", b"x y", b"-1", b"/9", b"aadl2:Nope", b"&#0;"]
            )
        elif action == 2:  # drop a line
            lines = bytes(data).split(b"\n")
            del lines[rng.randrange(1, len(lines))]
            data = bytearray(b"\n".join(lines))
        else:  # rename an element
            tags = [m.span(1) for m in re.finditer(rb"<([A-Za-z:]+)[ >/]", data)]
            start, end = rng.choice(tags[1:])
            data[start:end] = rng.choice([b"ownedValue", b"componentInstance", b"unit", b"zzz"])
        try:
            loads_aaxl2(bytes(data), "mutant.aaxl2")
            outcomes["ok"] += 1
        except RosaadlError as exc:
            assert exc.location.file == "mutant.aaxl2"
            outcomes["error"] += 1
    assert outcomes["error"] > 30 and outcomes["ok"] > 5


# ----------------------------------------------------------------------------- fast construction


def test_fast_objects_behave_like_pyecore_objects(tmp_path: Path) -> None:
    result = loads_aaxl2(GOOD, "good.aaxl2")
    root = result.root
    for obj in model.walk(result.model):
        for child in model.children(obj):
            assert child.eContainer() is obj
            assert getattr(obj, child.eContainmentFeature().name) is child or child in getattr(
                obj, child.eContainmentFeature().name
            )
        for feature in obj.eClass.eAllStructuralFeatures():
            value = obj.eGet(feature)
            if len(value) if feature.many else value != feature.get_default_value():
                assert obj.eIsSet(feature), (obj.eClass.name, feature.name)  # what pyecore saves
    t = root.componentInstances[1]
    # setters, collections and notifications work on them as on any pyecore object
    seen = []
    from pyecore.notification import EObserver

    EObserver(t, notifyChanged=seen.append)
    t.name = "renamed"
    t.category = metamodels.aadl().getEClassifier("ComponentCategory").from_string("thread")
    t.featureInstances.append(model.new("FeatureInstance", name="extra"))
    assert t.name == "renamed" and t.category.name == "thread" and len(seen) == 3
    assert t.featureInstances[-1].eContainer() is t
    pa = t.ownedPropertyAssociations[1]
    pa.ownedValues[0].value.value = 40
    assert own_property(t, "Period") == Quantity(40, "us")
    # the reference back-links pyecore keeps let delete() clean up
    cpu = root.componentInstances[0]
    ref_value = t.ownedPropertyAssociations[0].ownedValues[0].value.ownedItems[0]
    assert ref_value.referencedInstanceObject is cpu
    cpu.delete()
    assert ref_value.referencedInstanceObject is None and cpu not in root.componentInstances
    model.save(result.model, tmp_path / "m.xmi")
    again = model.load(tmp_path / "m.xmi")
    assert model.model_differences(result.model, again) == []


def test_generated_benchmark_file_imports_with_the_expected_count(tmp_path: Path) -> None:
    path = tmp_path / "gen_Instance.aaxl2"
    expected = write_aaxl2_instance(path, objects=3000)
    result = read_aaxl2(path)
    assert sum(1 for _ in model.walk(result.model)) == expected
    thread = model.find_instance(result.root, "proc1.t3")
    assert own_property(thread, "Period") == Quantity(40, "ms")
    assert own_property(thread, "Actual_Processor_Binding") == [model.find_instance(result.root, "cpu1")]
    assert result.era == "current" and not result.warnings


def test_gc_is_restored_and_foreign_frozen_objects_are_left_alone() -> None:
    import gc

    from rosaadl.bulk import gc_paused

    assert gc.isenabled()
    loads_aaxl2(GOOD, "good.aaxl2")
    assert gc.isenabled()
    with pytest.raises(ImportFormatError):
        loads_aaxl2(BAD_INPUTS["dangling-ref"][0], "bad.aaxl2")
    assert gc.isenabled()
    gc.disable()
    try:
        loads_aaxl2(GOOD, "good.aaxl2")
        assert not gc.isenabled()  # the caller's choice is kept
    finally:
        gc.enable()
    gc.freeze()  # a process that froze objects of its own (before a fork, say)
    try:
        frozen = gc.get_freeze_count()
        with gc_paused():
            kept = [[] for _ in range(100)]
        assert gc.get_freeze_count() == frozen and kept
    finally:
        gc.unfreeze()


def test_a_set_under_an_era_specific_uri_is_decoded_in_that_era() -> None:
    """A set written in an older layout under that era's own URI form (org.osate.workspace) is
    decoded in that era even when its positions would also decode in the file's era."""
    from rosaadl.importers.osate_eras import HrefUse, choose_era, predeclared_uri

    current = predeclared_uri("current", "Timing_Properties")
    older = predeclared_uri("2017-2020", "AADL_Project")
    assert "org.osate.workspace" in older
    # ms: the same literal at the same place in both eras, so only the URI form tells
    uses = [HrefUse(older, "/0/@ownedPropertyType.16/@ownedLiteral.3", "unit", "Timing_Properties::Period")]
    choice = choose_era(uses, [current])
    assert choice.era == "current"
    assert choice.set_eras.get("AADL_Project") == "2017-2020"


def test_a_literal_of_a_property_the_era_does_not_declare_is_decoded_where_it_is_declared() -> None:
    """ARINC653's URI is the same in the 2017-2020 and current eras, but its Memory_Type (with
    literal Data_Memory) is Memory_Kind (Memory_Data) today: a named value of Memory_Type in a
    current-era file is decoded with the 2017-2020 layout, not as today's literal at that place."""
    from rosaadl.importers.osate_eras import HrefUse, check_use, choose_era, predeclared_uri, table

    uri = predeclared_uri("current", "ARINC653")
    assert uri == predeclared_uri("2017-2020", "ARINC653")
    path = table("2017-2020").literal_path("ARINC653", "ARINC653::Supported_Memory_Type", "Data_Memory")
    assert path is not None
    use = HrefUse(uri, "/0/" + path, "enum", "ARINC653::Memory_Type")
    assert "not declared in the current ARINC653" in (check_use("current", use) or "")
    assert check_use("2017-2020", use) is None
    choice = choose_era([use], [predeclared_uri("current", "Timing_Properties")])
    assert choice.era == "current" and choice.era_of("ARINC653") == "2017-2020" and not choice.problems
    # a unit of AADL_Project qualifying a property the era lacks still decodes by its units type
    unit = HrefUse(
        predeclared_uri("2014", "AADL_Project"),
        "//@ownedPropertyType.11/@ownedLiteral.1",
        "unit",
        "Memory_Properties::Code_Size",
    )
    assert check_use("2014", unit) is None


def test_an_xmi_id_only_deep_in_the_file_is_still_found() -> None:
    """The reader indexes xmi:ids when the root or its first child carries one (EMF puts one on
    every object of a resource that uses them); a file that refers to an id given only further
    down is read again with ids, with the same result as a file with ids everywhere."""
    body = """  <componentInstance name="cpu" category="processor"/>
  <componentInstance name="b" category="bus" xmi:id="_bus">
    <featureInstance name="acc" category="busAccess" direction="in out" xmi:id="_acc"/>
  </componentInstance>
  <connectionInstance name="acc -> cpu" kind="accessConnection" source="#_acc"
      destination="//@componentInstance.0">
    <connectionReference context="/" source="_acc" destination="//@componentInstance.0"/>
  </connectionInstance>"""
    result = loads_aaxl2(_instance(body))
    connection = result.root.connectionInstances[0]
    assert connection.source is model.find_instance(result.root, "b.acc")
    assert connection.connectionReferences[0].source is connection.source
    # an id nobody carries is a located error, not a second silent read
    with pytest.raises(ImportFormatError, match="no element of the file has as xmi:id"):
        loads_aaxl2(_instance(body.replace('source="#_acc"', 'source="#_nowhere"')))

"""Instantiation of AADL system implementations (rosaadl.transforms.instantiate)."""

from __future__ import annotations

import logging
import os
import re
from pathlib import Path

import pytest
from corpus_cases import OSATE_INSTANCE_DIRS
from lxml import etree

from benchmarks.generators.declarative import (
    deadline_definition,
    period_definition,
    processor_binding_definition,
    time_units,
)
from rosaadl import model
from rosaadl.errors import ModelError, NameResolutionError, UsageError
from rosaadl.lookup import Factory, PropertyLookup
from rosaadl.properties import property_value
from rosaadl.transforms.instantiate import COMPATIBILITY_MODES, instantiate
from rosaadl.units import Quantity

new = model.new


# --------------------------------------------------------------------------- model builders


def _many(items):
    """A list for a many-valued feature, None when empty (model.new marks empty lists as set)."""
    return list(items) or None


def pa(prop, value, *applies_to):
    return new(
        "PropertyAssociation",
        property=prop,
        appliesTo=_many(applies_to),
        ownedValues=[new("ModalPropertyValue", value=value)],
    )


def ms(value):
    return new("IntegerValue", value=value, unit="ms")


def port(name, direction, classifier=None, category="event data port"):
    return new("Feature", name=name, category=category, direction=direction, classifier=classifier)


def sub(name, category, classifier=None, dims=(), modes=(), props=()):
    return new(
        "Subcomponent",
        name=name,
        category=category,
        classifier=classifier,
        arrayDimensions=_many(dims),
        inModes=_many(modes),
        ownedPropertyAssociations=_many(props),
    )


def conn(name, source, destination, kind="port", bidirectional=False, modes=(), props=()):
    return new(
        "Connection",
        name=name,
        kind=kind,
        source=source,
        destination=destination,
        bidirectional=bidirectional,
        inModes=_many(modes),
        ownedPropertyAssociations=_many(props),
    )


def ctype(name, category, *features, props=(), modes=(), flows=(), extended=None):
    return new(
        "ComponentType",
        name=name,
        category=category,
        features=_many(features),
        ownedPropertyAssociations=_many(props),
        modes=_many(modes),
        flowSpecifications=_many(flows),
        extended=extended,
    )


def cimpl(name, category, subs=(), conns=(), props=(), modes=(), flows=(), e2e=(), extended=None, line=None):
    return new(
        "ComponentImplementation",
        name=name,
        type=name.partition(".")[0],
        category=category,
        subcomponents=_many(subs),
        connections=_many(conns),
        ownedPropertyAssociations=_many(props),
        modes=_many(modes),
        flowImplementations=_many(flows),
        endToEndFlows=_many(e2e),
        extended=extended,
        line=line,
    )


def property_sets():
    project = new(
        "PropertySet",
        name="AADL_Project",
        ownedPropertyTypes=[
            time_units("us", "ms"),
            new("AadlInteger", name="Time", unitsType="AADL_Project::Time_Units"),
        ],
    )
    components = ["thread", "thread group", "process", "system", "device", "virtual processor"]
    timing = new(
        "PropertySet",
        name="Timing_Properties",
        ownedProperties=[period_definition(components), deadline_definition(components)],
    )
    deployment = new(
        "PropertySet",
        name="Deployment_Properties",
        ownedProperties=[
            processor_binding_definition(["thread", "process", "system"]),
            new(
                "Property",
                name="Actual_Connection_Binding",
                inherit=True,
                ownedType=new("ListType", ownedElementType=new("ReferenceType")),
                appliesTo=["connection"],
            ),
        ],
    )
    comm = new(
        "PropertySet",
        name="Communication_Properties",
        ownedProperties=[
            new(
                "Property",
                name="Connection_Pattern",
                ownedType=new(
                    "ListType", ownedElementType=new("ListType", ownedElementType=new("EnumerationType"))
                ),
                appliesTo=["connection"],
            )
        ],
    )
    return [project, timing, deployment, comm]


def workspace(*classifiers, name="Pkg", source="pkg.aadl"):
    ws = new("AadlModel", name="ws")
    ws.units.extend(property_sets())
    pkg = new("AadlPackage", name=name, sourceFile=source, classifiers=_many(classifiers))
    ws.units.append(pkg)
    return ws


def pipeline():
    """sys.i: two processes of two threads each, a processor and a bus; a thread-to-thread chain."""
    return workspace(
        ctype("msg", "data"),
        ctype(
            "worker", "thread", port("i", "in", "msg"), port("o", "out", "msg"), props=[pa("Period", ms(10))]
        ),
        ctype("p", "process", port("i", "in", "msg"), port("o", "out", "msg")),
        cimpl(
            "p.i",
            "process",
            subs=[sub("a", "thread", "worker"), sub("b", "thread", "worker")],
            conns=[conn("cin", "i", "a.i"), conn("ab", "a.o", "b.i"), conn("cout", "b.o", "o")],
        ),
        ctype("cpu", "processor", new("Feature", name="ba", category="bus access", access="requires")),
        ctype("net", "bus"),
        ctype("sys", "system"),
        cimpl(
            "sys.i",
            "system",
            subs=[
                sub("p1", "process", "p.i"),
                sub("p2", "process", "p.i"),
                sub("cpu", "processor", "cpu"),
                sub("lan", "bus", "net"),
            ],
            conns=[
                conn("k", "p1.o", "p2.i"),
                conn("acc", "lan", "cpu.ba", kind="access", bidirectional=True),
            ],
            props=[
                pa(
                    "Actual_Processor_Binding",
                    new("ListValue", ownedItems=[new("ReferenceValue", path="cpu")]),
                    "p1",
                    "p2",
                ),
                pa(
                    "Actual_Connection_Binding",
                    new("ListValue", ownedItems=[new("ReferenceValue", path="lan")]),
                    "k",
                ),
            ],
            line=7,
        ),
    )


def names(system, kind="ConnectionInstance"):
    return sorted(o.name for o in model.walk(system) if o.eClass.name == kind)


# --------------------------------------------------------------------------- hierarchy and features


def test_hierarchy_features_and_names():
    ws = pipeline()
    system = instantiate(ws, "Pkg::sys.i")
    assert ws.instances[-1] is system
    assert system.name == "sys_i_Instance" and system.classifier == "Pkg::sys.i"
    assert system.category.name == "system"
    # OSATE's order: an implementation's subcomponents by category (bus, process, processor)
    assert [c.name for c in system.componentInstances] == ["lan", "p1", "p2", "cpu"]
    thread = model.find_instance(system, "p1.a")
    assert (thread.subcomponent, thread.classifier, list(thread.index)) == ("a", "Pkg::worker", [])
    assert str(thread.category.name) == "thread"
    out = model.find_instance(system, "p1.a.o")
    assert (out.feature, out.classifier, out.direction.name, out.category.name) == (
        "o",
        "Pkg::msg",
        "out",
        "eventDataPort",
    )
    ba = model.find_instance(system, "cpu.ba")
    assert ba.access.name == "requires" and ba.category.name == "busAccess"
    assert [s.name for s in system.systemOperationModes] == ["No Modes"]


def test_semantic_connections_cross_the_hierarchy():
    system = instantiate(pipeline(), "Pkg::sys.i")
    # the bus lan comes before the processor cpu (OSATE's category order): the access connection
    # is found from lan first, whichever end the declaration names first
    assert names(system) == ["a.o -> b.i", "a.o -> b.i", "lan <-> cpu.ba", "p1.b.o -> p2.a.i"]
    across = next(c for c in system.connectionInstances if c.name == "p1.b.o -> p2.a.i")
    refs = across.connectionReferences
    assert [r.connection for r in refs] == ["cout", "k", "cin"]
    assert [model.instance_path(r.context) for r in refs] == [
        "sys_i_Instance.p1",
        "sys_i_Instance",
        "sys_i_Instance.p2",
    ]
    assert model.instance_path(refs[1].source) == "sys_i_Instance.p1.o"
    assert across.source is model.find_instance(system, "p1.b.o")
    assert across.destination is model.find_instance(system, "p2.a.i")
    assert across.complete and across.kind.name == "portConnection"
    inner = model.find_instance(system, "p1").connectionInstances
    assert [c.name for c in inner] == ["a.o -> b.i"]
    access = next(c for c in system.connectionInstances if c.kind.name == "accessConnection")
    assert access.bidirectional and access.source is model.find_instance(system, "lan")
    assert access.destination is model.find_instance(system, "cpu.ba")


def test_property_values_on_instances():
    ws = pipeline()
    system = instantiate(ws, "Pkg::sys.i")
    thread = model.find_instance(system, "p2.b")
    assert property_value(thread, "Period") == Quantity(10, "ms")
    # only the properties the model uses are cached on instances (as in OSATE); the lookup still
    # answers the others, here Deadline's default (=> Period)
    assert property_value(thread, "Deadline") is None
    assert PropertyLookup(ws).python_value(thread, "Deadline") == Quantity(10, "ms")
    assert property_value(thread, "Actual_Processor_Binding") == [model.find_instance(system, "cpu")]
    association = next(p for p in thread.ownedPropertyAssociations if p.property.endswith("Binding"))
    assert association.property == "Deployment_Properties::Actual_Processor_Binding"
    assert association.ownedValues[0].value.ownedItems[0].eClass.name == "InstanceReferenceValue"
    across = next(c for c in system.connectionInstances if c.name == "p1.b.o -> p2.a.i")
    assert property_value(across, "Actual_Connection_Binding") == [model.find_instance(system, "lan")]
    assert property_value(model.find_instance(system, "cpu"), "Period") is None  # does not apply
    assert PropertyLookup(ws).python_value(thread, "Timing_Properties::Period") == Quantity(10, "ms")


def test_arrays_and_connection_patterns():
    ws = workspace(
        ctype("t", "thread", port("i", "in"), port("o", "out")),
        ctype("s", "system"),
        cimpl(
            "s.i",
            "system",
            subs=[
                sub("src", "thread", "t", dims=["3"]),
                sub("dst", "thread", "t", dims=["3"]),
                sub("grid", "thread", "t", dims=["2", "3"]),
                sub("one", "thread", "t"),
            ],
            conns=[conn("same", "src.o", "dst.i"), conn("fan", "src.o", "one.i")],
        ),
    )
    system = instantiate(ws, "Pkg::s.i")
    assert [model.instance_path(c) for c in system.componentInstances][:3] == [
        "s_i_Instance.src[1]",
        "s_i_Instance.src[2]",
        "s_i_Instance.src[3]",
    ]
    grid = [c for c in system.componentInstances if c.name == "grid"]
    assert len(grid) == 6
    assert model.instance_path(grid[5]) == "s_i_Instance.grid[2][3]"
    assert names(system) == [
        "src[1].o -> dst[1].i",
        "src[1].o -> one.i",
        "src[2].o -> dst[2].i",
        "src[2].o -> one.i",
        "src[3].o -> dst[3].i",
        "src[3].o -> one.i",
    ]


def test_connections_inside_array_elements():
    ws = pipeline()
    impl = model.find_classifier(ws, "Pkg::sys.i")
    impl.subcomponents.append(sub("farm", "process", "p.i", dims=["2"]))
    system = instantiate(ws, "Pkg::sys.i")
    second = model.find_instance(system, "farm[2]")
    assert [c.name for c in second.connectionInstances] == ["a.o -> b.i"]
    ref = second.connectionInstances[0].connectionReferences[0]
    assert ref.context is second and ref.source is model.find_instance(system, "farm[2].a.o")
    assert second.connectionInstances[0].source is model.find_instance(system, "farm[2].a.o")


def test_connection_pattern_property():
    pattern = new(
        "ListValue",
        ownedItems=[new("ListValue", ownedItems=[new("NamedValue", name="Next")])],
    )
    ws = workspace(
        ctype("t", "thread", port("i", "in"), port("o", "out")),
        ctype("s", "system"),
        cimpl(
            "s.i",
            "system",
            subs=[sub("ring", "thread", "t", dims=["3"])],
            conns=[conn("c", "ring.o", "ring.i", props=[pa("Connection_Pattern", pattern)])],
        ),
    )
    system = instantiate(ws, "Pkg::s.i")
    assert names(system) == ["ring[1].o -> ring[2].i", "ring[2].o -> ring[3].i"]


def test_feature_groups_are_expanded_and_connected():
    group = new(
        "FeatureGroupType",
        name="bundle",
        features=[port("a", "out"), port("b", "in")],
    )
    mirror = new("FeatureGroupType", name="mirror", inverseOf="bundle")
    ws = workspace(
        group,
        mirror,
        ctype("left", "thread", new("Feature", name="g", category="feature group", classifier="bundle")),
        ctype("right", "thread", new("Feature", name="g", category="feature group", classifier="mirror")),
        ctype("s", "system"),
        cimpl(
            "s.i",
            "system",
            subs=[sub("l", "thread", "left"), sub("r", "thread", "right")],
            conns=[conn("fg", "l.g", "r.g", kind="feature group", bidirectional=True)],
        ),
    )
    system = instantiate(ws, "Pkg::s.i")
    rg = model.find_instance(system, "r.g")
    assert [(f.name, f.direction.name) for f in rg.featureInstances] == [("a", "in"), ("b", "out")]
    assert names(system) == ["l.g.a -> r.g.a", "r.g.b -> l.g.b"]


def test_modes_and_system_operation_modes():
    ws = workspace(
        ctype("t", "thread", port("i", "in"), port("o", "out")),
        ctype("s", "system"),
        cimpl(
            "s.i",
            "system",
            subs=[sub("x", "thread", "t", modes=["nominal"]), sub("y", "thread", "t")],
            conns=[conn("c1", "x.o", "y.i", modes=["nominal"]), conn("c2", "y.o", "x.i", modes=["degraded"])],
            modes=[new("Mode", name="nominal", initial=True), new("Mode", name="degraded")],
        ),
    )
    diagnostics = []
    system = instantiate(ws, "Pkg::s.i", diagnostics=diagnostics)
    assert [(m.name, m.initial) for m in system.modeInstances] == [("nominal", True), ("degraded", False)]
    assert [s.name for s in system.systemOperationModes] == ["som_0", "som_1"]
    assert [m.name for m in system.systemOperationModes[1].currentModes] == ["degraded"]
    assert list(model.find_instance(system, "x").inModes) == ["nominal"]
    # c2 needs x, which does not exist in mode degraded: OSATE removes it
    assert names(system) == ["x.o -> y.i"]
    assert list(system.connectionInstances[0].inSystemOperationModes) == ["som_0"]
    assert any("not active in any system operation mode" in d.message for d in diagnostics)


def test_end_to_end_flows():
    ws = workspace(
        ctype(
            "src",
            "thread",
            port("o", "out"),
            flows=[new("FlowSpecification", name="fs", kind="source", outEnd="o")],
        ),
        ctype(
            "snk",
            "thread",
            port("i", "in"),
            flows=[new("FlowSpecification", name="fk", kind="sink", inEnd="i")],
        ),
        ctype("s", "system"),
        cimpl(
            "s.i",
            "system",
            subs=[sub("a", "thread", "src"), sub("b", "thread", "snk")],
            conns=[conn("c", "a.o", "b.i")],
            e2e=[new("EndToEndFlow", name="e", elements=["a.fs", "c", "b.fk"])],
        ),
    )
    system = instantiate(ws, "Pkg::s.i")
    flow = system.endToEndFlows[0]
    assert flow.flow == "e"
    kinds = [e.eClass.name for e in flow.flowElements]
    assert kinds == ["FlowSpecificationInstance", "ConnectionInstance", "FlowSpecificationInstance"]
    assert flow.flowElements[1] is system.connectionInstances[0]


# --------------------------------------------------------------------------- errors and options


def test_unknown_root_and_type_root():
    ws = pipeline()
    with pytest.raises(NameResolutionError) as info:
        instantiate(ws, "Pkg::nope.i")
    assert "Pkg::nope.i" in info.value.message and "Pkg::sys.i" in info.value.message
    with pytest.raises(NameResolutionError) as info:
        instantiate(ws, "Pkg::sys")
    assert "not a component implementation" in info.value.message and "Pkg::sys.i" in info.value.message
    assert info.value.location.file == "pkg.aadl"
    assert list(ws.instances) == []
    with pytest.raises(UsageError):
        instantiate(ws, "Pkg::sys.i", compatibility="osate-1")
    with pytest.raises(UsageError, match="not 42"):
        instantiate(ws, 42)
    assert instantiate(ws, "SYS.I").classifier == "Pkg::sys.i"  # unqualified, declared once
    assert COMPATIBILITY_MODES == ("current", "osate-2.0")


def test_unresolved_classifier_is_located_unless_lenient():
    ws = pipeline()
    impl = model.find_classifier(ws, "Pkg::sys.i")
    impl.subcomponents.append(
        new("Subcomponent", name="ghost", category="system", classifier="Gone::x", line=12)
    )
    with pytest.raises(NameResolutionError) as info:
        instantiate(ws, "Pkg::sys.i")
    location = info.value.location
    assert (location.file, location.line, location.path) == ("pkg.aadl", 12, "sys_i_Instance.ghost")
    assert "Gone::x" in info.value.message
    diagnostics = []
    system = instantiate(ws, "Pkg::sys.i", strict=False, diagnostics=diagnostics)
    ghost = model.find_instance(system, "ghost")
    assert ghost.classifier is None and ghost.category.name == "system"
    assert any("Gone::x" in d.message for d in diagnostics)


def test_containment_and_extends_cycles():
    ws = workspace(ctype("s", "system"), cimpl("s.i", "system", subs=[sub("me", "system", "s.i")]))
    with pytest.raises(NameResolutionError, match="containment cycle"):
        instantiate(ws, "Pkg::s.i")
    ws = workspace(
        ctype("s", "system"),
        cimpl("s.i", "system", extended="s.j", line=3),
        cimpl("s.j", "system", extended="s.i", line=4),
    )
    with pytest.raises(NameResolutionError, match="extends cycle") as info:
        instantiate(ws, "Pkg::s.i")
    assert info.value.location.line in (3, 4)


def test_huge_arrays_fail_instead_of_hanging(monkeypatch):
    from rosaadl.transforms.instantiate import hierarchy

    monkeypatch.setattr(hierarchy, "MAX_COMPONENT_INSTANCES", 50)
    ws = workspace(
        ctype("t", "thread"),
        ctype("s", "system"),
        cimpl("s.i", "system", subs=[sub("many", "thread", "t", dims=["1000000"])]),
    )
    with pytest.raises(ModelError, match="component instances"):
        instantiate(ws, "Pkg::s.i")


def test_compatibility_with_osate_2_0():
    ws = workspace(
        ctype("t", "thread", port("o", "out")),
        ctype("p", "process", port("o", "out")),
        cimpl("p.i", "process", subs=[sub("t", "thread", "t")], conns=[conn("up", "t.o", "o")]),
        ctype("s", "system"),
        cimpl("s.i", "system", subs=[sub("p", "process", "p.i")]),
    )
    diagnostics = []
    assert names(instantiate(ws, "Pkg::s.i", diagnostics=diagnostics)) == []
    assert any("could not continue connection" in d.message for d in diagnostics)
    legacy = instantiate(ws, "Pkg::s.i", compatibility="osate-2.0")
    assert names(legacy) == ["p.t.o -> p.o"]
    assert not legacy.connectionInstances[0].complete


def test_deterministic_and_round_trips(tmp_path):
    first = model.dumps_xmi(instantiate(pipeline(), "Pkg::sys.i"))
    second = model.dumps_xmi(instantiate(pipeline(), "Pkg::sys.i"))
    assert first == second
    ws = pipeline()
    instantiate(ws, "Pkg::sys.i")
    path = model.save(ws, tmp_path / "ws.xmi")
    again = model.load(path)
    assert model.model_equal(ws, again)
    thread = model.find_instance(again.instances[0], "p2.b")
    assert property_value(thread, "Actual_Processor_Binding") == [
        model.find_instance(again.instances[0], "cpu")
    ]


def test_factory_objects_equal_ordinary_ones():
    factory = Factory()
    made = factory.new("PropertyAssociation", property="P")
    value = factory.new("ModalPropertyValue")
    factory.set(value, "value", factory.new("IntegerValue", value=3, unit="ms"))
    factory.extend(value, "inModes", ["a", "b"])
    factory.extend(made, "ownedValues", [value])
    ordinary = new(
        "PropertyAssociation",
        property="P",
        ownedValues=[
            new("ModalPropertyValue", value=new("IntegerValue", value=3, unit="ms"), inModes=["a", "b"])
        ],
    )
    assert model.dumps_xmi(made) == model.dumps_xmi(ordinary)
    assert made.ownedValues[0].eContainer() is made and value.value.eContainer() is value
    made.ownedValues.clear()  # pyecore operations keep working on factory-made objects
    assert list(made.ownedValues) == [] and factory.made["IntegerValue"] == 1


def test_a_thousand_threads_quickly():
    from time import process_time

    ws = workspace(
        ctype("t", "thread", port("i", "in"), port("o", "out"), props=[pa("Period", ms(5))]),
        ctype("p", "process"),
        cimpl(
            "p.i",
            "process",
            subs=[sub(f"t{i}", "thread", "t") for i in range(100)],
            conns=[conn(f"c{i}", f"t{i}.o", f"t{i + 1}.i") for i in range(99)],
        ),
        ctype("s", "system"),
        cimpl("s.i", "system", subs=[sub(f"p{i}", "process", "p.i") for i in range(10)]),
    )
    start = process_time()
    system = instantiate(ws, "Pkg::s.i")
    elapsed = process_time() - start
    assert len(names(system)) == 990
    assert elapsed < 10  # about 0.3 s; a regression to per-object name resolution costs far more


# --------------------------------------------------------------------------- OSATE corpus

_CORPUS_CASES = list(OSATE_INSTANCE_DIRS)

#: Cases instantiated with options, and why (everything else runs with the defaults).
_OPTIONS = {
    # the package CarHardwarePlatform that types subcomponent ecu is not in the origin repository;
    # OSATE instantiated ecu without a classifier, which strict=False reproduces
    "ex-carsystem": {"strict": False},
}


def _osate_counts(system_element) -> tuple[int, int, int]:
    return (
        len(system_element.findall(".//componentInstance")) + 1,
        len(system_element.findall(".//featureInstance")),
        len(system_element.findall(".//connectionInstance")),
    )


def _root_name(system_element, instance_file: Path, units) -> tuple[str, Path]:
    """``Pkg::Type.impl`` and the source file named by the componentImplementation href."""
    link = system_element.find("componentImplementation")
    if link is None:
        link = system_element.find("systemImplementation")
    href = link.get("href")
    source, _, fragment = href.partition("#")
    source_path = (instance_file.parent / source).resolve()
    if fragment.startswith("/"):  # a position: //@ownedPublicSection/@ownedClassifier.N
        position = int(re.search(r"ownedClassifier\.(\d+)", fragment).group(1))
        unit = next(u for u in units if u.sourceFile and Path(u.sourceFile).resolve() == source_path)
        public = [c for c in unit.classifiers if c.visibility is None or c.visibility.name == "public"]
        return f"{unit.name}::{public[position].name}", source_path
    parts = fragment.split(".")
    return "::".join(parts[:-2]) + "::" + ".".join(parts[-2:]), source_path


@pytest.mark.parametrize("case", _CORPUS_CASES)
def test_osate_corpus_counts(corpus, case):
    folder = corpus / "osate" / "aaxl2" / case
    if not folder.is_dir():
        pytest.skip(f"{folder} not in the corpus")
    instance_file = next(folder.rglob("*Instance.aaxl2"))
    tree = etree.parse(str(instance_file), etree.XMLParser(resolve_entities=False, no_network=True))
    root = tree.getroot()
    system_element = (
        root
        if root.tag.endswith("SystemInstance")
        else next(e for e in root if e.tag.endswith("SystemInstance"))
    )
    link = system_element.find("componentImplementation")
    if link is None:
        link = system_element.find("systemImplementation")
    source = (instance_file.parent / link.get("href").partition("#")[0]).resolve()
    if not source.is_file():
        pytest.skip(f"the source of the root implementation ({source.name}) is not in the corpus")
    from rosaadl.importers import aadl_text

    files = sorted(p for p in folder.rglob("*") if p.suffix.lower() in (".aadl", ".aadl2"))
    # read without the reader's name check: several origin repositories lack packages that only
    # type features (data types, bus types), which OSATE left unresolved too; instantiation
    # reports what it needs itself
    ws = aadl_text.read_files(files, check=False, warnings=[])
    root_name, _ = _root_name(system_element, instance_file, ws.units)
    options = dict(_OPTIONS.get(case, {}))
    # files written by OSATE 2.0 refer to the root with the old systemImplementation element
    if system_element.find("systemImplementation") is not None:
        options["compatibility"] = "osate-2.0"
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    system = instantiate(ws, root_name, **options)
    ours = (
        1 + sum(1 for o in model.walk(system) if o.eClass.name == "ComponentInstance"),
        sum(1 for o in model.walk(system) if o.eClass.name == "FeatureInstance"),
        sum(1 for o in model.walk(system) if o.eClass.name == "ConnectionInstance"),
    )
    assert ours == _osate_counts(system_element), f"(components, features, connections) for {root_name}"
    if case in _STALE:
        return
    expected = sorted(_connection_key(e.get("name")) for e in system_element.iter("connectionInstance"))
    got = sorted(_connection_key(o.name) for o in model.walk(system) if o.eClass.name == "ConnectionInstance")
    assert got == expected
    # end-to-end flows: the kinds of instance objects they go through, in order
    kinds = {"FlowSpecificationInstance": "flowSpecification", "ConnectionInstance": "connectionInstance"}
    ours_flows = sorted(
        (flow.name, tuple(kinds.get(e.eClass.name, "componentInstance") for e in flow.flowElements))
        for o in model.walk(system)
        if o.eClass.name in ("SystemInstance", "ComponentInstance")
        for flow in o.endToEndFlows
    )
    assert ours_flows == _osate_flows(system_element)


def _osate_flows(system_element) -> list[tuple[str, tuple[str, ...]]]:
    """(name, kinds of the flow elements) of every end-to-end flow instance of an OSATE file; the
    elements are given by xmi:id or by a path such as ``//@componentInstance.1/@flowSpecification.0``."""
    xmi_id = "{http://www.omg.org/XMI}id"
    by_id = {e.get(xmi_id): e for e in system_element.iter() if e.get(xmi_id)}

    def element(ref: str):
        if not ref.startswith("/"):
            return by_id[ref]
        current = system_element
        for step in ref.strip("/").split("/"):
            tag, _, position = step.lstrip("@").partition(".")
            current = [child for child in current if child.tag == tag][int(position or 0)]
        return current

    flows = []
    for flow in system_element.iter("endToEndFlow"):
        if flow.get("name") is None:  # the link to the declaration, not an instance
            continue
        refs = (flow.get("flowElement") or "").split()
        flows.append((flow.get("name"), tuple(element(ref).tag for ref in refs)))
    return sorted(flows)


#: Instance files older than the sources copied beside them (same counts, renamed elements).
_STALE = {
    # the source names the features system_in_f/thread_in_f, the instance system_out_f/thread_out_f
    "osate2-emv2-annex-instance",
}


def _connection_key(name: str) -> str:
    """A connection instance name with the two ends of a bidirectional one in a fixed order: OSATE
    orders subcomponents by category (the typed lists of its metamodel), rosaadl by declaration,
    so the end found first, written first, can differ."""
    if " <-> " in name:
        return " <-> ".join(sorted(name.split(" <-> ")))
    return name


def test_corpus_case_list_is_complete(corpus):
    folder = corpus / "osate" / "aaxl2"
    if not folder.is_dir():
        pytest.skip("no OSATE corpus")
    with_instances = sorted(p.name for p in folder.iterdir() if any(p.rglob("*Instance.aaxl2")))
    assert with_instances == sorted(_CORPUS_CASES)
    assert os.sep not in "".join(_CORPUS_CASES)


_ORDERED = """
package Ordered
public
  bus net end net;
  memory ram end ram;
  processor cpu end cpu;
  process proc end proc;
  process implementation proc.fast end proc.fast;
  system top end top;
  system implementation top.base
    subcomponents
      app: process proc;
      cpu1: processor cpu;
      mem: memory ram;
      lan: bus net;
      other: process proc;
  end top.base;
  system implementation top.refined extends top.base
    subcomponents
      app: refined to process proc.fast;
      cpu0: processor cpu;
      can: bus net;
  end top.refined;
end Ordered;
"""


def test_subcomponents_are_instantiated_in_osate_s_order():
    """OSATE's getAllSubcomponents: the farthest ancestor's subcomponents first, each
    implementation's by category (aadl2.ecore's list order for its class), a refinement moved
    to its refining implementation; OSATE 2.0's files show the same order."""
    from rosaadl.importers.aadl_text import read_string

    ws = read_string(_ORDERED, "ordered.aadl")
    system = instantiate(ws, "Ordered::top.refined")
    assert [c.name for c in system.componentInstances] == [
        "lan",
        "mem",
        "other",
        "cpu1",
        "can",
        "app",
        "cpu0",
    ]
    assert model.find_instance(system, "app").classifier == "Ordered::proc.fast"
    legacy = instantiate(
        read_string(_ORDERED, "ordered.aadl"), "Ordered::top.refined", compatibility="osate-2.0"
    )
    assert [c.name for c in legacy.componentInstances] == [c.name for c in system.componentInstances]


_FEATURE_APPLICABILITY = """
package Applies
public
  with Timing_Properties, Thread_Properties;
  bus can end can;
  data msg end msg;
  device sensor
    features
      canbus: requires bus access can;
      sample: out data port msg;
      anybus: requires bus access;
      tap: feature can;
      raw: out data port;
    properties
      Period => 25 ms;
      Priority => 5;
  end sensor;
  system top end top;
  system implementation top.i
    subcomponents
      s: device sensor;
      net: bus can;
  end top.i;
end Applies;
"""


def _applicability(tmp_path, compatibility="current"):
    from rosaadl.importers.aadl_text import read_files

    source = tmp_path / "applies.aadl"
    source.write_text(_FEATURE_APPLICABILITY)
    return instantiate(read_files([source]), "Applies::top.i", compatibility=compatibility)


def test_features_take_the_properties_that_apply_to_their_own_category(tmp_path):
    """Period applies to bus, Priority to data: OSATE today gives neither to a bus access feature
    or a data port (the feature's metaclass decides); in OSATE 2.0 a bus access was a bus and a
    data port a data, and the inherited values reached the features."""
    current = _applicability(tmp_path)
    canbus, sample = model.find_instance(current, "s.canbus"), model.find_instance(current, "s.sample")
    assert property_value(model.find_instance(current, "s"), "Period") == Quantity(25, "ms")
    assert property_value(canbus, "Period") is None and property_value(sample, "Priority") is None
    legacy = _applicability(tmp_path, "osate-2.0")
    assert property_value(model.find_instance(legacy, "s.canbus"), "Period") == Quantity(25, "ms")
    assert property_value(model.find_instance(legacy, "s.sample"), "Priority") == 5


def test_osate_2_0_features_take_the_properties_of_their_metaclass_s_supertypes(tmp_path):
    """OSATE 2.0.1 to 2.0.8 (aadl2.ecore from osate2 #167, Feb 2013, to #486, Oct 2014) made a bus
    access a ``Bus``, a data access, data port and event data port a ``Data``: ``applies to (bus)``
    held for every bus access feature, with a classifier or without, and for no abstract feature,
    whatever its classifier. OSATE today goes by the feature's own metaclass only."""
    legacy = _applicability(tmp_path, "osate-2.0")
    assert property_value(model.find_instance(legacy, "s.anybus"), "Period") == Quantity(25, "ms")
    assert property_value(model.find_instance(legacy, "s.raw"), "Priority") == 5
    assert property_value(model.find_instance(legacy, "s.tap"), "Period") is None
    current = _applicability(tmp_path)
    for path, name in (("s.anybus", "Period"), ("s.raw", "Priority"), ("s.tap", "Period")):
        assert property_value(model.find_instance(current, path), name) is None


_FEATURES_ORDERED = """
package FOrdered
public
  bus net end net;
  data msg end msg;
  device base
    features
      cmd: in event port;
      lan: requires bus access net;
      sample: out data port msg;
  end base;
  device camera extends base
    features
      image: out event data port msg;
      power: feature;
  end camera;
  system top end top;
  system implementation top.i
    subcomponents
      cam: device camera;
  end top.i;
end FOrdered;
"""


def test_features_are_instantiated_in_osate_s_order():
    """OSATE's getAllFeatures: the farthest ancestor's features first, each type's by category in
    aadl2.ecore's list order for its class (a device: data, event data, event ports, then bus
    access; feature groups and abstract features before all)."""
    from rosaadl.importers.aadl_text import read_string

    system = instantiate(read_string(_FEATURES_ORDERED, "fordered.aadl"), "FOrdered::top.i")
    cam = model.find_instance(system, "cam")
    assert [f.name for f in cam.featureInstances] == ["sample", "cmd", "lan", "power", "image"]


def test_a_feature_group_member_is_found_by_name_or_else_by_position_at_either_end():
    """OSATE's findDestinationFeatureInstance / findSourceFeatureInstance: the member of the
    feature group at one end that matches the leaf the connection reached the other end's
    group through; by position when an inverse names its features differently."""
    from rosaadl.transforms.instantiate.connection_instances import ConnectionInfo
    from rosaadl.transforms.instantiate.feature_group_matching import find_member
    from rosaadl.transforms.instantiate.mirrors import FeatureMirror

    def fi(name, parent=None, children=()):
        node = FeatureMirror(None, None, name, name.lower(), 0, "eventPort", "out", None, parent)
        for child in children:
            child.parent = node
        node.children = list(children)
        return node

    p1, p2 = fi("p1"), fi("P2")
    outs = fi("fa", children=[p1, p2])  # the group the connection left through its member P2
    x = fi("x")
    same = fi("fb", children=[fi("p1"), fi("p2")])
    renamed = fi("fb", children=[fi("q1"), fi("q2")])
    # towards the destination: x -> fa.P2, then fa -> fb
    info = ConnectionInfo(x)
    info.sources, info.destinations = [x, outs], [p2, renamed]
    assert find_member(info, same, at_destination=True) is same.children[1]
    assert find_member(info, renamed, at_destination=True) is renamed.children[1]
    # towards the source, the mirror image: fb -> fa, then fa.P2 -> x
    info.sources, info.destinations = [renamed, p2], [outs, x]
    assert find_member(info, same, at_destination=False) is same.children[1]
    assert find_member(info, renamed, at_destination=False) is renamed.children[1]
    # no step leaves a feature group: nothing to narrow to
    info.sources, info.destinations = [x], [renamed]
    assert find_member(info, renamed, at_destination=True) is None

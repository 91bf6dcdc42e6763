"""The AADL text reader, construct by construct: every construct of AADL into the right model
attribute, property values of every form, positions, determinism, saving and loading.

The legality rules and bad input are in ``test_aadl_text_legality.py``; ``read_files``, the checks
across files, the library and the real corpus in ``test_aadl_text_files.py``."""

from __future__ import annotations

from pathlib import Path

import pytest
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import AadlSyntaxError, ValidationError
from rosaadl.importers.aadl_text import read_string

# --------------------------------------------------------------------------- a text using all of AADL

FULL_TEXT = """\
package Everything::Pkg
public
  with Base_Types, Other::Lib;
  with My_Props;
  Lib renames package Other::Lib;
  renames package Deep::Pkg::all;
  FGR renames feature group Other::Lib::FG;
  renames feature group Other::Lib::FG2;
  CTR renames thread Other::Lib::Worker;

  feature group FG
    prototypes
      fp: feature;
    features
      d: in data port Base_Types::Integer;
      pa: in parameter;
    inverse of Other::Lib::FGI
    properties
      My_Props::Flag => true;
  end FG;

  feature group FG2 extends FG (fp => in data port Base_Types::Float)
  end FG2;

  abstract A
    prototypes
      cp: refined to data Base_Types::Integer [];
      ftp: in feature Base_Types::Integer;
    features
      p1: in data port Base_Types::Integer [3] {Queue_Size => 4;};
      p2: out event data port;
      p3: in out event port;
      g1: in feature group inverse of FG;
      g2: feature group FG [2];
      af: feature prototype ftp;
      af2: out feature;
      da: provides data access Base_Types::Integer;
      ba: refined to requires bus access Other::Lib::B.impl;
      vba: requires virtual bus access;
      sa: provides subprogram access S;
      sga: requires subprogram group access;
    flows
      fsrc: flow source p2 {Latency => 1 ms .. 2 ms;};
      fsnk: flow sink p1 in modes (m1);
      fpth: flow path p1 -> p2;
      fref: refined to flow path {Latency => 3 ms .. 4 ms;};
    modes
      m1: initial mode;
      m2: mode {My_Props::Count => 2;};
      t1: m1 -[ p1, p3 ]-> m2;
      m2 -[ self.tick, processor.clk, g1.x ]-> m1;
    properties
      My_Props::Count => 1 in modes (m1), 2 in modes (m2);
    annex EMV2 {** use types ErrorLibrary; **};
    annex Behavior_Specification none;
  end A;

  abstract implementation A.impl extends A.base (cp => data Base_Types::Float, -- a comment
      sp => (subprogram S.i, subprogram S.j))
    prototypes
      none;
    subcomponents
      s1: system Other::Lib::Sys.impl;
      s2: refined to thread T.i (p => data D) [2][My_Props::Max] (T.i, T.j (q => data E))
        {Priority => 5;} in modes (m1 => m2, m2);
      s3: data;
    calls
      seq1: { k1: subprogram S.i; k2: subprogram processor.svc {My_Props::Count => 1;};
              k3: subprogram s1.acc; } {My_Props::Count => 9;} in modes (m1);
    connections
      c1: port p1 -> s2.p1 {Latency => 1 ms .. 2 ms;} in modes (m1);
      c2: data access da <-> s3;
      c3: access s1.x -> s2.y;
      c4: feature group g1 <-> s1.g;
      c5: feature af -> s1.f;
      c6: parameter s2.a -> s2.b;
      c7: refined to port {Latency => 1 ms .. 3 ms;};
      c8: port processor.clk -> s2.tick;
      c9: port self.ev -> s2.q[1];
      c10: port s2[1].out_p -> s2[2 .. 3].in_p;
      c11: virtual bus access vba -> s1.v;
      port p1 -> s2.p2;
    flows
      fpth: flow path p1 -> c1 -> s2.fp -> c2 -> p2;
      fsrc: flow source s2.src -> c3 -> p2;
      e2e: end to end flow s2.src -> c10 -> s2.snk {Latency => 0 ms .. 10 ms;} in modes (m1);
      e2e2: refined to end to end flow;
    modes
      m3: mode;
    properties
      Period => 10 ms;
      Timing_Properties::Deadline => 20 ms applies to s2, s2.p1;
      Priority => 3 applies to s2[1].t, s1.c[2 .. 3];
      Compute_Execution_Time +=> 1 ms .. 2 ms delta 0.5 ms applies to s2;
      My_Props::Count => constant 5;
      Actual_Processor_Binding => (reference (s1.cpu)) applies to s2 in binding (Other::Lib::CPU);
      My_Props::Rec => [Name => "a ""quoted"" \\"x\\""; Value => 16#FF#; Big => 2#1#e10;];
      My_Props::Cls => classifier (Other::Lib::Sys.impl);
      My_Props::Cmp => compute (my_function);
      My_Props::Bool => not true and (false or My_Props::Flag);
      My_Props::Neg => - My_Props::Max;
      My_Props::Lst => ((1, 2), ());
      My_Props::Annexed => 1 applies to s1.annex {** EMV2 **};
    annex EMV2 {** multi
      line **} in modes (m1);
  end A.impl;

  system Sys
    requires modes
      rm: initial mode;
  end Sys;
private
  with Private_Lib;
  renames Private_Lib::all;
  thread T
    features
      p: in data port;
  end T;

  thread implementation T.i
  end T.i;
  annex EMV2 {**lib**};
properties
  My_Props::Count => 7 applies to T;
end Everything::Pkg;

property set My_Props is
  with Other_Props;
  Count_Type: type aadlinteger 0 .. 100 units My_Props::Speed;
  Speed: type units (mps, kmph => mps * 3.6, fast => kmph * 10);
  Enum_T: type enumeration (one, two, three);
  R_Type: type range of aadlreal -1.0 .. 1.0;
  R2: type range of Count_Type;
  C_Type: type classifier (thread, system, Everything::Pkg::A.impl);
  C_All: type classifier;
  Ref_T: type reference (thread, event data port, {emv2}** error type);
  Rec_T: type record (f1: aadlinteger; f2: list of Enum_T; f3: record (x: aadlstring;););
  L_T: type list of list of aadlboolean;
  I2: type aadlinteger - 5 .. + Max;
  Count: inherit aadlinteger => 0 applies to (all);
  Flag: aadlboolean applies to (thread, thread group, end to end flow, Everything::Pkg::A);
  Rate: list of aadlreal units (Hz) => (1.0 Hz) applies to (system);
  Max: constant aadlinteger => 100;
  Min: constant aadlreal units AADL_Project::Time_Units => 1.5 ms;
end My_Props;
"""


@pytest.fixture(scope="module")
def full():
    return read_string(FULL_TEXT, "full.aadl")


def unit(m: EObject, name: str) -> EObject:
    found = [u for u in m.units if u.name == name]
    assert len(found) == 1, [u.name for u in m.units]
    return found[0]


def classifier(m: EObject, qualified: str) -> EObject:
    pkg, _, local = qualified.rpartition("::")
    found = [c for c in unit(m, pkg).classifiers if c.name == local]
    assert len(found) == 1, f"{qualified}: {[c.name for c in unit(m, pkg).classifiers]}"
    return found[0]


def member(owner: EObject, feature: str, name: str | None) -> EObject:
    found = [x for x in getattr(owner, feature) if x.name == name]
    assert len(found) == 1, f"{feature} {name}: {[x.name for x in getattr(owner, feature)]}"
    return found[0]


def literal(value) -> str:
    return value.name if value is not None else ""


def enum(obj: EObject, feature: str) -> str:
    """The name of an enumeration value that the reader set, "" when it set none."""
    return getattr(obj, feature).name if obj.eIsSet(feature) else ""


def py(value: EObject | None):
    """A property value as plain Python, to compare with what the text says."""
    if value is None:
        return None
    kind = value.eClass.name
    if kind in ("IntegerValue", "RealValue"):
        return (value.value, value.unit) if value.unit else value.value
    if kind in ("BooleanValue", "StringValue"):
        return value.value
    if kind == "NamedValue":
        return ("named", value.name)
    if kind == "ReferenceValue":
        return ("reference", value.path)
    if kind == "ClassifierValue":
        return ("classifier", value.classifier)
    if kind == "ComputedValue":
        return ("compute", value.function)
    if kind == "ListValue":
        return [py(item) for item in value.ownedItems]
    if kind == "RecordValue":
        return {field.name: py(field.value) for field in value.ownedFields}
    if kind == "RangeValue":
        return ("range", py(value.minimum), py(value.maximum), py(value.delta))
    if kind == "OperationValue":
        return (value.operator, *[py(op) for op in value.ownedOperands])
    raise AssertionError(kind)


def association(owner: EObject, prop: str, index: int = 0) -> EObject:
    found = [pa for pa in owner.ownedPropertyAssociations if pa.property == prop]
    assert len(found) > index, [pa.property for pa in owner.ownedPropertyAssociations]
    return found[index]


def value_of(owner: EObject, prop: str, index: int = 0):
    pa = association(owner, prop, index)
    assert len(pa.ownedValues) == 1 and not pa.ownedValues[0].inModes
    return py(pa.ownedValues[0].value)


# --------------------------------------------------------------------------- packages and classifiers


def test_units_and_package_parts(full) -> None:
    assert [u.name for u in full.units] == ["Everything::Pkg", "My_Props"]
    pkg = unit(full, "Everything::Pkg")
    assert list(pkg.withs) == ["Base_Types", "Other::Lib", "My_Props"]
    assert list(pkg.privateWiths) == ["Private_Lib"]
    assert all(u.sourceFile == "full.aadl" for u in full.units)
    renamings = [
        (r.name, enum(r, "kind"), r.target, enum(r, "category"), enum(r, "visibility")) for r in pkg.renamings
    ]
    assert renamings == [
        ("Lib", "package", "Other::Lib", "", "public"),
        (None, "all", "Deep::Pkg", "", "public"),
        ("FGR", "featureGroupType", "Other::Lib::FG", "", "public"),
        (None, "featureGroupType", "Other::Lib::FG2", "", "public"),
        ("CTR", "classifier", "Other::Lib::Worker", "thread", "public"),
        (None, "all", "Private_Lib", "", "private"),
    ]
    assert [(a.name, a.text, enum(a, "visibility")) for a in pkg.annexLibraries] == [
        ("EMV2", "lib", "private")
    ]
    assert value_of(pkg, "My_Props::Count") == 7
    assert list(association(pkg, "My_Props::Count").appliesTo) == ["T"]
    visibility = {c.name: enum(c, "visibility") for c in pkg.classifiers}
    assert visibility == {
        "FG": "public",
        "FG2": "public",
        "A": "public",
        "A.impl": "public",
        "Sys": "public",
        "T": "private",
        "T.i": "private",
    }


def test_feature_group_types(full) -> None:
    fg = classifier(full, "Everything::Pkg::FG")
    assert fg.eClass.name == "FeatureGroupType"
    assert fg.inverseOf == "Other::Lib::FGI"
    assert [(f.name, enum(f, "category"), enum(f, "direction")) for f in fg.features] == [
        ("d", "dataPort", "in"),
        ("pa", "parameter", "in"),
    ]
    assert [(p.name, p.text) for p in fg.prototypes] == [("fp", "feature")]
    assert value_of(fg, "My_Props::Flag") is True
    fg2 = classifier(full, "Everything::Pkg::FG2")
    assert fg2.extended == "FG"
    assert fg2.prototypeBindings == "(fp => in data port Base_Types::Float)"


def test_component_type_features(full) -> None:
    a = classifier(full, "Everything::Pkg::A")
    assert a.eClass.name == "ComponentType" and enum(a, "category") == "abstract"
    rows = [
        (
            f.name,
            enum(f, "category"),
            enum(f, "direction"),
            enum(f, "access"),
            f.classifier,
            list(f.arrayDimensions),
            bool(f.refined),
            bool(f.inverse),
        )
        for f in a.features
    ]
    assert rows == [
        ("p1", "dataPort", "in", "", "Base_Types::Integer", ["3"], False, False),
        ("p2", "eventDataPort", "out", "", None, [], False, False),
        ("p3", "eventPort", "inOut", "", None, [], False, False),
        ("g1", "featureGroup", "in", "", "FG", [], False, True),
        ("g2", "featureGroup", "inOut", "", "FG", ["2"], False, False),
        ("af", "abstractFeature", "inOut", "", "prototype ftp", [], False, False),
        ("af2", "abstractFeature", "out", "", None, [], False, False),
        ("da", "dataAccess", "", "provides", "Base_Types::Integer", [], False, False),
        ("ba", "busAccess", "", "requires", "Other::Lib::B.impl", [], True, False),
        ("vba", "virtualBusAccess", "", "requires", None, [], False, False),
        ("sa", "subprogramAccess", "", "provides", "S", [], False, False),
        ("sga", "subprogramGroupAccess", "", "requires", None, [], False, False),
    ]
    p1 = member(a, "features", "p1")
    assert value_of(p1, "Queue_Size") == 4
    # without a direction, a feature group or abstract feature goes both ways; one that refines
    # another keeps the direction it refines
    text = (
        "package P\npublic\n"
        "system S features g: refined to feature group; a: refined to feature; end S;\nend P;\n"
    )
    m = read_string(text, "r")
    assert [f.eIsSet("direction") for f in m.units[0].classifiers[0].features] == [False, False]


def test_prototypes_are_kept_as_text_with_a_warning() -> None:
    warnings: list = []
    m = read_string(FULL_TEXT, "full.aadl", warnings=warnings)
    a = classifier(m, "Everything::Pkg::A")
    assert [(p.name, p.text, bool(p.refined)) for p in a.prototypes] == [
        ("cp", "data Base_Types::Integer []", True),
        ("ftp", "in feature Base_Types::Integer", False),
    ]
    impl = classifier(m, "Everything::Pkg::A.impl")
    assert impl.prototypeBindings == "(cp => data Base_Types::Float, sp => (subprogram S.i, subprogram S.j))"
    assert list(impl.prototypes) == []  # "prototypes none;"
    messages = [w for w in warnings if "prototypes are kept" in w.message]
    assert [(w.location.file, w.location.line) for w in messages] == [("full.aadl", 13), ("full.aadl", 27)]


def test_flow_specifications_modes_and_annexes(full) -> None:
    a = classifier(full, "Everything::Pkg::A")
    flows = [
        (f.name, enum(f, "kind"), f.inEnd, f.outEnd, bool(f.refined), list(f.inModes))
        for f in a.flowSpecifications
    ]
    assert flows == [
        ("fsrc", "source", None, "p2", False, []),
        ("fsnk", "sink", "p1", None, False, ["m1"]),
        ("fpth", "path", "p1", "p2", False, []),
        ("fref", "path", None, None, True, []),
    ]
    assert value_of(member(a, "flowSpecifications", "fsrc"), "Latency") == (
        "range",
        (1, "ms"),
        (2, "ms"),
        None,
    )
    assert [(m.name, bool(m.initial)) for m in a.modes] == [("m1", True), ("m2", False)]
    assert value_of(member(a, "modes", "m2"), "My_Props::Count") == 2
    transitions = [(t.name, t.source, list(t.triggers), t.destination) for t in a.modeTransitions]
    assert transitions == [
        ("t1", "m1", ["p1", "p3"], "m2"),
        (None, "m2", ["self.tick", "processor.clk", "g1.x"], "m1"),
    ]
    modal = association(a, "My_Props::Count")
    assert [(py(v.value), list(v.inModes)) for v in modal.ownedValues] == [(1, ["m1"]), (2, ["m2"])]
    assert [(x.name, x.text, list(x.inModes)) for x in a.annexSubclauses] == [
        ("EMV2", " use types ErrorLibrary; ", []),
        ("Behavior_Specification", None, []),
    ]
    sys_type = classifier(full, "Everything::Pkg::Sys")
    assert sys_type.requiresModes is True and [m.name for m in sys_type.modes] == ["rm"]


def test_implementation_parts(full) -> None:
    impl = classifier(full, "Everything::Pkg::A.impl")
    assert (impl.name, impl.type, impl.extended, enum(impl, "category")) == (
        "A.impl",
        "A",
        "A.base",
        "abstract",
    )
    s2 = member(impl, "subcomponents", "s2")
    assert (enum(s2, "category"), s2.classifier, bool(s2.refined)) == ("thread", "T.i", True)
    assert s2.prototypeBindings == "(p => data D)"
    assert list(s2.arrayDimensions) == ["2", "My_Props::Max"]
    assert list(s2.arrayElementBindings) == ["T.i", "T.j (q => data E)"]
    assert list(s2.inModes) == ["m1 => m2", "m2"]
    assert value_of(s2, "Priority") == 5
    s3 = member(impl, "subcomponents", "s3")
    assert (enum(s3, "category"), s3.classifier) == ("data", None)
    (seq,) = impl.callSequences
    assert (seq.name, list(seq.inModes), value_of(seq, "My_Props::Count")) == ("seq1", ["m1"], 9)
    assert [(c.name, c.called) for c in seq.calls] == [
        ("k1", "S.i"),
        ("k2", "processor.svc"),
        ("k3", "s1.acc"),
    ]
    assert value_of(seq.calls[1], "My_Props::Count") == 1
    assert [m.name for m in impl.modes] == ["m3"]
    assert [(x.name, x.text, list(x.inModes)) for x in impl.annexSubclauses] == [
        ("EMV2", " multi\n      line ", ["m1"])
    ]


def test_connections(full) -> None:
    impl = classifier(full, "Everything::Pkg::A.impl")
    rows = [
        (
            c.name,
            enum(c, "kind"),
            enum(c, "accessCategory"),
            c.source,
            c.destination,
            bool(c.bidirectional),
            bool(c.refined),
            list(c.inModes),
        )
        for c in impl.connections
    ]
    assert rows == [
        ("c1", "portConnection", "", "p1", "s2.p1", False, False, ["m1"]),
        ("c2", "accessConnection", "data", "da", "s3", True, False, []),
        ("c3", "accessConnection", "", "s1.x", "s2.y", False, False, []),
        ("c4", "featureGroupConnection", "", "g1", "s1.g", True, False, []),
        ("c5", "featureConnection", "", "af", "s1.f", False, False, []),
        ("c6", "parameterConnection", "", "s2.a", "s2.b", False, False, []),
        ("c7", "portConnection", "", None, None, False, True, []),
        ("c8", "portConnection", "", "processor.clk", "s2.tick", False, False, []),
        ("c9", "portConnection", "", "self.ev", "s2.q[1]", False, False, []),
        ("c10", "portConnection", "", "s2[1].out_p", "s2[2 .. 3].in_p", False, False, []),
        ("c11", "accessConnection", "virtualBus", "vba", "s1.v", False, False, []),
        (None, "portConnection", "", "p1", "s2.p2", False, False, []),
    ]
    assert value_of(member(impl, "connections", "c7"), "Latency") == ("range", (1, "ms"), (3, "ms"), None)
    unnamed = impl.connections[-1]
    assert (unnamed.line, unnamed.column) == (82, 7)


def test_flow_implementations_and_end_to_end_flows(full) -> None:
    impl = classifier(full, "Everything::Pkg::A.impl")
    assert [(f.name, enum(f, "kind"), list(f.elements)) for f in impl.flowImplementations] == [
        ("fpth", "path", ["p1", "c1", "s2.fp", "c2", "p2"]),
        ("fsrc", "source", ["s2.src", "c3", "p2"]),
    ]
    e2e = [(f.name, list(f.elements), bool(f.refined), list(f.inModes)) for f in impl.endToEndFlows]
    assert e2e == [
        ("e2e", ["s2.src", "c10", "s2.snk"], False, ["m1"]),
        ("e2e2", [], True, []),
    ]
    assert value_of(impl.endToEndFlows[0], "Latency") == ("range", (0, "ms"), (10, "ms"), None)


def test_property_associations(full) -> None:
    impl = classifier(full, "Everything::Pkg::A.impl")
    assert value_of(impl, "Period") == (10, "ms")
    deadline = association(impl, "Timing_Properties::Deadline")
    assert list(deadline.appliesTo) == ["s2", "s2.p1"]
    assert list(association(impl, "Priority").appliesTo) == ["s2[1].t", "s1.c[2 .. 3]"]
    cet = association(impl, "Compute_Execution_Time")
    assert cet.append is True and not cet.constant
    assert value_of(impl, "Compute_Execution_Time") == ("range", (1, "ms"), (2, "ms"), (0.5, "ms"))
    count = association(impl, "My_Props::Count")
    assert count.constant is True and not count.append and value_of(impl, "My_Props::Count") == 5
    binding = association(impl, "Actual_Processor_Binding")
    assert value_of(impl, "Actual_Processor_Binding") == [("reference", "s1.cpu")]
    assert list(binding.inBinding) == ["Other::Lib::CPU"]
    assert value_of(impl, "My_Props::Rec") == {"Name": 'a "quoted" "x"', "Value": 255, "Big": 1024}
    assert value_of(impl, "My_Props::Cls") == ("classifier", "Other::Lib::Sys.impl")
    assert value_of(impl, "My_Props::Cmp") == ("compute", "my_function")
    assert value_of(impl, "My_Props::Bool") == (
        "and",
        ("not", True),
        ("or", False, ("named", "My_Props::Flag")),
    )
    assert value_of(impl, "My_Props::Neg") == ("-", ("named", "My_Props::Max"))
    assert value_of(impl, "My_Props::Lst") == [[1, 2], []]
    assert list(association(impl, "My_Props::Annexed").appliesTo) == ["s1.annex {** EMV2 **}"]


def test_property_set(full) -> None:
    ps = unit(full, "My_Props")
    assert ps.eClass.name == "PropertySet" and list(ps.withs) == ["Other_Props"]
    types = {t.name: t for t in ps.ownedPropertyTypes}
    assert list(types) == [
        "Count_Type",
        "Speed",
        "Enum_T",
        "R_Type",
        "R2",
        "C_Type",
        "C_All",
        "Ref_T",
        "Rec_T",
        "L_T",
        "I2",
    ]
    count_type = types["Count_Type"]
    assert count_type.eClass.name == "AadlInteger" and count_type.unitsType == "My_Props::Speed"
    assert py(count_type.range) == ("range", 0, 100, None)
    speed = [(u.name, u.baseUnit, py(u.factor)) for u in types["Speed"].ownedLiterals]
    assert speed == [("mps", None, None), ("kmph", "mps", 3.6), ("fast", "kmph", 10)]
    assert [lit.name for lit in types["Enum_T"].ownedLiterals] == ["one", "two", "three"]
    r_type = types["R_Type"]
    assert r_type.eClass.name == "RangeType" and r_type.ownedNumberType.eClass.name == "AadlReal"
    assert py(r_type.ownedNumberType.range) == ("range", -1.0, 1.0, None)
    assert types["R2"].numberType == "Count_Type"
    assert list(types["C_Type"].categories) == ["thread", "system", "Everything::Pkg::A.impl"]
    assert list(types["C_All"].categories) == []
    assert list(types["Ref_T"].categories) == ["thread", "event data port", "{emv2}** error type"]
    fields = types["Rec_T"].ownedFields
    assert [f.name for f in fields] == ["f1", "f2", "f3"]
    assert fields[0].ownedType.eClass.name == "AadlInteger"
    assert fields[1].ownedType.eClass.name == "ListType" and fields[1].ownedType.elementType == "Enum_T"
    assert fields[2].ownedType.ownedFields[0].ownedType.eClass.name == "AadlString"
    inner = types["L_T"].ownedElementType
    assert inner.eClass.name == "ListType" and inner.ownedElementType.eClass.name == "AadlBoolean"
    assert py(types["I2"].range) == ("range", -5, ("+", ("named", "Max")), None)

    props = {p.name: p for p in ps.ownedProperties}
    assert list(props) == ["Count", "Flag", "Rate"]
    assert props["Count"].inherit is True and list(props["Count"].appliesTo) == ["all"]
    assert py(props["Count"].defaultValue) == 0
    assert not props["Flag"].inherit and props["Flag"].defaultValue is None
    assert list(props["Flag"].appliesTo) == [
        "thread",
        "thread group",
        "end to end flow",
        "Everything::Pkg::A",
    ]
    rate = props["Rate"].ownedType
    assert (
        rate.eClass.name == "ListType" and rate.ownedElementType.ownedUnitsType.ownedLiterals[0].name == "Hz"
    )
    assert py(props["Rate"].defaultValue) == [(1.0, "Hz")]
    consts = {c.name: c for c in ps.ownedPropertyConstants}
    assert list(consts) == ["Max", "Min"]
    assert py(consts["Max"].value) == 100 and consts["Max"].ownedType.eClass.name == "AadlInteger"
    assert consts["Min"].ownedType.unitsType == "AADL_Project::Time_Units" and py(consts["Min"].value) == (
        1.5,
        "ms",
    )


def test_every_element_is_located(full) -> None:
    count = 0
    for obj in model.walk(full):
        if obj is full:
            continue
        assert obj.eClass.findEStructuralFeature("line") is not None
        assert obj.line >= 1 and obj.column >= 1, (
            f"{obj.eClass.name} {getattr(obj, 'name', '')} has no position"
        )
        count += 1
    assert count > 200
    # a few exact positions (1-based line and column of the first character)
    a = classifier(full, "Everything::Pkg::A")
    assert (a.line, a.column) == (25, 12)
    p1 = member(a, "features", "p1")
    queue = association(p1, "Queue_Size")
    assert (p1.line, p1.column, queue.line, queue.column) == (30, 7, 30, 49)
    assert (queue.ownedValues[0].value.line, queue.ownedValues[0].value.column) == (30, 63)
    count_type = unit(full, "My_Props").ownedProperties[0].ownedType
    assert (count_type.line, count_type.column) == (140, 18)  # the 'aadlinteger' keyword


def test_reading_is_deterministic() -> None:
    first = model.dumps_xmi(read_string(FULL_TEXT, "full.aadl"))
    second = model.dumps_xmi(read_string(FULL_TEXT, "full.aadl"))
    assert first == second


def test_the_model_saves_and_loads(tmp_path: Path, full) -> None:
    saved = model.save(full, tmp_path / "full.xmi")
    again = model.load(saved)
    assert model.model_differences(full, again) == []


def test_read_string_adds_to_a_model_and_leaves_it_alone_on_error() -> None:
    m = read_string("package A public system S end S; end A;", "a.aadl")
    read_string(b"property set B is end B;", "b.aadl", model=m)
    assert [(u.name, u.sourceFile) for u in m.units] == [("A", "a.aadl"), ("B", "b.aadl")]
    with pytest.raises(AadlSyntaxError):
        read_string("package C public system S end S; end C; garbage", "c.aadl", model=m)
    with pytest.raises(ValidationError):
        read_string("package C public thread T end U; end C;", "c.aadl", model=m)
    assert [u.name for u in m.units] == ["A", "B"]


# --------------------------------------------------------------------------- values


def _value(text: str):
    m = read_string(f"package P public system S properties X::Y => {text}; end S; end P;", "v.aadl")
    (pa,) = m.units[0].classifiers[0].ownedPropertyAssociations
    return [(py(v.value), list(v.inModes)) for v in pa.ownedValues]


VALUES = [
    ("42", 42),
    ("1_000_000", 1_000_000),
    ("-7", -7),
    ("+7", 7),
    ("16#FF#", 255),
    ("16#ff_ff#", 65535),
    ("2#1010#", 10),
    ("8#777#", 511),
    ("2#1#e10", 1024),
    ("1e3", 1000),
    ("1E+6 us", (1_000_000, "us")),
    ("9223372036854775807", 2**63 - 1),
    ("-9223372036854775808", -(2**63)),
    ("2.5", 2.5),
    ("-0.5e-3 s", (-0.0005, "s")),
    ("1_0.2_5", 10.25),
    ("1.0e10", 1.0e10),
    ("true", True),
    ("FALSE", False),
    ('"text"', "text"),
    ('""', ""),
    ('"say ""hi"""', 'say "hi"'),
    (r'"a\tb\\c\"d\u0041"', 'a\tb\\c"dA'),
    ("Periodic", ("named", "Periodic")),
    ("AADL_Project::Max_Word", ("named", "AADL_Project::Max_Word")),
    ("-Max", ("-", ("named", "Max"))),
    ("+Pkg::Max", ("+", ("named", "Pkg::Max"))),
    ("reference (a.b[3].c)", ("reference", "a.b[3].c")),
    ("classifier (P::T.i)", ("classifier", "P::T.i")),
    ("compute (f)", ("compute", "f")),
    ("()", []),
    ("(1, 2 ms, (3))", [1, (2, "ms"), [3]]),
    ("[a => 1; b => [c => x;];]", {"a": 1, "b": {"c": ("named", "x")}}),
    ("1 ms .. 2 ms", ("range", (1, "ms"), (2, "ms"), None)),
    ("-1 .. Max delta 2", ("range", -1, ("named", "Max"), 2)),
    ("not true", ("not", True)),
    ("true and false or not A", ("or", ("and", True, False), ("not", ("named", "A")))),
    ("true and (false or A)", ("and", True, ("or", False, ("named", "A")))),
]


@pytest.mark.parametrize(("text", "expected"), VALUES, ids=[v[0] for v in VALUES])
def test_value_forms(text: str, expected) -> None:
    assert _value(text) == [(expected, [])]


def test_value_kinds_are_typed() -> None:
    m = read_string("package P public system S properties X::A => 3; X::B => 3.0; end S; end P;", "k.aadl")
    values = [pa.ownedValues[0].value for pa in m.units[0].classifiers[0].ownedPropertyAssociations]
    assert [(v.eClass.name, type(v.value)) for v in values] == [("IntegerValue", int), ("RealValue", float)]


def test_modal_values() -> None:
    assert _value("1 in modes (a), 2 in modes (b, c)") == [(1, ["a"]), (2, ["b", "c"])]
    assert _value("(1 in modes (a), 2)") == [(1, ["a"]), (2, [])]


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("9223372036854775808", "does not fit in 64 bits"),
        ("-9223372036854775809", "does not fit in 64 bits"),
        ("16#10000000000000000#", "does not fit in 64 bits"),
        ("1e99999999", "does not fit in 64 bits"),
        ("9" * 100_000, "does not fit in 64 bits"),
        ("2#102#", "not base-2 digits"),
        ("17#1#", "base of 17#1# must be 2 .. 16"),
        ("1.0e999", "out of range"),
        ("(" * 200 + "1" + ")" * 200, "nested more than"),
    ],
    ids=["above-max", "below-min", "based", "exponent", "many-digits", "digit", "base", "real", "nesting"],
)
def test_values_out_of_range_are_located_errors(text: str, fragment: str) -> None:
    with pytest.raises(AadlSyntaxError) as info:
        _value(text)
    assert fragment in info.value.message
    assert info.value.location.file == "v.aadl" and info.value.location.line == 1
    assert info.value.location.column >= 44

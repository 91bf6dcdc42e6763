"""OSATE .aaxl2 export: format details, hrefs that resolve into the sidecars, bad input.

The model here is this project's own small AADL text (two packages' worth of classifiers, a
user property set with units, an enumeration, a record and a list, modes, arrays, feature groups
with ``inverse of``, access and bidirectional connections). Every positional reference of the
exported file is resolved again, independently of the exporter, by reading the written sidecars
back with the AADL reader and counting members the way OSATE's Xtext model holds them.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
from lxml import etree

from rosaadl import model
from rosaadl.errors import ExportError, RosaadlError
from rosaadl.exporters.aaxl2 import (
    INSTANCES_FOLDER,
    dumps_aaxl2,
    export_aaxl2,
    instance_file_name,
    java_double,
    write_aaxl2,
)
from rosaadl.importers import osate_eras
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.aaxl2 import loads_aaxl2, read_aaxl2
from rosaadl.properties import EnumLiteral, Range, own_property
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity

ROOT = "demo::top::top.impl"

DEMO = """\
package demo::top
public
  with demo_props;

  data msg
    properties
      Data_Size => 24 Bytes;
  end msg;

  feature group io
    features
      din: in data port msg;
      dout: out event data port msg;
  end io;

  feature group io_inv
    inverse of io
  end io_inv;

  thread worker
    features
      inp: in event data port msg;
      outp: out event data port msg;
      shared: requires data access msg;
      grp: feature group io;
      trig: in event port;
      anyo: out feature;
      anyi: in feature;
    flows
      f1: flow path inp -> outp;
    properties
      Dispatch_Protocol => Periodic;
      Period => 10 ms;
      Compute_Execution_Time => 1 ms .. 2 ms;
  end worker;

  thread implementation worker.impl
  end worker.impl;

  thread implementation worker.fast extends worker.impl
    properties
      Period => 2500 us;
  end worker.fast;

  process app
    features
      inp: in event data port msg;
      outp: out event data port msg;
      grp: feature group io_inv;
      anyo: out feature;
      anyi: in feature;
  end app;

  process implementation app.impl
    subcomponents
      w: thread worker.impl;
      buf: data msg;
      pool: thread worker.fast[2];
    connections
      c1: port inp -> w.inp;
      c2: port w.outp -> outp;
      c3: data access buf -> w.shared;
      c4: feature group w.grp -> grp;
      c5: feature w.anyo -> anyo;
      c6: feature anyi -> w.anyi;
  end app.impl;

  processor cpu
    features
      net: requires bus access eth;
  end cpu;

  bus eth
  end eth;

  system top
  end top;

  system implementation top.impl
    subcomponents
      a: process app.impl;
      b: process app.impl in modes (nominal);
      cpu1: processor cpu;
      lan: bus eth;
    connections
      ab: port a.outp -> b.inp in modes (nominal);
      nb: bus access lan <-> cpu1.net;
      fa: feature a.anyo -> b.anyi;
    modes
      nominal: initial mode;
      degraded: mode;
    properties
      Actual_Processor_Binding => (reference (cpu1)) applies to a, b;
      Actual_Connection_Binding => (reference (lan)) applies to ab;
      Priority => 5 in modes (nominal), 7 in modes (degraded) applies to a;
      demo_props::Level => high applies to a;
      demo_props::Budget => 5 KB applies to a.w;
      demo_props::Window => [Start => 1 ms; Kind => soft;] applies to b;
      demo_props::Tags => ("x", "y");
      demo_props::Ratio => 0.0001;
      demo_props::Note => "caf\u00e9 & <co> ""quoted""\tend";
  end top.impl;
private
  data hidden
  end hidden;

  system implementation top.spare
    subcomponents
      h: data hidden;
  end top.spare;
end demo::top;
"""

PROPS = """\
property set demo_props is
  Size_Units: type units (B, KB => B * 1000);
  Level: enumeration (low, high) applies to (all);
  Budget: aadlinteger units demo_props::Size_Units applies to (all);
  Window: record (Start: AADL_Project::Time; Kind: enumeration (soft, hard);) applies to (all);
  Tags: list of aadlstring applies to (all);
  Note: aadlstring applies to (all);
  Ratio: aadlreal applies to (all);
end demo_props;
"""


@pytest.fixture(scope="module")
def workspace(tmp_path_factory) -> model.EObject:
    folder = tmp_path_factory.mktemp("demo")
    (folder / "demo.aadl").write_text(DEMO, encoding="utf-8")
    (folder / "demo_props.aadl").write_text(PROPS, encoding="utf-8")
    return read_files([folder], warnings=[])


@pytest.fixture(scope="module")
def instance(workspace):
    system = instantiate(workspace, ROOT)
    yield system
    workspace.instances.remove(system)


@pytest.fixture(scope="module")
def exported(instance):
    return export_aaxl2(instance)


@pytest.fixture(scope="module")
def written(instance, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("out")
    return write_aaxl2(instance, out)


XSI = "http://www.w3.org/2001/XMLSchema-instance"


def _tree(data: bytes) -> etree._Element:
    return etree.fromstring(data)


# ----------------------------------------------------------------------------- text forms


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (100.0, "100.0"),
        (0.5, "0.5"),
        (1.0e7, "1.0E7"),
        (12345678.9, "1.23456789E7"),
        (0.001, "0.001"),
        (0.0001, "1.0E-4"),
        (-2.5e-5, "-2.5E-5"),
        (123.456, "123.456"),
        (9999999.0, "9999999.0"),
        (0.0, "0.0"),
        (-0.0, "-0.0"),
        (float("inf"), "Infinity"),
    ],
)
def test_reals_are_written_as_java_writes_them(value: float, text: str) -> None:
    assert java_double(value) == text


def test_document_head_namespaces_and_encoding(exported) -> None:
    text = exported.data.decode("ascii")  # pure ASCII
    assert text.startswith(
        '<?xml version="1.0" encoding="ASCII"?>\n<instance:SystemInstance xmi:version="2.0" '
    )
    head = text.splitlines()[1]
    prefixes = re.findall(r"xmlns:(\w+)=", head)
    assert prefixes == ["xmi", "xsi", "aadl2", "instance"]
    assert head.endswith('name="top_impl_Instance" category="system">')
    assert text.endswith("</instance:SystemInstance>\n")


def test_non_ascii_and_markup_are_character_references(exported) -> None:
    text = exported.data.decode("ascii")
    assert 'value="caf&#xE9; &amp; &lt;co> &quot;quoted&quot;&#x9;end"' in text
    assert 'name="lan &lt;-> cpu1.net"' in text  # '>' stays as is, as EMF writes it
    again = loads_aaxl2(exported.data)
    assert own_property(again.root, "demo_props::Note") == 'caf\u00e9 & <co> "quoted"\tend'


def test_emf_defaults_are_left_out(exported) -> None:
    root = _tree(exported.data)
    features = {f.get("name"): f for f in root.iter("featureInstance")}
    assert "category" not in features["din"].attrib  # data port
    assert "direction" not in features["din"].attrib  # in
    assert features["dout"].get("direction") == "out"
    assert features["anyo"].get("category") == "abstractFeature"
    assert features["shared"].get("direction") == "in out"  # access features: in out, Java literal
    assert features["grp"].get("category") == "featureGroup"
    for component in root.iter("componentInstance"):
        assert component.get("category") != "abstract"
    connections = {c.get("name"): c for c in root.iter("connectionInstance")}
    port = connections["a.w.outp -> b.w.inp"]
    assert port.get("kind") == "portConnection" and port.get("complete") == "true"
    assert "bidirectional" not in port.attrib
    assert connections["lan <-> cpu1.net"].get("bidirectional") == "true"
    assert "kind" not in connections["a.w.anyo -> b.w.anyi"].attrib  # a feature connection
    modes = {m.get("name"): m for m in root.iter("modeInstance")}
    assert modes["nominal"].get("initial") == "true" and "initial" not in modes["degraded"].attrib
    # a number that is zero has no value attribute; booleans false are not written
    assert ' value="0"' not in exported.data.decode() and 'reverse="false"' not in exported.data.decode()


def test_index_children_and_array_elements(exported) -> None:
    root = _tree(exported.data)
    assert root.find("index") is None  # the root is not an element of anything
    a = next(c for c in root if c.get("name") == "a")
    assert [i.text for i in a.findall("index")] == ["0"]
    pool = [c for c in a.findall("componentInstance") if c.get("name") == "pool"]
    assert [[i.text for i in p.findall("index")] for p in pool] == [["1"], ["2"]]


def test_element_and_attribute_order(exported) -> None:
    root = _tree(exported.data)
    a = next(c for c in root if c.get("name") == "a")
    tags = [child.tag for child in a]
    expected = ["ownedPropertyAssociation", "featureInstance", "componentInstance", "connectionInstance"]
    expected += ["subcomponent", "index", "classifier"]
    assert [t for i, t in enumerate(tags) if i == 0 or tags[i - 1] != t] == expected
    top = [child.tag for child in root]
    assert top[-4:] == ["classifier", "systemOperationMode", "systemOperationMode", "componentImplementation"]
    connection = next(root.iter("connectionInstance"))
    assert list(connection.attrib)[-3:] == ["kind", "destination", "source"]


def test_units_and_enumerations_of_osate_sets_are_current_era_positions(exported) -> None:
    table = osate_eras.table(osate_eras.CURRENT_ERA)
    hrefs = [e.get("href") for e in _tree(exported.data).iter("unit", "namedValue")]
    osate = [h for h in hrefs if h.startswith("platform:/plugin/")]
    assert osate, "expected references into OSATE's property sets"
    decoded = set()
    for href in osate:
        uri, _, fragment = href.partition("#")
        assert fragment.startswith("/0/@")
        found = osate_eras.classify_uri(uri)
        assert found is not None and osate_eras.CURRENT_ERA in found.eras
        literal = table.literal(found.property_set, osate_eras.normalize_fragment(fragment))
        assert literal is not None, href
        decoded.add((literal.type_name, literal.name))
    assert ("AADL_Project::Time_Units", "ms") in decoded
    assert ("AADL_Project::Time_Units", "us") in decoded
    assert ("AADL_Project::Size_Units", "Bytes") in decoded
    assert ("AADL_Project::Supported_Dispatch_Protocols", "Periodic") in decoded
    sei = "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/"
    assert any(
        h.startswith(sei + "AADL_Project.aadl#/0/@ownedPropertyType.16/@ownedLiteral.3") for h in osate
    )


def test_values_read_back(exported, instance) -> None:
    again = loads_aaxl2(exported.data).root
    worker = model.find_instance(again, "a.w")
    assert own_property(worker, "Period") == Quantity(10, "ms")
    assert own_property(worker, "Compute_Execution_Time") == Range(Quantity(1, "ms"), Quantity(2, "ms"))
    assert own_property(worker, "Dispatch_Protocol") == EnumLiteral("Periodic")
    assert own_property(model.find_instance(again, "a.pool[2]"), "Period") == Quantity(2500, "us")
    assert own_property(model.find_instance(again, "a.inp"), "Data_Size") == Quantity(24, "Bytes")
    binding = own_property(model.find_instance(again, "a"), "Actual_Processor_Binding")
    assert [model.instance_path(t) for t in binding] == ["top_impl_Instance.cpu1"]
    assert own_property(again, "demo_props::Tags") == ["x", "y"]
    assert own_property(again, "demo_props::Ratio") == pytest.approx(1.0e-4)
    # the modal values keep their system operation modes
    modal = model.find_instance(again, "a").ownedPropertyAssociations
    priority = next(p for p in modal if p.property.endswith("Priority"))
    assert [list(v.inModes) for v in priority.ownedValues] == [["som_0"], ["som_1"]]
    # structure: same objects in the same places
    for kind in ("ComponentInstance", "FeatureInstance", "ConnectionInstance", "ModeInstance"):
        ours = [model.instance_path(o) for o in model.walk(instance) if o.eClass.name == kind]
        back = [model.instance_path(o) for o in model.walk(again) if o.eClass.name == kind]
        assert ours == back, kind


# ----------------------------------------------------------------------------- sidecars


_FEATURE_LISTS = {
    "ownedDataPort": "dataPort",
    "ownedEventPort": "eventPort",
    "ownedEventDataPort": "eventDataPort",
    "ownedParameter": "parameter",
    "ownedBusAccess": ("busAccess", "virtualBusAccess"),
    "ownedDataAccess": "dataAccess",
    "ownedSubprogramAccess": "subprogramAccess",
    "ownedSubprogramGroupAccess": "subprogramGroupAccess",
    "ownedFeatureGroup": "featureGroup",
    "ownedAbstractFeature": "abstractFeature",
}
_CONNECTION_LISTS = {
    "ownedPortConnection": "portConnection",
    "ownedAccessConnection": "accessConnection",
    "ownedFeatureConnection": "featureConnection",
    "ownedFeatureGroupConnection": "featureGroupConnection",
    "ownedParameterConnection": "parameterConnection",
}


def _members(element, step: str):
    """The members of ``element`` an Xtext containment list ``step`` holds, in text order."""
    name = step[1:]
    kind = element.eClass.name
    if name in _FEATURE_LISTS:
        wanted = _FEATURE_LISTS[name]
        wanted = wanted if isinstance(wanted, tuple) else (wanted,)
        return [f for f in element.features if f.category.name in wanted]
    if name.endswith("Subcomponent"):
        category = name[len("owned") : -len("Subcomponent")]
        return [s for s in element.subcomponents if s.category.name.lower() == category.lower()]
    if name in _CONNECTION_LISTS:
        return [c for c in element.connections if c.kind.name == _CONNECTION_LISTS[name]]
    lists = {
        "ownedMode": "modes",
        "ownedModeTransition": "modeTransitions",
        "ownedFlowSpecification": "flowSpecifications",
        "ownedEndToEndFlow": "endToEndFlows",
        "ownedPropertyType": "ownedPropertyTypes",
        "ownedProperty": "ownedProperties",
        "ownedLiteral": "ownedLiterals",
        "ownedField": "ownedFields",
    }
    if name in lists:
        return list(getattr(element, lists[name]))
    raise AssertionError(f"unexpected step {step} in a {kind}")


def _resolve(units: dict[str, model.EObject], href: str) -> model.EObject:
    """The declarative element an href into a sidecar designates (independently of the exporter)."""
    uri, _, fragment = href.partition("#")
    unit = units[Path(uri).name]
    if not fragment.startswith("/"):
        # OSATE's qualified name: the unit's name with its "::" written "." (demo.top.worker.fast)
        dotted = unit.name.replace("::", ".")
        qualifier, _, local = (
            fragment.partition(".")
            if unit.eClass.name == "PropertySet"
            else (
                fragment[: len(dotted)],
                ".",
                fragment[len(dotted) + 1 :],
            )
        )
        assert qualifier == dotted, href
        found = model.find_classifier(unit.eContainer(), f"{unit.name}::{local}")
        if found is None:
            found = next(p for p in unit.ownedProperties if p.name.lower() == local.lower())
        return found
    steps = fragment.split("/")[2:]
    assert fragment.startswith("/0/"), href
    current = unit
    for step in steps:
        name, _, number = step.partition(".")
        if name in ("@ownedPublicSection", "@ownedPrivateSection"):
            section = "private" if name == "@ownedPrivateSection" else "public"
            current = [c for c in current.classifiers if c.visibility.name == section]
            continue
        if name == "@ownedClassifier":
            current = current[int(number)]
            continue
        if name == "@ownedPropertyType" and not number:
            current = current.ownedType
            continue
        current = _members(current, name)[int(number)]
    return current


def _xml_path(element: etree._Element) -> str:
    """The instance path of an element of an exported file (names, array indices from ``<index>``)."""
    parts = []
    while element is not None:
        indexes = [i.text for i in element.findall("index") if i.text != "0"]
        parts.append(element.get("name") + "".join(f"[{i}]" for i in indexes))
        element = element.getparent()
    return ".".join(reversed(parts))


def _sidecar_units(folder: Path) -> dict[str, model.EObject]:
    files = sorted(folder.glob("*.aadl"))
    assert files
    sidecars = read_files(files, include_library=True, warnings=[], check=False)
    by_file = {}
    for unit in sidecars.units:
        if unit.sourceFile and Path(unit.sourceFile).parent == folder:
            by_file[Path(unit.sourceFile).name] = unit
    return by_file


def test_warnings_are_handed_back(tmp_path: Path) -> None:
    first = loads_aaxl2(_OPAQUE.encode(), "opaque.aaxl2")
    collected: list = []
    write_aaxl2(first.model, tmp_path, warnings=collected)
    again: list = []
    dumps_aaxl2(first.model, warnings=again)
    assert [w.message for w in collected] == [w.message for w in again]
    assert any("feature link(s) left out" in w.message for w in collected)
    assert (tmp_path / INSTANCES_FOLDER / "P_s_i_Instance.aaxl2").is_file()
    assert list(tmp_path.glob("*.aadl")) == []  # nothing declarative to write


def test_write_layout_and_sidecars(written: Path, exported) -> None:
    out = written.parent.parent
    assert written.parent.name == INSTANCES_FOLDER
    assert written.name == "demo_top_top_impl_Instance.aaxl2"
    assert sorted(p.name for p in out.glob("*.aadl")) == ["demo-top.aadl", "demo_props.aadl"]
    assert written.read_bytes() == exported.data
    assert (out / "demo-top.aadl").read_text() == exported.sidecars["demo-top.aadl"]
    leftovers = [p for p in out.rglob("*") if p.name.startswith(".")]
    assert leftovers == []  # no temporary files


def test_every_href_into_the_sidecars_resolves_to_the_named_element(written: Path, instance) -> None:
    units = _sidecar_units(written.parent.parent)
    root = _tree(written.read_bytes())
    checked: dict[str, int] = {}
    for link in root.iter():
        href = link.get("href")
        if href is None or not href.startswith("../"):
            continue
        target = _resolve(units, href)
        owner = link.getparent()
        tag = link.tag
        if tag in ("subcomponent", "feature", "mode", "flowSpecification", "endToEndFlow"):
            assert target.name == owner.get("name"), href
            expected = {"subcomponent": "Subcomponent", "feature": "Feature", "mode": "Mode"}.get(tag)
            assert expected is None or target.eClass.name == expected
        elif tag == "connection":
            assert target.eClass.name == "Connection"
            kind = target.kind.name
            assert link.get(f"{{{XSI}}}type") == "aadl2:" + kind[0].upper() + kind[1:], href
        elif tag in ("classifier", "componentImplementation"):
            assert target.eClass.name in ("ComponentType", "ComponentImplementation")
        elif tag == "property":
            assert target.eClass.name in ("Property", "RecordField")
        elif tag in ("unit", "namedValue"):
            assert target.eClass.name in ("UnitLiteral", "EnumerationLiteral")
        checked[tag] = checked.get(tag, 0) + 1
    assert {"subcomponent", "feature", "connection", "mode", "classifier", "unit", "namedValue"} <= set(
        checked
    )
    # connections: the declared names, context by context, outermost last as the instance has them
    connections = {
        model.instance_path(c): c for c in model.walk(instance) if c.eClass.name == "ConnectionInstance"
    }
    for conn_el in root.iter("connectionInstance"):
        ours = connections[_xml_path(conn_el)]
        refs = conn_el.findall("connectionReference")
        declared = [_resolve(units, r.find("connection").get("href")).name for r in refs]
        assert declared == [r.connection for r in ours.connectionReferences]


def test_user_property_set_literals_resolve_to_the_values(written: Path) -> None:
    units = _sidecar_units(written.parent.parent)
    root = _tree(written.read_bytes())
    named = {}
    for association in root.iter("ownedPropertyAssociation"):
        prop = association.find("property").get("href")
        for link in association.iter("namedValue", "unit"):
            if link.get("href").startswith("../"):
                named.setdefault(prop.rpartition(".")[2], set()).add(_resolve(units, link.get("href")).name)
    assert named == {"Level": {"high"}, "Budget": {"KB"}, "Window": {"soft"}}
    fields = [
        _resolve(units, p.get("href")).name for p in root.iter("ownedFieldValue") for p in p.iter("property")
    ]
    assert fields == ["Start", "Kind"]


def test_private_classifiers_are_counted_in_their_own_section(workspace, instance) -> None:
    from rosaadl.exporters.aaxl2.state import Writer

    links = Writer(instance, workspace, []).links
    package = model.find_unit(workspace, "demo::top")
    fragments = {c.name: links.classifier_fragment(c) for c in package.classifiers}
    assert fragments["hidden"] == "@ownedPrivateSection/@ownedClassifier.0"
    assert fragments["top.spare"] == "@ownedPrivateSection/@ownedClassifier.1"
    assert fragments["top.impl"] == "@ownedPublicSection/@ownedClassifier.11"
    spare = package.classifiers[-1]
    assert links.member_fragment(spare.subcomponents[0]) == (
        "@ownedPrivateSection/@ownedClassifier.1/@ownedDataSubcomponent.0"
    )


def test_inherited_period_points_into_the_declaring_implementation(exported) -> None:
    root = _tree(exported.data)
    pool = [c for c in root.iter("componentInstance") if c.get("name") == "pool"]
    classifiers = {c.find("classifier").get("href") for c in pool}
    assert classifiers == {"../demo-top.aadl#demo.top.worker.fast"}
    subs = {c.find("subcomponent").get("href").rpartition("#")[2] for c in pool}
    assert subs == {"/0/@ownedPublicSection/@ownedClassifier.7/@ownedThreadSubcomponent.1"}


def test_export_is_deterministic(instance) -> None:
    assert dumps_aaxl2(instance) == dumps_aaxl2(instance)


def test_model_root_selection(workspace) -> None:
    # a declarative model and a root: instantiated on the way, the model is left as it was
    before = len(workspace.instances)
    data = dumps_aaxl2(workspace, root=ROOT)
    assert len(workspace.instances) == before
    assert loads_aaxl2(data).root.classifier == "demo::top::top.impl"
    with pytest.raises(ExportError, match="no system instance"):
        dumps_aaxl2(model.new("AadlModel", name="empty"))
    with pytest.raises(RosaadlError, match="not found"):
        dumps_aaxl2(workspace, root="demo::top::nothing.impl")


# ----------------------------------------------------------------------------- instances without sources


_PS = "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/"
_PUB = "/0/@ownedPublicSection/@ownedClassifier"
_OPAQUE = f"""<?xml version="1.0" encoding="ASCII"?>
<instance:SystemInstance xmi:version="2.0" xmlns:xmi="http://www.omg.org/XMI"
    xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns:aadl2="http://aadl.info/AADL/2.0"
    xmlns:instance="http://aadl.info/AADL/2.0/instance" name="s_i_Instance" category="system">
  <componentInstance name="t" category="thread">
    <ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">
      <property href="../U.aadl#U.Mode_Of"/>
      <ownedValue>
        <ownedValue xsi:type="aadl2:NamedValue">
          <namedValue xsi:type="aadl2:EnumerationLiteral"
              href="../U.aadl#/0/@ownedPropertyType.0/@ownedLiteral.2"/>
        </ownedValue>
      </ownedValue>
    </ownedPropertyAssociation>
    <ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">
      <property href="{_PS}Timing_Properties.aadl#Timing_Properties.Period"/>
      <ownedValue>
        <ownedValue xsi:type="aadl2:IntegerLiteral" value="5">
          <unit href="{_PS}AADL_Project.aadl#/0/@ownedPropertyType.16/@ownedLiteral.3"/>
        </ownedValue>
      </ownedValue>
    </ownedPropertyAssociation>
    <featureInstance name="p" category="eventPort" direction="out">
      <feature xsi:type="aadl2:EventPort" href="../P.aadl#{_PUB}.0/@ownedEventPort.0"/>
    </featureInstance>
    <subcomponent xsi:type="aadl2:ThreadSubcomponent" href="../P.aadl#{_PUB}.1/@ownedThreadSubcomponent.0"/>
    <index>0</index>
    <classifier xsi:type="aadl2:ThreadType" href="../P.aadl#P.t"/>
  </componentInstance>
  <componentInstance name="u" category="thread">
    <featureInstance name="q" category="eventPort"/>
    <index>0</index>
  </componentInstance>
  <connectionInstance name="t.p -> u.q" complete="true" kind="portConnection"
      destination="//@componentInstance.1/@featureInstance.0"
      source="//@componentInstance.0/@featureInstance.0">
    <connectionReference context="/" source="//@componentInstance.0/@featureInstance.0"
        destination="//@componentInstance.1/@featureInstance.0">
      <connection xsi:type="aadl2:PortConnection" href="../P.aadl#{_PUB}.1/@ownedPortConnection.0"/>
    </connectionReference>
  </connectionInstance>
  <systemOperationMode name="No Modes"/>
  <componentImplementation xsi:type="aadl2:SystemImplementation" href="../P.aadl#P.s.i"/>
</instance:SystemInstance>
"""


def test_imported_instance_keeps_its_opaque_references_and_round_trips() -> None:
    first = loads_aaxl2(_OPAQUE.encode(), "opaque.aaxl2")
    result = export_aaxl2(first.model)
    text = result.data.decode("ascii")
    # kept as written: positional references into a set and a package we do not have
    assert 'href="../U.aadl#/0/@ownedPropertyType.0/@ownedLiteral.2"' in text
    assert 'href="../P.aadl#/0/@ownedPublicSection/@ownedClassifier.1/@ownedPortConnection.0"' in text
    assert '<connection xsi:type="aadl2:PortConnection"' in text  # the class its fragment names
    # classifiers and properties by qualified name, units re-encoded in the current era
    assert '<classifier xsi:type="aadl2:ThreadType" href="../P.aadl#P.t"/>' in text
    assert 'href="../U.aadl#U.Mode_Of"' in text
    assert "AADL_Project.aadl#/0/@ownedPropertyType.16/@ownedLiteral.3" in text
    # the links the reader did not keep are left out, and said so
    assert "<feature " not in text and "<subcomponent " not in text
    messages = " ".join(w.message for w in result.warnings)
    assert "2 feature link(s) left out" in messages and "2 subcomponent link(s) left out" in messages
    again = loads_aaxl2(result.data, "opaque.aaxl2")
    assert model.model_differences(first.model, again.model) == []


# ----------------------------------------------------------------------------- bad input


def _tiny(name: str = "t", feature: str = "p") -> model.EObject:
    system = model.new("SystemInstance", name="s_i_Instance", category="system", classifier="P::s.i")
    thread = model.new("ComponentInstance", name=name, category="thread", subcomponent=name)
    thread.featureInstances.append(model.new("FeatureInstance", name=feature, category="eventPort"))
    system.componentInstances.append(thread)
    return system


@pytest.mark.parametrize("name", ["a b", "../x", "", "9lives", "x__y", "t\u00e9"])
def test_a_name_that_is_not_an_aadl_identifier_is_a_located_error(name: str) -> None:
    with pytest.raises(ExportError) as caught:
        dumps_aaxl2(_tiny(name=name))
    assert "AADL identifier" in caught.value.message
    assert caught.value.location.path == f"s_i_Instance.{name}"


def test_a_bad_feature_name_names_its_component() -> None:
    with pytest.raises(ExportError) as caught:
        dumps_aaxl2(_tiny(feature="p q"))
    assert caught.value.location.path == "s_i_Instance.t.p q"


def test_a_control_character_in_a_string_is_a_located_error() -> None:
    system = _tiny()
    thread = system.componentInstances[0]
    thread.ownedPropertyAssociations.append(
        model.new(
            "PropertyAssociation",
            property="Programming_Properties::Source_Name",
            ownedValues=[model.new("ModalPropertyValue", value=model.new("StringValue", value="a\x01b"))],
        )
    )
    with pytest.raises(ExportError) as caught:
        dumps_aaxl2(system)
    assert "U+0001" in caught.value.message and caught.value.location.path == "s_i_Instance.t"


def test_a_reference_outside_the_instance_is_a_located_error() -> None:
    system, other = _tiny(), _tiny()
    system.componentInstances[0].ownedPropertyAssociations.append(
        model.new(
            "PropertyAssociation",
            property="Deployment_Properties::Actual_Processor_Binding",
            ownedValues=[
                model.new(
                    "ModalPropertyValue",
                    value=model.new(
                        "InstanceReferenceValue", referencedInstanceObject=other.componentInstances[0]
                    ),
                )
            ],
        )
    )
    with pytest.raises(ExportError, match="not part of the exported instance") as caught:
        dumps_aaxl2(system)
    assert caught.value.location.path == "s_i_Instance.t"


def test_a_system_instance_name_that_cannot_name_a_file_is_refused() -> None:
    system = _tiny()
    system.name = "../../etc/passwd"
    system.classifier = "../x#y"
    with pytest.raises(ExportError, match="system instance is named"):
        dumps_aaxl2(system)
    with pytest.raises(ExportError):
        instance_file_name(system)


def test_out_dir_escape_is_refused_and_nothing_is_written(tmp_path: Path, instance) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    out = tmp_path / "out"
    out.mkdir()
    os.symlink(outside, out / INSTANCES_FOLDER)
    with pytest.raises(ExportError, match="outside the output directory"):
        write_aaxl2(instance, out)
    assert list(outside.iterdir()) == []
    assert sorted(p.name for p in out.iterdir()) == [INSTANCES_FOLDER]


def test_errors_leave_no_output(tmp_path: Path) -> None:
    out = tmp_path / "out"
    with pytest.raises(ExportError):
        write_aaxl2(_tiny(name="a b"), out)
    assert not out.exists() or list(out.rglob("*")) == []


def test_not_a_model_is_refused() -> None:
    with pytest.raises(ExportError, match="expected an AadlModel or a SystemInstance"):
        dumps_aaxl2(model.new("AadlPackage", name="p"))
    with pytest.raises(ExportError, match="does not match"):
        dumps_aaxl2(_tiny(), root="Q::other.impl")


def test_reading_our_file_back_from_disk(written: Path) -> None:
    result = read_aaxl2(written)
    assert result.era == osate_eras.CURRENT_ERA
    assert all(present for _path, present in result.sidecars.values())
    # the references into the user property set stay opaque until its .aadl is read (as for OSATE's files)
    assert [w.message for w in result.warnings] == [
        "5 positional reference(s) into ../demo_props.aadl (not a predeclared property set) kept as "
        "uri#fragment until its .aadl source is read"
    ]


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("<annexInstance name='EMV2'><broken></annexInstance>", "not well-formed XML"),
        (
            "<!DOCTYPE a [<!ENTITY x 'y'>]><annexInstance name='E'>&x;</annexInstance>",
            "not well-formed|DOCTYPE",
        ),
        ("<other name='E'/>", "not an annexInstance"),
        ("<annexInstance xmlns='urn:x' name='E'/>", "not an annexInstance|default namespace"),
        ("<annexInstance xmlns:aadl2='urn:other' name='E'/>", "redefines the prefix"),
    ],
)
def test_bad_annex_text_is_a_located_error(text: str, problem: str) -> None:
    system = _tiny()
    system.componentInstances[0].annexInstances.append(model.new("AnnexInstance", name="EMV2", text=text))
    with pytest.raises(ExportError, match=problem) as caught:
        dumps_aaxl2(system)
    assert caught.value.location.path == "s_i_Instance.t"


def test_annex_text_is_embedded_with_its_namespace_on_the_root() -> None:
    system = _tiny()
    text = (
        '<annexInstance xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
        'xmlns:EMV2Instance="http://www.osate.org/EMV2Instance" xsi:type="EMV2Instance:EMV2AnnexInstance" '
        'name="EMV2">\n      <propagations name="p" feature="//@componentInstance.0/@featureInstance.0"/>\n'
        "    </annexInstance>"
    )
    system.componentInstances[0].annexInstances.append(model.new("AnnexInstance", name="EMV2", text=text))
    data = dumps_aaxl2(system)
    head = data.decode().splitlines()[1]
    assert re.findall(r"xmlns:(\w+)=", head) == ["xmi", "xsi", "EMV2Instance", "aadl2", "instance"]
    assert '    <annexInstance xsi:type="EMV2Instance:EMV2AnnexInstance" name="EMV2">' in data.decode()
    # laid out at the annex's depth, as OSATE writes it, whatever the text's own indentation
    assert (
        '      <propagations name="p" feature="//@componentInstance.0/@featureInstance.0"/>\n'
        "    </annexInstance>\n"
    ) in data.decode()
    again = loads_aaxl2(data)
    kept = again.root.componentInstances[0].annexInstances[0]
    assert kept.name == "EMV2"
    propagation = '<propagations name="p" feature="//@componentInstance.0/@featureInstance.0"/>'
    assert kept.text.splitlines()[1] == "  " + propagation
    assert dumps_aaxl2(again.model) == data


def test_annex_text_content_is_kept_when_re_indented() -> None:
    system = _tiny()
    text = '<annexInstance name="E"><note>two  spaces\n kept</note><a><b/></a></annexInstance>'
    system.componentInstances[0].annexInstances.append(model.new("AnnexInstance", name="E", text=text))
    again = loads_aaxl2(dumps_aaxl2(system))
    annex = etree.fromstring(again.root.componentInstances[0].annexInstances[0].text.encode())
    assert annex.findtext("note") == "two  spaces\n kept" and annex.find("a/b") is not None

""".aaxl2 hrefs by qualified name, for packages whose names have several segments.

OSATE names a package, classifier, property, property type or constant in an href by its
qualified name with every ``::`` written ``.``: for ``process implementation Alert.basic`` of
``package functional::Alert``, ``…/functional-Alert.aadl#functional.Alert.Alert.basic``
(``Aadl2QualifiedNameFragmentProvider`` over ``Aadl2QualifiedNameProvider``; Xtext's
``QualifiedName.toString()`` joins the segments with dots). It finds the element by comparing
that text with the fragment of every element of the resource, case included, so an href
written ``functional::Alert.Alert.basic`` designates nothing.

The model here is this project's own: three packages of two and three segments and a property
set, with cross-package classifiers, a classifier value and modes. It is exported, checked
against OSATE's metamodel from the corpus, every href into the written sidecars is resolved the
way OSATE resolves it (names) or counted the way its Xtext model holds members (positions), and
the file is read back with our reader; the reader also reads hrefs in OSATE's dotted form
written by hand in OSATE's shapes (instance and declarative files).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree
from osate_conformance import check

from rosaadl import model
from rosaadl.errors import ImportFormatError
from rosaadl.exporters.aaxl2 import export_aaxl2, write_aaxl2
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.aaxl2 import loads_aaxl2, read_aaxl2
from rosaadl.importers.aaxl2.xmi import qualified_name
from rosaadl.transforms.instantiate import instantiate

ROOT = "platform::Top::Main::Station.basic"

ALERT = """\
package functional::Alert
public
  with functional::Sensing, Alert_Props;

  thread Monitor
    features
      reading: in data port functional::Sensing::Sample;
      alarm: out event port;
    properties
      Dispatch_Protocol => Periodic;
      Period => 20 ms;
  end Monitor;

  thread implementation Monitor.basic
  end Monitor.basic;

  process Alert
    features
      reading: in data port functional::Sensing::Sample;
  end Alert;

  process implementation Alert.basic
    subcomponents
      mon: thread Monitor.basic;
    connections
      c1: port reading -> mon.reading;
    modes
      idle: initial mode;
      alarmed: mode;
    properties
      Alert_Props::Handler => classifier (functional::Alert::Monitor.basic);
      Alert_Props::Level => 2;
  end Alert.basic;
end functional::Alert;
"""

SENSING = """\
package functional::Sensing
public
  data Sample
  end Sample;

  data implementation Sample.raw
  end Sample.raw;

  device Probe
    features
      value: out data port Sample.raw;
  end Probe;
end functional::Sensing;
"""

TOP = """\
package platform::Top::Main
public
  with functional::Alert, functional::Sensing;

  system Station
  end Station;

  system implementation Station.basic
    subcomponents
      alert: process functional::Alert::Alert.basic;
      probe: device functional::Sensing::Probe;
    connections
      c0: port probe.value -> alert.reading;
  end Station.basic;
end platform::Top::Main;
"""

PROPS = """\
property set Alert_Props is
  Handler: classifier (thread) applies to (process);
  Level: aadlinteger applies to (process);
end Alert_Props;
"""

XSI_TYPE = "{http://www.w3.org/2001/XMLSchema-instance}type"


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> tuple[model.EObject, Path]:
    """(the instance of ``ROOT``, the ``.aaxl2`` file written for it beside its sidecars)."""
    folder = tmp_path_factory.mktemp("multi")
    for name, text in (
        ("alert.aadl", ALERT),
        ("sensing.aadl", SENSING),
        ("top.aadl", TOP),
        ("p.aadl", PROPS),
    ):
        (folder / name).write_text(text, encoding="utf-8")
    system = instantiate(read_files([folder], warnings=[]), ROOT)
    return system, write_aaxl2(system, tmp_path_factory.mktemp("out"))


@pytest.fixture(scope="module")
def written(exported) -> Path:
    return exported[1]


def _links(data: bytes) -> list[etree._Element]:
    """The elements of a file that link into a ``.aadl`` file beside the instances folder."""
    return [e for e in etree.fromstring(data).iter() if (e.get("href") or "").startswith("../")]


def _by_path(root: model.EObject, cls: str = "ComponentInstance") -> dict[str, model.EObject]:
    return {model.instance_path(o): o for o in model.walk(root) if model.is_a(o, cls)}


# ----------------------------------------------------------------------------- the form written


def test_classifiers_of_multi_segment_packages_are_named_with_dots(written: Path) -> None:
    hrefs = {(e.tag, e.getparent().get("name")): e.get("href") for e in _links(written.read_bytes())}
    assert hrefs[("classifier", "alert")] == "../functional-Alert.aadl#functional.Alert.Alert.basic"
    assert hrefs[("classifier", "mon")] == "../functional-Alert.aadl#functional.Alert.Monitor.basic"
    assert hrefs[("classifier", "probe")] == "../functional-Sensing.aadl#functional.Sensing.Probe"
    root = "../platform-Top-Main.aadl#platform.Top.Main.Station.basic"
    assert hrefs[("componentImplementation", "Station_basic_Instance")] == root
    assert hrefs[("classifier", "Station_basic_Instance")] == root
    # the classifier value, and the properties of the user's set
    assert hrefs[("classifier", None)] == "../functional-Alert.aadl#functional.Alert.Monitor.basic"
    properties = {e.get("href") for e in _links(written.read_bytes()) if e.tag == "property"}
    assert properties == {"../Alert_Props.aadl#Alert_Props.Handler", "../Alert_Props.aadl#Alert_Props.Level"}
    fragments = [e.get("href").partition("#")[2] for e in _links(written.read_bytes())]
    assert fragments and not [f for f in fragments if "::" in f]


def test_the_file_conforms_to_osate_metamodel(written: Path, corpus: Path) -> None:
    folder = corpus / "osate" / "metamodel"
    if not (folder / "aadl2.ecore").is_file():
        pytest.skip("OSATE's metamodel is not in the corpus")
    report = check(written.read_bytes(), folder)
    assert report.ok, report
    assert report.objects > 10


# ----------------------------------------------------------------------------- resolution as OSATE does


def _osate_fragments(unit: model.EObject) -> dict[str, model.EObject]:
    """The elements of a unit that OSATE names by qualified name, by that name's fragment: the
    unit, its classifiers (packages) or properties, property types and constants (property sets),
    each ``Owner::Name`` split at ``::`` and joined with dots, as Xtext's ``QualifiedName`` prints."""

    def dotted(*names: str) -> str:
        return ".".join(segment for name in names for segment in name.split("::"))

    if model.is_a(unit, "PropertySet"):
        members = [*unit.ownedPropertyTypes, *unit.ownedProperties, *unit.ownedPropertyConstants]
    else:
        members = list(unit.classifiers)
    found = {dotted(unit.name): unit}
    for member in members:
        found[dotted(unit.name, member.name)] = member
    return found


_MEMBER_LISTS = {"Port": "features", "Subcomponent": "subcomponents", "Connection": "connections"}


def _at_position(unit: model.EObject, fragment: str) -> model.EObject:
    """The member ``/0/@ownedPublicSection/@ownedClassifier.N/@owned<Class>.M`` designates: the
    M-th member of that class of the N-th public classifier (enough for this model's links)."""
    steps = fragment.split("/")
    assert steps[:3] == ["", "0", "@ownedPublicSection"], fragment
    classifier = [c for c in unit.classifiers if c.visibility.name != "private"][int(steps[3].split(".")[1])]
    cls, _, position = steps[4][len("@owned") :].partition(".")
    if cls == "Mode":
        return classifier.modes[int(position)]
    kind = next(k for k in _MEMBER_LISTS if cls.endswith(k))
    members = [m for m in getattr(classifier, _MEMBER_LISTS[kind]) if _aadl2_class(m) == cls]
    return members[int(position)]


def _aadl2_class(member: model.EObject) -> str:
    """aadl2's class of a feature, subcomponent or connection (``DataPort``, ``ThreadSubcomponent``)."""
    if model.is_a(member, "Feature"):
        name = member.category.name
    elif model.is_a(member, "Subcomponent"):
        name = member.category.name + "Subcomponent"
    else:
        name = member.kind.name
    return name[0].upper() + name[1:]


def test_every_href_into_the_sidecars_designates_the_element_osate_would_find(written: Path) -> None:
    folder = written.parent.parent
    sidecars = read_files(sorted(folder.glob("*.aadl")), warnings=[], check=False)
    units = {
        Path(u.sourceFile).name: u
        for u in sidecars.units
        if u.sourceFile and Path(u.sourceFile).parent == folder
    }
    assert set(units) == {
        "functional-Alert.aadl",
        "functional-Sensing.aadl",
        "platform-Top-Main.aadl",
        "Alert_Props.aadl",
    }
    by_name = {file: _osate_fragments(unit) for file, unit in units.items()}
    seen = set()
    for link in _links(written.read_bytes()):
        uri, _, fragment = link.get("href").partition("#")
        file = uri[len("../") :]
        xsi_type = (link.get(XSI_TYPE) or "").partition(":")[2]
        if fragment.startswith("/"):
            target = _at_position(units[file], fragment)
            if link.tag in ("subcomponent", "feature", "mode"):
                assert target.name == link.getparent().get("name"), link.get("href")
            seen.add(f"{link.tag} by position")
            continue
        target = by_name[file].get(fragment)
        assert target is not None, f"OSATE finds no element named {fragment!r} in {file}"
        if link.tag == "property":
            assert model.is_a(target, "Property")
        else:
            implementation = model.is_a(target, "ComponentImplementation")
            assert xsi_type.endswith("Implementation") == implementation, link.get("href")
            assert xsi_type.lower().startswith(target.category.name.lower()), link.get("href")
        seen.add(f"{link.tag} by name")
    assert {
        "classifier by name",
        "componentImplementation by name",
        "property by name",
        "subcomponent by position",
        "feature by position",
        "connection by position",
        "mode by position",
    } <= seen


# ----------------------------------------------------------------------------- read back


def test_our_file_reads_back_with_the_qualified_names(exported) -> None:
    instance, written = exported
    result = read_aaxl2(written)
    back = result.model.instances[0]
    ours, theirs = _by_path(instance), _by_path(back)
    assert set(ours) == set(theirs)
    assert {p: c.classifier for p, c in theirs.items()} == {p: c.classifier for p, c in ours.items()}
    assert theirs["Station_basic_Instance.alert"].classifier == "functional::Alert::Alert.basic"

    def properties(objects):
        return {p: sorted(a.property for a in o.ownedPropertyAssociations) for p, o in objects.items()}

    assert properties(theirs) == properties(ours)
    handler = next(
        a
        for a in theirs["Station_basic_Instance.alert"].ownedPropertyAssociations
        if a.property == "Alert_Props::Handler"
    )
    value = handler.ownedValues[0].value
    assert value.classifier == "functional::Alert::Monitor.basic"


def test_a_file_read_back_is_written_again_with_the_same_hrefs_by_name(written: Path) -> None:
    first = written.read_bytes()
    again = export_aaxl2(read_aaxl2(written).model).data
    named = [
        (e.tag, e.get("href")) for e in _links(first) if not e.get("href").partition("#")[2].startswith("/")
    ]
    assert named == [
        (e.tag, e.get("href")) for e in _links(again) if not e.get("href").partition("#")[2].startswith("/")
    ]


# ----------------------------------------------------------------------------- OSATE's form read


NS = (
    'xmlns:xmi="http://www.omg.org/XMI" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" '
    'xmlns:aadl2="http://aadl.info/AADL/2.0" xmlns:instance="http://aadl.info/AADL/2.0/instance"'
)
POS = "../alert.aadl#/0/@ownedPublicSection/@ownedClassifier."
TOP_POS = "../top.aadl#/0/@ownedPublicSection/@ownedClassifier."
# hrefs by name as OSATE writes them for packages functional::Alert and platform::Top::Main
ALERT_A = "../alert.aadl#functional.Alert"
TOP_S = "../top.aadl#platform.Top.Main.Station"
OSATE_INSTANCE = f"""<?xml version="1.0" encoding="ASCII"?>
<instance:SystemInstance xmi:version="2.0" {NS} name="Station_basic_Instance" category="system">
  <componentInstance name="alert" category="process">
    <ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">
      <property href="../p.aadl#Alert_Props.Handler"/>
      <ownedValue>
        <ownedValue xsi:type="aadl2:ClassifierValue">
          <classifier xsi:type="aadl2:ThreadImplementation" href="{ALERT_A}.Monitor.basic"/>
        </ownedValue>
      </ownedValue>
    </ownedPropertyAssociation>
    <componentInstance name="mon" category="thread">
      <subcomponent xsi:type="aadl2:ThreadSubcomponent" href="{POS}3/@ownedThreadSubcomponent.0"/>
      <index>0</index>
      <classifier xsi:type="aadl2:ThreadType" href="{ALERT_A}.Monitor"/>
    </componentInstance>
    <subcomponent xsi:type="aadl2:ProcessSubcomponent" href="{TOP_POS}1/@ownedProcessSubcomponent.0"/>
    <index>0</index>
    <classifier xsi:type="aadl2:ProcessImplementation" href="{ALERT_A}.Alert.basic"/>
  </componentInstance>
  <classifier xsi:type="aadl2:SystemImplementation" href="{TOP_S}.basic"/>
  <systemOperationMode name="No Modes"/>
  <componentImplementation xsi:type="aadl2:SystemImplementation" href="{TOP_S}.basic"/>
</instance:SystemInstance>
"""


def test_the_reader_decodes_osate_dotted_names_by_the_class_of_the_link() -> None:
    result = loads_aaxl2(OSATE_INSTANCE.encode("ascii"), "/p/instances/Station_basic_Instance.aaxl2")
    system = result.model.instances[0]
    classifiers = {p: c.classifier for p, c in _by_path(system).items()}
    assert classifiers == {
        "Station_basic_Instance": "platform::Top::Main::Station.basic",
        "Station_basic_Instance.alert": "functional::Alert::Alert.basic",
        "Station_basic_Instance.alert.mon": "functional::Alert::Monitor",
    }
    (association,) = system.componentInstances[0].ownedPropertyAssociations
    assert association.property == "Alert_Props::Handler"
    assert association.ownedValues[0].value.classifier == "functional::Alert::Monitor.basic"


def test_the_2014_root_link_without_a_class_is_an_implementation() -> None:
    text = OSATE_INSTANCE.replace(
        '<componentImplementation xsi:type="aadl2:SystemImplementation" href',
        "<systemImplementation href",
    ).replace(
        f'  <classifier xsi:type="aadl2:SystemImplementation" href="{TOP_S}.basic"/>\n',
        "",
    )
    system = loads_aaxl2(text.encode("ascii"), "/p/instances/x.aaxl2").model.instances[0]
    assert system.classifier == "platform::Top::Main::Station.basic"


OSATE_PACKAGE = f"""<?xml version="1.0" encoding="UTF-8"?>
<aadl2:Package xmi:version="2.0" {NS} name="platform::Top::Main" publicSection="#//@ownedPublicSection">
  <ownedPublicSection importedUnit="aadl2:AadlPackage {ALERT_A} aadl2:PropertySet ../p.aadl#Alert_Props">
    <ownedClassifier xsi:type="aadl2:SystemType" name="Station"/>
    <ownedClassifier xsi:type="aadl2:SystemImplementation" name="Station.basic">
      <ownedRealization implemented="#//@ownedPublicSection/@ownedClassifier.0"/>
      <ownedProcessSubcomponent name="alert"
        processSubcomponentType="aadl2:ProcessImplementation {ALERT_A}.Alert.basic"/>
      <ownedProcessSubcomponent name="spare" processSubcomponentType="aadl2:ProcessType {ALERT_A}.Alert"/>
    </ownedClassifier>
    <ownedClassifier xsi:type="aadl2:SystemImplementation" name="Station.more">
      <ownedExtension extended="aadl2:SystemImplementation {TOP_S}.basic"/>
      <ownedRealization implemented="#//@ownedPublicSection/@ownedClassifier.0"/>
    </ownedClassifier>
  </ownedPublicSection>
</aadl2:Package>
"""


def test_the_reader_decodes_dotted_names_in_a_declarative_package() -> None:
    result = loads_aaxl2(OSATE_PACKAGE.encode("utf-8"), "/p/top.aaxl2")
    (package,) = [u for u in result.model.units if u.name == "platform::Top::Main"]
    assert list(package.withs) == ["functional::Alert", "Alert_Props"]
    basic = next(c for c in package.classifiers if c.name == "Station.basic")
    assert {s.name: s.classifier for s in basic.subcomponents} == {
        "alert": "functional::Alert::Alert.basic",
        "spare": "functional::Alert::Alert",
    }
    more = next(c for c in package.classifiers if c.name == "Station.more")
    assert more.extended == "platform::Top::Main::Station.basic"


@pytest.mark.parametrize(
    ("fragment", "kind", "name"),
    [
        ("functional.Alert.Alert.basic", "ProcessImplementation", "functional::Alert::Alert.basic"),
        ("functional.Alert.Alert", "ProcessType", "functional::Alert::Alert"),
        ("functional.Alert", "AadlPackage", "functional::Alert"),
        ("Timing_Properties.Period", "Property", "Timing_Properties::Period"),
        ("P.T.i", "ThreadImplementation", "P::T.i"),
        ("P.T", "FeatureGroupType", "P::T"),
        # no class: the first dot ends the owner (one-segment packages, every property set)
        ("P.T.i", None, "P::T.i"),
        # as earlier versions of this project wrote them
        ("functional::Alert.Alert.basic", "ProcessImplementation", "functional::Alert::Alert.basic"),
        # odd text gives a name, never a failure
        ("T.i", "ThreadImplementation", "T::i"),
        ("..", "ThreadImplementation", "::."),
        ("", "ThreadType", ""),
    ],
)
def test_qualified_name_of_a_fragment(fragment: str, kind: str | None, name: str) -> None:
    assert qualified_name(fragment, kind) == name


@pytest.mark.parametrize(
    "damage",
    [
        lambda t: t[: t.index("functional.Alert.Alert.basic") + 10],  # truncated inside an href
        lambda t: t.replace('href="../alert.aadl#functional.Alert.Alert.basic"', ""),  # no href
    ],
)
def test_hostile_or_truncated_dotted_links_are_located_errors(damage) -> None:
    with pytest.raises(ImportFormatError) as caught:
        loads_aaxl2(damage(OSATE_INSTANCE).encode("ascii"), "bad.aaxl2")
    assert caught.value.location.file == "bad.aaxl2"
    assert caught.value.location.line


def test_odd_dotted_fragments_read_without_failing() -> None:
    text = OSATE_INSTANCE.replace("#functional.Alert.Alert.basic", "#..").replace(
        "#platform.Top.Main.Station.basic", "#Station."
    )
    system = loads_aaxl2(text.encode("ascii"), "odd.aaxl2").model.instances[0]
    assert system.componentInstances[0].classifier == "::."

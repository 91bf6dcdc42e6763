"""Corpus models that ``with`` a property set or package OSATE contributes read with the library's.

OSATE ships, besides the predeclared property sets, the SEI's contributed ones (``ARINC429``,
``ARINC653``, ``Code_Generation_Properties``, ``Data_Model``, ``Physical``, ``SEI``) and the
packages ``Base_Types`` and ``PhysicalResources`` (plug-in ``org.osate.contribution.sei``); real
models name them in ``with`` clauses and expect them there. For every corpus project with such a
clause: no "not loaded" warning and no error about them (projects with missing sources of their
own still fail, for those only), and their values decode against the library's declarations.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.errors import NameResolutionError
from rosaadl.exporters.aaxl2 import export_aaxl2
from rosaadl.importers.aadl_text import library_files, read_files
from rosaadl.properties import EnumLiteral, own_property, property_value, python_value
from rosaadl.resolution import Resolver
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity, standard_units

#: the units OSATE's contribution plug-in holds, as the library ships them
CONTRIBUTED = (
    "ARINC429",
    "ARINC653",
    "Code_Generation_Properties",
    "Data_Model",
    "Physical",
    "SEI",
    "Base_Types",
    "PhysicalResources",
)

#: corpus project folder (read as one workspace) → the contributed units its files ``with``
CASES: dict[str, tuple[str, ...]] = {
    "osate/aaxl2/ex-issue440-arinc653": ("ARINC653", "Data_Model"),
    "osate/aaxl2/ex-latency-nobus": ("ARINC653", "Base_Types"),
    "osate/aaxl2/ex-latency-normal": ("ARINC653", "Base_Types"),
    "osate/aaxl2/ex-latency-partitioned-distributed": ("ARINC653", "Base_Types"),
    "osate/aaxl2/ex-latency-unbound": ("ARINC653", "Base_Types"),
    "osate/aaxl2/osate2-simple-control-modes": ("Physical", "PhysicalResources", "SEI"),
    "osate/aaxl2/case-hamr-edp-domains": ("Base_Types",),
    "osate/aaxl2/ex-carsystem": ("SEI",),
    "osate/aaxl2/fmw-uav-v3": ("Base_Types", "Data_Model"),
    "osate/aaxl2/gtse-atsv-tier0/org.osate.atsv.integration.tests/src/test/resources": ("SEI",),
    "osate/aaxl2/inspecta-firewall-platform": ("Base_Types", "Data_Model"),
    "osate/aaxl2/osate2-pulseox": ("Data_Model",),
    "osate/busload": ("SEI",),
    "aadl-ros/rpio/docs/gettingStarted/tutorials/basics/files": ("SEI",),
    "aadl-ros/rpio/examples/basics/aadl_to_aadlil/input": ("Base_Types", "Data_Model"),
    "aadl-ros/rpio/examples/basics/packageCreate/HelloWorld_v2/Design": ("Base_Types", "Data_Model"),
    "aadl-ros/rpio/examples/basics/robochart_to_aadl/output": ("Base_Types", "Data_Model"),
    "aadl-ros/rpio/examples/basics/transformations/HelloWorld/Design": ("Base_Types", "Data_Model"),
}

_WITH = re.compile(r"\bwith\s+([A-Za-z_][\w:]*(?:\s*,\s*[A-Za-z_][\w:]*)*)\s*;", re.I)
_COMMENT = re.compile(r"--[^\n]*")


def _withs(path: Path) -> set[str]:
    """The contributed units a file names in its ``with`` clauses (lower case)."""
    text = _COMMENT.sub("", path.read_text("utf-8", errors="replace"))
    named = {name.strip().lower() for clause in _WITH.findall(text) for name in clause.split(",")}
    return named & {name.lower() for name in CONTRIBUTED}


def _read(folder: Path) -> tuple[list, list]:
    """(warnings, errors) of reading ``folder`` with the library; a project whose own sources
    are incomplete raises, with every error found."""
    warnings: list = []
    try:
        read_files([folder], warnings=warnings)
    except NameResolutionError as exc:
        return warnings, list(exc.errors)
    return warnings, []


def _about(diagnostic, names: tuple[str, ...]) -> bool:
    text = diagnostic.message.lower()
    return any(re.search(rf"\b{name.lower()}\b", text) for name in names)


@pytest.mark.corpus
def test_every_corpus_file_that_withs_a_contributed_unit_is_a_case(corpus: Path) -> None:
    files = [
        p
        for p in corpus.rglob("*")
        if p.suffix.lower() in (".aadl", ".aadl2") and p.is_file() and "predeclared" not in p.parts
    ]
    found: dict[str, set[str]] = {}
    for path in files:
        named = _withs(path)
        if named:
            folder = next((f for f in CASES if path.is_relative_to(corpus / f)), str(path))
            found.setdefault(folder, set()).update(named)
    # the second copy of the gtse-atsv-tier0 sources is the same file (read once, as one project)
    found = {f: n for f, n in found.items() if "org.osate.atsv.integration.tests/org.osate" not in f}
    assert found == {f: {n.lower() for n in names} for f, names in CASES.items()}


@pytest.mark.corpus
@pytest.mark.parametrize("folder", sorted(CASES), ids=sorted(CASES))
def test_contributed_units_are_loaded_for_the_corpus_model(corpus: Path, folder: str) -> None:
    path = corpus / folder
    if not path.is_dir():
        pytest.skip(f"{folder} is not in the corpus")
    warnings, errors = _read(path)
    not_loaded = [str(w) for w in warnings if "not loaded" in w.message and _about(w, CONTRIBUTED)]
    assert not_loaded == []
    assert [str(e) for e in errors if _about(e, CONTRIBUTED)] == []


@pytest.mark.corpus
def test_every_property_of_a_contributed_set_the_corpus_uses_resolves_to_the_library(corpus: Path) -> None:
    """Each association of a contributed set's property in the corpus cases names a property the
    library declares, so its value is checked against that property's type while reading."""
    library = {str(p.resolve()) for p in library_files()}
    sets = {name.lower() for name in CONTRIBUTED}
    used: dict[str, set[str]] = {}
    for folder in CASES:
        workspace = read_files([corpus / folder], check=False, warnings=[])
        resolver = Resolver(workspace)
        for unit in workspace.units:
            if unit.sourceFile and str(Path(unit.sourceFile).resolve()) in library:
                continue
            for assoc in model.walk(unit):
                if not model.is_a(assoc, "PropertyAssociation"):
                    continue
                qualifier = (assoc.property or "").rpartition("::")[0]
                if qualifier.lower() in sets:
                    prop = resolver.property(assoc.property, assoc)
                    assert prop is not None, f"{folder}: {assoc.property}"
                    assert str(Path(prop.eContainer().sourceFile).resolve()) in library
                    used.setdefault(qualifier.lower(), set()).add(assoc.property.rpartition("::")[2])
    assert {"arinc653", "physical", "sei"} <= set(used)
    assert {"Memory_Type", "Module_Major_Frame", "HM_Error_ID_Levels"} <= used["arinc653"]


@pytest.mark.corpus
def test_a_physical_voltage_decodes(corpus: Path) -> None:
    """``Physical::Voltage => 12.0V applies to power`` on SimpleControlSystem::SCS reaches the
    instance as 12 V, which the library's Voltage_Units convert (mV, V => mV * 1000, ...)."""
    workspace = read_files([corpus / "osate/aaxl2/osate2-simple-control-modes"], warnings=[])
    system = instantiate(workspace, "SimpleControlSystem::SCS.tier1")
    power = model.find_instance(system, "power")
    voltage = property_value(power, "Physical::Voltage")
    assert voltage == Quantity(12.0, "V")
    units = standard_units()
    units.add_units_type(Resolver(workspace).property_type("Physical::Voltage_Units"))
    assert voltage.to("mV", units) == pytest.approx(12000.0)
    assert model.find_unit(workspace, "PhysicalResources") is not None


@pytest.mark.corpus
def test_arinc653_values_decode(corpus: Path) -> None:
    """The ARINC653 values of bugtrack issue 440 (its RAMSES packages are not in the corpus, so
    it is read without resolving) decode on the instance: times, records, enumeration lists."""
    workspace = read_files([corpus / "osate/aaxl2/ex-issue440-arinc653"], check=False, warnings=[])
    system = instantiate(workspace, "test_queuing::root.impl", strict=False)
    found: dict[str, list] = {}
    for obj in model.walk(system):
        for name in ("Module_Major_Frame", "HM_Error_ID_Levels", "Memory_Type", "Partition_Identifier"):
            value = property_value(obj, f"ARINC653::{name}")
            if value is not None:
                found.setdefault(name, []).append(value)
    assert {frame.to("ms") for frame in found["Module_Major_Frame"]} <= {2000, 4000}
    assert [EnumLiteral("Data_Memory")] in found["Memory_Type"]
    level = found["HM_Error_ID_Levels"][0][0]
    assert set(level) == {"ErrorIdentifier", "Description", "ErrorLevel", "ErrorCode"}
    assert 1 in found["Partition_Identifier"]


@pytest.mark.corpus
def test_the_aaxl2_export_points_at_osates_contributed_units(corpus: Path) -> None:
    """OSATE keeps Physical and PhysicalResources in its contribution plug-in: the export refers
    to them there (Voltage_Units is ownedPropertyType.1 of OSATE's Physical, V its literal 1) and
    writes no sidecar for them."""
    workspace = read_files([corpus / "osate/aaxl2/osate2-simple-control-modes"], warnings=[])
    result = export_aaxl2(instantiate(workspace, "SimpleControlSystem::SCS.tier1"))
    assert not any(name.lower().startswith("physical") for name in result.sidecars)
    assert not any("not in the model" in w.message for w in result.warnings)
    physical = "platform:/plugin/org.osate.contribution.sei/resources/properties/Physical.aadl"
    data = result.data.decode("ascii")
    assert f'<property href="{physical}#Physical.Voltage"/>' in data
    assert f'<unit href="{physical}#/0/@ownedPropertyType.1/@ownedLiteral.1"/>' in data


_OWN_MODEL = """
package Avionics
public
  with ARINC429, ARINC653, Code_Generation_Properties;

  subprogram filter
    features
      input : in parameter;
      output : out parameter { Code_Generation_Properties::Return_Parameter => true; };
    properties
      Code_Generation_Properties::Convention => AADL;
  end filter;

  thread reader
    features
      altitude : in data port {
        ARINC429::WordID => 203; ARINC429::FirstBit => 11; ARINC429::NumberBits => 17;
      };
    properties
      ARINC653::DAL => LEVEL_B;
      ARINC653::Time_Capacity => 5 ms;
  end reader;

  virtual processor partition
    properties
      ARINC653::Partition_Identifier => 1;
  end partition;

  processor module
  end module;

  processor implementation module.impl
    subcomponents
      part : virtual processor partition;
    properties
      ARINC653::Module_Schedule => ([Partition => reference (part); Duration => 20 ms;
                                     Periodic_Processing_Start => true;]);
      ARINC653::Module_Major_Frame => 20 ms;
  end module.impl;

  process app
  end app;

  process implementation app.impl
    subcomponents
      r : thread reader;
  end app.impl;

  system avionics
  end avionics;

  system implementation avionics.impl
    subcomponents
      cpu : processor module.impl;
      sw : process app.impl;
    properties
      Deployment_Properties::Actual_Processor_Binding => (reference (cpu.part)) applies to sw;
  end avionics.impl;
end Avionics;
"""


def test_a_model_of_our_own_with_arinc429_arinc653_and_code_generation_reads_and_decodes(
    tmp_path: Path,
) -> None:
    path = tmp_path / "Avionics.aadl"
    path.write_text(_OWN_MODEL)
    warnings: list = []
    workspace = read_files([path], warnings=warnings)
    assert [str(w) for w in warnings] == []
    system = instantiate(workspace, "Avionics::avionics.impl")
    altitude = model.find_instance(system, "sw.r.altitude")
    assert [property_value(altitude, f"ARINC429::{n}") for n in ("WordID", "FirstBit", "NumberBits")] == [
        203,
        11,
        17,
    ]
    reader = model.find_instance(system, "sw.r")
    assert property_value(reader, "ARINC653::DAL") == EnumLiteral("LEVEL_B")
    assert property_value(reader, "ARINC653::Time_Capacity").to("us") == 5000
    cpu = model.find_instance(system, "cpu")
    (window,) = property_value(cpu, "ARINC653::Module_Schedule")
    assert window["Partition"] is model.find_instance(system, "cpu.part")
    assert window["Duration"] == Quantity(20, "ms") and window["Periodic_Processing_Start"] is True
    resolver = Resolver(workspace)
    subprogram = resolver.classifier("Avionics::filter")
    assert own_property(subprogram, "Code_Generation_Properties::Convention") == EnumLiteral("AADL")
    convention = resolver.property("Code_Generation_Properties::Convention")
    assert python_value(convention.defaultValue) == EnumLiteral("Legacy")


def test_a_value_outside_a_contributed_set_s_type_is_a_located_error(tmp_path: Path) -> None:
    path = tmp_path / "Bad.aadl"
    path.write_text(
        "package Bad\npublic\n  with ARINC653, Physical;\n  memory ram\n    properties\n"
        "      ARINC653::Memory_Kind => (Memory_IO);\n      Physical::Voltage => 5.0 W;\n"
        "  end ram;\nend Bad;\n"
    )
    with pytest.raises(NameResolutionError) as info:
        read_files([path], warnings=[])
    messages = [f"{e.location.line}: {e.message}" for e in info.value.errors]
    assert any(m.startswith("6:") and "Memory_IO" in m for m in messages), messages
    assert any(m.startswith("7:") and "W" in m for m in messages), messages

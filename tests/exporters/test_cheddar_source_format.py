"""Cheddar export writes back the format it read: a Cheddar 2 file whose tasks name a processor
or an address space it does not declare (Cheddar 2's reader does not check those names) is
exported as Cheddar 2 unless Cheddar 3 is asked for, so import → export → import gives an equal
model; a model that did not come from a Cheddar file is still written as Cheddar 3."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from lxml import etree

from rosaadl import model
from rosaadl.cli import main
from rosaadl.errors import Diagnostic, ExportError
from rosaadl.exporters.cheddar import dumps_cheddar, structure_problems, write_cheddar
from rosaadl.exporters.cheddar.export import source_format
from rosaadl.importers.cheddar import cheddar_format_of, load_cheddar, loads_cheddar
from rosaadl.properties import own_property

CP = "Cheddar_Properties::"

_V2_UNDECLARED = """<?xml version="1.0"?>
<cheddar>
 <processors><processor><name>a</name><scheduler>RATE_MONOTONIC_PROTOCOL</scheduler></processor>
 </processors>
 <address_spaces><address_space><name>ea</name><cpu_name>a</cpu_name></address_space></address_spaces>
 <tasks>
  <task task_type="PERIODIC_TYPE"><cpu_name>a</cpu_name><address_space_name>ea</address_space_name>
   <name>T1</name><capacity>1</capacity><period>10</period></task>
  <task task_type="PERIODIC_TYPE"><cpu_name>gpu</cpu_name><address_space_name>ea</address_space_name>
   <name>T2</name><capacity>1</capacity><period>5</period></task>
  <task task_type="PERIODIC_TYPE"><cpu_name>a</cpu_name><address_space_name>nowhere</address_space_name>
   <name>T3</name><capacity>1</capacity><period>4</period></task>
 </tasks>
</cheddar>
"""


def _format(data: bytes) -> int:
    return cheddar_format_of(etree.fromstring(data))


def _round_trip(first, name: str) -> bytes:
    exported = dumps_cheddar(first)
    assert _format(exported) == 2 and structure_problems(exported, 2) == []
    second = loads_cheddar(exported, name)
    assert model.model_differences(first, second) == []
    assert dumps_cheddar(second) == exported
    return exported


@pytest.mark.corpus
def test_cheddar2_file_with_an_undeclared_processor_round_trips(corpus: Path, tmp_path: Path) -> None:
    path = corpus / "cheddar" / "edf_pip_resource_v2.xml"
    diagnostics: list[Diagnostic] = []
    first = load_cheddar(path, diagnostics=diagnostics)
    assert [d.location.path for d in diagnostics] == ["/cheddar/tasks/task[3]/cpu_name"]
    assert source_format(first.instances[0]) == 2
    exported = _round_trip(first, path.name)
    third = etree.fromstring(exported).findall("tasks/task")[2]
    assert third.findtext("name") == "T3" and third.findtext("cpu_name") == "cpu"
    # the format survives the model's own files
    saved = model.load(model.save(first, tmp_path / "edf.json"))
    assert write_cheddar(saved, tmp_path / "edf.xml").read_bytes() == exported
    # Cheddar 3, asked for, still refuses what Cheddar 3's reader would refuse, and says why
    with pytest.raises(ExportError, match="cpu_name 'cpu' is not a processor") as caught:
        dumps_cheddar(first, cheddar_format=3)
    assert "read from a Cheddar 2 file" in caught.value.message


def test_undeclared_processor_and_address_space_are_written_back_as_read() -> None:
    diagnostics: list[Diagnostic] = []
    first = loads_cheddar(_V2_UNDECLARED.encode(), "undeclared.xml", diagnostics=diagnostics)
    assert len(diagnostics) == 2
    root = first.instances[0]
    assert own_property(root, CP + "Cheddar_Format") == 2
    exported = _round_trip(first, "undeclared.xml")
    tasks = {t.findtext("name"): t for t in etree.fromstring(exported).find("tasks")}
    assert tasks["T2"].findtext("cpu_name") == "gpu"
    assert tasks["T3"].findtext("address_space_name") == "nowhere"
    assert dumps_cheddar(first, cheddar_format=2) == exported


def test_the_default_format_follows_the_source() -> None:
    v2 = loads_cheddar(_V2_UNDECLARED.replace("gpu", "a").replace("nowhere", "ea").encode(), "ok.xml")
    assert _format(dumps_cheddar(v2)) == 2
    assert _format(dumps_cheddar(v2, cheddar_format=3)) == 3
    v3 = loads_cheddar(dumps_cheddar(v2, cheddar_format=3), "ok.xmlv3")
    assert source_format(v3.instances[0]) == 3 and _format(dumps_cheddar(v3)) == 3
    del v3.instances[0].ownedPropertyAssociations[:]  # a system not read from Cheddar
    assert source_format(v3.instances[0]) is None
    with pytest.raises(ExportError, match="cheddar_format must be 2 or 3"):
        dumps_cheddar(v2, cheddar_format=4)


def test_cli_export_writes_a_cheddar2_input_back_as_cheddar2(tmp_path: Path, capsys) -> None:
    source = tmp_path / "undeclared.xml"
    source.write_text(_V2_UNDECLARED)
    saved = tmp_path / "model.json"
    assert main(["import", str(source), "-o", str(saved)]) == 0
    capsys.readouterr()
    out = tmp_path / "back.xml"
    assert main(["--format", "json", "export", "cheddar", str(saved), "-o", str(out)]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["ok"] and report["output"] == str(out)
    assert _format(out.read_bytes()) == 2
    assert model.model_differences(model.load(saved), loads_cheddar(out.read_bytes(), "undeclared.xml")) == []
    refused = tmp_path / "refused.xmlv3"
    assert main(["export", "cheddar", str(saved), "-o", str(refused), "--cheddar-format", "3"]) == 1
    assert not refused.exists()

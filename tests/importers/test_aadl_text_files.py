"""The AADL text reader over files: ``read_files`` (folders, the component library, a user unit
that replaces a library unit), the checks of names, units and literals across files, and the
real-world corpus (every file reads, every project resolves or is explained)."""

from __future__ import annotations

import logging
from importlib import resources
from pathlib import Path

import pytest

from rosaadl.errors import AadlSyntaxError, NameResolutionError, ParseError, RosaadlError
from rosaadl.importers.aadl_text import library_files, read_files, read_string

# --------------------------------------------------------------------------- checks across files


def _write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


WRONG_UNITS = """\
package Bad_Values
public
  thread T
    properties
      Period => 10 kg;
      Deadline => 10;
      Dispatch_Protocol => Periodical;
      Priority => 3 ms;
      Compute_Execution_Time => 1 ms .. 2 Mbps;
  end T;
end Bad_Values;
"""


def test_wrong_units_and_literals_are_located_errors(tmp_path: Path) -> None:
    path = _write(tmp_path, "bad_values.aadl", WRONG_UNITS)
    with pytest.raises(NameResolutionError) as info:
        read_files([path])
    found = [(d.location.line, d.location.column, d.message) for d in info.value.errors]
    assert [(line, column) for line, column, _ in found] == [(5, 17), (6, 19), (7, 28), (8, 19), (9, 41)]
    assert all(d.location.file == str(path) for d in info.value.errors)
    assert "kg is not a unit of AADL_Project::Time_Units" in found[0][2]
    assert "needs a unit" in found[1][2]
    assert "Periodical is not a literal" in found[2][2]
    assert "without unit" in found[3][2]
    assert "Mbps is not a unit" in found[4][2]
    assert f"{path}:5:17" in str(info.value)


def test_cyclic_extends_is_a_located_error(tmp_path: Path) -> None:
    text = "package Cyclic\npublic\n  system A extends B end A;\n  system B extends A end B;\nend Cyclic;\n"
    path = _write(tmp_path, "cyclic.aadl", text)
    with pytest.raises(NameResolutionError) as info:
        read_files([path])
    first = info.value.errors[0]
    assert "cycle" in first.message and (first.location.file, first.location.line) == (str(path), 3)


def test_unresolved_names_are_reported_together(tmp_path: Path) -> None:
    text = (
        "package Broken\npublic\n  with Missing_Pkg;\n"
        "  system S features p: in data port Nowhere::T; end S;\n"
        "  system implementation S.i subcomponents x: process Missing_Pkg::P; end S.i;\nend Broken;\n"
    )
    path = _write(tmp_path, "broken.aadl", text)
    warnings: list = []
    with pytest.raises(NameResolutionError) as info:
        read_files([path], warnings=warnings)
    assert [d.location.line for d in info.value.errors] == [4, 5]
    assert any("Missing_Pkg" in w.message for w in warnings)
    # without the check, the same files read
    m = read_files([path], check=False)
    assert m.units[-1].name == "Broken"


# --------------------------------------------------------------------------- read_files and the library


def test_library_files() -> None:
    files = library_files()
    root = Path(str(resources.files("rosaadl.library")))
    relative = [p.relative_to(root).parts for p in files]
    assert relative == sorted(relative)
    assert len(files) >= 20 and all(p.suffix == ".aadl" and p.is_file() for p in files)
    names = {p.name for p in files}
    assert {"AADL_Project.aadl", "Timing_Properties.aadl", "SEI.aadl", "ros.aadl"} <= names
    assert files == library_files()


def test_library_reads_without_warnings(caplog) -> None:
    warnings: list = []
    with caplog.at_level(logging.WARNING, logger="rosaadl"):
        m = read_files([], warnings=warnings)
    assert warnings == []
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []
    names = {u.name for u in m.units}
    assert {"AADL_Project", "Timing_Properties", "SEI", "Base_Types", "ros"} <= names
    assert all(u.sourceFile and Path(u.sourceFile).is_file() for u in m.units)
    assert len(read_files([], include_library=False).units) == 0


def test_folders_are_searched_recursively_in_sorted_order(tmp_path: Path) -> None:
    _write(tmp_path, "b/two.aadl", "package Two public end Two;")
    _write(tmp_path, "a/z.AADL2", "package Three public end Three;")
    _write(tmp_path, "a/deeper/one.aadl", "package One public end One;")
    _write(tmp_path, ".hidden/x.aadl", "this is not read")
    _write(tmp_path, "notes.txt", "neither is this")
    m = read_files(tmp_path, include_library=False)
    assert [u.name for u in m.units] == ["One", "Three", "Two"]
    assert Path(m.units[0].sourceFile) == tmp_path / "a" / "deeper" / "one.aadl"
    # a file named twice (directly and through its folder) is read once
    again = read_files([tmp_path / "b" / "two.aadl", tmp_path / "b"], include_library=False)
    assert [u.name for u in again.units] == ["Two"]


def test_missing_input_is_a_located_error(tmp_path: Path) -> None:
    with pytest.raises(ParseError) as info:
        read_files([tmp_path / "nowhere.aadl"])
    assert info.value.location.file == str(tmp_path / "nowhere.aadl")


def test_a_user_unit_replaces_the_library_unit(tmp_path: Path) -> None:
    path = _write(
        tmp_path, "SEI.aadl", "property set SEI is\n  Weight: aadlreal applies to (all);\nend SEI;\n"
    )
    warnings: list = []
    m = read_files([path], warnings=warnings, check=False)
    seis = [u for u in m.units if u.name == "SEI"]
    assert len(seis) == 1 and seis[0].sourceFile == str(path)
    (note,) = [w for w in warnings if "replaces" in w.message]
    assert note.location.file == str(path) and note.location.line == 1


def test_syntax_errors_in_files_name_the_file(tmp_path: Path) -> None:
    path = _write(tmp_path, "broken.aadl", "package P public system S end S end P;")
    with pytest.raises(AadlSyntaxError) as info:
        read_files([path], include_library=False)
    assert info.value.location.file == str(path)


# --------------------------------------------------------------------------- the real corpus

CORPUS_FOLDERS = ("osate/aaxl2", "osate/busload", "aadl-ros", "cheddar", "osate/predeclared")


def _corpus_files(corpus: Path) -> list[Path]:
    return sorted(
        p
        for folder in CORPUS_FOLDERS
        if (corpus / folder).is_dir()
        for p in (corpus / folder).rglob("*")
        if p.suffix.lower() in (".aadl", ".aadl2") and p.is_file()
    )


#: what the corpus holds today; fewer files read is a regression
CORPUS_FILE_COUNT = 120


@pytest.mark.corpus
def test_every_corpus_file_reads(corpus: Path, record_property) -> None:
    files = _corpus_files(corpus)
    failures = []
    units = 0
    for path in files:
        try:
            units += len(read_string(path.read_bytes(), str(path)).units)
        except RosaadlError as exc:
            failures.append(str(exc).splitlines()[0])
    record_property("aadl_files_read", len(files) - len(failures))
    assert failures == [], f"{len(failures)} of {len(files)} corpus files do not read:\n" + "\n".join(
        failures
    )
    assert len(files) >= CORPUS_FILE_COUNT, (
        f"only {len(files)} AADL files read (expected {CORPUS_FILE_COUNT})"
    )
    assert units >= len(files)


# The folder of each OSATE example (or other project) in the corpus: None when it must resolve
# without errors, else (names the errors must all be about, the reason from the corpus INDEX).
PROJECTS: list[tuple[str, dict, tuple[tuple[str, ...], str] | None]] = [
    ("osate/aaxl2/case-hamr-edp-domains", {}, None),
    (
        "osate/aaxl2/ex-carsystem",
        {},
        (
            ("CarHardwarePlatform::",),
            "package CarHardwarePlatform (with-ed by CarSystem.aadl) is not in the corpus",
        ),
    ),
    ("osate/aaxl2/ex-crossdomain-security", {}, None),
    ("osate/aaxl2/ex-issue228-featuregroups", {}, None),
    (
        "osate/aaxl2/ex-issue440-arinc653",
        {},
        (
            ("RAMSES_processors::", "RAMSES_buses::"),
            "RAMSES packages (RAMSES_processors, RAMSES_buses) are not in the corpus",
        ),
    ),
    ("osate/aaxl2/ex-large-modes", {}, None),
    ("osate/aaxl2/ex-latency-nobus", {}, None),
    ("osate/aaxl2/ex-latency-normal", {}, None),
    ("osate/aaxl2/ex-latency-partitioned-distributed", {}, None),
    ("osate/aaxl2/ex-latency-unbound", {}, None),
    (
        "osate/aaxl2/ex-mission-aircraft",
        {},
        (("OperationalEnvironment_pkg::",), "package OperationalEnvironment_pkg is not in the corpus"),
    ),
    ("osate/aaxl2/ex-pullprotocols", {}, None),
    ("osate/aaxl2/ex-simple-thread-latency", {}, None),
    (
        "osate/aaxl2/fmw-uav-v3",
        {},
        (
            ("CASE_Model_Transformations", "UAS::", "CASE_RF_Msg", "CASE_MsgHeader"),
            "packages UAS and CASE_Model_Transformations (CASE plug-in) are not in the corpus",
        ),
    ),
    # the case folder holds two copies of this source; one project is one copy
    ("osate/aaxl2/gtse-atsv-tier0/org.osate.atsv.integration.tests/src/test/resources", {}, None),
    ("osate/aaxl2/inspecta-firewall-platform", {}, None),
    ("osate/aaxl2/osate2-emv2-annex-instance", {}, None),
    ("osate/aaxl2/osate2-issue2318-bidir", {}, None),
    ("osate/aaxl2/osate2-issue2780-featuregroups", {}, None),
    ("osate/aaxl2/osate2-pulseox", {}, None),
    # complete with the library's PhysicalResources and Physical (OSATE's contribution plug-in)
    ("osate/aaxl2/osate2-simple-control-modes", {}, None),
    ("osate/busload", {}, None),
    ("cheddar", {}, None),
    # OSATE's own predeclared property sets of each era stand alone (they replace our library's)
    ("osate/predeclared/2014-09_daa8bac2", {"include_library": False}, None),
    ("osate/predeclared/2017-10_a09722639e", {"include_library": False}, None),
    ("osate/predeclared/HEAD_d4e6c73e", {"include_library": False}, None),
    ("aadl-ros/rpio/docs/gettingStarted/tutorials/basics/files", {}, None),
    ("aadl-ros/rpio/examples/basics/robochart_to_aadl/output", {}, None),
    (
        "aadl-ros/rpio/examples/basics/aadl_to_aadlil/input",
        {},
        (("HardwareParts::",), "INDEX.md: package HardwareParts is referenced but not in the repository"),
    ),
    (
        "aadl-ros/rpio/examples/basics/packageCreate/HelloWorld_v2/Design",
        {},
        (
            ("messages::",),
            "its messages package lacks the data types the model uses (marked TODO in the source)",
        ),
    ),
    (
        "aadl-ros/rpio/examples/basics/transformations/HelloWorld/Design",
        {},
        (
            ("messages::",),
            "its messages package lacks the data types the model uses (marked TODO in the source)",
        ),
    ),
]


@pytest.mark.corpus
@pytest.mark.parametrize(("folder", "options", "incomplete"), PROJECTS, ids=[p[0] for p in PROJECTS])
def test_corpus_projects_resolve(corpus: Path, folder: str, options: dict, incomplete) -> None:
    path = corpus / folder
    if not path.is_dir():
        pytest.skip(f"{folder} is not in the corpus")
    if incomplete is None:
        m = read_files([path], **options)
        assert any(u.sourceFile and Path(u.sourceFile).is_relative_to(path) for u in m.units)
        return
    names, reason = incomplete
    with pytest.raises(NameResolutionError) as info:
        read_files([path], **options)
    others = [str(d) for d in info.value.errors if not any(n in d.message for n in names)]
    assert others == [], "errors not explained by the missing sources:\n" + "\n".join(others)
    pytest.skip(f"sources incomplete: {reason}")


def test_corpus_project_table_covers_every_case(corpus: Path) -> None:
    cases = {p.name for p in (corpus / "osate" / "aaxl2").iterdir() if p.is_dir()}
    with_sources = {
        c
        for c in cases
        if any(q.suffix.lower() in (".aadl", ".aadl2") for q in (corpus / "osate" / "aaxl2" / c).rglob("*"))
    }
    listed = {folder.split("/")[2] for folder, _, _ in PROJECTS if folder.startswith("osate/aaxl2/")}
    assert with_sources == listed

"""Wrong arguments to the public functions are errors that name them, never a bare TypeError.

The entry points the README and ``docs/`` show are called with arguments of the wrong kind
(None, a number, a ROSMOD project where an AADL model belongs, a path no system accepts);
each must raise a :class:`RosaadlError`, and a wrong file system target must be a located
:class:`ExportError`, not an ``OSError``.
"""

from __future__ import annotations

import math
import os
from fractions import Fraction
from pathlib import Path

import pytest

from rosaadl import fileio, model
from rosaadl.analysis.rendering import as_float
from rosaadl.analysis.report import run_analyses
from rosaadl.analysis.schedulability import analyze_schedulability
from rosaadl.arguments import checked, describe, expect_number, expect_path
from rosaadl.errors import ExportError, ParseError, RosaadlError, UsageError
from rosaadl.exporters.aadl_text import write_model
from rosaadl.exporters.aaxl2 import dumps_aaxl2, export_aaxl2
from rosaadl.exporters.cheddar import dumps_cheddar
from rosaadl.exporters.rclpy import generate_workspace, plan_workspace
from rosaadl.exporters.rosmod_text import write_project
from rosaadl.formats import read_input
from rosaadl.importers import osate_eras
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.aaxl2 import loads_aaxl2, read_aaxl2
from rosaadl.importers.cheddar import load_cheddar, loads_cheddar
from rosaadl.importers.rosmod_text import read_project
from rosaadl.importers.rosmod_webgme import read_webgmex
from rosaadl.properties import property_value
from rosaadl.transforms.aadl_to_rosmod import aadl_to_rosmod
from rosaadl.transforms.instantiate import instantiate
from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl
from rosaadl.units import Quantity
from rosaadl.workflow.binding import bind_project, read_bindings
from rosaadl.workflow.library_catalog import describe as describe_component
from rosaadl.workflow.library_catalog import list_packages

# --------------------------------------------------------------------------- the decorator


@checked
def _halve(count: int, *, label: str = "x") -> str:
    return f"{label}{count // 2}"


@checked
def _buggy(count: int) -> int:
    return {}["missing"] + count  # a bug of ours, whatever the argument


@checked(model="AadlModel")
def _needs_model(model: object, name: str | None = None) -> str:
    return model.eClass.name


def test_a_wrong_argument_is_a_usage_error_naming_the_function_and_the_parameter():
    assert _halve(4, label="y") == "y2"
    with pytest.raises(UsageError, match=r"_halve\(\): count must be int, not str '4'"):
        _halve("4")
    with pytest.raises(UsageError, match=r"count must be int, not None"):
        _halve(None, label="y")
    assert _halve(4, label=None) == "None2", "arguments are looked at only when the call fails"
    with pytest.raises(UsageError, match="missing a required argument"):
        _halve()


def test_a_bug_with_right_arguments_propagates_unchanged():
    with pytest.raises(KeyError, match="missing"):
        _buggy(1)


def test_a_metamodel_class_is_checked_before_the_call():
    aadl = read_files([])
    assert _needs_model(aadl) == "AadlModel"
    with pytest.raises(UsageError, match=r"model must be an AadlModel, not None"):
        _needs_model(None)
    with pytest.raises(UsageError, match=r"model must be an AadlModel, not an AadlPackage"):
        _needs_model(aadl.units[0])


def test_describe_names_a_value_shortly():
    assert describe(None) == "None"
    assert describe(3) == "int 3"
    assert describe("x" * 100).endswith("...") and len(describe("x" * 100)) < 70
    assert describe(read_files([])) == "an AadlModel"


def test_expect_path_and_expect_number():
    assert expect_path("a/b") == Path("a/b")
    assert expect_path(Path("c")) == Path("c")
    for bad in (None, 3, b"a", "", "a\x00b"):
        with pytest.raises(UsageError):
            expect_path(bad)
    assert expect_number(Fraction(1, 3), "u") == Fraction(1, 3)
    for bad, options in (
        (True, {}),
        ("1", {}),
        (math.inf, {}),
        (math.nan, {}),
        (0, {"positive": True}),
        (1.5, {"integer": True}),
        (-1, {"minimum": 0}),
    ):
        with pytest.raises(UsageError):
            expect_number(bad, "value", **options)


# --------------------------------------------------------------------------- the entry points


@pytest.fixture(scope="module")
def rosmod_project():
    return model.new("rosmod.Project", name="p")


ENTRY_POINTS = [
    ("read_files(None)", lambda p: read_files(None)),
    ("read_files([42])", lambda p: read_files([42])),
    ("read_project(None)", lambda p: read_project(None)),
    ("read_project('')", lambda p: read_project("")),
    ("read_webgmex(3)", lambda p: read_webgmex(3)),
    ("read_aaxl2(None)", lambda p: read_aaxl2(None)),
    ("loads_aaxl2('text')", lambda p: loads_aaxl2("text")),
    ("load_cheddar(None)", lambda p: load_cheddar(None)),
    ("loads_cheddar(1)", lambda p: loads_cheddar(1)),
    ("read_input(None)", lambda p: read_input(None)),
    ("read_input(NUL)", lambda p: read_input("a\x00b")),
    ("read_bindings(None)", lambda p: read_bindings(None)),
    ("instantiate(None, root)", lambda p: instantiate(None, "a::b.impl")),
    ("instantiate(project, root)", lambda p: instantiate(p, "a::b.impl")),
    ("instantiate(model, 7)", lambda p: instantiate(read_files([]), 7)),
    ("run_analyses(None)", lambda p: run_analyses(None)),
    ("run_analyses(project)", lambda p: run_analyses(p)),
    ("analyze_schedulability(None)", lambda p: analyze_schedulability(None)),
    ("property_value(None, 'Period')", lambda p: property_value(None, "Period")),
    ("rosmod_to_aadl(None)", lambda p: rosmod_to_aadl(None)),
    ("rosmod_to_aadl(model)", lambda p: rosmod_to_aadl(read_files([]))),
    ("aadl_to_rosmod(None)", lambda p: aadl_to_rosmod(None)),
    ("aadl_to_rosmod(project)", lambda p: aadl_to_rosmod(p)),
    ("bind_project(None, None)", lambda p: bind_project(None, None)),
    ("write_model(None, out)", lambda p: write_model(None, "out")),
    ("write_project(None, out)", lambda p: write_project(None, "out")),
    ("export_aaxl2(None)", lambda p: export_aaxl2(None)),
    ("dumps_aaxl2(project)", lambda p: dumps_aaxl2(p)),
    ("dumps_cheddar(None)", lambda p: dumps_cheddar(None)),
    ("plan_workspace(None)", lambda p: plan_workspace(None)),
    ("generate_workspace(None, out)", lambda p: generate_workspace(None, "out")),
    ("list_packages(None)", lambda p: list_packages(None)),
    ("describe(None, name)", lambda p: describe_component(None, "x")),
    ("model.save(None, path)", lambda p: model.save(None, "x.xmi")),
    ("model.load(None)", lambda p: model.load(None)),
    ("model.find_instance(None, path)", lambda p: model.find_instance(None, "a.b")),
    ("Quantity.to(None)", lambda p: Quantity(1, "ms").to(None)),
]


@pytest.mark.parametrize("call", [c for _, c in ENTRY_POINTS], ids=[n for n, _ in ENTRY_POINTS])
def test_an_entry_point_called_wrongly_raises_a_rosaadl_error(call, rosmod_project, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(RosaadlError):
        call(rosmod_project)
    assert not list(tmp_path.iterdir()), "nothing is written for a wrong call"


# --------------------------------------------------------------------------- file system targets


def test_writing_under_a_file_names_the_file_that_blocks_it(tmp_path):
    blocker = tmp_path / "taken"
    blocker.write_text("a file")
    with pytest.raises(ExportError, match="taken is a file, not a folder") as caught:
        fileio.atomic_write_text(blocker / "out.aadl", "x")
    assert caught.value.location.file.endswith("out.aadl")


def test_writing_onto_a_folder_is_a_located_error(tmp_path):
    (tmp_path / "folder").mkdir()
    with pytest.raises(ExportError, match="folder"):
        fileio.atomic_write_text(tmp_path / "folder", "x")
    assert [p.name for p in (tmp_path / "folder").iterdir()] == []


def test_a_name_the_system_refuses_is_a_located_error_not_an_oserror(tmp_path):
    too_long = tmp_path / ("n" * (os.pathconf(tmp_path, "PC_NAME_MAX") + 1))
    with pytest.raises(ExportError):
        fileio.atomic_write_text(too_long, "x")
    with pytest.raises(ParseError):
        read_files([too_long / "m.aadl"])


def test_unknown_osate_era_is_a_usage_error():
    with pytest.raises(UsageError, match="unknown OSATE era"):
        osate_eras.table("1999")


def test_numbers_beyond_the_float_range_print_as_infinities():
    huge = Fraction(10**400, 3)
    assert as_float(huge) == math.inf and as_float(-huge) == -math.inf
    assert as_float(Fraction(1, 4)) == 0.25

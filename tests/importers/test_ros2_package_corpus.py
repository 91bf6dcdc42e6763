"""Round trip through source: every ROSMOD project of the corpus → AADL → rclpy workspace →
``import ros2-package`` gives, per node, the same ports (kind and message or service type) and
the same timer periods as the ROSMOD model's component instances on that node.

Each deployment of each textual project is generated and read back; the WebGME seeds are read
back at their first deployment per project. A node of the model is found in the import under
the ROS node name the generator gives it; message types compare by their ROS 2 name (the
generator writes ``sensor_state`` as ``SensorState``).

One thing the generator itself leaves out of the code is told apart from the differences and
reported (``record_property``), not failed: the type of a service no client is joined to (a
client is joined to the first server of its type; the generator types a subprogram access no
connection reaches ``Srv``). A publisher no subscriber of its deployment reads is generated
(a ROSMOD component's own port), and compared like any other.
Everything else that differs fails the project.
"""

from __future__ import annotations

import logging
from collections import Counter
from decimal import Decimal
from pathlib import Path

import pytest
from conftest import corpus_dir
from corpus_cases import ROSMOD_PROJECTS, WEBGME_SEEDS

from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace, naming
from rosaadl.importers import aadl_text
from rosaadl.importers.ros2_package import read_ros2_packages
from rosaadl.transforms import rosmod_to_aadl as converter
from rosaadl.transforms.instantiate import instantiate

CORPUS = corpus_dir() / "rosmod"


def _textual_projects() -> list[Path]:
    """The ROSMOD projects of the corpus (textual, legacy and the AGSE robot)."""
    return [CORPUS / p for p in ROSMOD_PROJECTS if (CORPUS / p).exists()]


@pytest.fixture(scope="module")
def library():
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    return aadl_text.read_files([], include_library=True, check=False)


def _type(text: str | None) -> str:
    return naming.message_name((text or "").rpartition("/")[2])


def _period(value: Decimal | None) -> Decimal | None:
    return value.normalize() if value is not None and value > 0 else None


def _expected(node) -> tuple[Counter, Counter]:
    ports: Counter = Counter()
    timers: Counter = Counter()
    for instance in node.componentInstances:
        for port in instance.component.ports:
            ports[(port.eClass.name, _type(port.type))] += 1
        for timer in instance.component.timers:
            timers[_period(timer.period)] += 1
    return ports, timers


def _imported(component) -> tuple[Counter, Counter]:
    ports = Counter((p.eClass.name, _type(p.type)) for p in component.ports)
    timers = Counter(_period(t.period) for t in component.timers)
    return ports, timers


def _without_generator_omissions(
    expected: Counter, found: Counter, deployment, omitted: list, node
) -> Counter:
    """``expected`` less what the generator leaves out (see the module docstring), noted in ``omitted``."""
    expected = Counter(expected)
    for (kind, type_name), count in list(expected.items()):
        missing = count - found.get((kind, type_name), 0)
        if missing <= 0:
            continue
        if (
            kind == "Server"
            and found.get(("Server", "Srv"), 0) - expected.get(("Server", "Srv"), 0) >= missing
        ):
            expected[(kind, type_name)] -= missing
            expected[(kind, "Srv")] += missing
            omitted.append(
                f"{deployment.name}/{node.name}: service {type_name} (no client joined) generated as Srv"
            )
    return +expected


def _round_trip(
    library, project, tmp_path: Path, *, first_only: bool, omitted: list | None = None
) -> list[str]:
    """The differences found, one line per node; every deployment generated and read back.
    What the generator leaves out goes to ``omitted``."""
    omitted = [] if omitted is None else omitted
    converted = converter.rosmod_to_aadl(project)
    units = list(converted.model.units)
    library.units.extend(units)
    deployments = {d.name: d for d in project.deployments}
    differences = []
    checked = 0
    try:
        for index, (name, root) in enumerate(sorted(converted.roots.items())):
            if first_only and index:
                break
            instance = instantiate(library, root, strict=False)
            try:
                src = tmp_path / f"d{index}" / "src"
                generate_workspace(
                    instance, src, options=GenerationOptions(year=2024), rosmod_trace=converted.trace
                )
            finally:
                library.instances.remove(instance)
            imported = read_ros2_packages([src], warnings=[])
            components = {c.name: c for p in imported.software.packages for c in p.components}
            for node in deployments[name].nodes:
                ros_name = naming.node_name(node.name)
                if ros_name not in components:
                    differences.append(f"{name}/{node.name}: no component {ros_name!r} imported")
                    continue
                expected, found = _expected(node), _imported(components[ros_name])
                ports = _without_generator_omissions(expected[0], found[0], deployments[name], omitted, node)
                expected = (ports, expected[1])
                if expected != found:
                    differences.append(f"{name}/{node.name}: expected {expected}, imported {found}")
                checked += 1
    finally:
        for unit in units:
            library.units.remove(unit)
    assert checked or not project.deployments, "no node was compared"
    return differences


@pytest.mark.corpus
@pytest.mark.parametrize("folder", _textual_projects(), ids=lambda p: str(p.relative_to(CORPUS)))
def test_rosmod_project_reads_back_from_its_rclpy_packages(library, folder, tmp_path, record_property):
    from rosaadl.importers.rosmod_text import read_project

    omitted: list[str] = []
    assert _round_trip(library, read_project(folder), tmp_path, first_only=False, omitted=omitted) == []
    record_property("left out by the generator", omitted)


@pytest.mark.corpus
@pytest.mark.parametrize("seed", WEBGME_SEEDS)
def test_webgme_projects_read_back_from_their_rclpy_packages(library, seed, tmp_path, record_property):
    from rosaadl.importers.rosmod_webgme import read_webgmex

    path = CORPUS / "webgme" / seed
    if not path.is_file():
        pytest.skip(f"{path} is not in the corpus")
    report: list[str] = []
    omitted: list[str] = []
    for index, project in enumerate(read_webgmex(path)):
        report += _round_trip(library, project, tmp_path / f"p{index}", first_only=True, omitted=omitted)
    assert report == []
    record_property("left out by the generator", omitted)

"""The generator on real models: the library's tracking application read from its AADL text, and
every ROSMOD project of the corpus converted to AADL (textual projects and WebGME exports).

Every deployment of every project is generated, compiles, and has a node per process and a
construct per thread and port (the checks of ``test_rclpy_ast``); every .msg/.srv of the corpus
parses with ``rosidl_adapter`` (one run).  ROS 2's flake8, pep257 and copyright checks and
``colcon build``/``colcon test`` (each a few seconds per package) run by default on the tracking
application and on ten-components (clients and servers, timers, publishers, subscribers); set
``ROSAADL_ROS_TOOLS_ALL=1`` to run them on the first deployment of every project.
"""

from __future__ import annotations

import compileall
import io
import logging
import os
import shutil
import subprocess
from contextlib import redirect_stdout
from pathlib import Path

import pytest
from conftest import corpus_dir
from test_rclpy_ast import check_constructs, check_rclpy_calls
from test_rclpy_models import ros_environment, ros_python
from test_rclpy_ros_tools import CHECK_INTERFACES

from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace
from rosaadl.importers import aadl_text
from rosaadl.transforms import rosmod_to_aadl as converter
from rosaadl.transforms.instantiate import instantiate

#: The Debian packages that give each ROS 2 tool (the tests say which to install when one is missing).
DEBIAN_PACKAGE = {
    "ament_flake8": "python3-ament-flake8",
    "ament_pep257": "python3-ament-pep257",
    "ament_copyright": "python3-ament-copyright",
    "rosidl": "python3-rosidl",
    "colcon": "colcon python3-colcon-ros",
}


def _missing(tool: str) -> None:
    pytest.skip(f"{tool} is not installed (Debian package {DEBIAN_PACKAGE[tool]}); nothing of it was checked")


OPTIONS = GenerationOptions(year=2024)
CORPUS = corpus_dir() / "rosmod"
#: The ROSMOD project checked with the ROS 2 tools by default (clients and servers, timers,
#: publishers and subscribers in one project).
ROS_TOOLS_PROJECTS = ("ten-components",)
ALL_ROS_TOOLS = os.environ.get("ROSAADL_ROS_TOOLS_ALL") == "1"


def _textual_projects() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    from rosaadl.importers.rosmod_text import is_rosmod_project

    found = []
    for folder in sorted(p for p in CORPUS.rglob("*") if p.is_dir()):
        if folder.name.startswith(".") or any(folder.is_relative_to(f) for f in found):
            continue
        if is_rosmod_project(folder):
            found.append(folder)
    return found


def _webgme_files() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    return sorted(p for p in (CORPUS / "webgme").glob("samples-*.webgmex"))


@pytest.fixture(scope="module")
def interfaces() -> dict[str, list[Path]]:
    """The .msg/.srv files of the first deployment of each project generated so far."""
    return {}


@pytest.fixture(scope="module")
def library():
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    return aadl_text.read_files([], include_library=True, check=False)


def _python_packages(root: Path) -> list[Path]:
    return sorted(p.parent for p in root.glob("*/setup.py"))


def _compiles(root: Path) -> bool:
    with redirect_stdout(io.StringIO()):
        return bool(compileall.compile_dir(str(root), quiet=1, force=True))


def _lint(packages: list[Path], cwd: Path) -> None:
    for tool in ("ament_flake8", "ament_pep257", "ament_copyright"):
        path = shutil.which(tool)
        if path is None:
            _missing(tool)
        done = subprocess.run(
            [path, *map(str, packages)],
            cwd=cwd,
            env=ros_environment(ros_python(tool)),
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert done.returncode == 0, f"{tool}:\n{done.stdout[-4000:]}{done.stderr[-2000:]}"


def _rosidl(files: list[Path], cwd: Path) -> None:
    assert files, "no .msg/.srv file to check"
    python = ros_python("rosidl")
    if python is None:
        _missing("rosidl")
    done = subprocess.run(
        [python, "-c", CHECK_INTERFACES, *map(str, files)],
        cwd=cwd,
        env=ros_environment(python),
        capture_output=True,
        text=True,
        timeout=300,
    )
    if "No module named 'rosidl" in done.stderr:
        _missing("rosidl")
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]


def _colcon(root: Path) -> None:
    colcon = shutil.which("colcon")
    if colcon is None:
        _missing("colcon")
    python = ros_python("colcon")
    env = ros_environment(python)
    # interface packages that need ROS 2 message packages Debian does not ship are left out
    ignore = []
    for cmake in root.glob("src/*/CMakeLists.txt"):
        text = cmake.read_text()
        if "DEPENDENCIES" in text:
            ignore.append(cmake.parent.name)
    extra = ["--packages-ignore", *ignore] if ignore else []
    build = subprocess.run(
        [colcon, "build", "--base-paths", "src", *extra],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert build.returncode == 0, build.stdout[-5000:] + build.stderr[-3000:]
    test = subprocess.run(
        [colcon, "test", "--base-paths", "src", *extra],
        cwd=root,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert test.returncode == 0, test.stdout[-5000:] + test.stderr[-3000:]
    result = subprocess.run(
        [colcon, "test-result", "--all"], cwd=root, env=env, capture_output=True, text=True, timeout=300
    )
    summary = result.stdout.strip().splitlines()[-1] if result.stdout.strip() else ""
    assert summary.endswith("0 errors, 0 failures, 0 skipped"), result.stdout[-3000:]
    packages = _python_packages(root / "src")
    assert summary.startswith(f"Summary: {3 * len(packages)} tests"), summary


def _check_workspace(instance, result, src: Path, *, ros_tools: bool) -> None:
    assert not result.skipped
    assert _compiles(src)
    assert check_rclpy_calls([src / p for p in result.written if p.endswith(".py") and "/test/" not in p]) > 0
    check_constructs(instance, result, src)
    processes = [o for o in _walk_components(instance) if o.category.name == "process"]
    assert len(result.plan.nodes) == len(processes)
    if ros_tools:
        _lint(_python_packages(src), src)


def _walk_components(root):
    stack = [root]
    while stack:
        current = stack.pop()
        yield current
        stack.extend(current.componentInstances)


# --------------------------------------------------------------------------- the library


@pytest.mark.corpus
def test_library_tracking_application(library, tmp_path):
    instance = instantiate(library, "sys_tracking::tracking.impl")
    try:
        src = tmp_path / "src"
        result = generate_workspace(instance, src, options=OPTIONS)
        assert sorted(p.name for p in src.iterdir() if p.is_dir()) == [
            "nd_ocv_color_tracking",
            "nd_pos_to_cmd",
            "tracking_bringup",
            "tracking_interfaces",
            "usb_cam",
        ]
        launch = (src / "tracking_bringup/launch/tracking.launch.py").read_text()
        assert "('image_in', '/usb_cam/image_raw')" in launch and "prefix='taskset -c 1'" in launch
        _check_workspace(instance, result, src, ros_tools=True)
        _rosidl(sorted(src.rglob("*.msg")), src)
    finally:
        library.instances.remove(instance)


@pytest.mark.corpus
@pytest.mark.slow
def test_library_tracking_application_builds_with_colcon(library, tmp_path):
    if shutil.which("colcon") is None:
        pytest.skip("colcon is not installed (Debian packages colcon python3-colcon-ros)")
    instance = instantiate(library, "sys_tracking::tracking.impl")
    try:
        generate_workspace(instance, tmp_path / "src", options=OPTIONS)
    finally:
        library.instances.remove(instance)
    _colcon(tmp_path)


# --------------------------------------------------------------------------- ROSMOD projects


def _generate_project(
    library, project, tmp_path, *, ros_tools: bool, interfaces=None, key: str = "", colcon: bool = False
) -> tuple[int, int]:
    """(deployments generated, deployments in the project); the first deployment's .msg/.srv
    files go into ``interfaces`` under the project's name."""
    converted = converter.rosmod_to_aadl(project)
    units = list(converted.model.units)
    library.units.extend(units)
    generated = 0
    try:
        for index, (deployment, root) in enumerate(sorted(converted.roots.items())):
            instance = instantiate(library, root, strict=False)
            try:
                src = tmp_path / f"d{index}" / "src"
                result = generate_workspace(instance, src, options=OPTIONS, rosmod_trace=converted.trace)
                assert not [d for d in result.diagnostics if d.severity == "error"], deployment
                _check_workspace(instance, result, src, ros_tools=ros_tools and index == 0)
                if colcon and index == 0:
                    _colcon(src.parent)
                if index == 0 and interfaces is not None:
                    interfaces[key] = sorted(p for p in src.rglob("*") if p.suffix in (".msg", ".srv"))
                generated += 1
            finally:
                library.instances.remove(instance)
    finally:
        for unit in units:
            library.units.remove(unit)
    return generated, len(converted.roots)


@pytest.mark.corpus
@pytest.mark.parametrize("folder", _textual_projects(), ids=lambda p: p.name)
def test_rosmod_textual_project(library, interfaces, folder, tmp_path_factory):
    from rosaadl.importers.rosmod_text import read_project

    tools = folder.name in ROS_TOOLS_PROJECTS or ALL_ROS_TOOLS
    tmp_path = tmp_path_factory.mktemp(folder.name)
    generated, deployments = _generate_project(
        library, read_project(folder), tmp_path, ros_tools=tools, interfaces=interfaces, key=folder.name
    )
    assert generated == deployments  # a project without a deployment has no node to generate


@pytest.mark.corpus
@pytest.mark.parametrize("path", _webgme_files(), ids=lambda p: p.name)
def test_rosmod_webgme_projects(library, path, tmp_path):
    from rosaadl.importers.rosmod_webgme import read_webgmex

    projects = read_webgmex(path)
    assert projects
    generated = deployments = 0
    for index, project in enumerate(projects):
        done, total = _generate_project(library, project, tmp_path / f"p{index}", ros_tools=ALL_ROS_TOOLS)
        generated, deployments = generated + done, deployments + total
    assert generated == deployments > 0


@pytest.mark.corpus
def test_every_corpus_interface_parses_with_rosidl(library, interfaces, tmp_path_factory):
    """The .msg/.srv of the first deployment of every textual project, in one rosidl run."""
    if ros_python("rosidl") is None:
        pytest.skip("rosidl is not installed (Debian package python3-rosidl)")
    from rosaadl.importers.rosmod_text import read_project

    for folder in _textual_projects():
        if folder.name not in interfaces:  # the project's own test did not run in this session
            _generate_project(
                library,
                read_project(folder),
                tmp_path_factory.mktemp(folder.name),
                ros_tools=False,
                interfaces=interfaces,
                key=folder.name,
            )
    files = [path for name in sorted(interfaces) for path in interfaces[name]]
    assert len(files) > 20
    _rosidl(files, Path.cwd())


@pytest.mark.corpus
@pytest.mark.slow
@pytest.mark.parametrize(
    "folder",
    [f for f in _textual_projects() if ALL_ROS_TOOLS or f.name in ROS_TOOLS_PROJECTS],
    ids=lambda p: p.name,
)
def test_rosmod_project_builds_with_colcon(library, folder, tmp_path):
    """The first deployment of the project, built and tested with colcon."""
    if shutil.which("colcon") is None:
        pytest.skip("colcon is not installed (Debian packages colcon python3-colcon-ros)")
    from rosaadl.importers.rosmod_text import read_project

    generated, deployments = _generate_project(
        library, read_project(folder), tmp_path, ros_tools=False, colcon=True
    )
    assert generated == deployments

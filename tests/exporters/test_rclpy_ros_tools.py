"""The generated workspaces against the ROS 2 tools themselves (Debian's packages):
``ament_flake8``/``ament_pep257``/``ament_copyright`` with ROS 2's settings, ``colcon build`` and
``colcon test``, and ``rosidl_adapter``/``rosidl_parser`` on every ``.msg``/``.srv``.

Install the tools with ``apt-get install -y --no-install-recommends colcon python3-colcon-ros
python3-ament-flake8 python3-ament-pep257 python3-ament-copyright python3-rosidl
python3-flake8-blind-except python3-flake8-builtins python3-flake8-class-newline
python3-flake8-comprehensions python3-flake8-deprecated python3-flake8-docstrings
python3-flake8-import-order python3-flake8-quotes rosidl-core ament-cmake``; every test skips
with the reason when a tool is missing.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from test_rclpy_models import (
    hostile_instance,
    ros_environment,
    ros_python,
    services_instance,
)

from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace

OPTIONS = GenerationOptions(year=2024)
#: The flake8 plugins ROS 2's ament_flake8 runs with (its package's dependencies).
ROS_FLAKE8_PLUGINS = (
    "flake8-blind-except",
    "flake8-builtins",
    "flake8-class-newline",
    "flake8-comprehensions",
    "flake8-deprecated",
    "flake8-docstrings",
    "flake8-import-order",
    "flake8-quotes",
)
#: Interface packages that need ROS 2 message packages Debian does not have (geometry_msgs).
NEEDS_ROS_MESSAGES = ("app_interfaces",)


def _tool(name: str) -> str:
    path = shutil.which(name)
    if path is None:
        pytest.skip(f"{name} is not installed (Debian package python3-{name.replace('_', '-')})")
    return path


def _run(
    command: list[str], cwd: Path, python: str | None, timeout: int = 300
) -> subprocess.CompletedProcess:
    env = ros_environment(python) if python else None
    return subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    """One colcon workspace with the services and hostile-names applications (the tracking
    application is built from the library's text in ``test_rclpy_corpus``)."""
    root = tmp_path_factory.mktemp("colcon")
    results = {}
    for name, make in (("services", services_instance), ("hostile", hostile_instance)):
        _, instance = make()
        results[name] = generate_workspace(instance, root / "src" / name, options=OPTIONS)
    packages = sorted(p.parent for p in (root / "src").glob("*/*/package.xml"))
    return root, results, packages


def _python_packages(packages: list[Path]) -> list[Path]:
    return [p for p in packages if (p / "setup.py").is_file()]


def test_flake8_with_ros2_settings(workspace):
    tool = _tool("ament_flake8")
    python = ros_python("ament_flake8")
    version = _run([python, "-m", "flake8", "--version"], Path.cwd(), python)
    listed = "".join(version.stdout.split())  # flake8 wraps its plugin list
    missing = [p for p in ROS_FLAKE8_PLUGINS if p not in listed]
    if missing:
        pytest.skip(f"flake8 plugins of ROS 2 missing: {', '.join(missing)} (Debian python3-<plugin>)")
    root, _, packages = workspace
    paths = [str(p) for p in _python_packages(packages)]
    done = _run([tool, *paths], root, python)
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert "No problems found" in done.stdout


def test_pep257_with_ros2_settings(workspace):
    tool = _tool("ament_pep257")
    root, _, packages = workspace
    paths = [str(p) for p in _python_packages(packages)]
    done = _run([tool, *paths], root, ros_python("ament_pep257"))
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]


def test_copyright_headers(workspace):
    tool = _tool("ament_copyright")
    root, _, packages = workspace
    paths = [str(p) for p in _python_packages(packages)]
    done = _run([tool, *paths], root, ros_python("ament_copyright"))
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-2000:]
    assert "No problems found" in done.stdout


CHECK_INTERFACES = r"""
import pathlib, sys, tempfile
from rosidl_adapter.msg import convert_msg_to_idl
from rosidl_adapter.parser import parse_message_string, parse_service_string
from rosidl_adapter.srv import convert_srv_to_idl
from rosidl_parser.definition import IdlLocator
from rosidl_parser.parser import parse_idl_file

count = 0
for name in sys.argv[1:]:
    path = pathlib.Path(name)
    package_dir = path.parent.parent
    package = package_dir.name
    text = path.read_text()
    out = pathlib.Path(tempfile.mkdtemp())
    relative = path.relative_to(package_dir)
    if path.suffix == ".msg":
        spec = parse_message_string(package, path.stem, text)
        assert spec.fields or spec.constants or not text.strip(), name
        idl = convert_msg_to_idl(package_dir, package, relative, out)
    else:
        spec = parse_service_string(package, path.stem, text)
        idl = convert_srv_to_idl(package_dir, package, relative, out)
    parse_idl_file(IdlLocator(out, idl.relative_to(out)))
    count += 1
print("checked", count)
"""


def test_interfaces_parse_with_rosidl(workspace):
    python = ros_python("rosidl", "colcon")
    if python is None:
        pytest.skip("rosidl is not installed (Debian package python3-rosidl)")
    probe = _run([python, "-c", "import rosidl_adapter.parser, rosidl_parser.parser"], Path.cwd(), python)
    if probe.returncode != 0:
        pytest.skip("rosidl_adapter is not importable (Debian package python3-rosidl)")
    root, _, _ = workspace
    files = sorted(str(p) for p in (root / "src").rglob("*") if p.suffix in (".msg", ".srv"))
    assert len(files) >= 3
    done = _run([python, "-c", CHECK_INTERFACES, *files], root, python)
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert f"checked {len(files)}" in done.stdout


@pytest.mark.slow
def test_colcon_build_and_test(workspace):
    colcon = _tool("colcon")
    python = ros_python("colcon")
    root, _, packages = workspace
    names = [p.name for p in packages]
    skip = [n for n in NEEDS_ROS_MESSAGES if n in names]
    build = _run(
        [
            colcon,
            "build",
            "--base-paths",
            "src",
            "--packages-ignore",
            *skip,
            "--event-handlers",
            "console_cohesion+",
        ],
        root,
        python,
        timeout=600,
    )
    assert build.returncode == 0, build.stdout[-6000:] + build.stderr[-3000:]
    built = [n for n in names if n not in skip]
    for name in built:
        assert (root / "install" / name / "share" / name / "package.xml").is_file(), name
    # the interface package generated and compiled its C code from the .msg files
    assert list((root / "build" / "systeme_interfaces").rglob("donnees*.h"))
    test = _run(
        [colcon, "test", "--base-paths", "src", "--packages-ignore", *skip], root, python, timeout=600
    )
    assert test.returncode == 0, test.stdout[-6000:] + test.stderr[-3000:]
    result = _run([colcon, "test-result", "--all", "--verbose"], root, python)
    python_packages = [p for p in _python_packages(packages) if p.name not in skip]
    summary = result.stdout.strip().splitlines()[-1]
    assert summary == f"Summary: {3 * len(python_packages)} tests, 0 errors, 0 failures, 0 skipped", (
        result.stdout[-4000:]
    )

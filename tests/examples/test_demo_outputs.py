"""What ``rosaadl demo`` writes is accepted by the tools it is meant for: the ``.aaxl2`` files load
into OSATE's own metamodel, the Cheddar files re-import and keep to Cheddar's vocabulary, and the
ROS 2 workspace compiles, builds and passes its tests with colcon."""

from __future__ import annotations

import compileall
import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import pytest

from rosaadl.cli import main
from rosaadl.importers.cheddar import loads_cheddar

HELPERS = Path(__file__).resolve().parents[1] / "exporters"


def _helper(name: str) -> ModuleType:
    """A helper module of the exporter tests (OSATE conformance, Cheddar vocabulary, ROS tools)."""
    key = f"demo_outputs_{name}"
    if key not in sys.modules:
        if str(HELPERS) not in sys.path:
            sys.path.insert(0, str(HELPERS))  # the helpers import each other by module name
        spec = importlib.util.spec_from_file_location(key, HELPERS / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[key] = module
        spec.loader.exec_module(module)
    return sys.modules[key]


@pytest.fixture(scope="module")
def demo_out(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("demo") / "out"
    assert main(["-q", "demo", "-o", str(out)]) == 0
    return out


def test_aaxl2_files_load_into_osates_metamodel(demo_out: Path, corpus: Path) -> None:
    conformance = _helper("osate_conformance")
    files = sorted(demo_out.rglob("*.aaxl2"))
    assert len(files) == 3  # both deployments and the proposed binding
    for path in files:
        result = conformance.check(path.read_bytes(), corpus / "osate" / "metamodel")
        assert result.ok, (path.name, result)


def test_cheddar_files_reimport_and_keep_to_the_vocabulary(demo_out: Path) -> None:
    export_tests = _helper("test_cheddar_export")
    files = sorted(demo_out.rglob("*.xmlv3"))
    assert len(files) == 3
    for path in files:
        data = path.read_bytes()
        assert export_tests.conformance_problems(data, 3) == [], path.name
        back = loads_cheddar(data, str(path))
        threads = [
            o
            for o in back.instances[0].eAllContents()
            if getattr(o, "category", None) is not None
            and o.eClass.name == "ComponentInstance"
            and o.category.name == "thread"
        ]
        assert len(threads) == 3, path.name  # the three nodes' measured threads


@pytest.mark.slow
def test_workspace_compiles_builds_and_passes_colcon_test(demo_out: Path) -> None:
    src = demo_out / "ros2_ws" / "src"
    assert compileall.compile_dir(str(src), quiet=1, force=True)
    colcon = shutil.which("colcon")
    if colcon is None:
        pytest.skip("colcon is not installed (Debian package colcon)")
    models = _helper("test_rclpy_models")
    python = models.ros_python("colcon")
    env = models.ros_environment(python) if python else None
    root = src.parent
    # Debian has no rosidl_default_generators: the interfaces package is checked by the rclpy
    # tests with rosidl's parser instead (see tests/exporters/test_rclpy_ros_tools.py)
    ignore = ["tracking_interfaces"]

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([colcon, *args], cwd=root, env=env, capture_output=True, text=True, timeout=600)

    build = run("build", "--base-paths", "src", "--packages-ignore", *ignore)
    assert build.returncode == 0, build.stdout[-4000:] + build.stderr[-2000:]
    test = run("test", "--base-paths", "src", "--packages-ignore", *ignore)
    assert test.returncode == 0, test.stdout[-4000:] + test.stderr[-2000:]
    summary = run("test-result", "--all").stdout.strip().splitlines()[-1]
    assert summary.endswith("0 errors, 0 failures, 0 skipped"), summary

"""Layout and packaging: one distribution, one import namespace, data files shipped."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import tomllib

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ["rosaadl", "metamodels", "importers", "transforms", "analysis", "exporters", "library", "examples"]


def test_layout_folders_exist() -> None:
    for folder in FOLDERS + ["tests", "benchmarks"]:
        assert (ROOT / folder).is_dir(), folder
    for folder in FOLDERS:
        assert (ROOT / folder / "__init__.py").is_file(), folder


def test_every_python_package_is_declared() -> None:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    mapping = config["package-dir"]
    declared = set(config["packages"])
    reverse = {folder: pkg for pkg, folder in mapping.items()}
    found = set()
    for folder, package in reverse.items():  # only the mapped folders: demo output may hold packages too
        for init in (ROOT / folder).rglob("__init__.py"):
            rel = init.parent.relative_to(ROOT / folder)
            found.add(".".join([package, *rel.parts]))
    assert found == declared, f"undeclared: {sorted(found - declared)}, missing: {sorted(declared - found)}"


@pytest.mark.slow
def test_wheel_installs_only_rosaadl_with_data(tmp_path) -> None:
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), str(ROOT)],
        check=True,
        capture_output=True,
    )
    (wheel,) = tmp_path.glob("rosaadl-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names if not n.split("/")[0].endswith((".dist-info", ".data"))}
    assert tops == {"rosaadl"}
    for needed in (
        "rosaadl/metamodels/aadl.ecore",
        "rosaadl/metamodels/rosmod.ecore",
        "rosaadl/metamodels/trace.ecore",
        "rosaadl/transforms/engine.py",
        "rosaadl/cli/__init__.py",
    ):
        assert needed in names, needed
    # pure Python: built from pyproject.toml alone, no extension module inside
    assert wheel.name.endswith("-py3-none-any.whl"), wheel.name
    assert not [n for n in names if n.endswith((".so", ".pyd", ".c"))]
    top_level = next(n for n in names if n.endswith("top_level.txt"))
    assert zipfile.ZipFile(wheel).read(top_level).decode().split() == ["rosaadl"]

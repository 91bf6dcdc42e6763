"""The import layers hold (import-linter, with the contracts of pyproject.toml), and the rules
import-linter cannot see: every core module is under the core's contract, and no
transformation opens, reads or writes a file."""

from __future__ import annotations

import ast
import shutil
import sys
from pathlib import Path

import pytest
from layers import ROOT, check, package_folders, tomllib

CONTRACTS = {
    c["id"]: c
    for c in tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]["contracts"]
}
#: rosaadl's own subpackages that are layers above the core (everything else in rosaadl/ is core)
LAYERS = {"cli", "workflow"}


@pytest.mark.slow
def test_the_import_layers_hold() -> None:
    if not Path(sys.executable).with_name("lint-imports").exists() and shutil.which("lint-imports") is None:
        pytest.fail("lint-imports (import-linter, a dev dependency) is not installed")
    done = check()
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
    assert "Contracts: 3 kept, 0 broken." in done.stdout


def test_every_core_module_is_under_the_core_contract() -> None:
    core = ROOT / "rosaadl"
    modules = {f"rosaadl.{p.stem}" for p in core.glob("*.py") if p.stem not in ("__init__", "__main__")}
    modules |= {
        f"rosaadl.{p.name}" for p in core.iterdir() if (p / "__init__.py").is_file() and p.name not in LAYERS
    }
    modules.add("rosaadl.metamodels")
    assert set(CONTRACTS["core"]["source_modules"]) == modules
    layered = set(CONTRACTS["layers"]["layers"])
    assert {f"rosaadl.{name}" for name in LAYERS} <= layered
    # every mapped folder is a layer, the core, or data
    mapped = set(package_folders()) - {"rosaadl", "rosaadl.metamodels", "rosaadl.library", "rosaadl.examples"}
    assert mapped <= layered


#: what opens, reads or writes a file (a transformation takes models and gives models)
_FILE_METHODS = {"open", "read_text", "read_bytes", "write_text", "write_bytes", "mkdir", "unlink", "rmdir"}
_FILE_MODULES = {"os": {"replace", "rename", "remove", "makedirs"}, "shutil": None, "resources": {"files"}}


def test_no_transformation_touches_a_file() -> None:
    found = []
    for path in sorted(package_folders()["rosaadl.transforms"].rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call):
                continue
            func = node.func
            if isinstance(func, ast.Name):
                touches = func.id == "open"
                name = func.id
            elif isinstance(func, ast.Attribute):
                name = func.attr
                owner = func.value.id if isinstance(func.value, ast.Name) else None
                if owner in _FILE_MODULES:
                    touches = _FILE_MODULES[owner] is None or name in _FILE_MODULES[owner]
                else:
                    touches = name in _FILE_METHODS
            else:
                continue
            if touches:
                found.append(f"{path.relative_to(ROOT)}:{node.lineno}: {name}()")
    assert not found, "\n".join(found)

"""The import layers of rosaadl, checked with import-linter (the contracts are in pyproject.toml).

import-linter reads a package from its folder, but rosaadl's subpackages live in top-level
folders that ``pyproject.toml`` maps into ``rosaadl`` (``importers/`` is ``rosaadl.importers``),
which an editable install resolves at import time only. :func:`installed_layout` copies the
Python files into the layout a wheel has, and :func:`check` runs ``lint-imports`` on that copy.

``python tests/layers.py`` (what ``make lint`` runs) prints import-linter's report and exits with
its status.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10 (tomli is a dev dependency there)
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent


def package_folders(root: Path = ROOT) -> dict[str, Path]:
    """Package name → the folder it is read from (``[tool.setuptools] package-dir``)."""
    config = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    return {package: root / folder for package, folder in config["package-dir"].items()}


def installed_layout(dest: Path, root: Path = ROOT) -> Path:
    """Copy every module of the distribution into ``dest`` as a wheel lays them out; returns
    ``dest`` (the folder to put on ``sys.path``)."""
    for package, folder in package_folders(root).items():
        target = dest.joinpath(*package.split("."))
        for source in folder.rglob("*.py"):
            relative = source.relative_to(folder)
            if relative.parts and relative.parts[0] in (".venv", "build"):
                continue
            copy = target / relative
            copy.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, copy)
    return dest


def check(root: Path = ROOT) -> subprocess.CompletedProcess[str]:
    """Run ``lint-imports`` with the contracts of ``pyproject.toml`` on the installed layout."""
    linter = Path(sys.executable).with_name("lint-imports")
    with tempfile.TemporaryDirectory(prefix="rosaadl-layers-") as folder:
        layout = installed_layout(Path(folder) / "site", root)
        env = {**os.environ, "PYTHONPATH": str(layout)}
        return subprocess.run(
            [str(linter), str(root / "pyproject.toml"), "--no-cache"],
            cwd=folder,
            env=env,
            capture_output=True,
            text=True,
            timeout=300,
        )


if __name__ == "__main__":
    done = check()
    sys.stdout.write(done.stdout)
    sys.stderr.write(done.stderr)
    sys.exit(done.returncode)

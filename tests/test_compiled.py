"""The modules setup.py compiles (rosaadl.compiled): the compiled module is the one imported where it
was built, it refuses a source other than its own, and the Python source passes the same tests."""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
from pathlib import Path

import pytest

from rosaadl.compiled import MODULES, check_built_from_source, source_hash

ROOT = Path(__file__).resolve().parent.parent


def test_a_compiled_module_refuses_a_source_other_than_its_own(tmp_path: Path) -> None:
    compiled = tmp_path / "reader.cpython-311-x86_64-linux-gnu.so"
    compiled.write_bytes(b"\x7fELF")
    source = tmp_path / "reader.py"
    source.write_text("VALUE = 1\n")
    built_from = {"pkg.reader": source_hash(source)}
    check_built_from_source("pkg.reader", str(compiled), built_from)  # the same source: imported
    source.write_text("VALUE = 2\n")
    with pytest.raises(ImportError, match=r"compiled from another version of .*reader\.py: rebuild"):
        check_built_from_source("pkg.reader", str(compiled), built_from)
    with pytest.raises(ImportError, match="compiled from another version"):
        check_built_from_source("pkg.reader", str(compiled), {})  # no hash kept for it
    # the source itself, and a compiled module installed without its source, are not checked
    check_built_from_source("pkg.reader", str(source), {})
    source.unlink()
    check_built_from_source("pkg.reader", str(compiled), {})


def _built(name: str) -> list[Path]:
    """The compiled module ``name`` beside its source, if this install built it."""
    source = ROOT / MODULES[name]
    return sorted(source.parent.glob(f"{source.stem}.*.so"))


@pytest.mark.parametrize("name", sorted(MODULES))
def test_the_compiled_module_is_the_one_imported_where_it_was_built(name: str) -> None:
    built = _built(name)
    if not built:
        pytest.skip(f"{name} is not compiled in this install (no Cython or C compiler at install)")
    module = importlib.import_module(name)
    assert Path(module.__file__) == built[0]  # and its check passed: the source is its own


# imports the modules of rosaadl.compiled from their Python source, then runs pytest
_FROM_SOURCE = """
import importlib.abc, importlib.util, sys
from pathlib import Path
import pytest
root = Path(sys.argv[1])
modules = {MODULES!r}

class FromSource(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path, target=None):
        if name in modules:
            return importlib.util.spec_from_file_location(name, root / modules[name])
        return None

sys.meta_path.insert(0, FromSource())
code = pytest.main(sys.argv[2:])
for name in modules:
    assert sys.modules[name].__file__.endswith(".py"), sys.modules[name].__file__
sys.exit(code)
"""


@pytest.mark.slow
def test_the_python_source_of_the_compiled_modules_passes_their_tests() -> None:
    if not any(_built(name) for name in MODULES):
        pytest.skip("nothing is compiled in this install: the whole suite runs the source")
    script = _FROM_SOURCE.replace("{MODULES!r}", repr(MODULES))
    tests = ["tests/importers/test_aaxl2.py", "tests/test_fast_builder.py"]
    done = subprocess.run(
        [sys.executable, "-c", script, str(ROOT), "-q", "-p", "no:cacheprovider", *tests],
        cwd=ROOT,
        env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"},
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert " passed" in done.stdout and " failed" not in done.stdout

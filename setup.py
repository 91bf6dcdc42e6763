"""The build step of rosaadl (the rest of its packaging is in pyproject.toml): the modules named in
rosaadl/compiled.py are also compiled by Cython, each from its unchanged source into an extension
module of the same name, with the hash of that source written beside them for the check at import.

The extensions are optional: without Cython, with ROSAADL_NO_COMPILE set, or where the C compiler
fails, rosaadl installs without them and runs the Python source.
"""

import importlib.util
import os
from pathlib import Path

from setuptools import Extension, setup

ROOT = Path(__file__).resolve().parent


def _compiled_module():
    spec = importlib.util.spec_from_file_location("_rosaadl_compiled", ROOT / "rosaadl" / "compiled.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _write_atomically(path: Path, text: str) -> None:
    partial = path.with_name(path.name + ".partial")
    partial.write_text(text, encoding="utf-8")
    os.replace(partial, path)


def _extensions() -> list:
    if os.environ.get("ROSAADL_NO_COMPILE"):
        return []
    try:
        from Cython.Build import cythonize
    except ImportError:
        return []
    compiled = _compiled_module()
    hashes = {name: compiled.source_hash(ROOT / source) for name, source in compiled.MODULES.items()}
    lines = [f"    {name!r}: {digest!r},\n" for name, digest in sorted(hashes.items())]
    _write_atomically(
        ROOT / compiled.HASHES_FILE,
        '"""Written by setup.py: the hash of each compiled module\'s source (see rosaadl.compiled)."""\n\n'
        "SHA256 = {\n" + "".join(lines) + "}\n",
    )
    return cythonize(
        [Extension(name, [source], optional=True) for name, source in compiled.MODULES.items()],
        build_dir="build/cython",
        # the annotations document; they do not restrict what a function accepts
        compiler_directives={"language_level": "3", "annotation_typing": False},
        quiet=True,
    )


setup(ext_modules=_extensions())

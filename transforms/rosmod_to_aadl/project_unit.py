"""The ROSMOD → AADL rule of the project itself: its own unit.

The ``<project>_project`` package (``Unit_Kind => Project``) keeps the project's facts that no
other unit holds: the format version, the project's path, the name and file of its software
model, its settings.
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.transforms.engine import Context
from rosaadl.transforms.rosmod_to_aadl.rules import TRANSFORMATION, state, unit_header
from rosaadl.transforms.rosmod_to_aadl.vocabulary import (
    FORMAT_VERSION,
    PROJECT_PATH,
    SOFTWARE_NAME,
    SOURCE_FILE,
)

__all__: list[str] = []  # its rule is declared on TRANSFORMATION


@TRANSFORMATION.rule("rosmod.Project", name="project")
def _project(ctx: Context, src: EObject) -> EObject:
    st = state(ctx)
    f = st.factory
    pkg = unit_header(st, src, "Project")
    f.text(pkg, FORMAT_VERSION, src.formatVersion)
    f.text(pkg, PROJECT_PATH, src.path)
    if src.software is not None:
        f.text(pkg, SOFTWARE_NAME, src.software.name)
        f.text(pkg, SOURCE_FILE, src.software.sourceFile)
    f.settings(pkg, src.properties)
    return pkg

"""What the models of the workflow are read with: the component library's units.

Units made by a transformation are read together with the library (``read_files(...,
include_library=True)``), where a unit named like a library unit would replace it: the workflow
passes :func:`library_unit_names` to :func:`rosaadl.transforms.rosmod_to_aadl.rosmod_to_aadl` as
the names its packages must not take.
"""

from __future__ import annotations

from functools import lru_cache

from rosaadl.importers.aadl_text import library_files

__all__ = ["library_unit_names"]


@lru_cache(maxsize=1)
def library_unit_names() -> frozenset[str]:
    """Lower-case names of the library's units (one per ``.aadl`` file, named like the file),
    which generated packages must not take: a user unit named like a library unit replaces it."""
    return frozenset(path.name[: -len(".aadl")].lower() for path in library_files())

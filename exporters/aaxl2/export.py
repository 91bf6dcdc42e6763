"""The entry points of the ``.aaxl2`` writer: which instance to write, and where.

:func:`export_aaxl2` picks the instance (:func:`select_instance`: the ``SystemInstance``
given, the one instance of an ``AadlModel``, the one ``root`` names, or ``root`` instantiated
from the model's declarative units) and gives the document and its sidecars in memory
(:class:`Aaxl2Export`); :func:`dumps_aaxl2` gives the bytes alone and :func:`write_aaxl2`
writes both, atomically, under ``instances/`` of an output folder.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl.arguments import checked
from rosaadl.errors import Diagnostic, ExportError, Location
from rosaadl.fileio import safe_join, write_files
from rosaadl.model import is_a

from .document import write_document
from .sidecars import sidecar_texts
from .state import Writer
from .vocabulary import FILE_STEM_RE

__all__ = [
    "Aaxl2Export",
    "export_aaxl2",
    "dumps_aaxl2",
    "write_aaxl2",
    "instance_file_name",
    "select_instance",
    "INSTANCES_FOLDER",
]

#: The folder, under the output directory, that holds the ``.aaxl2`` file (as in OSATE projects).
INSTANCES_FOLDER = "instances"


@dataclass
class Aaxl2Export:
    """An instance file and its sidecars, in memory.

    ``file_name`` is relative to the output directory (``instances/X_Instance.aaxl2``);
    ``sidecars`` maps ``.aadl`` file names (relative to the output directory) to their text.
    """

    file_name: str
    data: bytes
    sidecars: dict[str, str] = field(default_factory=dict)
    warnings: list[Diagnostic] = field(default_factory=list)
    instance: EObject | None = None


def select_instance(
    subject: EObject, root: str | None, diagnostics: list[Diagnostic]
) -> tuple[EObject, EObject | None]:
    """(the SystemInstance to write, the AadlModel holding its declarative model, or None)."""
    if not isinstance(subject, EObject):
        raise ExportError(f"expected an AadlModel or a SystemInstance, got {type(subject).__name__}")
    if is_a(subject, "SystemInstance"):
        container = subject.eContainer()
        aadl_model = container if container is not None and is_a(container, "AadlModel") else None
        if root and not root_matches(subject, root):
            raise ExportError(
                f"root {root!r} does not match the instance given ({subject.classifier or subject.name})",
                Location(path=subject.name or None),
            )
        return subject, aadl_model
    if not is_a(subject, "AadlModel"):
        raise ExportError(f"expected an AadlModel or a SystemInstance, got a {subject.eClass.name}")
    instances = list(subject.instances)
    if root:
        matches = [i for i in instances if root_matches(i, root)]
        if matches:
            return matches[-1], subject
        if not subject.units:
            known = ", ".join(i.classifier or i.name or "?" for i in instances) or "none"
            raise ExportError(
                f"root {root!r} is not an instance of the model (instances: {known}) and the model has "
                "no declarative units to instantiate it from",
                Location(path=root),
            )
        from rosaadl.transforms.instantiate import Instantiator

        instantiator = Instantiator(subject)
        system = instantiator.run(root)
        diagnostics.extend(instantiator.diagnostics)
        return system, subject
    if len(instances) == 1:
        return instances[0], subject
    if not instances:
        raise ExportError(
            "the model holds no system instance; name the root implementation to instantiate "
            "(root='Pkg::System.impl')"
        )
    names = ", ".join(i.classifier or i.name or "?" for i in instances)
    raise ExportError(f"the model holds {len(instances)} system instances ({names}); name the one to write")


def root_matches(instance: EObject, root: str) -> bool:
    """Is ``root`` (``Pkg::Sys.impl``, spaces and case aside) the instance's classifier or name?"""
    wanted = "".join(root.split()).lower()
    return wanted in ((instance.classifier or "").replace(" ", "").lower(), (instance.name or "").lower())


def instance_file_name(instance: EObject) -> str:
    """OSATE's file name for an instance: ``Pkg_Type_impl_Instance.aaxl2`` (``::`` and ``.`` → ``_``)."""
    classifier = (instance.classifier or "").strip()
    if classifier and "#" not in classifier and "/" not in classifier:
        stem = classifier.replace("::", "_").replace(".", "_") + "_Instance"
    else:
        stem = instance.name or ""
    if not FILE_STEM_RE.match(stem):
        raise ExportError(
            f"cannot name the instance file after {stem!r}: expected letters, digits and underscores",
            Location(path=instance.name or None),
        )
    return f"{stem}.aaxl2"


@checked
def export_aaxl2(subject: EObject, *, root: str | None = None) -> Aaxl2Export:
    """An instance as an OSATE ``.aaxl2`` document and its ``.aadl`` sidecars, in memory.

    ``subject`` is a ``SystemInstance`` or an ``AadlModel``; ``root`` (``Pkg::Sys.impl``) picks
    the instance of the model to write, or the implementation to instantiate when the model holds
    no such instance. Problems are :class:`ExportError` naming the instance path.
    """
    diagnostics: list[Diagnostic] = []
    system, aadl_model = select_instance(subject, root, diagnostics)
    writer = Writer(system, aadl_model, diagnostics)
    data = write_document(writer)
    sidecars = sidecar_texts(writer)
    file_name = f"{INSTANCES_FOLDER}/{instance_file_name(system)}"
    return Aaxl2Export(file_name, data, sidecars, diagnostics, system)


@checked
def dumps_aaxl2(
    subject: EObject, *, root: str | None = None, warnings: list[Diagnostic] | None = None
) -> bytes:
    """The ``.aaxl2`` bytes of an instance (see :func:`export_aaxl2`); warnings are logged and
    appended to ``warnings`` when given."""
    result = export_aaxl2(subject, root=root)
    if warnings is not None:
        warnings.extend(result.warnings)
    return result.data


@checked
def write_aaxl2(
    subject: EObject,
    out_dir: str | os.PathLike[str],
    *,
    root: str | None = None,
    warnings: list[Diagnostic] | None = None,
) -> Path:
    """Write ``instances/<Name>_Instance.aaxl2`` and its ``.aadl`` sidecars into ``out_dir``.

    Everything is made in memory first, so an error leaves no output; the files are written
    all-or-nothing (:func:`rosaadl.fileio.write_files`) and no path lands outside ``out_dir``.
    Returns the path of the ``.aaxl2`` file; warnings are logged and appended to ``warnings``
    when given.
    """
    result = export_aaxl2(subject, root=root)
    targets = [(safe_join(out_dir, name), text) for name, text in result.sidecars.items()]
    instance_path = safe_join(out_dir, *result.file_name.split("/"))
    write_files([*targets, (instance_path, result.data)])
    if warnings is not None:
        warnings.extend(result.warnings)
    return instance_path

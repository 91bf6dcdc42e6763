"""The state of one ``.aaxl2`` export, shared by the parts of the writer: :class:`Writer`.

A :class:`Writer` holds the instance to write and its declarative model (with the
:class:`~.declarations.Declarations` that place hrefs into it), the EMF path of every instance
object (:mod:`.paths`), the lines of the document being written, and what the writing of
property values learns on the way (types, the era each of OSATE's sets is written in, the
associations left out). Its methods are the helpers every part uses: located errors and
warnings, escaped attribute text, and intra-file references by EMF path.

The writing itself is functions over a :class:`Writer`: :mod:`.instances` (instance objects),
:mod:`.values` (property associations and values), :mod:`.document` (the document and its
report) and :mod:`.sidecars`.
"""

from __future__ import annotations

import logging
from typing import Any

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic, ExportError, Location
from rosaadl.model import instance_path, is_a

from .declarations import Declarations
from .emf_text import INVALID_XML, InvalidText, attr_text
from .property_types import TypeBuilder, TypeInfo

__all__ = ["Writer"]

log = logging.getLogger(__package__)


class Writer:
    """One export (no state survives it)."""

    def __init__(self, system: EObject, aadl_model: EObject | None, diagnostics: list[Diagnostic]) -> None:
        self.system = system
        self.model = aadl_model
        self.warnings = diagnostics
        self.resolver = None
        if aadl_model is not None and len(aadl_model.units):
            from rosaadl.resolution import Resolver

            self.resolver = Resolver(aadl_model)
        self.types = TypeBuilder(self.resolver) if self.resolver is not None else None
        self.links = Declarations(self.resolver)
        # EMF paths: of every instance object by id(), the roots written, operation modes by name
        self.paths: dict[int, str] = {}
        self.roots: list[EObject] = []
        self.som_by_name: dict[str, EObject] = {}
        # the document being written (lines), and the namespaces annex instances bring
        self.out: list[str] = []
        self.extra_ns: dict[str, str] = {}
        # property values: associations left out, caches, the era of each of OSATE's sets
        self.skipped: list[str] = []
        self.property_cache: dict[str, tuple[str, TypeInfo | None]] = {}
        self.literal_cache: dict[tuple, str] = {}
        self.set_eras: dict[str, str] = {}
        self.wanted_set_eras: dict[str, str] = {}

    # ------------------------------------------------------------------ diagnostics

    def warn(self, message: str, obj: EObject | None = None) -> None:
        path = instance_path(obj) if obj is not None and is_a(obj, "InstanceObject") else None
        diagnostic = Diagnostic("warning", message, Location(path=path))
        self.warnings.append(diagnostic)
        log.warning("%s", diagnostic)

    def error(self, message: str, obj: EObject | None = None) -> ExportError:
        path = instance_path(obj) if obj is not None and is_a(obj, "InstanceObject") else None
        return ExportError(message, Location(path=path or (obj.name if obj is not None else None)))

    def text(self, value: str, obj: EObject | None, what: str) -> str:
        """``value`` as an attribute's text (a located error for a character XML cannot carry)."""
        try:
            return attr_text(value)
        except InvalidText:
            bad = next(c for c in value if INVALID_XML.match(c))
            raise self.error(
                f"{what} {value!r} holds the character U+{ord(bad):04X}, which an XML 1.0 file cannot carry",
                obj,
            ) from None

    # ------------------------------------------------------------------ intra-file references

    def ref(self, target: EObject | None, owner: EObject, what: str) -> str:
        """The EMF path of ``target``, an object of the exported instance (else a located error)."""
        if target is None:
            raise self.error(f"{what} refers to nothing", owner)
        path = self.paths.get(id(target))
        if path is None:
            shown = instance_path(target) if is_a(target, "InstanceObject") else target.name
            raise self.error(f"{what} refers to {shown!r}, which is not part of the exported instance", owner)
        return path

    def refs(self, targets: Any, owner: EObject, what: str) -> str:
        return " ".join(self.ref(t, owner, what) for t in targets)

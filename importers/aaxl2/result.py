"""What an ``.aaxl2`` import gives back: :class:`ImportResult`."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cached_property

from pyecore.ecore import EObject

from rosaadl.errors import Diagnostic

__all__ = ["ImportResult"]


@dataclass
class ImportResult:
    """What :func:`~rosaadl.importers.aaxl2.read_aaxl2` produced.

    ``model`` is an ``AadlModel``: ``instances`` (SystemInstance roots), ``componentInstances``
    (further ``ComponentInstance`` roots of an ``xmi:XMI`` file, such as the data-type
    instances ``FeatureInstance.type`` refers to) and ``units`` (for declarative files).
    ``era`` is the OSATE era whose predeclared property sets the file refers to (None when it
    refers to none); ``property_set_eras`` names the sets decoded with another era's table
    (see :class:`~rosaadl.importers.osate_eras.EraChoice`); ``warnings`` also holds ``info``
    diagnostics; ``sidecars`` maps each declarative ``.aadl`` URI the file refers to
    (other than predeclared sets) to its resolved path and whether that file is present
    (looked up on first use: an import itself touches no file).
    """

    model: EObject
    source: str
    kind: str  # "instance" | "package" | "property set"
    era: str | None = None
    property_set_eras: dict[str, str] = field(default_factory=dict)
    warnings: list[Diagnostic] = field(default_factory=list)
    # the declarative URIs, and the directory relative ones resolve against (None: kept as URIs;
    # not normalised, the paths in ``sidecars`` are)
    sidecar_uris: tuple[str, ...] = ()
    base_dir: str | None = None

    @cached_property
    def sidecars(self) -> dict[str, tuple[str, bool]]:
        out = {}
        for uri in self.sidecar_uris:
            if self.base_dir is None or ":" in uri.split("/")[0]:
                out[uri] = (uri, False)
                continue
            resolved = os.path.normpath(os.path.join(self.base_dir, uri))
            out[uri] = (resolved, os.path.isfile(resolved))
        return out

    @property
    def instances(self) -> list[EObject]:
        return list(self.model.instances)

    @property
    def root(self) -> EObject | None:
        """The first system instance (None for declarative files)."""
        return self.model.instances[0] if self.model.instances else None

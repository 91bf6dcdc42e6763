"""WebGME ROSMOD exports (``.webgmex``) → ``rosmod.ecore`` models, one ``Project`` per ROSMOD project.

A ``.webgmex`` file is a zip archive whose ``project.json`` holds the content-addressed objects of
one WebGME project tree; the reader follows WebGME's own rules (``common/core`` of
webgme-engine) to navigate it, then maps each ROSMOD project onto ``rosmod.ecore``. WebGME facts
without a slot go into ``properties`` (keys of attributes exactly as WebGME spells them; children
without a slot as ``"<Kind>:<name>"`` properties whose value is a JSON object of their attributes
and pointers).

The modules, one idea each:

* :mod:`.projects` — the entry points (:func:`read_webgmex`, :func:`project_names`) and the
  mapping of one project;
* :mod:`.archive` — the zip archive and its safety checks (:func:`load_project_json`,
  :data:`~.archive.MAX_TOTAL_BYTES`, :data:`~.archive.MAX_MEMBERS`);
* :mod:`.tree` — the WebGME tree: overlays, inheritance, pointers, the META aspect;
* :mod:`.mapping` — the state of one project's mapping and the helpers its parts share;
  :mod:`.software`, :mod:`.systems`, :mod:`.deployments` — the parts of a project (their
  docstrings give the mapping of each).

Problems are raised together as a :class:`~rosaadl.importers.rosmod_text.RosmodImportError`,
the error of the textual reader, collected by the same
:class:`~rosaadl.importers.rosmod_text.context.ImportContext`.
"""

from __future__ import annotations

from rosaadl.importers.rosmod_webgme.archive import MAX_MEMBERS, MAX_TOTAL_BYTES, load_project_json
from rosaadl.importers.rosmod_webgme.projects import project_names, read_webgmex

__all__ = [
    "MAX_TOTAL_BYTES",
    "MAX_MEMBERS",
    "read_webgmex",
    "project_names",
    "load_project_json",
]

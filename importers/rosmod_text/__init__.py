"""Textual ROSMOD projects (v0.3, v0.2, v0.1 and the v0.4 jsonpickle file) → ``rosmod.ecore`` models.

Layouts read by :func:`read_project`:

* **v0.3** — a folder with a ``<name>.rosmod`` marker and ``01-Software/`` (one ``.rml`` file,
  ``msg/<pkg>.<Name>.msg``, ``srv/<pkg>.<Name>.srv``, ``abl/`` and ``pnp/`` side files),
  ``02-Hardware/*.rhw`` (one :class:`System` per file) and ``03-Deployment/*.rdp`` (one
  :class:`Deployment` per file); the older folder names ``01-Software-Configuration/``,
  ``02-Hardware-Configuration/`` are accepted too;
* **v0.2** — the same folders (or the three files side by side) with a single-workspace ``.rml``
  holding ``messages``/``services``/``components``/``nodes`` blocks, ``host`` hardware and
  ``host_instance`` deployments;
* **v0.1** — a ``.rosml`` file (``workspace W;`` + v0.2-style packages; software only);
* **v0.4** — the jsonpickle ``.rml`` of ROSMOD's Python tool, read without unpickling anything.

The parsers are hand-written and tolerant of what real files do: ``/* */`` and ``//``
comments, CRLF, keys with spaces and ``?`` (``Is Periodic? = true;``), properties in any order,
unknown statements (skipped with a warning). Names are resolved after parsing; every problem
(syntax, unknown host, unknown package or component, duplicate name, unknown message type of
one of the project's own packages) is collected with its file, line and column and raised
together as a :class:`RosmodImportError`. Types of packages that are not in the project
(``std_msgs/String``) are kept as external references, not errors. Line and column are kept on
every element read from text; ``sourceFile`` (relative to the project folder) on the software,
each system and each deployment.

The modules, one idea each:

* :mod:`.project` — the entry points: the files of a project, the dialect of each, the order
  of reading; :mod:`.summary` — the counts of a project;
* :mod:`.v03`, :mod:`.v02`, :mod:`.v01`, :mod:`.v04` — one dialect each (their docstrings give
  how each maps onto ``rosmod.ecore``); :mod:`.groups` — the top-level ``group`` blocks of a
  deployment (``group G { <node>/<component instance>/<port> … }``), beside ``group = "…";``;
* :mod:`.blocks` — the tokenizer and the generic statement tree the block dialects share;
  :mod:`.statements` — values, names and model objects read from statements;
  :mod:`.files` — reading a file safely (:data:`~.files.MAX_FILE_BYTES`), side files;
* :mod:`.resolution` — the names across files; :mod:`.context` — the errors and warnings of a
  run (:class:`RosmodImportError` and the :class:`~.context.ImportContext` the WebGME reader
  shares).
"""

from __future__ import annotations

from rosaadl.importers.rosmod_text.context import RosmodImportError
from rosaadl.importers.rosmod_text.files import MAX_FILE_BYTES
from rosaadl.importers.rosmod_text.project import is_rosmod_project, read_project, read_software_file
from rosaadl.importers.rosmod_text.statements import scheme_literal
from rosaadl.importers.rosmod_text.summary import SUMMARY_KEYS, summarize

__all__ = [
    "MAX_FILE_BYTES",
    "RosmodImportError",
    "read_project",
    "read_software_file",
    "is_rosmod_project",
    "summarize",
    "SUMMARY_KEYS",
    "scheme_literal",
]

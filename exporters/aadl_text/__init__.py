"""AADL v2 text (SAE AS5506C) from the declarative AADL model.

:func:`write_unit` turns one ``AadlPackage`` or ``PropertySet`` into AADL text that OSATE
accepts: two spaces per level, sections in the standard's order, one blank line between
classifiers, a trailing newline. The same model always gives the same text, byte for byte.
:func:`write_units` names the texts (``a::b`` → ``a-b.aadl``) and :func:`write_model` writes them
atomically into a folder, never outside it.

Every name the writer puts in the text is checked: an element whose name is not an AADL
identifier, or a reference that is not a well-formed qualified name or path, is an
:class:`~rosaadl.errors.ExportError` naming the element, never text that would not read back.
Reserved words used as names (``data: out event data port``) are accepted, with a warning,
because real models do this and our reader reads them; OSATE does not.

How the opaque and list attributes of the metamodel are written:

* ``arrayDimensions``: one string per dimension, the size (``"3"``), a property constant
  (``"Pkg::Size"``) or ``""`` for ``[]``; written ``[3][Pkg::Size]``. A string already in
  brackets (``"[3]"``) is accepted too.
* ``prototypeBindings`` (classifiers and subcomponents): the binding text, with or without its
  outer parentheses (``"p => data T"`` or ``"(p => data T)"``); written in parentheses after the
  ``extends`` clause of a classifier, after the classifier of a subcomponent.
* ``Prototype.text``: the text after ``name:`` (and after ``refined to``), e.g. ``"data T"``.
* ``arrayElementBindings``: one implementation reference per element, written ``(A.i, B.i)``.
* ``AnnexSubclause.text`` / ``AnnexLibrary.text``: the annex text with or without its ``{** **}``
  delimiters; ``None`` is written ``none``.
* An access connection's category comes from ``Connection.accessCategory`` when it is set,
  else from the features and subcomponents its ends name (found in the model); when neither
  tells, ``access`` is written alone (our reader accepts it; OSATE needs the category) and a
  warning is logged.
* The direction of a feature group or abstract feature: ``in out`` is written as no direction
  word (OSATE's reading of an undirected one), ``in``/``out`` as such.
* Modal values are written in parentheses, ``(v1 in modes (a), v2)``, the form OSATE reads;
  a property block of a flow implementation is written although OSATE's grammar has none there.

The modules, each one idea, around one shared state (:class:`.context.UnitContext`: the lines,
where the writer is, the name checks):

* :mod:`.lexical`: the lexical rules names are checked against, reserved words, category words,
  :func:`unit_file_name`;
* :mod:`.context`: the state of one unit being written;
* :mod:`.packages`, :mod:`.classifiers`, :mod:`.implementations`, :mod:`.property_sets`: the
  text of each kind of element;
* :mod:`.associations`: property associations (values printed by
  :class:`rosaadl.property_text.ValuePrinter`, with the context's name checks);
* :mod:`.writer`: the public functions.
"""

from rosaadl.exporters.aadl_text.lexical import RESERVED_WORDS, unit_file_name
from rosaadl.exporters.aadl_text.writer import write_model, write_unit, write_units
from rosaadl.property_text import format_real

__all__ = ["write_unit", "write_units", "write_model", "unit_file_name", "format_real", "RESERVED_WORDS"]

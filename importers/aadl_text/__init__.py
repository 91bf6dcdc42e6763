"""AADL v2 text (SAE AS5506C) into the declarative AADL model (``metamodels/aadl.ecore``).

:func:`read_string` reads the packages and property sets of one text into an ``AadlModel``;
:func:`read_files` reads files and folders (``.aadl``/``.aadl2``, folders searched recursively in
sorted order) together with the component library of this project (``library_files``), then
checks names, units and enumeration literals across all of them.

The text is parsed by :mod:`rosaadl.importers.aadl_syntax` (a deterministic LALR(1) grammar);
the builder makes each classifier, package and property set as soon as the parser has made its
node, and its tree is released then (the whole parse tree of a file is never held: reading
takes the memory of the model, the text and the tree of one classifier), with
:class:`rosaadl.bulk.FastFactory` (no pyecore notifications or per-value checks: the values are
typed by construction).  What the text says is kept: names and references exactly
as written (``Timing_Properties::Period``, ``ros_data::Image.rgb``, ``a.b[2].c``), every value
form, ``line``/``column`` on every element and ``sourceFile`` on every unit.  Only comments and
layout are lost.  Constructs that the metamodel keeps as text:

* prototypes: a ``Prototype`` with ``text`` = what follows ``name:`` (and ``refined to``), e.g.
  ``"data Base_Types::Integer"``; prototypes are kept but not interpreted (a warning says so);
* prototype bindings: their source text in parentheses, ``"(p => data D)"``;
* array element implementations: ``"A.impl"`` or ``"A.impl (p => data D)"``;
* array dimensions: ``"3"``, ``"Pkg::Size"`` or ``""`` for ``[]``;
* annex subclauses and libraries: ``text`` is exactly what lies between ``{**`` and ``**}``
  (``None`` for ``annex X none;``);
* mode references in ``in modes``: ``"m"`` or ``"m => n"``; connection ends and triggers
  ``processor.x`` / ``self.x`` as written; ``applies to (all)`` is ``["all"]``.

Values: integers (based ``16#FF#``, exponents ``1e3``, underscores) become Python ints and must
fit the metamodel's 64-bit ``ELong``; reals become floats; strings are unescaped (``""`` and
``\\"`` are ``"``); ``-X`` on a named constant is an ``OperationValue`` ``-``, as are ``not``,
``and`` and ``or``.

Errors are located (file:line:column): syntax errors and literals out of range
(:class:`AadlSyntaxError`); the legality rules the grammar leaves to the builder
(:class:`ValidationError`, every one found in the text in one error: which subcomponent and
feature categories a component category may hold, as AS5506C's containment rules say
(:data:`SUBCOMPONENTS_ALLOWED`, :data:`FEATURES_ALLOWED`), which connection kinds, calls and
flows it may have, an implementation of another category than its type, ``end`` names, unit
conversions); and, in :func:`read_files`, the names, units and enumeration literals that do not
resolve (:class:`NameResolutionError`, every one in one error; with ``lenient=True`` a classifier
or package that is not found is a warning instead, as OSATE reads a project whose with-ed package
is missing).  A name declared twice in one namespace is a warning (real, tool-generated models
have them; look-ups find the first).

The package, one idea per module:

* :mod:`.reading`: the entry points (``read_string``, ``read_files``, ``library_files``);
* :mod:`.units`: the builder of packages and classifiers (:func:`.units.read_units`: built while
  parsed), around :mod:`.members` (the members
  of classifiers), :mod:`.values` (property associations and values) and
  :mod:`.property_sets` (property sets and types);
* :mod:`.legality`: the legality tables and the checks of what AADL allows where, with the
  diagnostics of one file;
* :mod:`.checks`: the checks across units (names, units, enumeration literals);
* :mod:`.factory` (making model objects fast), :mod:`.lexical` (literals and the source text)
  and :mod:`.tree` (the vocabulary of the parse tree and small readers of its nodes).
"""

from __future__ import annotations

from rosaadl.importers.aadl_text.legality import (
    CALLS_ALLOWED,
    CONNECTIONS_ALLOWED,
    FEATURES_ALLOWED,
    SUBCOMPONENTS_ALLOWED,
)
from rosaadl.importers.aadl_text.reading import AADL_SUFFIXES, library_files, read_files, read_string

__all__ = [
    "read_string",
    "read_files",
    "library_files",
    "AADL_SUFFIXES",
    "FEATURES_ALLOWED",
    "SUBCOMPONENTS_ALLOWED",
    "CONNECTIONS_ALLOWED",
    "CALLS_ALLOWED",
]

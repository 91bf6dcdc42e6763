"""Read OSATE ``.aaxl2`` files: instance models (and declarative packages / property sets).

:func:`read_aaxl2` turns an OSATE instance file into our instance model (see
``docs/instance-model.md``): an ``AadlModel`` whose ``instances`` hold the ``SystemInstance``
roots, with component, feature, connection, flow and mode instances and the property values
OSATE resolved onto them. Declarative ``.aaxl2`` files (root ``aadl2:Package`` or
``aadl2:PropertySet``) become an ``AadlPackage`` / ``PropertySet`` in ``AadlModel.units``.

What the file format gives, and how it is decoded:

* Intra-file references: ``//@componentInstance.4/@featureInstance.0`` (``/`` is the root,
  ``/1/@…`` the second root of an ``xmi:XMI`` file), space-separated lists, or ``xmi:id``
  UUIDs in 2014 files. All must resolve; a dangling one is a located error.
* References into the declarative model are ``href`` child elements: classifiers and
  properties by qualified name (``../P.aadl#P.L.i`` → ``P::L.i``,
  ``…#Timing_Properties.Period`` → ``Timing_Properties::Period``); subcomponents, features,
  modes and flows by position, whose names are those of the instance elements. Declared
  connections are only known by position: ``ConnectionReference.connection`` keeps the href
  (``uri#fragment``) until the ``.aadl`` sidecars are read.
* Units, enumeration literals and record fields are positional hrefs into the property set
  that declares them. For OSATE's predeclared sets they are decoded with the per-era tables
  of :mod:`rosaadl.importers.osate_eras`; the era is chosen from the URI forms and checked
  against every such href (see :func:`~rosaadl.importers.osate_eras.choose_era`) and recorded
  on the result.
  Hrefs into other property sets keep their ``uri#fragment`` text and are reported once
  per property set.
* EMF omits default values: a component without ``category`` is abstract, a feature without
  one a data port, no ``direction`` is ``in``, no ``kind`` a feature connection, booleans false.
* Annex instances (EMV2) are kept opaque: an ``AnnexInstance`` with the element's XML text.

Speed: pyecore's normal object construction costs about 25 µs per object (feature lookups,
value checks, notifications to listeners a new object cannot have yet). The reader builds
objects through :class:`~rosaadl.bulk.FastFactory`, which writes the state pyecore would
(attribute value holders, container and containment feature; ``_isset``, which saving reads,
and inverse references are made on first read from those) directly, in about a tenth of that
time, and pauses the cyclic garbage collector while it builds (:func:`~rosaadl.bulk.gc_paused`).
The file is parsed without its indentation (half the nodes), and the parsed document is freed
last (:meth:`.document.Reader.release`), so that glibc does not merge its freed nodes within
the call.

The package, one idea per module:

* :mod:`.load`: the entry points (:func:`read_aaxl2`, :func:`loads_aaxl2`) and the order of a read;
* :mod:`.document`: :class:`~.document.Reader`, the state of one read and its helpers (located
  errors, ``xsi:type``, hrefs and links, references queued for later);
* :mod:`.instances`: one reader per instance element (components, features, connections, ...);
* :mod:`.values`: property associations and values;
* :mod:`.references`: intra-file references, resolved once every object exists;
* :mod:`.literals`: positional hrefs into property sets, decoded once the era is known;
* :mod:`.declarative`: ``aadl2:Package`` and ``aadl2:PropertySet`` files;
* :mod:`.xmi`: the file format's vocabulary (namespaces, tags, class names) and href text;
* :mod:`.metamodel`: what the reader needs from ``aadl.ecore``, looked up once per process;
* :mod:`.result`: :class:`ImportResult`.
"""

from __future__ import annotations

from .load import DEFAULT_MAX_BYTES, loads_aaxl2, read_aaxl2
from .result import ImportResult

__all__ = [
    "ImportResult",
    "read_aaxl2",
    "loads_aaxl2",
    "DEFAULT_MAX_BYTES",
]

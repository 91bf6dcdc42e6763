"""Write OSATE ``.aaxl2`` instance files, with the ``.aadl`` sidecars their references point into.

:func:`write_aaxl2` takes a ``SystemInstance`` (or an ``AadlModel`` holding one, or a declarative
``AadlModel`` and the root implementation to instantiate) and writes what OSATE itself would
write: ``instances/<Pkg>_<Type>_<impl>_Instance.aaxl2`` and, beside the ``instances`` folder, the
packages and property sets the instance refers to, written by :mod:`rosaadl.exporters.aadl_text`.
:func:`dumps_aaxl2` gives the ``.aaxl2`` bytes alone and :func:`export_aaxl2` everything in
memory (bytes, sidecar texts, warnings).

The file follows OSATE's serialisation (EMF's XMI writer on ``aadl2.ecore``/``instance.ecore``):

* ``encoding="ASCII"``: every other character is written as a character reference
  (``&#xE9;``), as are line feeds, carriage returns and tabs in attribute values;
* elements and attributes in the metamodel's feature order (attributes: ``name``,
  ``category``, ``direction``, ...; children: property associations, feature instances,
  component instances, modes, flows, connection instances, then the links into the
  declarative model: ``subcomponent``, ``index``, ``classifier``);
* EMF's default omission: no ``category`` on an abstract component or a data port, no
  ``direction`` for ``in``, no ``kind`` for a feature connection, no boolean that is false,
  no number that is zero; Java enumeration literals (``in out``, ``thread group``);
  ``<index>0</index>`` children for components that are not array elements;
* intra-file references as EMF paths (``//@componentInstance.4/@featureInstance.0``, the root
  ``/``; ``/0/@…`` and ``/1`` when an ``xmi:XMI`` document holds several roots);
* references into the declarative model as ``href`` children: classifiers and properties by
  qualified name with every ``::`` written ``.``, as OSATE's fragment provider names them
  (``../P.aadl#P.T.impl``, ``…/Timing_Properties.aadl#Timing_Properties.Period``,
  ``../functional-Alert.aadl#functional.Alert.Alert.basic`` for ``package functional::Alert``;
  :func:`.vocabulary.name_fragment`), subcomponents, features, connections, modes and flows
  by position, counted the way OSATE's Xtext model holds them
  (``#/0/@ownedPublicSection/@ownedClassifier.10/@ownedAbstractSubcomponent.0``: classifiers
  per package section, members per containment list of their class);
* units and enumeration literals of OSATE's own property sets as positional references of the
  current OSATE era (:mod:`rosaadl.importers.osate_eras`), under
  ``platform:/plugin/org.osate.aadl2.contrib/…`` (``org.osate.contribution.sei`` for ``SEI``,
  ``Data_Model``, ``Base_Types``, …); those of other property sets point into the sidecars.

Instances read from an ``.aaxl2`` file have no declarative model: references that the reader
kept as written (``uri#fragment``) are written back as they were, classifiers and properties by
qualified name, and links the reader did not keep (a feature instance's declaration) are left
out, with one warning that says how many.

The package, one idea per module:

* :mod:`.export`: the entry points, and which instance a call writes;
* :mod:`.state`: :class:`~.state.Writer`, the state of one export and its helpers;
* :mod:`.paths`: the roots of the file and the EMF path of every instance object;
* :mod:`.instances`: instance objects as XMI elements;
* :mod:`.values`: property associations and values as XMI elements;
* :mod:`.value_hrefs`: the hrefs a value's names become (properties, units, literals, fields);
* :mod:`.declarations`: hrefs into the declarative model (classifiers, members by position);
* :mod:`.property_types` and :mod:`.osate_sets`: what a value's type tells, from the model,
  the library's copy of OSATE's sets, or the era tables;
* :mod:`.document`: the document, written again for an older era's layout when needed, and
  its report;
* :mod:`.sidecars`: the ``.aadl`` files written beside the instance;
* :mod:`.emf_text` and :mod:`.vocabulary`: EMF's text forms and OSATE's class names.
"""

from __future__ import annotations

from .emf_text import java_double
from .export import (
    INSTANCES_FOLDER,
    Aaxl2Export,
    dumps_aaxl2,
    export_aaxl2,
    instance_file_name,
    write_aaxl2,
)

__all__ = [
    "Aaxl2Export",
    "export_aaxl2",
    "dumps_aaxl2",
    "write_aaxl2",
    "instance_file_name",
    "java_double",
    "INSTANCES_FOLDER",
]

"""AADL name resolution over the declarative model.

The declarative model (``aadl.ecore``) keeps cross references as the names written in the text:
``Feature.classifier = "ros_data::Image.rgb"``, ``Classifier.extended = "ros::node"``,
``PropertyAssociation.property = "Period"``. A :class:`Resolver` indexes the units of an
``AadlModel`` once (case-insensitively, as AADL names are) and turns those names into model
elements following AADL's visibility rules:

* classifiers: the context's own package, fully qualified names (``P::T``, ``P::T.impl``),
  package aliases and classifier aliases from ``renames`` declarations, and ``renames P::all``;
* properties, property types and constants: ``Set::Name`` qualified, or unqualified through the
  predeclared property sets (``Period`` is ``Timing_Properties::Period``), then through the
  property sets the context names in its ``with`` clauses;
* enumeration and unit literals of a property type.

It also computes the *effective members* of classifiers (features of a type with its ``extends``
chain, ``refined to`` replacing the inherited member in place; subcomponents, connections, flows,
modes and end-to-end flows of an implementation chain) and caches every answer, so that
instantiating large models does not resolve the same name twice. :meth:`Resolver.check` reports
every reference that does not resolve as a located :class:`~rosaadl.errors.Diagnostic`.

The modules, one idea each:

* :mod:`.names`: names and paths as written (:func:`split_name`, :func:`split_path`, the AADL
  words of feature categories);
* :mod:`.index`: the units of a model by name, the unit of an element, qualified names and
  locations;
* :mod:`.visibility`: which classifier, property, type or constant a name denotes from a unit;
* :mod:`.property_types`: the types of property values, their units and literals;
* :mod:`.members`: extends chains, effective members and refinements;
* :mod:`.check`: the reference check;
* :mod:`.resolver`: the :class:`Resolver` that brings them together and caches the answers.
"""

from __future__ import annotations

from .names import FEATURE_WORDS, PathSegment, feature_category_word, split_name, split_path
from .resolver import Resolver
from .visibility import PREDECLARED_PROPERTY_SETS

__all__ = [
    "FEATURE_WORDS",
    "PREDECLARED_PROPERTY_SETS",
    "Resolver",
    "PathSegment",
    "split_path",
    "split_name",
    "feature_category_word",
]

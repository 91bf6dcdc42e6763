"""AADL property value lookup on declarative elements and instance objects.

The rules are AADL's (SAE AS5506C §11.3), as OSATE applies them.  For a component the value of a
property comes from, in this order:

1. a *contained* property association (``applies to`` path) declared in an enclosing
   implementation or in the property block of an enclosing subcomponent — the outermost one wins;
2. the subcomponent's own associations (through ``refined to``);
3. the classifier: the implementation, its ``extends`` chain, then the type and its chain;
4. for an ``inherit`` property, the value of the containing component;
5. the property's default value.

Features look at their own associations, then at their classifier (a data type gives its
``Data_Size`` to the ports it types); connections at their declaration; modes and flows at their
declaration.  ``+=>`` appends the list items to the value found further down that order; values
in modes keep their ``in modes``; ``in binding`` associations apply when the component is bound
to a processor of the named classifier.

:class:`PropertyLookup` answers questions on declarative elements (classifiers, subcomponents,
features, connections, modes, flows) and on instance objects.  An instance object made by
:mod:`rosaadl.transforms.instantiate` already carries its resolved values; for other instance
trees the values are computed from the declarative model.  Values come back as
``PropertyExpression`` elements, or as Python values through :meth:`PropertyLookup.python_value`.

The modules, one idea each:

* :mod:`.keys`: the canonical key of a property, its definition and display name;
* :mod:`.associations`: the associations of the model by holder and key (the shared state);
* :mod:`.nodes`: contained associations carried down a component hierarchy;
* :mod:`.order`: the lookup order, ``+=>`` parts and default values;
* :mod:`.binding`: values ``in binding``;
* :mod:`.values`: building the value elements (units, literals, constants, references, modes);
* :mod:`.declarative` and :mod:`.instances`: where a lookup starts on each kind of element;
* :mod:`.applies_to`: which objects a property applies to;
* :mod:`.factory`: the object factory of bulk producers;
* :mod:`.property_lookup`: the :class:`PropertyLookup` that holds one lookup's state.
"""

from __future__ import annotations

from .applies_to import accepts
from .factory import Factory
from .instances import resolve_instance_path
from .nodes import ComponentNode
from .order import Found
from .property_lookup import PropertyLookup
from .values import NoValue

__all__ = [
    "PropertyLookup",
    "Found",
    "ComponentNode",
    "Factory",
    "NoValue",
    "accepts",
    "resolve_instance_path",
]

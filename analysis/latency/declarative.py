"""What the flow latency analysis asks of the declarative model an instance was made from.

**Assigned values.** Whether a property is *assigned* to an instance object, as OSATE's flow
latency analysis asks.

OSATE takes an assigned ``Deadline`` as the worst case under its ``DL`` preference, and an
assigned ``Queue_Size`` as a queue (``FlowLatencyAnalysisSwitch.isAssignedDeadline`` and
``hasAssignedPropertyValue``: a property association reaches the object; the default value does
not count). rosaadl's instances carry every value, default values included (a ``Deadline``
equal to the ``Period``, a ``Queue_Size`` of 1), so the question goes back to the declarative
model the instance was made from: the AADL lookup order (contained associations, the
subcomponent, the classifiers, ``inherit``) without the default value. An instance without its
declarative model (read from an ``.aaxl2`` file, or built by hand) carries assigned values only:
there a value is assigned when it is present.

**Modes of end-to-end flows.** The modes an end-to-end flow is declared ``in modes`` of (the
instance does not carry them).

**Classifiers.** ``Required_Virtual_Bus_Class`` names protocols by classifier, not by instance:
their ``Period``, ``Latency``, ``Transmission_Time``, ``Data_Size`` and own required protocols
are read on the classifiers (the AADL lookup order: the implementation, its ``extends``, the type).
"""

from __future__ import annotations

import logging
from typing import Any

from rosaadl import model as _model
from rosaadl.errors import RosaadlError
from rosaadl.lookup.instances import by_name, find_instance, instance_node

__all__ = ["DeclarativeValues"]

log = logging.getLogger(__name__)


class DeclarativeValues:
    """Answers, for one instance, "is property ``name`` assigned to this component or feature
    instance?" and "what is property ``name`` of this classifier?" from the declarative model,
    when the instance has one at hand."""

    def __init__(self, root: Any) -> None:
        self.root = root
        self._lookup: Any = None
        self._tried = False
        self._nodes: dict[int, Any] = {}
        self._answers: dict[tuple[int, str], bool | None] = {}

    def lookup(self) -> Any | None:
        """The property lookup of the declarative model holding the instance (None without one)."""
        if not self._tried:
            self._tried = True
            holder = _model.root_of(self.root)
            if getattr(holder, "units", None):
                from rosaadl.lookup import PropertyLookup
                from rosaadl.resolution import Resolver

                try:
                    self._lookup = PropertyLookup(holder, Resolver(holder))
                except (RosaadlError, LookupError, AttributeError, TypeError) as exc:
                    log.debug("no declarative model for assigned values: %s", exc)
        return self._lookup

    def classifier(self, name: str) -> Any | None:
        """The classifier a qualified name (``Pkg::vb``) names, or None."""
        holder = _model.root_of(self.root)
        if self.lookup() is None or not isinstance(name, str):
            return None
        try:
            return _model.find_classifier(holder, name)
        except (RosaadlError, LookupError, AttributeError, TypeError):
            return None

    def classifier_value(self, classifier: Any, name: str) -> Any:
        """The Python value of property ``name`` on ``classifier`` (None when it has none)."""
        lookup = self.lookup()
        if lookup is None:
            return None
        try:
            return lookup.python_value(classifier, name)
        except (RosaadlError, LookupError, AttributeError, TypeError) as exc:
            log.debug("%s of classifier %s not resolved: %s", name, getattr(classifier, "name", ""), exc)
            return None

    def flow_modes(self, flow: Any) -> list[str]:
        """The modes (lower case) an end-to-end flow instance's declaration is ``in modes`` of,
        [] when it is in every mode or the declarative model cannot tell."""
        lookup = self.lookup()
        container = flow.eContainer()
        if lookup is None or container is None or not _model.is_a(container, "ComponentInstance"):
            return []
        try:
            node = instance_node(lookup.associations, container, self._nodes)
            decl = by_name(lookup.resolver.end_to_end_flows(node.impl), flow.flow or flow.name)
        except (RosaadlError, LookupError, AttributeError, TypeError) as exc:
            log.debug("flow %s not resolved: %s", _model.instance_path(flow), exc)
            return []
        return [m.lower() for m in (getattr(decl, "inModes", None) or [])]

    def declared(self, obj: Any, name: str) -> bool | None:
        """Whether an association of ``name`` reaches ``obj`` in the declarative model (None when
        the declarative model cannot tell)."""
        marker = (id(obj), name.lower())
        if marker in self._answers:
            return self._answers[marker]
        answer = None
        lookup = self.lookup()
        if lookup is not None:
            try:
                answer = self._declared(lookup, obj, lookup.property_key(name))
            except (RosaadlError, LookupError, AttributeError, TypeError) as exc:
                log.debug("assigned %s of %s not resolved: %s", name, _model.instance_path(obj), exc)
        self._answers[marker] = answer
        return answer

    def _declared(self, lookup: Any, obj: Any, key: str) -> bool | None:
        """Whether the lookup of ``key`` on ``obj`` ends at an association (the default value,
        which :func:`~rosaadl.lookup.instances.find_instance` adds last, has none)."""
        if not _model.is_a(obj, "ComponentInstance", "FeatureInstance"):
            return None
        found, _evaluate, _reference = find_instance(lookup.associations, obj, key, None, self._nodes)
        return found is not None and found.association is not None

"""Instantiate a root system implementation of a declarative AADL model, as OSATE does.

:func:`instantiate` builds a ``SystemInstance`` (conventions: ``docs/instance-model.md``):

* the component hierarchy, arrays expanded (one instance per element, 1-based ``index``);
* feature instances of every component (feature groups expanded with ``inverse of``, feature
  arrays expanded where AADL allows them);
* mode instances, mode transition instances and the system operation modes;
* semantic connection instances from ultimate source to ultimate destination, found with OSATE's
  algorithm (each declared connection is a hop; a connection instance starts at a thread, device,
  processor or shared data/bus, or at a feature nothing inside continues, goes up, across once and
  down), with one connection reference per hop, bidirectional access connections merged, modal
  connections limited to the system operation modes they exist in, and connections between
  component arrays replicated according to ``Connection_Pattern``;
* end-to-end flow instances;
* the resolved property values of every instance object (see :mod:`rosaadl.lookup`), with
  ``reference (...)`` values turned into references to instance objects.

Everything that depends only on a classifier (effective members, resolved connection ends,
property associations) is computed once per classifier, so large models instantiate quickly.

The package holds one module per idea, all working on one :class:`Instantiator` (the state the
stages share) and the instance mirrors beside the instance objects:

==========================  ==========================================================
:mod:`.instantiator`        the shared state, the root, the stages in their order
:mod:`.mirrors`             component / feature / connection records, category words, paths
:mod:`.order`               OSATE's order of subcomponents and features
:mod:`.hierarchy`           component instances (prototypes, containment cycles)
:mod:`.features`            feature instances, feature groups, feature arrays
:mod:`.modes`               modes, mode transitions, system operation modes, modal connections
:mod:`.declared`            declared connections resolved per implementation
:mod:`.connections`         the semantic connection walk (up, across, down)
:mod:`.feature_group_matching`  connection ends in feature groups, member by member
:mod:`.connection_instances`    a connection under construction and the instance it becomes
:mod:`.arrays`              array sizes, Connection_Pattern replication between elements
:mod:`.flows`               flow specification and end-to-end flow instances
:mod:`.property_values`     property values on every instance object
==========================  ==========================================================
"""

from __future__ import annotations

from .hierarchy import MAX_COMPONENT_INSTANCES
from .instantiator import COMPATIBILITY_MODES, Instantiator, instantiate
from .modes import MAX_SYSTEM_OPERATION_MODES

__all__ = [
    "instantiate",
    "Instantiator",
    "COMPATIBILITY_MODES",
    "MAX_COMPONENT_INSTANCES",
    "MAX_SYSTEM_OPERATION_MODES",
]

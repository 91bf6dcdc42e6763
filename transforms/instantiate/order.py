"""The order in which OSATE lists the members of a classifier (getAllSubcomponents, getAllFeatures).

Instance objects are made in that order, so that instance files, connection names and every
"first one found" rule agree with OSATE's. The two tables are aadl2.ecore's typed member lists per
class of classifier; :func:`in_osate_order` sorts members by them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from pyecore.ecore import EObject

from rosaadl.resolution import Resolver

from .mirrors import literal

__all__ = ["FEATURE_ORDER", "SUBCOMPONENT_ORDER", "in_osate_order"]

# The order in which OSATE's Xtext model lists an implementation's subcomponents: its
# ownedSubcomponent union concatenates one list per category, in aadl2.ecore's order for the
# implementation's class (ComponentImplementation's abstract list first).
SUBCOMPONENT_ORDER: dict[str, list[str]] = {
    category: ["abstract", *members.split(",")]
    for category, members in {
        "abstract": "bus,data,device,memory,process,processor,system,subprogram,subprogram group,"
        "thread,thread group,virtual bus,virtual processor",
        "bus": "virtual bus",
        "data": "data,subprogram",
        "device": "bus,data,virtual bus",
        "memory": "bus,memory,virtual bus",
        "process": "data,subprogram,subprogram group,thread,thread group",
        "processor": "bus,memory,virtual bus,virtual processor",
        "subprogram": "data,subprogram",
        "subprogram group": "subprogram,subprogram group,data",
        "system": "bus,data,device,memory,process,processor,subprogram,subprogram group,system,"
        "virtual bus,virtual processor",
        "thread": "subprogram group,subprogram,data",
        "thread group": "data,thread,thread group,subprogram,subprogram group",
        "virtual bus": "virtual bus",
        "virtual processor": "virtual bus,virtual processor",
    }.items()
}
# The same for a component type's features: ComponentType's feature group and abstract feature
# lists first, then the lists of the type's class, in aadl2.ecore's order.
FEATURE_ORDER: dict[str, list[str]] = {
    category: ["featureGroup", "abstractFeature", *members.split()]
    for category, members in {
        "abstract": "busAccess dataAccess subprogramAccess dataPort eventPort eventDataPort "
        "subprogramGroupAccess",
        "bus": "busAccess dataPort eventDataPort eventPort",
        "data": "subprogramAccess dataAccess subprogramGroupAccess",
        "device": "dataPort eventDataPort eventPort busAccess subprogramAccess subprogramGroupAccess",
        "memory": "busAccess dataPort eventDataPort eventPort",
        "subprogram": "eventDataPort eventPort parameter dataAccess subprogramAccess subprogramGroupAccess",
        "subprogram group": "subprogramAccess subprogramGroupAccess",
        "system": "busAccess dataAccess dataPort subprogramGroupAccess subprogramAccess eventPort "
        "eventDataPort",
        "processor": "dataPort eventDataPort eventPort busAccess subprogramAccess subprogramGroupAccess",
        "process": "dataPort eventDataPort eventPort dataAccess subprogramAccess subprogramGroupAccess",
        "thread": "dataPort eventDataPort eventPort dataAccess subprogramAccess subprogramGroupAccess",
        "thread group": "dataPort eventDataPort eventPort dataAccess subprogramAccess subprogramGroupAccess",
        "virtual bus": "dataPort eventDataPort eventPort busAccess",
        "virtual processor": "dataPort eventDataPort eventPort subprogramAccess subprogramGroupAccess "
        "busAccess",
    }.items()
}


def in_osate_order(
    resolver: Resolver,
    classifier: EObject,
    items: list,
    member: Callable[[Any], EObject],
    category: Callable[[Any], str],
    table: dict[str, list[str]],
) -> list:
    """Members of ``classifier`` (``member(item)`` is the declaration) in the order OSATE lists
    them (getAllSubcomponents, getAllFeatures): the farthest ancestor's first, each
    classifier's by category (``category(item)``, ranked by ``table`` for the classifier's
    class), declaration order within one; a refinement counts among its own classifier's
    (OSATE removes the refined member and appends the refinement). OSATE 2.0's files show
    the same order."""
    if len(items) < 2:
        return items
    chain = list(reversed(resolver.extends_chain(classifier)))
    level = {id(c): n for n, c in enumerate(chain)}

    def key(pair: tuple[int, Any]) -> tuple[int, int, int]:
        position, item = pair
        owner = member(item).eContainer()
        order = table.get(literal(getattr(owner, "category", None)), ())
        word = category(item)
        return (
            level.get(id(owner), len(chain)),
            order.index(word) if word in order else len(order),
            position,
        )

    return [item for _, item in sorted(enumerate(items), key=key)]

"""Counts of a ``rosmod.Project`` (packages, messages, …, component instances), for checks and reports.

The same for every reader (textual dialects and WebGME exports): facts the metamodel has no
class for are counted from the properties the readers keep them in (``Action:``,
``Action Client:``, ``Action Server:``, ``Container:``).
"""

from __future__ import annotations

from pyecore.ecore import EObject

__all__ = ["SUMMARY_KEYS", "summarize"]

#: The keys of :func:`summarize`, in the order of the tables of the corpus's INDEX.md.
SUMMARY_KEYS = (
    "packages",
    "messages",
    "services",
    "actions",
    "components",
    "timers",
    "publishers",
    "subscribers",
    "clients",
    "servers",
    "action_clients",
    "action_servers",
    "systems",
    "hosts",
    "deployments",
    "containers",
    "nodes",
    "component_instances",
    "max_nodes",
    "max_component_instances",
)


def summarize(project: EObject) -> dict[str, int]:
    """Counts of a ROSMOD project (packages, messages, …, component instances), for checks and reports."""
    counts = dict.fromkeys(SUMMARY_KEYS, 0)
    software = project.software
    for package in software.packages if software is not None else []:
        counts["packages"] += 1
        counts["messages"] += len(package.messages)
        counts["services"] += len(package.services)
        counts["actions"] += _count(package.properties, "Action:")
        for comp in package.components:
            counts["components"] += 1
            counts["timers"] += len(comp.timers)
            for port in comp.ports:
                counts[port.eClass.name.lower() + "s"] += 1  # the exact class name: publishers, …
            counts["action_clients"] += _count(comp.properties, "Action Client:")
            counts["action_servers"] += _count(comp.properties, "Action Server:")
    for system in project.systems:
        counts["systems"] += 1
        counts["hosts"] += len(system.hosts)
    for deployment in project.deployments:
        counts["deployments"] += 1
        counts["containers"] += _count(deployment.properties, "Container:")
        nodes = len(deployment.nodes)
        instances = sum(len(n.componentInstances) for n in deployment.nodes)
        counts["nodes"] += nodes
        counts["component_instances"] += instances
        counts["max_nodes"] = max(counts["max_nodes"], nodes)
        counts["max_component_instances"] = max(counts["max_component_instances"], instances)
    return counts


def _count(properties, prefix: str) -> int:
    """How many of ``properties`` have a key starting with ``prefix``."""
    return sum(1 for p in properties if (p.key or "").startswith(prefix))

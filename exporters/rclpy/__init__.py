"""ROS 2 ``rclpy`` packages from AADL thread models, keeping hand-written code across regenerations.

RAMSES-style refinement of an AADL instance into a ROS 2 workspace (``docs/code-generation.md``):
one ``ament_python`` package per software package with one module and ``Node`` subclass per
process, threads as callback groups of a ``MultiThreadedExecutor``, ports as publishers and
subscriptions, subprogram accesses as services and clients; an ``<app>_interfaces`` package for
the messages that are not standard ROS 2 ones; an ``<app>_bringup`` package with a launch file
per deployment and per host, applying processor bindings and real-time priorities.

>>> result = generate_workspace(instance, "ws/src")          # doctest: +SKIP
>>> result.written, result.moved, result.orphaned             # doctest: +SKIP
"""

from rosaadl.exporters.rclpy.messages import InterfaceDefinition, InterfaceType, MessageCatalog
from rosaadl.exporters.rclpy.nodes import NodeClass, PortPlan, ServicePlan, ThreadPlan
from rosaadl.exporters.rclpy.workspace import (
    LICENSES,
    MANIFEST_NAME,
    BlockMove,
    FileChange,
    GenerationOptions,
    GenerationResult,
    PlannedFile,
    WorkspacePlan,
    generate_workspace,
    plan_workspace,
    rename_map,
)

__all__ = [
    "LICENSES",
    "MANIFEST_NAME",
    "BlockMove",
    "FileChange",
    "GenerationOptions",
    "GenerationResult",
    "InterfaceDefinition",
    "InterfaceType",
    "MessageCatalog",
    "NodeClass",
    "PlannedFile",
    "PortPlan",
    "ServicePlan",
    "ThreadPlan",
    "WorkspacePlan",
    "generate_workspace",
    "plan_workspace",
    "rename_map",
]

"""Bind the deployments of a ROSMOD project to a robot of the component library.

A ROSMOD project says which components run in which node on which host, and at what rates
(timer periods); it knows nothing of the boards' cores or of the nodes' execution times. The
component library knows both: robots made of boards, chips and cores (``library/hardware``), and
nodes with one platform-dependent implementation (PDM) per core type, carrying the execution
times measured there (``library/nodes``). :func:`bind_deployment` joins them, following an
explicit bindings file (:func:`parse_bindings`; the example's ``examples/tracking/bindings.json``),
into an AADL deployment package shaped like the library's ``sys_tracking``:

* the library robot (``"robot": "pioneer_3dx::Pioneer_3DX.impl"``) as the subcomponent
  ``robot``;
* one process per ROSMOD component instance, of the library node named for it
  (``"library": "nd_usb_cam::usb_cam_nd"``), in the PDM whose ``Reference_Processor`` is the
  type of the core it is bound to (``"core": "OdroidXU4.Exynos_SOC.little_procs_cluster.
  little_proc1"`` is an ``Exynos_5422::ARM_A7``, so ``usb_cam_nd.xu4_a7``), bound to that core
  with ``Actual_Processor_Binding``;
* one port connection per topic, as ROSMOD matches them (a publisher and a subscriber of the
  same message type, and of the same ``<port>.Topic`` setting when there is one), between the
  library ports that carry the topic's message type, bound with ``Actual_Connection_Binding``
  to the ROS virtual bus (``ROSbus: virtual bus ros::ROSbus.impl``) or to a bus of the robot;
* the connections between nodes and the robot's own ports the bindings file lists (the camera
  stream, the velocity commands), bound to the robot bus it names;
* the rates of the ROSMOD model on the library threads: a thread that handles a subscriber's
  messages runs at the rate of the topic (its publisher's rate), a thread that publishes runs at
  the rate of the component's timer (the fastest, when it has several; a component without a
  timer publishes from its fastest subscriber callback); the other threads of the node and the
  node itself run at the node's fastest rate. ROSMOD's deadlines and priorities go with the
  rates (the subscriber's own, or the timer's), a node's priority on its process. So the CPU
  load of a thread is the PDM's execution time over the ROSMOD period.

The input is the ROSMOD project itself, not the AADL that :mod:`~rosaadl.transforms.rosmod_to_aadl`
makes of it: every fact the binding needs (components, their timers, ports and message types,
nodes, deployments, which publisher feeds which subscriber) is a first-class element of the
ROSMOD model, whereas the converted AADL holds generic threads and processors that the library
nodes and boards replace, and would have to be read back into these facts.

Every problem of the bindings file (unknown robot, library node, core path, port or bus, a core
of a type the node has no PDM for, a ROSMOD node without binding) is a :class:`BindingError`
located at the file, line and entry (``deployments.pioneer_3dx.nodes.usb_cam_node.core``).

The modules, one idea each: :mod:`.bindings_file` (the file's format and its parser),
:mod:`.library` (robots' cores, ports and buses; library nodes and their PDMs),
:mod:`.matching` (each component instance matched with its entry, node, PDM, core and ports),
:mod:`.rates` (topics, rates and thread timings) and :mod:`.deployment` (the bound package).
They read and write no files: reading the bindings file and the library, writing the bound
package and searching a better binding (:func:`~rosaadl.workflow.binding.propose_binding`) are
the workflow's (:mod:`rosaadl.workflow.binding`).
"""

from rosaadl.transforms.bind.bindings_file import (
    BINDINGS_VERSION,
    MAX_BINDINGS_BYTES,
    ROS_BUS,
    BindingError,
    BindingsFile,
    DeploymentSpec,
    NodeSpec,
    RobotLink,
    parse_bindings,
)
from rosaadl.transforms.bind.deployment import ROBOT, BoundDeployment, BoundNode, BoundTopic, bind_deployment
from rosaadl.transforms.bind.library import Core, robot_cores
from rosaadl.transforms.bind.rates import ThreadTiming

__all__ = [
    "BINDINGS_VERSION",
    "MAX_BINDINGS_BYTES",
    "ROBOT",
    "ROS_BUS",
    "BindingError",
    "BindingsFile",
    "DeploymentSpec",
    "NodeSpec",
    "RobotLink",
    "Core",
    "ThreadTiming",
    "BoundNode",
    "BoundTopic",
    "BoundDeployment",
    "parse_bindings",
    "robot_cores",
    "bind_deployment",
]

"""rosaadl: model-driven engineering of ROS robots with AADL.

Read ROSMOD projects, AADL text, OSATE ``.aaxl2`` and Cheddar XML into pyecore models; convert
ROSMOD ⇄ AADL with a traced rule engine; analyse deployments; export to OSATE and Cheddar;
generate ROS 2 rclpy packages.
"""

from rosaadl.errors import Diagnostic, Location, RosaadlError

__all__ = ["__version__", "Diagnostic", "Location", "RosaadlError"]

__version__ = "0.1.0"

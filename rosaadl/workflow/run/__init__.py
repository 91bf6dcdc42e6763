"""Running a generated ROS 2 application: ``rosaadl run`` (see ``docs/running.md``).

One module per idea: :mod:`~rosaadl.workflow.run.plan` (the nodes and topics a run starts and
watches, with the modelled rates), :mod:`~rosaadl.workflow.run.environment` (the ROS 2 of this
Python, the environment and the colcon build), :mod:`~rosaadl.workflow.run.cores` (the launch
prefix mapped onto this machine), :mod:`~rosaadl.workflow.run.processes` (starting and stopping
the nodes), :mod:`~rosaadl.workflow.run.monitor` (the rclpy topic monitor, a process of its own)
and :mod:`~rosaadl.workflow.run.session` (one run from start to report).
"""

from rosaadl.workflow.run.environment import ros_missing
from rosaadl.workflow.run.plan import PLAN_FILE, RunError, RunPlan, load_plan, run_plan
from rosaadl.workflow.run.session import RunOptions, RunResult, prepare_run, run_application

__all__ = [
    "PLAN_FILE",
    "RunError",
    "RunOptions",
    "RunPlan",
    "RunResult",
    "load_plan",
    "prepare_run",
    "ros_missing",
    "run_application",
    "run_plan",
]

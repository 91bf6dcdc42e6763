"""The launch prefix of a node on this machine: the model's cores and scheduling mapped onto it.

The launch file writes ``taskset -c <cpus>`` for a node's processor binding and ``chrt -f|-r
<priority>`` for its real-time scheduling (:func:`rosaadl.exporters.rclpy.deployment.launch_prefix`).
On the machine the run happens on:

* a CPU number of the model that this process may run on is kept; one that does not exist here
  (or is not allowed to it) is mapped onto the allowed CPUs in turn (``cpu mod count``, in the
  order of the allowed CPUs), with a warning naming both;
* ``chrt`` is kept when this process may set that policy (probed once, with the ``chrt`` of the
  machine running ``true``); otherwise it is dropped, with a warning: the node runs under the
  default policy (``SCHED_OTHER``);
* ``chrt`` is dropped too, with a warning, for a node on a CPU that several cores of the model
  were mapped onto (:func:`shared_cpus`): the model's priorities were chosen (and analysed) per
  core, and between nodes of different cores sharing a CPU a higher ``SCHED_FIFO`` priority
  starves the lower one (seen here: a node at priority 50 folded onto the CPU of one at 55 did not
  get through its imports in 60 s).
"""

from __future__ import annotations

import os
import shutil
import subprocess
from dataclasses import dataclass, field

from rosaadl.workflow.run.plan import NodeLaunch

__all__ = ["Machine", "machine", "map_cpus", "shared_cpus", "node_prefix", "quietest_cpus"]

_CHRT_FLAGS = {"SCHED_FIFO": "-f", "SCHED_RR": "-r"}


@dataclass
class Machine:
    """What this machine allows: its CPUs and whether real-time scheduling may be set."""

    cpus: list[int]
    realtime: dict[str, bool] = field(default_factory=dict)  # policy -> permitted
    taskset: str | None = None
    chrt: str | None = None


def machine(*, realtime: bool = True) -> Machine:
    """The CPUs this process may run on and, per real-time policy, whether ``chrt`` may set it
    (``realtime=False``: never)."""
    try:
        cpus = sorted(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cpus = list(range(os.cpu_count() or 1))
    found = Machine(cpus=cpus, taskset=shutil.which("taskset"), chrt=shutil.which("chrt"))
    for policy, flag in _CHRT_FLAGS.items():
        permitted = False
        if realtime and found.chrt is not None:
            try:
                probe = subprocess.run(
                    [found.chrt, flag, "1", "true"], capture_output=True, timeout=10, check=False
                )
                permitted = probe.returncode == 0
            except (OSError, subprocess.SubprocessError):
                permitted = False
        found.realtime[policy] = permitted
    return found


def map_cpus(cpus: list[int], available: list[int]) -> tuple[list[int], list[tuple[int, int]]]:
    """(the CPUs to use, the (model CPU, CPU used) pairs that had to be moved)."""
    if not available:
        return [], []
    used: list[int] = []
    moved: list[tuple[int, int]] = []
    for cpu in cpus:
        target = cpu if cpu in available else available[cpu % len(available)]
        if target != cpu:
            moved.append((cpu, target))
        if target not in used:
            used.append(target)
    return sorted(used), moved


def shared_cpus(nodes: list[NodeLaunch], here: Machine) -> set[int]:
    """The CPUs of this machine that more than one core of the model is mapped onto."""
    cores_on: dict[int, set[int]] = {}
    for node in nodes:
        for cpu in node.cpus or ():
            target, _ = map_cpus([cpu], here.cpus)
            for used in target:
                cores_on.setdefault(used, set()).add(cpu)
    return {cpu for cpu, cores in cores_on.items() if len(cores) > 1}


def node_prefix(
    node: NodeLaunch, here: Machine, shared: set[int] = frozenset()
) -> tuple[list[str], list[str]]:
    """(the command prefix of ``node`` on this machine, the warnings it gave); ``shared``: the
    CPUs several model cores are mapped onto (:func:`shared_cpus`)."""
    prefix: list[str] = []
    cpus: list[int] = []
    warnings: list[str] = []
    if node.cpus:
        cpus, moved = map_cpus(node.cpus, here.cpus)
        for model_cpu, used in moved:
            warnings.append(
                f"node {node.full_name}: core {model_cpu} of the model does not exist here "
                f"(CPUs {_cpu_list(here.cpus)}); it runs on CPU {used}"
            )
        if here.taskset is None:
            warnings.append(f"node {node.full_name}: taskset is not installed; its CPU affinity is not set")
        elif cpus:
            prefix += [here.taskset, "-c", _cpu_list(cpus)]
    flag = _CHRT_FLAGS.get(node.policy.upper())
    crowded = sorted(set(cpus) & set(shared))
    if flag and node.priority is not None and crowded:
        warnings.append(
            f"node {node.full_name}: CPU {_cpu_list(crowded)} runs nodes of several cores of the model; "
            f"its {node.policy.upper()} priority {node.priority} is not applied there (it would starve "
            "the nodes of lower priority): it runs under the default scheduling"
        )
    elif flag and node.priority is not None:
        if here.chrt is not None and here.realtime.get(node.policy.upper()):
            prefix += [here.chrt, flag, str(node.priority)]
        else:
            warnings.append(
                f"node {node.full_name}: {node.policy.upper()} priority {node.priority} cannot be set "
                "here (chrt is missing or not permitted); it runs under the default scheduling"
            )
    return prefix, warnings


def _cpu_list(cpus: list[int]) -> str:
    return ",".join(str(c) for c in cpus)


def quietest_cpus(nodes: list[NodeLaunch], here: Machine, loads: dict[int, float]) -> list[int]:
    """The CPUs for the run's own processes (the topic monitor), away from the nodes' work: the
    CPUs of this machine no pinned node uses, else the one the model loads least (``loads``:
    per CPU, in %); none (no pinning) when no node is pinned."""
    pinned = [set(map_cpus(node.cpus, here.cpus)[0]) for node in nodes if node.cpus]
    if not pinned or not here.cpus:
        return []
    used = set().union(*pinned)
    free = [cpu for cpu in here.cpus if cpu not in used]
    return free or [min(here.cpus, key=lambda cpu: (loads.get(cpu, 0.0), cpu))]

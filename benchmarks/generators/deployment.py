"""Robots to deploy: boards of multi-core processors and ROS nodes of periodic callbacks.

:func:`robot_to_deploy` builds, with the model API, an ``AadlModel`` holding one
``SystemInstance`` as the instantiator makes it: ``boards`` boards (systems), each with a
processor of cores (every other board has cores half as fast: the load a callback puts on a core
scales with ``Reference_Processor`` MIPS over the core's ``SEI::MIPSCapacity``, as OSATE's CPU
load analysis scales it), a RAM, and one network bus for all (100 Mbit/s); ``nodes`` processes of ``threads``
periodic threads in all (ROS periods of 10 to 100 ms), each bound round robin to a core; the
first node a device driver allowed only on the first board (``Allowed_Processor_Binding``); a
topic from each node's first thread to the next node's. ``bench_deploy`` and the tests use it
(the 30-node / 300-thread / 3-board / 16-core and 100-node / 1 000-thread / 6-board / 48-core
scale models of the deployment issue).
"""

from __future__ import annotations

import random
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model

__all__ = ["SCALE_MODELS", "robot_to_deploy"]

#: name → (nodes, threads, boards, cores)
SCALE_MODELS = {
    "30 nodes / 300 threads / 3 boards / 16 cores": (30, 300, 3, 16),
    "100 nodes / 1000 threads / 6 boards / 48 cores": (100, 1000, 6, 48),
}

_PERIODS_US = (10_000, 20_000, 25_000, 50_000, 100_000)


def _pa(prop: str, value: EObject) -> EObject:
    return model.new(
        "PropertyAssociation", property=prop, ownedValues=[model.new("ModalPropertyValue", value=value)]
    )


def _num(value: float | int, unit: str) -> EObject:
    return model.new("RealValue" if isinstance(value, float) else "IntegerValue", value=value, unit=unit)


def _ref(*targets: EObject) -> EObject:
    return model.new(
        "ListValue",
        ownedItems=[model.new("InstanceReferenceValue", referencedInstanceObject=t) for t in targets],
    )


def _component(name: str, category: str, *props: EObject) -> EObject:
    ci = model.new("ComponentInstance", name=name, category=category)
    ci.ownedPropertyAssociations.extend(props)
    return ci


def robot_to_deploy(
    nodes: int,
    threads: int,
    boards: int,
    cores: int,
    *,
    load: float = 0.6,
    seed: int = 1,
    open_chain: bool = False,
) -> Any:
    """The ``SystemInstance`` (inside its ``AadlModel``) of a robot of ``boards`` boards and
    ``cores`` cores in all, and ``nodes`` ROS nodes of ``threads`` threads in all, whose
    callbacks need about ``load`` of the cores' capacity in all. The first callbacks of the nodes
    talk in a ring (no cause-effect chain: every callback is fed), or with ``open_chain`` in a
    line from node 0 to the last node (one chain through every node)."""
    rng = random.Random(seed)
    workspace = model.new("AadlModel", name="robot")
    reference = model.new(
        "ComponentType",
        name="Reference",
        category="processor",
        ownedPropertyAssociations=[_pa("SEI::MIPSCapacity", _num(2000.0, "MIPS"))],
    )
    workspace.units.append(model.new("AadlPackage", name="Hw", classifiers=[reference]))
    root = model.new("SystemInstance", name="robot_i_Instance", category="system")
    core_objs, board_objs = [], []
    capacity = 0.0
    for b in range(boards):
        board = _component(f"board{b}", "system")
        mips = 2000.0 if b % 2 == 0 else 1000.0
        cpu = _component("cpu", "processor")
        count = cores // boards + (1 if b < cores % boards else 0)
        for k in range(count):
            core = _component(
                f"core{k}",
                "processor",
                _pa("SEI::MIPSCapacity", _num(mips, "MIPS")),
                _pa(
                    "Deployment_Properties::Scheduling_Protocol",
                    model.new("NamedValue", name="RATE_MONOTONIC_PROTOCOL"),
                ),
            )
            cpu.componentInstances.append(core)
            core_objs.append(core)
            capacity += mips / 2000.0
        board.componentInstances.append(cpu)
        board.componentInstances.append(
            _component("ram", "memory", _pa("Memory_Properties::Memory_Size", _num(4096, "MByte")))
        )
        root.componentInstances.append(board)
        board_objs.append(board)
    root.componentInstances.append(
        _component("net", "bus", _pa("SEI::BandWidthCapacity", _num(12500.0, "KBytesps")))
    )
    per_thread = load * capacity / threads  # mean utilisation of a thread on the reference core
    firsts = []
    for n in range(nodes):
        count = threads // nodes + (1 if n < threads % nodes else 0)
        process = _component(
            f"node{n}", "process", _pa("SEI::RAMBudget", _num(rng.randint(20, 200), "MByte"))
        )
        for t in range(count):
            period = rng.choice(_PERIODS_US)
            cet = max(1, round(period * per_thread * rng.uniform(0.2, 1.8)))
            thread = _component(
                f"cb{t}",
                "thread",
                _pa("Timing_Properties::Period", _num(period, "us")),
                _pa(
                    "Timing_Properties::Compute_Execution_Time",
                    model.new("RangeValue", minimum=_num(cet, "us"), maximum=_num(cet, "us")),
                ),
                _pa("Thread_Properties::Dispatch_Protocol", model.new("NamedValue", name="Periodic")),
                _pa(
                    "Timing_Properties::Reference_Processor",
                    model.new("ClassifierValue", classifier="Hw::Reference"),
                ),
            )
            if t == 0:
                for direction in ("out", "in"):
                    port = model.new(
                        "FeatureInstance",
                        name=direction,
                        feature=direction,
                        category="event data port",
                        direction=direction,
                    )
                    port.ownedPropertyAssociations.append(
                        _pa("Memory_Properties::Data_Size", _num(rng.randint(1, 16), "KByte"))
                    )
                    thread.featureInstances.append(port)
                firsts.append(thread)
            process.componentInstances.append(thread)
        process.ownedPropertyAssociations.append(
            _pa("Deployment_Properties::Actual_Processor_Binding", _ref(core_objs[n % len(core_objs)]))
        )
        if n == 0:
            process.ownedPropertyAssociations.append(
                _pa("Deployment_Properties::Allowed_Processor_Binding", _ref(board_objs[0]))
            )
        root.componentInstances.append(process)
    for n in range(nodes - 1 if open_chain else nodes):
        src, dst = firsts[n], firsts[(n + 1) % nodes]
        root.connectionInstances.append(
            model.new(
                "ConnectionInstance",
                name=f"node{n}.cb0.out -> node{(n + 1) % nodes}.cb0.in",
                kind="portConnection",
                source=src.featureInstances[0],
                destination=dst.featureInstances[1],
            )
        )
    workspace.instances.append(root)
    return root

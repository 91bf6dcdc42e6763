"""Instance models built directly with the model API, as the instantiator makes them.

* :func:`robot_fleet`: boards of four cores, ROS nodes of a periodic publisher and a sporadic
  subscriber bound round robin to the cores, nested virtual buses, a topic per node
  (``bench_analysis``).
* :func:`ros_ring`: N ROS nodes of N classifiers in 20 software packages, in a ring of port
  connections, one processor per 8 nodes (``bench_rclpy``).
* :func:`flat_instance`: N objects of a few instance classes, given as dynamic or static
  (pyecoregen) metamodel classes (``bench_metamodel``).
"""

from __future__ import annotations

from typing import Any

from pyecore.ecore import EObject

from rosaadl import model

__all__ = ["FLAT_CLASSES", "FLAT_PER_UNIT", "flat_instance", "robot_fleet", "ros_ring"]


class _Classes(dict):
    """Metamodel classes by name, looked up once (model.new accepts the class itself)."""

    def __missing__(self, name: str):
        self[name] = model.eclass_of(name)
        return self[name]


_C = _Classes()


def _new(class_name: str, /, **values: Any) -> EObject:
    return model.new(_C[class_name], **values)


def _pa(prop: str, value: EObject) -> EObject:
    return _new("PropertyAssociation", property=prop, ownedValues=[_new("ModalPropertyValue", value=value)])


def _num(value: float | int, unit: str) -> EObject:
    return _new("RealValue" if isinstance(value, float) else "IntegerValue", value=value, unit=unit)


def _ref(*targets: EObject) -> EObject:
    return _new(
        "ListValue", ownedItems=[_new("InstanceReferenceValue", referencedInstanceObject=t) for t in targets]
    )


# --------------------------------------------------------------------------- the analysed fleet


def _thread(name: str, period: int, cet: int, dispatch: str, ports: list[EObject]) -> EObject:
    ci = _new("ComponentInstance", name=name, category="thread")
    ci.ownedPropertyAssociations.extend(
        [
            _pa("Timing_Properties::Period", _num(period, "us")),
            _pa(
                "Timing_Properties::Compute_Execution_Time",
                _new("RangeValue", minimum=_num(cet // 2, "us"), maximum=_num(cet, "us")),
            ),
            _pa("Thread_Properties::Dispatch_Protocol", _new("NamedValue", name=dispatch)),
        ]
    )
    ci.featureInstances.extend(ports)
    return ci


def _port(name: str, direction: str, size: int) -> EObject:
    fi = _new("FeatureInstance", name=name, feature=name, category="event data port", direction=direction)
    fi.ownedPropertyAssociations.append(_pa("Memory_Properties::Data_Size", _num(size, "Bytes")))
    return fi


def _board(index: int) -> tuple[EObject, list[EObject], EObject]:
    """A board of four cores and a network bus with two nested virtual buses: the board, its
    cores and the innermost virtual bus."""
    board = _new("ComponentInstance", name=f"board{index}", category="system")
    cores = []
    for c in range(4):
        core = _new("ComponentInstance", name=f"core{c}", category="processor")
        core.ownedPropertyAssociations.extend(
            [
                _pa("SEI::MIPSCapacity", _num(2000.0, "MIPS")),
                _pa(
                    "Deployment_Properties::Scheduling_Protocol",
                    _new("NamedValue", name="RATE_MONOTONIC_PROTOCOL"),
                ),
            ]
        )
        board.componentInstances.append(core)
        cores.append(core)
    net = _new("ComponentInstance", name="net", category="bus")
    net.ownedPropertyAssociations.extend(
        [
            _pa("SEI::BandWidthCapacity", _num(1000, "Mbps")),
            _pa("SEI::BandWidthBudget", _num(60000.0, "KBytesps")),
            _pa("Memory_Properties::Data_Size", _num(38, "Bytes")),
        ]
    )
    ros = _new("ComponentInstance", name="ros", category="virtual bus")
    dds = _new("ComponentInstance", name="dds", category="virtual bus")
    ros.ownedPropertyAssociations.append(_pa("Memory_Properties::Data_Size", _num(20, "Bytes")))
    dds.ownedPropertyAssociations.append(_pa("Memory_Properties::Data_Size", _num(16, "Bytes")))
    ros.componentInstances.append(dds)
    net.componentInstances.append(ros)
    board.componentInstances.append(net)
    return board, cores, dds


def robot_fleet(boards: int, nodes: int, bind: bool = True) -> EObject:
    """A ``SystemInstance`` of ``boards`` boards of four cores and ``nodes`` ROS nodes.

    Each node is a process with a periodic publisher and a sporadic subscriber, bound round
    robin to the cores (unless ``bind`` is false); each board has a network bus with two nested
    virtual buses, and a topic goes from each node to the next, bound to the virtual buses."""
    root = _new("SystemInstance", name="fleet_i_Instance", category="system")
    cores, buses = [], []
    for b in range(boards):
        board, board_cores, bus = _board(b)
        cores.extend(board_cores)
        buses.append(bus)
        root.componentInstances.append(board)
    publishers, subscribers = [], []
    for n in range(nodes):
        period = (10_000, 20_000, 40_000, 100_000)[n % 4]
        pub = _thread("pub", period, period // 20, "Periodic", [_port("o", "out", 24 + 8 * (n % 50))])
        sub = _thread("sub", period, period // 40, "Sporadic", [_port("i", "in", 24 + 8 * (n % 50))])
        node = _new("ComponentInstance", name=f"node{n}", category="process")
        node.componentInstances.extend([pub, sub])
        if bind:
            core = cores[n % len(cores)]
            for t in (pub, sub):
                t.ownedPropertyAssociations.append(
                    _pa("Deployment_Properties::Actual_Processor_Binding", _ref(core))
                )
        root.componentInstances.append(node)
        publishers.append(pub)
        subscribers.append(sub)
    for n in range(nodes):
        src, dst = publishers[n], subscribers[(n + 1) % nodes]
        conn = _new(
            "ConnectionInstance",
            name=f"node{n}.pub.o -> node{(n + 1) % nodes}.sub.i",
            kind="portConnection",
            source=src.featureInstances[0],
            destination=dst.featureInstances[0],
        )
        conn.ownedPropertyAssociations.extend(
            [
                _pa("Deployment_Properties::Actual_Connection_Binding", _ref(buses[n % len(buses)])),
                _pa("SEI::BandWidthBudget", _num(10.0, "KBytesps")),
            ]
        )
        root.connectionInstances.append(conn)
    return root


# --------------------------------------------------------------------------- the generated ROS ring

RING_PACKAGES = 20


def _us(value: int) -> EObject:
    return _new("IntegerValue", value=value, unit="us")


def _message(index: int) -> tuple[str | None, str]:
    """The ROS message type of node ``index`` (None for a custom one) and its data classifier."""
    if index % 2:
        return "sensor_msgs/Image", "ros_data::Image.rgb"
    return None, f"pkg{index % RING_PACKAGES}::Sample{index % 3}"


def _ring_thread(
    name: str, dispatch: str, direction: str, index: int, period: int
) -> tuple[EObject, EObject]:
    """A thread of node ``index`` and its message port."""
    package = f"pkg{index % RING_PACKAGES}"
    message, classifier = _message(index)
    props = [
        _pa("Thread_Properties::Dispatch_Protocol", _new("NamedValue", name=dispatch)),
        _pa("Timing_Properties::Period", _us(period)),
        _pa("Timing_Properties::Deadline", _us(period // 2)),
        _pa(
            "Timing_Properties::Compute_Execution_Time",
            _new("RangeValue", minimum=_us(100), maximum=_us(900)),
        ),
        _pa("Thread_Properties::Priority", _new("IntegerValue", value=20)),
    ]
    thread = _new(
        "ComponentInstance",
        name=name,
        subcomponent=name,
        category="thread",
        classifier=f"{package}::{name}{index}.impl",
        ownedPropertyAssociations=props,
    )
    port_props = [_pa("Communication_Properties::Queue_Size", _new("IntegerValue", value=4))]
    if message:
        port_props.append(_pa("ROS_Properties::Message_Type", _new("StringValue", value=message)))
    port = _new(
        "FeatureInstance",
        name="msg",
        feature="msg",
        category="event data port",
        direction=direction,
        classifier=classifier,
        ownedPropertyAssociations=port_props,
    )
    thread.featureInstances.append(port)
    return thread, port


def _ring_node(index: int, cpu: EObject) -> tuple[EObject, dict[str, EObject]]:
    """Node ``index``: a process with a publisher and a receiver thread; their ports by direction."""
    package = f"pkg{index % RING_PACKAGES}"
    period = 10_000 + 1_000 * (index % 7)
    process = _new(
        "ComponentInstance",
        name=f"node{index}",
        subcomponent=f"node{index}",
        category="process",
        classifier=f"{package}::node{index}.impl",
        ownedPropertyAssociations=[
            _pa("Thread_Properties::Priority", _new("IntegerValue", value=10 + index % 80)),
            _pa("Deployment_Properties::Actual_Processor_Binding", _ref(cpu)),
        ],
    )
    message, classifier = _message(index)
    for direction in ("in", "out"):
        props = [_pa("ROS_Properties::Message_Type", _new("StringValue", value=message))] if message else []
        process.featureInstances.append(
            _new(
                "FeatureInstance",
                name=f"data_{direction}",
                feature=f"data_{direction}",
                category="event data port",
                direction=direction,
                classifier=classifier,
                ownedPropertyAssociations=props,
            )
        )
    ports = {}
    for name, dispatch, direction in (("publisher", "Periodic", "out"), ("receiver", "Sporadic", "in")):
        thread, ports[direction] = _ring_thread(name, dispatch, direction, index, period)
        process.componentInstances.append(thread)
    return process, ports


def ros_ring(nodes: int) -> EObject:
    """A ``SystemInstance`` of ``nodes`` ROS nodes in a ring.

    N processes of N distinct classifiers spread over 20 software packages, each with a periodic
    publisher thread and a sporadic subscriber thread (``Period``, ``Deadline``,
    ``Compute_Execution_Time``, ``Priority``, ``Queue_Size``, standard and custom message types),
    a ring of port connections between the nodes (one semantic connection per pair, with its
    connection references) and one processor per 8 nodes."""
    ws = _new("AadlModel", name="bench")
    root = _new(
        "SystemInstance", name="bench_impl_Instance", classifier="bench::bench.impl", category="system"
    )
    ws.instances.append(root)
    cpus = [
        _new("ComponentInstance", name=f"cpu{index}", subcomponent=f"cpu{index}", category="processor")
        for index in range((nodes + 7) // 8)
    ]
    processes = []
    for index in range(nodes):
        process, ports = _ring_node(index, cpus[index // 8])
        processes.append((process, ports))
        root.componentInstances.append(process)
    root.componentInstances.extend(cpus)
    for index, (process, ports) in enumerate(processes):
        target, target_ports = processes[(index + 1) % nodes]
        source_port, destination_port = ports["out"], target_ports["in"]
        out_feature, in_feature = process.featureInstances[1], target.featureInstances[0]
        refs = [
            _new(
                "ConnectionReference",
                connection="c_out",
                context=process,
                source=source_port,
                destination=out_feature,
            ),
            _new(
                "ConnectionReference",
                connection=f"ring{index}",
                context=root,
                source=out_feature,
                destination=in_feature,
            ),
            _new(
                "ConnectionReference",
                connection="c_in",
                context=target,
                source=in_feature,
                destination=destination_port,
            ),
        ]
        root.connectionInstances.append(
            _new(
                "ConnectionInstance",
                name=f"{process.name}.publisher.msg -> {target.name}.receiver.msg",
                kind="portConnection",
                complete=True,
                source=source_port,
                destination=destination_port,
                connectionReferences=refs,
            )
        )
    return root


# --------------------------------------------------------------------------- flat instance objects

FLAT_PER_UNIT = 11  # objects made per component instance
FLAT_CLASSES = (
    "SystemInstance",
    "ComponentInstance",
    "FeatureInstance",
    "ConnectionInstance",
    "PropertyAssociation",
    "ModalPropertyValue",
    "IntegerValue",
)


def flat_instance(classes: dict[str, Any], objects: int) -> tuple[Any, int]:
    """About ``objects`` instance objects made with ``classes`` (the ``FLAT_CLASSES`` by name,
    dynamic or static): a root of component instances with three features, two integer property
    values and a connection each. Returns the root and the number of objects."""
    C = classes
    units = max(1, objects // FLAT_PER_UNIT)
    root = C["SystemInstance"](name="top")
    for i in range(units):
        comp = C["ComponentInstance"](name=f"t{i}")
        root.componentInstances.append(comp)
        feats = [C["FeatureInstance"](name=f"p{j}") for j in range(3)]
        comp.featureInstances.extend(feats)
        for prop, value in (("Timing_Properties::Period", 33333), ("Timing_Properties::Deadline", 30000)):
            pa = C["PropertyAssociation"](property=prop)
            mv = C["ModalPropertyValue"]()
            mv.value = C["IntegerValue"](value=value, unit="us")
            pa.ownedValues.append(mv)
            comp.ownedPropertyAssociations.append(pa)
        conn = C["ConnectionInstance"](name=f"t{i}.p0 -> t{i}.p1")
        conn.source = feats[0]
        conn.destination = feats[1]
        root.connectionInstances.append(conn)
    return root, units * FLAT_PER_UNIT + 1

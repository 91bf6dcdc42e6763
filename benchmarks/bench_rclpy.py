"""Code generation benchmark: a ROS 2 workspace for a system of N nodes (default 1 000).

The instance is built directly with the model API, as the instantiator makes them: N processes
of N distinct classifiers spread over 20 software packages, each with a periodic publisher
thread and a sporadic subscriber thread (``Period``, ``Deadline``, ``Compute_Execution_Time``,
``Priority``, ``Queue_Size``, standard and custom message types), a ring of port connections
between the nodes (one semantic connection per pair, with its connection references) and one
processor per 8 nodes.

Side by side: building the instance, the first generation (every file written), a regeneration
of the unchanged model (nothing written), and a regeneration after renaming a thread in every
tenth node (the trace moves the blocks), against the floor of 10 s for 1 000 nodes.
Usage: ``python -m benchmarks.bench_rclpy [--nodes N] [--output DIR]``.
"""

from __future__ import annotations

import argparse
import logging
import tempfile
import time
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import model

FLOOR_SECONDS = 10.0
FLOOR_NODES = 1000
PACKAGES = 20


class _Classes(dict):
    """Metamodel classes by name, looked up once (model.new accepts the class itself)."""

    def __missing__(self, name: str):
        self[name] = model.eclass_of(name)
        return self[name]


_C = _Classes()


def new(class_name: str, /, **values) -> EObject:
    return model.new(_C[class_name], **values)


def _pa(prop: str, value: EObject) -> EObject:
    return new("PropertyAssociation", property=prop, ownedValues=[new("ModalPropertyValue", value=value)])


def _us(value: int) -> EObject:
    return new("IntegerValue", value=value, unit="us")


def build_instance(nodes: int) -> EObject:
    """A ``SystemInstance`` of ``nodes`` ROS nodes in a ring (see the module docstring)."""
    ws = new("AadlModel", name="bench")
    root = new(
        "SystemInstance", name="bench_impl_Instance", classifier="bench::bench.impl", category="system"
    )
    ws.instances.append(root)
    cpus = []
    for index in range((nodes + 7) // 8):
        cpu = new("ComponentInstance", name=f"cpu{index}", subcomponent=f"cpu{index}", category="processor")
        cpus.append(cpu)
    processes = []
    for index in range(nodes):
        package = f"pkg{index % PACKAGES}"
        period = 10_000 + 1_000 * (index % 7)
        process = new(
            "ComponentInstance",
            name=f"node{index}",
            subcomponent=f"node{index}",
            category="process",
            classifier=f"{package}::node{index}.impl",
            ownedPropertyAssociations=[
                _pa("Thread_Properties::Priority", new("IntegerValue", value=10 + index % 80)),
                _pa(
                    "Deployment_Properties::Actual_Processor_Binding",
                    new(
                        "ListValue",
                        ownedItems=[new("InstanceReferenceValue", referencedInstanceObject=cpus[index // 8])],
                    ),
                ),
            ],
        )
        message = "sensor_msgs/Image" if index % 2 else None
        classifier = "ros_data::Image.rgb" if index % 2 else f"{package}::Sample{index % 3}"
        for direction in ("in", "out"):
            props = (
                [_pa("ROS_Properties::Message_Type", new("StringValue", value=message))] if message else []
            )
            process.featureInstances.append(
                new(
                    "FeatureInstance",
                    name=f"data_{direction}",
                    feature=f"data_{direction}",
                    category="event data port",
                    direction=direction,
                    classifier=classifier,
                    ownedPropertyAssociations=props,
                )
            )
        threads = {}
        for name, dispatch, direction in (("publisher", "Periodic", "out"), ("receiver", "Sporadic", "in")):
            props = [
                _pa("Thread_Properties::Dispatch_Protocol", new("NamedValue", name=dispatch)),
                _pa("Timing_Properties::Period", _us(period)),
                _pa("Timing_Properties::Deadline", _us(period // 2)),
                _pa(
                    "Timing_Properties::Compute_Execution_Time",
                    new("RangeValue", minimum=_us(100), maximum=_us(900)),
                ),
                _pa("Thread_Properties::Priority", new("IntegerValue", value=20)),
            ]
            thread = new(
                "ComponentInstance",
                name=name,
                subcomponent=name,
                category="thread",
                classifier=f"{package}::{name}{index}.impl",
                ownedPropertyAssociations=props,
            )
            port_props = [_pa("Communication_Properties::Queue_Size", new("IntegerValue", value=4))]
            if message:
                port_props.append(_pa("ROS_Properties::Message_Type", new("StringValue", value=message)))
            port = new(
                "FeatureInstance",
                name="msg",
                feature="msg",
                category="event data port",
                direction=direction,
                classifier=classifier,
                ownedPropertyAssociations=port_props,
            )
            thread.featureInstances.append(port)
            process.componentInstances.append(thread)
            threads[direction] = port
        processes.append((process, threads))
        root.componentInstances.append(process)
    root.componentInstances.extend(cpus)
    for index, (process, threads) in enumerate(processes):
        target, target_threads = processes[(index + 1) % nodes]
        source_port = threads["out"]
        destination_port = target_threads["in"]
        out_feature = process.featureInstances[1]
        in_feature = target.featureInstances[0]
        refs = [
            new(
                "ConnectionReference",
                connection="c_out",
                context=process,
                source=source_port,
                destination=out_feature,
            ),
            new(
                "ConnectionReference",
                connection=f"ring{index}",
                context=root,
                source=out_feature,
                destination=in_feature,
            ),
            new(
                "ConnectionReference",
                connection="c_in",
                context=target,
                source=in_feature,
                destination=destination_port,
            ),
        ]
        root.connectionInstances.append(
            new(
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


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_rclpy", description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=FLOOR_NODES)
    parser.add_argument(
        "--output", type=Path, default=None, help="folder to generate into (default: a temporary one)"
    )
    args = parser.parse_args(argv)
    logging.getLogger("rosaadl").setLevel(logging.ERROR)

    from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace
    from rosaadl.transforms import trace as tracing

    options = GenerationOptions(year=2024)
    start = time.perf_counter()
    root = build_instance(args.nodes)
    build = time.perf_counter() - start

    with tempfile.TemporaryDirectory(prefix="bench_rclpy_") as scratch:
        out = args.output or Path(scratch) / "src"
        start = time.perf_counter()
        first = generate_workspace(root, out, options=options)
        generate = time.perf_counter() - start

        start = time.perf_counter()
        second = generate_workspace(root, out, options=options)
        unchanged = time.perf_counter() - start

        trace = tracing.new_trace("rename")
        for process in root.componentInstances[: args.nodes : 10]:
            thread = process.componentInstances[1]
            old = tracing.element_key(thread)
            thread.name = thread.subcomponent = "listener"
            link = model.new("trace.TraceLink", rule="rename")
            link.sources.append(model.new("trace.TraceElement", path=old))
            link.targets.append(model.new("trace.TraceElement", path=tracing.element_key(thread)))
            trace.links.append(link)
        start = time.perf_counter()
        third = generate_workspace(root, out, options=options, trace=trace)
        renamed = time.perf_counter() - start

    floor = FLOOR_SECONDS * args.nodes / FLOOR_NODES
    rows = [
        ("build instance", build, f"{args.nodes} nodes, {2 * args.nodes} threads"),
        ("generate", generate, f"{len(first.written)} files written"),
        ("regenerate, unchanged", unchanged, f"{len(second.written)} files written"),
        (
            "regenerate, renames",
            renamed,
            f"{len(third.written)} files written, {len(third.moved)} blocks moved",
        ),
    ]
    print(f"{'step':<24} {'seconds':>8}  notes")
    for name, seconds, note in rows:
        print(f"{name:<24} {seconds:>8.2f}  {note}")
    verdict = "ok" if generate <= floor else "SLOWER than the floor"
    print(f"floor: generate {args.nodes} nodes in {floor:.1f} s -> {verdict}")
    return 0 if generate <= floor else 1


if __name__ == "__main__":
    import sys

    raise SystemExit(main(sys.argv[1:]))

"""Instantiation benchmark: a generated system of P processes × T threads (default 100 × 100).

Every thread has an in and an out event data port typed by a data type with ``Data_Size``,
``Dispatch_Protocol``, ``Period`` and ``Compute_Execution_Time``; the threads of a process form a
chain of port connections, the processes form a chain too (one semantic connection per process
boundary), and every process is bound to the processor by a contained ``applies to`` association,
which its threads inherit.  The property sets are the few definitions the model uses, written
out here so that the benchmark measures instantiation only.

Side by side in one run, for a tenth of the size and the full size: building the declarative
model, instantiating it (wall clock and CPU time), the objects made, against the floor of 10 s
for 10 000 threads (scaled for the smaller size).  Usage: ``python -m benchmarks.bench_instantiate
[--processes P] [--threads T]``.
"""

from __future__ import annotations

import argparse
import logging
import time

from pyecore.ecore import EObject

from rosaadl import model

FLOOR_SECONDS = 10.0
FLOOR_THREADS = 10_000


def _property_sets() -> list[EObject]:
    new = model.new
    time_units = new(
        "UnitsType",
        name="Time_Units",
        ownedLiterals=[
            new("UnitLiteral", name="ps"),
            new("UnitLiteral", name="ns", baseUnit="ps", factor=new("IntegerValue", value=1000)),
            new("UnitLiteral", name="us", baseUnit="ns", factor=new("IntegerValue", value=1000)),
            new("UnitLiteral", name="ms", baseUnit="us", factor=new("IntegerValue", value=1000)),
        ],
    )
    size_units = new(
        "UnitsType",
        name="Size_Units",
        ownedLiterals=[
            new("UnitLiteral", name="bits"),
            new("UnitLiteral", name="Bytes", baseUnit="bits", factor=new("IntegerValue", value=8)),
        ],
    )
    project = new(
        "PropertySet",
        name="AADL_Project",
        ownedPropertyTypes=[
            time_units,
            size_units,
            new("AadlInteger", name="Time", unitsType="AADL_Project::Time_Units"),
            new("RangeType", name="Time_Range", numberType="AADL_Project::Time"),
            new("AadlInteger", name="Size", unitsType="AADL_Project::Size_Units"),
        ],
    )
    timing = new(
        "PropertySet",
        name="Timing_Properties",
        withs=["AADL_Project"],
        ownedProperties=[
            new(
                "Property",
                name="Period",
                inherit=True,
                type="AADL_Project::Time",
                appliesTo=["thread", "thread group", "process", "system", "device", "virtual processor"],
            ),
            new(
                "Property",
                name="Deadline",
                inherit=True,
                type="AADL_Project::Time",
                defaultValue=new("NamedValue", name="Timing_Properties::Period"),
                appliesTo=["thread", "thread group", "process", "system", "device", "virtual processor"],
            ),
            new(
                "Property",
                name="Compute_Execution_Time",
                type="AADL_Project::Time_Range",
                appliesTo=["thread", "device", "subprogram", "event port", "event data port"],
            ),
        ],
    )
    thread = new(
        "PropertySet",
        name="Thread_Properties",
        ownedProperties=[
            new(
                "Property",
                name="Dispatch_Protocol",
                ownedType=new(
                    "EnumerationType",
                    ownedLiterals=[new("EnumerationLiteral", name=n) for n in ("Periodic", "Sporadic")],
                ),
                appliesTo=["thread", "device", "virtual processor"],
            )
        ],
    )
    memory = new(
        "PropertySet",
        name="Memory_Properties",
        withs=["AADL_Project"],
        ownedProperties=[
            new(
                "Property",
                name="Data_Size",
                type="AADL_Project::Size",
                appliesTo=["data", "data port", "event data port", "subprogram", "thread", "process"],
            )
        ],
    )
    deployment = new(
        "PropertySet",
        name="Deployment_Properties",
        ownedProperties=[
            new(
                "Property",
                name="Actual_Processor_Binding",
                inherit=True,
                ownedType=new("ListType", ownedElementType=new("ReferenceType", categories=["processor"])),
                appliesTo=["thread", "thread group", "process", "system", "virtual processor", "device"],
            )
        ],
    )
    return [project, timing, thread, memory, deployment]


def _pa(prop: str, value: EObject, applies_to: list[str] | None = None) -> EObject:
    return model.new(
        "PropertyAssociation",
        property=prop,
        appliesTo=applies_to or [],
        ownedValues=[model.new("ModalPropertyValue", value=value)],
    )


def build_model(processes: int = 100, threads: int = 100) -> EObject:
    """The declarative model of the benchmark system (``bench::top.impl``)."""
    new = model.new
    ws = new("AadlModel", name="bench")
    ws.units.extend(_property_sets())
    pkg = new("AadlPackage", name="bench", sourceFile="bench.aadl")
    ws.units.append(pkg)
    ports = [
        new("Feature", name="inp", category="event data port", direction="in", classifier="msg"),
        new("Feature", name="outp", category="event data port", direction="out", classifier="msg"),
    ]
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="msg",
            category="data",
            ownedPropertyAssociations=[_pa("Data_Size", new("IntegerValue", value=8, unit="Bytes"))],
        )
    )
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="worker",
            category="thread",
            features=[
                new(
                    "Feature",
                    name=f.name,
                    category=f.category,
                    direction=f.direction,
                    classifier=f.classifier,
                )
                for f in ports
            ],
            ownedPropertyAssociations=[
                _pa("Dispatch_Protocol", new("NamedValue", name="Periodic")),
                _pa("Period", new("IntegerValue", value=10, unit="ms")),
                _pa(
                    "Compute_Execution_Time",
                    new(
                        "RangeValue",
                        minimum=new("IntegerValue", value=1, unit="ms"),
                        maximum=new("IntegerValue", value=2, unit="ms"),
                    ),
                ),
            ],
        )
    )
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="node",
            category="process",
            features=[
                new(
                    "Feature",
                    name=f.name,
                    category=f.category,
                    direction=f.direction,
                    classifier=f.classifier,
                )
                for f in ports
            ],
        )
    )
    node = new("ComponentImplementation", name="node.impl", type="node", category="process")
    node.subcomponents.extend(
        new("Subcomponent", name=f"t{i}", category="thread", classifier="worker")
        for i in range(1, threads + 1)
    )
    node.connections.append(new("Connection", name="cin", kind="port", source="inp", destination="t1.inp"))
    node.connections.extend(
        new("Connection", name=f"c{i}", kind="port", source=f"t{i}.outp", destination=f"t{i + 1}.inp")
        for i in range(1, threads)
    )
    node.connections.append(
        new("Connection", name="cout", kind="port", source=f"t{threads}.outp", destination="outp")
    )
    pkg.classifiers.append(node)
    pkg.classifiers.append(new("ComponentType", name="cpu", category="processor"))
    pkg.classifiers.append(new("ComponentType", name="top", category="system"))
    top = new("ComponentImplementation", name="top.impl", type="top", category="system")
    top.subcomponents.extend(
        new("Subcomponent", name=f"p{i}", category="process", classifier="node.impl")
        for i in range(1, processes + 1)
    )
    top.subcomponents.append(new("Subcomponent", name="cpu", category="processor", classifier="cpu"))
    top.connections.extend(
        new("Connection", name=f"k{i}", kind="port", source=f"p{i}.outp", destination=f"p{i + 1}.inp")
        for i in range(1, processes)
    )
    top.ownedPropertyAssociations.append(
        _pa(
            "Actual_Processor_Binding",
            new("ListValue", ownedItems=[new("ReferenceValue", path="cpu")]),
            [f"p{i}" for i in range(1, processes + 1)],
        )
    )
    pkg.classifiers.append(top)
    return ws


def run(processes: int, threads: int) -> dict[str, float | int]:
    from rosaadl.transforms.instantiate import Instantiator

    start = time.perf_counter()
    ws = build_model(processes, threads)
    built = time.perf_counter() - start
    start = time.perf_counter()
    cpu = time.process_time()
    instantiator = Instantiator(ws)
    instantiator.run("bench::top.impl")
    seconds = time.perf_counter() - start
    cpu = time.process_time() - cpu
    made = instantiator.factory.made
    counts = {
        name: made.get(name, 0) for name in ("ComponentInstance", "FeatureInstance", "ConnectionInstance")
    }
    counts["PropertyAssociation"] = made.get("PropertyAssociation", 0)
    objects = sum(made.values()) + 1
    return {
        "threads": processes * threads,
        "objects": objects,
        "build_s": built,
        "instantiate_s": seconds,
        "cpu_s": cpu,
        "components": counts["ComponentInstance"] + 1,
        "features": counts["FeatureInstance"],
        "connections": counts["ConnectionInstance"],
        "property_associations": counts["PropertyAssociation"],
    }


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_instantiate", description=__doc__.splitlines()[0])
    parser.add_argument("--processes", type=int, default=100)
    parser.add_argument("--threads", type=int, default=100, help="threads per process")
    args = parser.parse_args(argv)
    logging.getLogger("rosaadl").setLevel(logging.ERROR)
    sizes = [(max(1, args.processes // 10), args.threads), (args.processes, args.threads)]
    print(
        f"{'threads':>8} {'objects':>9} {'components':>10} {'features':>9} {'connections':>11} "
        f"{'props':>7} {'build s':>8} {'inst. s':>8} {'cpu s':>7} {'floor s':>8}"
    )
    status = 0
    for processes, threads in sizes:
        result = run(processes, threads)
        floor = FLOOR_SECONDS * result["threads"] / FLOOR_THREADS
        print(
            f"{result['threads']:>8} {result['objects']:>9} {result['components']:>10} "
            f"{result['features']:>9} {result['connections']:>11} {result['property_associations']:>7} "
            f"{result['build_s']:>8.2f} {result['instantiate_s']:>8.2f} {result['cpu_s']:>7.2f} "
            f"{floor:>8.2f}",
            flush=True,
        )
        if result["instantiate_s"] > floor:
            status = 1
    return status


if __name__ == "__main__":
    import sys

    raise SystemExit(main(sys.argv[1:]))

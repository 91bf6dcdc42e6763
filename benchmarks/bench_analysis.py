"""Analysis benchmark: resource, budget, bus load, latency and deployment analyses at scale.

One synthetic robot fleet per run: ``--boards`` boards of four cores, ``--nodes`` ROS nodes (a
process with a periodic publisher and a sporadic subscriber) bound round robin to the cores, a
network bus per board with two nested virtual buses, and a topic per node to the next node,
bound to the virtual buses. Timed (best of ``--rounds``, CPU seconds):

  * bound resource allocation (processor/core MIPS and load) and not-bound budgets;
  * OSATE's bus load analysis and its CSV report;
  * end-to-end latency of every maximal thread chain (limited to 100 chains);
  * the deployment search, exact on a small problem (8 nodes on 4 cores) and by the heuristic on
    the whole fleet;
  * every default analysis together, rendered as JSON.

Floors: each analysis of the default fleet (400 nodes, 800 threads) under 2 s; the exact
deployment search of 8 nodes on 4 cores under 2 s.
Usage: ``python -m benchmarks.bench_analysis [--boards B] [--nodes N] [--rounds R]``.
"""

from __future__ import annotations

import argparse
import gc
import time
from collections.abc import Callable
from typing import Any

from rosaadl import model
from rosaadl.analysis.budgets import analyze_budgets
from rosaadl.analysis.busload import analyze_bus_load
from rosaadl.analysis.deployment import search_deployment
from rosaadl.analysis.latency import analyze_latency
from rosaadl.analysis.report import run_analyses
from rosaadl.analysis.resources import analyze_resources

__all__ = ["main", "fleet"]

FLOOR_SECONDS = 2.0

new = model.new


def _pa(prop: str, value: Any) -> Any:
    return new("PropertyAssociation", property=prop, ownedValues=[new("ModalPropertyValue", value=value)])


def _num(value: float | int, unit: str) -> Any:
    return new("RealValue" if isinstance(value, float) else "IntegerValue", value=value, unit=unit)


def _ref(*targets: Any) -> Any:
    return new(
        "ListValue", ownedItems=[new("InstanceReferenceValue", referencedInstanceObject=t) for t in targets]
    )


def _thread(name: str, period: int, cet: int, dispatch: str, ports: list[Any]) -> Any:
    ci = new("ComponentInstance", name=name, category="thread")
    ci.ownedPropertyAssociations.extend(
        [
            _pa("Timing_Properties::Period", _num(period, "us")),
            _pa(
                "Timing_Properties::Compute_Execution_Time",
                new("RangeValue", minimum=_num(cet // 2, "us"), maximum=_num(cet, "us")),
            ),
            _pa("Thread_Properties::Dispatch_Protocol", new("NamedValue", name=dispatch)),
        ]
    )
    ci.featureInstances.extend(ports)
    return ci


def _port(name: str, direction: str, size: int) -> Any:
    fi = new("FeatureInstance", name=name, feature=name, category="event data port", direction=direction)
    fi.ownedPropertyAssociations.append(_pa("Memory_Properties::Data_Size", _num(size, "Bytes")))
    return fi


def fleet(boards: int, nodes: int, bind: bool = True) -> Any:
    """The synthetic instance described in the module docstring."""
    root = new("SystemInstance", name="fleet_i_Instance", category="system")
    cores, buses = [], []
    for b in range(boards):
        board = new("ComponentInstance", name=f"board{b}", category="system")
        for c in range(4):
            core = new("ComponentInstance", name=f"core{c}", category="processor")
            core.ownedPropertyAssociations.extend(
                [
                    _pa("SEI::MIPSCapacity", _num(2000.0, "MIPS")),
                    _pa(
                        "Deployment_Properties::Scheduling_Protocol",
                        new("NamedValue", name="RATE_MONOTONIC_PROTOCOL"),
                    ),
                ]
            )
            board.componentInstances.append(core)
            cores.append(core)
        net = new("ComponentInstance", name="net", category="bus")
        net.ownedPropertyAssociations.extend(
            [
                _pa("SEI::BandWidthCapacity", _num(1000, "Mbps")),
                _pa("SEI::BandWidthBudget", _num(60000.0, "KBytesps")),
                _pa("Memory_Properties::Data_Size", _num(38, "Bytes")),
            ]
        )
        ros = new("ComponentInstance", name="ros", category="virtual bus")
        dds = new("ComponentInstance", name="dds", category="virtual bus")
        ros.ownedPropertyAssociations.append(_pa("Memory_Properties::Data_Size", _num(20, "Bytes")))
        dds.ownedPropertyAssociations.append(_pa("Memory_Properties::Data_Size", _num(16, "Bytes")))
        ros.componentInstances.append(dds)
        net.componentInstances.append(ros)
        board.componentInstances.append(net)
        buses.append(dds)
        root.componentInstances.append(board)
    publishers, subscribers = [], []
    for n in range(nodes):
        period = (10_000, 20_000, 40_000, 100_000)[n % 4]
        pub = _thread("pub", period, period // 20, "Periodic", [_port("o", "out", 24 + 8 * (n % 50))])
        sub = _thread("sub", period, period // 40, "Sporadic", [_port("i", "in", 24 + 8 * (n % 50))])
        node = new("ComponentInstance", name=f"node{n}", category="process")
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
        conn = new(
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


def _best(run: Callable[[], Any], rounds: int) -> tuple[float, Any]:
    best, result = float("inf"), None
    for _ in range(rounds):
        gc.collect()
        start = time.process_time()
        result = run()
        best = min(best, time.process_time() - start)
    return best, result


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_analysis", description=__doc__.splitlines()[0])
    parser.add_argument("--boards", type=int, default=25)
    parser.add_argument("--nodes", type=int, default=400)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)

    root = fleet(args.boards, args.nodes)
    unbound = fleet(args.boards, args.nodes, bind=False)
    small = fleet(1, 8, bind=False)
    rows: list[tuple[str, float, str, float | None]] = []

    seconds, result = _best(lambda: analyze_resources(root), args.rounds)
    rows.append(("bound resources", seconds, f"{len(result.processors)} processors", FLOOR_SECONDS))
    seconds, result = _best(lambda: analyze_budgets(root), args.rounds)
    rows.append(("not-bound budgets", seconds, f"{len(result.totals[0].rows)} components", FLOOR_SECONDS))
    seconds, result = _best(lambda: analyze_bus_load(root), args.rounds)
    buses = sum(len(b.walk()) for m in result.modes for b in m.buses)
    rows.append(
        ("bus load", seconds, f"{buses} buses, {len(root.connectionInstances)} connections", FLOOR_SECONDS)
    )
    seconds, text = _best(lambda: analyze_bus_load(root).csv_text(), args.rounds)
    rows.append(("bus load + OSATE CSV", seconds, f"{len(text.splitlines())} lines", FLOOR_SECONDS))
    seconds, result = _best(lambda: analyze_latency(root), args.rounds)
    rows.append(("latency", seconds, f"{len(result.chains)} chains", FLOOR_SECONDS))
    seconds, result = _best(lambda: search_deployment(small), args.rounds)
    rows.append(
        (
            "deployment, 8 nodes / 4 cores",
            seconds,
            f"{result.method}, {result.nodes} nodes, max {float(result.max_load) * 100:.1f} %",
            FLOOR_SECONDS,
        )
    )
    seconds, result = _best(lambda: search_deployment(unbound, node_limit=2000), 1)
    rows.append(
        (
            f"deployment, {args.nodes} nodes / {4 * args.boards} cores",
            seconds,
            f"{result.method}, max {float(result.max_load) * 100:.1f} %",
            None,
        )
    )
    seconds, text = _best(lambda: run_analyses(root).to_json(), 1)
    rows.append(("all default analyses + JSON", seconds, f"{len(text) // 1024} KiB", None))

    width = max(len(r[0]) for r in rows)
    print(f"{'analysis':<{width}}  {'CPU s':>8}  {'floor s':>7}  result")
    status = 0
    for name, secs, what, floor in rows:
        verdict = "" if floor is None else ("" if secs <= floor else "  ** over the floor **")
        if floor is not None and secs > floor:
            status = 1
        floor_text = "-" if floor is None else f"{floor:.1f}"
        print(f"{name:<{width}}  {secs:8.3f}  {floor_text:>7}  {what}{verdict}")
    return status


if __name__ == "__main__":
    import sys

    raise SystemExit(main(sys.argv[1:]))

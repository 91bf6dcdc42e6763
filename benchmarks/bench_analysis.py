"""Analysis benchmark: resource, budget, bus load, latency and deployment analyses at scale.

One synthetic robot fleet per run (``benchmarks.generators.instances.robot_fleet``): ``--boards``
boards of four cores, ``--nodes`` ROS nodes (a process with a periodic publisher and a sporadic
subscriber) bound round robin to the cores, a network bus per board with two nested virtual
buses, and a topic per node to the next node, bound to the virtual buses. Timed (best of
``--rounds``, CPU seconds):

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

from benchmarks.generators.instances import robot_fleet
from benchmarks.harness import Goal, Report, best_of
from rosaadl.analysis.budgets import analyze_budgets
from rosaadl.analysis.busload import analyze_bus_load
from rosaadl.analysis.deployment import search_deployment
from rosaadl.analysis.latency import analyze_latency
from rosaadl.analysis.report import run_analyses
from rosaadl.analysis.resources import analyze_resources

__all__ = ["main"]

FLOOR_SECONDS = 2.0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_analysis", description=__doc__.splitlines()[0])
    parser.add_argument("--boards", type=int, default=25)
    parser.add_argument("--nodes", type=int, default=400)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)

    root = robot_fleet(args.boards, args.nodes)
    unbound = robot_fleet(args.boards, args.nodes, bind=False)
    small = robot_fleet(1, 8, bind=False)
    report = Report("analysis")
    floor = Goal(FLOOR_SECONDS)

    timing = best_of(lambda: analyze_resources(root), args.rounds)
    report.time("bound resources", timing, goal=floor, note=f"{len(timing.result.processors)} processors")
    timing = best_of(lambda: analyze_budgets(root), args.rounds)
    report.time(
        "not-bound budgets", timing, goal=floor, note=f"{len(timing.result.totals[0].rows)} components"
    )
    timing = best_of(lambda: analyze_bus_load(root), args.rounds)
    buses = sum(len(b.walk()) for m in timing.result.modes for b in m.buses)
    connections = len(root.connectionInstances)
    report.time("bus load", timing, goal=floor, note=f"{buses} buses, {connections} connections")
    timing = best_of(lambda: analyze_bus_load(root).csv_text(), args.rounds)
    report.time("bus load + OSATE CSV", timing, goal=floor, note=f"{len(timing.result.splitlines())} lines")
    timing = best_of(lambda: analyze_latency(root), args.rounds)
    report.time("latency", timing, goal=floor, note=f"{len(timing.result.chains)} chains")
    timing = best_of(lambda: search_deployment(small), args.rounds)
    result = timing.result
    report.time(
        "deployment, 8 nodes / 4 cores",
        timing,
        goal=floor,
        note=f"{result.method}, {result.nodes} nodes, max {float(result.max_load) * 100:.1f} %",
    )
    timing = best_of(lambda: search_deployment(unbound, node_limit=2000), 1)
    result = timing.result
    report.time(
        f"deployment, {args.nodes} nodes / {4 * args.boards} cores",
        timing,
        note=f"{result.method}, max {float(result.max_load) * 100:.1f} %",
    )
    timing = best_of(lambda: run_analyses(root).to_json(), 1)
    report.time("all default analyses + JSON", timing, note=f"{len(timing.result) // 1024} KiB")
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

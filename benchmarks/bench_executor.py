"""Executor benchmark: the ``executor`` analysis on a generated 100-node, 500-callback, 40-chain
model, beside the preemptive response-time analysis (schedulability) of the same model.

The model: 100 ROS nodes (processes) of five callbacks each (two timers that publish, three
subscriptions), four nodes per core on 25 cores of seven boards, executors alternating between
single-threaded and multi-threaded; 40 topics from a timer of node ``k`` to a subscription of
node ``k + 50`` make 40 cause-effect chains. Floor: the executor analysis in 2 s of CPU.
Usage: ``python -m benchmarks.bench_executor [--nodes N] [--rounds R]``.
"""

from __future__ import annotations

import argparse

from benchmarks.generators.instances import _board, _new, _pa, _port, _ref, _thread
from benchmarks.harness import Goal, Report, best_of
from rosaadl.analysis.executor_analysis import analyze_executors
from rosaadl.analysis.schedulability import analyze_schedulability

__all__ = ["main", "executor_fleet"]

FLOOR_SECONDS = 2.0


def executor_fleet(nodes: int = 100, chains: int = 40):
    """A ``SystemInstance`` of ``nodes`` nodes of five callbacks and ``chains`` topic chains."""
    root = _new("SystemInstance", name="exec_i_Instance", category="system")
    cores = []
    for b in range(-(-nodes // 16)):
        board, board_cores, _bus = _board(b)
        cores.extend(board_cores)
        root.componentInstances.append(board)
    timers, subscriptions = [], []
    for n in range(nodes):
        period = (10_000, 20_000, 40_000, 100_000)[n % 4]
        threads = []
        for k in range(2):
            threads.append(
                _thread(f"timer{k}", period * (k + 1), period // 50, "Periodic", [_port("o", "out", 24)])
            )
        for k in range(3):
            threads.append(_thread(f"sub{k}", period, period // 50, "Sporadic", [_port("i", "in", 24)]))
        node = _new("ComponentInstance", name=f"node{n}", category="process")
        node.componentInstances.extend(threads)
        if n % 2:
            node.ownedPropertyAssociations.append(
                _pa("ROS_Properties::Executor_Kind", _new("NamedValue", name="Single_Threaded"))
            )
        core = cores[(n // 4) % len(cores)]
        for thread in threads:
            thread.ownedPropertyAssociations.append(
                _pa("Deployment_Properties::Actual_Processor_Binding", _ref(core))
            )
        root.componentInstances.append(node)
        timers.append(threads[0])
        subscriptions.append(threads[2])
    for k in range(chains):
        src, dst = timers[k], subscriptions[(k + nodes // 2) % nodes]
        root.connectionInstances.append(
            _new(
                "ConnectionInstance",
                name=f"topic{k}",
                kind="portConnection",
                source=src.featureInstances[0],
                destination=dst.featureInstances[0],
            )
        )
    return root


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_executor", description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=100)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    root = executor_fleet(args.nodes)
    report = Report("executor")
    preemptive = best_of(lambda: analyze_schedulability(root), args.rounds)
    tasks = sum(len(d.tasks) for d in preemptive.result.domains)
    report.time("preemptive RTA (schedulability)", preemptive, note=f"{tasks} threads")
    timing = best_of(lambda: analyze_executors(root, schedulability=preemptive.result), args.rounds)
    result = timing.result
    report.time(
        "executor analysis",
        timing,
        preemptive,
        goal=Goal(FLOOR_SECONDS),
        note=f"{len(result.executors)} executors, {len(result.callbacks)} callbacks, "
        f"{len(result.chains)} chains",
    )
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

"""ROSMOD ⇄ AADL conversion benchmark: the largest corpus deployment and generated projects.

Side by side for each input: ROSMOD → AADL (``rosmod_to_aadl``, with its trace), writing the
AADL text (``write_model``), and AADL → ROSMOD (``aadl_to_rosmod`` on the converted model).
Generated projects have N nodes, each running one component instance with 5 callbacks (2
timers, 2 subscribers, 1 server) plus a publisher and a client; there are N/2 message types,
so that every topic joins 2 publishers to 4 subscribers (4 N topic connections). The table ends
with how the conversion time grows from 100 to 1 000 to 5 000 nodes (the exponent k in
t ∝ N^k). Floors: the corpus deployment in under 1 s, 1 000 nodes in under 20 s.

Usage: ``python -m benchmarks.bench_rosmod_convert [--sizes 100,1000,5000] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import gc
import logging
import math
import os
import tempfile
import time
from collections.abc import Callable
from decimal import Decimal
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.exporters.aadl_text import write_model
from rosaadl.importers import rosmod_text
from rosaadl.transforms.aadl_to_rosmod import aadl_to_rosmod
from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl

CORPUS_PROJECT = "textual-v0.3/periodic-timers"
FLOORS = {"corpus": 1.0, 1000: 20.0}


def _corpus() -> Path:
    env = os.environ.get("ROSAADL_CORPUS")
    root = Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "corpus"
    return root / "rosmod"


def generate_project(nodes: int) -> EObject:
    """A ROSMOD project with ``nodes`` nodes of one component instance with 5 callbacks each."""
    new = model.new
    components = max(1, nodes // 2)
    package = new("rosmod.Package", name="gen")
    for k in range(components):
        package.messages.append(
            new(
                "rosmod.Message",
                name=f"Topic{k}",
                definition=f"uint64 stamp\nfloat64[{k % 4 + 1}] values\n",
                fields=[
                    new("rosmod.Field", name="stamp", type="uint64"),
                    new("rosmod.Field", name="values", type="float64", isArray=True, arrayLength=k % 4 + 1),
                ],
            )
        )
    package.services.append(new("rosmod.Service", name="Call", definition="int64 request\n---\nbool ok\n"))
    comps = []
    for k in range(components):
        comp = new("rosmod.Component", name=f"comp_{k}", datatype="Base")
        comp.ports.extend(
            [
                new("rosmod.Publisher", name="out", type=f"gen/Topic{k}"),
                new("rosmod.Client", name="ask", type="gen/Call"),
                new(
                    "rosmod.Subscriber",
                    name="in_a",
                    type=f"gen/Topic{(k + 1) % components}",
                    priority=50,
                    deadline=Decimal("0.05"),
                ),
                new(
                    "rosmod.Subscriber",
                    name="in_b",
                    type=f"gen/Topic{(k + 2) % components}",
                    priority=40,
                    deadline=Decimal("0.1"),
                ),
                new("rosmod.Server", name="answer", type="gen/Call", priority=60, deadline=Decimal("0.02")),
            ]
        )
        comp.timers.extend(
            [
                new(
                    "rosmod.Timer", name="fast", period=Decimal("0.01"), priority=70, deadline=Decimal("0.01")
                ),
                new("rosmod.Timer", name="slow", period=Decimal("1.0"), priority=30, deadline=Decimal("0.5")),
            ]
        )
        comps.append(comp)
    package.components.extend(comps)
    system = new("rosmod.System", name="cluster")
    hosts = [
        new("rosmod.Host", name=f"host_{h}", ipAddress=f"10.0.{h // 250}.{h % 250}", architecture="x64")
        for h in range(max(1, nodes // 10))
    ]
    system.hosts.extend(hosts)
    deployment = new("rosmod.Deployment", name="generated", systemName="cluster", system=system)
    for n in range(nodes):
        host = hosts[n % len(hosts)]
        node = new("rosmod.Node", name=f"node_{n}", priority=50, host=host, hostRef=f"cluster/{host.name}")
        comp = comps[n % components]
        node.componentInstances.append(
            new(
                "rosmod.ComponentInstance",
                name=f"inst_{n}",
                component=comp,
                componentRef=f"gen/{comp.name}",
                schedulingScheme="PFIFO",
            )
        )
        deployment.nodes.append(node)
    project = new("rosmod.Project", name=f"generated_{nodes}", formatVersion="0.3")
    project.software = new("rosmod.Software", name="software", packages=[package])
    project.systems.append(system)
    project.deployments.append(deployment)
    return project


def _best(action: Callable[[], object], repeat: int) -> tuple[float, object]:
    best = math.inf
    result = None
    for _ in range(repeat):
        gc.collect()
        start = time.perf_counter()
        result = action()
        best = min(best, time.perf_counter() - start)
    return best, result


def _row(label: str, project: EObject, repeat: int, folder: Path) -> tuple[str, float, float, float, int]:
    forward, result = _best(lambda: rosmod_to_aadl(project), repeat)
    out = folder / label.replace(" ", "_").replace("/", "_")
    writing, _ = _best(lambda: write_model(result.model, out), 1)
    back, _ = _best(lambda: aadl_to_rosmod(result.model), repeat)
    threads = sum(
        len(i.component.timers)
        + sum(1 for p in i.component.ports if p.eClass.name in ("Subscriber", "Server"))
        for d in project.deployments
        for n in d.nodes
        for i in n.componentInstances
    )
    return label, forward, writing, back, threads


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_rosmod_convert", description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,5000", help="generated project sizes (nodes)")
    parser.add_argument("--repeat", type=int, default=3, help="best of this many runs (small inputs)")
    args = parser.parse_args(argv)
    logging.disable(logging.WARNING)
    sizes = [int(s) for s in args.sizes.split(",") if s.strip()]
    rows = []
    status = 0
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        corpus = _corpus() / CORPUS_PROJECT
        if corpus.is_dir():
            project = rosmod_text.read_project(corpus)
            rows.append((*_row(CORPUS_PROJECT, project, args.repeat, folder), FLOORS["corpus"]))
        else:
            print(f"(corpus project {CORPUS_PROJECT} not found: its row is skipped)")
        timings: dict[int, float] = {}
        for size in sizes:
            project = generate_project(size)
            repeat = args.repeat if size <= 1000 else 1
            row = _row(f"generated {size} nodes", project, repeat, folder)
            timings[size] = row[1]
            rows.append((*row, FLOORS.get(size)))
    print(f"{'input':<34} {'threads':>8} {'to AADL s':>10} {'write s':>9} {'to ROSMOD s':>12} {'floor s':>8}")
    for label, forward, writing, back, threads, floor in rows:
        mark = ""
        if floor is not None and forward > floor:
            mark = "  SLOWER THAN THE FLOOR"
            status = 1
        shown = f"{floor:.1f}" if floor is not None else "-"
        print(f"{label:<34} {threads:>8} {forward:>10.3f} {writing:>9.3f} {back:>12.3f} {shown:>8}{mark}")
    ordered = sorted(timings)
    for small, large in zip(ordered, ordered[1:], strict=False):
        if timings[small] > 0:
            k = math.log(timings[large] / timings[small]) / math.log(large / small)
            print(f"growth {small} → {large} nodes: t ∝ N^{k:.2f}")
    return status


if __name__ == "__main__":
    raise SystemExit(main(__import__("sys").argv[1:]))

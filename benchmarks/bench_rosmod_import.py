"""ROSMOD import benchmark: the largest corpus projects and generated projects of growing size.

Side by side for each input: the time to tokenize and parse the files alone (the floor of the
reader), the full import into a ``rosmod.Project`` (parse, model objects, name resolution), and
saving the result as XMI. Generated v0.3 projects have N nodes, each running one component
instance with 5 callbacks (2 timers, 2 subscribers, 1 server) plus 2 publishers and a client;
the table ends with how the import time grows from 100 to 1 000 to 5 000 nodes (the exponent k
in t ∝ N^k). The corpus rows are skipped when the corpus is absent.

Usage: ``python -m benchmarks.bench_rosmod_import [--sizes 100,1000,5000] [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import logging
import math
import os
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from rosaadl import model
from rosaadl.importers import rosmod_text, rosmod_webgme
from rosaadl.importers.rosmod_text.blocks import parse_blocks

CORPUS_PROJECTS = (
    "textual-v0.3/periodic-timers",
    "textual-v0.3/sequential-leds",
    "textual-v0.3/client-server",
    "textual-v0.3/agse",
    "agse2015/agse_rosmod_project",
)
CORPUS_SEEDS = ("webgme/samples-2018-05-19_noTLC.webgmex", "webgme/samples-2016-06-13_noTLC.webgmex")


def _corpus() -> Path:
    env = os.environ.get("ROSAADL_CORPUS")
    root = Path(env) if env else Path(__file__).resolve().parents[2] / "shared" / "corpus"
    return root / "rosmod"


def generate_project(folder: Path, nodes: int) -> Path:
    """Write a v0.3 project with ``nodes`` nodes and 5 callbacks per node; returns its folder."""
    project = folder / f"generated_{nodes}"
    sw = project / "01-Software"
    (sw / "msg").mkdir(parents=True)
    (sw / "srv").mkdir()
    (project / "02-Hardware").mkdir()
    (project / "03-Deployment").mkdir()
    (project / f"generated_{nodes}.rosmod").write_text("This is a ROSMOD Project")
    topics = 20
    for k in range(topics):
        (sw / "msg" / f"gen.Topic{k}.msg").write_text(
            f"uint64 stamp\nfloat64[{k % 4 + 1}] values\nint32 id\n"
        )
    for k in range(topics // 4):
        (sw / "srv" / f"gen.Call{k}.srv").write_text("int64 request\n---\nbool ok\nfloat64 value\n")
    rml = ["/*\n * generated software model\n */\npackage gen\n{\n"]
    for c in range(nodes):
        a, b = c % topics, (c + 7) % topics
        s = c % (topics // 4)
        rml.append(
            f"  // ROSMOD Component - comp_{c}\n  component comp_{c} : Base\n  {{\n"
            f"    publisher <gen/Topic{a}> out_a;\n    publisher <gen/Topic{b}> out_b;\n"
            f"    client <gen/Call{(s + 1) % (topics // 4)}> ask;\n"
            f"    subscriber <gen/Topic{b}> in_b\n    {{\n      priority = 50;\n"
            "      deadline = 0.05;\n    }\n"
            f"    subscriber <gen/Topic{(a + 3) % topics}> in_c\n    {{\n      priority = 40;\n"
            "      deadline = 0.1;\n    }\n"
            f"    server <gen/Call{s}> answer\n    {{\n      priority = 60;\n      deadline = 0.02;\n    }}\n"
            "    timer fast\n    {\n\tperiod = 0.01;\n\tpriority = 70;\n\tdeadline = 0.01;\n    }\n"
            "    timer slow\n    {\n\tperiod = 1.0;\n\tpriority = 30;\n\tdeadline = 0.5;\n    }\n  }\n"
        )
    rml.append("}\n")
    (sw / "generated.rml").write_text("".join(rml))
    hosts = max(1, nodes // 10)
    (project / "02-Hardware" / "cluster.rhw").write_text(
        "".join(
            f'hardware host_{h}\n{{\n  ip_address = "10.{h // 250}.{h % 250}.1";\n  username = "ros";\n'
            f'  sshkey = "~/.ssh/id_rsa";\n  deployment_path = "/home/ros";\n'
            f'  install_path = "/opt/ros/indigo";\n  arch = armv7l;\n}}\n'
            for h in range(hosts)
        )
    )
    rdp = ["using cluster;\n"]
    for c in range(nodes):
        rdp.append(
            f"// ROSMOD Node - node_{c}\nnode node_{c}\n{{\n  properties\n  {{\n"
            f'    ref = "cluster/host_{c % hosts}";\n    priority = 50;\n  }}\n'
            f"  component_instance comp_{c}_i\n  {{\n      properties\n      {{\n"
            f'\tref = "gen/comp_{c}";\n\tscheduling_scheme = FIFO;\n\tlogging\n\t{{\n'
            "\t  Is Periodic? = true;\n\t  Periodic Log Unit = 1000;\n\t}\n      }\n  }\n}\n"
        )
    (project / "03-Deployment" / "deployment.rdp").write_text("".join(rdp))
    return project


def _best(func: Callable[[], object], repeat: int) -> tuple[float, float, object]:
    """Best wall-clock and CPU seconds over ``repeat`` runs, and the last result."""
    wall = cpu = math.inf
    result = None
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        result = func()
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    return wall, cpu, result


def _parse_only(project: Path) -> int:
    count = 0
    for path in sorted(project.rglob("*")):
        if path.suffix in (".rml", ".rhw", ".rdp"):
            text = path.read_text()
            if not text.lstrip().startswith("{"):  # the v0.4 JSON file has no blocks to parse
                count += len(parse_blocks(text, str(path)))
    return count


def _row(
    label: str, parse: float | None, full: float, full_cpu: float, save: float | None, counts: dict[str, int]
) -> str:
    p = f"{parse * 1000:10.1f}" if parse is not None else f"{'-':>10}"
    s = f"{save * 1000:10.1f}" if save is not None else f"{'-':>10}"
    callbacks = counts["timers"] + counts["subscribers"] + counts["servers"]
    return (
        f"{label:46} {counts['nodes']:6d} {callbacks:9d} {p} {full * 1000:11.1f} {full_cpu * 1000:11.1f} {s}"
    )


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_rosmod_import", description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,5000", help="node counts of the generated projects")
    parser.add_argument("--repeat", type=int, default=3, help="best of this many runs (corpus rows)")
    args = parser.parse_args(argv)
    sizes = [int(s) for s in args.sizes.split(",") if s]
    logging.disable(logging.WARNING)  # the corpus has known, expected warnings
    header = (
        f"{'input':46} {'nodes':>6} {'callbacks':>9} {'parse ms':>10} {'import ms':>11} "
        f"{'import cpu':>11} {'save ms':>10}"
    )
    print(header)
    print("-" * len(header))
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        corpus = _corpus()
        if corpus.is_dir():
            for name in CORPUS_PROJECTS:
                path = corpus / name
                parse, _, _ = _best(lambda p=path: _parse_only(p), args.repeat)
                full, cpu, project = _best(lambda p=path: rosmod_text.read_project(p), args.repeat)
                save, _, _ = _best(lambda pr=project: model.save(pr, out / "p.xmi"), 1)
                print(_row(name, parse, full, cpu, save, rosmod_text.summarize(project)))
            for name in CORPUS_SEEDS:
                path = corpus / name
                full, cpu, projects = _best(lambda p=path: rosmod_webgme.read_webgmex(p), args.repeat)
                counts = dict.fromkeys(("nodes", "timers", "subscribers", "servers"), 0)
                for project in projects:
                    for key, value in rosmod_text.summarize(project).items():
                        if key in counts:
                            counts[key] += value
                label = f"{Path(name).stem} ({len(projects)} projects)"
                print(_row(label, None, full, cpu, None, counts))
        else:
            print(f"(corpus not found at {corpus}: corpus rows skipped)")
        timings: list[tuple[int, float]] = []
        for size in sizes:
            path = generate_project(out, size)
            parse, _, _ = _best(lambda p=path: _parse_only(p), 1)
            full, cpu, project = _best(lambda p=path: rosmod_text.read_project(p), 1)
            save, _, _ = _best(lambda pr=project, n=size: model.save(pr, out / f"g{n}.xmi"), 1)
            timings.append((size, cpu))
            print(_row(f"generated ({size} nodes)", parse, full, cpu, save, rosmod_text.summarize(project)))
    print()
    for (n1, t1), (n2, t2) in zip(timings, timings[1:], strict=False):
        exponent = math.log(t2 / t1) / math.log(n2 / n1)
        print(f"import CPU time growth {n1} -> {n2} nodes: x{t2 / t1:.1f} (exponent k = {exponent:.2f})")
    return 0


if __name__ == "__main__":
    import sys

    raise SystemExit(main(sys.argv[1:]))

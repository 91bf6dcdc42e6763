"""Throughput of the AADL concrete-syntax parser (``importers/aadl_syntax.py``).

Prints MB/s of ``parse`` on every ``.aadl``/``.aadl2`` file of the real-world corpus
(``$ROSAADL_CORPUS`` or ``../shared/corpus``) and on a generated package of 10 000 components,
plus the one-off cost of compiling the grammar with and without lark's on-disk table cache.

    python benchmarks/bench_aadl_syntax.py [--repeat N] [--components N]

Target: the whole AADL reader (parse + model building) must read >= 1 MB/s on a 2-core
machine, so ``parse`` alone should stay well above 2 MB/s.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import tempfile
import time
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parent.parent


def load_aadl_syntax() -> ModuleType:
    try:
        from rosaadl.importers import aadl_syntax
    except ImportError:  # not installed: load the module from the source tree
        sys.path.insert(0, str(ROOT))
        name = "_rosaadl_importers_aadl_syntax"
        spec = importlib.util.spec_from_file_location(name, ROOT / "importers" / "aadl_syntax.py")
        assert spec is not None and spec.loader is not None
        aadl_syntax = importlib.util.module_from_spec(spec)
        sys.modules[name] = aadl_syntax
        spec.loader.exec_module(aadl_syntax)
    return aadl_syntax


def corpus_texts() -> list[tuple[str, bytes]]:
    env = os.environ.get("ROSAADL_CORPUS")
    folder = Path(env) if env else ROOT.parent / "shared" / "corpus"
    if not folder.is_dir():
        return []
    files = sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in (".aadl", ".aadl2"))
    return [(str(p), p.read_bytes()) for p in files]


def generated_package(components: int = 10_000) -> str:
    """A package of ``components`` component types, each with an implementation.

    Threads with ports, flows and properties, grouped 100 to a process whose implementation
    has the thread subcomponents, connections and contained property associations, and one
    system holding the processes on a processor.
    """
    processes = max(1, components // 101)
    threads = components - processes - 1
    out = ["package Generated\npublic\n  with Base_Types, Timing_Properties;\n"]
    for i in range(threads):
        out.append(
            f"  thread T{i}\n    features\n"
            f"      input: in event data port Base_Types::Integer {{Queue_Size => 4;}};\n"
            f"      output: out data port Base_Types::Float;\n"
            f"    flows\n      f: flow path input -> output;\n"
            f"    properties\n      Dispatch_Protocol => Periodic;\n      Period => {10 + i % 90} ms;\n"
            f"  end T{i};\n\n"
            f"  thread implementation T{i}.impl\n    properties\n"
            f"      Compute_Execution_Time => 1 ms .. {2 + i % 7} ms;\n"
            f'      Source_Text => ("t{i}.c");\n'
            f"  end T{i}.impl;\n\n"
        )
    per_process = -(-threads // processes)
    for p in range(processes):
        members = range(p * per_process, min(threads, (p + 1) * per_process))
        out.append(f"  process P{p}\n  end P{p};\n\n  process implementation P{p}.impl\n    subcomponents\n")
        out.extend(f"      t{i}: thread T{i}.impl;\n" for i in members)
        out.append("    connections\n")
        out.extend(f"      c{i}: port t{i}.output -> t{i + 1}.input;\n" for i in list(members)[:-1])
        out.append("    properties\n")
        out.extend(f"      Priority => {i % 50} applies to t{i};\n" for i in members)
        out.append(f"  end P{p}.impl;\n\n")
    out.append(
        "  system S\n  end S;\n\n  system implementation S.impl\n    subcomponents\n      cpu: processor;\n"
    )
    out.extend(f"      p{p}: process P{p}.impl;\n" for p in range(processes))
    out.append("    properties\n")
    out.extend(
        f"      Actual_Processor_Binding => (reference (cpu)) applies to p{p};\n" for p in range(processes)
    )
    out.append("  end S.impl;\nend Generated;\n")
    return "".join(out)


def best_time(action, repeat: int) -> tuple[float, float]:
    """The best wall-clock and the best CPU time of ``repeat`` runs (CPU time is what counts
    on a shared machine, where other processes stretch the wall-clock time)."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        start, start_cpu = time.perf_counter(), time.process_time()
        action()
        wall = min(wall, time.perf_counter() - start)
        cpu = min(cpu, time.process_time() - start_cpu)
    return wall, cpu


def rate(size: int, wall: float, cpu: float) -> str:
    return f"{size / wall / 1e6:.2f} MB/s (CPU time: {size / cpu / 1e6:.2f} MB/s)"


def main(argv: list[str] | None = None) -> int:
    options = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    options.add_argument("--repeat", type=int, default=5, help="runs per measurement; the best is shown")
    options.add_argument("--components", type=int, default=10_000, help="size of the generated package")
    args = options.parse_args(argv)

    aadl_syntax = load_aadl_syntax()
    with tempfile.TemporaryDirectory() as cache:
        os.environ["ROSAADL_CACHE_DIR"] = ""
        aadl_syntax._reader.cache_clear()
        start = time.perf_counter()
        aadl_syntax._reader()
        compile_seconds = time.perf_counter() - start
        os.environ["ROSAADL_CACHE_DIR"] = cache
        aadl_syntax._reader.cache_clear()
        aadl_syntax._reader()  # writes the cache file
        aadl_syntax._reader.cache_clear()
        start = time.perf_counter()
        aadl_syntax._reader()
        cached_seconds = time.perf_counter() - start
    print(
        f"grammar: compiled in {compile_seconds:.2f} s, loaded from the table cache in {cached_seconds:.2f} s"
    )

    corpus = corpus_texts()
    if corpus:
        size = sum(len(data) for _, data in corpus)

        def parse_corpus() -> None:
            for name, data in corpus:
                aadl_syntax.parse(data, name)

        wall, cpu = best_time(parse_corpus, args.repeat)
        print(
            f"corpus: {len(corpus)} files, {size / 1e6:.2f} MB in {wall:.3f} s "
            f"-> {rate(size, wall, cpu)}, best of {args.repeat}"
        )
    else:
        print("corpus: not found (set ROSAADL_CORPUS); skipped")

    text = generated_package(args.components).encode("utf-8")
    wall, cpu = best_time(lambda: aadl_syntax.parse(text, "<generated>"), args.repeat)
    print(
        f"generated package: {args.components} components, {len(text) / 1e6:.2f} MB in {wall:.3f} s "
        f"-> {rate(len(text), wall, cpu)}, best of {args.repeat}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

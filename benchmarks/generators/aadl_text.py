"""AADL text generated at scale, for the reader, the parser and the ``.aadl`` -> ``.aaxl2`` path.

* :func:`aadl_package_text`: one package of N components, threads with ports, flows and
  properties in processes with connections and contained property associations
  (``bench_aadl_syntax``, ``bench_aadl_reader``).
"""

from __future__ import annotations

__all__ = ["aadl_package_text"]


def aadl_package_text(components: int = 10_000) -> str:
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

"""AADL text generated at scale, for the reader, the parser and the ``.aadl`` -> ``.aaxl2`` path.

* :func:`aadl_package_text`: one package of N components, threads with ports, flows and
  properties in processes with connections and contained property associations
  (``bench_aadl_syntax``, ``bench_aadl_reader``).
* :func:`instantiable_package_text`: a property set and a package whose system instantiates to
  N instance objects (``bench_aaxl2_export``).
* :func:`renamed_copies_text`: given AADL texts (the corpus's), copies of them under new unit
  names up to a size, as one file of many packages and property sets of real-world shape
  (``bench_aadl_reader``'s peak memory, the reader's memory-bound test).
"""

from __future__ import annotations

import re
from collections.abc import Iterable

__all__ = ["aadl_package_text", "instantiable_package_text", "renamed_copies_text"]

# the name of a package (``a::b``) or property set a text declares, at the start of a line
_UNIT_NAME = re.compile(
    r"^[ \t]*(?:package[ \t]+([A-Za-z]\w*(?:::[A-Za-z]\w*)*)|property[ \t]+set[ \t]+([A-Za-z]\w*)[ \t]+is)",
    re.MULTILINE | re.IGNORECASE,
)


def renamed_copies_text(texts: Iterable[str], size: int) -> str:
    """At least ``size`` characters of AADL: the ``texts`` (each a whole file, ending with its
    last unit) again and again, the names of the units each declares followed by ``R<copy>``
    wherever they occur in it (``Pkg`` -> ``PkgR3``, ``Pkg::T`` -> ``PkgR3::T``), so that every
    copy declares units of its own.  Texts declaring no unit are left out."""
    sources = []
    for text in texts:
        names = sorted({a or b for a, b in _UNIT_NAME.findall(text)}, key=len, reverse=True)
        if names:
            pattern = re.compile(r"(?<![\w:])(" + "|".join(map(re.escape, names)) + r")(?!\w)", re.IGNORECASE)
            sources.append((text, pattern))
    if not sources:
        raise ValueError("no text declares a package or property set")
    out: list[str] = []
    total = copy = 0
    while total < size:
        for text, pattern in sources:
            suffix = f"R{copy}"
            renamed = pattern.sub(lambda m, s=suffix: m.group(1) + s, text) + "\n"
            out.append(renamed)
            total += len(renamed)
            if total >= size:
                break
        copy += 1
    return "".join(out)


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


def instantiable_package_text(objects: int = 50_000, threads_per_process: int = 40) -> str:
    """AADL text (a property set and package ``gen``) whose instance of ``gen::top.impl`` has about
    ``objects`` instance objects and values.

    Processors, and processes of periodic threads with an in and an out port, chained by port
    connections, every thread with Period, Compute_Execution_Time, Dispatch_Protocol, a
    user-property-set enumeration and units, every process bound to a processor.
    """
    # per thread: the component, 2 features with their inherited values, 6 associations with
    # their values, a connection with its reference: about 50 objects (measured)
    per_process = threads_per_process * 50 + 34
    processes = max(1, -(-objects // per_process))  # at least ``objects``
    lines = [
        "property set gen_props is",
        "  Size_Units: type units (B, KB => B * 1000);",
        "  Level: enumeration (low, mid, high) applies to (all);",
        "  Budget: aadlinteger units gen_props::Size_Units applies to (all);",
        "end gen_props;",
        "",
        "package gen",
        "public",
        "  with gen_props;",
        "  data msg",
        "    properties",
        "      Data_Size => 16 Bytes;",
        "  end msg;",
        "  thread worker",
        "    features",
        "      inp: in event data port msg;",
        "      outp: out event data port msg;",
        "    properties",
        "      Dispatch_Protocol => Periodic;",
        "      Period => 20 ms;",
        "      Compute_Execution_Time => 1 ms .. 3 ms;",
        "      gen_props::Level => mid;",
        "      gen_props::Budget => 4 KB;",
        "  end worker;",
        "  thread implementation worker.impl",
        "  end worker.impl;",
        "  processor cpu",
        "  end cpu;",
        "  process app",
        "    features",
        "      inp: in event data port msg;",
        "      outp: out event data port msg;",
        "  end app;",
        "  process implementation app.impl",
        "    subcomponents",
    ]
    lines += [f"      t{i}: thread worker.impl;" for i in range(threads_per_process)]
    lines += ["    connections", "      cin: port inp -> t0.inp;"]
    lines += [f"      c{i}: port t{i}.outp -> t{i + 1}.inp;" for i in range(threads_per_process - 1)]
    lines += [f"      cout: port t{threads_per_process - 1}.outp -> outp;", "  end app.impl;"]
    lines += ["  system top", "  end top;", "  system implementation top.impl", "    subcomponents"]
    lines += [f"      p{i}: process app.impl;" for i in range(processes)]
    lines += [f"      cpu{i}: processor cpu;" for i in range(processes)]
    lines += ["    connections"]
    lines += [f"      x{i}: port p{i}.outp -> p{i + 1}.inp;" for i in range(processes - 1)]
    lines += ["    properties"]
    lines += [
        f"      Actual_Processor_Binding => (reference (cpu{i})) applies to p{i};" for i in range(processes)
    ]
    lines += ["  end top.impl;", "end gen;", ""]
    return "\n".join(lines)

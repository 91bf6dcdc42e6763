"""The latency analysis in the text report, its CSV table, and OSATE's latency CSV report.

``analyze --only latency -o DIR`` writes ``<instance>__Latency.csv`` (every contributor of
every flow and mode, in microseconds) and, per system kind, OSATE's own report
``<instance>__latency_<AS|SS>-MF-ET-EQ.csv`` laid out as ``LatencyCSVReport`` writes it (the
contributor rows with the buses and protocols under a connection first and in parentheses,
``Latency Total``, ``Specified End To End Latency``, the summary lines), in milliseconds as
Java prints them, so that it can be diffed with OSATE's.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from rosaadl.analysis.busload import java_double
from rosaadl.analysis.latency.model import LatencyChain, LatencyResult
from rosaadl.analysis.rendering import csv_text, fmt, table

__all__ = ["latency_text", "latency_csv", "osate_latency_csv"]


def latency_text(result: LatencyResult) -> list[str]:
    """The ``End-to-end latency`` section of the text report."""
    lines = ["End-to-end latency (us)", ""]
    rows = [[c.name, c.mode, c.best_us, c.worst_us, c.expected_us, c.met] for c in result.chains]
    lines += table(["chain", "mode", "best", "worst", "expected", "met"], rows)
    lines.append("")
    return lines


def latency_csv(result: LatencyResult, base: str) -> dict[str, str]:
    """``<base>__Latency.csv`` (every contributor of every chain and mode, then the chain's
    total) and OSATE's report per system kind."""
    rows: list[list[Any]] = [
        ["Chain", "Mode", "Element", "Kind", "Best (us)", "Worst (us)", "Method", "Note"]
    ]
    for chain in result.chains:
        for hop in chain.hops:
            method = (
                hop.worst_method
                if hop.best_method == hop.worst_method
                else f"{hop.best_method}/{hop.worst_method}"
            )
            rows.append(
                [chain.name, chain.mode, hop.path, hop.kind, hop.best_us, hop.worst_us, method, hop.note]
            )
        rows.append(
            [
                chain.name,
                chain.mode,
                "Total",
                "",
                chain.best_us,
                chain.worst_us,
                "",
                f"expected {fmt(chain.expected_us)}",
            ]
        )
    files = {f"{base}__Latency.csv": csv_text(rows)}
    for synchronous in (False, True):
        code = result.preferences.code(synchronous)
        files[f"{base}__latency_{code}.csv"] = osate_latency_csv(result, synchronous)
    return files


def _ms(value: Fraction | None) -> str:
    return java_double((value or Fraction(0)) / 1000) + "ms"


def _cell(text: str) -> str:
    return f'"{text}"' if "," in text or '"' in text else text


def osate_latency_csv(result: LatencyResult, synchronous: bool) -> str:
    """OSATE's latency CSV report of one system kind (``LatencyCSVReport.getReportContent``)."""
    mode = "sync" if synchronous else "async"
    out = [f"Latency analysis with preference settings: {result.preferences.description(synchronous)}", ""]
    for chain in result.chains:
        if chain.mode != mode:
            continue
        out += _section(chain, result.system)
    return "\n".join(out) + "\n"


def _section(chain: LatencyChain, system: str) -> list[str]:
    flow = chain.flow_path.partition(".")[2] or chain.name
    in_mode = chain.system_mode
    lines = [f"\"Latency results for end-to-end flow '{flow}' of system '{system}' {in_mode}\"", ""]
    lines.append("Result,Min Specified,Min Actual,Min Method,Max Specified,Max Actual,Max Method,Comments")
    for hop in chain.hops:
        label = f"({hop.label})" if hop.depth else hop.label
        cells = [
            label,
            _ms(hop.specified_best_us),
            _ms(hop.best_us),
            hop.best_method,
            _ms(hop.specified_worst_us),
            _ms(hop.worst_us),
            hop.worst_method,
        ]
        if hop.note:
            cells += hop.note.split("; ")
        lines.append(",".join(_cell(c) for c in cells))
    best, worst = Fraction(round(chain.best_us)), Fraction(round(chain.worst_us))  # OSATE rounds to the µs
    specified = _ms(chain.specified_best_us), _ms(chain.specified_worst_us)
    lines.append(f"Latency Total,{specified[0]},{_ms(best)},,{specified[1]},{_ms(worst)}")
    lines.append(f"Specified End To End Latency,,{_ms(chain.expected_best_us)},,,{_ms(chain.expected_us)}")
    lines.append("End to end Latency Summary")
    lines += [f"{severity},{_cell(message)}" for severity, message in chain.issues]
    lines += ["", "", ""]
    return lines

"""The analysis registry: a new analysis is one module and one registration.

A toy analysis registered here (as a plug-in module would register itself) is selected with
``analyze --only``, has its key in the JSON document, its section in the text report and its
CSV file, and runs beside the built-in ones on the real tracking example.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.analysis import (
    ANALYSES,
    DEFAULT_ANALYSES,
    Analysis,
    analyses,
    parse_only,
    registered,
    run_analyses,
)
from rosaadl.analysis.rendering import csv_text
from rosaadl.cli import main
from rosaadl.errors import Diagnostic, Location, UsageError

LIBRARY_SYSTEMS = Path(__file__).resolve().parents[2] / "library" / "systems"
ROOT = "sys_tracking::tracking.impl"


@dataclass(frozen=True)
class ThreadCount:
    """The toy result: how many thread instances the system has."""

    threads: int
    diagnostics: tuple[Diagnostic, ...] = ()

    @property
    def ok(self) -> bool:
        return self.threads > 0

    def as_dict(self) -> dict:
        return {"threads": self.threads}


def _count(context) -> ThreadCount:
    threads = [c for c in model.component_instances(context.root) if c.category.name == "thread"]
    note = Diagnostic("warning", f"{len(threads)} threads counted", Location(path=context.root.name))
    return ThreadCount(len(threads), (note,))


TOY = Analysis(
    name="threadcount",
    json_key="thread_count",
    order=65,
    run=_count,
    text=lambda result: ["Thread count", "", f"threads: {result.threads}", ""],
    csv=lambda result, base: {f"{base}__ThreadCount.csv": csv_text([["Threads"], [result.threads]])},
    default=False,
    aliases=("threads",),
)


def test_the_built_in_analyses_are_registered_in_report_order() -> None:
    assert tuple(a.name for a in analyses()) == ANALYSES
    assert tuple(a.name for a in analyses() if a.default) == DEFAULT_ANALYSES
    assert {a.json_key for a in analyses()} == {
        "cpu",
        "budget",
        "bus",
        "schedulability",
        "simulation",
        "latency",
        "executor",
        "deployment",
        "compare",
    }


def test_a_registered_analysis_is_selected_by_name_or_alias_and_only_while_registered() -> None:
    with registered(TOY):
        assert parse_only("threads,cpu") == ("cpu", "threadcount")
        assert "threadcount" not in parse_only(None)  # not a default one
    with pytest.raises(UsageError, match="unknown analysis threadcount"):
        parse_only("threadcount")


def test_a_name_already_taken_is_refused() -> None:
    clash = Analysis(name="budgets", json_key="x", order=1, run=_count, text=TOY.text, aliases=("cpu",))
    with pytest.raises(UsageError, match="analysis name cpu is taken"), registered(clash):
        pass
    assert "budgets" not in {a.name for a in analyses()}


def test_run_analyses_runs_a_registered_analysis_beside_the_built_in_ones() -> None:
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    system = instantiate(read_files([LIBRARY_SYSTEMS]), ROOT)
    with registered(TOY):
        report = run_analyses(system, "cpu,threads")
    assert [name for name, _ in report.results()] == ["cpu", "threadcount"]
    count = report.result("threads")
    assert (
        count.threads == sum(1 for c in model.component_instances(system) if c.category.name == "thread") > 0
    )
    document = report.as_dict()
    assert list(document["analyses"]) == ["cpu", "thread_count"]
    assert document["analyses"]["thread_count"] == {"threads": count.threads}
    assert f"warning: {count.threads} threads counted" in report.text()  # its findings join the report
    assert f"threads: {count.threads}" in report.text()
    assert report.csv_files()[f"{system.name}__ThreadCount.csv"] == f"Threads\n{count.threads}\n"


def test_the_cli_selects_the_registered_analysis_and_writes_its_json_and_csv(tmp_path, capsys) -> None:
    out = tmp_path / "csv"
    args = ["analyze", str(LIBRARY_SYSTEMS), "--root", ROOT, "--only", "threadcount", "-o", str(out)]
    with registered(TOY):
        code = main(["--format", "json", *args])
        document = json.loads(capsys.readouterr().out)
        help_text = _help(capsys)
    assert code == 0
    assert list(document["analyses"]) == ["thread_count"]
    assert document["analyses"]["thread_count"]["threads"] > 0
    assert any("threads counted" in w["message"] for w in document["warnings"])
    (written,) = out.iterdir()
    assert written.name.endswith("__ThreadCount.csv")
    assert written.read_text().splitlines() == [
        "Threads",
        str(document["analyses"]["thread_count"]["threads"]),
    ]
    assert "threadcount" in help_text
    # the text report has its section
    with registered(TOY):
        assert main(args[:-2]) == 0
    assert "Thread count" in capsys.readouterr().out
    # once unregistered, it is unknown again: a usage error
    assert main(args) == 2
    assert "unknown analysis threadcount" in capsys.readouterr().err


def _help(capsys) -> str:
    assert main(["analyze", "--help"]) == 0
    return " ".join(capsys.readouterr().out.split())

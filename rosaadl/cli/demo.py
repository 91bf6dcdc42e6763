"""``rosaadl demo [-o OUT]``: the paper's workflow end to end on the bundled tracking example.

1. read the ROSMOD project (``examples/tracking``);
2. convert it to AADL (``OUT/aadl/*.aadl``), read back and instantiated;
3. bind each deployment to a robot of the component library as the project's ``bindings.json``
   says (``OUT/aadl/<deployment>_bound.aadl``, :mod:`rosaadl.workflow.binding`);
4. instantiate the bound deployments (read back from the written files, with the library);
5. run every analysis on each (``OUT/<deployment>/analysis/*.csv`` and ``analyses.json``);
6. for a deployment whose binding fails (a core over 100 %, not schedulable, deadlines missed),
   search the cores of its robot for a better binding, write it as AADL
   (``OUT/aadl/<deployment>_proposed.aadl``), instantiate and analyse it like the others;
7. export each deployment to OSATE (``OUT/<deployment>/osate/instances/*.aaxl2`` and the
   ``.aadl`` files it refers to) and to Cheddar (``OUT/<deployment>/<deployment>.xmlv3``);
8. generate the ROS 2 workspace (``OUT/ros2_ws/src``) of the proposed binding (else of the first
   deployment that passes, else of the first one);
9. write the reports: ``OUT/<deployment>/report.html`` and ``report.json`` for every deployment,
   and ``OUT/report.html`` / ``OUT/report.json`` for the first overloaded deployment with the
   proposed binding (the finding and its remedy on one page), or the first deployment when none
   is overloaded.

Progress goes to stderr, one line per stage; the summary to stdout (``--format json``: one JSON
document). Finding an overload is the expected result, not a failure: the exit code is 0 when
every stage ran, 1 when a stage failed (with the located error), 2 for a missing or wrong
``--project``/``--bindings``/``-o``. A stage whose exporter is not part of this installation is
reported as pending, never faked.
"""

from __future__ import annotations

import importlib
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import click

from rosaadl.cli.common import EXIT_ERRORS, EXIT_OK, Options, Report, pass_options
from rosaadl.errors import Diagnostic, Location, RosaadlError, UsageError
from rosaadl.fileio import existing

__all__ = ["command", "run_demo", "DemoRun", "STAGES", "BINDINGS_FILE", "example_project"]

#: The stages, in order: (key, what it does).
STAGES = (
    ("read", "read the ROSMOD project"),
    ("convert", "convert it to AADL"),
    ("bind", "bind the deployments to robots of the library"),
    ("instantiate", "instantiate the bound deployments"),
    ("analyse", "run every analysis"),
    ("search", "search a better binding for failing deployments"),
    ("aaxl2", "export OSATE .aaxl2"),
    ("cheddar", "export Cheddar XML"),
    ("rclpy", "generate the ROS 2 workspace"),
    ("report", "write the reports"),
)
#: The bindings file of a project, beside its ``.rosmod`` marker.
BINDINGS_FILE = "bindings.json"


def example_project() -> Path:
    """The bundled example: the tracking application as a ROSMOD project."""
    return Path(str(resources.files("rosaadl.examples") / "tracking"))


def _percent(value: float) -> str:
    return f"{value:.0f} %" if abs(value - round(value)) < 0.05 else f"{value:.1f} %"


@dataclass
class _Deployment:
    """One deployment through the stages (a bound one, or a proposal)."""

    name: str
    bound: Any  # BoundDeployment
    aadl: Path
    folder: Path
    instance: Any = None
    report: Any = None  # AnalysisReport (with the search result for a failing deployment)
    proposal: Any = None  # Proposal, for a failing deployment
    proposed_from: str | None = None
    verdict: dict[str, Any] = field(default_factory=dict)


@dataclass
class DemoRun:
    """What a demo run did: per stage its time and outcome, the artefacts, the verdicts."""

    project: Path
    out: Path
    stages: list[dict[str, Any]] = field(default_factory=list)
    artefacts: list[Path] = field(default_factory=list)
    deployments: list[_Deployment] = field(default_factory=list)
    pending: list[str] = field(default_factory=list)
    failures: list[RosaadlError | Diagnostic] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)
    workspace_from: str | None = None
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return not self.failures

    def as_dict(self) -> dict[str, Any]:
        return {
            "project": str(self.project),
            "output": str(self.out),
            "seconds": round(self.seconds, 3),
            "stages": self.stages,
            "deployments": {d.name: d.verdict for d in self.deployments},
            "workspace_from": self.workspace_from,
            "artefacts": [str(p) for p in self.artefacts],
            "pending": self.pending,
            "summary": self.summary,
        }


class _StageFailed(Exception):
    """A stage the later ones depend on failed (its error is in ``DemoRun.failures``)."""


def _verdict(name: str, report: Any, root: str) -> dict[str, Any]:
    """What the analyses say of a binding: the core loads, schedulability, deadline misses, and the
    MIPS budgets exceeded (a property of the library nodes, not of the binding)."""
    data = report.as_dict()["analyses"]
    prefix = f"{root}.robot."
    cores = []
    for row in data.get("cpu", {}).get("processors", []):
        if row.get("load_percent") is None:
            continue
        cores.append({"core": row["path"].removeprefix(prefix), "load_percent": float(row["load_percent"])})
    loaded = [c for c in cores if c["load_percent"] > 0]
    top = max(loaded, key=lambda c: c["load_percent"]) if loaded else None
    overloaded = [c for c in cores if c["load_percent"] > 100]
    unschedulable = []
    if report.schedulability is not None:
        for dom in report.schedulability.domains:
            if dom.schedulable is False:
                unschedulable.append((dom.path + (f".{dom.core}" if dom.core else "")).removeprefix(prefix))
    misses = sum(s.deadline_misses for s in report.simulation.tasks) if report.simulation is not None else 0
    budgets = []
    if report.budget is not None:
        budgets = [
            f"{(d.location.path or '').removeprefix(root + '.')} {d.message}"
            for d in report.budget.diagnostics
            if d.severity == "error"
        ]
    failed = [d.message for d in report.failures]
    return {
        "deployment": name,
        "max_core": top,
        "overloaded": overloaded,
        "unschedulable": unschedulable,
        "deadline_misses": misses,
        "binding_passes": not overloaded and not unschedulable and not misses and not failed,
        "budgets_exceeded": budgets,
        "analysis_failures": failed,
        "all_analyses_pass": bool(report.ok),
    }


def _describe(d: _Deployment, by_name: dict[str, _Deployment]) -> list[str]:
    """The summary lines of a deployment (and of the binding proposed for it)."""
    v = d.verdict
    kinds = {c.path: c.kind for c in d.bound.cores}
    if v["overloaded"]:
        worst = max(v["overloaded"], key=lambda c: c["load_percent"])
        kind = f" ({kinds[worst['core']]})" if worst["core"] in kinds else ""
        at = _percent(worst["load_percent"])
        text = f"{d.name}: core {worst['core'].rpartition('.')[2]}{kind} at {at} — overloaded"
        extra = ["not schedulable"] if v["unschedulable"] else []
        if v["deadline_misses"]:
            extra.append(f"{v['deadline_misses']} deadline misses in simulation")
        if extra:
            text += f" ({', '.join(extra)})"
    elif not v["binding_passes"]:
        reasons = [f"not schedulable on {', '.join(v['unschedulable'])}"] if v["unschedulable"] else []
        if v["deadline_misses"]:
            reasons.append(f"{v['deadline_misses']} deadline misses in simulation")
        reasons += v["analysis_failures"]
        text = f"{d.name}: binding fails ({'; '.join(reasons)})"
    else:
        top = v["max_core"]
        where = f"{top['core'].rpartition('.')[2]} at {_percent(top['load_percent'])}" if top else "no load"
        text = f"{d.name}: binding passes (max core {where})"
    proposed = next((p for p in by_name.values() if p.proposed_from == d.name), None)
    if proposed is not None:
        top = proposed.verdict["max_core"]
        load = f" (max core {_percent(top['load_percent'])})" if top else ""
        passes = proposed.verdict["binding_passes"]
        text += f"; proposed binding passes{load}" if passes else f"; the proposed binding fails too{load}"
    elif d.proposal is not None:
        best = _percent(float(d.proposal.search.max_load * 100))
        text += f"; no binding on the robot's cores passes (best effort: max core {best})"
    lines = [text]
    if proposed is not None and d.proposal is not None:
        order = [n.process for n in d.bound.nodes]
        placed = sorted(d.proposal.cores.items(), key=lambda item: order.index(item[0]))
        lines.append(
            f"  proposed ({proposed.name}): " + ", ".join(f"{p} on {c.rpartition('.')[2]}" for p, c in placed)
        )
    for item in [d] + ([proposed] if proposed is not None else []):
        lines.extend(
            f"  budget finding on {item.name}: {budget}" for budget in item.verdict["budgets_exceeded"]
        )
    return lines


def run_demo(
    project_dir: Path,
    out: Path,
    *,
    bindings: Path | None = None,
    progress: Callable[[str], None] = lambda _line: None,
    debug: bool = False,
) -> DemoRun:
    """Run every stage (see the module documentation); never raises for a stage's failure: it is
    recorded in ``DemoRun.failures`` (the stages that depend on it do not run)."""
    run = DemoRun(project=project_dir, out=out)
    started = time.perf_counter()
    state: dict[str, Any] = {}
    total = len(STAGES)

    def stage(index: int, key: str, body: Callable[[], str], *, needed: bool) -> None:
        title = dict(STAGES)[key]
        begin = time.perf_counter()
        try:
            detail = body()
            status = "pending" if detail.startswith("pending") else "ok"
        except RosaadlError as exc:
            run.failures.append(exc)
            status, detail = "failed", "failed (the error is below)"
        except Exception as exc:  # noqa: BLE001 - a crashing stage is reported, located by its name
            if debug:
                raise
            run.failures.append(Diagnostic("error", f"stage {key!r} crashed: {type(exc).__name__}: {exc}"))
            status, detail = "failed", "crashed (the error is below)"
        seconds = time.perf_counter() - begin
        run.stages.append({"stage": key, "status": status, "seconds": round(seconds, 3), "detail": detail})
        progress(f"[{index}/{total}] {title}: {detail} ({seconds:.1f} s)")
        if status == "failed" and needed:
            raise _StageFailed(key)

    try:
        stage(1, "read", lambda: _read(run, state), needed=True)
        stage(2, "convert", lambda: _convert(run, state), needed=True)
        stage(3, "bind", lambda: _bind(run, state, bindings), needed=True)
        stage(4, "instantiate", lambda: _instantiate(run, state), needed=True)
        stage(5, "analyse", lambda: _analyse(run, state), needed=True)
        stage(6, "search", lambda: _search(run, state), needed=True)
        stage(7, "aaxl2", lambda: _aaxl2(run, state), needed=False)
        stage(8, "cheddar", lambda: _cheddar(run, state), needed=False)
        stage(9, "rclpy", lambda: _rclpy(run, state), needed=False)
        stage(10, "report", lambda: _reports(run, state), needed=False)
    except _StageFailed:
        pass
    run.seconds = time.perf_counter() - started
    by_name = {d.name: d for d in run.deployments}
    for d in run.deployments:
        if d.verdict and d.proposed_from is None:
            run.summary.extend(_describe(d, by_name))
    return run


# ------------------------------------------------------------------------------- the stages


def _rel(run: DemoRun, path: Path) -> str:
    try:  # artefacts may be recorded resolved while the output folder was given relative
        return str(path.resolve().relative_to(run.out.resolve()))
    except ValueError:
        return str(path)


def _read(run: DemoRun, state: dict[str, Any]) -> str:
    from rosaadl.importers.rosmod_text import read_project, summarize

    warnings: list[Diagnostic] = []
    project = read_project(run.project, warnings=warnings)
    run.warnings.extend(warnings)
    state["project"] = project
    counts = summarize(project)
    return (
        f"{project.name}: {counts['components']} components, {counts['nodes']} nodes in "
        f"{counts['deployments']} deployments"
    )


def _convert(run: DemoRun, state: dict[str, Any]) -> str:
    from rosaadl.exporters.aadl_text import write_model
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate
    from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl
    from rosaadl.workflow.workspace import library_unit_names

    result = rosmod_to_aadl(state["project"], reserved_units=library_unit_names())
    run.warnings.extend(w.as_diagnostic() for w in result.warnings)
    written = write_model(result.model, run.out / "aadl")
    run.artefacts.extend(written)
    state["converted_units"] = {u.name.lower() for u in result.model.units}
    model = read_files(written)
    for root in result.roots.values():
        instantiate(model, root, diagnostics=[])
    return (
        f"{len(written)} AADL packages in {_rel(run, run.out / 'aadl')}, read back; "
        f"{len(result.roots)} generic deployments instantiate"
    )


def _bind(run: DemoRun, state: dict[str, Any], bindings: Path | None) -> str:
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.bind import bind_deployment
    from rosaadl.transforms.rosmod_to_aadl import aadl_identifier
    from rosaadl.workflow.binding import read_bindings, write_bound

    spec_file = read_bindings(bindings if bindings is not None else run.project / BINDINGS_FILE)
    library = read_files([], include_library=True)
    state["library"] = library
    taken = set(state["converted_units"])
    parts = []
    for name, spec in spec_file.deployments.items():
        package = f"{aadl_identifier(name)}_bound"
        while package.lower() in taken:
            package += "_1"
        taken.add(package.lower())
        bound = bind_deployment(state["project"], spec, library, package_name=package)
        run.warnings.extend(bound.warnings)
        path = write_bound(bound, run.out / "aadl")
        run.artefacts.append(path)
        folder = run.out / aadl_identifier(name)
        run.deployments.append(_Deployment(name, bound, path, folder))
        parts.append(f"{name} → {bound.robot} ({_rel(run, path)})")
    state["taken"] = taken
    for deployment in state["project"].deployments:
        if deployment.name not in spec_file.deployments:
            run.warnings.append(
                Diagnostic(
                    "warning",
                    f"deployment {deployment.name!r} has no entry in the bindings file: not bound",
                    Location(file=spec_file.file),
                )
            )
            parts.append(f"{deployment.name} not bound (no entry)")
    return "; ".join(parts)


def _instantiate(run: DemoRun, state: dict[str, Any]) -> str:
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    model = read_files([d.aadl for d in run.deployments])
    parts = []
    for d in run.deployments:
        diagnostics: list[Diagnostic] = []
        d.instance = instantiate(model, d.bound.root, diagnostics=diagnostics)
        run.warnings.extend(x for x in diagnostics if x.severity != "info")
        parts.append(f"{d.name} ({d.bound.root})")
    return ", ".join(parts)


def _analyse_one(run: DemoRun, d: _Deployment) -> None:
    from rosaadl.analysis.report import run_analyses

    d.report = run_analyses(d.instance)
    d.verdict = _verdict(d.name, d.report, d.instance.name or "")


def _write_analysis(run: DemoRun, d: _Deployment) -> None:
    from rosaadl.fileio import atomic_write_text

    folder = d.folder / "analysis"
    run.artefacts.extend(d.report.write_csv(folder))
    target = folder / "analyses.json"
    atomic_write_text(target, d.report.to_json() + "\n")
    run.artefacts.append(target)


def _analyse(run: DemoRun, state: dict[str, Any]) -> str:
    parts = []
    for d in run.deployments:
        _analyse_one(run, d)
        top = d.verdict["max_core"]
        load = f"max core {_percent(top['load_percent'])}" if top else "no core load"
        status = "binding passes" if d.verdict["binding_passes"] else "binding FAILS"
        parts.append(f"{d.name} {load}, {status}")
    return "; ".join(parts)


def _search(run: DemoRun, state: dict[str, Any]) -> str:
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate
    from rosaadl.transforms.rosmod_to_aadl import aadl_identifier
    from rosaadl.workflow.binding import propose_binding, write_bound

    failing = [d for d in run.deployments if not d.verdict["binding_passes"]]
    taken = state["taken"]
    parts = []
    for d in failing:
        name = f"{aadl_identifier(d.name)}_proposed"
        while name.lower() in taken:
            name += "_1"
        taken.add(name.lower())
        proposal = propose_binding(state["project"], d.bound, d.instance, package_name=name)
        d.proposal = proposal
        d.report = d.report.with_result("deploy", proposal.search)
        if proposal.bound is None:
            best = _percent(float(proposal.search.max_load * 100))
            parts.append(f"{d.name}: no binding passes (best max core {best})")
            continue
        path = write_bound(proposal.bound, run.out / "aadl")
        run.artefacts.append(path)
        proposed = _Deployment(name, proposal.bound, path, run.out / name, proposed_from=d.name)
        model = read_files([path])
        proposed.instance = instantiate(model, proposal.bound.root, diagnostics=[])
        _analyse_one(run, proposed)
        run.deployments.append(proposed)
        verdict = "passes" if proposed.verdict["binding_passes"] else "FAILS"
        parts.append(
            f"{d.name} → {_rel(run, path)} ({proposal.search.method}"
            f"{' optimal' if proposal.search.optimal else ''}, "
            f"max core {_percent(float(proposal.search.max_load * 100))}), analysed: {verdict}"
        )
    for d in run.deployments:
        _write_analysis(run, d)
    return "; ".join(parts) if parts else "every binding passes: nothing to search"


def _optional(module: str, function: str) -> Callable[..., Any] | None:
    """An exporter's entry point, or None when this installation does not have it."""
    try:
        found = importlib.import_module(module)
    except ImportError:
        return None
    entry = getattr(found, function, None)
    return entry if callable(entry) else None


def _aaxl2(run: DemoRun, state: dict[str, Any]) -> str:
    write_aaxl2 = _optional("rosaadl.exporters.aaxl2", "write_aaxl2")
    if write_aaxl2 is None:
        run.pending.append("export OSATE .aaxl2 (rosaadl.exporters.aaxl2.write_aaxl2 is not available)")
        return "pending: the .aaxl2 exporter is not available"
    parts = []
    for d in run.deployments:
        path = write_aaxl2(d.instance, d.folder / "osate")
        run.artefacts.append(Path(path))
        parts.append(_rel(run, Path(path)))
    return ", ".join(parts)


def _cheddar(run: DemoRun, state: dict[str, Any]) -> str:
    from rosaadl.exporters.cheddar import write_cheddar

    parts = []
    for d in run.deployments:
        diagnostics: list[Diagnostic] = []
        path = write_cheddar(d.instance, d.folder / f"{d.folder.name}.xmlv3", diagnostics=diagnostics)
        run.artefacts.append(path)
        parts.append(_rel(run, path))
    return ", ".join(parts)


def _rclpy(run: DemoRun, state: dict[str, Any]) -> str:
    generate = _optional("rosaadl.exporters.rclpy", "generate_workspace")
    options_class = _optional("rosaadl.exporters.rclpy", "GenerationOptions")
    if generate is None or options_class is None:
        run.pending.append("generate the ROS 2 workspace (rosaadl.exporters.rclpy is not available)")
        return "pending: the rclpy generator is not available"
    chosen = next((d for d in run.deployments if d.proposed_from and d.verdict["binding_passes"]), None)
    chosen = chosen or next((d for d in run.deployments if d.verdict["binding_passes"]), None)
    chosen = chosen or run.deployments[0]
    target = run.out / "ros2_ws" / "src"
    result = generate(
        chosen.instance, target, options=options_class(app_name=state["project"].name or None), force=True
    )
    run.workspace_from = chosen.name
    run.warnings.extend(x for x in result.diagnostics if x.severity != "info")
    files = sorted(p for p in target.rglob("*") if p.is_file())
    run.artefacts.extend(files)
    return f"{len(files)} files in {_rel(run, target)} from {chosen.name}"


def _reports(run: DemoRun, state: dict[str, Any]) -> str:
    from rosaadl.exporters.report import write_report

    project = state["project"].name
    for d in run.deployments:
        origin = f" (proposed for {d.proposed_from})" if d.proposed_from else ""
        title = f"{project} deployed on {d.bound.robot}: {d.name}{origin}"
        run.artefacts.extend(write_report(d.instance, d.report, d.folder, title=title))
    headline = next((d for d in run.deployments if d.verdict["overloaded"]), run.deployments[0])
    title = f"{project} deployed on {headline.bound.robot}: {headline.name}"
    if headline.proposal is not None:
        title += ", with the proposed binding"
    run.artefacts.extend(write_report(headline.instance, headline.report, run.out, title=title))
    return f"{_rel(run, run.out / 'report.html')} ({headline.name}) and one per deployment"


# ------------------------------------------------------------------------------- the command


@click.command("demo")
@click.option(
    "-o",
    "--output",
    "out",
    type=click.Path(path_type=Path),
    default=Path("demo-out"),
    show_default=True,
    help="Folder for everything the demo writes.",
)
@click.option(
    "--project",
    "project_dir",
    type=click.Path(path_type=Path),
    default=None,
    help="A ROSMOD project folder to run on instead of the bundled tracking example.",
)
@click.option(
    "--bindings",
    type=click.Path(path_type=Path),
    default=None,
    help=f"The bindings file (default: {BINDINGS_FILE} in the project folder).",
)
@pass_options
def command(options: Options, out: Path, project_dir: Path | None, bindings: Path | None) -> None:
    """Run the whole workflow on the bundled tracking example: ROSMOD → AADL, binding to the
    library's robots, analyses, deployment search, OSATE and Cheddar export, ROS 2 code, report."""
    from rosaadl.importers.rosmod_text import is_rosmod_project

    project = project_dir if project_dir is not None else example_project()
    if not existing(project):
        raise UsageError(f"no ROSMOD project folder at {project}")
    if not project.is_dir() or not is_rosmod_project(project):
        raise UsageError(
            f"{project} is not a ROSMOD project folder (no .rosmod marker, no 01-Software folder)"
        )
    bindings_file = bindings if bindings is not None else project / BINDINGS_FILE
    if not bindings_file.is_file():
        raise UsageError(f"no bindings file at {bindings_file} (give one with --bindings)")
    if existing(out) and not out.is_dir():
        raise UsageError(f"the output {out} is a file, not a folder")
    run = run_demo(project, out, bindings=bindings_file, progress=options.progress, debug=options.debug)
    report = Report()
    for failure in run.failures:
        report.error(failure)
    if options.verbosity > 0:
        for warning in run.warnings:
            report.warn(warning)
    report.say(
        f"rosaadl demo: {run.project.name} ({run.project}) in {run.seconds:.1f} s, written to {run.out}"
    )
    for line in run.summary:
        report.say(f"  {line}")
    folders: dict[str, int] = {}  # what each top-level entry of the output holds on disk
    for entry in sorted(run.out.iterdir()) if run.out.is_dir() else []:
        folders[entry.name] = sum(1 for f in entry.rglob("*") if f.is_file()) if entry.is_dir() else 1
    report.say(
        "  produced: "
        + ", ".join(f"{k} ({n} file{'s' if n != 1 else ''})" for k, n in sorted(folders.items()))
    )
    if run.workspace_from:
        report.say(f"  ROS 2 workspace generated from {run.workspace_from}")
    for item in run.pending:
        report.say(f"  pending: {item}")
    if run.failures:
        failed = [s["stage"] for s in run.stages if s["status"] == "failed"]
        report.say(f"  failed stages: {', '.join(failed)}")
    report.data.update(run.as_dict())
    code = report.emit(options)
    sys.exit(EXIT_OK if run.ok and code == EXIT_OK else EXIT_ERRORS)

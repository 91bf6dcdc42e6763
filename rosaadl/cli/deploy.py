"""``rosaadl deploy INPUTS... --root Pkg::Sys.impl``: the best binding of processes (or threads) to
cores by a constraint solver, written as ``<package>_proposed.aadl``; exit 1 with the reason when
no binding passes."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import (
    EXIT_ERRORS,
    EXIT_OK,
    Options,
    Report,
    inputs_argument,
    lenient_option,
    output_option,
    pass_options,
    root_option,
)
from rosaadl.cli.inputs import choose_instance, read_aadl_inputs
from rosaadl.errors import Diagnostic, Location, UsageError

__all__ = ["command"]


@click.command("deploy")
@inputs_argument
@root_option("The root system implementation (Pkg::Sys.impl).", required=True)
@output_option("Folder for <package>_proposed.aadl (default: the folder of the first input).", required=False)
@click.option(
    "--time-limit",
    type=float,
    default=10.0,
    show_default=True,
    help="Seconds the solver may take in all (wall clock; CP-SAT's deterministic time with --deterministic).",
)
@click.option(
    "--keep", type=int, default=1, show_default=True, help="The N best distinct bindings to report."
)
@click.option(
    "--granularity",
    type=click.Choice(["process", "thread"]),
    default="process",
    show_default=True,
    help="Bind whole processes, or each thread on its own.",
)
@click.option(
    "--deterministic",
    is_flag=True,
    help="Limit the solver by its deterministic time: the same binding on any machine and load.",
)
@lenient_option()
@pass_options
def command(
    options: Options,
    inputs: tuple[Path, ...],
    root: str,
    out: Path | None,
    time_limit: float,
    keep: int,
    granularity: str,
    deterministic: bool,
    lenient: bool,
) -> None:
    """Find the best deployment: each core at most 100 % loaded and schedulable, memory and bus
    within capacity, Allowed_Processor_Binding honoured; then, in this order, the least highest
    core load, the least bus load and the fewest moves from the current binding."""
    from rosaadl.workflow.deploy import deploy_instance

    if time_limit <= 0:
        raise UsageError("--time-limit must be a positive number of seconds")
    if keep < 1:
        raise UsageError("--keep must be at least 1")
    report = Report()
    loaded = read_aadl_inputs(list(inputs), lenient=lenient)
    instance = choose_instance(loaded, root, lenient=lenient)
    report.note(loaded.warnings)
    folder = out if out is not None else (inputs[0] if inputs[0].is_dir() else inputs[0].parent)
    options.progress(f"solving the deployment of {instance.name} (at most {time_limit:g} s)")
    run = deploy_instance(
        instance,
        folder,
        time_limit=time_limit,
        keep=keep,
        granularity=granularity,
        deterministic=deterministic,
    )
    proposal = run.proposal
    # what the problem could not read (a thread without Period, a MIPS demand without capacity)
    # counts as no load: said as warnings beside the proposal, which stands
    report.note(
        Diagnostic("warning", d.message, d.location) if d.severity == "error" else d
        for d in proposal.problem.diagnostics
    )
    for line in proposal.text():
        report.say(line)
    if run.output is not None:
        report.say(f"proposed binding: {run.root} in {run.output}")
    else:
        for reason in proposal.explanation:
            report.error(Diagnostic("error", reason.message, Location(path=reason.path)))
        if not proposal.explanation:
            report.error(
                Diagnostic(
                    "error",
                    f"no binding found within {time_limit:g} s (raise --time-limit)",
                    Location(path=instance.name),
                )
            )
    report.data.update(run.as_dict())
    report.data["ok"] = report.ok
    code = report.emit(options)
    sys.exit(EXIT_OK if code == EXIT_OK and run.output is not None else EXIT_ERRORS)

"""``rosaadl run WORKSPACE_OR_MODEL [--root R] --duration S [--emulate] [-o RUN_DIR]``: the
generated ROS 2 application, built and run for S seconds, compared with its model.

Given a model (AADL text, a model file, or a ROSMOD project converted on the way), the workspace
is generated into ``RUN_DIR/src`` (as ``generate rclpy`` writes it: user code is kept across
runs) with its run plan; given a run folder made that way, its packages (with the user code
written since) are run again. See :mod:`rosaadl.workflow.run`.

Progress goes to stderr; stdout has a line per node and per topic (``--format json``: ``{"ok",
"nodes", "topics", "errors", "warnings", ...}``). Exit 0 when every node started and exited 0 when
stopped (and, with ``--emulate``, every topic published on in the model carried messages), 1
otherwise or when the workspace cannot be built, 2 for wrong arguments, 130 on Ctrl-C (after the
nodes are stopped).
"""

from __future__ import annotations

import sys
from pathlib import Path

import click

from rosaadl.cli.common import Options, Report, inputs_argument, lenient_option, pass_options, root_option
from rosaadl.cli.inputs import choose_instance, read_generator_inputs
from rosaadl.errors import UsageError

__all__ = ["command", "DEFAULT_RUN_DIR"]

#: The run folder when ``-o`` is not given (for a model).
DEFAULT_RUN_DIR = Path("rosaadl-run")


def _rate(value: float | None) -> str:
    return "-" if value is None else f"{value:g} Hz"


@click.command("run")
@inputs_argument
@root_option("The system implementation to run (or the instance to take).")
@click.option(
    "--duration",
    type=click.FloatRange(min=1.0, max=86400.0),
    required=True,
    help="Seconds the nodes run before they are stopped.",
)
@click.option(
    "--emulate",
    is_flag=True,
    help="Run the workload twin: each dispatch burns its Compute_Execution_Time and publishes Data_Size.",
)
@click.option(
    "-o",
    "--output",
    "out",
    type=click.Path(path_type=Path),
    help=f"The run folder (src, build, install, logs) [default: {DEFAULT_RUN_DIR}].",
)
@click.option(
    "--measure",
    is_flag=True,
    help="Trace every dispatch and message and write RUN_DIR/measurements.json (see docs/measurements.md).",
)
@click.option(
    "--warm-up",
    "warm_up",
    type=click.FloatRange(min=0.0, max=3600.0),
    default=2.0,
    show_default=True,
    metavar="S",
    help="With --measure: seconds the nodes run once all are up before the measured window (start-up and "
    "discovery left out); the nodes then run --duration seconds more.",
)
@click.option(
    "--period-scale",
    default="1",
    show_default=True,
    metavar="F|auto",
    help="Multiply every period of the nodes by F (execution times unchanged), for a machine with fewer "
    "cores than the model's; auto: the smallest F that keeps every CPU here at most 60 % loaded by the "
    "model's work. Recorded in measurements.json; analyze --compare compares against the scaled model.",
)
@click.option("--no-realtime", is_flag=True, help="Do not apply the model's real-time priorities (chrt).")
@click.option("--no-build", is_flag=True, help="Run the run folder's install as it is (no colcon build).")
@click.option("--app-name", help="Name of the application's packages (default: the root type's name).")
@click.option("--project", help="The project to take from a .webgmex archive.")
@lenient_option()
@pass_options
def command(
    options: Options,
    inputs: tuple[Path, ...],
    root: str | None,
    duration: float,
    emulate: bool,
    measure: bool,
    warm_up: float,
    period_scale: str,
    out: Path | None,
    no_realtime: bool,
    no_build: bool,
    app_name: str | None,
    project: str | None,
    lenient: bool,
) -> None:
    """Build and run the generated ROS 2 nodes for S seconds; report what each topic carried."""
    from rosaadl.workflow.run import PLAN_FILE, RunError, RunOptions, load_plan, prepare_run, run_application
    from rosaadl.workflow.run.measure import planned_chains
    from rosaadl.workflow.run.period_scale import parse_period_scale

    try:
        scale = parse_period_scale(period_scale)
    except RunError as exc:
        raise UsageError(exc.message) from None
    report = Report()
    if len(inputs) == 1 and inputs[0].is_dir() and (inputs[0] / PLAN_FILE).is_file():
        folder = inputs[0]
        if out is not None and out.resolve() != folder.resolve():
            raise UsageError("a run folder runs in place: leave out -o", file=str(out))
        if root is not None:
            raise UsageError("a run folder holds one application: leave out --root", file=str(folder))
        plan = load_plan(folder)
        options.progress(f"running the run folder {folder} ({plan.model})")
    else:
        folder = out if out is not None else DEFAULT_RUN_DIR
        if folder.exists() and not folder.is_dir():
            raise UsageError("the run folder is a file", file=str(folder))
        from rosaadl.exporters.rclpy import GenerationOptions

        loaded, rosmod_trace = read_generator_inputs(inputs, project=project, lenient=lenient)
        instance = choose_instance(loaded, root, lenient=lenient)
        folder.mkdir(parents=True, exist_ok=True)
        plan, generated = prepare_run(
            instance, folder, rosmod_trace=rosmod_trace, options=GenerationOptions(app_name=app_name)
        )
        report.note([*loaded.warnings, *generated.diagnostics])
        options.progress(
            f"generated {len(generated.written)} file(s) into {folder / 'src'} "
            f"({len(plan.nodes)} node(s), {len(plan.topics)} topic(s))"
        )
    try:
        result = run_application(
            folder,
            plan,
            RunOptions(
                duration=duration,
                emulate=emulate,
                realtime=not no_realtime,
                build=not no_build,
                measure=measure,
                warm_up=warm_up if measure else 0.0,
                chains=tuple(planned_chains(plan)) if measure else (),  # kept in the plan
                root=plan.model if measure else None,
                period_scale=scale,
            ),
            progress=options.progress,
        )
    except RunError as exc:  # no runtime, a failed build, no monitor: the report says so
        report.error(exc)
        report.data.update({"run_folder": str(folder), "nodes": [], "topics": []})
        sys.exit(report.emit(options))
    report.note([*result.errors, *result.warnings])
    for node in result.nodes:
        state = "started" if node.started else "did not start"
        report.say(f"node  {node.name}: {state}, exit code {node.exit_code}")
    for topic in result.topics:
        size = "-" if topic.bytes_per_message is None else f"{topic.bytes_per_message:g} B"
        report.say(
            f"topic {topic.name} ({topic.type}): {topic.messages} message(s), {_rate(topic.rate_hz)} "
            f"(model {_rate(topic.model_rate_hz)}), {size}/message"
        )
    report.data.update(result.data())
    sys.exit(report.emit(options))

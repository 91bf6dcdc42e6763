"""``rosaadl import INPUT -o MODEL``: read another tool's file into a rosaadl model (XMI or JSON).

``rosaadl import ros2-package DIR... -o MODEL`` reads ROS 2 ``rclpy`` packages statically and
``rosaadl import ros2-graph -o MODEL`` a running ROS 2 graph; both give a ROSMOD model. Any other
first word is an input file or folder (``rosaadl import x.aaxl2 -o m.xmi``).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

import click
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.cli.common import Options, Report, output_option, pass_options, time_unit_option
from rosaadl.errors import UsageError
from rosaadl.formats import expand_errors, read_input

__all__ = ["command"]


class _ImportGroup(click.Group):
    """``import``: its sub-verbs, and ``import INPUT`` for every file format (the ``file`` sub-verb)."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        if args and args[0] not in self.commands and args[0] not in ("-h", "--help"):
            args = ["file", *args]
        return super().parse_args(ctx, args)


@click.group("import", cls=_ImportGroup)
def command() -> None:
    """Import another tool's file into a rosaadl model: an OSATE .aaxl2, a Cheddar .xmlv3/.xml, a
    ROSMOD project or .webgmex, AADL text (``rosaadl import INPUT -o MODEL``), ROS 2 rclpy
    packages (``import ros2-package``) or a running ROS 2 graph (``import ros2-graph``)."""


def _import(options: Options, out: Path, source: str, read: Callable[[list], tuple[EObject, str]]) -> None:
    """Run ``read`` (it appends its warnings to the list it is given and returns the root read and
    its kind), write the model to ``out`` and exit: 1 with every located error, no file written."""
    from rosaadl.errors import RosaadlError

    if out.suffix.lower() not in (".xmi", ".json"):
        raise UsageError("the output must be a .xmi or .json model file", file=str(out))
    report = Report()
    warnings: list = []
    try:
        root, kind = read(warnings)
    except UsageError:
        raise
    except RosaadlError as exc:
        for error in expand_errors(exc):
            report.error(error)
        sys.exit(report.emit(options))
    report.note(warnings, info=True)
    written = model.save(root, out)
    options.progress(f"wrote {written}")
    report.say(f"{source} -> {written}")
    report.data.update({"input": source, "output": str(written), "kind": kind})
    sys.exit(report.emit(options))


@command.command("file")
@click.argument("source", type=click.Path(path_type=Path))
@output_option("Model file to write (.xmi or .json).")
@time_unit_option("What Cheddar's plain integer times are.")
@click.option("--project", help="The project to take from a .webgmex archive holding several.")
@click.option("--strict", is_flag=True, help="Treat what readers tolerate (unknown elements...) as errors.")
@pass_options
def import_file(
    options: Options, source: Path, out: Path, time_unit: str, project: str | None, strict: bool
) -> None:
    """Import an OSATE .aaxl2, a Cheddar .xmlv3/.xml, a ROSMOD project or .webgmex, or AADL text."""

    def read(warnings: list) -> tuple[EObject, str]:
        loaded = read_input(source, time_unit=time_unit, project=project, strict=strict)
        if len(loaded.roots) > 1:
            names = ", ".join(getattr(r, "name", "?") for r in loaded.roots)
            raise UsageError(
                f"the input holds several projects ({names}); choose one with --project", file=str(source)
            )
        warnings.extend(loaded.warnings)
        return loaded.root, loaded.kind

    _import(options, out, str(source), read)


@command.command("ros2-package")
@click.argument("folders", nargs=-1, required=True, type=click.Path(path_type=Path))
@output_option("Model file to write (.xmi or .json): a ROSMOD project.")
@pass_options
def import_ros2_package(options: Options, folders: tuple[Path, ...], out: Path) -> None:
    """Read ROS 2 rclpy packages (package folders or workspaces) statically, without running them:
    nodes, publishers, subscriptions, services, clients, timers, Python launch files."""
    from rosaadl.fileio import existing
    from rosaadl.importers.ros2_package import read_ros2_packages

    for folder in folders:
        if not existing(folder) or not folder.is_dir():
            raise UsageError("no such folder", file=str(folder))
    source = ", ".join(map(str, folders))
    _import(options, out, source, lambda warnings: (read_ros2_packages(list(folders), warnings), "rosmod"))


@command.command("ros2-graph")
@click.option(
    "--wait", type=click.FloatRange(0, 3600), default=2.0, show_default=True, help="Seconds of discovery."
)
@click.option("--domain-id", type=click.IntRange(0, 232), help="ROS_DOMAIN_ID [default: the environment's]")
@click.option(
    "--measure",
    type=click.FloatRange(0, 3600),
    default=0.0,
    show_default=True,
    help="Seconds of sampling every topic's rate and message sizes (0: none).",
)
@output_option("Model file to write (.xmi or .json): a ROSMOD project.")
@pass_options
def import_ros2_graph(
    options: Options, wait: float, domain_id: int | None, measure: float, out: Path
) -> None:
    """Join a running ROS 2 graph (with rclpy) and read its nodes, topics with types and QoS,
    services and clients; --measure also samples topic rates (periodic publishers get timers)
    and message sizes."""
    from rosaadl.workflow.ros2_graph import read_graph

    def read(warnings: list) -> tuple[EObject, str]:
        return read_graph(wait=wait, domain_id=domain_id, measure=measure, warnings=warnings), "rosmod"

    where = f"ROS 2 graph (domain {domain_id})" if domain_id is not None else "ROS 2 graph"
    _import(options, out, where, read)

"""The node processes of a run: their command lines, starting them, and stopping them cleanly.

A node is started as ``ros2 launch`` would start it from the launch file: the package's
executable from the install folder, behind the launch ``prefix`` as this machine allows it
(:mod:`rosaadl.workflow.run.cores`), with ``--ros-args`` giving its name (``__node``), namespace
(``__ns``), parameters (``-p name:=value``) and remappings (``-r from:=to``). Each node runs in a
session of its own (a Ctrl-C in the terminal reaches ``rosaadl run``, which stops the nodes) and
writes its output to ``logs/<node>.log`` in the run folder.

Stopping is what ``ros2 launch`` does on Ctrl-C: SIGINT to every node, then SIGTERM to those still
running after a grace period, then SIGKILL; how each node ended is recorded.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO

from rosaadl.workflow.run.plan import NodeLaunch, RunError

__all__ = [
    "NodeProcess",
    "node_command",
    "parameter_text",
    "start_node",
    "stop_nodes",
    "wait_started",
    "GRACE_SECONDS",
    "TERM_SECONDS",
]

#: Seconds a node has to end after SIGINT, then after SIGTERM.
GRACE_SECONDS = 10.0
TERM_SECONDS = 3.0
_POLL = 0.02


@dataclass
class NodeProcess:
    """A started node."""

    node: NodeLaunch
    command: list[str]
    log: Path
    process: subprocess.Popen | None = None
    started: bool = False
    exit_code: int | None = None
    stopped_by: str = ""  # "" (ended by itself) | SIGINT | SIGTERM | SIGKILL
    warnings: list[str] = field(default_factory=list)
    _out: IO | None = None

    def running(self) -> bool:
        return self.process is not None and self.process.poll() is None


def parameter_text(value: object) -> str:
    """A parameter value as ``-p name:=value`` takes it (YAML: ``true``, ``3``, ``0.05``, ``'x'``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        text = repr(value)
        return text if any(c in text for c in ".en") else text + ".0"
    return "'" + str(value).replace("'", "''") + "'"


def node_command(
    node: NodeLaunch, install: Path, prefix: list[str], extra: list[tuple[str, object]] = ()
) -> list[str]:
    """The command line starting ``node`` from the install folder (see the module docstring)."""
    executable = install / "lib" / node.package / node.executable
    command = [*prefix, str(executable), "--ros-args", "-r", f"__node:={node.name}"]
    if node.namespace:
        command += ["-r", f"__ns:={node.namespace}"]
    for name, value in [*node.parameters, *extra]:
        command += ["-p", f"{name}:={parameter_text(value)}"]
    for source, target in node.remappings:
        command += ["-r", f"{source}:={target}"]
    return command


def start_node(
    node: NodeLaunch, command: list[str], env: dict[str, str], logs: Path, cwd: Path
) -> NodeProcess:
    """Start one node (its output to ``logs/<name>.log``); a :class:`RunError` when it cannot."""
    executable = Path(command[command.index("--ros-args") - 1])
    if not executable.is_file():
        raise RunError(
            f"node {node.full_name}: no executable {executable.name} in package {node.package} "
            "(the workspace was not built, or the package has no such entry point)",
            file=str(executable),
        )
    log = logs / f"{node.full_name.strip('/').replace('/', '.') or 'node'}.log"
    started = NodeProcess(node=node, command=command, log=log)
    started._out = open(log, "wb")  # noqa: SIM115 - kept open while the node runs
    try:
        started.process = subprocess.Popen(
            command,
            cwd=cwd,
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=started._out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    except OSError as exc:
        started._out.close()
        raise RunError(f"node {node.full_name} could not start: {exc}", file=str(executable)) from exc
    return started


def wait_started(nodes: list[NodeProcess], seconds: float) -> None:
    """Wait ``seconds`` (less when a node ends); a node still running then is *started*."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and all(n.running() for n in nodes):
        time.sleep(_POLL)
    for node in nodes:
        node.started = node.running()
        if not node.started:
            _finish(node, "")


def _finish(node: NodeProcess, how: str) -> None:
    if node.process is not None and node.exit_code is None:
        node.exit_code = node.process.wait()
        node.stopped_by = how if node.stopped_by == "" else node.stopped_by
    if node._out is not None and not node._out.closed:
        node._out.close()


def _wait(nodes: list[NodeProcess], seconds: float) -> list[NodeProcess]:
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and any(n.running() for n in nodes):
        time.sleep(_POLL)
    return [n for n in nodes if n.running()]


def _signal(node: NodeProcess, signum: int) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.kill(node.process.pid, signum)  # the node itself (taskset and chrt exec it)
    node.stopped_by = signal.Signals(signum).name


def stop_nodes(nodes: list[NodeProcess], *, grace: float = GRACE_SECONDS, term: float = TERM_SECONDS) -> None:
    """SIGINT to every running node, SIGTERM after ``grace`` seconds, SIGKILL ``term`` later."""
    running = [n for n in nodes if n.running()]
    for node in nodes:
        if not node.running():
            _finish(node, "")
    previous = 0.0
    for signum, wait in ((signal.SIGINT, grace), (signal.SIGTERM, term), (signal.SIGKILL, term)):
        if not running:
            break
        name = signal.Signals(signum).name
        for node in running:
            if node.stopped_by:
                node.warnings.append(
                    f"node {node.node.full_name} did not stop within {previous:g} s of {node.stopped_by}; "
                    f"sent {name}"
                )
            _signal(node, signum)
        running = _wait(running, wait)
        previous = wait
    for node in nodes:
        _finish(node, node.stopped_by)

"""The ROS 2 runtime of ``make ros`` (the project's ``ros`` extra: PyPI wheels of ROS 2 kilted for
CPython 3.11 on Linux) for the tests that build and run generated packages.

A test module needing it starts with ``pytestmark = runtime_marks()``: the ``ros_runtime``
marker and a skip with the reason where the runtime (or cmake, make, g++) is not there.  The
runtime lives in this interpreter's environment (``sys.prefix``): colcon, cmake's ``python3``
and the nodes all run with it, ``AMENT_PREFIX_PATH``/``CMAKE_PREFIX_PATH`` are that prefix, and
a built workspace adds its own ``install/setup.bash`` (``LD_LIBRARY_PATH`` of the generated
interface libraries, ``PYTHONPATH`` of its packages).
"""

from __future__ import annotations

import functools
import importlib.util
import os
import platform
import shlex
import shutil
import subprocess
import sys
import types
from pathlib import Path

import pytest

__all__ = [
    "runtime_missing",
    "runtime_marks",
    "runtime_environment",
    "workspace_environment",
    "colcon_build",
    "generate_demo_workspace",
    "launch_nodes",
    "node_command",
]

#: What the runtime tests import from the runtime.
_PROBE = "import rclpy, std_msgs.msg, sensor_msgs.msg, geometry_msgs.msg, rosidl_parser.parser, colcon_core"
#: The build tools the machine gives (Debian's packages; .ci/run installs them).
_BUILD_TOOLS = {"cmake": "cmake", "make": "make", "g++": "g++"}


@functools.cache
def runtime_missing() -> str:
    """Why the ROS 2 runtime cannot be used here ("" when it can)."""
    tools = [
        f"{tool} (Debian package {package})"
        for tool, package in _BUILD_TOOLS.items()
        if not shutil.which(tool)
    ]
    if tools:
        return f"the ROS 2 runtime needs {', '.join(tools)}"
    done = subprocess.run(
        [sys.executable, "-c", _PROBE], capture_output=True, text=True, timeout=120, env=runtime_environment()
    )
    if done.returncode != 0:
        version = platform.python_version()
        return (
            f"the ROS 2 runtime is not installed in {sys.prefix} (`make ros`; its wheels are for "
            f"CPython 3.11 on Linux, this is {platform.python_implementation()} {version} on "
            f"{sys.platform}): {done.stderr.strip().splitlines()[-1:] or ['no error text']}"
        )
    return ""


def runtime_marks() -> list[pytest.MarkDecorator]:
    """The marks of a test module that needs the runtime."""
    reason = runtime_missing()
    return [pytest.mark.ros_runtime, pytest.mark.skipif(bool(reason), reason=reason)]


def runtime_environment(domain: int | None = None) -> dict[str, str]:
    """The environment of the runtime: this prefix's tools first on PATH, the ament/CMake prefix,
    DDS discovery on this machine only, in a domain of its own (102..201, from the process id:
    other test runs and ``rosaadl run`` may share the machine, mostly in the low domains)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["PATH"] = os.pathsep.join([str(Path(sys.prefix) / "bin"), env.get("PATH", "")])
    env["AMENT_PREFIX_PATH"] = env["CMAKE_PREFIX_PATH"] = sys.prefix
    env["ROS_DOMAIN_ID"] = str(domain if domain is not None else 102 + os.getpid() % 100)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env["RCUTILS_COLORIZED_OUTPUT"] = "0"
    env["PYTHONUNBUFFERED"] = "1"
    return env


def workspace_environment(root: Path, domain: int | None = None) -> dict[str, str]:
    """:func:`runtime_environment` with the built workspace ``root``'s ``install/setup.bash``."""
    done = subprocess.run(
        ["bash", "-c", ". install/setup.bash >/dev/null && env -0"],
        cwd=root,
        env=runtime_environment(domain),
        capture_output=True,
        timeout=60,
        check=True,
    )
    return dict(item.split("=", 1) for item in done.stdout.decode().split("\0") if "=" in item)


def colcon_build(root: Path, *packages: str) -> subprocess.CompletedProcess:
    """``colcon build`` of the workspace ``root`` (only ``packages`` when given) with the runtime."""
    command = [str(Path(sys.prefix) / "bin" / "colcon"), "build", "--base-paths", "src"]
    if packages:
        command += ["--packages-select", *packages]
    return subprocess.run(
        command + ["--event-handlers", "console_cohesion+"],
        cwd=root,
        env=runtime_environment(),
        capture_output=True,
        text=True,
        timeout=600,
    )


def generate_demo_workspace(out: Path) -> Path:
    """The demo's workspace (the tracking example on its proposed deployment) under ``out``; its
    root (``src`` inside)."""
    done = subprocess.run(
        [sys.executable, "-m", "rosaadl", "-q", "demo", "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return out / "ros2_ws"


def launch_nodes(path: Path) -> list[dict[str, object]]:
    """The ``Node`` actions of a generated launch file as keyword dicts, its prefixes fitted to this
    machine by the file itself (``launch`` and ``launch_ros`` are stubbed: they have no wheel)."""
    launch = types.ModuleType("launch")
    launch.LaunchDescription = list
    actions = types.ModuleType("launch_ros.actions")
    actions.Node = lambda **kwargs: kwargs
    launch_ros = types.ModuleType("launch_ros")
    launch_ros.actions = actions
    stubs = {"launch": launch, "launch_ros": launch_ros, "launch_ros.actions": actions}
    saved = {name: sys.modules.get(name) for name in stubs}
    sys.modules.update(stubs)
    try:
        spec = importlib.util.spec_from_file_location(f"launch_{path.stem.replace('.', '_')}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return list(module.generate_launch_description())
    finally:
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module


def _parameter_text(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value) if isinstance(value, float) else str(value)


def node_command(
    root: Path, node: dict[str, object], *, prefix: str = "all", **parameters: object
) -> list[str]:
    """The command line that starts ``node`` (a :func:`launch_nodes` dict) of the built workspace
    ``root`` as ``ros2 launch`` would: its prefix (``prefix``: ``all``, ``chrt`` for its
    scheduling without its CPU affinity, or ``none``), name, namespace, parameters
    (``parameters`` added or overriding; ``__`` in a name stands for ``.``) and remappings."""
    package, executable = str(node["package"]), str(node["executable"])
    words = shlex.split(str(node.get("prefix") or "")) if prefix != "none" else []
    if prefix == "chrt":
        words = words[words.index("chrt") :] if "chrt" in words else []
    command = list(words)
    command += [str(root / "install" / package / "lib" / package / executable), "--ros-args"]
    command += ["-r", f"__node:={node['name']}"]
    if node.get("namespace"):
        command += ["-r", f"__ns:=/{str(node['namespace']).strip('/')}"]
    values = dict(node["parameters"][0]) if node.get("parameters") else {}
    values.update({name.replace("__", "."): value for name, value in parameters.items()})
    for name, value in values.items():
        command += ["-p", f"{name}:={_parameter_text(value)}"]
    for local, target in node.get("remappings") or ():
        command += ["-r", f"{local}:={target}"]
    return command

"""The ROS 2 of this Python environment: finding it, the environment a run uses, and the build.

ROS 2 comes from PyPI wheels installed into rosaadl's own virtual environment (the ``ros`` extra):
``rclpy``, the RMW, the message packages and, for interface packages, the ament/rosidl build
tools and colcon. Their prefix is the environment's (``sys.prefix``), so a run puts it on
``AMENT_PREFIX_PATH`` and ``CMAKE_PREFIX_PATH``. A workspace is built with colcon into one merged
install folder (``--merge-install``) whose ``lib`` (the interface packages' type supports) goes on
``LD_LIBRARY_PATH`` and whose ``lib/pythonX.Y/site-packages`` on ``PYTHONPATH``, as its
``setup.bash`` would put them.

A run talks on a ROS domain of its own (``ROS_DOMAIN_ID`` derived from the process id, unless the
caller's environment sets one) restricted to this host, so that runs side by side, or another
ROS 2 system on the network, do not see each other's topics.

The wheels' exported CMake targets (``<pkg>__rosidl_generator_py``) name the Python include
folder of the machine they were built on (``/opt/python/cp311-cp311/include/python3.11``), which
CMake refuses at generation when an interface package uses them (a ``.srv`` needs
``service_msgs``'): the build injects :data:`CMAKE_FIXUP` (``CMAKE_PROJECT_INCLUDE``), which drops
the include folders that do not exist from the imported targets once the package's
``CMakeLists.txt`` has been read. The local Python's own include folder is the one rosidl adds.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

from rosaadl.workflow.run.plan import RunError

__all__ = [
    "ROS_MODULES",
    "BUILD_LOG",
    "CMAKE_FIXUP",
    "ros_missing",
    "require_ros",
    "run_environment",
    "colcon_build",
    "tail",
]

#: The Python modules a run needs from the ROS 2 wheels.
ROS_MODULES = ("rclpy", "rclpy.serialization", "colcon_core")
#: The build's output, kept in the run folder.
BUILD_LOG = "build.log"
#: CMake run at each package's ``project()``: drop the missing include folders of imported targets.
CMAKE_FIXUP = """\
# Made by rosaadl run: the ROS 2 wheels' exported targets name include folders of the machine
# they were built on; CMake refuses a target naming a folder that does not exist.
function(_rosaadl_drop_missing_include_folders)
  get_property(targets DIRECTORY "${CMAKE_SOURCE_DIR}" PROPERTY IMPORTED_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(folders ${target} INTERFACE_INCLUDE_DIRECTORIES)
    if(folders)
      set(kept "")
      set(dropped FALSE)
      foreach(folder IN LISTS folders)
        if(folder MATCHES "^\\$<" OR EXISTS "${folder}")
          list(APPEND kept "${folder}")
        else()
          set(dropped TRUE)
        endif()
      endforeach()
      if(dropped)
        set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${kept}")
      endif()
    endif()
  endforeach()
endfunction()
cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL _rosaadl_drop_missing_include_folders)
"""
_DOMAINS = 200  # ROS_DOMAIN_ID 1..200 (Fast DDS takes 0..232)
_BUILD_TIMEOUT = 1800


def ros_missing() -> list[str]:
    """The ROS 2 modules this Python cannot import (empty when the runtime is installed)."""
    missing = []
    for name in ROS_MODULES:
        try:
            found = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            found = None
        if found is None:
            missing.append(name)
    return missing


def require_ros() -> None:
    """A :class:`RunError` saying how to install ROS 2 when this Python has not got it."""
    missing = ros_missing()
    if missing:
        raise RunError(
            f"the ROS 2 runtime is not installed in this Python ({sys.prefix}; missing "
            f"{', '.join(missing)}): install it with `pip install -e '.[ros]'` (or `make ros`)"
        )


def _joined(*parts: str | None) -> str:
    items: list[str] = []
    for part in parts:
        for item in (part or "").split(os.pathsep):
            if item and item not in items:
                items.append(item)
    return os.pathsep.join(items)


def _site_packages(install: Path) -> Path:
    return install / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages"


def run_environment(install: Path | None = None, *, base: dict[str, str] | None = None) -> dict[str, str]:
    """The environment of the build, the nodes and the monitor (``install``: the workspace's
    merged install folder, once built)."""
    env = dict(os.environ if base is None else base)
    prefix = sys.prefix
    bin_dir = str(Path(sys.executable).parent)
    own = [str(install)] if install is not None else []
    env["AMENT_PREFIX_PATH"] = _joined(*own, prefix, env.get("AMENT_PREFIX_PATH"))
    env["CMAKE_PREFIX_PATH"] = _joined(*own, prefix, env.get("CMAKE_PREFIX_PATH"))
    env["PATH"] = _joined(bin_dir, env.get("PATH") or os.defpath)
    if install is not None:
        env["LD_LIBRARY_PATH"] = _joined(str(install / "lib"), env.get("LD_LIBRARY_PATH"))
        env["PYTHONPATH"] = _joined(str(_site_packages(install)), env.get("PYTHONPATH"))
        env["COLCON_PREFIX_PATH"] = _joined(str(install), env.get("COLCON_PREFIX_PATH"))
    env.setdefault("ROS_DOMAIN_ID", str(1 + os.getpid() % _DOMAINS))
    env.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    env["PYTHONUNBUFFERED"] = "1"
    return env


def colcon_build(workspace: Path, *, jobs: int | None = None) -> Path:
    """Build ``workspace/src`` into ``workspace/install`` with colcon; its install folder.

    The output goes to ``workspace/build.log``; a failure is a :class:`RunError` quoting its end.
    """
    install = workspace / "install"
    fixup = workspace / "build" / "rosaadl-cmake-fixup.cmake"
    fixup.parent.mkdir(parents=True, exist_ok=True)
    fixup.write_text(CMAKE_FIXUP, encoding="utf-8")
    command = [
        sys.executable,
        "-m",
        "colcon",
        "--log-base",
        str(workspace / "log"),
        "build",
        "--merge-install",
        "--base-paths",
        str(workspace / "src"),
        "--build-base",
        str(workspace / "build"),
        "--install-base",
        str(install),
        "--event-handlers",
        "console_direct+",
        "desktop_notification-",
        "status-",
        "--cmake-args",
        f"-DCMAKE_PROJECT_INCLUDE={fixup}",
    ]
    if jobs:
        command += ["--parallel-workers", str(jobs)]
    log = workspace / BUILD_LOG
    try:
        with open(log, "wb") as out:
            done = subprocess.run(
                command,
                cwd=workspace,
                env=run_environment(),
                stdout=out,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                timeout=_BUILD_TIMEOUT,
                check=False,
            )
    except subprocess.TimeoutExpired as exc:
        raise RunError(f"colcon build did not end within {_BUILD_TIMEOUT} s", file=str(log)) from exc
    except OSError as exc:
        raise RunError(f"colcon build could not start: {exc}", file=str(workspace)) from exc
    if done.returncode != 0:
        raise RunError(
            f"colcon build failed (exit {done.returncode}):\n{tail(log)}\n(the whole output is in {log})",
            file=str(workspace / "src"),
        )
    return install


def tail(path: Path, lines: int = 15) -> str:
    """The last ``lines`` lines of a log file, indented (empty when it cannot be read)."""
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return ""
    return "\n".join("  " + line for line in text.rstrip().splitlines()[-lines:])

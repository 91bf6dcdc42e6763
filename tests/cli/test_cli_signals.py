"""SIGTERM and SIGINT during ``export aaxl2`` and ``generate rclpy`` on a 3 000-thread model:
exit 143 / 130, no temporary and no partial file left; the next run succeeds and leaves none."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from benchmarks.generators.instances import ros_ring
from rosaadl import model

pytestmark = pytest.mark.slow

NODES = 1500  # two threads per node: 3 000 threads
COMMANDS = {"export aaxl2": ["export", "aaxl2"], "generate rclpy": ["generate", "rclpy"]}
EXIT = {signal.SIGINT: 130, signal.SIGTERM: 143}
WAIT = {signal.SIGTERM: 120.0, signal.SIGINT: 2.0}  # until a temporary appears, at most


@pytest.fixture(scope="module")
def ring(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("ring") / "ring.json"
    model.save(ros_ring(NODES).eContainer(), path)
    return path


def _files(folder: Path) -> set[str]:
    return {str(path.relative_to(folder)) for path in folder.rglob("*") if path.is_file()}


def _temporaries(folder: Path) -> list[str]:
    return [name for _, _, names in os.walk(folder) for name in names if name.endswith(".tmp")]


def _interrupted(args: list[str], out: Path, signum: int) -> tuple[int, str]:
    """Run the CLI, send ``signum`` once a temporary appears in ``out`` (the write is under
    way) or after ``WAIT[signum]`` seconds, whichever comes first; its exit code and stderr."""
    process = subprocess.Popen(
        [sys.executable, "-m", "rosaadl", *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    try:
        deadline = time.monotonic() + WAIT[signum]
        while time.monotonic() < deadline and process.poll() is None and not _temporaries(out):
            time.sleep(0.003)
        assert process.poll() is None, "the command ended before it could be interrupted"
        process.send_signal(signum)
        _, err = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    return process.returncode, err.decode()


@pytest.mark.parametrize("command", list(COMMANDS))
def test_an_interrupted_run_leaves_no_temporary_and_no_partial_file(command, ring, tmp_path) -> None:
    out = tmp_path / "out"
    args = [*COMMANDS[command], str(ring), "-o", str(out)]
    complete: set[str] | None = None
    for signum in (signal.SIGTERM, signal.SIGINT):
        code, err = _interrupted(args, out, signum)
        assert code == EXIT[signum], err
        assert "interrupted" in err and "Traceback" not in err
        assert _temporaries(out) == []
        complete = complete or _files(out) or None  # all-or-nothing: none, or every file
        assert _files(out) in (set(), complete)
    # a temporary left by a killed writer (its process is gone) is swept by the next run
    stale = out / "instances" if command == "export aaxl2" else out
    stale.mkdir(parents=True, exist_ok=True)
    (stale / f".rosaadl-{_ended_process()}-0123456789ab.tmp").write_text("partial")
    done = subprocess.run(
        [sys.executable, "-m", "rosaadl", *args], capture_output=True, text=True, timeout=600, check=False
    )
    assert done.returncode == 0, done.stderr
    assert _temporaries(out) == []
    assert complete is None or _files(out) == complete


def _ended_process() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid

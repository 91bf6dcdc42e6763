"""Every reader answers mutated input: exit 0 or 1, a location in every error, no traceback, in
bounded time.

Each format has a small valid seed made here (AADL text, ``.aaxl2`` and Cheddar files exported
by rosaadl itself, ``.xmi``/``.json`` models, the bundled example's ROSMOD v0.3 software file in
a copy of its project, v0.1 ``.rosml``, v0.4 JSON, a ``.webgmex`` archive, ``.msg``/``.srv``,
the bundled measurements CSV and a ``measurements.json``, the files of the ROS 2 tutorial
package of ``tests/data``); hypothesis mutates its bytes (truncation, deletion, duplication,
insertion of random or hostile bytes, huge and odd numbers in place of digits) and ``rosaadl
check --format json`` (``library add-profile`` for the measurement files, and ``analyze
--compare`` for ``measurements.json``; the message parser for ``.msg``/``.srv``) must give exit
0 or 1, every error with a file or an element path, and no ``Traceback``, within
:data:`SECONDS` of CPU time (a loaded machine stretches the wall clock, not the work) and
:data:`PEAK_MIB` per input. The whole module is bounded by the example
counts (well under a minute)."""

from __future__ import annotations

import contextlib
import io
import json
import shutil
import time
import zipfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from benchmarks.harness import reset_peak, status_kib
from rosaadl import model
from rosaadl.cli import main
from rosaadl.errors import RosaadlError
from rosaadl.exporters.aaxl2 import dumps_aaxl2
from rosaadl.exporters.cheddar import dumps_cheddar
from rosaadl.importers import ros_msg
from rosaadl.importers.aadl_text import read_files
from rosaadl.transforms.instantiate import instantiate
from tests.conftest import ROOT
from tests.importers.test_rosmod_text import V02_RML
from tests.measurements_sample import tracking_measurements, tracking_measurements_text

#: the time one input may take, reading and checking it (a hang or a quadratic blow-up fails)
SECONDS = 10.0
#: the memory one input (of at most a few hundred KB) may take above what was resident before
PEAK_MIB = 256
EXAMPLES = 30
#: Mutated measurement files compared with their model (an analysis each: fewer).
COMPARED_EXAMPLES = 8

AADL = """package fuzz_pkg
public
  with ros;
  data msg
    properties
      Data_Size => 8 Bytes;
  end msg;
  thread worker
    features
      inp: in event data port msg;
      outp: out event data port msg;
  end worker;
  thread implementation worker.impl
    properties
      Dispatch_Protocol => Periodic;
      Period => 10 ms;
      Compute_Execution_Time => 1 ms .. 2 ms;
      Priority => 3;
  end worker.impl;
  process proc
  end proc;
  process implementation proc.impl
    subcomponents
      a: thread worker.impl;
      b: thread worker.impl;
    connections
      c1: port a.outp -> b.inp;
  end proc.impl;
  processor cpu
    properties
      Scheduling_Protocol => (RMS);
  end cpu;
  system top
  end top;
  system implementation top.impl
    subcomponents
      p: process proc.impl;
      c: processor cpu;
    properties
      Actual_Processor_Binding => (reference (c)) applies to p;
  end top.impl;
end fuzz_pkg;
"""

ROSMOD_V04 = {
    "py/object": "rosmod.Project",
    "name": "fuzz",
    "children": [{"py/object": "rosmod.Software", "name": "Software", "children": []}],
}

TRACKING = ROOT / "examples" / "tracking"
MEASUREMENTS = ROOT / "examples" / "profiles" / "sample_measurements.csv"
SYSTEMS = ROOT / "library" / "systems"
MSG = "# a message\nint64 value\nstring[] names\nfloat64[3] vector\nstd_msgs/Header header\n"
SRV = "int64 request\n---\nbool ok\nstring why\n"


# --------------------------------------------------------------------------- seeds


def _instance(folder: Path):
    source = folder / "fuzz_pkg.aadl"
    source.write_text(AADL)
    return instantiate(read_files([source]), "fuzz_pkg::top.impl")


@pytest.fixture(scope="module")
def seeds(tmp_path_factory) -> dict[str, tuple[str, bytes]]:
    """Format → (file suffix, valid bytes)."""
    instance = _instance(tmp_path_factory.mktemp("seed"))
    out = {
        "aadl": (".aadl", AADL.encode()),
        "aaxl2": (".aaxl2", dumps_aaxl2(instance)),
        "cheddar": (".xmlv3", dumps_cheddar(instance)),
        "xmi": (".xmi", model.dumps_xmi(instance)),
        "json": (".json", model.dumps_json(instance)),
        "rosmod-v03": (
            ".rml",
            (ROOT / "examples" / "tracking" / "01-Software" / "tracking.rml").read_bytes(),
        ),
        "rosmod-v01": (".rosml", ("workspace WS;\n" + V02_RML).encode()),
        "rosmod-v04": (".rml", json.dumps(ROSMOD_V04).encode()),
    }
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        archive.writestr("project.json", json.dumps({"projectId": "fuzz", "objects": {}}))
    out["webgmex"] = (".webgmex", buffer.getvalue())
    return out


# --------------------------------------------------------------------------- mutations

_HOSTILE = [
    b"",
    b"\x00",
    b"\xff\xfe",
    b"]]>",
    b"<!DOCTYPE x [<!ENTITY e SYSTEM 'file:///etc/passwd'>]>",
    b"&e;",
    b"{",
    b"}",
    b"[[[[[[[[",
    b'"',
    b"9" * 5000,
    b"1e309",
    b"NaN",
    b"-1",
    b"1_0",
    b"../../x",
    b"\n" * 3,
    "é\u202e".encode(),
]


@st.composite
def mutated(draw, data: bytes) -> bytes:
    """``data`` with one to three of: a cut, a deleted span, a duplicated span, inserted random
    or hostile bytes, a run of digits replaced by a huge or odd number."""
    for _ in range(draw(st.integers(1, 3))):
        size = len(data)
        at = draw(st.integers(0, size))
        kind = draw(st.sampled_from(["cut", "delete", "duplicate", "random", "hostile", "number"]))
        if kind == "cut":
            data = data[:at]
        elif kind == "delete":
            data = data[:at] + data[at + draw(st.integers(1, 64)) :]
        elif kind == "duplicate":
            span = data[at : at + draw(st.integers(1, 256))]
            data = data[:at] + span * draw(st.integers(2, 50)) + data[at:]
        elif kind == "random":
            data = data[:at] + draw(st.binary(min_size=1, max_size=16)) + data[at:]
        elif kind == "hostile":
            data = data[:at] + draw(st.sampled_from(_HOSTILE)) + data[at:]
        else:
            digits = [i for i, b in enumerate(data) if 48 <= b <= 57]
            if digits:
                i = draw(st.sampled_from(digits))
                data = (
                    data[:i]
                    + draw(st.sampled_from([b"9" * 400, b"1e309", b"NaN", b"-0", b"x"]))
                    + data[i + 1 :]
                )
    return data


# --------------------------------------------------------------------------- the check


def _run(args: list[str]) -> tuple[int, str, str, float]:
    out, err = io.StringIO(), io.StringIO()
    before = reset_peak()
    start = time.process_time()  # CPU time: a hang, not a loaded machine
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(args)
    took = time.process_time() - start
    peak = status_kib("VmHWM:") if before is not None else None
    if peak is not None:
        grown = (peak - before) / 1024
        assert grown < PEAK_MIB, f"{args}: {grown:.0f} MiB above the memory resident before"
    return code, out.getvalue(), err.getvalue(), took


def _answered(code: int, out: str, err: str, took: float, what: str) -> None:
    assert "Traceback" not in out + err, f"{what}: a traceback\n{err[-3000:]}"
    assert code in (0, 1), f"{what}: exit {code}\n{out[-2000:]}\n{err[-2000:]}"
    assert took < SECONDS, f"{what}: took {took:.1f} s"
    if code == 1 and out.strip().startswith("{"):
        document = json.loads(out)
        for error in document.get("errors", []):
            assert error.get("file") or error.get("path"), f"{what}: an error with no location: {error}"


_SETTINGS = settings(
    max_examples=EXAMPLES,
    deadline=None,
    derandomize=True,
    suppress_health_check=[
        HealthCheck.function_scoped_fixture,
        HealthCheck.too_slow,
        HealthCheck.data_too_large,
    ],
)

FORMATS = ["aadl", "aaxl2", "cheddar", "xmi", "json", "rosmod-v03", "rosmod-v01", "rosmod-v04", "webgmex"]


@pytest.mark.parametrize("fmt", FORMATS)
def test_the_seed_reads_and_every_mutation_is_answered(fmt, seeds, tmp_path):
    suffix, seed = seeds[fmt]
    if fmt == "rosmod-v03":  # a v0.3 software file is read with its project
        project = tmp_path / "project"
        shutil.copytree(TRACKING, project)
        path = target = project / "01-Software" / "tracking.rml"
        checked = project
    else:
        path, target, checked = tmp_path / f"seed{suffix}", tmp_path / f"fuzz{suffix}", None
    path.write_bytes(seed)
    code, out, err, took = _run(["--format", "json", "check", str(checked or path)])
    _answered(code, out, err, took, f"{fmt} seed")
    assert code == 0 or fmt == "webgmex", f"the {fmt} seed itself does not read:\n{out[-2000:]}"

    @_SETTINGS
    @given(data=st.data())
    def mutate(data):
        target.write_bytes(data.draw(mutated(seed)))
        _answered(*_run(["--format", "json", "check", str(checked or target)]), f"{fmt} mutation")

    mutate()


def test_measurement_files_are_answered(tmp_path):
    @_SETTINGS
    @given(data=st.data())
    def mutate(data):
        source = tmp_path / "m.csv"
        source.write_bytes(data.draw(mutated(MEASUREMENTS.read_bytes())))
        out_dir = tmp_path / "profiles"
        _answered(*_run(["library", "add-profile", str(source), "-o", str(out_dir)]), "measurements")

    mutate()


@pytest.mark.parametrize("kind", ["msg", "srv"])
def test_message_definitions_are_answered(kind):
    seed = (MSG if kind == "msg" else SRV).encode()

    @_SETTINGS
    @given(data=st.data())
    def mutate(data):
        text = data.draw(mutated(seed)).decode("utf-8", "replace")
        start = time.process_time()  # CPU time: a hang, not a loaded machine
        try:
            if kind == "msg":
                ros_msg.parse_msg(text, name="Fuzz", package="fuzz_msgs", filename="Fuzz.msg")
            else:
                ros_msg.parse_srv(text, name="Fuzz", package="fuzz_msgs", filename="Fuzz.srv")
        except RosaadlError as exc:
            assert str(exc)
        assert time.process_time() - start < SECONDS

    mutate()


ROS2_TUTORIAL = ROOT / "tests" / "data" / "ros2_tutorial" / "src" / "py_pubsub"


@pytest.mark.parametrize(
    "member",
    ["package.xml", "setup.py", "py_pubsub/publisher_member_function.py", "launch/pubsub.launch.py"],
)
def test_ros2_package_files_are_answered(member, tmp_path):
    """A ROS 2 package (the tutorial fixture) with one of its files mutated: its manifest, its
    entry points, a node, a launch file."""
    package = tmp_path / "py_pubsub"
    shutil.copytree(ROS2_TUTORIAL, package)
    seed = (ROS2_TUTORIAL / member).read_bytes()
    code, out, err, took = _run(["--format", "json", "check", str(package)])
    _answered(code, out, err, took, "ros2-package seed")
    assert code == 0, out[-2000:]

    @_SETTINGS
    @given(data=st.data())
    def mutate(data):
        (package / member).write_bytes(data.draw(mutated(seed)))
        _answered(*_run(["--format", "json", "check", str(package)]), f"ros2-package {member} mutation")

    mutate()


def test_measurements_json_files_are_answered(tmp_path):
    """A measured run's ``measurements.json`` (the tracking sample, with the board and core a run
    names, of version 3: a timer thread's dispatch latency) mutated: read by ``library
    add-profile`` and by ``analyze --compare`` of its model."""
    document = tracking_measurements()
    document["version"] = 3
    document["run"].update(board="xu4", core="a15")
    document["threads"][0]["dispatch_latency_us"] = {"min": 612.5, "mean": 1034.25, "max": 1842.2}
    seed = tracking_measurements_text(document).encode()
    source = tmp_path / "m.json"
    source.write_bytes(seed)
    code, out, err, took = _run(
        ["--format", "json", "library", "add-profile", str(source), "-o", str(tmp_path)]
    )
    _answered(code, out, err, took, "measurements.json seed")
    assert code == 0, out[-2000:] + err[-2000:]
    compare = ["--format", "json", "analyze", str(SYSTEMS), "--root", "sys_tracking::tracking.impl"]
    compare += ["--only", "compare", "--compare", str(source)]

    @_SETTINGS
    @given(data=st.data())
    def mutate(data):
        source.write_bytes(data.draw(mutated(seed)))
        out_dir = tmp_path / "profiles"
        _answered(*_run(["library", "add-profile", str(source), "-o", str(out_dir)]), "measurements.json")

    @settings(_SETTINGS, max_examples=COMPARED_EXAMPLES)
    @given(data=st.data())
    def compared(data):
        source.write_bytes(data.draw(mutated(seed)))
        _answered(*_run(compare), "measurements.json compared")

    mutate()
    compared()

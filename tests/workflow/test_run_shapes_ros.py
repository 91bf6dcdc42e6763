"""``rosaadl run --emulate`` on a real ROS 2 runtime (``make ros``) of the project of
:mod:`rosmod_shapes`: the shapes the ROSMOD projects of the corpus met when they ran (one run of
a few seconds for the module, its build included: about 30 s on 2 cores).

The assertions count messages; they do not time them: the caller's topic carries at least half
of what its timer gives in the run, the answerer's (published from its service callback) as many
as the calls it answered, at least a quarter of the caller's dispatches."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from ros_runtime import runtime_marks
from rosmod_shapes import CALL_PERIOD, ROOT, converted_project

pytestmark = [*runtime_marks(), pytest.mark.slow]

DURATION = 4


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """(exit code, JSON report, stderr) of the run."""
    folder = tmp_path_factory.mktemp("relay")
    aadl = converted_project(folder)
    command = ["run", str(aadl), "--root", ROOT, "--duration", str(DURATION), "--emulate"]
    done = subprocess.run(
        [sys.executable, "-m", "rosaadl", "--format", "json", *command, "-o", str(folder / "run")],
        capture_output=True,
        text=True,
        timeout=900,
    )
    return done.returncode, json.loads(done.stdout or "{}"), done.stderr


def test_every_node_starts_and_exits_0(report):
    """Five nodes under SCHED_FIFO where permitted, the first with three threads: none is kept
    from coming up by another's executor loop, and the sleeper's node with its timer of period 0
    starts."""
    code, data, stderr = report
    assert {n["name"]: (n["started"], n["exit_code"]) for n in data["nodes"]} == {
        name: (True, 0) for name in ("/both", "/ear_1", "/ear_2", "/beacon", "/slow")
    }, stderr[-3000:]
    assert code == 0 and data["errors"] == [], data["errors"]


def test_the_service_is_called_and_its_server_publishes(report):
    _, data, _ = report
    topics = {t["name"]: t for t in data["topics"]}
    dispatches = DURATION / CALL_PERIOD
    assert topics["/both/caller_i_tick_pub"]["messages"] >= dispatches / 2
    assert topics["/both/answerer_i_answer_pub"]["messages"] >= dispatches / 4
    assert topics["/both/answerer_i_answer_pub"]["model_rate_hz"] == pytest.approx(1 / CALL_PERIOD)


def test_topics_the_twin_cannot_feed_are_warnings(report):
    """The ten-minute timer's topic and the beacon's (nothing of the model dispatches it) carry
    nothing, and the report says why, without an error."""
    _, data, _ = report
    topics = {t["name"]: t for t in data["topics"]}
    silent = [name for name, t in topics.items() if t["messages"] == 0]
    assert sorted(silent) == ["/beacon/beacon_i_signal_pub", "/sleeper_i/nap_pub"]
    warnings = " ".join(w["message"] for w in data["warnings"])
    assert "/sleeper_i/nap_pub: no message in 4 s, none expected" in warnings
    assert "/beacon/beacon_i_signal_pub: no message in 4 s, none expected" in warnings

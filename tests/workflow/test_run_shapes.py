"""What ``rosaadl run`` met on the ROSMOD projects of the corpus, checked without a ROS 2 runtime
on a project of our own with the same shapes (:mod:`rosmod_shapes`): a component with no timer
publishing from its service callback is dispatched by the twin's calls of its clients, the
executor's wait loop leaves the real-time priority to the callbacks, and a timer slower than the
run is no missing message.  ``test_run_shapes_ros`` runs the same project for real."""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys

import pytest
from rosmod_shapes import CALL_PERIOD, ROOT, converted_project

from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace
from rosaadl.importers.aadl_text import read_files
from rosaadl.transforms.instantiate import instantiate
from rosaadl.workflow.run import run_plan
from rosaadl.workflow.run.session import expects_messages


@pytest.fixture(scope="module")
def relay(tmp_path_factory):
    """(the generated packages' folder, the generation result, the run plan) of the project."""
    folder = tmp_path_factory.mktemp("relay")
    aadl = converted_project(folder)
    instance = instantiate(read_files([aadl]), ROOT)
    result = generate_workspace(instance, folder / "src", options=GenerationOptions(year=2024))
    return folder / "src", result, run_plan(result.plan)


def _module(src, result, node: str) -> ast.Module:
    [cls] = [c for c in result.plan.classes if c.node_name == node]
    return ast.parse((src / cls.package / cls.package / f"{cls.module}.py").read_text())


def _function(module: ast.Module, name: str) -> ast.FunctionDef:
    """The function ``name`` of the node class (else of the module)."""
    [node] = [c for c in module.body if isinstance(c, ast.ClassDef) and "Node" in map(ast.unparse, c.bases)]
    scopes = [*node.body, *module.body]
    return next(n for n in scopes if isinstance(n, ast.FunctionDef) and n.name == name)


def test_a_server_with_no_timer_is_dispatched_as_often_as_its_callers_call(relay):
    """The answerer (no timer; its publisher is sent from its service callback) is dispatched by
    the caller's timer, in the same process, through the service: its topic has the caller's
    rate, where it had none (and a run with --emulate saw no message on it: an error)."""
    _, result, plan = relay
    rates = {t.name: t.model_rate_hz for t in plan.topics}
    assert rates["/both/caller_i_tick_pub"] == pytest.approx(1 / CALL_PERIOD)
    assert rates["/both/answerer_i_answer_pub"] == pytest.approx(1 / CALL_PERIOD)
    [both] = [c for c in result.plan.classes if c.node_name == "both"]
    callers = [t for t in both.threads if t.twin_calls]
    assert [[s.name for s in t.twin_calls] for t in callers] == [["poke_client"]]
    assert callers[0].timer == "periodic"


def test_the_emulated_dispatch_calls_its_components_services(relay):
    """The caller's generated twin table maps its timer thread to the client and its call
    method; ``emulate`` calls them after publishing, through ``twin_call``."""
    src, result, _ = relay
    module = _module(src, result, "both")
    init = ast.unparse(_function(module, "__init__"))
    assert "self.twin_calls = {" in init
    assert "(self.cli_caller_i_poke_client, self.call_caller_i_poke_client)" in init
    emulate = ast.unparse(_function(module, "emulate"))
    assert "self.twin_call(client, call)" in emulate
    twin_call = ast.unparse(_function(module, "twin_call"))
    assert "service_is_ready()" in twin_call and "twin_waiting" in twin_call
    # a node that calls nothing has an empty table and the same methods
    assert "self.twin_calls = {}" in ast.unparse(_function(_module(src, result, "slow"), "__init__"))


def test_the_executor_wait_loop_leaves_the_real_time_priority_to_the_callbacks(relay):
    """rclpy's MultiThreadedExecutor offers a ready task again and again until a worker takes it
    (ros2/rclpy#1223); under the launch prefix's ``chrt -f`` that loop kept the CPU from the
    workers on 2 CPUs (ksp_rover_controller, ten-components: the timers stopped after a second).
    ``main`` puts the loop's thread under SCHED_OTHER before it spins."""
    src, result, _ = relay
    module = _module(src, result, "both")
    calls = [ast.unparse(n.func) for n in ast.walk(_function(module, "main")) if isinstance(n, ast.Call)]
    assert calls.index("wait_loop_at_normal_priority") < calls.index("executor.spin")
    # the teardown (and its watchdog) runs at the node's priority again
    assert calls.index("restore_scheduling") < calls.index("threading.Timer")
    chrt = shutil.which("chrt")
    if chrt is None or subprocess.run([chrt, "-f", "1", "true"], capture_output=True).returncode != 0:
        pytest.skip("chrt -f is not permitted here: the policy change itself is not run")
    function = ast.unparse(_function(module, "wait_loop_at_normal_priority"))
    probe = "\n".join(
        [
            "import os",
            function,
            "assert os.sched_getscheduler(0) == os.SCHED_FIFO",
            ast.unparse(_function(module, "restore_scheduling")),
            "started = wait_loop_at_normal_priority()",
            "print(os.sched_getscheduler(0) == os.SCHED_OTHER)",
            "restore_scheduling(started)",
            "print(os.sched_getscheduler(0) == os.SCHED_FIFO)",
        ]
    )
    done = subprocess.run([chrt, "-f", "1", sys.executable, "-c", probe], capture_output=True, text=True)
    assert done.stdout.split() == ["True", "True"], done.stderr


def test_a_timer_slower_than_the_run_is_no_missing_message(relay):
    """The sleeper's ten-minute timer first fires after ten minutes: an 8 s run expects no message
    on its topic (long-running-operation's 120 s timer was an error)."""
    _, _, plan = relay
    rate = {t.name: t.model_rate_hz for t in plan.topics}["/sleeper_i/nap_pub"]
    assert rate == pytest.approx(1 / 600, rel=1e-3)
    assert not expects_messages(rate, 8.0)
    assert expects_messages(rate, 600.0) and expects_messages(2.0, 8.0)


def test_a_node_with_no_thread_publishes_where_its_subscribers_listen(relay):
    """The beacon's process has no thread (its component has a publisher only): its node uses the
    process's port, which the connection only passes (it runs from the thread group's port
    inside).  The port is remapped to the topic the listeners subscribe to; it was left on its
    relative name, a topic of its own nobody listened to (routing: the sinks heard nothing)."""
    _, result, plan = relay
    nodes = {n.node_name: n for n in result.plan.nodes}
    [(local, topic)] = nodes["beacon"].remappings
    assert local == "beacon_i_signal_pub"
    listening = {target for n in ("ear_1", "ear_2") for _, target in nodes[n].remappings}
    assert topic in listening
    [signal] = [t for t in plan.topics if t.name == topic]
    assert signal.publishers == ["/beacon"] and signal.subscribers == ["/ear_1", "/ear_2"]
    # nothing of the model dispatches the beacon: no rate, and none expected from the twin
    assert signal.model_rate_hz is None and not expects_messages(None, 8.0)


def test_a_timer_of_period_0_is_made_cancelled(relay):
    """ROSMOD's timer of period 0 (a timer the component's own code starts) is made cancelled, and
    ``start_timers`` leaves it so: a timer thread without a period refused to start its node (the
    ``timer`` project's node exited 1)."""
    src, result, plan = relay
    [slow] = [c for c in result.plan.classes if c.node_name == "slow"]
    spare = next(t for t in slow.threads if t.ident.endswith("spare_timer"))
    assert spare.timer == "periodic" and spare.dormant
    assert any("spare_timer" in d.message and "Period" in d.message for d in result.diagnostics)
    module = _module(src, result, "slow")
    init = ast.unparse(_function(module, "__init__"))
    assert "self.period_of('sleeper_i_spare_timer', dormant=True)" in init
    assert "self.timer_sleeper_i_spare_timer.cancel()" in init
    assert "is_canceled()" in ast.unparse(_function(module, "start_timers"))
    rates = {t.name: t.model_rate_hz for t in plan.topics}
    assert rates["/sleeper_i/nap_pub"] == pytest.approx(1 / 600, rel=1e-3)

"""The run plan of ``rosaadl run``: the launch file's nodes, the topics resolved as ROS 2 does, the
modelled rates propagated through the dispatching ports, and the plan file of a run folder."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import pytest

from rosaadl.exporters.rclpy import WorkspacePlan
from rosaadl.exporters.rclpy.deployment import NodeInstance
from rosaadl.exporters.rclpy.messages import InterfaceType
from rosaadl.exporters.rclpy.nodes import NodeClass, PortPlan, QoS, ServicePlan, ThreadPlan
from rosaadl.exporters.rclpy.twin import assign_twin_outputs
from rosaadl.workflow.run import PLAN_FILE, RunError, load_plan, run_plan
from rosaadl.workflow.run.plan import resolve_name, save_plan

_PROCESS = SimpleNamespace(componentInstances=[], featureInstances=[])
_POINT = InterfaceType("geometry_msgs", "msg", "Point")


def _port(local: str, direction: str, *, triggers: bool = False) -> PortPlan:
    return PortPlan(
        name=local,
        ident=local,
        direction=direction,
        category="eventDataPort",
        msg=_POINT,
        local=local,
        qos=QoS(),
        key=local,
        rel_path=(local,),
        triggers=triggers,
    )


def _thread(ident: str, timer: str | None, *ports: PortPlan, services=()) -> ThreadPlan:
    return ThreadPlan(
        name=ident,
        ident=ident,
        dispatch="",
        key=ident,
        rel_path=(ident,),
        ports=list(ports),
        services=list(services),
        timer=timer,
    )


def _node(name: str, *threads: ThreadPlan, namespace: str = "", periods=(), remap=()) -> NodeInstance:
    cls = NodeClass(
        package="pkg",
        module=name,
        class_name=name,
        executable=name,
        node_name=name,
        classifier="",
        key=name,
        threads=list(threads),
    )
    assign_twin_outputs(cls)
    parameters = [(f"{ident}.period", period) for ident, period in periods]
    return NodeInstance(
        process=_PROCESS,
        path=f"sys.{name}",
        key=name,
        cls=cls,
        node_name=name,
        namespace=namespace,
        ident=name,
        parameters=parameters,
        remappings=list(remap),
        cpus=[3],
        policy="SCHED_FIFO",
        priority=40,
    )


def _plan(*nodes: NodeInstance) -> WorkspacePlan:
    return WorkspacePlan(app="app", root=SimpleNamespace(classifier="P::S.impl", name="S"), nodes=list(nodes))


def _rates(plan) -> dict[str, float | None]:
    return {t.name: t.model_rate_hz for t in plan.topics}


def test_names_resolve_as_ros_does():
    assert resolve_name("/abs/t", "/ns", "n") == "/abs/t"
    assert resolve_name("rel", "/ns", "n") == "/ns/rel"
    assert resolve_name("rel", "", "n") == "/rel"
    assert resolve_name("~/priv", "/ns", "n") == "/ns/n/priv"


def test_rates_follow_the_dispatching_ports():
    """A periodic publisher at 20 Hz feeds a sporadic thread (20 Hz out) and a timed one (its own
    10 Hz plus 20 Hz); a server-only thread and a cycle have no known rate; a topic nobody in
    the model publishes on is an outside input."""
    source = _node(
        "source",
        _thread("tick", "periodic", _port("out", "out")),
        periods=[("tick", 0.05)],
        remap=[("out", "/raw")],
    )
    relay = _node(
        "relay",
        _thread("on_raw", None, _port("raw", "in", triggers=True), _port("cooked", "out")),
        _thread("mixed", "periodic", _port("raw2", "in", triggers=True), _port("mix", "out")),
        periods=[("mixed", 0.1)],
        namespace="/robot",
        remap=[("raw", "/raw"), ("raw2", "/raw")],
    )
    server = _node(
        "server",
        _thread(
            "serve",
            None,
            _port("answer", "out"),
            services=[
                ServicePlan(
                    name="s", ident="s", role="server", srv=_POINT, local="s", key="s", rel_path=("s",)
                )
            ],
        ),
    )
    loop = _node(
        "loop",
        _thread("a", None, _port("x", "in", triggers=True), _port("y", "out")),
        _thread("b", None, _port("y2", "in", triggers=True), _port("x2", "out")),
        _thread("c", None, _port("ext", "in", triggers=True), _port("never", "out")),
        remap=[("x", "/x"), ("x2", "/x"), ("y", "/y"), ("y2", "/y"), ("ext", "/outside")],
    )
    component = _node(  # a ROSMOD component: its publisher is its own, its timer thread sends it
        "component",
        _thread("own", None, _port("pub", "out")),
        _thread("timer", "periodic"),
        periods=[("timer", 0.5)],
    )
    component.cls.threads[0].container = True
    assign_twin_outputs(component.cls)
    plan = run_plan(_plan(source, relay, server, loop, component))
    assert _rates(plan) == {
        "/raw": 20.0,
        "/robot/cooked": 20.0,
        "/robot/mix": 30.0,
        "/answer": None,
        "/x": None,
        "/y": None,
        "/outside": None,
        "/never": None,
        "/pub": 2.0,
    }
    topics = {t.name: t for t in plan.topics}
    assert topics["/raw"].publishers == ["/source"]
    assert topics["/raw"].subscribers == ["/robot/relay"]
    assert topics["/outside"].publishers == [] and topics["/never"].publishers == ["/loop"]
    assert [n.full_name for n in plan.nodes] == ["/source", "/robot/relay", "/server", "/loop", "/component"]
    relay_launch = plan.nodes[1]
    assert (relay_launch.cpus, relay_launch.policy, relay_launch.priority) == ([3], "SCHED_FIFO", 40)
    # the threads a periodic timer dispatches (their traced release is the timer's due time)
    assert [n.timers for n in plan.nodes] == [["tick"], ["mixed"], [], [], ["timer"]]


def test_plan_round_trips_through_the_run_folder(tmp_path):
    plan = run_plan(_plan(_node("n", _thread("t", "periodic", _port("o", "out")), periods=[("t", 0.5)])))
    save_plan(plan, tmp_path)
    again = load_plan(tmp_path)
    assert again == plan
    assert again.topics[0].model_rate_hz == 2.0
    assert again.nodes[0].timers == ["t"]


def test_a_plan_written_before_the_timers_were_kept_still_loads(tmp_path):
    plan = run_plan(_plan(_node("n", _thread("t", "periodic", _port("o", "out")), periods=[("t", 0.5)])))
    document = plan.as_json()
    del document["nodes"][0]["timers"]
    (tmp_path / "rosaadl-run.json").write_text(json.dumps(document))
    assert load_plan(tmp_path).nodes[0].timers is None


def test_the_model_chains_are_kept_in_the_plan_so_a_rerun_of_the_folder_measures_them(tmp_path):
    plan = run_plan(_plan(_node("n", _thread("t", "periodic", _port("o", "out")), periods=[("t", 0.5)])))
    plan.chains = [{"name": "s.flow", "topics": [["/a", "/n", "/m"], ["/b", "/m", "/k"]]}]
    save_plan(plan, tmp_path)
    assert load_plan(tmp_path).chains == plan.chains
    older = json.loads((tmp_path / PLAN_FILE).read_text(encoding="utf-8"))
    del older["chains"]  # a plan written before the chains were kept
    (tmp_path / PLAN_FILE).write_text(json.dumps(older), encoding="utf-8")
    assert load_plan(tmp_path).chains == []


@pytest.mark.parametrize(
    "text",
    [
        "",
        "{",
        "[]",
        '{"version": 99}',
        '{"version": 1, "app": "a", "model": "m", "nodes": [{"x": 1}], "topics": []}',
        '{"version": 1, "app": "a", "model": "m", "nodes": [], "topics": [], "chains": [{"name": "c"}]}',
    ],
    ids=["empty", "truncated", "list", "version", "fields", "chain"],
)
def test_a_broken_plan_file_is_a_located_error(tmp_path, text):
    (tmp_path / PLAN_FILE).write_text(text, encoding="utf-8")
    with pytest.raises(RunError) as caught:
        load_plan(tmp_path)
    assert caught.value.location.file == str(tmp_path / PLAN_FILE)


def test_a_folder_without_plan_is_not_a_run_folder(tmp_path):
    with pytest.raises(RunError, match="not a folder made by `rosaadl run`"):
        load_plan(tmp_path)


def test_tracking_plan_has_the_launch_files_nodes(tmp_path):
    """On the library's tracking application: the nodes, remappings and rates of its launch file."""
    from rosaadl.exporters.rclpy import plan_workspace
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    library = read_files([])
    instance = instantiate(library, "sys_tracking::tracking.impl")
    workspace = plan_workspace(instance)
    plan = run_plan(workspace)
    launch = workspace.file(f"{workspace.app}_bringup/launch/{workspace.app}.launch.py").text
    for node in plan.nodes:
        assert f"name='{node.name}'" in launch
        for source, target in node.remappings:
            assert f"('{source}', '{target}')" in launch
    rates = _rates(plan)
    assert rates["/ocv_color_tracking/point_out"] == 10.0
    assert rates["/usb_cam/image_raw"] == pytest.approx(30.0, rel=1e-3)
    assert {t.name: t.model_bytes for t in plan.topics}["/usb_cam/image_raw"] > 100_000
    json.dumps(plan.as_json())


def test_a_prepared_run_folder_keeps_the_model_chains(tmp_path):
    """``prepare_run`` saves the tracking flow as the topics it crosses between the nodes."""
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate
    from rosaadl.workflow.run import prepare_run

    instance = instantiate(read_files([]), "sys_tracking::tracking.impl")
    prepare_run(instance, tmp_path)
    assert load_plan(tmp_path).chains == [
        {
            "name": "rem_trk_sw.etef_tracking",
            "topics": [
                ["/usb_cam/image_raw", "/usb_cam", "/ocv_color_tracking"],
                ["/ocv_color_tracking/point_out", "/ocv_color_tracking", "/pos_to_cmd"],
            ],
        }
    ]


def test_the_monitor_keeps_off_the_cpus_of_the_nodes_work():
    from rosaadl.workflow.run.cores import Machine, quietest_cpus
    from rosaadl.workflow.run.monitor import monitor_command
    from rosaadl.workflow.run.plan import NodeLaunch

    def node(name, cpus):
        return NodeLaunch(name=name, namespace="/", package="p", executable=name, path=name, cpus=cpus)

    here = Machine(cpus=[0, 1, 2])
    nodes = [node("a", [0]), node("b", [4]), node("c", None)]  # core 4 of the model: CPU 1 here
    assert quietest_cpus(nodes, here, {}) == [2]
    two = Machine(cpus=[0, 1])
    assert quietest_cpus(nodes, two, {}) == [1]  # core 4 of the model: CPU 0 here
    nodes.append(node("d", [1]))
    assert quietest_cpus(nodes, two, {0: 40.0, 1: 4.0}) == [1]
    assert quietest_cpus(nodes, two, {0: 4.0, 1: 40.0}) == [0]
    assert quietest_cpus([node("c", None)], two, {}) == []  # nothing pinned: the monitor is not
    assert monitor_command(Path("s"), Path("o"), [1])[-3:] == ["s", "o", "1"]
    assert monitor_command(Path("s"), Path("o"))[-2:] == ["s", "o"]

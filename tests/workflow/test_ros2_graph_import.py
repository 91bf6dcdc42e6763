"""``import ros2-graph``: a live graph of small rclpy processes started by the test (a random
``ROS_DOMAIN_ID`` each, away from other tests on the machine), and the faults of a graph (a node
that leaves during discovery, a topic with two types, no node, no rclpy) without ROS 2."""

from __future__ import annotations

import os
import random
import subprocess
import sys
import time
from decimal import Decimal
from pathlib import Path
from types import SimpleNamespace

import pytest

from rosaadl.cli import main
from rosaadl.errors import ImportFormatError, RosaadlError
from rosaadl.workflow import ros2_graph

NODES = """
import sys
import rclpy
from rclpy.lifecycle import LifecycleNode
from rclpy.node import Node
from rcl_interfaces.srv import GetParameters
from std_msgs.msg import Int32, String


class Talker(Node):
    def __init__(self):
        super().__init__('talker', namespace='/demo')
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.create_timer(0.05, self.tick)

    def tick(self):
        self.pub.publish(String(data='x' * 40))


class Listener(Node):
    def __init__(self):
        super().__init__('listener', namespace='/demo')
        self.create_subscription(String, 'chatter', lambda msg: None, 10)
        self.create_service(GetParameters, 'lookup', lambda req, res: res)


class Mixed(Node):
    def __init__(self):
        super().__init__('mixed')
        self.a = self.create_publisher(String, '/mixed', 10)
        self.c = self.create_client(GetParameters, '/demo/lookup')


class Managed(LifecycleNode):
    def __init__(self):
        super().__init__('managed', namespace='/demo')
        self.create_subscription(String, 'chatter', lambda msg: None, 10)


class MixedToo(Node):
    def __init__(self):
        super().__init__('mixed_too')
        self.b = self.create_publisher(Int32, '/mixed', 10)


rclpy.init()
# one DDS participant refuses a second type on a topic: the other type comes from another process
nodes = [MixedToo()] if sys.argv[1:] == ['other'] else [Talker(), Listener(), Mixed(), Managed()]
executor = rclpy.executors.SingleThreadedExecutor()
for node in nodes:
    executor.add_node(node)
print('ready', flush=True)
try:
    executor.spin()
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
"""


def _domain() -> int:
    return random.SystemRandom().randint(101, 230)


@pytest.fixture
def graph(tmp_path):
    """The nodes above running in one process, on a domain of their own: its id."""
    pytest.importorskip("rclpy", reason="rclpy (ROS 2) is not installed: no live graph to read")
    script = tmp_path / "nodes.py"
    script.write_text(NODES)
    domain = _domain()
    env = {**os.environ, "ROS_DOMAIN_ID": str(domain)}
    processes = [
        subprocess.Popen(
            [sys.executable, str(script), *extra],
            env=env,
            cwd=tmp_path,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for extra in ([], ["other"])
    ]
    try:
        for process in processes:
            assert process.stdout.readline().strip() == "ready", process.stderr.read()
        yield domain
    finally:
        for process in processes:
            process.terminate()
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()


def _components(project) -> dict:
    return {c.name: c for p in project.software.packages for c in p.components}


def _ports(component) -> list[tuple[str, str, str]]:
    topics = {p.key: p.value for p in component.properties}
    return sorted((p.eClass.name, p.type, topics[f"{p.name}.Topic"]) for p in component.ports)


@pytest.mark.slow
@pytest.mark.ros_runtime  # measured rates: run with the other runtime tests, on a quiet machine
def test_live_graph_nodes_topics_services_rates_and_sizes(graph, tmp_path):
    warnings: list = []
    started = time.monotonic()
    for wait in (3.0, 6.0, 12.0):  # discovery on a loaded machine may take longer: again, longer
        warnings.clear()
        try:
            project = ros2_graph.read_graph(wait=wait, domain_id=graph, measure=1.5, warnings=warnings)
        except ImportFormatError:
            continue
        comps = _components(project)
        if len(comps) == 5:
            break
    assert time.monotonic() - started < 60
    assert sorted(comps) == ["listener", "managed", "mixed", "mixed_too", "talker"]
    assert _ports(comps["talker"]) == [("Publisher", "std_msgs/String", "/demo/chatter")]
    assert _ports(comps["listener"]) == [
        ("Server", "rcl_interfaces/GetParameters", "/demo/lookup"),
        ("Subscriber", "std_msgs/String", "/demo/chatter"),
    ]
    assert _ports(comps["mixed"]) == [("Client", "rcl_interfaces/GetParameters", "/demo/lookup")]
    assert _ports(comps["mixed_too"]) == []
    # a managed node keeps its own ports; its lifecycle services and topic are named, left out
    assert _ports(comps["managed"]) == [("Subscriber", "std_msgs/String", "/demo/chatter")]
    qos = {p.key: p.value for p in comps["talker"].properties}
    assert (qos["demo_chatter.Reliability"], qos["demo_chatter.Durability"]) == ("reliable", "volatile")
    # the 50 ms publisher gets a timer within 10 % of its period
    [timer] = comps["talker"].timers
    assert abs(timer.period - Decimal("0.05")) <= Decimal("0.005")
    # a 40-character string: 4 (length) + 41 bytes, padded as CDR pads it
    sizes = {p.key: p.value for p in project.properties}
    assert 45 <= int(sizes["Data_Size:std_msgs/String"]) <= 48
    messages = [w.message for w in warnings]
    assert any("disagree on its type" in m for m in messages)
    assert any("host" in m and "profiles" in m for m in messages)
    assert [w.location.path for w in warnings if "lifecycle" in w.message] == ["/demo/managed"]
    # the model converts to AADL: the talker's port joined to the listener's
    from rosaadl.transforms import rosmod_to_aadl

    converted = rosmod_to_aadl.rosmod_to_aadl(project)
    [data] = [c for u in converted.model.units for c in getattr(u, "classifiers", []) if c.name == "String"]
    [size] = [a for a in data.ownedPropertyAssociations if a.property.endswith("Data_Size")]
    assert size.ownedValues[0].value.value == int(sizes["Data_Size:std_msgs/String"])


# --------------------------------------------------------------------------- without ROS 2


class _FakeNode:
    """The graph API of an rclpy node over a fixed graph; ``gone`` nodes leave during discovery."""

    def __init__(self, graph: dict, gone: set[str]) -> None:
        self.graph = graph
        self.gone = gone

    def get_fully_qualified_name(self) -> str:
        return "/rosaadl_graph"

    def get_node_names_and_namespaces(self):
        return [(name.rpartition("/")[2], name.rpartition("/")[0] or "/") for name in self.graph]

    def _of(self, kind: str, name: str, namespace: str):
        full = namespace.rstrip("/") + "/" + name
        if full in self.gone:
            raise RuntimeError(f"Node name not found: {full}")
        return self.graph[full].get(kind, [])

    def get_publisher_names_and_types_by_node(self, name, namespace):
        return self._of("pub", name, namespace)

    def get_subscriber_names_and_types_by_node(self, name, namespace):
        return self._of("sub", name, namespace)

    def get_service_names_and_types_by_node(self, name, namespace):
        return self._of("srv", name, namespace)

    def get_client_names_and_types_by_node(self, name, namespace):
        return self._of("cli", name, namespace)

    def get_publishers_info_by_topic(self, topic):
        return []

    get_subscriptions_info_by_topic = get_publishers_info_by_topic


def _observe(graph: dict, gone: set[str] = frozenset()):
    warnings: list = []
    observer = ros2_graph._Observer(SimpleNamespace(), _FakeNode(graph, set(gone)), warnings)
    observer.read()
    return observer.facts, warnings


def test_a_node_that_leaves_during_discovery_is_a_located_warning():
    facts, warnings = _observe(
        {
            "/a": {"pub": [("/t", ["std_msgs/msg/String"]), ("/rosout", ["rcl_interfaces/msg/Log"])]},
            "/b": {"sub": [("/t", ["std_msgs/msg/String"])]},
            "/_ros2cli_daemon_0": {"pub": [("/t", ["std_msgs/msg/String"])]},
        },
        gone={"/b"},
    )
    assert sorted(facts.nodes) == ["/a"]
    assert [(p.kind, p.type, p.topic) for p in facts.nodes["/a"].ports] == [
        ("Publisher", "std_msgs/String", "/t")
    ]
    assert [(w.location.path, "left the graph" in w.message) for w in warnings] == [("/b", True)]


def test_a_topic_with_two_types_is_left_out_with_a_located_warning():
    facts, warnings = _observe(
        {
            "/a": {
                "pub": [
                    ("/t", ["std_msgs/msg/String"]),
                    ("/both", ["std_msgs/msg/String", "std_msgs/msg/Int32"]),
                ]
            },
            "/b": {"sub": [("/t", ["std_msgs/msg/Int32"])], "srv": [("/b/get_parameters", ["x/srv/Y"])]},
        }
    )
    assert facts.nodes["/a"].ports == [] and facts.nodes["/b"].ports == []
    paths = sorted(w.location.path for w in warnings)
    assert paths == ["/a", "/t"]


def test_actions_lifecycle_and_hidden_names_are_left_out_each_named_once_on_its_node():
    """As rclpy's graph API gives them: an action server's and client's hidden services and
    topics, a managed node's lifecycle interface, a hidden topic."""
    fib = "tut/action/Fibonacci"
    facts, warnings = _observe(
        {
            "/server": {
                "pub": [
                    ("/fib/_action/feedback", [f"{fib}_FeedbackMessage"]),
                    ("/fib/_action/status", ["action_msgs/msg/GoalStatusArray"]),
                    ("/server/transition_event", ["lifecycle_msgs/msg/TransitionEvent"]),
                    ("/odom", ["nav_msgs/msg/Odometry"]),
                ],
                "srv": [
                    ("/fib/_action/cancel_goal", ["action_msgs/srv/CancelGoal"]),
                    ("/fib/_action/get_result", [f"{fib}_GetResult"]),
                    ("/fib/_action/send_goal", [f"{fib}_SendGoal"]),
                    ("/server/change_state", ["lifecycle_msgs/srv/ChangeState"]),
                    ("/server/get_state", ["lifecycle_msgs/srv/GetState"]),
                    ("/server/get_transition_graph", ["lifecycle_msgs/srv/GetAvailableTransitions"]),
                ],
            },
            "/client": {
                "sub": [
                    ("/fib/_action/feedback", [f"{fib}_FeedbackMessage"]),
                    ("/fib/_action/status", ["action_msgs/msg/GoalStatusArray"]),
                    ("/_debug/state", ["std_msgs/msg/String"]),
                ],
                "cli": [
                    ("/fib/_action/cancel_goal", ["action_msgs/srv/CancelGoal"]),
                    ("/fib/_action/send_goal", [f"{fib}_SendGoal"]),
                ],
            },
        }
    )
    assert [(p.kind, p.topic) for p in facts.nodes["/server"].ports] == [("Publisher", "/odom")]
    assert facts.nodes["/client"].ports == []
    assert sorted((w.location.path, w.message) for w in warnings) == [
        ("/client", "action client /fib (tut/action/Fibonacci): a ROSMOD model has no actions; left out"),
        ("/client", "hidden topic /_debug/state (std_msgs/msg/String): left out"),
        ("/server", "a managed (lifecycle) node: its lifecycle services and transition_event topic "
         "are left out (a ROSMOD model has no lifecycle states)"),
        ("/server", "action server /fib (tut/action/Fibonacci): a ROSMOD model has no actions; left out"),
    ]  # fmt: skip


def test_an_actions_name_and_type_from_each_of_its_services_and_topics():
    assert ros2_graph.action_of("/ns/fib/_action/send_goal", "p/action/Fib_SendGoal") == (
        "/ns/fib",
        "p/action/Fib",
    )
    assert ros2_graph.action_of("/fib/_action/status", "action_msgs/msg/GoalStatusArray") == ("/fib", None)
    assert ros2_graph.action_of("/fib/action/send_goal", "p/action/Fib_SendGoal") is None
    assert ros2_graph.hidden("/a/_b") and ros2_graph.hidden("/_a") and not ros2_graph.hidden("/a_b/c_")


def test_no_rclpy_is_a_clear_error_and_exit_1(monkeypatch, tmp_path, capsys):
    monkeypatch.setitem(sys.modules, "rclpy", None)
    with pytest.raises(RosaadlError, match="rclpy is not installed"):
        ros2_graph.read_graph(warnings=[])
    out = tmp_path / "graph.xmi"
    assert main(["import", "ros2-graph", "--wait", "0", "-o", str(out)]) == 1
    assert "rclpy is not installed" in capsys.readouterr().err and not out.exists()


def test_an_empty_graph_is_an_error_and_no_output(monkeypatch, tmp_path, capsys):
    monkeypatch.setattr(ros2_graph, "observe_graph", lambda **_: ros2_graph.SystemFacts("ros2_graph"))
    with pytest.raises(ImportFormatError, match="no ROS 2 node"):
        ros2_graph.read_graph(wait=0.1, warnings=[])
    out = tmp_path / "graph.json"
    assert main(["import", "ros2-graph", "--wait", "0.1", "--domain-id", "5", "-o", str(out)]) == 1
    assert "no ROS 2 node" in capsys.readouterr().err and not out.exists()


def test_the_graph_reader_is_in_the_workflow_layer():
    assert Path(ros2_graph.__file__).parent.name == "workflow"


# --------------------------------------------------------------------------- steady rates


def _arrivals(gaps: list[float]) -> list[float]:
    times = [0.0]
    for gap in gaps:
        times.append(times[-1] + gap)
    return times


def test_a_jittery_timer_is_periodic_with_its_mean_period():
    chance = random.Random(7)
    gaps = [0.05 + chance.uniform(-0.004, 0.004) for _ in range(100)]
    period = ros2_graph.steady_period(_arrivals(gaps))
    assert period == pytest.approx(0.05, rel=0.01)


def test_a_stall_of_the_machine_and_the_burst_after_it_keep_the_period():
    """One 2.4 s gap (a stalled machine: the timer skips the periods it missed), then five
    messages queued meanwhile delivered at once: the mean gap is half again the period and the spread several
    times the period, but the publisher is still the 20 Hz timer it is."""
    gaps = [0.05] * 40 + [2.4] + [0.0005] * 5 + [0.05] * 40
    assert ros2_graph.steady_period(_arrivals(gaps)) == pytest.approx(0.05)
    assert sum(gaps) / len(gaps) > 1.4 * 0.05


def test_irregular_arrivals_have_no_period():
    chance = random.Random(3)
    assert ros2_graph.steady_period(_arrivals([chance.expovariate(20) for _ in range(200)])) is None
    assert ros2_graph.steady_period(_arrivals([0.01, 0.1] * 50)) is None
    assert ros2_graph.steady_period([1.0]) is None
    assert ros2_graph.steady_period([1.0, 1.0, 1.0]) is None

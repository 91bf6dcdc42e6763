"""``import ros2-package`` on rclpy code rosaadl did not write (``tests/data/ros2_tutorial``, nodes
written as the ROS 2 tutorials write them), on code with extra parts, and on bad input."""

from __future__ import annotations

import os
import subprocess
import sys
from decimal import Decimal
from pathlib import Path

import pytest

from rosaadl.cli import main
from rosaadl.errors import ImportFormatError
from rosaadl.importers.ros2_package import read_ros2_packages, sources
from rosaadl.transforms import rosmod_to_aadl

TUTORIAL = Path(__file__).resolve().parent.parent / "data" / "ros2_tutorial"
PUBSUB = TUTORIAL / "src" / "py_pubsub"


def _components(project) -> dict:
    return {c.name: c for p in project.software.packages for c in p.components}


def _ports(component) -> list[tuple[str, str, str]]:
    topics = {p.key: p.value for p in component.properties}
    return sorted((p.eClass.name, p.type, topics[f"{p.name}.Topic"]) for p in component.ports)


def _timers(component) -> list[tuple[str, Decimal | None]]:
    return [(t.name, t.period if t.eIsSet("period") else None) for t in component.timers]


def _where(warnings) -> dict[tuple[str, int | None], str]:
    return {(Path(w.location.file).name, w.location.line): w.message for w in warnings if w.location.file}


@pytest.fixture(scope="module")
def tutorial():
    warnings: list = []
    return read_ros2_packages([TUTORIAL], warnings), warnings


def test_every_tutorial_node_is_read_with_its_ports_and_timers(tutorial):
    project, _ = tutorial
    comps = _components(project)
    assert sorted(comps) == [
        "adder",
        "fan_out",
        "listener",
        "minimal_client_async",
        "minimal_param_node",
        "minimal_publisher_old_school",
        "talker",
    ]
    assert _ports(comps["talker"]) == [("Publisher", "std_msgs/String", "/demo/chatter")]
    assert _timers(comps["talker"]) == [("timer", Decimal("0.5"))]
    assert _ports(comps["listener"]) == [("Subscriber", "std_msgs/String", "/demo/chatter")]
    qos = {p.key: p.value for p in comps["listener"].properties}
    assert (qos["subscription.Reliability"], qos["subscription.Durability"], qos["subscription.Depth"]) == (
        "best_effort",
        "transient_local",
        "5",
    )
    assert _ports(comps["adder"]) == [("Server", "example_interfaces/AddTwoInts", "/add_two_ints")]
    client = _ports(comps["minimal_client_async"])
    assert client == [("Client", "example_interfaces/AddTwoInts", "/add_two_ints")]
    assert _ports(comps["minimal_publisher_old_school"]) == [("Publisher", "std_msgs/String", "/topic")]
    # the launch file sets the period parameter: 0.1 s instead of the declared 0.2 s
    param = comps["minimal_param_node"]
    assert _timers(param) == [("timer", Decimal("0.1")), ("slow_timer", None)]
    assert _ports(param) == [("Publisher", "sensor_msgs/Imu", "/imu")]
    assert [d.name for d in project.deployments] == ["pubsub"]


def test_what_the_source_does_not_decide_is_a_located_warning(tutorial):
    _, warnings = tutorial
    where = _where(warnings)
    assert "in a loop" in where[("fan_out.py", 17)]
    assert "random.random()" in where[("fan_out.py", 18)]
    assert "message_type" in where[("fan_out.py", 19)]
    assert "the name topic is not known" in where[("param_talker.py", 22)]
    assert "computed from parameter 'period'" in where[("pubsub.launch.py", 22)]
    assert "not literal" in where[("pubsub.launch.py", 20)]
    assert "turtlesim/turtlesim_node" in where[("pubsub.launch.py", 29)]
    assert "XML or YAML" in where[("pubsub.launch.xml", None)]
    assert all(w.severity == "warning" for w in warnings)


def test_the_tutorial_model_converts_to_aadl_with_the_topic_connected(tutorial):
    project, _ = tutorial
    converted = rosmod_to_aadl.rosmod_to_aadl(project)
    assert converted.roots
    from rosaadl.exporters.aadl_text import write_unit

    text = "\n".join(write_unit(u) for u in converted.model.units if u.eClass.name == "AadlPackage")
    assert "talker" in text and "listener" in text and "->" in text


GENERATED_STYLE = """
import time
import rclpy
from rclpy.node import Node
from my_interfaces.msg import Sample

PAYLOAD = 64


def fill(msg, size):
    msg.data = bytes(size)
    return msg


class Worker(Node):
    def __init__(self, **kwargs):
        super().__init__('worker', **kwargs)
        self.declare_parameter('rosaadl.emulate', False)
        self.declare_parameter('work.period', 0.25)
        self.pub = self.create_publisher(Sample, 'work/out', 3)
        self.timer = self.create_timer(self.period_of('work'), self.on_work)
        self.once = self.create_timer(0.0, self.on_start)

    def period_of(self, thread):
        period = float(self.get_parameter(thread + '.period').value)
        if period <= 0.0:
            raise ValueError(thread)
        return period

    def on_start(self):
        self.once.cancel()

    def on_work(self):
        started = time.monotonic()
        if self.get_parameter('rosaadl.emulate').value:
            self.pub.publish(fill(Sample(), PAYLOAD))
"""


def test_helpers_extra_parameters_and_one_shot_timers_are_tolerated(tmp_path):
    package = tmp_path / "worker_pkg"
    (package / "worker_pkg").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>worker_pkg</name></package>")
    (package / "worker_pkg" / "worker.py").write_text(GENERATED_STYLE)
    warnings: list = []
    comps = _components(read_ros2_packages([package], warnings))
    assert _ports(comps["worker"]) == [("Publisher", "my_interfaces/Sample", "/work/out")]
    assert _timers(comps["worker"]) == [("timer", Decimal("0.25"))]
    assert [w.message for w in warnings] == [
        "one-shot timer once (its callback on_start cancels it): not a periodic timer; left out"
    ]


SHADOWED = """import rclpy
from rclpy.node import Node
from std_msgs.msg import String

TOPIC = 'chatter'


def helper():
    TOPIC = 'other'
    return TOPIC


class Talker(Node):
    LABEL = 'x'

    def __init__(self):
        super().__init__('talker')
        self.pub = self.create_publisher(String, TOPIC, 10)


def main():
    rclpy.init()
    rclpy.spin(Talker())
"""


def test_a_module_constant_is_not_lost_to_a_local_of_the_same_name(tmp_path):
    """A function's or class's own names are not the module's: the constant TOPIC stays known
    though ``helper`` binds a local TOPIC (it was "not known" once definitions counted)."""
    package = _package(tmp_path, "<package format='3'><name>pkg</name></package>", SHADOWED)
    warnings: list = []
    comps = _components(read_ros2_packages([package], warnings))
    assert _ports(comps["talker"]) == [("Publisher", "std_msgs/String", "/chatter")]
    assert not [w for w in warnings if "TOPIC" in w.message], warnings


# --------------------------------------------------------------------------- bad input


def _package(tmp_path: Path, manifest: str, source: str = "") -> Path:
    folder = tmp_path / "pkg"
    (folder / "pkg").mkdir(parents=True)
    (folder / "package.xml").write_text(manifest)
    (folder / "pkg" / "node.py").write_text(source or GENERATED_STYLE)
    return folder


BOMB = """<?xml version="1.0"?>
<!DOCTYPE package [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>
<package format="3"><name>&b;</name></package>
"""


@pytest.mark.parametrize(
    ("manifest", "expected"),
    [
        (BOMB, "entities"),
        ("<package><name>pkg</name>", "malformed XML"),
        ("", "empty"),
        ("<other/>", "not <package>"),
        ("<package><name>../../etc</name></package>", "not a ROS package name"),
    ],
    ids=["entities", "truncated", "empty", "not-a-package", "bad-name"],
)
def test_a_bad_manifest_is_a_located_error_and_nothing_is_imported(tmp_path, manifest, expected):
    folder = _package(tmp_path, manifest)
    with pytest.raises(ImportFormatError) as caught:
        read_ros2_packages([folder], [])
    messages = [str(e) for e in caught.value.errors]
    assert any(expected in m and "package.xml" in m for m in messages), messages


def test_a_syntax_error_is_located_and_the_other_files_are_read(tmp_path):
    folder = _package(tmp_path, "<package><name>pkg</name></package>")
    (folder / "pkg" / "broken.py").write_text("import rclpy\n\nclass Broken(:\n    pass\n")
    warnings: list = []
    assert "worker" in _components(read_ros2_packages([folder], warnings))
    assert ("broken.py", 3) in _where(warnings)


def test_a_link_out_of_the_folder_and_a_huge_file_are_not_read(tmp_path, monkeypatch):
    folder = _package(tmp_path, "<package><name>pkg</name></package>")
    outside = tmp_path / "outside.py"
    outside.write_text(GENERATED_STYLE.replace("'worker'", "'stolen'"))
    os.symlink(outside, folder / "pkg" / "link.py")
    (folder / "pkg" / "huge.py").write_text("x = 1\n" * 1000)
    monkeypatch.setattr(sources, "MAX_FILE_BYTES", 4000)
    warnings: list = []
    comps = _components(read_ros2_packages([folder], warnings))
    assert "stolen" not in comps
    where = _where(warnings)
    assert "outside the folders given" in where[("link.py", None)]
    assert "bytes" in where[("huge.py", None)]


def test_cli_imports_and_refuses(tmp_path, capsys):
    out = tmp_path / "tutorial.xmi"
    assert main(["import", "ros2-package", str(TUTORIAL), "-o", str(out)]) == 0
    assert out.is_file()
    assert main(["check", str(PUBSUB)]) == 0
    assert "warning" in capsys.readouterr().out
    bad = _package(tmp_path, BOMB)
    out = tmp_path / "bad.xmi"
    assert main(["import", "ros2-package", str(bad), "-o", str(out)]) == 1
    assert not out.exists()
    err = capsys.readouterr().err
    assert "package.xml:1" in err and "Traceback" not in err
    assert main(["check", str(bad)]) == 1
    assert main(["import", "ros2-package", str(tmp_path / "none"), "-o", str(out)]) == 2


def test_convert_takes_the_imported_model_and_the_packages_themselves(tmp_path, capsys):
    model_file = tmp_path / "tutorial.json"
    assert main(["-q", "import", "ros2-package", str(TUTORIAL), "-o", str(model_file)]) == 0
    for source, out in ((model_file, tmp_path / "from_model"), (TUTORIAL, tmp_path / "from_packages")):
        assert main(["-q", "convert", str(source), "-o", str(out)]) == 0, capsys.readouterr().err
        deployment = (out / "pubsub_deployment.aadl").read_text()
        assert "port talker." in deployment and "-> listener." in deployment


def test_measured_sizes_become_the_data_size_of_types_without_a_fixed_one():
    from rosaadl.importers import ros_msg
    from rosaadl.importers.ros2_package.building import build_project
    from rosaadl.importers.ros2_package.facts import NodeFact, PortFact, SystemFacts

    facts = SystemFacts("measured")
    facts.nodes["/a"] = NodeFact("/a", "a", ports=[PortFact("Publisher", "std_msgs/String", "/t")])
    facts.nodes["/b"] = NodeFact("/b", "b", ports=[PortFact("Subscriber", "std_msgs/String", "/t")])
    facts.message_sizes = {"std_msgs/String": 28}
    project = build_project(facts, [])
    assert ros_msg.measured_sizes(project) == {"std_msgs/String": 28}
    converted = rosmod_to_aadl.rosmod_to_aadl(project)
    [data] = [c for u in converted.model.units for c in getattr(u, "classifiers", []) if c.name == "String"]
    [size] = [a for a in data.ownedPropertyAssociations if a.property.endswith("Data_Size")]
    assert size.ownedValues[0].value.value == 28
    project.properties[0].value = "-3"
    assert ros_msg.measured_sizes(project) == {}


def test_a_launch_node_through_a_wrapper_that_passes_its_keywords_on():
    """A module function taking ``**kwargs`` and handing them to ``launch_ros``'s ``Node`` (the
    generated launch files fit the prefix to the machine that way) is a launch ``Node``; its own
    forwarding call is not one (no warning for it)."""
    import ast

    from rosaadl.importers.ros2_package.launching import launch_actions

    text = (
        "from launch import LaunchDescription\n"
        "from launch_ros.actions import Node as RosNode\n"
        "def Node(**kwargs):\n"
        "    kwargs['prefix'] = 'taskset -c 0'\n"
        "    return RosNode(**kwargs)\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([Node(package='p', executable='e', name='renamed',\n"
        "                                   remappings=[('a', 'b')])])\n"
    )
    warnings: list = []
    actions = launch_actions(ast.parse(text), "x.launch.py", warnings)
    assert [(a.package, a.executable, a.name, a.remappings) for a in actions] == [
        ("p", "e", "renamed", {"a": "b"})
    ]
    assert warnings == []


SCRIPT_MAKES_THREE = """import rclpy
from rclpy.node import Node


class Alpha(Node):
    def __init__(self):
        super().__init__('alpha')


class Beta(Node):
    def __init__(self):
        super().__init__('beta')


class Gamma(Node):
    def __init__(self):
        super().__init__('gamma')


rclpy.init()
nodes = [Alpha(), Beta(), Gamma()]
"""

_READ_SCRIPT = """
import ast, sys
from rosaadl.importers.ros2_package.node_classes import SCRIPT, read_module
module = read_module(ast.parse(sys.argv[1]), "three.py", "pkg", [])
print(module.functions[SCRIPT])
"""


def test_the_nodes_a_script_makes_come_in_one_order_whatever_the_hash_seed():
    """The classes a module run as a script makes are listed in the order the source has them,
    the same under every string hash seed (a set's order changed from run to run)."""
    seen = set()
    for seed in ("1", "2", "3"):
        done = subprocess.run(
            [sys.executable, "-c", _READ_SCRIPT, SCRIPT_MAKES_THREE],
            capture_output=True,
            text=True,
            env={**os.environ, "PYTHONHASHSEED": seed},
            check=True,
        )
        seen.add(done.stdout.strip())
    assert seen == {"['Alpha', 'Beta', 'Gamma']"}

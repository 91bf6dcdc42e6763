"""``import ros2-package`` on the other ways rclpy users write nodes, packages and launch files
(``tests/data/ros2_styles``): lifecycle nodes, names given to a constructor, class attributes,
QoS profiles bound to names, several nodes in one ``main``, a script with its node at module level
installed by CMake, entry points in ``setup.cfg``, actions, launch groups and arguments."""

from __future__ import annotations

import ast
from decimal import Decimal
from pathlib import Path

import pytest

from rosaadl.importers.ros2_package import read_ros2_packages
from rosaadl.importers.ros2_package.evaluation import Scope
from rosaadl.importers.ros2_package.launching import cmake_programs, launch_actions, setup_cfg_entry_points
from rosaadl.importers.ros2_package.node_classes import SCRIPT, dotted, module_imports, read_module
from rosaadl.importers.ros2_package.qos import read_qos

STYLES = Path(__file__).resolve().parent.parent / "data" / "ros2_styles"


@pytest.fixture(scope="module")
def styles():
    warnings: list = []
    return read_ros2_packages([STYLES], warnings), warnings


def _read_text(read, text: str, file: str) -> tuple[object, dict[int | None, str]]:
    """What ``read(tree, file, warnings)`` gives for the source ``text``, and its warnings by line."""
    warnings: list = []
    found = read(ast.parse(text), file, warnings)
    return found, {w.location.line: w.message for w in warnings}


def _components(project) -> dict:
    return {c.name: c for p in project.software.packages for c in p.components}


def _ports(component) -> list[tuple]:
    props = {p.key: p.value for p in component.properties}
    return sorted(
        (
            p.eClass.name,
            p.type,
            props[f"{p.name}.Topic"],
            props.get(f"{p.name}.Depth"),
            props.get(f"{p.name}.Reliability"),
        )
        for p in component.ports
    )


def _timers(component) -> list[Decimal | None]:
    return [t.period if t.eIsSet("period") else None for t in component.timers]


def _where(warnings) -> dict[tuple[str, int | None], list[str]]:
    found: dict = {}
    for w in warnings:
        found.setdefault((Path(w.location.file).name, w.location.line), []).append(w.message)
    return found


def test_every_style_is_read_with_its_names_qos_and_periods(styles):
    project, _ = styles
    comps = _components(project)
    assert sorted(comps) == ["beacon", "heartbeat", "imu_relay", "mission", "named", "ping", "pong", "walker"]
    # a class deriving from a node class of another module: that class's __init__ runs with the
    # arguments super().__init__ gives it; the base class is no node of its own
    assert _ports(comps["walker"]) == [
        ("Publisher", "geometry_msgs/Twist", "/cmd_vel", "10", "reliable"),
        ("Publisher", "std_msgs/Empty", "/alive", "1", "reliable"),
    ]
    assert _timers(comps["walker"]) == [Decimal("0.05")]
    # a topic named by a parameter's default, which the launch file sets; one computed from a
    # parameter the launch file sets is left out (named in a warning)
    assert _ports(comps["named"]) == [("Publisher", "std_msgs/String", "/health", "10", "reliable")]
    # a LifecycleNode named by main (renamed by the launch file's LifecycleNode action), in the
    # namespace it gives itself; its period 1 / RATE_HZ (a class attribute)
    assert _ports(comps["beacon"]) == [("Publisher", "std_msgs/Header", "/fleet/beacon", "1", "reliable")]
    assert _timers(comps["beacon"]) == [Decimal("0.25")]
    # topics from the constructor's argument and default; QoS through names; the launch group's namespace
    assert _ports(comps["imu_relay"]) == [
        ("Publisher", "sensor_msgs/Imu", "/rover/audit", None, None),
        ("Publisher", "sensor_msgs/Imu", "/rover/relayed", "5", "best_effort"),
        ("Subscriber", "sensor_msgs/Imu", "/rover/imu/raw", "3", "best_effort"),
    ]
    # two nodes of one main, each with its own ports; the second in its own namespace
    assert _ports(comps["ping"]) == [("Publisher", "std_msgs/String", "/ball", "10", "reliable")]
    assert _timers(comps["ping"]) == [Decimal("0.25")]
    assert _ports(comps["pong"]) == [("Subscriber", "std_msgs/String", "/court/ball", "10", "reliable")]
    # a module-level script installed by CMake; its period parameter set by a launch argument's default
    assert _ports(comps["heartbeat"]) == [("Publisher", "std_msgs/Empty", "/rover/pulse", "1", "reliable")]
    assert _timers(comps["heartbeat"]) == [Decimal("0.5")]
    assert _ports(comps["mission"]) == [("Server", "example_interfaces/Trigger", "/abort", None, None)]
    [deployment] = project.deployments
    assert sorted(n.name for n in deployment.nodes) == [
        "beacon",
        "heartbeat",
        "imu_relay",
        "named",
        "ping",
        "pong",
    ]


def test_what_the_styles_leave_out_is_named_at_its_line(styles):
    _, warnings = styles
    where = _where(warnings)
    assert "action server 'plan' example_interfaces/Fibonacci" in where[("mission.py", 13)][0]
    assert "action client 'replan'" in where[("mission.py", 14)][0]
    assert "the QoS tuned is not known" in where[("relay.py", 19)][0]  # changed after it was made
    assert "C/C++ source" in where[("package.xml", None)][0]
    assert where[("styles.launch.py", 18)] == ["launch argument 'robot' is taken at its default 'rover'"]
    assert "default '0.5'" in where[("styles.launch.py", 23)][0]
    assert any("under a condition" in m for m in where[("styles.launch.py", 27)])
    assert "included launch description" in where[("styles.launch.py", 28)][0]
    assert "ExecuteProcess" in where[("styles.launch.py", 30)][0]
    assert (
        "computed from parameter 'prefix', which the launch file sets" in where[("styles.launch.py", 31)][0]
    )
    assert all(w.severity == "warning" for w in warnings)


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("10", {"depth": "10", "reliability": "reliable", "durability": "volatile"}),
        ("qos_profile_sensor_data", {"depth": "5", "reliability": "best_effort", "durability": "volatile"}),
        (
            "QoSPresetProfiles.PARAMETERS.value",
            {"depth": "1000", "reliability": "reliable", "durability": "volatile"},
        ),
        ("QoSProfile(depth=4)", {"depth": "4", "reliability": "reliable", "durability": "volatile"}),
        (
            "QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)",
            {"depth": "1", "reliability": "reliable", "durability": "transient_local"},
        ),
        (
            "QoSProfile(history=QoSHistoryPolicy.RMW_QOS_POLICY_HISTORY_KEEP_ALL)",
            {"reliability": "reliable", "durability": "volatile"},
        ),
        ("QoSProfile(history=HistoryPolicy.KEEP_LAST)", None),  # rclpy refuses it: no depth
        ("QoSProfile(depth=3, reliability=ReliabilityPolicy.SOMETIMES)", None),
        ("QoSProfile(**settings)", None),
        ("make_qos()", None),
    ],
)
def test_qos_forms_as_rclpy_reads_them(source, expected):
    text = "from rclpy.qos import QoSProfile, QoSPresetProfiles, qos_profile_sensor_data\n"
    imports = module_imports(ast.parse(text))
    found = read_qos(ast.parse(source, mode="eval").body, Scope(), lambda e: dotted(e, imports))
    assert (found.as_dict() if found is not None else None) == expected


def test_nested_groups_push_their_namespaces_and_an_absolute_one_stays():
    text = (
        "from launch import LaunchDescription\n"
        "from launch.actions import GroupAction\n"
        "from launch_ros.actions import Node, PushROSNamespace\n"
        "def generate_launch_description():\n"
        "    inner = GroupAction(actions=[PushROSNamespace('arm'), Node(package='p', executable='a'),\n"
        "                                 Node(package='p', executable='b', namespace='/fixed')])\n"
        "    return LaunchDescription([\n"
        "        Node(package='p', executable='c', namespace='before'),\n"
        "        GroupAction([Node(package='p', executable='d'), PushROSNamespace('/robot'), inner,\n"
        "                     PushROSNamespace(unknown)]),\n"
        "    ])\n"
    )
    actions, where = _read_text(launch_actions, text, "x.launch.py")
    assert sorted((a.executable, a.namespace) for a in actions) == [
        ("a", "robot/arm"),
        ("b", "/fixed"),
        ("c", "before"),
        ("d", ""),
    ]
    assert where == {}


def test_setup_cfg_and_cmake_programs_read_or_located(tmp_path):
    warnings: list = []
    entries = setup_cfg_entry_points(
        "[options.entry_points]\nconsole_scripts =\n    talk = pkg.talker:main\n    broken\n",
        "setup.cfg",
        warnings,
    )
    assert [(e.executable, e.module, e.function) for e in entries] == [("talk", "pkg.talker", "main")]
    assert "'broken'" in warnings[0].message
    warnings.clear()
    assert setup_cfg_entry_points("[options.entry_points\nx", "setup.cfg", warnings) == []
    assert warnings[0].location.file == "setup.cfg" and "does not read" in warnings[0].message
    warnings.clear()
    cmake = (
        "project(x)\ninstall(PROGRAMS nodes/a.py ${EXTRA} README.md\n  DESTINATION lib/${PROJECT_NAME})\n"
        "install(PROGRAMS tools/b.py DESTINATION bin)\n"
    )
    entries = cmake_programs(cmake, "CMakeLists.txt", warnings)
    assert [(e.executable, e.module, e.function) for e in entries] == [("a.py", "nodes.a", SCRIPT)]
    assert [(w.location.line, "not a literal path" in w.message) for w in warnings] == [(2, True)]
    # a package whose only manifest is fine but whose setup.cfg is not: the node is still read
    package = tmp_path / "p"
    (package / "p").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>p</name></package>")
    (package / "setup.cfg").write_bytes(b"[options.entry_points]\n\xff\xfe")
    (package / "p" / "n.py").write_text(
        "import rclpy\nfrom std_msgs.msg import String\n"
        "node = rclpy.create_node('n')\nnode.create_publisher(String, 't', 1)\n"
    )
    warnings.clear()
    project = read_ros2_packages([package], warnings)
    assert sorted(_components(project)) == ["n"]
    assert any(w.location.file.endswith("setup.cfg") and "UTF-8" in w.message for w in warnings)


def test_conditional_and_repeated_creations_are_named_at_their_line():
    text = (
        "from rclpy.node import Node\n"
        "from std_msgs.msg import String\n"
        "class Fan(Node):\n"
        "    def __init__(self, debug=False):\n"
        "        super().__init__('fan')\n"
        "        if debug:\n"
        "            self.create_publisher(String, 'debug', 1)\n"
        "        self.outs = [self.create_publisher(String, f'out{i}', 1) for i in range(3)]\n"
        "        try:\n"
        "            self.create_timer(0.1, self.cb)\n"
        "        except RuntimeError:\n"
        "            self.create_timer(1.0, self.cb)\n"
        "    def cb(self):\n"
        "        pass\n"
    )
    module, where = _read_text(
        lambda tree, file, warnings: read_module(tree, file, "p", warnings), text, "fan.py"
    )
    [fan] = module.nodes
    assert [(p.topic, p.location.line) for p in fan.ports] == [("debug", 7)]
    assert [t.period for t in fan.timers] == [Decimal("0.1"), Decimal("1.0")]
    assert sorted(where) == [7, 8, 12]
    assert "runs only when debug" in where[7]
    assert "in a loop" in where[8]
    assert "RuntimeError is raised" in where[12]


def test_launch_nodes_made_several_times_and_group_settings_are_named():
    text = (
        "from launch import LaunchDescription\n"
        "from launch_ros.actions import Node, SetRemap\n"
        "def robot(name):\n"
        "    return Node(package='p', executable='e', name=name)\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([robot('a'), robot('b'), SetRemap(src='x', dst='y'),\n"
        "        *[Node(package='p', executable='f') for _ in range(2)]])\n"
    )
    actions, where = _read_text(launch_actions, text, "x.launch.py")
    assert actions == []
    assert "launched in robot(), which the file calls 2 times" in where[4]
    assert where[6].startswith("SetRemap:")
    assert "p/f is launched in a loop" in where[7]


def test_hostile_class_cycles_and_launch_self_references_are_read_without_a_traceback(tmp_path):
    package = tmp_path / "h"
    (package / "h").mkdir(parents=True)
    (package / "launch").mkdir()
    (package / "package.xml").write_text("<package format='3'><name>h</name></package>")
    head = "from rclpy.node import Node\nfrom std_msgs.msg import String\n"
    (package / "h" / "a.py").write_text(head + "from .b import B\nclass A(B):\n    pass\n")
    (package / "h" / "b.py").write_text(head + "from .a import A\nclass B(A):\n    pass\n")
    (package / "h" / "c.py").write_text(
        head + "from ....far import Base\nclass C(Node, Base):\n    def __init__(self):\n"
        "        super().__init__('c')\n        self.create_publisher(String, 'x', 1)\n"
    )
    (package / "launch" / "l.launch.py").write_text(
        "from launch import LaunchDescription\nfrom launch.actions import GroupAction\n"
        "from launch_ros.actions import Node, PushRosNamespace\n"
        "g = GroupAction([PushRosNamespace(g), g])\n"
        "def generate_launch_description():\n"
        "    n = Node(package='h', executable='c')\n"
        "    return LaunchDescription([GroupAction([PushRosNamespace(ns), n]), g])\n"
    )
    warnings: list = []
    project = read_ros2_packages([package], warnings)
    assert sorted(_components(project)) == ["c"]
    assert any("pushed namespace" in w.message for w in warnings)


def test_setup_py_entry_points_through_names_and_setuptools_or_named():
    from rosaadl.importers.ros2_package.launching import entry_points

    text = (
        "import setuptools\n"
        "SCRIPTS = ['talk = pkg.talker:main']\n"
        "setuptools.setup(name='pkg', entry_points={'console_scripts': SCRIPTS})\n"
        "setuptools.setup(name='other', entry_points=computed())\n"
        "setuptools.setup(entry_points={'console_scripts': [f'{n} = p.{n}:main' for n in 'a']})\n"
        "setuptools.setup(**options)\n"
    )
    entries, where = _read_text(entry_points, text, "setup.py")
    assert [(e.executable, e.module, e.function) for e in entries] == [("talk", "pkg.talker", "main")]
    assert sorted(where) == [4, 5, 6]
    assert "not a literal dictionary" in where[4]
    assert "not a literal list" in where[5]
    assert "setup(**options)" in where[6]

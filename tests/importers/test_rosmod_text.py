"""Textual ROSMOD projects: v0.3 folders, v0.2 workspaces, v0.1 .rosml, the v0.4 jsonpickle file."""

from __future__ import annotations

import json
import os
import random
import tempfile
from decimal import Decimal
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosaadl import model
from rosaadl.errors import Diagnostic, NameResolutionError, ParseError, RosaadlError
from rosaadl.importers import rosmod_text
from rosaadl.importers.rosmod_text import SUMMARY_KEYS, RosmodImportError, read_project, summarize

# --------------------------------------------------------------------------- fixtures (own, small)

RML = """/*
 * a small software model
 */
// ROSMOD Package - nav
package nav
{
  // ROSMOD Component - Planner
  component Planner : Base
  {
    publisher <nav/Path> path_pub;
    subscriber <nav/Goal> goal_sub
    {
      priority = 60;
      deadline = 0.250;
    }
    client <nav/Plan> plan_client;
    server <nav/Plan> plan_server { deadline = 1.5; priority = 10; }
    subscriber <std_msgs/String> log_sub { priority = 1; deadline = 0.1; }
    timer tick
    {
\tperiod = 0.100;
\tpriority = 50;
\tdeadline = 0.05;
    }
  }
  component Driver : KSP
  {
    subscriber <nav/Path> path_sub { priority = 50; deadline = 0.2; }
  }
}
"""

RHW = """/* hardware */
hardware board
{
  ip_address = "10.0.0.2";
  username = "robot";
  sshkey = "~/.ssh/id_rsa";
  deployment_path = "/home/robot";
  install_path = "/opt/ros/indigo";
  init = "/etc/init.sh";
  arch = armv7l;
}
hardware laptop
{
  ip_address = "localhost";
  username = "dev";
  sshkey = "~/.ssh/id";
  deployment_path = "/home/dev";
  install_path = "/opt/ros/indigo";
  arch = x64;
}
"""

RDP = """/*
 * deployment
 */
using lab;

// ROSMOD Node - planner_node
node planner_node
{
  properties
  {
    ref = "lab/board";
    priority = 70;
    cmd_args = "--fast -v";
  }
  component_instance planner_i
  {
      properties
      {
\tref = "nav/Planner";
\tscheduling_scheme = EDF;
\tlogging
\t{
\t  Is Periodic? = true;
\t  Periodic Log Unit = 1000;
\t}
      }
      port_instance p1
      {
\tref = "Planner/path_pub";
\tgroup = "g1";
      }
  }
}
node driver_node
{
  properties { ref = "lab/laptop"; priority = 50; }
  component_instance driver_i { properties { ref = "nav/Driver"; scheduling_scheme = PFIFO; } }
}
"""

MESSAGES = {
    "msg/nav.Path.msg": "# a path\ngeometry_msgs/Point[] points\n",
    "msg/nav.Goal.msg": "float64 x\nfloat64 y\nfloat64[2] tolerance\n",
    "srv/nav.Plan.srv": "nav/Goal goal\n---\nnav/Path path\nbool ok\n",
}


def write_v03(
    root: Path, *, rml: str = RML, rhw: str = RHW, rdp: str = RDP, extra: dict | None = None
) -> Path:
    project = root / "demo"
    (project / "01-Software").mkdir(parents=True)
    (project / "02-Hardware").mkdir()
    (project / "03-Deployment").mkdir()
    (project / "demo.rosmod").write_text("This is a ROSMOD Project")
    (project / "01-Software" / "software.rml").write_text(rml)
    (project / "02-Hardware" / "lab.rhw").write_text(rhw)
    # the deployment with Windows line ends
    (project / "03-Deployment" / "deployment.rdp").write_bytes(rdp.replace("\n", "\r\n").encode())
    files = dict(MESSAGES)
    files.update(extra or {})
    for rel, text in files.items():
        path = project / "01-Software" / rel
        path.parent.mkdir(exist_ok=True)
        if text is None:
            path.unlink(missing_ok=True)
        else:
            path.write_text(text)
    return project


def errors_of(path: Path, **kwargs) -> list[RosaadlError]:
    with pytest.raises(RosmodImportError) as info:
        read_project(path, **kwargs)
    exc = info.value
    assert isinstance(exc, RosaadlError)
    assert exc.errors and all(isinstance(e, RosaadlError) for e in exc.errors)
    return exc.errors


def only_error(path: Path, **kwargs) -> RosaadlError:
    errors = errors_of(path, **kwargs)
    assert len(errors) == 1, [str(e) for e in errors]
    return errors[0]


# --------------------------------------------------------------------------- v0.3 model content


def test_v03_project_model(tmp_path):
    warnings: list[Diagnostic] = []
    project = read_project(write_v03(tmp_path), warnings=warnings)
    assert warnings == []
    assert (project.name, project.formatVersion) == ("demo", "0.3")
    software = project.software
    assert (software.name, software.sourceFile) == ("software", "01-Software/software.rml")
    nav = software.packages[0]
    assert [m.name for m in nav.messages] == ["Goal", "Path"]
    assert [s.name for s in nav.services] == ["Plan"]
    goal = nav.messages[0]
    assert [(f.name, f.type, f.arrayLength) for f in goal.fields] == [
        ("x", "float64", 0),
        ("y", "float64", 0),
        ("tolerance", "float64", 2),
    ]
    assert goal.definition == MESSAGES["msg/nav.Goal.msg"]
    plan = nav.services[0]
    assert [f.type for f in plan.requestFields] == ["nav/Goal"]
    assert [f.name for f in plan.responseFields] == ["path", "ok"]
    planner, driver = nav.components
    assert (planner.name, planner.datatype, driver.datatype) == ("Planner", "Base", "KSP")
    assert (planner.line, planner.column) == (8, 3)
    ports = {p.name: p for p in planner.ports}
    assert [p.eClass.name for p in planner.ports] == [
        "Publisher",
        "Subscriber",
        "Client",
        "Server",
        "Subscriber",
    ]
    assert ports["path_pub"].type == "nav/Path"
    assert ports["goal_sub"].priority == 60 and ports["goal_sub"].deadline == Decimal("0.250")
    assert ports["plan_server"].deadline == Decimal("1.5") and ports["plan_server"].priority == 10
    assert ports["log_sub"].type == "std_msgs/String"  # external type: kept, not an error
    (tick,) = planner.timers
    assert (tick.period, tick.priority, tick.deadline) == (Decimal("0.100"), 50, Decimal("0.05"))
    assert isinstance(tick.period, Decimal)

    (system,) = project.systems
    assert (system.name, system.sourceFile) == ("lab", "02-Hardware/lab.rhw")
    board = system.hosts[0]
    assert (board.ipAddress, board.username, board.sshKey, board.deploymentPath, board.installPath) == (
        "10.0.0.2",
        "robot",
        "~/.ssh/id_rsa",
        "/home/robot",
        "/opt/ros/indigo",
    )
    assert board.architecture == "armv7l"
    assert [(p.key, p.value) for p in board.properties] == [("init", "/etc/init.sh")]

    (deployment,) = project.deployments
    assert (deployment.name, deployment.systemName, deployment.system) == ("deployment", "lab", system)
    assert deployment.sourceFile == "03-Deployment/deployment.rdp"
    node, node2 = deployment.nodes
    assert (node.name, node.hostRef, node.host, node.priority, node.arguments) == (
        "planner_node",
        "lab/board",
        board,
        70,
        "--fast -v",
    )
    assert (node.line, node.column) == (7, 1)  # CRLF line ends count as one line end
    (inst,) = node.componentInstances
    assert (inst.componentRef, inst.component, inst.schedulingScheme.name) == ("nav/Planner", planner, "EDF")
    assert [(p.key, p.value) for p in inst.logging] == [
        ("Is Periodic?", "true"),
        ("Periodic Log Unit", "1000"),
    ]
    assert [(p.name, p.port, p.group) for p in inst.portInstances] == [("p1", "Planner/path_pub", "g1")]
    assert node2.host is system.hosts[1]
    assert node2.componentInstances[0].schedulingScheme.name == "PFIFO"
    assert summarize(project) == {
        **dict.fromkeys(summarize(project), 0),
        "packages": 1,
        "messages": 2,
        "services": 1,
        "components": 2,
        "timers": 1,
        "publishers": 1,
        "subscribers": 3,
        "clients": 1,
        "servers": 1,
        "systems": 1,
        "hosts": 2,
        "deployments": 1,
        "nodes": 2,
        "component_instances": 2,
        "max_nodes": 2,
        "max_component_instances": 2,
    }


def test_same_project_twice_is_equal_and_saves_and_reloads(tmp_path):
    path = write_v03(tmp_path)
    first, second = read_project(path), read_project(path)
    assert model.model_differences(first, second) == []
    for name in ("p.xmi", "p.json"):
        model.save(first, tmp_path / name)
        again = model.load(tmp_path / name)
        assert model.model_differences(first, again, ignore=()) == []
        model.save(again, tmp_path / ("2" + name))
        assert (tmp_path / name).read_bytes() == (tmp_path / ("2" + name)).read_bytes()


def test_lone_rml_file_finds_its_messages(tmp_path):
    project = read_project(write_v03(tmp_path) / "01-Software" / "software.rml")
    assert project.name == "software" and project.systems == [] and project.deployments == []
    assert len(project.software.packages[0].messages) == 2


def test_side_files_abl_pnp_and_stale_messages(tmp_path):
    extra = {
        "abl/nav.Planner.tick.abl": "do tick { LOCAL 3; }",
        "pnp/nav.Planner.path_pub.pnp": "0,0,0,eth0\n",
        "abl/nav.Planner.gone.abl": "stale",
        "msg/other.Thing.msg": "int32 x\n",  # package not in the .rml: skipped, as ROSMOD does
        "msg/README.msg": "int32 x\n",
    }
    warnings: list[Diagnostic] = []
    project = read_project(write_v03(tmp_path, extra=extra), warnings=warnings)
    planner = project.software.packages[0].components[0]
    assert [(p.key, p.value) for p in planner.properties] == [
        ("abl:tick", "do tick { LOCAL 3; }"),
        ("pnp:path_pub", "0,0,0,eth0\n"),
    ]
    texts = sorted(w.message for w in warnings)
    assert any("'other.Thing.msg'" in t and "not defined in the software model" in t for t in texts)
    assert any("'README.msg'" in t for t in texts)
    assert any("'nav.Planner.gone.abl'" in t for t in texts)
    assert all(w.severity == "warning" and w.location.file for w in warnings)


def test_repeated_host_later_definition_wins_unless_strict(tmp_path):
    rhw = RHW + 'hardware board { ip_address = "10.0.0.9"; arch = arm; }\n'
    path = write_v03(tmp_path, rhw=rhw)
    warnings: list[Diagnostic] = []
    project = read_project(path, warnings=warnings)
    hosts = project.systems[0].hosts
    assert [h.name for h in hosts] == ["laptop", "board"]
    assert hosts[1].ipAddress == "10.0.0.9"
    assert project.deployments[0].nodes[0].host is hosts[1]
    assert len(warnings) == 1 and "defined again at line 21" in warnings[0].message
    err = only_error(path, strict=True)
    assert isinstance(err, NameResolutionError)
    assert "duplicate host name 'board'" in err.message and err.location.line == 21


def test_unknown_statements_are_warnings(tmp_path):
    rml = RML.replace("    timer tick", "    gizmo <x> y;\n    timer tick")
    warnings: list[Diagnostic] = []
    read_project(write_v03(tmp_path, rml=rml), warnings=warnings)
    assert ["unknown statement 'gizmo <x> y'" in w.message for w in warnings] == [True]


# --------------------------------------------------------------------------- bad input → located errors


def _loc(err: RosaadlError) -> tuple[str, int | None, int | None]:
    return (Path(err.location.file).name, err.location.line, err.location.column)


def test_node_on_unknown_host(tmp_path):
    err = only_error(write_v03(tmp_path, rdp=RDP.replace('"lab/board"', '"lab/nowhere"')))
    assert isinstance(err, NameResolutionError)
    assert "unknown host 'nowhere'" in err.message
    assert _loc(err) == ("deployment.rdp", 11, 11)


def test_unknown_hardware_model(tmp_path):
    errors = errors_of(write_v03(tmp_path, rdp=RDP.replace("using lab;", "using moon;")))
    messages = [e.message for e in errors]
    assert any("unknown hardware model 'moon' in 'using'" in m for m in messages)
    assert _loc(errors[0])[:2] == ("deployment.rdp", 4)


def test_component_reference_to_unknown_package(tmp_path):
    err = only_error(write_v03(tmp_path, rdp=RDP.replace('"nav/Planner"', '"navigation/Planner"')))
    assert "unknown package 'navigation'" in err.message and "packages: nav" in err.message
    assert _loc(err) == ("deployment.rdp", 19, 8)


def test_component_reference_to_unknown_component(tmp_path):
    err = only_error(write_v03(tmp_path, rdp=RDP.replace('"nav/Driver"', '"nav/Pilot"')))
    assert "unknown component 'Pilot'" in err.message
    assert _loc(err)[0] == "deployment.rdp"


def test_port_instance_of_unknown_port(tmp_path):
    err = only_error(write_v03(tmp_path, rdp=RDP.replace('"Planner/path_pub"', '"Planner/nope"')))
    assert "'Planner/nope' is not a port of component 'Planner'" in err.message


@pytest.mark.parametrize(
    ("old", "new", "fragment", "line"),
    [
        ("component Driver : KSP", "component Planner : KSP", "duplicate component name 'Planner'", 26),
        ("timer tick", "timer path_pub", "duplicate port or timer name 'path_pub'", 19),
    ],
)
def test_duplicate_software_names(tmp_path, old, new, fragment, line):
    err = only_error(write_v03(tmp_path, rml=RML.replace(old, new), rdp="using lab;\n"))
    assert isinstance(err, NameResolutionError)
    assert fragment in err.message and err.location.line == line


def test_duplicate_node_and_instance_names(tmp_path):
    rdp = RDP.replace("node driver_node", "node planner_node")
    err = only_error(write_v03(tmp_path, rdp=rdp))
    assert "duplicate node name 'planner_node'" in err.message and "first defined at line 7" in err.message


def test_duplicate_package(tmp_path):
    rml = RML + "package nav { }\n"
    err = only_error(write_v03(tmp_path, rml=rml, rdp="using lab;\n"))
    assert "duplicate package name 'nav'" in err.message and err.location.line == 31


def test_unknown_message_type(tmp_path):
    err = only_error(write_v03(tmp_path, rml=RML.replace("<nav/Path> path_pub", "<nav/Trajectory> path_pub")))
    assert isinstance(err, NameResolutionError)
    assert (
        "unknown message type 'nav/Trajectory'" in err.message and "its messages: Goal, Path" in err.message
    )
    assert _loc(err) == ("software.rml", 10, 16)


def test_unknown_service_type(tmp_path):
    err = only_error(write_v03(tmp_path, rml=RML.replace("<nav/Plan> plan_client", "<nav/Goal> plan_client")))
    assert "unknown service type 'nav/Goal'" in err.message


def test_unknown_nested_type_in_a_message_file(tmp_path):
    extra = {"msg/nav.Goal.msg": "nav/Pose pose\nfloat64 x\n"}
    err = only_error(write_v03(tmp_path, extra=extra))
    assert "unknown message type 'nav/Pose'" in err.message
    assert _loc(err) == ("nav.Goal.msg", 1, 1)


def test_message_file_syntax_error(tmp_path):
    err = only_error(write_v03(tmp_path, extra={"msg/nav.Goal.msg": "float64 x\nfloat64[y] z\n"}))
    assert isinstance(err, ParseError) and _loc(err) == ("nav.Goal.msg", 2, 1)


def test_unclosed_brace(tmp_path):
    rml = RML.rstrip().removesuffix("}")  # the package's closing brace is missing
    err = only_error(write_v03(tmp_path, rml=rml))
    assert isinstance(err, ParseError)
    assert "unclosed '{' of 'package nav'" in err.message and "end of the file" in err.message
    assert _loc(err) == ("software.rml", 6, 1)


@pytest.mark.parametrize(
    ("rml", "fragment", "line", "column"),
    [
        (
            "package p {\n  component C : Base {\n    timer t { period = 1.0 }\n  }\n}\n",
            "expected ';'",
            3,
            28,
        ),
        ("package p\n{\n}\n}\n", "unexpected '}'", 4, 1),
        ("/* never closed\npackage p { }\n", "unterminated comment", 1, 1),
        ('package p { component C : Base { timer t { period = "1.0; } } }\n', "unterminated string", 1, 53),
        (
            "package p { component C : Base { timer t { period = fast; } } }\n",
            "expected a number of seconds",
            1,
            53,
        ),
        ("package p { component C : Base { timer t { priority = 1.5; } } }\n", "expected an integer", 1, 55),
        ("package p { component C : Base { timer t { deadline = -1; } } }\n", "must not be negative", 1, 55),
        ("package p { component C : Base { publisher p; } }\n", "malformed publisher", 1, 34),
        ("package p { component : Base { } }\n", "malformed component", 1, 13),
        ("package p { component C { } } package\n", "found the end of the file", 1, 31),
        ("package p { = 3; }\n", "expected a name before '='", 1, 13),
    ],
)
def test_syntax_errors_are_located(tmp_path, rml, fragment, line, column):
    err = only_error(write_v03(tmp_path, rml=rml, rdp="using lab;\n"))
    assert fragment in err.message, err.message
    assert _loc(err) == ("software.rml", line, column)


def test_every_problem_is_reported_together(tmp_path):
    rdp = RDP.replace('"lab/board"', '"lab/nowhere"').replace('"nav/Driver"', '"gone/Driver"')
    rml = RML.replace("<nav/Path> path_pub", "<nav/Trajectory> path_pub")
    errors = errors_of(write_v03(tmp_path, rml=rml, rdp=rdp))
    names = sorted(Path(e.location.file).name for e in errors)
    assert names == ["deployment.rdp", "deployment.rdp", "software.rml"]
    with pytest.raises(RosmodImportError) as info:
        read_project(write_v03(tmp_path / "again", rml=rml, rdp=rdp))
    assert "(and 2 more)" in info.value.message
    assert len(str(info.value).splitlines()) == 3
    assert len(info.value.diagnostics()) == 3


def test_syntax_error_in_one_file_does_not_hide_the_others(tmp_path):
    errors = errors_of(write_v03(tmp_path, rml="package p {\n", rhw="hardware h { arch = x86 \n}\n"))
    assert sorted(Path(e.location.file).name for e in errors) == ["lab.rhw", "software.rml"]


def test_garbage_and_binary_files(tmp_path):
    project = write_v03(tmp_path)
    rml = project / "01-Software" / "software.rml"
    rng = random.Random(7)
    rml.write_bytes(rng.randbytes(5 * 1024 * 1024))
    err = only_error(project)
    assert isinstance(err, ParseError) and _loc(err)[0] == "software.rml" and err.location.line
    rml.write_bytes(b"package p \x00 { }")
    assert "unexpected character" in only_error(project).message
    rml.write_bytes(b"package caf\xe9 { }")
    err = only_error(project)
    assert "not UTF-8" in err.message and _loc(err) == ("software.rml", 1, 12)


def test_too_large_file_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(rosmod_text.files, "MAX_FILE_BYTES", 100)  # where the reader looks it up
    errors = errors_of(write_v03(tmp_path))
    assert sorted(_loc(e)[0] for e in errors) == ["deployment.rdp", "lab.rhw", "software.rml"]
    assert all("above 100 bytes are refused" in e.message for e in errors)


def test_deeply_nested_blocks_are_refused(tmp_path):
    err = only_error(write_v03(tmp_path, rml="package p " + "{ x " * 500 + "}" * 500))
    assert "nested more than" in err.message


def test_not_a_project(tmp_path):
    (tmp_path / "empty").mkdir()
    assert "not a ROSMOD project" in only_error(tmp_path / "empty").message
    assert "no such file" in only_error(tmp_path / "missing").message
    project = write_v03(tmp_path)
    (project / "01-Software" / "second.rml").write_text("package q { }")
    assert "one software model; found 2" in only_error(project).message
    assert rosmod_text.is_rosmod_project(project) and not rosmod_text.is_rosmod_project(tmp_path / "empty")


@given(st.text(alphabet=st.sampled_from(list('{};=<>/:"ab12 .?\n\t*')), max_size=120))
@settings(max_examples=150, deadline=None)
def test_fuzzed_models_fail_cleanly(text):
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "x.rml").write_text("package p { component C : Base { " + text + " } }")
        (folder / "x.rdp").write_text("using h; " + text)
        try:
            read_project(folder)
        except RosmodImportError as exc:
            assert all(e.location.file for e in exc.errors)


# --------------------------------------------------------------------------- v0.2 / v0.1 / v0.4

V02_RML = """/* ROS Workspace Model */
package robot
{
    messages
    {
        msg Pose { float64 x; float64 y; int32 MODE = 2; }
        msg Track { robot/Pose[] poses; uint8[4] id; }
    }
    services
    {
        srv Reset { request { bool hard; } response { } }
    }
    components
    {
        component Sensor
        {
            provides Reset;
            publisher<Pose> pose_pub;
            timer Sample { period = 500ms; }
        }
        component Tracker
        {
            requires Reset;
            subscriber<Pose> pose_sub;
            publisher<std_msgs/String> log_pub;
            timer Tick { period = 0.5s; }
        }
    }
    nodes
    {
        node sensing { component<Sensor> sensor_i; }
        node tracking { component<Tracker> tracker_i; component<Sensor> spare_i; }
    }
}
"""
V02_RHW = (
    'host alpha { ip_address = "10.0.0.1"; architecture = "arm"; }\nhost beta { ip_address = "10.0.0.2"; }\n'
)
V02_RDP = """using cluster;
host_instance alpha
{
    properties { username = "pi"; sshkey = "~/.ssh/pi"; ENV ROS_IP = "10.0.0.1"; }
    nodes { node_instance sensing { reference = "robot/sensing"; cmdline_arguments = "-v"; } }
}
host_instance beta
{
    properties { username = "ubuntu"; }
    nodes { node_instance tracking { reference = "robot/tracking"; } }
}
"""


def write_v02(root: Path, rdp: str = V02_RDP) -> Path:
    folder = root / "v02"
    folder.mkdir()
    (folder / "workspace.rml").write_text(V02_RML)
    (folder / "cluster.rhw").write_text(V02_RHW)
    (folder / "deployment.rdp").write_text(rdp)
    return folder


def test_v02_workspace(tmp_path):
    project = read_project(write_v02(tmp_path))
    assert project.formatVersion == "0.2"
    robot = project.software.packages[0]
    pose, track = robot.messages
    assert [(f.name, f.type, f.constantValue) for f in pose.fields] == [
        ("x", "float64", None),
        ("y", "float64", None),
        ("MODE", "int32", "2"),
    ]
    assert pose.definition == "float64 x\nfloat64 y\nint32 MODE=2\n"
    assert [(f.type, f.isArray, f.arrayLength) for f in track.fields] == [
        ("robot/Pose", True, 0),
        ("uint8", True, 4),
    ]
    assert [f.name for f in robot.services[0].requestFields] == ["hard"]
    sensor, tracker = robot.components
    assert [(p.eClass.name, p.name, p.type) for p in sensor.ports] == [
        ("Server", "Reset_server", "robot/Reset"),
        ("Publisher", "pose_pub", "robot/Pose"),
    ]
    assert [(p.eClass.name, p.name) for p in tracker.ports][0] == ("Client", "Reset_client")
    assert sensor.timers[0].period == Decimal("0.5") and tracker.timers[0].period == Decimal("0.5")
    assert [(p.key, json.loads(p.value)) for p in robot.properties] == [
        ("node:sensing", {"sensor_i": "robot/Sensor"}),
        ("node:tracking", {"tracker_i": "robot/Tracker", "spare_i": "robot/Sensor"}),
    ]
    (deployment,) = project.deployments
    assert deployment.system is project.systems[0]
    sensing, tracking = deployment.nodes
    assert (sensing.hostRef, sensing.host.name, sensing.arguments) == ("alpha", "alpha", "-v")
    assert [(i.name, i.componentRef, i.component) for i in tracking.componentInstances] == [
        ("tracker_i", "robot/Tracker", tracker),
        ("spare_i", "robot/Sensor", sensor),
    ]
    assert [(p.key, p.value) for p in sensing.properties] == [("reference", "robot/sensing")]
    props = {p.key: json.loads(p.value) for p in deployment.properties}
    assert props["host_instance:alpha"] == {"username": "pi", "sshkey": "~/.ssh/pi", "ENV ROS_IP": "10.0.0.1"}
    assert project.systems[0].hosts[0].architecture == "arm"


def test_v02_unknown_software_node_and_host(tmp_path):
    rdp = V02_RDP.replace('"robot/tracking"', '"robot/mapping"').replace(
        "host_instance beta", "host_instance gamma"
    )
    errors = errors_of(write_v02(tmp_path, rdp=rdp))
    messages = sorted(e.message for e in errors)
    assert any("unknown node 'mapping'" in m for m in messages)
    assert any("unknown host 'gamma'" in m for m in messages)


def test_v01_rosml(tmp_path):
    path = tmp_path / "input.rosml"
    path.write_text("workspace WS;\n" + V02_RML)
    project = read_project(path)
    assert (project.formatVersion, project.software.name) == ("0.1", "WS")
    assert summarize(project)["components"] == 2


def test_v04_refusals(tmp_path):
    folder = tmp_path / "v04"
    folder.mkdir()
    (folder / "x.rml").write_text('{"py/object": "__main__.Project",\n "children": [}')
    err = only_error(folder)
    assert "malformed JSON" in err.message and _loc(err)[:2] == ("x.rml", 2)
    (folder / "x.rml").write_text('{"py/object": "__main__.Software"}')
    assert "expected a ROSMOD v0.4 project" in only_error(folder).message


def test_v04_dangling_object_reference_is_reported_not_a_crash(tmp_path):
    folder = tmp_path / "v04"
    folder.mkdir()
    deployment = {"py/object": "__main__.Deployment", "children": {"_inner": [{"py/id": 99}]}}
    data = {"py/object": "__main__.Project", "children": {"_inner": [deployment]}}
    (folder / "x.rml").write_text(json.dumps(data))
    err = only_error(folder)
    assert isinstance(err, NameResolutionError) and "the host reference is missing" in err.message


# --------------------------------------------------------------------------- corpus

# Per project: packages, messages, services, components, timers, publishers, subscribers, clients,
# servers, .rhw files, hosts, .rdp files, max nodes and max component instances in one .rdp.
# Values are INDEX.md's, except where INDEX.md's regular expressions miscounted (see the comments).
EXPECTED = {
    "agse2015/agse_rosmod_project": (1, 10, 8, 8, 6, 6, 11, 9, 8, 1, 3, 1, 6, 8),
    "agse2015/agse_rosmod_v3": (3, 10, 8, 8, 6, 6, 11, 9, 8, 1, 3, 1, 6, 8),
    "legacy-v0.2/sample": (1, 1, 1, 3, 3, 2, 1, 1, 1, 1, 2, 1, 1, 3),
    "textual-v0.3/agse": (1, 10, 8, 8, 6, 6, 13, 9, 8, 1, 3, 1, 6, 8),
    "textual-v0.3/client-server": (1, 0, 1, 2, 1, 0, 0, 1, 1, 2, 33, 3, 30, 60),
    "textual-v0.3/integration": (2, 2, 0, 3, 1, 2, 2, 0, 0, 2, 34, 3, 7, 7),
    "textual-v0.3/isorc2016": (1, 5, 0, 10, 5, 5, 5, 0, 0, 2, 33, 2, 25, 25),
    "textual-v0.3/ksp_rover_controller": (1, 3, 0, 4, 3, 3, 4, 0, 0, 1, 32, 1, 3, 4),
    # hardware.rhw defines Server_Machine twice (arch x86, then arm): 33 distinct hosts, not 34;
    # ROSMOD resolves "hardware/Server_Machine" to the later definition, and so do we.
    "textual-v0.3/long-running-operation": (1, 1, 0, 2, 2, 1, 1, 0, 0, 1, 33, 2, 2, 2),
    "textual-v0.3/periodic-timers": (1, 0, 0, 8, 15, 0, 0, 0, 0, 1, 33, 7, 30, 150),
    "textual-v0.3/publish-subscribe": (1, 1, 0, 2, 1, 1, 1, 0, 0, 2, 33, 2, 2, 2),
    "textual-v0.3/roscpp/ksp_rover_control": (1, 3, 0, 4, 3, 3, 4, 0, 0, 2, 4, 2, 3, 4),
    "textual-v0.3/roscpp/ksp_stearwing_control": (1, 3, 0, 4, 3, 3, 4, 0, 0, 2, 4, 2, 3, 4),
    "textual-v0.3/roscpp/pub_sub_cycle_example": (1, 1, 0, 2, 0, 2, 2, 0, 0, 1, 1, 1, 1, 2),
    "textual-v0.3/roscpp/pub_sub_traffic_gen": (1, 1, 1, 2, 0, 1, 1, 1, 1, 2, 5, 2, 4, 4),
    "textual-v0.3/roscpp/routing": (1, 1, 0, 4, 0, 1, 1, 0, 0, 1, 5, 1, 7, 7),
    "textual-v0.3/roscpp/tg_test": (1, 2, 0, 4, 0, 4, 2, 0, 0, 1, 2, 1, 4, 4),
    # msg/New_Package.led_state.msg belongs to a package the .rml does not define (a leftover of a
    # rename); ROSMOD skips such files, so the project has 1 message, not the 2 files INDEX counts.
    "textual-v0.3/sequential-leds": (1, 1, 0, 1, 0, 1, 1, 0, 0, 1, 32, 2, 31, 31),
    "textual-v0.3/ten-components": (1, 4, 2, 10, 7, 5, 4, 2, 2, 1, 32, 6, 4, 10),
    # New_Package.ComponentName.msg / New_Package.ComponentService.srv: same leftover as above,
    # so 1 message and 1 service, not 2 and 2.
    "textual-v0.3/three-components": (1, 1, 1, 3, 3, 2, 1, 1, 1, 2, 33, 4, 2, 3),
    "textual-v0.3/timer": (1, 0, 0, 1, 2, 0, 0, 0, 0, 1, 1, 1, 1, 1),
    # the v0.4 jsonpickle file: INDEX's regular expressions count nothing in JSON; it holds
    # 1 package, 1 component with 1 timer, 1 hardware model with 1 computer, 1 deployment with
    # 1 node and 1 component instance (as INDEX's note on the file says).
    "textual-v0.3/timer_example": (1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 1, 1, 1),
    "textual-v0.3/trajectory-planner": (1, 1, 1, 2, 1, 1, 1, 1, 1, 2, 33, 3, 2, 2),
    "textual-v0.3/uav": (1, 2, 0, 3, 1, 2, 2, 0, 0, 2, 33, 5, 2, 3),
}
# the columns of EXPECTED: the counts of summarize, in order, but for those INDEX.md has no column
# for in its textual table (actions, containers, and the totals of nodes and component instances)
_NOT_IN_INDEX = ("actions", "action_clients", "action_servers", "containers", "nodes", "component_instances")
_KEYS = tuple(k for k in SUMMARY_KEYS if k not in _NOT_IN_INDEX)
assert len(_KEYS) == 14


def _rosmod_corpus() -> Path:
    env = os.environ.get("ROSAADL_CORPUS")
    return (Path(env) if env else Path(__file__).resolve().parents[3] / "shared" / "corpus") / "rosmod"


def _textual_projects() -> list[str]:
    root = _rosmod_corpus()
    if not root.is_dir():
        return sorted(EXPECTED)
    found = [p.parent for p in root.rglob("*.rosmod")]
    found += [p for p in (root / "legacy-v0.2").iterdir() if p.is_dir()]
    found += [p.parent for p in root.rglob("timer_example.rml")]
    return sorted(p.relative_to(root).as_posix() for p in found)


@pytest.fixture(scope="module")
def imported(corpus):
    cache: dict[str, object] = {}

    def get(name: str):
        if name not in cache:
            cache[name] = read_project(corpus / "rosmod" / name)
        return cache[name]

    return get


@pytest.mark.corpus
def test_every_textual_corpus_project_is_listed(corpus):
    assert _textual_projects() == sorted(EXPECTED)


@pytest.mark.corpus
@pytest.mark.parametrize("name", _textual_projects())
def test_corpus_project_counts(imported, name):
    counts = summarize(imported(name))
    assert tuple(counts[k] for k in _KEYS) == EXPECTED[name]


@pytest.mark.corpus
@pytest.mark.parametrize("name", _textual_projects())
def test_corpus_project_is_stable_and_saves(imported, corpus, name, tmp_path):
    project = imported(name)
    assert model.model_differences(project, read_project(corpus / "rosmod" / name)) == []
    model.save(project, tmp_path / "p.xmi")
    assert model.model_differences(project, model.load(tmp_path / "p.xmi"), ignore=()) == []
    # every deployed instance and node is resolved
    for deployment in project.deployments:
        for node in deployment.nodes:
            assert node.host is not None
            assert all(i.component is not None for i in node.componentInstances)


@pytest.mark.corpus
def test_corpus_v01_and_details(corpus, imported):
    project = read_project(corpus / "rosmod" / "legacy-v0.1" / "input.rosml")
    counts = summarize(project)
    assert (project.formatVersion, counts["packages"], counts["components"], counts["timers"]) == (
        "0.1",
        2,
        6,
        6,
    )
    assert [p.key for pkg in project.software.packages for p in pkg.properties] == [
        "node:Ros_node",
        "node:Ros_node_2",
    ]
    agse = imported("agse2015/agse_rosmod_project")
    servos = [n for n in agse.deployments[0].nodes if n.host.name == "Servos"]
    assert sorted(n.name for n in servos) == ["positioning", "servos"]
    assert [p.key for p in agse.deployments[0].properties].count("host_instance:Servos") == 3
    example = imported("textual-v0.3/timer_example")
    node = example.deployments[0].nodes[0]
    assert (node.hostRef, node.priority, node.componentInstances[0].componentRef) == (
        "hardware/BBB_111",
        80,
        "timer_package/Timer_Component",
    )
    assert example.deployments[0].system is example.systems[0]
    periodic = imported("textual-v0.3/periodic-timers")
    inst = periodic.deployments[0].nodes[0].componentInstances[0]
    assert [p.key for p in inst.logging] == ["Is Periodic?", "Periodic Log Unit"]

"""ROSMOD → AADL (rosaadl.transforms.rosmod_to_aadl): the mapping, names, times, trace, errors,
and every corpus project converted, written, read back and instantiated."""

from __future__ import annotations

import functools
import logging
import zipfile
from decimal import Decimal
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.errors import ImportFormatError, TransformationError
from rosaadl.importers import ros_msg, rosmod_text, rosmod_webgme
from rosaadl.importers.rosmod_text import RosmodImportError
from rosaadl.properties import Reference, own_property
from rosaadl.transforms import trace as tracing
from rosaadl.transforms.aadl_to_rosmod import aadl_to_rosmod
from rosaadl.transforms.rosmod_to_aadl import (
    NameScope,
    aadl_identifier,
    rosmod_to_aadl,
    seconds_to_time,
    time_to_seconds,
)
from rosaadl.units import Quantity
from rosaadl.workflow.convert import convert_project_files
from rosaadl.workflow.workspace import library_unit_names

# --------------------------------------------------------------------------- a small project of our own

RML = """/* nav software */
package nav
{
  component Planner : Base
  {
    publisher <nav/Path> path_pub;
    subscriber <nav/Goal> goal_sub { priority = 60; deadline = 0.250; }
    client <nav/Plan> plan_client;
    subscriber <std_msgs/String> log_sub { priority = 1; deadline = 0.1; }
    timer tick { period = 0.1; priority = 50; deadline = 0.05; }
    timer data { period = 0.0333333; }
  }
  component Driver : KSP
  {
    subscriber <nav/Path> path_sub { priority = 50; deadline = 0.2; }
    server <nav/Plan> plan_server { deadline = 1.5; priority = 10; }
  }
}
"""
RHW = """hardware board-1
{
  ip_address = "10.0.0.2";
  username = "robot";
  arch = armv7l;
  init = "/etc/init.sh";
}
hardware laptop { ip_address = "localhost"; arch = x64; }
"""
RDP = """using lab-net;
node planner_node
{
  properties { ref = "lab-net/board-1"; priority = 70; cmd_args = "--fast"; }
  component_instance planner
  {
    properties
    {
      ref = "nav/Planner";
      scheduling_scheme = PFIFO;
      logging { Is Periodic? = true; Periodic Log Unit = 1000; }
    }
    port_instance p1 { ref = "Planner/path_pub"; group = "g1"; }
  }
}
node driver_node
{
  properties { ref = "lab-net/laptop"; priority = 50; }
  component_instance driver { properties { ref = "nav/Driver"; scheduling_scheme = EDF; } }
  component_instance planner2 { properties { ref = "nav/Planner"; } }
}
"""
FILES = {
    "demo-project.rosmod": "This is a ROSMOD Project",
    "01-Software/nav.rml": RML,
    "01-Software/msg/nav.Path.msg": "float64[3] x  # a point\nint32 n\n",
    "01-Software/msg/nav.Goal.msg": "string name\n",
    "01-Software/srv/nav.Plan.srv": "int32 a\n---\nfloat64 b\n",
    "02-Hardware/lab-net.rhw": RHW,
    "03-Deployment/main.rdp": RDP,
}


def write_model(aadl, folder: Path):
    from rosaadl.exporters.aadl_text import write_model as write

    return write(aadl, folder)


def write_files(folder: Path, files: dict[str, str]) -> Path:
    for relative, text in files.items():
        target = folder / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text, encoding="utf-8")
    return folder


@pytest.fixture
def project(tmp_path):
    return rosmod_text.read_project(write_files(tmp_path / "demo-project", FILES))


def unit(result, name):
    found = model.find_unit(result.model, name)
    assert found is not None, f"no unit {name}: {[u.name for u in result.model.units]}"
    return found


def classifier(result, qualified):
    found = model.find_classifier(result.model, qualified)
    assert found is not None, qualified
    return found


def member(owner, feature, name):
    return next(m for m in getattr(owner, feature) if m.name == name)


def prop(holder, name):
    return own_property(holder, name)


# --------------------------------------------------------------------------- names and times


@pytest.mark.parametrize(
    ("rosmod", "aadl"),
    [
        ("Planner", "Planner"),
        ("board-1", "board_1"),
        ("3_Sat_Cluster", "x3_Sat_Cluster"),
        ("Intro System", "Intro_System"),
        ("a__b_", "a_b"),
        ("__", "x"),
        ("", "x"),
        ("nœud", "n_ud"),
    ],
)
def test_aadl_identifier(rosmod, aadl):
    assert aadl_identifier(rosmod) == aadl


def test_name_scope_is_case_insensitive_and_avoids_reserved_words():
    scope = NameScope(["taken"])
    assert scope.take("data") == "data_1"  # reserved word
    assert scope.take("Port") == "Port_1"
    assert scope.take("Taken") == "Taken_1"
    assert scope.take("node") == "node"
    assert scope.take("NODE") == "NODE_1"
    assert scope.take("node") == "node_2"
    assert scope.take("node_1") == "node_1_1"  # NODE_1 is taken, case-insensitively


def test_library_unit_names_are_reserved_for_units():
    names = library_unit_names()
    assert {"ros", "ros_data", "rosmod_properties", "timing_properties"} <= names


@pytest.mark.parametrize(
    ("seconds", "value", "unit", "exact"),
    [
        ("0.5", 500, "ms", True),
        ("0.500", 500, "ms", True),
        ("2", 2000, "ms", True),
        ("0", 0, "ms", True),
        ("0.033333", 33333, "us", True),
        ("0.0333333", 33333300, "ns", True),
        ("1e-9", 1, "ns", True),
        ("1.5e-12", 2, "ps", False),
    ],
)
def test_seconds_to_time_is_exact(seconds, value, unit, exact):
    assert seconds_to_time(Decimal(seconds)) == (value, unit, exact)
    if exact:
        assert time_to_seconds(value, unit) == Decimal(seconds)


def test_time_to_seconds_gives_plain_decimals():
    assert str(time_to_seconds(500, "ms")) == "0.5"
    assert str(time_to_seconds(10, "sec")) == "10"
    assert str(time_to_seconds(2, "min")) == "120"
    assert time_to_seconds(3, "Bytes") is None


@pytest.mark.parametrize("seconds", ["soon", None, "nan", "inf", [1]])
def test_seconds_to_time_refuses_what_is_not_a_number_of_seconds(seconds):
    with pytest.raises(TransformationError, match="not a number of seconds"):
        seconds_to_time(seconds)


# --------------------------------------------------------------------------- the mapping


def test_units_and_their_kinds(project):
    result = rosmod_to_aadl(project)
    kinds = {u.name: str(prop(u, "ROSMOD_Properties::Unit_Kind")) for u in result.model.units}
    assert kinds == {
        "demo_project_project": "Project",
        "nav": "Software",
        "std_msgs": "Interfaces",
        "lab_net_hardware": "Hardware",
        "main_deployment": "Deployment",
    }
    assert result.roots == {"main": "main_deployment::main.impl"}
    project_unit = unit(result, "demo_project_project")
    assert prop(project_unit, "ROSMOD_Properties::Name") == "demo-project"
    assert prop(project_unit, "ROSMOD_Properties::Software_Name") == "nav"
    assert list(unit(result, "nav").withs) == ["ros", "ROS_Properties", "ROSMOD_Properties", "std_msgs"]


def test_messages_and_services(project):
    result = rosmod_to_aadl(project)
    path = classifier(result, "nav::Path_1")  # 'path' is an AADL reserved word
    assert prop(path, "ROSMOD_Properties::Name") == "Path"
    assert path.category.name == "data"
    assert prop(path, "Data_Size") == Quantity(28, "Bytes")  # 3 float64 + int32
    assert prop(path, "ROS_Properties::Message_Type") == "nav/Path"
    assert prop(path, "ROSMOD_Properties::Definition") == "float64[3] x  # a point\nint32 n\n"
    assert prop(classifier(result, "nav::Goal"), "Data_Size") is None  # a string: variable size
    plan = classifier(result, "nav::Plan")
    assert plan.category.name == "subprogram"
    assert [(f.name, f.direction.name, f.classifier) for f in plan.features] == [
        ("request", "in", "nav::Plan_Request"),
        ("response", "out", "nav::Plan_Response"),
    ]
    assert prop(classifier(result, "nav::Plan_Request"), "Data_Size") == Quantity(4, "Bytes")
    assert prop(classifier(result, "nav::Plan_Response"), "Data_Size") == Quantity(8, "Bytes")
    string = classifier(result, "std_msgs::String")
    assert prop(string, "ROS_Properties::Message_Type") == "std_msgs/String"


def test_component_thread_group_threads_and_queue(project):
    result = rosmod_to_aadl(project)
    planner = classifier(result, "nav::Planner")
    assert planner.category.name == "threadGroup"
    assert [
        (f.name, f.category.name, f.direction.name if f.eIsSet("direction") else f.access.name)
        for f in planner.features
    ] == [
        ("path_pub", "eventDataPort", "out"),
        ("goal_sub", "eventDataPort", "in"),
        ("plan_client", "subprogramAccess", "requires"),
        ("log_sub", "eventDataPort", "in"),
    ]
    assert member(planner, "features", "log_sub").classifier == "std_msgs::String"
    assert prop(planner, "ROSMOD_Properties::Datatype") == "Base"
    impl = classifier(result, "nav::Planner.impl")
    subs = {s.name: s for s in impl.subcomponents}
    assert list(subs) == ["callback_queue", "tick", "data_1", "goal_sub_callback", "log_sub_callback"]
    assert subs["callback_queue"].classifier == "ros::callback_queue"
    tick = subs["tick"]
    assert tick.classifier == "nav::timer_callback.impl"
    assert prop(tick, "Period") == Quantity(100, "ms")
    assert prop(tick, "Deadline") == Quantity(50, "ms")
    assert prop(tick, "Priority") == 50
    data = subs["data_1"]  # 'data' is an AADL reserved word
    assert prop(data, "ROSMOD_Properties::Name") == "data"
    assert prop(data, "Period") == Quantity(33333300, "ns")
    assert prop(data, "Deadline") is None and prop(data, "Priority") is None
    goal = subs["goal_sub_callback"]
    assert goal.classifier == "nav::subscriber_callback.impl"
    assert prop(goal, "Deadline") == Quantity(250, "ms")
    assert prop(goal, "ROSMOD_Properties::Deadline_Seconds") == "0.250"  # as written
    assert prop(goal, "Period") is None  # sporadic
    conns = {(c.source, c.destination): c.kind.name for c in impl.connections}
    assert conns[("goal_sub", "goal_sub_callback.cb_msg")] == "portConnection"
    assert conns[("callback_queue", "tick.callback_queue")] == "accessConnection"
    assert sum(1 for c in impl.connections if c.source == "callback_queue") == 4
    thread = classifier(result, "nav::timer_callback")
    assert thread.extended == "ros::timer"
    assert [(f.name, f.classifier) for f in thread.features] == [("callback_queue", "ros::callback_queue")]
    driver_impl = classifier(result, "nav::Driver.impl")
    assert ("plan_server_callback.srv", "plan_server") in {
        (c.source, c.destination) for c in driver_impl.connections
    }


def test_hardware(project):
    result = rosmod_to_aadl(project)
    impl = classifier(result, "lab_net_hardware::lab_net.impl")
    board = member(impl, "subcomponents", "board_1")
    assert board.category.name == "processor"
    assert prop(board, "ROSMOD_Properties::Name") == "board-1"
    ptype = classifier(result, board.classifier)
    assert prop(ptype, "ROSMOD_Properties::IP_Address") == "10.0.0.2"
    assert prop(ptype, "Hardware_Properties::Architecture") == "armv7l"
    settings = prop(ptype, "ROSMOD_Properties::Settings")
    assert settings == [{"Key": "init", "Value": "/etc/init.sh"}]


def test_deployment_nodes_bindings_and_topics(project):
    result = rosmod_to_aadl(project)
    dep = unit(result, "main_deployment")
    assert prop(dep, "ROSMOD_Properties::System_Name") == "lab-net"
    impl = classifier(result, "main_deployment::main.impl")
    assert [(s.name, s.category.name) for s in impl.subcomponents] == [
        ("lab_net", "system"),
        ("ROSbus", "virtualBus"),
        ("planner_node", "process"),
        ("driver_node", "process"),
    ]
    bindings = {
        (a.property, a.appliesTo[0]): [i.path for i in a.ownedValues[0].value.ownedItems]
        for a in impl.ownedPropertyAssociations
    }
    assert bindings[("Actual_Processor_Binding", "planner_node")] == ["lab_net.board_1"]
    assert bindings[("Actual_Processor_Binding", "driver_node")] == ["lab_net.laptop"]
    # path_pub of planner (on planner_node) reaches path_sub of driver (on driver_node)
    topics = [c for c in impl.connections if c.kind.name == "portConnection"]
    assert [(c.source, c.destination) for c in topics] == [
        ("planner_node.planner_path_pub", "driver_node.driver_path_sub")
    ]
    # a topic between two nodes carries its binding itself; one inside a node is bound from here
    assert prop(topics[0], "Actual_Connection_Binding") == [Reference("ROSbus")]
    # plan_client of planner2 (driver_node) is served by driver's plan_server in the same node, and
    # plan_client of planner (planner_node) across the nodes
    services = [c for c in impl.connections if c.kind.name == "accessConnection"]
    assert [(c.source, c.destination) for c in services] == [
        ("driver_node.driver_plan_server", "planner_node.planner_plan_client")
    ]
    process = classifier(result, "main_deployment::planner_node")
    assert process.extended == "ros::node"
    assert prop(process, "Priority") == 70
    assert prop(process, "ROSMOD_Properties::Arguments") == "--fast"
    driver_impl = classifier(result, "main_deployment::driver_node.impl")
    assert driver_impl.extended == "ros::node.impl"
    inner = {(c.source, c.destination) for c in driver_impl.connections}
    assert ("driver.plan_server", "planner2.plan_client") in inner  # the service inside the node
    planner = member(classifier(result, "main_deployment::planner_node.impl"), "subcomponents", "planner")
    assert planner.classifier == "nav::Planner.impl"
    assert str(prop(planner, "ROSMOD_Properties::Scheduling_Scheme")) == "PFIFO"
    assert prop(planner, "ROSMOD_Properties::Logging") == [
        {"Key": "Is Periodic?", "Value": "true"},
        {"Key": "Periodic Log Unit", "Value": "1000"},
    ]
    assert prop(planner, "ROSMOD_Properties::Port_Instances") == [
        {"Name": "p1", "Port_Ref": "Planner/path_pub", "Group_Name": "g1"}
    ]


def test_output_is_deterministic(project):
    from rosaadl.exporters.aadl_text import write_unit

    first = [write_unit(u) for u in rosmod_to_aadl(project).model.units]
    second = [write_unit(u) for u in rosmod_to_aadl(project).model.units]
    assert first == second


def test_trace_links_rosmod_elements_to_aadl_elements(project, tmp_path):
    result = rosmod_to_aadl(project)
    index = tracing.TraceIndex(result.trace)
    assert {"project", "package", "message", "component", "timer", "subscriber", "node"} <= set(index.rules())
    timer = project.software.packages[0].components[0].timers[0]
    (link,) = index.links_from(timer)
    assert link.rule == "timer"
    targets = [end.path for end in link.targets]
    assert targets[0] == "/units[nav]/classifiers[Planner.impl]/subcomponents[tick]"
    for end in link.targets:  # every key is the element's key in the finished model
        assert tracing.find_by_key(result.model, end.path) is end.object
    saved = tracing.save_trace(result.trace, tmp_path / "demo.trace")
    again = tracing.TraceIndex(tracing.load_trace(saved))
    assert again.origin_keys(targets[0]) == ["/software[nav]/packages[nav]/components[Planner]/timers[tick]"]
    assert rosmod_to_aadl(project, trace=False).trace is None


# --------------------------------------------------------------------------- bad input


def test_component_instance_without_its_component_is_a_located_error(project):
    inst = project.deployments[0].nodes[0].componentInstances[0]
    inst.component = None
    with pytest.raises(TransformationError) as err:
        rosmod_to_aadl(project)
    assert err.value.rule == "component_instance"
    assert "nav/Planner" in err.value.message
    assert err.value.location.file == "03-Deployment/main.rdp"
    assert err.value.location.line == 5


def test_node_on_a_host_that_does_not_resolve_is_a_located_error(project):
    node = project.deployments[0].nodes[1]
    node.host = None
    node.hostRef = "lab-net/nowhere"
    with pytest.raises(TransformationError) as err:
        rosmod_to_aadl(project)
    assert "lab-net/nowhere" in err.value.message and err.value.location.line == 16


def test_node_on_a_host_of_another_project_is_an_error(project, tmp_path):
    other = rosmod_text.read_project(write_files(tmp_path / "other", FILES))
    project.deployments[0].nodes[0].host = other.systems[0].hosts[0]
    with pytest.raises(TransformationError, match="not a host of a hardware model of this project"):
        rosmod_to_aadl(project)


def test_port_of_an_unknown_message_type_is_a_located_error(project):
    port = project.software.packages[0].components[0].ports[0]
    port.type = "nav/Missing"
    with pytest.raises(TransformationError) as err:
        rosmod_to_aadl(project)
    assert err.value.rule == "publisher"
    assert "package 'nav' defines no message 'Missing'" in err.value.message
    assert err.value.location.file == "01-Software/nav.rml" and err.value.location.line == 6


def test_publisher_of_a_service_type_is_an_error(project):
    project.software.packages[0].components[0].ports[0].type = "nav/Plan"
    with pytest.raises(TransformationError, match="needs a message type, but 'nav/Plan' is a service"):
        rosmod_to_aadl(project)


def test_link_that_joins_nothing_is_an_error():
    new = model.new
    system = new("rosmod.System", name="lab", hosts=[new("rosmod.Host", name="h")])
    system.links.append(new("rosmod.Link", name="l", host=system.hosts[0]))
    project = new("rosmod.Project", name="p", systems=[system])
    with pytest.raises(TransformationError, match="link 'l' does not join"):
        rosmod_to_aadl(project)


def test_not_a_project_is_an_error():
    with pytest.raises(TransformationError):
        rosmod_to_aadl(model.new("AadlModel", name="x"))


@pytest.mark.parametrize(
    ("relative", "old", "new", "message"),
    [
        ("03-Deployment/main.rdp", "lab-net/laptop", "lab-net/nowhere", "unknown host 'nowhere'"),
        ("03-Deployment/main.rdp", '"nav/Driver"', '"navx/Driver"', "unknown package 'navx'"),
        ("01-Software/nav.rml", "component Driver", "component Planner", "duplicate component name"),
        ("01-Software/nav.rml", "<nav/Goal>", "<nav/Gaol>", "unknown message type 'nav/Gaol'"),
        ("01-Software/nav.rml", "timer data { period = 0.0333333; }", "timer data {", "unclosed '{'"),
    ],
)
def test_bad_projects_fail_with_located_errors_before_conversion(tmp_path, relative, old, new, message):
    files = dict(FILES)
    assert old in files[relative]
    files[relative] = files[relative].replace(old, new, 1)
    folder = write_files(tmp_path / "bad", files)
    with pytest.raises(RosmodImportError) as err:
        rosmod_to_aadl(rosmod_text.read_project(folder))
    assert message in str(err.value)
    assert err.value.location.file.endswith(relative) and err.value.location.line


def test_bad_webgme_archives_fail_with_located_errors(tmp_path):
    not_zip = tmp_path / "x.webgmex"
    not_zip.write_bytes(b"this is not a zip archive")
    with pytest.raises(ImportFormatError) as err:
        rosmod_webgme.read_webgmex(not_zip)
    assert err.value.location.file == str(not_zip)
    evil = tmp_path / "evil.webgmex"
    with zipfile.ZipFile(evil, "w") as archive:
        archive.writestr("project.json", "{}")
        archive.writestr("../../x", "boom")
    with pytest.raises(ImportFormatError) as err:
        rosmod_webgme.read_webgmex(evil)
    assert err.value.location.path == "../../x"
    assert not (tmp_path.parent / "x").exists()


# --------------------------------------------------------------------------- write, read, instantiate


def _threads_expected(deployment) -> int:
    return sum(
        len(i.component.timers)
        + sum(1 for p in i.component.ports if p.eClass.name in ("Subscriber", "Server"))
        for n in deployment.nodes
        for i in n.componentInstances
    )


def _check_reads_and_instantiates(project, folder: Path) -> None:
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    result = rosmod_to_aadl(project)
    write_model(result.model, folder)
    aadl = read_files([folder])
    for deployment in project.deployments:
        root = instantiate(aadl, result.roots[deployment.name])
        threads = [
            o
            for o in model.walk(root)
            if o.eClass.name == "ComponentInstance" and o.category.name == "thread"
        ]
        assert len(threads) == _threads_expected(deployment), deployment.name
        for thread in threads:
            assert property_dispatch(thread) in ("Periodic", "Sporadic")
    back = aadl_to_rosmod(aadl)
    assert model.model_differences(project, back) == []


def property_dispatch(thread) -> str:
    from rosaadl.properties import property_value

    return str(property_value(thread, "Dispatch_Protocol"))


def test_small_project_reads_back_and_instantiates(project, tmp_path):
    _check_reads_and_instantiates(project, tmp_path / "aadl")


def test_instance_carries_times_bindings_and_topics(project, tmp_path):
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.properties import property_value
    from rosaadl.transforms.instantiate import instantiate

    result = rosmod_to_aadl(project)
    write_model(result.model, tmp_path)
    root = instantiate(read_files([tmp_path]), result.roots["main"])
    tick = model.find_instance(root, "planner_node.planner.tick")
    assert property_value(tick, "Period") == Quantity(100, "ms")
    assert property_value(tick, "Priority") == 50
    assert str(property_value(tick, "Dispatch_Protocol")) == "Periodic"
    goal = model.find_instance(root, "planner_node.planner.goal_sub_callback")
    assert str(property_value(goal, "Dispatch_Protocol")) == "Sporadic"
    node = model.find_instance(root, "planner_node")
    (host,) = property_value(node, "Actual_Processor_Binding")
    assert model.instance_path(host) == "main_impl_Instance.lab_net.board_1"
    queue = model.find_instance(root, "planner_node.planner.callback_queue")
    assert str(property_value(queue, "Concurrency_Control_Protocol")) == "Semaphore"
    assert str(property_value(queue, "ROSMOD_Properties::Scheduling_Scheme")) == "PFIFO"  # inherited
    ends = {
        (model.instance_path(c.source), model.instance_path(c.destination))
        for c in model.walk(root)
        if c.eClass.name == "ConnectionInstance" and c.kind.name == "portConnection"
    }
    assert (
        "main_impl_Instance.planner_node.planner.path_pub",
        "main_impl_Instance.driver_node.driver.path_sub_callback.cb_msg",
    ) in ends


# --------------------------------------------------------------------------- the corpus

CORPUS_PROJECTS = [
    *(f"textual-v0.3/{n}" for n in (
        "agse", "client-server", "integration", "isorc2016", "ksp_rover_controller",
        "long-running-operation", "periodic-timers", "publish-subscribe", "sequential-leds",
        "ten-components", "three-components", "timer", "timer_example", "trajectory-planner", "uav",
    )),
    *(f"textual-v0.3/roscpp/{n}" for n in (
        "ksp_rover_control", "ksp_stearwing_control", "pub_sub_cycle_example", "pub_sub_traffic_gen",
        "routing", "tg_test",
    )),
    "legacy-v0.2/sample",
    "legacy-v0.1/input.rosml",
    "agse2015/agse_rosmod_project",
    "agse2015/agse_rosmod_v3",
]  # fmt: skip
WEBGME_PROJECTS = [
    *(("samples-2016-06-13_noTLC.webgmex", n) for n in (
        "AGSE", "AGSE Pub-Sub", "Blinking LEDs", "Client Server", "Integration Test",
        "Introduction to ROSMOD", "KSP Flight Controller", "KSP Rover Controller", "Periodic Timer",
        "Publish Subscribe",
    )),
    *(("samples-2018-05-19_noTLC.webgmex", n) for n in (
        "AGSE", "Introduction to ROSMOD", "KSP Flight Controller", "KSP Rover Controller",
    )),
]  # fmt: skip


@functools.cache
def read_corpus_project(root: str, relative: str):
    return rosmod_text.read_project(Path(root) / "rosmod" / relative)


@functools.cache
def read_webgme_project(root: str, archive: str, name: str):
    return rosmod_webgme.read_webgmex(Path(root) / "rosmod" / "webgme" / archive, project=name)[0]


@pytest.mark.parametrize("relative", CORPUS_PROJECTS)
def test_corpus_textual_project_converts_reads_and_instantiates(corpus, relative, tmp_path, caplog):
    caplog.set_level(logging.ERROR)
    project = read_corpus_project(str(corpus), relative)
    _check_reads_and_instantiates(project, tmp_path)


@pytest.mark.parametrize(("archive", "name"), WEBGME_PROJECTS)
def test_corpus_webgme_project_converts_reads_and_instantiates(corpus, archive, name, tmp_path, caplog):
    caplog.set_level(logging.ERROR)
    project = read_webgme_project(str(corpus), archive, name)
    _check_reads_and_instantiates(project, tmp_path)


def test_corpus_deployment_threads_match_the_callbacks(corpus):
    """Without the reader: the declarative model already holds one thread per callback."""
    project = read_corpus_project(str(corpus), "textual-v0.3/periodic-timers")
    result = rosmod_to_aadl(project)
    for deployment in project.deployments:
        impl = model.find_classifier(result.model, result.roots[deployment.name])
        count = 0
        for sub in impl.subcomponents:
            if sub.category.name != "process":
                continue
            process = model.find_classifier(result.model, sub.classifier)
            for group in process.subcomponents:
                tg = model.find_classifier(result.model, group.classifier)
                count += sum(1 for s in tg.subcomponents if s.category.name == "thread")
        assert count == _threads_expected(deployment)
    assert max(sum(len(n.componentInstances) for n in d.nodes) for d in project.deployments) == 150
    assert result.warnings == []


# --------------------------------------------------------------------------- topics, networks


def _networked_project(topic_of_sub: str | None = None):
    new = model.new
    msg = new("rosmod.Message", name="Scan", definition="float32[4] r\n")
    msg.fields.extend(
        ros_msg.fields_to_model(ros_msg.parse_msg(msg.definition, name="Scan", package="p").fields)
    )
    talker = new("rosmod.Component", name="talker")
    talker.ports.append(new("rosmod.Publisher", name="out", type="p/Scan"))
    talker.properties.append(new("rosmod.Property", key="out.Topic", value="p/front"))
    listener = new("rosmod.Component", name="listener")
    listener.ports.append(new("rosmod.Subscriber", name="in", type="p/Scan"))
    if topic_of_sub is not None:
        listener.properties.append(new("rosmod.Property", key="in.Topic", value=topic_of_sub))
    package = new("rosmod.Package", name="p", messages=[msg], components=[talker, listener])
    hosts = [
        new("rosmod.Host", name=n, interfaces=[new("rosmod.Interface", name="eth0")]) for n in ("a", "b", "c")
    ]
    net = new("rosmod.Network", name="net", subnet="10.0.0.0")
    system = new("rosmod.System", name="lab", hosts=hosts, networks=[net])
    for host in hosts[:2]:  # c is not on the network
        system.links.append(
            new(
                "rosmod.Link",
                name=f"{host.name}_link",
                host=host,
                interface=host.interfaces[0],
                network=net,
                ip="10.0.0.9",
            )
        )
    nodes = []
    for name, host, comp in (
        ("n1", hosts[0], talker),
        ("n2", hosts[1], listener),
        ("n3", hosts[2], listener),
    ):
        node = new("rosmod.Node", name=name, host=host, hostRef=f"lab/{host.name}")
        inst = new(
            "rosmod.ComponentInstance", name=f"{name}_i", component=comp, componentRef=f"p/{comp.name}"
        )
        node.componentInstances.append(inst)
        nodes.append(node)
    deployment = new("rosmod.Deployment", name="dep", systemName="lab", system=system, nodes=nodes)
    return new(
        "rosmod.Project",
        name="net",
        software=new("rosmod.Software", name="sw", packages=[package]),
        systems=[system],
        deployments=[deployment],
    )


def test_topics_between_linked_hosts_are_bound_to_their_network():
    project = _networked_project("p/front")
    result = rosmod_to_aadl(project)
    impl = model.find_classifier(result.model, "dep_deployment::dep.impl")
    bound = {c.destination: prop(c, "Actual_Connection_Binding") for c in impl.connections}
    assert bound == {"n2.n2_i_in": [Reference("lab.net")], "n3.n3_i_in": [Reference("ROSbus")]}
    assert {prop(c, "ROS_Properties::Topic_Name") for c in impl.connections} == {"front"}
    hardware = model.find_classifier(result.model, "lab_hardware::lab.impl")
    links = [(c.name, c.source, c.destination, c.accessCategory.name) for c in hardware.connections]
    assert links == [("a_link", "net", "a.eth0", "bus"), ("b_link", "net", "b.eth0", "bus")]
    assert prop(hardware.connections[0], "ROSMOD_Properties::IP_Address") == "10.0.0.9"
    assert model.model_differences(project, aadl_to_rosmod(result.model)) == []


def test_advertised_topics_must_match():
    result = rosmod_to_aadl(_networked_project("p/rear"))  # same type, another topic
    impl = model.find_classifier(result.model, "dep_deployment::dep.impl")
    assert list(impl.connections) == []
    result = rosmod_to_aadl(_networked_project(None))  # a plain subscriber: not the advertised topic
    impl = model.find_classifier(result.model, "dep_deployment::dep.impl")
    assert list(impl.connections) == []


def test_a_topic_inside_a_node_is_bound_from_the_deployment(project):
    result = rosmod_to_aadl(project)
    impl = classifier(result, "main_deployment::main.impl")
    inner = [a for a in impl.ownedPropertyAssociations if a.property == "Actual_Connection_Binding"]
    assert [(list(a.appliesTo), a.ownedValues[0].value.ownedItems[0].path) for a in inner] == [
        (["driver_node.topic_Path"], "ROSbus"),
        (["driver_node.service_Plan"], "ROSbus"),
    ]
    node = classifier(result, "main_deployment::driver_node.impl")
    assert ("planner2.path_pub", "driver.path_sub") in {(c.source, c.destination) for c in node.connections}


# ------------------------------------------------------------- files in, files out (the CLI's work)


def test_convert_project_files(tmp_path):
    folder = write_files(tmp_path / "demo-project", FILES)
    warnings = []
    written = convert_project_files(
        folder, tmp_path / "out", trace_file=tmp_path / "out" / "demo.trace", warnings=warnings
    )
    names = sorted(p.name for p in written)
    assert names == [
        "demo.trace",
        "demo_project_project.aadl",
        "lab_net_hardware.aadl",
        "main_deployment.aadl",
        "nav.aadl",
        "std_msgs.aadl",
    ]
    assert tracing.load_trace(tmp_path / "out" / "demo.trace").transformation == "rosmod2aadl"
    assert "package nav\n" in (tmp_path / "out" / "nav.aadl").read_text()


def test_convert_project_files_puts_each_project_of_an_archive_in_its_folder(corpus, tmp_path):
    archive = corpus / "rosmod" / "webgme" / "samples-2018-05-19_noTLC.webgmex"
    written = convert_project_files(archive, tmp_path / "out", trace_file=tmp_path / "out" / "t.json")
    folders = sorted({p.parent.name for p in written if p.suffix == ".aadl"})
    assert folders == ["AGSE", "Introduction_to_ROSMOD", "KSP_Flight_Controller", "KSP_Rover_Controller"]
    assert (tmp_path / "out" / "t_Introduction_to_ROSMOD.json").is_file()
    one = convert_project_files(archive, tmp_path / "one", project="AGSE")
    assert {p.parent for p in one} == {tmp_path / "one"}


def test_convert_project_files_fails_before_writing(tmp_path):
    files = dict(FILES)
    files["01-Software/nav.rml"] = files["01-Software/nav.rml"].replace(
        "timer data { period = 0.0333333; }", "timer data {"
    )
    folder = write_files(tmp_path / "bad", files)
    with pytest.raises(RosmodImportError):
        convert_project_files(folder, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_names_that_clash_with_the_library_or_each_other():
    new = model.new
    packages = [
        new("rosmod.Package", name="ros", components=[new("rosmod.Component", name="Node")]),
        new("rosmod.Package", name="ROS_Properties"),
        new("rosmod.Package", name="../../x"),
    ]
    hosts = [new("rosmod.Host", name="h"), new("rosmod.Host", name="H")]
    project = new(
        "rosmod.Project",
        name="clash",
        software=new("rosmod.Software", name="sw", packages=packages),
        systems=[new("rosmod.System", name="ros", hosts=hosts)],
    )
    result = rosmod_to_aadl(project, reserved_units=library_unit_names())
    names = [u.name for u in result.model.units]
    assert names == ["clash_project", "ros_1", "ROS_Properties_1", "x", "ros_hardware"]
    assert prop(result.model.units[1], "ROSMOD_Properties::Name") == "ros"
    assert prop(result.model.units[3], "ROSMOD_Properties::Name") == "../../x"
    impl = model.find_classifier(result.model, "ros_hardware::ros.impl")
    assert [s.name for s in impl.subcomponents] == ["h", "H_1"]
    assert model.model_differences(project, aadl_to_rosmod(result.model)) == []

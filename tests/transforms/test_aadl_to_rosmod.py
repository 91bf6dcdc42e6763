"""AADL → ROSMOD (rosaadl.transforms.aadl_to_rosmod): the inverse of the convention for every corpus
project, names from the trace, edits in the AADL, and the best-effort mapping of other models."""

from __future__ import annotations

import functools
import importlib.util
import logging
from pathlib import Path

import pytest
from corpus_cases import ROSMOD_PROJECTS, WEBGME_SEEDS

from rosaadl import model
from rosaadl.errors import Diagnostic, TransformationError
from rosaadl.exporters.rosmod_text import write_project
from rosaadl.importers import rosmod_text, rosmod_webgme
from rosaadl.properties import own_property
from rosaadl.transforms import trace as tracing
from rosaadl.transforms.aadl_to_rosmod import (
    aadl_to_rosmod,
    aadl_to_rosmod_traced,
    is_rosmod_convention,
    top_level_systems,
)
from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl
from rosaadl.workflow.convert import convert_aadl_files, library_units

_WRITER = importlib.util.find_spec("rosaadl.exporters.aadl_text") is not None
_READER = _WRITER and importlib.util.find_spec("rosaadl.importers.aadl_text") is not None
_INSTANTIATE = importlib.util.find_spec("rosaadl.transforms.instantiate") is not None
needs_reader = pytest.mark.skipif(
    not _READER,
    reason="the AADL text writer or reader (exporters/aadl_text, importers/aadl_text) has not landed",
)
needs_instantiate = pytest.mark.skipif(
    not (_READER and _INSTANTIATE), reason="the AADL reader or the instantiator has not landed"
)

RML = """package nav
{
  component Planner : Base
  {
    publisher <nav/Goal> goal_pub;
    subscriber <nav/Goal> goal_sub { priority = 60; deadline = 0.250; }
    timer tick { period = 0.1; priority = 50; deadline = 0.05; }
  }
}
"""
RHW = """hardware board-1 { ip_address = "10.0.0.2"; arch = armv7l; }
hardware laptop { ip_address = "localhost"; arch = x64; }
"""
RDP = """using lab-net;
node planner_node
{
  properties { ref = "lab-net/board-1"; priority = 70; }
  component_instance planner
  {
    properties { ref = "nav/Planner"; scheduling_scheme = PFIFO; logging { Is Periodic? = true; } }
  }
}
"""
FILES = {
    "small.rosmod": "This is a ROSMOD Project",
    "01-Software/nav.rml": RML,
    "01-Software/msg/nav.Goal.msg": "float64 x\nfloat64 y\n",
    "02-Hardware/lab-net.rhw": RHW,
    "03-Deployment/field test.rdp": RDP,
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
    return rosmod_text.read_project(write_files(tmp_path / "small", FILES))


def through_text(project, folder: Path, edit=None):
    """Convert, write the AADL, optionally edit the files, read them back (with the library)."""
    from rosaadl.importers.aadl_text import read_files

    result = rosmod_to_aadl(project)
    write_model(result.model, folder)
    if edit is not None:
        edit(folder)
    return result, read_files([folder])


def strip_names(aadl) -> int:
    """Remove every ROSMOD_Properties::Name but the project package's; how many were removed."""
    removed = 0
    for obj in list(model.walk(aadl)):
        if obj.eClass.name != "PropertyAssociation" or obj.property != "ROSMOD_Properties::Name":
            continue
        owner = obj.eContainer()
        if owner.eClass.name == "AadlPackage" and owner.name.endswith("_project"):
            continue
        owner.ownedPropertyAssociations.remove(obj)
        removed += 1
    return removed


# --------------------------------------------------------------------------- the convention


def test_in_memory_round_trip(project):
    result = rosmod_to_aadl(project)
    assert is_rosmod_convention(result.model)
    back = aadl_to_rosmod(result.model)
    assert model.model_differences(project, back) == []
    timer = back.software.packages[0].components[0].timers[0]
    assert str(timer.period) == "0.1" and timer.priority == 50
    sub = back.software.packages[0].components[0].ports[1]
    assert str(sub.deadline) == "0.250"  # as written, from Deadline_Seconds
    node = back.deployments[0].nodes[0]
    assert node.host is back.systems[0].hosts[0] and node.hostRef == "lab-net/board-1"
    assert node.componentInstances[0].component is back.software.packages[0].components[0]


@needs_reader
def test_round_trip_through_aadl_text(project, tmp_path):
    _, aadl = through_text(project, tmp_path)
    warnings: list[Diagnostic] = []
    back = aadl_to_rosmod(aadl, library=library_units(aadl), warnings=warnings)
    assert model.model_differences(project, back) == []
    assert warnings == []


@needs_reader
def test_the_trace_gives_the_names_back(project, tmp_path):
    result, aadl = through_text(project, tmp_path)
    trace_file = tracing.save_trace(result.trace, tmp_path / "small.trace")
    assert strip_names(aadl) == 3  # lab-net, board-1 and 'field test'
    without = aadl_to_rosmod(aadl)
    assert {d.name for d in without.deployments} == {"field_test"}
    assert {h.name for h in without.systems[0].hosts} == {"board_1", "laptop"}
    with_trace = aadl_to_rosmod(aadl, trace=tracing.load_trace(trace_file))
    assert model.model_differences(project, with_trace) == []


@needs_reader
def test_edited_times_win_over_the_written_seconds(project, tmp_path):
    def edit(folder):
        nav = folder / "nav.aadl"
        text = nav.read_text()
        assert "Deadline => 250 ms;" in text and "Period => 100 ms;" in text
        nav.write_text(
            text.replace("Deadline => 250 ms;", "Deadline => 300 ms;").replace(
                "Period => 100 ms;", "Period => 20 us;"
            )
        )

    _, aadl = through_text(project, tmp_path, edit)
    back = aadl_to_rosmod(aadl)
    comp = back.software.packages[0].components[0]
    assert str(comp.ports[1].deadline) == "0.3"  # the stale "0.250" is not used
    assert str(comp.timers[0].period) == "0.00002"


@needs_reader
def test_elements_outside_the_convention_are_located_warnings(project, tmp_path):
    def edit(folder):
        dep = folder / "field_test_deployment.aadl"
        text = dep.read_text()
        dep.write_text(
            text.replace(
                "      ROSbus: virtual bus ros::ROSbus.impl;",
                "      ROSbus: virtual bus ros::ROSbus.impl;\n      camera: device;",
            )
        )

    _, aadl = through_text(project, tmp_path, edit)
    warnings: list[Diagnostic] = []
    back = aadl_to_rosmod(aadl, library=library_units(aadl), warnings=warnings)
    assert [w.message for w in warnings] == [
        "device camera of field_test.impl has no ROSMOD counterpart; skipped"
    ]
    location = warnings[0].location
    assert location.file.endswith("field_test_deployment.aadl") and location.line
    assert location.path == "field_test_deployment::field_test.impl.camera"
    assert len(back.deployments[0].nodes) == 1


def test_not_a_model_is_an_error(project):
    with pytest.raises(TransformationError, match="expected an AADL model"):
        aadl_to_rosmod(project)


# --------------------------------------------------------------------------- the corpus

CORPUS_PROJECTS = list(ROSMOD_PROJECTS)
WEBGME_ARCHIVES = list(WEBGME_SEEDS)


@functools.cache
def webgme_projects(root: str, archive: str):
    return rosmod_webgme.read_webgmex(Path(root) / "rosmod" / "webgme" / archive)


@pytest.mark.parametrize("relative", CORPUS_PROJECTS)
def test_corpus_textual_project_round_trips(corpus, relative, caplog):
    caplog.set_level(logging.ERROR)
    project = rosmod_text.read_project(corpus / "rosmod" / relative)
    result = rosmod_to_aadl(project)
    assert model.model_differences(project, aadl_to_rosmod(result.model)) == []


@pytest.mark.parametrize("archive", WEBGME_ARCHIVES)
def test_corpus_webgme_projects_round_trip(corpus, archive, caplog):
    caplog.set_level(logging.ERROR)
    projects = webgme_projects(str(corpus), archive)
    assert len(projects) >= 4
    for project in projects:
        result = rosmod_to_aadl(project)
        assert model.model_differences(project, aadl_to_rosmod(result.model)) == [], project.name


@needs_reader
def test_corpus_names_come_back_from_the_trace(corpus, tmp_path, caplog):
    caplog.set_level(logging.ERROR)
    (project,) = [
        p
        for p in webgme_projects(str(corpus), "samples-2018-05-19_noTLC.webgmex")
        if p.name == "Introduction to ROSMOD"
    ]
    result, aadl = through_text(project, tmp_path)
    assert strip_names(aadl) > 0
    assert model.model_differences(project, aadl_to_rosmod(aadl)) != []
    assert model.model_differences(project, aadl_to_rosmod(aadl, trace=result.trace)) == []


# --------------------------------------------------------------------------- best effort

ROBOT = """package robot_sw
public
  with ROS_Properties;

  data Odometry
    properties
      ROS_Properties::Message_Type => "nav_msgs/Odometry";
  end Odometry;

  data Blob
  end Blob;

  thread sensor
    features
      odom: out event data port Odometry;
      raw: out event data port Blob;
    properties
      Dispatch_Protocol => Periodic;
      Period => 50 ms;
      Priority => 20;
  end sensor;

  thread implementation sensor.impl
  end sensor.impl;

  thread fuser
    features
      odom: in event data port Odometry;
      both: in out event data port Blob;
    properties
      Dispatch_Protocol => Sporadic;
      Deadline => 20 ms;
  end fuser;

  thread implementation fuser.impl
  end fuser.impl;

  thread idle
    properties
      Dispatch_Protocol => Background;
  end idle;

  thread implementation idle.impl
  end idle.impl;

  process driver
    features
      odom_out: out event data port Odometry;
      raw_out: out event data port Blob;
  end driver;

  process implementation driver.impl
    subcomponents
      sense: thread sensor.impl;
      rest: thread idle.impl;
    connections
      c1: port sense.odom -> odom_out;
      c2: port sense.raw -> raw_out;
  end driver.impl;

  process planner
    features
      odom_in: in event data port Odometry;
  end planner;

  process implementation planner.impl
    subcomponents
      fuse: thread fuser.impl;
    connections
      c3: port odom_in -> fuse.odom;
  end planner.impl;

  processor cpu
  end cpu;

  device lidar
  end lidar;

  system robot
  end robot;

  system implementation robot.impl
    subcomponents
      drv: process driver.impl;
      pln: process planner.impl;
      cpu1: processor cpu;
      cpu2: processor cpu;
      scan: device lidar;
    connections
      odom: port drv.odom_out -> pln.odom_in;
      mixed: port drv.raw_out -> pln.odom_in;
    properties
      Actual_Processor_Binding => (reference (cpu1)) applies to drv;
      Actual_Processor_Binding => (reference (cpu2)) applies to pln;
  end robot.impl;
end robot_sw;
"""


@needs_instantiate
def test_best_effort_on_a_model_of_our_own(tmp_path):
    from rosaadl.importers.aadl_text import read_files

    (tmp_path / "robot_sw.aadl").write_text(ROBOT)
    aadl = read_files([tmp_path / "robot_sw.aadl"])
    assert not is_rosmod_convention(aadl)
    library = library_units(aadl)
    assert top_level_systems(aadl, library=library) == ["robot_sw::robot.impl"]
    warnings: list[Diagnostic] = []
    project = aadl_to_rosmod(aadl, library=library, warnings=warnings)
    (deployment,) = project.deployments
    assert [(n.name, n.host.name, n.hostRef) for n in deployment.nodes] == [
        ("drv", "cpu1", "robot/cpu1"),
        ("pln", "cpu2", "robot/cpu2"),
    ]
    assert [i.name for i in deployment.nodes[0].componentInstances] == ["sense", "rest"]
    (package,) = project.software.packages
    assert package.name == "robot_sw"
    sensor, idle, fuser = package.components
    assert (sensor.name, idle.name, fuser.name) == ("sensor", "idle", "fuser")
    assert [(p.eClass.name, p.name, p.type) for p in sensor.ports] == [
        ("Publisher", "odom", "nav_msgs/Odometry"),
        ("Publisher", "raw", "robot_sw/Blob"),
    ]
    (timer,) = sensor.timers
    assert (timer.name, str(timer.period), timer.priority) == ("sense_timer", "0.05", 20)
    assert [(p.name, str(p.deadline)) for p in fuser.ports] == [("odom", "0.02")]
    assert [m.name for m in package.messages] == ["Blob"]
    messages = [w.message for w in warnings]
    paths = [w.location.path for w in warnings]
    assert any("device scan" in m for m in messages) and "robot_impl_Instance.scan" in paths
    assert any("thread rest has dispatch protocol Background" in m for m in messages)
    assert any("port both is 'in out'" in m for m in messages)
    assert any("robot_sw::Blob has no ROS_Properties::Message_Type" in m for m in messages)
    assert any("joins ports of different types" in m for m in messages)
    assert not aadl.instances  # the instances made for the conversion are not left behind
    out = tmp_path / "project"
    write_project(project, out)
    again = rosmod_text.read_project(out)
    assert rosmod_text.summarize(again)["component_instances"] == 3


@needs_instantiate
def test_best_effort_on_the_library_tracking_application(tmp_path):
    from rosaadl.importers.aadl_text import read_files

    aadl = read_files([], include_library=True)
    warnings: list[Diagnostic] = []
    project = aadl_to_rosmod(aadl, roots=["sys_tracking::tracking.impl"], warnings=warnings)
    (deployment,) = project.deployments
    nodes = {n.name: n for n in deployment.nodes}
    assert set(nodes) == {"usbcam", "tracker", "poscmd"}
    assert nodes["usbcam"].host.name == "big_proc1"
    assert nodes["poscmd"].host.name == "little_proc1"
    types = {p.type for pkg in project.software.packages for c in pkg.components for p in c.ports}
    assert {"sensor_msgs/Image", "geometry_msgs/Point", "geometry_msgs/Twist"} <= types
    periods = {str(t.period) for pkg in project.software.packages for c in pkg.components for t in c.timers}
    assert "0.033333" in periods and "0.1" in periods
    assert any(w.location.path == "tracking_impl_Instance.p3DX.camera" for w in warnings)
    out = tmp_path / "tracking"
    write_project(project, out)
    again = rosmod_text.read_project(out)
    counts = rosmod_text.summarize(again)
    assert counts["nodes"] == 3 and counts["component_instances"] == 6 and counts["hosts"] == 8


@needs_instantiate
def test_best_effort_without_roots_warns(tmp_path):
    from rosaadl.importers.aadl_text import read_files

    aadl = read_files([], include_library=True)
    warnings: list[Diagnostic] = []
    project = aadl_to_rosmod(aadl, library=library_units(aadl), warnings=warnings)
    assert len(project.deployments) == 0
    assert any("no root system implementation" in w.message for w in warnings)


@needs_instantiate
def test_best_effort_with_an_unknown_root_is_an_error():
    from rosaadl.importers.aadl_text import read_files

    aadl = read_files([], include_library=True)
    with pytest.raises(TransformationError, match="cannot instantiate nowhere::sys.impl"):
        aadl_to_rosmod(aadl, roots=["nowhere::sys.impl"])


# ------------------------------------------------------ the trace of AADL → ROSMOD, and names both ways

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "tracking"
#: the best-effort rules that keep the AADL name (the others name components after classifiers,
#: timers after threads, hardware models and deployments after the root's type)
KEEPS_AADL_NAMES = {"host", "node", "thread", "port"}


def _named(obj) -> str | None:
    return getattr(obj, "name", None) if obj.eClass.findEStructuralFeature("name") else None


def names_lost(back, forward, keeps=None) -> tuple[int, list[str]]:
    """Follow ``back`` (an AADL → ROSMOD trace) then ``forward`` (ROSMOD → AADL): how many
    ROSMOD elements were checked, and those whose name did not come back. Each ROSMOD element
    must have its name among the AADL elements made from it (as their name, or in their
    ``ROSMOD_Properties::Name`` where it is not an AADL identifier), and — for every rule when ``keeps``
    is None, else for the rules in ``keeps`` — one of the AADL elements it came from must have a
    namesake there too (the model read from files is named by the reader: it is not checked)."""
    made: dict[int, set[str]] = {}
    for link in forward.links:
        for end in link.sources:
            names = made.setdefault(id(end.object), set())
            for target in link.targets:  # its AADL name, and the ROSMOD name it keeps when not one
                names.update((_named(target.object), own_property(target.object, "ROSMOD_Properties::Name")))
    checked, lost = 0, []
    for link in back.links:
        for end in link.targets:
            names = made.get(id(end.object), set())
            checked += 1
            name = _named(end.object)
            if name not in names and f"{name}_project" not in names:  # a project's package: <name>_project
                lost.append(f"{link.rule}: {end.path} is not in {sorted(n for n in names if n)}")
            origins = [s.object for s in link.sources if not model.is_a(s.object, "AadlModel")]
            kept = any(_named(o) in names for o in origins)
            if (keeps is None or link.rule in keeps) and origins and not kept:
                lost.append(
                    f"{link.rule}: {[s.path for s in link.sources]} -> {sorted(n for n in names if n)}"
                )
    return checked, lost


def test_the_trace_of_aadl_to_rosmod(project, tmp_path):
    result = rosmod_to_aadl(project)
    back = aadl_to_rosmod_traced(result.model)
    assert model.model_differences(project, back.project) == [] and back.warnings == []
    assert back.trace.transformation == "aadl2rosmod"
    index = tracing.TraceIndex(back.trace)
    assert {
        "project",
        "package",
        "message",
        "component",
        "port",
        "timer",
        "callback",
        "hardware",
        "host",
    } <= set(index.rules())
    assert {"deployment", "node", "component_instance", "interface"} <= set(index.rules()) or not any(
        h.interfaces for s in project.systems for h in s.hosts
    )
    (link,) = index.links_from("/units[nav]/classifiers[Planner.impl]/subcomponents[tick]")
    assert (link.rule, [e.path for e in link.targets]) == (
        "timer",
        ["/software[nav]/packages[nav]/components[Planner]/timers[tick]"],
    )
    (link,) = index.links_from("/units[nav]/classifiers[Planner.impl]/subcomponents[goal_sub_callback]")
    assert (link.rule, [e.path for e in link.targets]) == (
        "callback",
        ["/software[nav]/packages[nav]/components[Planner]/ports[goal_sub]"],
    )
    (link,) = [link for link in back.trace.links if link.rule == "component_instance"]
    assert [e.className for e in link.sources] == ["Subcomponent", "Subcomponent"]
    assert [e.path for e in link.targets] == [
        "/deployments[field test]/nodes[planner_node]/componentInstances[planner]"
    ]
    saved = tracing.save_trace(back.trace, tmp_path / "back.trace.json")
    again = tracing.TraceIndex(tracing.load_trace(saved))
    assert again.origin_keys("/software[nav]/packages[nav]/components[Planner]/timers[tick]") == [
        "/units[nav]/classifiers[Planner.impl]/subcomponents[tick]"
    ]
    # the untraced conversion gives the same project
    assert model.model_differences(back.project, aadl_to_rosmod(result.model)) == []


def test_a_trace_is_given_as_a_model_not_as_a_file(project, tmp_path):
    result = rosmod_to_aadl(project)
    saved = tracing.save_trace(result.trace, tmp_path / "small.trace")
    with pytest.raises(TransformationError, match="expected the trace"):
        aadl_to_rosmod(result.model, trace=saved)


@needs_reader
def test_tracking_example_names_survive_both_ways(tmp_path, caplog):
    """ROSMOD → AADL → ROSMOD gives the project back, and AADL → ROSMOD → AADL the names back,
    through AADL text, with the traces of the three runs."""
    caplog.set_level(logging.ERROR)
    project = rosmod_text.read_project(EXAMPLE)
    first, aadl = through_text(project, tmp_path)
    back = aadl_to_rosmod_traced(aadl, trace=first.trace, library=library_units(aadl))
    assert model.model_differences(project, back.project) == [] and back.warnings == []
    again = rosmod_to_aadl(back.project)
    checked, lost = names_lost(back.trace, again.trace)
    assert checked > 30 and lost == []
    assert [u.name for u in again.model.units] == [u.name for u in first.model.units]


@needs_instantiate
def test_library_tracking_application_names_survive_both_ways(caplog):
    """Best effort: processes, processors, threads and ports keep their AADL names through ROSMOD
    and back; every ROSMOD element keeps its name through AADL."""
    from rosaadl.importers.aadl_text import read_files

    caplog.set_level(logging.ERROR)
    aadl = read_files([], include_library=True)
    back = aadl_to_rosmod_traced(aadl, roots=["sys_tracking::tracking.impl"], library=library_units(aadl))
    assert back.trace.transformation == "aadl2rosmod_best_effort"
    paths = {e.path for link in back.trace.links if link.rule == "node" for e in link.sources}
    assert (
        "/instances[tracking_impl_Instance]/componentInstances[rem_trk_sw]/componentInstances[usbcam]"
        in paths
    )
    again = rosmod_to_aadl(back.project)
    checked, lost = names_lost(back.trace, again.trace, keeps=KEEPS_AADL_NAMES)
    assert checked > 30 and lost == []


@pytest.mark.parametrize("relative", CORPUS_PROJECTS)
def test_corpus_names_survive_both_ways(corpus, relative, caplog):
    caplog.set_level(logging.ERROR)
    project = rosmod_text.read_project(corpus / "rosmod" / relative)
    first = rosmod_to_aadl(project)
    strip_names(first.model)
    back = aadl_to_rosmod_traced(first.model, trace=first.trace)
    assert model.model_differences(project, back.project) == []
    checked, lost = names_lost(back.trace, rosmod_to_aadl(back.project).trace)
    assert checked > 0 and lost == []


@pytest.mark.parametrize("archive", WEBGME_ARCHIVES)
def test_corpus_webgme_names_survive_both_ways(corpus, archive, caplog):
    caplog.set_level(logging.ERROR)
    for project in webgme_projects(str(corpus), archive):
        first = rosmod_to_aadl(project)
        strip_names(first.model)
        back = aadl_to_rosmod_traced(first.model, trace=first.trace)
        assert model.model_differences(project, back.project) == [], project.name
        checked, lost = names_lost(back.trace, rosmod_to_aadl(back.project).trace)
        assert checked > 0 and lost == [], project.name


#: AADL models of the corpus that are not ROSMOD projects, with their roots
CORPUS_AADL = {
    "osate/aaxl2/ex-latency-normal/core-examples/flowlatencyexamples": (
        "latency_distributed::latencytest.normal"
    ),
    "osate/aaxl2/ex-simple-thread-latency/core-examples/flowlatencyexamples": "SimpleThreadLatency::s.i",
    "osate/aaxl2/ex-pullprotocols/latency-case-study": "pullprotocols::stub.i",
}


@needs_instantiate
@pytest.mark.parametrize("relative", sorted(CORPUS_AADL))
def test_corpus_aadl_names_survive_both_ways(corpus, relative, caplog):
    from rosaadl.importers.aadl_text import read_files

    caplog.set_level(logging.ERROR)
    aadl = read_files([corpus / relative])
    back = aadl_to_rosmod_traced(aadl, roots=[CORPUS_AADL[relative]], library=library_units(aadl))
    assert back.project.deployments[0].nodes
    checked, lost = names_lost(back.trace, rosmod_to_aadl(back.project).trace, keeps=KEEPS_AADL_NAMES)
    assert checked > 0 and lost == []


# ------------------------------------------------------------- files in, files out (the CLI's work)


@needs_instantiate
def test_convert_aadl_files_best_effort(tmp_path):
    (tmp_path / "robot_sw.aadl").write_text(ROBOT)
    warnings: list[Diagnostic] = []
    written = convert_aadl_files([tmp_path / "robot_sw.aadl"], tmp_path / "robot", warnings=warnings)
    assert (tmp_path / "robot" / "03-Deployment" / "robot.rdp") in written
    assert rosmod_text.summarize(rosmod_text.read_project(tmp_path / "robot"))["nodes"] == 2
    assert any("device scan" in w.message for w in warnings)


@needs_reader
def test_convert_aadl_files_with_the_trace(project, tmp_path):
    result = rosmod_to_aadl(project)
    write_model(result.model, tmp_path / "aadl")
    trace_file = tracing.save_trace(result.trace, tmp_path / "small.trace")
    convert_aadl_files([tmp_path / "aadl"], tmp_path / "small", trace_file=trace_file)
    back = rosmod_text.read_project(tmp_path / "small")
    assert {d.name for d in back.deployments} == {"field test"}
    assert {h.name for h in back.systems[0].hosts} == {"board-1", "laptop"}

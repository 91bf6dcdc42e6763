"""ROSMOD v0.3 text writer (rosaadl.exporters.rosmod_text): layout and syntax, re-reading into an
equal project for every corpus project, hostile names, atomicity, what v0.3 text cannot hold."""

from __future__ import annotations

import functools
import logging
from decimal import Decimal
from pathlib import Path

import pytest
from corpus_cases import ROSMOD_PROJECTS, WEBGME_SEEDS

from rosaadl import model
from rosaadl.errors import Diagnostic, ExportError
from rosaadl.exporters.rosmod_text import MARKER_TEXT, render_project, text_normal_form, write_project
from rosaadl.importers import rosmod_text, rosmod_webgme

new = model.new

RML = """package nav
{
  component Planner : Base
  {
    publisher <nav/Goal> goal_pub;
    subscriber <nav/Goal> goal_sub { priority = 60; deadline = 0.250; queue = 10; }
    client <nav/Plan> plan_client;
    timer tick { period = 0.1; priority = 50; deadline = 0.05; }
  }
  component Driver
  {
    server <nav/Plan> plan_server { priority = 10; }
  }
}
"""
FILES = {
    "demo.rosmod": MARKER_TEXT,
    "01-Software/nav.rml": RML,
    "01-Software/msg/nav.Goal.msg": "# a goal\nfloat64 x\r\nfloat64 y\n",
    "01-Software/srv/nav.Plan.srv": "nav/Goal goal\n---\nbool ok\n",
    "01-Software/abl/nav.Planner.tick.abl": "do tick { LOCAL 5; }\n",
    "02-Hardware/lab.rhw": (
        'hardware board { ip_address = "10.0.0.2"; arch = armv7l; init = "a \\"b\\"\\nc"; }\n'
    ),
    "02-Hardware/snp/lab.board.snp": "profile\n",
    "03-Deployment/main.rdp": """using lab;
node planner_node
{
  properties { ref = "lab/board"; priority = 70; cmd_args = "--x 1"; restart = always; }
  component_instance planner
  {
    properties
    {
      ref = "nav/Planner";
      scheduling_scheme = PFIFO;
      logging { Is Periodic? = true; Periodic Log Unit = 1000; }
      User Configuration = "{ }";
    }
    port_instance p1 { ref = "Planner/goal_pub"; group = "g"; }
  }
}
""",
}


def write_files(folder: Path, files: dict[str, str]) -> Path:
    for relative, text in files.items():
        target = folder / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(text.encode("utf-8"))
    return folder


@pytest.fixture
def project(tmp_path):
    return rosmod_text.read_project(write_files(tmp_path / "demo", FILES))


def reread_equal(project, folder: Path) -> list[str]:
    write_project(project, folder)
    back = rosmod_text.read_project(folder)
    return model.model_differences(text_normal_form(project), text_normal_form(back))


# --------------------------------------------------------------------------- layout and syntax


def test_layout(project, tmp_path):
    written = write_project(project, tmp_path / "out")
    relative = sorted(p.relative_to(tmp_path / "out").as_posix() for p in written)
    assert relative == [
        "01-Software/abl/nav.Planner.tick.abl",
        "01-Software/msg/nav.Goal.msg",
        "01-Software/nav.rml",
        "01-Software/srv/nav.Plan.srv",
        "02-Hardware/lab.rhw",
        "02-Hardware/snp/lab.board.snp",
        "03-Deployment/main.rdp",
        "demo.rosmod",
    ]
    assert (tmp_path / "out" / "demo.rosmod").read_text() == MARKER_TEXT
    msg = (tmp_path / "out" / "01-Software/msg/nav.Goal.msg").read_bytes()
    assert msg == b"# a goal\nfloat64 x\r\nfloat64 y\n"  # the definition exactly as in the model


def test_syntax_follows_the_corpus_projects(project):
    files = render_project(project)
    rml = files["01-Software/nav.rml"]
    assert "// ROSMOD Package - nav\npackage nav\n{\n" in rml
    assert "  component Planner : Base\n  {\n" in rml
    assert "  component Driver\n  {\n" in rml  # no datatype
    assert "    publisher <nav/Goal> goal_pub;\n" in rml
    assert (
        "    subscriber <nav/Goal> goal_sub\n    {\n      priority = 60;\n      deadline = 0.250;\n"
        "      queue = 10;\n    }\n"
    ) in rml
    assert "    timer tick\n    {\n\tperiod = 0.1;\n\tpriority = 50;\n\tdeadline = 0.05;\n    }\n" in rml
    rhw = files["02-Hardware/lab.rhw"]
    assert (
        'hardware board\n{\n  ip_address = "10.0.0.2";\n  arch = armv7l;\n  init = "a \\"b\\"\\nc";\n}\n'
        in rhw
    )
    rdp = files["03-Deployment/main.rdp"]
    assert "using lab;\n" in rdp
    assert (
        '    ref = "lab/board";\n    priority = 70;\n    cmd_args = "--x 1";\n    restart = always;\n' in rdp
    )
    assert "\tlogging\n\t{\n\t  Is Periodic? = true;\n\t  Periodic Log Unit = 1000;\n\t}\n" in rdp
    assert '\tUser Configuration = "{ }";\n' in rdp
    assert '      port_instance p1\n      {\n\tref = "Planner/goal_pub";\n\tgroup = "g";\n      }\n' in rdp


def test_writes_are_deterministic(project, tmp_path):
    first = {p.name: p.read_bytes() for p in write_project(project, tmp_path / "a")}
    second = {p.name: p.read_bytes() for p in write_project(project, tmp_path / "b")}
    assert first == second
    assert render_project(project) == render_project(project)


def test_small_project_reads_back_equal(project, tmp_path):
    assert reread_equal(project, tmp_path / "out") == []
    back = rosmod_text.read_project(tmp_path / "out")
    comp = back.software.packages[0].components[0]
    assert str(comp.ports[1].deadline) == "0.250"
    assert [(p.key, p.value) for p in comp.properties] == [
        ("goal_sub.queue", "10"),
        ("abl:tick", "do tick { LOCAL 5; }\n"),
    ]
    host = back.systems[0].hosts[0]
    assert [(p.key, p.value) for p in host.properties] == [("init", 'a "b"\nc'), ("snp", "profile\n")]


def test_values_that_need_quoting_read_back(tmp_path):
    host = new("rosmod.Host", name="h", ipAddress="::1", sshKey='C:\\keys\\"id"', architecture="x86 64")
    host.properties.append(new("rosmod.Property", key="note", value="line 1\nline 2\t// not a comment"))
    host.properties.append(new("rosmod.Property", key="empty", value=""))
    system = new("rosmod.System", name="lab", hosts=[host])
    project = new("rosmod.Project", name="q", systems=[system])
    assert reread_equal(project, tmp_path / "q") == []
    back = rosmod_text.read_project(tmp_path / "q").systems[0].hosts[0]
    assert (back.sshKey, back.architecture) == ('C:\\keys\\"id"', "x86 64")
    assert [p.value for p in back.properties] == ["line 1\nline 2\t// not a comment", ""]


def test_unhosted_nodes_and_webgme_facts_are_left_out_with_warnings(tmp_path):
    comp = new("rosmod.Component", name="c", schedulingScheme="EDF")
    comp.ports.append(new("rosmod.Publisher", name="p", type="std_msgs/String", latching=True))
    comp.timers.append(new("rosmod.Timer", name="t", period=Decimal("1"), operation="tick()"))
    comp.properties.append(new("rosmod.Property", key="Libraries", value="boost"))
    package = new("rosmod.Package", name="pkg", components=[comp])
    package.properties.append(new("rosmod.Property", key="Authors", value="me"))
    node = new("rosmod.Node", name="n")
    node.componentInstances.append(new("rosmod.ComponentInstance", name="i", component=comp))
    deployment = new("rosmod.Deployment", name="d", nodes=[node])
    deployment.properties.append(new("rosmod.Property", key="Container:box", value="{}"))
    project = new(
        "rosmod.Project",
        name="w",
        software=new("rosmod.Software", name="sw", packages=[package]),
        deployments=[deployment],
    )
    warnings: list[Diagnostic] = []
    write_project(project, tmp_path / "w", warnings=warnings)
    messages = sorted(w.message for w in warnings)
    assert all(m.startswith("not written (v0.3 text has no place for it): ") for m in messages)
    dropped = [m.split(": ", 1)[1] for m in messages]
    assert dropped == sorted(
        [
            "component 'c': scheduling scheme EDF",
            "publisher 'p': latching True",
            "timer 't': operation 'tick()'",
            "component 'c': setting 'Libraries'",
            "package 'pkg': setting 'Authors'",
            "deployment 'd': setting 'Container:box'",
            "node 'n': a v0.3 node needs a host and this one has none",
        ]
    )
    assert all(w.location.path and w.location.path.startswith("Project(w)") for w in warnings)
    back = rosmod_text.read_project(tmp_path / "w")
    assert len(back.deployments[0].nodes) == 0
    assert model.model_differences(text_normal_form(project), text_normal_form(back)) == []


def test_host_only_reference_gets_a_using_statement(tmp_path):
    host = new("rosmod.Host", name="sat1")
    system = new("rosmod.System", name="cluster", hosts=[host])
    comp = new("rosmod.Component", name="c")
    node = new("rosmod.Node", name="n", host=host, hostRef="sat1")
    node.componentInstances.append(new("rosmod.ComponentInstance", name="i", component=comp))
    project = new(
        "rosmod.Project",
        name="legacy",
        software=new(
            "rosmod.Software", name="sw", packages=[new("rosmod.Package", name="p", components=[comp])]
        ),
        systems=[system],
        deployments=[new("rosmod.Deployment", name="orbit", nodes=[node])],
    )
    files = render_project(project)
    assert "using cluster;\n" in files["03-Deployment/orbit.rdp"]
    assert '\tref = "p/c";\n' in files["03-Deployment/orbit.rdp"]
    assert reread_equal(project, tmp_path / "legacy") == []


# --------------------------------------------------------------------------- hostile names, atomicity


@pytest.mark.parametrize(
    ("where", "name"),
    [
        ("package", "../../x"),
        ("package", "a.b"),
        ("component", "has space"),
        ("message", "../evil"),
        ("deployment", "../../etc/passwd"),
        ("deployment", ".hidden"),
        ("system", "a/b"),
        ("project", ".."),
        ("software", "sub/dir"),
        ("host", "h{"),
    ],
)
def test_hostile_names_are_refused_and_nothing_is_written(tmp_path, where, name):
    msg = new("rosmod.Message", name="M", definition="int32 a\n")
    comp = new("rosmod.Component", name="C")
    package = new("rosmod.Package", name="p", messages=[msg], components=[comp])
    software = new("rosmod.Software", name="sw", packages=[package])
    host = new("rosmod.Host", name="h")
    system = new("rosmod.System", name="lab", hosts=[host])
    deployment = new("rosmod.Deployment", name="d")
    project = new("rosmod.Project", name="p", software=software, systems=[system], deployments=[deployment])
    target = {
        "package": package,
        "component": comp,
        "message": msg,
        "deployment": deployment,
        "system": system,
        "project": project,
        "software": software,
        "host": host,
    }[where]
    target.name = name
    out = tmp_path / "deep" / "out"
    with pytest.raises(ExportError) as err:
        write_project(project, out)
    assert repr(name) in err.value.message
    assert err.value.location.path
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_a_failed_write_leaves_an_existing_project_unchanged(project, tmp_path):
    out = tmp_path / "out"
    write_project(project, out)
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    project.software.packages[0].components[0].name = "bad name"
    with pytest.raises(ExportError):
        write_project(project, out)
    after = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    assert after == before


def test_duplicate_names_are_refused(project):
    package = project.software.packages[0]
    package.components[1].name = package.components[0].name
    with pytest.raises(ExportError, match="two components are named 'Planner'"):
        render_project(project)


def test_bad_port_type_is_refused(project):
    project.software.packages[0].components[0].ports[0].type = "no package"
    with pytest.raises(ExportError, match="expected 'package/Type'"):
        render_project(project)


# --------------------------------------------------------------------------- the corpus

CORPUS_PROJECTS = list(ROSMOD_PROJECTS)


@functools.cache
def webgme_projects(root: str, archive: str):
    return rosmod_webgme.read_webgmex(Path(root) / "rosmod" / "webgme" / archive)


@pytest.mark.parametrize("relative", CORPUS_PROJECTS)
def test_corpus_textual_project_reads_back_equal(corpus, relative, tmp_path, caplog):
    caplog.set_level(logging.ERROR)
    project = rosmod_text.read_project(corpus / "rosmod" / relative)
    assert reread_equal(project, tmp_path / "out") == []


def test_corpus_v03_project_needs_no_normalisation_but_file_places(corpus, tmp_path, caplog):
    """A v0.3 project of the corpus comes back as it was, but for where it lives."""
    caplog.set_level(logging.ERROR)
    project = rosmod_text.read_project(corpus / "rosmod" / "textual-v0.3" / "three-components")
    out = tmp_path / "three-components"
    warnings: list[Diagnostic] = []
    write_project(project, out, warnings=warnings)
    assert warnings == []
    back = rosmod_text.read_project(out)
    diffs = model.model_differences(project, back)
    assert all(".path:" in d for d in diffs), diffs


@pytest.mark.parametrize("archive", WEBGME_SEEDS)
def test_corpus_webgme_projects_read_back_equal(corpus, archive, tmp_path, caplog):
    caplog.set_level(logging.ERROR)
    for index, project in enumerate(webgme_projects(str(corpus), archive)):
        assert reread_equal(project, tmp_path / f"p{index}") == [], project.name

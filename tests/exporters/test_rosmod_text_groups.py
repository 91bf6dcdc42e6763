"""ROSMOD port groups written back in the form they were read: ``group = "…";`` inside a port
instance, or a top-level ``group G { <node>/<instance>/<port> }`` block."""

from __future__ import annotations

import pytest
from rosmod_group_projects import V03_BLOCK, write_v02_groups, write_v03_groups

from rosaadl import model
from rosaadl.errors import Diagnostic, ExportError
from rosaadl.exporters.rosmod_text import render_project, text_normal_form, write_project
from rosaadl.importers import rosmod_text

new = model.new


def round_trip(project, folder):
    """(the project read back from its written text in ``folder/<its name>``, the model
    differences in normal form)."""
    folder = folder / project.name
    write_project(project, folder)
    back = rosmod_text.read_project(folder)
    return back, model.model_differences(text_normal_form(project), text_normal_form(back))


@pytest.mark.parametrize("write", [write_v02_groups, write_v03_groups], ids=["v0.2-blocks", "both-forms"])
def test_read_write_read_is_equal_and_a_fixed_point(tmp_path, write):
    project = rosmod_text.read_project(write(tmp_path / "in"))
    back, differences = round_trip(project, tmp_path / "out")
    assert differences == []
    assert render_project(back) == render_project(project)  # what was written reads back as it was


def test_a_v03_project_with_both_forms_comes_back_as_it_was(tmp_path):
    project = rosmod_text.read_project(write_v03_groups(tmp_path / "in"))
    back, _ = round_trip(project, tmp_path / "out")
    differences = model.model_differences(project, back)
    assert all(".path:" in d for d in differences), differences


def test_both_forms_are_written_as_they_were_read(tmp_path):
    project = rosmod_text.read_project(write_v03_groups(tmp_path))
    rdp = render_project(project)["03-Deployment/relays.rdp"]
    # the groups written inside the port instances stay there
    assert (
        '      port_instance pubStoA\n      {\n\tref = "Relay/pub";\n\tgroup = "inline_flow";\n      }\n'
        in rdp
    )
    assert (
        '      port_instance subStoA\n      {\n\tref = "Relay/sub";\n\tgroup = "inline_flow";\n      }\n'
        in rdp
    )
    # the block comes back as written, paths in its order; the port instance it made is not
    # written again, the one it grouped keeps its own block without a group of its own
    assert rdp.endswith(V03_BLOCK)
    assert '      port_instance subX\n      {\n\tref = "Relay/sub";\n      }\n' in rdp
    assert "port_instance pub\n" not in rdp
    assert rdp.count("group") == 3  # two inside port instances, the block


def test_v02_group_blocks_are_written_as_blocks(tmp_path):
    project = rosmod_text.read_project(write_v02_groups(tmp_path))
    warnings: list[Diagnostic] = []
    rdp = render_project(project, warnings=warnings)["03-Deployment/cluster.rdp"]
    assert rdp.endswith(
        "// ROSMOD Group - Group_1\ngroup Group_1\n{\n"
        "    tracking_1/tracker_i/pose_sub\n    sensing_1/sensor_i/pose_pub\n"
        "    sensing_1/sensor_i/Reset_server\n    tracking_1/tracker_i/Reset_client\n}\n\n"
        "// ROSMOD Group - Group_2\ngroup Group_2\n{\n"
        "    sensing_2/sensor_i/pose_pub\n    tracking_2/tracker_i/pose_sub\n}\n"
    )
    assert "port_instance" not in rdp and 'group = "' not in rdp
    # the v0.2 host instances are what v0.3 text cannot hold; the groups are not among them
    assert not any("group:" in w.message for w in warnings)
    assert sum("host_instance:" in w.message for w in warnings) == 2


def test_a_group_block_made_or_changed_in_the_model(tmp_path):
    """Members added to a block group, members gone, groups with no member, names ROSMOD
    cannot write: what is written, and that it reads back equal."""
    project = rosmod_text.read_project(write_v03_groups(tmp_path / "in"))
    deployment = project.deployments[0]
    relay1, relay2 = (node.componentInstances[0] for node in deployment.nodes)
    relay1.portInstances[0].group = "block_flow"  # pubStoA joins the block: listed after the others
    relay2.portInstances[1].group = None  # the port the block made leaves it
    for key in ("group:nobody", "group:not a word"):
        deployment.properties.append(new("rosmod.Property", key=key, value=""))
    warnings: list[Diagnostic] = []
    rdp = render_project(project, warnings=warnings)["03-Deployment/relays.rdp"]
    assert rdp.endswith("group block_flow\n{\n    relay1/relay_i/sub\n    relay1/relay_i/pub\n}\n")
    assert '      port_instance pub\n      {\n\tref = "Relay/pub";\n      }\n' in rdp  # no group: inline
    assert sorted(w.message for w in warnings if "group:" in w.message) == [
        "not written (v0.3 text has no place for it): deployment 'relays': setting 'group:nobody'",
        "not written (v0.3 text has no place for it): deployment 'relays': setting 'group:not a word'",
    ]
    back, differences = round_trip(project, tmp_path / "out")
    assert differences == []
    assert [(p.key, p.value) for p in back.deployments[0].properties] == [
        ("group:block_flow", "relay1/relay_i/sub\nrelay1/relay_i/pub")
    ]


def test_two_port_instances_of_one_port_keep_their_groups_inside(tmp_path):
    """A block names a port, so two port instances of one port cannot both be in blocks: they are
    written with their groups inside, and read back so."""
    project = rosmod_text.read_project(write_v03_groups(tmp_path / "in"))
    relay1 = project.deployments[0].nodes[0].componentInstances[0]
    relay1.portInstances.append(new("rosmod.PortInstance", name="subY", port="Relay/sub", group="other"))
    rdp = render_project(project)["03-Deployment/relays.rdp"]
    assert '\tref = "Relay/sub";\n\tgroup = "block_flow";\n' in rdp
    assert "    relay1/relay_i/sub\n" not in rdp
    assert round_trip(project, tmp_path / "out")[1] == []


def test_a_block_member_that_cannot_be_written_is_refused(tmp_path):
    project = rosmod_text.read_project(write_v03_groups(tmp_path / "in"))
    port = project.deployments[0].nodes[0].componentInstances[0].portInstances[1]
    port.port = "Relay/not a word"
    with pytest.raises(ExportError) as info:
        write_project(project, tmp_path / "out")
    assert "cannot write port 'not a word'" in info.value.message and "PortInstance(subX)" in str(info.value)
    assert not (tmp_path / "out").exists()

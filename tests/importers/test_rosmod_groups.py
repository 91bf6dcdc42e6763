"""ROSMOD port groups written as top-level ``group`` blocks of a deployment, beside ``group = "…";``."""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from rosmod_group_projects import V03_BLOCK, V03_GROUPS_RDP, write_v02_groups, write_v03_groups

from rosaadl.cli import main
from rosaadl.errors import Diagnostic, NameResolutionError, ParseError
from rosaadl.importers.rosmod_text import RosmodImportError, read_project


def groups_of(project) -> list[tuple[str, str, str, str | None, str | None]]:
    """(node, instance, port instance, its port, its group) of every port instance."""
    return [
        (node.name, inst.name, port.name, port.port, port.group)
        for deployment in project.deployments
        for node in deployment.nodes
        for inst in node.componentInstances
        for port in inst.portInstances
    ]


def settings_of(project) -> list[tuple[str, str]]:
    return [(p.key, p.value) for d in project.deployments for p in d.properties if p.key.startswith("group:")]


def test_v02_group_blocks_give_each_port_its_group(tmp_path):
    project = read_project(write_v02_groups(tmp_path))
    assert groups_of(project) == [
        ("sensing_1", "sensor_i", "pose_pub", "Sensor/pose_pub", "Group_1"),
        ("sensing_1", "sensor_i", "Reset_server", "Sensor/Reset_server", "Group_1"),
        ("sensing_2", "sensor_i", "pose_pub", "Sensor/pose_pub", "Group_2"),
        ("tracking_1", "tracker_i", "pose_sub", "Tracker/pose_sub", "Group_1"),
        ("tracking_1", "tracker_i", "Reset_client", "Tracker/Reset_client", "Group_1"),
        ("tracking_2", "tracker_i", "pose_sub", "Tracker/pose_sub", "Group_2"),
    ]
    # the form read: the paths as written, in their order
    assert settings_of(project) == [
        (
            "group:Group_1",
            "tracking_1/tracker_i/pose_sub\nsensing_1/sensor_i/pose_pub\n"
            "sensing_1/sensor_i/Reset_server\ntracking_1/tracker_i/Reset_client",
        ),
        ("group:Group_2", "sensing_2/sensor_i/pose_pub\ntracking_2/tracker_i/pose_sub"),
    ]
    port = project.deployments[0].nodes[2].componentInstances[0].portInstances[0]
    assert (port.line, port.column) == (22, 5)  # where its path is written


def test_both_forms_in_one_deployment(tmp_path):
    project = read_project(write_v03_groups(tmp_path))
    assert groups_of(project) == [
        ("relay1", "relay_i", "pubStoA", "Relay/pub", "inline_flow"),
        ("relay1", "relay_i", "subX", "Relay/sub", "block_flow"),  # its port_instance, grouped by the block
        ("relay2", "relay_i", "subStoA", "Relay/sub", "inline_flow"),
        ("relay2", "relay_i", "pub", "Relay/pub", "block_flow"),  # made by the block
    ]
    assert settings_of(project) == [("group:block_flow", "relay2/relay_i/pub\nrelay1/relay_i/sub")]


def test_a_block_agrees_with_the_group_written_inside_a_port_instance(tmp_path):
    rdp = V03_GROUPS_RDP.replace('{ ref = "Relay/sub"; }', '{ ref = "Relay/sub"; group = "block_flow"; }')
    project = read_project(write_v03_groups(tmp_path, rdp))
    assert ("relay1", "relay_i", "subX", "Relay/sub", "block_flow") in groups_of(project)


def test_an_empty_group_is_skipped_with_a_warning(tmp_path):
    warnings: list[Diagnostic] = []
    rdp = V03_GROUPS_RDP + "group nothing\n{\n}\n"
    project = read_project(write_v03_groups(tmp_path, rdp), warnings=warnings)
    assert [w.message for w in warnings] == ["group 'nothing' lists no port; skipped"]
    assert warnings[0].location.line == V03_GROUPS_RDP.count("\n") + 1
    assert [key for key, _ in settings_of(project)] == ["group:block_flow"]


# --------------------------------------------------------------------------- located errors


def errors_in(tmp_path: Path, rdp: str) -> list:
    with pytest.raises(RosmodImportError) as info:
        read_project(write_v03_groups(tmp_path, rdp))
    return info.value.errors


def block_with(*members: str, head: str = "group block_flow") -> str:
    block = "// ROSMOD Group - block_flow\n" + head + "\n{\n" + "".join(f"    {m}\n" for m in members) + "}\n"
    return V03_GROUPS_RDP.replace(V03_BLOCK, block)


FIRST_MEMBER = V03_GROUPS_RDP.count("\n") - 2  # the line after "group block_flow" and "{"


@pytest.mark.parametrize(
    ("rdp", "fragment", "line", "column"),
    [
        (block_with("relay1/relay_i"), "malformed member 'relay1/relay_i' of group 'block_flow'", 0, 5),
        (block_with("relay1/relay_i/sub/x"), "expected <node>/<component_instance>/<port>", 0, 5),
        (block_with('"relay1/relay_i/sub"'), "malformed member 'relay1/relay_i/sub'", 0, 5),
        (block_with("relay1 / relay_i / sub"), "malformed member 'relay1'", 0, 5),
        (block_with("relay1/relay_i/sub;"), "unexpected ';' in 'group block_flow'", 0, 23),
        (block_with("relay1/relay_i/sub = x"), "unexpected '='", 0, 24),
        (block_with("relay1 { }"), "unexpected '{'", 0, 12),
        (block_with("relay1/relay_i/sub", head="group"), "malformed group: expected 'group <name>'", -2, 1),
        (block_with("relay1/relay_i/sub", head="group a b"), "malformed group", -2, 1),
        # truncated files
        (V03_GROUPS_RDP.removesuffix("}\n"), "unclosed '{' of 'group block_flow'", -1, 1),
        (V03_GROUPS_RDP.removesuffix("}\n") + "    relay1/rel", "unclosed '{'", -1, 1),
        (
            V03_GROUPS_RDP.removesuffix("{\n    relay2/relay_i/pub\n    relay1/relay_i/sub\n}\n"),
            "found the end",
            -2,
            7,
        ),
    ],
)
def test_malformed_and_truncated_group_blocks_are_located(tmp_path, rdp, fragment, line, column):
    (err,) = errors_in(tmp_path, rdp)
    assert isinstance(err, ParseError)
    assert fragment in err.message, err.message
    assert (Path(err.location.file).name, err.location.line, err.location.column) == (
        "relays.rdp",
        FIRST_MEMBER + line,
        column,
    )


@pytest.mark.parametrize(
    ("members", "fragment", "line"),
    [
        (["nobody/relay_i/sub"], "'nobody/relay_i/sub' names no node of deployment 'relays'", 0),
        (
            ["relay1/ghost/sub"],
            "node 'relay1' has no component instance 'ghost' (its component instances: relay_i)",
            0,
        ),
        (
            ["relay1/relay_i/nothing"],
            "'nothing' is not a port of component 'Relay' of relay1/relay_i (its ports: pub, sub)",
            0,
        ),
        (["relay2/relay_i/sub"], "'relay2/relay_i/sub' is already in group 'inline_flow' (line 18)", 0),
        (["relay2/relay_i/pub", "relay2/relay_i/pub"], "is already in group 'block_flow' (line", 1),
    ],
)
def test_group_members_that_do_not_resolve_are_located(tmp_path, members, fragment, line):
    (err,) = errors_in(tmp_path, block_with(*members))
    assert isinstance(err, NameResolutionError)
    assert fragment in err.message, err.message
    assert (Path(err.location.file).name, err.location.line, err.location.column) == (
        "relays.rdp",
        FIRST_MEMBER + line,
        5,
    )


def test_a_group_defined_twice_and_a_port_instance_name_taken(tmp_path):
    rdp = V03_GROUPS_RDP.replace(
        'port_instance subStoA { ref = "Relay/sub";', 'port_instance pub { ref = "Relay/sub";'
    )
    rdp += "group block_flow\n{\n    relay1/relay_i/pub\n}\n"
    errors = errors_in(tmp_path, rdp)
    messages = sorted(e.message for e in errors)
    assert len(errors) == 2, messages
    assert (
        "duplicate group name 'block_flow' in deployment 'relays' (first defined at line 22)" in messages[0]
    )
    assert (
        "would make a port instance 'pub', but relay2/relay_i has a port instance of that name" in messages[1]
    )
    assert all(e.location.line for e in errors)


def test_check_refuses_a_malformed_group_with_its_place(tmp_path, capsys):
    project = write_v03_groups(tmp_path, block_with("relay1/relay_i"))
    assert main(["check", str(project)]) == 1
    err = capsys.readouterr().err
    assert f"relays.rdp:{FIRST_MEMBER}:5" in err and "malformed member" in err
    assert "Traceback" not in err


@given(st.text(alphabet=st.sampled_from(list('{};=/"ab1 \n')), max_size=80))
@settings(max_examples=150, deadline=None)
def test_fuzzed_group_blocks_fail_cleanly(text):
    with tempfile.TemporaryDirectory() as tmp:
        try:
            read_project(write_v03_groups(Path(tmp), V03_GROUPS_RDP + "group g {\n" + text))
        except RosmodImportError as exc:
            assert all(e.location.file and e.location.line for e in exc.errors)

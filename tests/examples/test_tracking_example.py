"""The tracking example project: it reads cleanly, says what the README says, and converts."""

from __future__ import annotations

from decimal import Decimal
from pathlib import Path

import pytest

from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_text import is_rosmod_project, read_project, summarize
from rosaadl.transforms.rosmod_to_aadl import rosmod_to_aadl

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "tracking"


@pytest.fixture(scope="module")
def project():
    warnings: list = []
    read = read_project(EXAMPLE, warnings=warnings, strict=True)
    assert warnings == []
    return read


def test_is_a_rosmod_v03_project(project):
    assert is_rosmod_project(EXAMPLE)
    assert project.formatVersion == "0.3"
    counts = summarize(project)
    expected = {"packages": 1, "messages": 3, "components": 3, "timers": 3, "publishers": 3}
    assert {k: counts[k] for k in expected} == expected
    assert (counts["subscribers"], counts["systems"], counts["hosts"], counts["deployments"]) == (2, 2, 2, 2)
    assert (counts["nodes"], counts["component_instances"]) == (6, 6)


def test_messages_have_the_sizes_the_readme_gives(project):
    (package,) = project.software.packages
    sizes = {m.name: ros_msg.data_size(ros_msg.parse_msg(m.definition)) for m in package.messages}
    assert sizes == {"Image": 921_612, "Point": 24, "Twist": 48}


def test_timers_are_the_applications_rates(project):
    (package,) = project.software.packages
    periods = {c.name: [t.period for t in c.timers] for c in package.components}
    assert periods == {
        "usb_cam": [Decimal("0.05")],  # 20 Hz: the example's choice (examples/README.md)
        "ocv_color_tracking": [Decimal("0.1")],
        "pos_to_cmd": [Decimal("0.1")],
    }


def test_deployments_put_every_node_on_the_robots_computer(project):
    hosts = {d.name: {n.host.name for n in d.nodes} for d in project.deployments}
    assert hosts == {"pioneer_3dx": {"odroid_xu4"}, "leo_rover": {"raspberry_pi4b"}}
    for deployment in project.deployments:
        components = sorted(ci.component.name for n in deployment.nodes for ci in n.componentInstances)
        assert components == ["ocv_color_tracking", "pos_to_cmd", "usb_cam"]


def test_converts_to_aadl_without_warnings(project):
    result = rosmod_to_aadl(project)
    assert result.warnings == []
    assert sorted(result.roots) == ["leo_rover", "pioneer_3dx"]

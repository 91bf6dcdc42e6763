"""Names in generated code: valid identifiers and ROS names from any model name, and hostile
models that never make the generator write outside the output folder."""

from __future__ import annotations

import compileall
import io
import keyword
import os
import re
from contextlib import redirect_stdout

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_rclpy_models import hostile_instance

from rosaadl.errors import ExportError
from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace, naming
from rosaadl.exporters.rclpy.topics import normalize_ros_name

OPTIONS = GenerationOptions(year=2024)
ROS_PACKAGE = re.compile(r"^(?!.*__)(?!.*_$)[a-z][a-z0-9_]*$")  # rosidl_adapter's package pattern
ROS_MESSAGE = re.compile(r"^[A-Z][A-Za-z0-9]*$")
ROS_CONSTANT = re.compile(r"^[A-Z]([A-Z0-9_]?[A-Z0-9]+)*$")
ROS_TOPIC = re.compile(r"^(~/|/)?[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*$")


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("../../etc", "etc"),
        ("imagePublisher.xu4_a15", "image_publisher_xu4_a15"),
        ("Größe ünïcødé", "grosse_unicode"),
        ("caméra", "camera"),
        ("2fast", "n_2fast"),
        ("rm -rf /", "rm_rf"),
    ],
)
def test_snake(text, expected):
    assert naming.snake(text) == expected


def test_keywords_and_reserved_names():
    assert naming.identifier("class") == "class_"
    assert naming.identifier("match") == "match_"
    assert naming.package_name('../../evil"pkg') == "evil_pkg"
    assert naming.package_name("rclpy") == "rclpy_pkg"  # never shadows a dependency
    assert naming.package_name("os") == "os_pkg"  # nor the standard library
    assert naming.module_name("time") == "time_node"
    assert naming.field_name("import") == "import_value"
    assert naming.member_name("publishers") == "publishers_"  # an attribute of rclpy's Node
    assert naming.message_name("video_stream.rgb") == "VideoStreamRgb"
    assert naming.constant_name("maxSpeed") == "MAX_SPEED"


def test_names_without_ascii_letters_are_stable_hashes():
    first, second = naming.snake("相机"), naming.snake("相机")
    assert first == second and re.fullmatch(r"n_[0-9a-f]{8}", first)
    assert naming.snake("相机") != naming.snake("照相机")
    assert ROS_MESSAGE.match(naming.message_name("相机"))


def test_long_names_are_shortened_with_a_hash():
    long = "a_very_long_component_name_" * 10
    name = naming.snake(long)
    assert len(name) <= naming.MAX_NAME and name != naming.snake(long + "x")
    assert naming.snake("short_name") == "short_name"


def test_name_tables_hand_out_unique_names():
    table = naming.NameTable({"taken"})
    # case-insensitive, as ROS and AADL names collide on file systems that fold case
    assert [table.unique(n) for n in ("a", "a", "taken", "A")] == ["a", "a_2", "taken_2", "A_3"]


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("/../../etc/pa'ss\"wd", "/etc/pa_ss_wd"),
        ("~private topic", "~/private_topic"),
        ("usb_cam/image_raw", "usb_cam/image_raw"),
        ("..", None),
    ],
)
def test_ros_names(text, expected):
    assert normalize_ros_name(text) == expected


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=80))
def test_any_text_gives_valid_names(text):
    identifier = naming.identifier(text)
    assert identifier.isidentifier() and not keyword.iskeyword(identifier) and identifier.isascii()
    package = naming.package_name(text)
    assert ROS_PACKAGE.match(package) and package.isidentifier() and len(package) >= 2
    assert package not in naming.RESERVED_PACKAGES
    module = naming.module_name(text)
    assert module.isidentifier() and not keyword.iskeyword(module) and module.isascii()
    assert ROS_MESSAGE.match(naming.message_name(text))
    assert ROS_PACKAGE.match(naming.field_name(text)) and not keyword.iskeyword(naming.field_name(text))
    assert ROS_CONSTANT.match(naming.constant_name(text))
    topic = normalize_ros_name(text)
    assert topic is None or ROS_TOPIC.match(topic)
    assert naming.identifier(text) == identifier  # deterministic


# --------------------------------------------------------------------------- hostile models


def test_hostile_model_stays_inside_the_output_folder(tmp_path):
    _, instance = hostile_instance()
    sentinel = tmp_path / "etc"
    sentinel.mkdir()
    out = tmp_path / "ws" / "src"
    result = generate_workspace(instance, out, options=OPTIONS)
    root = out.resolve()
    for path in result.written:
        target = (out / path).resolve()
        assert root in target.parents, path
    assert list(sentinel.iterdir()) == []
    assert {p.name for p in tmp_path.iterdir()} == {"etc", "ws"}
    packages = sorted(p.name for p in out.iterdir() if p.is_dir())
    assert packages == ["evil_pkg", "systeme_bringup", "systeme_interfaces"]
    assert all(ROS_PACKAGE.match(p) for p in packages)
    for module in (out / "evil_pkg" / "evil_pkg").glob("*.py"):
        assert module.stem.isidentifier() and not keyword.iskeyword(module.stem)
    with redirect_stdout(io.StringIO()):
        assert compileall.compile_dir(str(out), quiet=1, force=True)
    node = (out / "evil_pkg/evil_pkg/etc_passwd.py").read_text()
    assert "super().__init__('etc_passwd', **kwargs)" in node
    assert "'def_/lambda_'" in node and "self.cbg_for_ = MutuallyExclusiveCallbackGroup()" in node
    launch = (out / "systeme_bringup/launch/systeme.launch.py").read_text()
    assert "('def_/lambda_', '/etc/pa_ss_wd')" in launch
    assert "executable='rm_rf'" in launch
    msg = (out / "systeme_interfaces/msg/Donnees.msg").read_text()
    assert "float64 import_value\nfloat64 grosse\n" in msg


def test_a_link_out_of_the_output_folder_is_refused(tmp_path):
    _, instance = hostile_instance()
    outside = tmp_path / "outside"
    outside.mkdir()
    out = tmp_path / "src"
    out.mkdir()
    os.symlink(outside, out / "evil_pkg")
    with pytest.raises(ExportError, match="outside the output directory"):
        generate_workspace(instance, out, options=OPTIONS)
    assert list(outside.iterdir()) == []
    assert sorted(p.name for p in out.iterdir()) == ["evil_pkg"]  # nothing else was written

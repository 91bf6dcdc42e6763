"""The generated ROS 2 application on a real ROS 2 runtime (``make ros``: the ``ros`` extra's PyPI
wheels of ROS 2 kilted in this venv), not only built and linted.

One workspace, the demo's (the tracking example on its proposed deployment), is generated and built
with colcon against the venv once for the module (about 15 s on 2 cores); the tests then run its
nodes as separate processes.  Every test skips with the reason where the runtime is not installed
(the wheels are for CPython 3.11 on Linux only).
"""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
from ros_runtime import (
    colcon_build,
    generate_demo_workspace,
    runtime_environment,
    runtime_marks,
    workspace_environment,
)

pytestmark = runtime_marks()

#: The packages of the demo's workspace.
PACKAGES = ("nd_ocv_color_tracking", "nd_pos_to_cmd", "tracking_bringup", "tracking_interfaces", "usb_cam")


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """The demo's workspace, built with the runtime's colcon (its root)."""
    root = generate_demo_workspace(tmp_path_factory.mktemp("runtime") / "demo")
    done = colcon_build(root)
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-3000:]
    return root


def executable(root: Path, package: str, name: str) -> str:
    return str(root / "install" / package / "lib" / package / name)


# --------------------------------------------------------------------------- the installation


def test_aadl_grammar_and_rosidl_share_one_lark():
    """ros-rosidl-parser's wheel requires lark-parser 0.12, which writes the same ``lark`` module
    as the lark 1.x of rosaadl's AADL grammar; ``make ros`` installs lark 1.x last, and both work."""
    import lark
    from rosidl_parser.definition import Message
    from rosidl_parser.parser import parse_idl_string

    from rosaadl.importers import aadl_text

    assert int(lark.__version__.split(".")[0]) >= 1, lark.__version__
    model = aadl_text.read_string("package p\npublic\n  thread t\n  end t;\nend p;\n", "p.aadl")
    assert [unit.name for unit in model.units] == ["p"]
    idl = parse_idl_string("module pkg { module msg { struct Frame { sequence<uint8> data; }; }; };\n")
    [message] = idl.get_elements_of_type(Message)
    assert message.structure.namespaced_type.name == "Frame"


def test_interface_package_builds_and_its_messages_serialize(built):
    """The generated ``*_interfaces`` package built with colcon against the venv (cmake, g++):
    its C type support loads and a message serializes with its payload."""
    assert list(
        (built / "install" / "tracking_interfaces" / "lib").glob("libtracking_interfaces__rosidl_*.so")
    )
    script = textwrap.dedent(
        """
        from rclpy.serialization import serialize_message
        from tracking_interfaces.msg import VideoStream
        print(len(serialize_message(VideoStream(data=bytes(1000)))))
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", script],
        env=workspace_environment(built),
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert int(done.stdout) >= 1000


TALKER = """
import sys, rclpy
from std_msgs.msg import String
rclpy.init()
node = rclpy.create_node('talker')
publisher = node.create_publisher(String, 'chatter', 10)
timer = node.create_timer(0.05, lambda: publisher.publish(String(data='x' * 100)))
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
rclpy.try_shutdown()
"""

LISTENER = """
import rclpy
from std_msgs.msg import String
rclpy.init()
node = rclpy.create_node('listener')
got = []
node.create_subscription(String, 'chatter', lambda msg: got.append(len(msg.data)), 10)
while len(got) < 5:
    rclpy.spin_once(node, timeout_sec=0.5)
print(got[:5])
rclpy.try_shutdown()
"""


def test_publish_and_subscribe_between_two_processes():
    env = runtime_environment()
    talker = subprocess.Popen([sys.executable, "-c", TALKER], env=env, stderr=subprocess.PIPE, text=True)
    try:
        listener = subprocess.run(
            [sys.executable, "-c", LISTENER], env=env, capture_output=True, text=True, timeout=60
        )
    finally:
        talker.send_signal(signal.SIGINT)
        _, talker_err = talker.communicate(timeout=30)
    assert listener.returncode == 0, listener.stderr[-3000:]
    assert listener.stdout.strip() == "[100, 100, 100, 100, 100]"
    assert talker.returncode == 0, talker_err[-3000:]


def test_generated_nodes_start_and_stop(built):
    """Every generated node of the demo starts and stops on SIGINT with exit code 0."""
    env = workspace_environment(built)
    nodes = {
        name: subprocess.Popen(
            [executable(built, package, name)],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        for package, name in (
            ("usb_cam", "usb_cam"),
            ("nd_ocv_color_tracking", "ocv_color_tracking"),
            ("nd_pos_to_cmd", "pos_to_cmd"),
        )
    }
    time.sleep(2.0)
    for process in nodes.values():
        process.send_signal(signal.SIGINT)
    for name, process in nodes.items():
        out, _ = process.communicate(timeout=30)
        assert process.returncode == 0, f"{name}: {out[-3000:]}"

"""Two small ROSMOD projects of our own whose deployments group ports as real projects do.

* :func:`write_v02_groups`: the shape of ROSMOD's orbiter sample projects (a v0.2 workspace,
  ``host_instance`` deployments, then top-level ``group G { <node>/<instance>/<port> }`` blocks,
  one path a line, listed in an order that is not the model's);
* :func:`write_v03_groups`: a v0.3 project whose one ``.rdp`` has both forms: ``group = "…";``
  inside port instances and a top-level block, one of whose ports already has a ``port_instance``.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["V02_GROUPS_RDP", "V03_GROUPS_RDP", "V03_BLOCK", "write_v02_groups", "write_v03_groups"]

_V02_RML = """package robot
{
    messages { msg Pose { float64 x; } }
    services { srv Reset { request { bool hard; } response { } } }
    components
    {
        component Sensor { provides Reset; publisher<Pose> pose_pub; }
        component Tracker { requires Reset; subscriber<Pose> pose_sub; }
    }
    nodes
    {
        node sensing { component<Sensor> sensor_i; }
        node tracking { component<Tracker> tracker_i; }
    }
}
"""

V02_GROUPS_RDP = """using cluster;
// ROS Host Instance - alpha
host_instance alpha
{
    properties { username = "pi"; }
    nodes
    {
        node_instance sensing_1 { reference = "robot/sensing"; }
        node_instance sensing_2 { reference = "robot/sensing"; }
    }
}
// ROS Host Instance - beta
host_instance beta
{
    properties { username = "ubuntu"; }
    nodes { node_instance tracking_1 { reference = "robot/tracking"; }
            node_instance tracking_2 { reference = "robot/tracking"; } }
}
// ROS Group - Group_1
group Group_1
{
    tracking_1/tracker_i/pose_sub
    sensing_1/sensor_i/pose_pub
    sensing_1/sensor_i/Reset_server
    tracking_1/tracker_i/Reset_client
}
// ROS Group - Group_2
group Group_2
{
    sensing_2/sensor_i/pose_pub
    tracking_2/tracker_i/pose_sub
}
"""

_V03_RML = """package comm
{
  component Relay : Base
  {
    publisher <comm/Data> pub;
    subscriber <comm/Data> sub;
  }
}
"""

#: The top-level group block of :data:`V03_GROUPS_RDP` (its last lines).
V03_BLOCK = """// ROSMOD Group - block_flow
group block_flow
{
    relay2/relay_i/pub
    relay1/relay_i/sub
}
"""

V03_GROUPS_RDP = (
    """using lab;
node relay1
{
  properties { ref = "lab/board"; priority = 50; }
  component_instance relay_i
  {
      properties { ref = "comm/Relay"; scheduling_scheme = FIFO; }
      port_instance pubStoA { ref = "Relay/pub"; group = "inline_flow"; }
      port_instance subX { ref = "Relay/sub"; }
  }
}
node relay2
{
  properties { ref = "lab/board"; priority = 50; }
  component_instance relay_i
  {
      properties { ref = "comm/Relay"; scheduling_scheme = FIFO; }
      port_instance subStoA { ref = "Relay/sub"; group = "inline_flow"; }
  }
}
"""
    + V03_BLOCK
)


def _write(folder: Path, files: dict[str, str]) -> Path:
    for relative, text in files.items():
        target = folder / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text)
    return folder


def write_v02_groups(root: Path, rdp: str = V02_GROUPS_RDP) -> Path:
    """The v0.2-shaped project in ``root/orbiter`` (deployment ``03-Deployment/cluster.rdp``)."""
    return _write(
        root / "orbiter",
        {
            "orbiter.rosmod": "This is a ROSMOD Project",
            "01-Software/robot.rml": _V02_RML,
            "02-Hardware/cluster.rhw": (
                'host alpha { ip_address = "10.0.0.1"; }\nhost beta { ip_address = "10.0.0.2"; }\n'
            ),
            "03-Deployment/cluster.rdp": rdp,
        },
    )


def write_v03_groups(root: Path, rdp: str = V03_GROUPS_RDP) -> Path:
    """The v0.3 project in ``root/relays`` (deployment ``03-Deployment/relays.rdp``)."""
    return _write(
        root / "relays",
        {
            "relays.rosmod": "This is a ROSMOD Project",
            "01-Software/comm.rml": _V03_RML,
            "01-Software/msg/comm.Data.msg": "int32 value\n",
            "02-Hardware/lab.rhw": 'hardware board { ip_address = "10.0.0.2"; }\n',
            "03-Deployment/relays.rdp": rdp,
        },
    )

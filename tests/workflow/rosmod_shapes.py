"""A small ROSMOD v0.3 project of our own with the shapes the corpus projects run into
(``rosaadl run`` on every project of the corpus): a component with no timer whose publisher is
sent from its service callback (the AGSE image processor, pub_sub_traffic_gen's sender), its
client in another component of the same process (several components, so several threads, per
node: a MultiThreadedExecutor under ``SCHED_FIFO``), two more nodes listening to both topics (as
many busy real-time nodes as a 2-CPU machine has CPUs, besides the first), a component with a
publisher and nothing else in a node of its own (routing's and tg_test's senders: no thread, no
timer), a timer whose period is longer than any run (long-running-operation's 120 s timer) and
one of period 0 (the `timer` project's sporadic timer, which the component's code would start).
Written into a folder by :func:`write_project`."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

__all__ = ["PROJECT_FILES", "ROOT", "CALL_PERIOD", "write_project", "converted_project"]

#: The deployment to run (its system implementation once converted to AADL).
ROOT = "relay_deployment::relay.impl"
#: The caller's timer period (s): its dispatches call the service, each call dispatches the server.
CALL_PERIOD = 0.05

_SOFTWARE = """\
// A caller on a timer, an answerer with no timer, listeners, a beacon with no callback, a sleeper
// on a timer of ten minutes.
package relay
{
  component caller : Base
  {
    timer call_timer
    {
      period = CALL_PERIOD;
      priority = 50;
      deadline = 0.05;
    }
    client <relay/poke> poke_client;
    publisher <relay/tick> tick_pub;
  }
  component answerer : Base
  {
    server <relay/poke> poke_server
    {
      priority = 50;
      deadline = 0.05;
    }
    publisher <relay/answer> answer_pub;
  }
  component listener : Base
  {
    subscriber <relay/tick> tick_sub
    {
      priority = 50;
      deadline = 0.05;
    }
    subscriber <relay/answer> answer_sub
    {
      priority = 50;
      deadline = 0.05;
    }
    subscriber <relay/signal> signal_sub
    {
      priority = 50;
      deadline = 0.05;
    }
  }
  component beacon : Base
  {
    publisher <relay/signal> signal_pub;
  }
  component sleeper : Base
  {
    timer nap_timer
    {
      period = 600.0;
      priority = 50;
      deadline = 1.0;
    }
    timer spare_timer
    {
      period = 0.0;
      priority = 50;
      deadline = 1.0;
    }
    publisher <relay/nap> nap_pub;
  }
}
""".replace("CALL_PERIOD", str(CALL_PERIOD))

_HARDWARE = """\
hardware bench
{
  ip_address = "127.0.0.1";
  username = "robot";
  sshkey = "~/.ssh/id_rsa";
  deployment_path = "/tmp/relay";
  install_path = "/opt/ros";
  arch = x64;
}
"""


def _instance(name: str, component: str) -> str:
    return f"""\
  component_instance {name}
  {{
    properties
    {{
      ref = "relay/{component}";
      scheduling_scheme = FIFO;
    }}
  }}
"""


def _node(name: str, *instances: tuple[str, str]) -> str:
    head = f'node {name}\n{{\n  properties\n  {{\n    ref = "bench/bench";\n    priority = 50;\n  }}\n'
    return head + "".join(_instance(*pair) for pair in instances) + "}\n"


_DEPLOYMENT = (
    "using bench;\n"
    + _node("both", ("caller_i", "caller"), ("answerer_i", "answerer"))
    + "".join(_node(f"ear_{n}", ("listener_i", "listener")) for n in (1, 2))
    + _node("beacon", ("beacon_i", "beacon"))
    + _node("slow", ("sleeper_i", "sleeper"))
)

#: path in the project -> text
PROJECT_FILES = {
    "relay.rosmod": "This is a ROSMOD Project",
    "01-Software/software.rml": _SOFTWARE,
    "01-Software/msg/relay.tick.msg": "uint8[] data\n",
    "01-Software/msg/relay.answer.msg": "uint8[] data\n",
    "01-Software/msg/relay.nap.msg": "uint8[] data\n",
    "01-Software/msg/relay.signal.msg": "uint8[] data\n",
    "01-Software/srv/relay.poke.srv": "int32 ask\n---\nint32 answer\n",
    "02-Hardware/bench.rhw": _HARDWARE,
    "03-Deployment/relay.rdp": _DEPLOYMENT,
}


def write_project(folder: Path) -> Path:
    """Write the project into ``folder`` (made); return it."""
    for path, text in PROJECT_FILES.items():
        target = folder / path
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(text, encoding="utf-8")
    return folder


def converted_project(folder: Path) -> Path:
    """Write the project into ``folder/project`` and convert it to AADL (``rosaadl convert``) into
    ``folder/aadl``; return the AADL folder."""
    project = write_project(folder / "project")
    done = subprocess.run(
        [sys.executable, "-m", "rosaadl", "-q", "convert", str(project), "-o", str(folder / "aadl")],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return folder / "aadl"

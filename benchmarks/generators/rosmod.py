"""ROSMOD projects generated at scale: as a model, and as the files of a textual v0.3 project.

* :func:`rosmod_project`: a ``rosmod.Project`` built with the model API (``bench_rosmod_convert``).
* :func:`write_rosmod_project`: the ``.rml``/``.rhw``/``.rdp`` files of a v0.3 project
  (``bench_rosmod_import``).
"""

from __future__ import annotations

from decimal import Decimal
from pathlib import Path

from pyecore.ecore import EObject

from rosaadl import model

__all__ = ["rosmod_project", "write_rosmod_project"]


def rosmod_project(nodes: int) -> EObject:
    """A ``rosmod.Project`` of ``nodes`` nodes, each running one component instance with 5
    callbacks (2 timers, 2 subscribers, 1 server) plus a publisher and a client; there are
    ``nodes / 2`` message types, so that every topic joins 2 publishers to 4 subscribers."""
    new = model.new
    components = max(1, nodes // 2)
    package = new("rosmod.Package", name="gen")
    for k in range(components):
        package.messages.append(
            new(
                "rosmod.Message",
                name=f"Topic{k}",
                definition=f"uint64 stamp\nfloat64[{k % 4 + 1}] values\n",
                fields=[
                    new("rosmod.Field", name="stamp", type="uint64"),
                    new("rosmod.Field", name="values", type="float64", isArray=True, arrayLength=k % 4 + 1),
                ],
            )
        )
    package.services.append(new("rosmod.Service", name="Call", definition="int64 request\n---\nbool ok\n"))
    comps = []
    for k in range(components):
        comp = new("rosmod.Component", name=f"comp_{k}", datatype="Base")
        comp.ports.extend(
            [
                new("rosmod.Publisher", name="out", type=f"gen/Topic{k}"),
                new("rosmod.Client", name="ask", type="gen/Call"),
                new(
                    "rosmod.Subscriber",
                    name="in_a",
                    type=f"gen/Topic{(k + 1) % components}",
                    priority=50,
                    deadline=Decimal("0.05"),
                ),
                new(
                    "rosmod.Subscriber",
                    name="in_b",
                    type=f"gen/Topic{(k + 2) % components}",
                    priority=40,
                    deadline=Decimal("0.1"),
                ),
                new("rosmod.Server", name="answer", type="gen/Call", priority=60, deadline=Decimal("0.02")),
            ]
        )
        comp.timers.extend(
            [
                new(
                    "rosmod.Timer", name="fast", period=Decimal("0.01"), priority=70, deadline=Decimal("0.01")
                ),
                new("rosmod.Timer", name="slow", period=Decimal("1.0"), priority=30, deadline=Decimal("0.5")),
            ]
        )
        comps.append(comp)
    package.components.extend(comps)
    system = new("rosmod.System", name="cluster")
    hosts = [
        new("rosmod.Host", name=f"host_{h}", ipAddress=f"10.0.{h // 250}.{h % 250}", architecture="x64")
        for h in range(max(1, nodes // 10))
    ]
    system.hosts.extend(hosts)
    deployment = new("rosmod.Deployment", name="generated", systemName="cluster", system=system)
    for n in range(nodes):
        host = hosts[n % len(hosts)]
        node = new("rosmod.Node", name=f"node_{n}", priority=50, host=host, hostRef=f"cluster/{host.name}")
        comp = comps[n % components]
        node.componentInstances.append(
            new(
                "rosmod.ComponentInstance",
                name=f"inst_{n}",
                component=comp,
                componentRef=f"gen/{comp.name}",
                schedulingScheme="PFIFO",
            )
        )
        deployment.nodes.append(node)
    project = new("rosmod.Project", name=f"generated_{nodes}", formatVersion="0.3")
    project.software = new("rosmod.Software", name="software", packages=[package])
    project.systems.append(system)
    project.deployments.append(deployment)
    return project


def write_rosmod_project(folder: Path, nodes: int) -> Path:
    """Write a textual v0.3 project of ``nodes`` nodes into ``folder``; returns its folder.

    Each node runs one component instance with 5 callbacks (2 timers, 2 subscribers, 1 server)
    plus 2 publishers and a client, over 20 message types and 5 services."""
    project = folder / f"generated_{nodes}"
    sw = project / "01-Software"
    (sw / "msg").mkdir(parents=True)
    (sw / "srv").mkdir()
    (project / "02-Hardware").mkdir()
    (project / "03-Deployment").mkdir()
    (project / f"generated_{nodes}.rosmod").write_text("This is a ROSMOD Project")
    topics = 20
    for k in range(topics):
        (sw / "msg" / f"gen.Topic{k}.msg").write_text(
            f"uint64 stamp\nfloat64[{k % 4 + 1}] values\nint32 id\n"
        )
    for k in range(topics // 4):
        (sw / "srv" / f"gen.Call{k}.srv").write_text("int64 request\n---\nbool ok\nfloat64 value\n")
    rml = ["/*\n * generated software model\n */\npackage gen\n{\n"]
    for c in range(nodes):
        a, b = c % topics, (c + 7) % topics
        s = c % (topics // 4)
        rml.append(
            f"  // ROSMOD Component - comp_{c}\n  component comp_{c} : Base\n  {{\n"
            f"    publisher <gen/Topic{a}> out_a;\n    publisher <gen/Topic{b}> out_b;\n"
            f"    client <gen/Call{(s + 1) % (topics // 4)}> ask;\n"
            f"    subscriber <gen/Topic{b}> in_b\n    {{\n      priority = 50;\n"
            "      deadline = 0.05;\n    }\n"
            f"    subscriber <gen/Topic{(a + 3) % topics}> in_c\n    {{\n      priority = 40;\n"
            "      deadline = 0.1;\n    }\n"
            f"    server <gen/Call{s}> answer\n    {{\n      priority = 60;\n      deadline = 0.02;\n    }}\n"
            "    timer fast\n    {\n\tperiod = 0.01;\n\tpriority = 70;\n\tdeadline = 0.01;\n    }\n"
            "    timer slow\n    {\n\tperiod = 1.0;\n\tpriority = 30;\n\tdeadline = 0.5;\n    }\n  }\n"
        )
    rml.append("}\n")
    (sw / "generated.rml").write_text("".join(rml))
    hosts = max(1, nodes // 10)
    (project / "02-Hardware" / "cluster.rhw").write_text(
        "".join(
            f'hardware host_{h}\n{{\n  ip_address = "10.{h // 250}.{h % 250}.1";\n  username = "ros";\n'
            f'  sshkey = "~/.ssh/id_rsa";\n  deployment_path = "/home/ros";\n'
            f'  install_path = "/opt/ros/indigo";\n  arch = armv7l;\n}}\n'
            for h in range(hosts)
        )
    )
    rdp = ["using cluster;\n"]
    for c in range(nodes):
        rdp.append(
            f"// ROSMOD Node - node_{c}\nnode node_{c}\n{{\n  properties\n  {{\n"
            f'    ref = "cluster/host_{c % hosts}";\n    priority = 50;\n  }}\n'
            f"  component_instance comp_{c}_i\n  {{\n      properties\n      {{\n"
            f'\tref = "gen/comp_{c}";\n\tscheduling_scheme = FIFO;\n\tlogging\n\t{{\n'
            "\t  Is Periodic? = true;\n\t  Periodic Log Unit = 1000;\n\t}\n      }\n  }\n}\n"
        )
    (project / "03-Deployment" / "deployment.rdp").write_text("".join(rdp))
    return project

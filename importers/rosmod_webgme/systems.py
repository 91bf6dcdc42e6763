"""The ``Systems`` of a WebGME ROSMOD project → ``rosmod.System`` objects with hosts, networks and links.

A host takes ``Architecture``, ``OS`` and ``ROS Install`` into its slots, the first member of its
``Users`` set (by name) gives ``username``/``sshKey``/``deploymentPath``, and the ``IP`` of a link
from one of its interfaces gives ``ipAddress``. A link joins an interface of the system (``src``)
to a network of the system (``dst``); other ends are left out with a warning.
"""

from __future__ import annotations

import json
import os

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.importers.rosmod_webgme.mapping import SKIPPED_KINDS, Mapper, text
from rosaadl.importers.rosmod_webgme.tree import Node

__all__ = ["system", "host"]


def system(m: Mapper, node: Node) -> EObject:
    """A ``System``: its hosts, networks and links (users are kept as ``User:<name>`` properties)."""
    system = model.new("rosmod.System", name=node.name, sourceFile=os.path.basename(m.filename))
    m.by_path[node.path] = system
    links = []
    for child in m.children(node):
        kind = child.meta_type
        if kind == "Host":
            system.hosts.append(host(m, child))
        elif kind == "Network":
            network = model.new(
                "rosmod.Network",
                name=child.name,
                subnet=text(child.attribute("Subnet")) or None,
                netmask=text(child.attribute("Netmask")) or None,
            )
            system.networks.append(network)
            m.by_path[child.path] = network
        elif kind == "Link":
            links.append(child)
        elif kind == "User":
            system.properties.append(
                m.prop(
                    f"User:{child.name}",
                    json.dumps({k: text(child.attribute(k)) for k in ("Directory", "Key")}, sort_keys=True),
                )
            )
        elif kind not in SKIPPED_KINDS:
            m.unknown(node, child, system.properties)
    for child in links:
        link = model.new("rosmod.Link", name=child.name, ip=text(child.attribute("IP")) or None)
        src = child.pointer("src")
        dst = child.pointer("dst")
        interface = m.by_path.get(src.path) if src is not None else None
        network = m.by_path.get(dst.path) if dst is not None else None
        if model.is_a(interface, "rosmod.Interface"):
            link.interface = interface
            link.host = interface.eContainer()
        elif src is not None:
            m.warn(
                child,
                f"link {child.name!r}: its src {src.element_path()!r} is not an interface of this system",
            )
        if model.is_a(network, "rosmod.Network"):
            link.network = network
        elif dst is not None:
            m.warn(
                child, f"link {child.name!r}: its dst {dst.element_path()!r} is not a network of this system"
            )
        for key, value in child.project_attributes().items():
            if key != "IP":
                m.warn(child, f"link attribute {key!r} = {text(value)!r} has no rosmod slot; dropped")
        system.links.append(link)
        if link.host is not None and link.host.ipAddress is None and link.ip:
            link.host.ipAddress = link.ip
    return system


def host(m: Mapper, node: Node) -> EObject:
    """A ``Host`` with its interfaces; its first user gives ``username``, ``sshKey``, ``deploymentPath``."""
    host = model.new(
        "rosmod.Host",
        name=node.name,
        architecture=text(node.attribute("Architecture")) or None,
        os=text(node.attribute("OS")) or None,
        installPath=text(node.attribute("ROS Install")) or None,
    )
    m.by_path[node.path] = host
    for key, value in node.project_attributes().items():
        if key not in ("Architecture", "OS", "ROS Install"):
            host.properties.append(m.prop(key, value))
    users = sorted(node.set_members("Users"), key=lambda u: (u.name, u.path))
    if users:
        first = users[0]
        host.username = first.name
        host.sshKey = text(first.attribute("Key")) or None
        host.deploymentPath = text(first.attribute("Directory")) or None
        if len(users) > 1:
            host.properties.append(m.prop("Users", ", ".join(u.name for u in users)))
    for child in m.children(node):
        if child.meta_type == "Interface":
            interface = model.new("rosmod.Interface", name=child.name)
            host.interfaces.append(interface)
            m.by_path[child.path] = interface
        elif child.meta_type not in SKIPPED_KINDS:
            host.properties.append(m.prop(f"{child.meta_type}:{child.name}", m.opaque(child)))
    return host

"""Declarative AADL (``aadl.ecore``) → ROSMOD projects (``rosmod.ecore``).

:func:`aadl_to_rosmod` has two modes:

* **the convention** — for packages made by :func:`rosaadl.transforms.rosmod_to_aadl.rosmod_to_aadl`
  (marked ``ROSMOD_Properties::Unit_Kind``), the inverse mapping, read from the declarative
  model: software packages give packages, messages, services and components (ports from the
  thread group's features, timers from its periodic threads, callback priorities and deadlines
  from the threads connected to its ports); hardware packages give hardware models (processors
  → hosts, buses → networks, bus access connections → links); deployment packages give
  deployments (processes → nodes bound to their hosts by ``Actual_Processor_Binding``, thread
  group subcomponents → component instances); the project package gives the project's own
  data. The ROSMOD name of every element is its ``ROSMOD_Properties::Name``, else the name the
  forward conversion's trace gives for it (``trace=``), else its AADL name; so a project
  converted forward and back is the original one (``docs/rosmod-aadl-mapping.md``).
* **best effort** — for other AADL models: each root system implementation (``roots=``, by
  default the top-level ones of packages that are not part of rosaadl's library) is
  instantiated; each process becomes a node (on the host of the processor it is bound to), each
  thread a component instance of a component made from the thread's classifier, with a timer
  when the thread is periodic and publishers, subscribers, clients and servers from its ports
  (message types from ``ROS_Properties::Message_Type``, else an empty message named after the
  data classifier); processors become hosts. Each element that has no ROSMOD counterpart
  (devices, buses, memories, abstract components, ports without a direction ROSMOD knows, threads
  that neither run periodically nor on an input, connections that ROSMOD's matching by message
  type would not make) is reported as a located warning.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable, Sequence
from decimal import Decimal, InvalidOperation
from functools import lru_cache
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, Location, RosaadlError, TransformationError
from rosaadl.importers import ros_msg
from rosaadl.importers.rosmod_text import scheme_literal
from rosaadl.properties import EnumLiteral, Reference, own_property, python_value
from rosaadl.transforms import rosmod_to_aadl as fwd
from rosaadl.transforms import trace as tracing
from rosaadl.units import Quantity

__all__ = ["aadl_to_rosmod", "top_level_systems", "is_rosmod_convention", "convert_aadl_files"]

log = logging.getLogger(__name__)

_SCHEMES = ("FIFO", "PFIFO", "EDF")


def _new(class_name: str, /, **values: Any) -> EObject:
    return _model.new(f"rosmod.{class_name}", **{k: v for k, v in values.items() if v is not None})


def _set(obj: EObject, **values: Any) -> None:
    """Set the features whose value is not None (the others stay unset)."""
    for key, value in values.items():
        if value is not None:
            setattr(obj, key, value)


def _enum(value: object) -> str:
    return str(getattr(value, "name", value) or "")


def _value(holder: EObject, prop: str) -> Any:
    return own_property(holder, prop)


def _text(holder: EObject, prop: str) -> str | None:
    value = _value(holder, prop)
    return value if isinstance(value, str) else None


def _int(holder: EObject, prop: str) -> int | None:
    value = _value(holder, prop)
    if isinstance(value, Quantity):
        value = value.value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    return int(value)


def _seconds(holder: EObject, prop: str, text_prop: str | None = None) -> Decimal | None:
    """The seconds of a time property; its ROSMOD text (``text_prop``) when it has that value."""
    value = _value(holder, prop)
    if not isinstance(value, Quantity):
        return None
    seconds = fwd.time_to_seconds(value.value, value.unit)
    text = _text(holder, text_prop) if text_prop is not None and seconds is not None else None
    if text is not None:
        try:
            written = Decimal(text)
        except InvalidOperation:
            return seconds
        if written == seconds:
            return written
    return seconds


def _location(element: EObject | None, path: str | None = None) -> Location:
    if element is None:
        return Location(path=path)
    file = None
    current = element
    while current is not None:
        feature = current.eClass.findEStructuralFeature("sourceFile")
        if feature is not None and current.eGet(feature):
            file = current.eGet(feature)
            break
        current = current.eContainer()
    line = getattr(element, "line", None) if element.eClass.findEStructuralFeature("line") else None
    column = getattr(element, "column", None) if element.eClass.findEStructuralFeature("column") else None
    return Location(file=file, line=line or None, column=column or None, path=path)


def is_rosmod_convention(model: EObject) -> bool:
    """True when the model holds packages made by the ROSMOD → AADL conversion."""
    return any(
        unit.eClass.name == "AadlPackage" and own_property(unit, fwd.UNIT_KIND) is not None
        for unit in model.units
    )


@lru_cache(maxsize=1)
def _library_folder() -> Path | None:
    try:
        from importlib import resources

        return Path(str(resources.files("rosaadl.library"))).resolve()
    except (ModuleNotFoundError, TypeError):  # pragma: no cover - the library is package data
        return None


def _is_library_unit(unit: EObject) -> bool:
    folder = _library_folder()
    source = getattr(unit, "sourceFile", None)
    if not source or folder is None:
        return False
    try:
        return folder in Path(source).resolve().parents
    except OSError:  # pragma: no cover - a path the OS cannot resolve
        return False


def top_level_systems(model: EObject, units: Iterable[EObject] | None = None) -> list[str]:
    """Qualified names of the system implementations of ``units`` (default: the model's units that
    are not rosaadl library files) that no classifier of the model uses as a subcomponent or
    extends: the roots a best-effort conversion instantiates."""
    used: set[str] = set()
    for unit in model.units:
        if unit.eClass.name != "AadlPackage":
            continue
        for classifier in unit.classifiers:
            if classifier.extended:
                used.add(_qualify(classifier.extended, unit).lower())
            if classifier.eClass.name == "ComponentImplementation":
                for sub in classifier.subcomponents:
                    if sub.classifier:
                        used.add(_qualify(sub.classifier, unit).lower())
    chosen = list(units) if units is not None else [u for u in model.units if not _is_library_unit(u)]
    roots = []
    for unit in chosen:
        if unit.eClass.name != "AadlPackage":
            continue
        for classifier in unit.classifiers:
            if classifier.eClass.name != "ComponentImplementation" or _enum(classifier.category) != "system":
                continue
            name = f"{unit.name}::{classifier.name}"
            if name.lower() not in used:
                roots.append(name)
    return roots


def _qualify(name: str, unit: EObject) -> str:
    name = "".join(name.split())
    return name if "::" in name else f"{unit.name}::{name}"


# =========================================================================== diagnostics


class _Report:
    def __init__(self, warnings: list[Diagnostic] | None) -> None:
        self.warnings = warnings

    def warn(self, message: str, location: Location) -> None:
        diag = Diagnostic("warning", message, location)
        log.warning("%s", diag)
        if self.warnings is not None:
            self.warnings.append(diag)


# =========================================================================== the convention


class _Index:
    """Classifiers of the model by lower-case qualified name."""

    def __init__(self, model: EObject) -> None:
        self.classifiers: dict[str, EObject] = {}
        self.unit_of: dict[int, EObject] = {}
        for unit in model.units:
            if unit.eClass.name != "AadlPackage":
                continue
            for classifier in unit.classifiers:
                self.classifiers.setdefault(f"{unit.name}::{classifier.name}".lower(), classifier)
                self.unit_of[id(classifier)] = unit

    def find(self, name: str | None, context: EObject) -> EObject | None:
        """The classifier ``name``, unqualified names looked up in the package of ``context``."""
        if not name:
            return None
        unit = context
        while unit is not None and unit.eClass.name != "AadlPackage":
            unit = unit.eContainer()
        if unit is None:
            return self.classifiers.get("".join(name.split()).lower())
        return self.classifiers.get(_qualify(name, unit).lower())

    def implementation(self, ctype: EObject) -> EObject | None:
        unit = self.unit_of.get(id(ctype))
        if unit is None:
            return None
        found = self.classifiers.get(f"{unit.name}::{ctype.name}.impl".lower())
        if found is not None:
            return found
        for classifier in unit.classifiers:
            if (
                classifier.eClass.name == "ComponentImplementation"
                and (classifier.type or "").lower() == (ctype.name or "").lower()
            ):
                return classifier
        return None


class _Convention:
    """The inverse of the forward conversion, on the declarative model."""

    def __init__(self, model: EObject, trace: EObject | None, report: _Report) -> None:
        self.model = model
        self.report = report
        self.index = _Index(model)
        self.trace = tracing.TraceIndex(trace) if trace is not None else None
        self.components: dict[str, EObject] = {}  # lower qualified impl/type name → Component
        self.hardware: dict[str, tuple[EObject, dict[str, EObject]]] = {}  # system impl → (System, hosts)
        self.systems_by_name: dict[str, EObject] = {}

    # -- names
    def name(self, element: EObject, default: str | None = None, suffix: str = "") -> str | None:
        given = _text(element, fwd.NAME)
        if given is not None:
            return given
        if self.trace is not None and element.eContainer() is not None:
            origin = self._traced_name(element)
            if origin is not None:
                return origin
        name = default if default is not None else element.name
        if suffix and name and name.endswith(suffix) and len(name) > len(suffix):
            return name[: -len(suffix)]
        return name

    def _traced_name(self, element: EObject) -> str | None:
        keys = self.trace.origin_keys(tracing.element_key(element))
        if not keys:
            return None
        step = keys[0].rstrip("/").rpartition("/")[2]
        if "[" in step and step.endswith("]"):
            return step[step.index("[") + 1 : -1]
        return None

    def settings(self, holder: EObject, prop: str = fwd.SETTINGS) -> list[EObject]:
        value = _value(holder, prop)
        out = []
        for item in value if isinstance(value, list) else []:
            if isinstance(item, dict):
                out.append(_new("Property", key=_str(item.get("Key")), value=_str(item.get("Value"))))
        return out

    def warn(self, message: str, element: EObject | None) -> None:
        self.report.warn(message, _location(element, _path(element)))

    # -- whole project
    def run(self) -> EObject:
        units = [u for u in self.model.units if u.eClass.name == "AadlPackage"]
        kinds: dict[str, list[EObject]] = {}
        for position, unit in enumerate(units):
            kind = own_property(unit, fwd.UNIT_KIND)
            if kind is None:
                if not _is_library_unit(unit):
                    self.warn(
                        f"package {unit.name} is not part of a ROSMOD project (no Unit_Kind); skipped", unit
                    )
                continue
            kinds.setdefault(str(kind).lower(), []).append(
                (_int(unit, fwd.POSITION) or 10**9, position, unit)
            )
        ordered = {k: [u for *_, u in sorted(v, key=lambda t: (t[0], t[1]))] for k, v in kinds.items()}
        project_units = ordered.get("project", [])
        if len(project_units) > 1:
            self.warn(f"{len(project_units)} project packages; the first one is used", project_units[1])
        project = _new("Project", name=self.model.name)
        software_units = ordered.get("software", [])
        if project_units:
            unit = project_units[0]
            project.name = self.name(unit, suffix=fwd.UNIT_SUFFIXES["Project"])
            project.formatVersion = _text(unit, fwd.FORMAT_VERSION)
            project.path = _text(unit, fwd.PROJECT_PATH)
            project.properties.extend(self.settings(unit))
            software_name = _text(unit, fwd.SOFTWARE_NAME)
            if software_name is not None or software_units:
                project.software = _new(
                    "Software", name=software_name, sourceFile=_text(unit, fwd.SOURCE_FILE)
                )
        elif software_units:
            project.software = _new("Software", name=self.model.name)
        for unit in software_units:
            project.software.packages.append(self.package(unit))
        for unit in ordered.get("hardware", []):
            project.systems.append(self.system(unit))
        for unit in ordered.get("deployment", []):
            project.deployments.append(self.deployment(unit))
        return project

    # -- software
    def package(self, unit: EObject) -> EObject:
        package = _new("Package", name=self.name(unit))
        package.properties.extend(self.settings(unit))
        pending = []
        for classifier in unit.classifiers:
            if classifier.eClass.name != "ComponentType":
                continue
            category = _enum(classifier.category)
            if category == "data":
                if _text(classifier, fwd.MESSAGE_TYPE) is not None:
                    package.messages.append(self.message(classifier, package.name))
            elif category == "subprogram":
                if _text(classifier, fwd.SERVICE_TYPE) is not None:
                    package.services.append(self.service(classifier, package.name))
            elif category == "threadGroup":
                pending.append(classifier)
            elif category != "thread":
                self.warn(
                    f"{category} {classifier.name} has no ROSMOD counterpart in a software package",
                    classifier,
                )
        for classifier in pending:
            package.components.append(self.component(classifier, unit))
        return package

    def _definition(self, classifier: EObject) -> str | None:
        return _text(classifier, fwd.DEFINITION)

    def message(self, classifier: EObject, package: str) -> EObject:
        msg = _new("Message", name=self.name(classifier), definition=self._definition(classifier))
        if msg.definition:
            try:
                spec = ros_msg.parse_msg(msg.definition, name=msg.name, package=package)
                msg.fields.extend(ros_msg.fields_to_model(spec.fields))
            except RosaadlError as exc:
                self.warn(f"message {msg.name}: its definition does not parse ({exc.message})", classifier)
        return msg

    def service(self, classifier: EObject, package: str) -> EObject:
        srv = _new("Service", name=self.name(classifier), definition=self._definition(classifier))
        if srv.definition:
            try:
                spec = ros_msg.parse_srv(srv.definition, name=srv.name, package=package)
                srv.requestFields.extend(ros_msg.fields_to_model(spec.request.fields))
                srv.responseFields.extend(ros_msg.fields_to_model(spec.response.fields))
            except RosaadlError as exc:
                self.warn(f"service {srv.name}: its definition does not parse ({exc.message})", classifier)
        return srv

    def port_type(self, feature: EObject, context: EObject) -> str | None:
        given = _text(feature, fwd.MESSAGE_TYPE)
        if given is not None:
            return given
        target = self.index.find(feature.classifier, context)
        if target is None:
            if feature.classifier:
                self.warn(
                    f"feature {feature.name}: classifier {feature.classifier} does not resolve", feature
                )
            return None
        for prop in (fwd.MESSAGE_TYPE, fwd.SERVICE_TYPE):
            found = _text(target, prop)
            if found is not None:
                return found
        unit = self.index.unit_of.get(id(target))
        return f"{unit.name}/{target.name}" if unit is not None else target.name

    def component(self, ctype: EObject, unit: EObject) -> EObject:
        comp = _new("Component", name=self.name(ctype), datatype=_text(ctype, fwd.DATATYPE))
        scheme = _value(ctype, fwd.SCHEDULING_SCHEME)
        if isinstance(scheme, EnumLiteral) and scheme.name.upper() in _SCHEMES:
            comp.schedulingScheme = scheme_literal(scheme.name.upper())
        comp.properties.extend(self.settings(ctype))
        ports: dict[str, EObject] = {}
        for feature in ctype.features:
            category = _enum(feature.category)
            direction = _enum(feature.direction)
            access = _enum(feature.access)
            if category in ("eventDataPort", "dataPort", "eventPort") and direction in ("in", "out"):
                cls = "Publisher" if direction == "out" else "Subscriber"
            elif category == "subprogramAccess":
                cls = "Client" if access == "requires" else "Server"
            else:
                self.warn(f"feature {feature.name} of {ctype.name} is not a ROSMOD port; skipped", feature)
                continue
            port = _new(cls, name=self.name(feature), type=self.port_type(feature, ctype))
            if cls == "Publisher":
                latching = _value(feature, fwd.LATCHING)
                if isinstance(latching, bool):
                    port.latching = latching
            comp.ports.append(port)
            ports[feature.name.lower()] = port
        impl = self.index.implementation(ctype)
        if impl is None:
            self.warn(f"thread group {ctype.name} has no implementation: no timers or callbacks", ctype)
        else:
            self.callbacks(comp, impl, ports)
        self.components[f"{unit.name}::{impl.name if impl is not None else ctype.name}".lower()] = comp
        self.components.setdefault(f"{unit.name}::{ctype.name}".lower(), comp)
        return comp

    def callbacks(self, comp: EObject, impl: EObject, ports: dict[str, EObject]) -> None:
        served: dict[str, EObject] = {}  # thread name → the port it serves
        for conn in impl.connections:
            source, destination = conn.source or "", conn.destination or ""
            kind = _enum(conn.kind)
            if kind == "portConnection" and "." not in source and "." in destination:
                port = ports.get(source.lower())
                if port is not None:
                    served[destination.partition(".")[0].lower()] = port
            elif kind == "accessConnection" and "." in source and "." not in destination:
                port = ports.get(destination.lower())
                if port is not None and port.eClass.name == "Server":
                    served[source.partition(".")[0].lower()] = port
        for sub in impl.subcomponents:
            category = _enum(sub.category)
            if category == "data":
                continue
            if category != "thread":
                self.warn(f"{category} {sub.name} in {impl.name} has no ROSMOD counterpart; skipped", sub)
                continue
            port = served.get(sub.name.lower())
            if port is not None:
                _set(
                    port,
                    priority=_int(sub, fwd.PRIORITY),
                    deadline=_seconds(sub, fwd.DEADLINE, fwd.DEADLINE_SECONDS),
                    operation=_text(sub, fwd.OPERATION),
                )
                continue
            comp.timers.append(
                _new(
                    "Timer",
                    name=self.name(sub),
                    period=_seconds(sub, fwd.PERIOD, fwd.PERIOD_SECONDS),
                    priority=_int(sub, fwd.PRIORITY),
                    deadline=_seconds(sub, fwd.DEADLINE, fwd.DEADLINE_SECONDS),
                    operation=_text(sub, fwd.OPERATION),
                )
            )

    # -- hardware
    def system(self, unit: EObject) -> EObject:
        system = _new(
            "System",
            name=self.name(unit, suffix=fwd.UNIT_SUFFIXES["Hardware"]),
            sourceFile=_text(unit, fwd.SOURCE_FILE),
        )
        system.properties.extend(self.settings(unit))
        impl = next(
            (
                c
                for c in unit.classifiers
                if c.eClass.name == "ComponentImplementation" and _enum(c.category) == "system"
            ),
            None,
        )
        hosts: dict[str, EObject] = {}
        if impl is None:
            self.warn(f"hardware package {unit.name} has no system implementation", unit)
            return system
        networks: dict[str, EObject] = {}
        interfaces: dict[tuple[str, str], EObject] = {}
        for sub in impl.subcomponents:
            category = _enum(sub.category)
            ptype = self.index.find(sub.classifier, impl)
            if category == "processor":
                host = _new("Host", name=self.name(sub))
                if ptype is not None:
                    _set(
                        host,
                        ipAddress=_text(ptype, fwd.IP_ADDRESS),
                        username=_text(ptype, fwd.USERNAME),
                        sshKey=_text(ptype, fwd.SSH_KEY),
                        deploymentPath=_text(ptype, fwd.DEPLOYMENT_PATH),
                        installPath=_text(ptype, fwd.INSTALL_PATH),
                        architecture=_text(ptype, fwd.ARCHITECTURE),
                        os=_text(ptype, fwd.OS),
                    )
                    host.properties.extend(self.settings(ptype))
                    for feature in ptype.features if ptype.eClass.name == "ComponentType" else []:
                        if _enum(feature.category) == "busAccess":
                            interface = _new("Interface", name=self.name(feature))
                            host.interfaces.append(interface)
                            interfaces[(sub.name.lower(), feature.name.lower())] = interface
                system.hosts.append(host)
                hosts[sub.name.lower()] = host
            elif category == "bus":
                network = _new(
                    "Network",
                    name=self.name(sub),
                    subnet=_text(ptype, fwd.SUBNET) if ptype is not None else None,
                    netmask=_text(ptype, fwd.NETMASK) if ptype is not None else None,
                )
                system.networks.append(network)
                networks[sub.name.lower()] = network
            else:
                self.warn(f"{category} {sub.name} of {impl.name} has no ROSMOD counterpart; skipped", sub)
        for conn in impl.connections:
            if _enum(conn.kind) != "accessConnection":
                self.warn(f"connection {conn.name} of {impl.name} is not a link; skipped", conn)
                continue
            network = networks.get((conn.source or "").lower())
            host_name, _, iface_name = (conn.destination or "").partition(".")
            host = hosts.get(host_name.lower())
            interface = interfaces.get((host_name.lower(), iface_name.lower()))
            if network is None or host is None or interface is None:
                self.warn(f"connection {conn.name} does not join a bus to a processor's bus access", conn)
                continue
            system.links.append(
                _new(
                    "Link",
                    name=self.name(conn),
                    ip=_text(conn, fwd.IP_ADDRESS),
                    host=host,
                    network=network,
                    interface=interface,
                )
            )
        self.hardware[f"{unit.name}::{impl.name}".lower()] = (system, hosts)
        return system

    # -- deployment
    def deployment(self, unit: EObject) -> EObject:
        deployment = _new(
            "Deployment",
            name=self.name(unit, suffix=fwd.UNIT_SUFFIXES["Deployment"]),
            sourceFile=_text(unit, fwd.SOURCE_FILE),
            systemName=_text(unit, fwd.SYSTEM_NAME),
        )
        deployment.properties.extend(self.settings(unit))
        impl = next(
            (
                c
                for c in unit.classifiers
                if c.eClass.name == "ComponentImplementation" and _enum(c.category) == "system"
            ),
            None,
        )
        if impl is None:
            self.warn(f"deployment package {unit.name} has no system implementation", unit)
            return deployment
        hardware: dict[str, tuple[EObject, dict[str, EObject]]] = {}
        bindings: dict[str, Any] = {}
        for assoc in impl.ownedPropertyAssociations:
            if _model_property(assoc, fwd.PROCESSOR_BINDING):
                for target in assoc.appliesTo:
                    bindings[" ".join(target.split()).lower()] = assoc
        for sub in impl.subcomponents:
            category = _enum(sub.category)
            if category == "system":
                found = self.hardware.get(
                    _qualify(sub.classifier or "", self.index.unit_of[id(impl)]).lower()
                )
                if found is None:
                    self.warn(f"system {sub.name} is not a hardware model of the project", sub)
                    continue
                hardware[sub.name.lower()] = found
                if deployment.system is None and found[0].name == deployment.systemName:
                    deployment.system = found[0]
            elif category == "process":
                deployment.nodes.append(self.node(sub, impl, hardware, bindings))
            elif category != "virtualBus":
                self.warn(f"{category} {sub.name} of {impl.name} has no ROSMOD counterpart; skipped", sub)
        return deployment

    def node(self, sub: EObject, impl: EObject, hardware: dict, bindings: dict) -> EObject:
        ptype_impl = self.index.find(sub.classifier, impl)
        ptype = None
        if ptype_impl is not None and ptype_impl.eClass.name == "ComponentImplementation":
            ptype = self.index.find(ptype_impl.type, ptype_impl)
        elif ptype_impl is not None:
            ptype, ptype_impl = ptype_impl, None
        node = _new("Node", name=self.name(sub))
        if ptype is not None:
            _set(
                node,
                priority=_int(ptype, fwd.PRIORITY),
                arguments=_text(ptype, fwd.ARGUMENTS),
                hostRef=_text(ptype, fwd.HOST_REF),
            )
            node.properties.extend(self.settings(ptype))
        assoc = bindings.get(sub.name.lower())
        if assoc is not None:
            targets = _references(assoc)
            host = None
            if targets:
                hw_name, _, host_name = targets[0].partition(".")
                found = hardware.get(hw_name.lower())
                if found is not None:
                    host = found[1].get(host_name.lower())
            if host is None:
                self.warn(
                    f"process {sub.name} is bound to {targets}, which is not a host of the project", assoc
                )
            else:
                node.host = host
                if node.hostRef is None:
                    node.hostRef = f"{host.eContainer().name}/{host.name}"
        if ptype_impl is None:
            self.warn(f"process {sub.name} has no implementation: no component instances", sub)
            return node
        for inner in ptype_impl.subcomponents:
            if _enum(inner.category) != "threadGroup":
                self.warn(
                    f"{_enum(inner.category)} {inner.name} of a node is not a component instance", inner
                )
                continue
            node.componentInstances.append(self.instance(inner, ptype_impl))
        return node

    def instance(self, sub: EObject, impl: EObject) -> EObject:
        inst = _new("ComponentInstance", name=self.name(sub))
        qualified = _qualify(sub.classifier or "", self.index.unit_of[id(impl)]).lower()
        comp = self.components.get(qualified)
        if comp is None:
            self.warn(f"thread group {sub.name}: {sub.classifier} is not a component of the project", sub)
        else:
            inst.component = comp
            package = comp.eContainer()
            inst.componentRef = _text(sub, fwd.COMPONENT_REF) or f"{package.name}/{comp.name}"
        scheme = _value(sub, fwd.SCHEDULING_SCHEME)
        if isinstance(scheme, EnumLiteral) and scheme.name.upper() in _SCHEMES:
            inst.schedulingScheme = scheme_literal(scheme.name.upper())
        inst.logging.extend(self.settings(sub, fwd.LOGGING))
        ports = _value(sub, fwd.PORT_INSTANCES)
        for item in ports if isinstance(ports, list) else []:
            if isinstance(item, dict):
                inst.portInstances.append(
                    _new(
                        "PortInstance",
                        name=_str(item.get("Name")),
                        port=_str(item.get("Port_Ref")),
                        group=_str(item.get("Group_Name")),
                    )
                )
        inst.properties.extend(self.settings(sub))
        return inst


def _words(category: str) -> str:
    """``threadGroup`` → ``thread group``."""
    return "".join(f" {c.lower()}" if c.isupper() else c for c in category)


def _str(value: Any) -> str | None:
    return value if isinstance(value, str) else None


def _model_property(assoc: EObject, name: str) -> bool:
    from rosaadl.properties import property_name_matches

    return property_name_matches(assoc.property or "", name)


def _references(assoc: EObject) -> list[str]:
    values = [python_value(v.value) for v in assoc.ownedValues]
    out: list[str] = []
    for value in values:
        items = value if isinstance(value, list) else [value]
        out.extend(" ".join(item.path.split()) for item in items if isinstance(item, Reference))
    return out


def _path(element: EObject | None) -> str | None:
    """``Pkg::Classifier.member`` for a declarative element."""
    if element is None:
        return None
    parts: list[str] = []
    current = element
    while current is not None and current.eClass.name not in ("AadlModel",):
        name = getattr(current, "name", None) if current.eClass.findEStructuralFeature("name") else None
        if name:
            parts.append(name)
        current = current.eContainer()
    parts.reverse()
    if len(parts) >= 2:
        return f"{parts[0]}::{'.'.join(parts[1:])}"
    return parts[0] if parts else None


# =========================================================================== best effort


_PORT_CATEGORIES = {"eventDataPort", "dataPort", "eventPort"}


class _BestEffort:
    """Other AADL models, through their instances (see the module documentation)."""

    def __init__(self, model: EObject, report: _Report) -> None:
        self.model = model
        self.report = report
        self.index = _Index(model)
        self.project = _new("Project", name=model.name or "project", formatVersion="0.3")
        self.project.software = _new("Software", name="software")
        self.packages: dict[str, EObject] = {}
        self.components: dict[str, EObject] = {}
        self.messages: dict[str, str] = {}  # data classifier → "pkg/Type"

    def warn(self, message: str, element: EObject | None, declared: EObject | None = None) -> None:
        path = _model.instance_path(element) if element is not None else None
        self.report.warn(message, _location(declared, path) if declared is not None else Location(path=path))

    def package(self, name: str) -> EObject:
        found = self.packages.get(name)
        if found is None:
            found = self.packages[name] = _new("Package", name=name)
            self.project.software.packages.append(found)
        return found

    def run(self, roots: Sequence[str]) -> EObject:
        from rosaadl.transforms.instantiate import instantiate

        if not roots:
            self.report.warn(
                "no root system implementation to convert: the model has no top-level system "
                "implementation outside the library (name one with roots=)",
                Location(),
            )
        used_systems: set[str] = set()
        for root in roots:
            diagnostics: list[Diagnostic] = []
            try:
                instance = instantiate(self.model, root, diagnostics=diagnostics, strict=False)
            except RosaadlError as exc:
                raise TransformationError(
                    f"cannot instantiate {root} to convert it: {exc.message}", exc.location
                ) from None
            try:
                self.deployment(instance, root, used_systems)
            finally:
                if instance in self.model.instances:
                    self.model.instances.remove(instance)
        return self.project

    def deployment(self, instance: EObject, root: str, used: set[str]) -> None:
        type_name = root.rpartition("::")[2].partition(".")[0]
        base = type_name if type_name not in used else root.replace("::", "_").replace(".", "_")
        used.add(base)
        system = _new("System", name=base)
        deployment = _new("Deployment", name=base, systemName=base, system=system)
        self.project.systems.append(system)
        self.project.deployments.append(deployment)
        hosts: dict[int, EObject] = {}
        host_names: set[str] = set()
        node_names: set[str] = set()
        processes: list[EObject] = []
        stack = list(reversed(list(instance.componentInstances)))
        while stack:  # document order; what is inside processes is the nodes' business
            child = stack.pop()
            category = _enum(child.category)
            if category == "process":
                processes.append(child)
                continue
            if category == "processor":
                host = _new("Host", name=_unique(child.name, _model.instance_path(child), host_names))
                arch = own_property(child, fwd.ARCHITECTURE)
                if isinstance(arch, str):
                    host.architecture = arch
                system.hosts.append(host)
                hosts[id(child)] = host
            elif category not in ("system", "virtualProcessor", "virtualBus"):
                self.warn(f"{_words(category)} {child.name} has no ROSMOD counterpart; skipped", child)
                continue
            stack.extend(reversed(list(child.componentInstances)))
        for process in processes:
            deployment.nodes.append(self.node(process, hosts, system, node_names))
        for conn in _walk_connections(instance):
            self.check_connection(conn)

    def node(self, process: EObject, hosts: dict[int, EObject], system: EObject, names: set[str]) -> EObject:
        node = _new("Node", name=_unique(process.name, _model.instance_path(process), names))
        priority = own_property(process, fwd.PRIORITY)
        if isinstance(priority, int) and not isinstance(priority, bool):
            node.priority = priority
        binding = own_property(process, fwd.PROCESSOR_BINDING)
        targets = binding if isinstance(binding, list) else [binding] if binding is not None else []
        host = None
        for target in targets:
            host = hosts.get(id(target)) if isinstance(target, EObject) else None
            if host is None:
                current = target.eContainer() if isinstance(target, EObject) else None
                while current is not None and host is None:  # a core of a bound processor
                    host = hosts.get(id(current))
                    current = current.eContainer()
            if host is not None:
                break
        if host is not None:
            node.host = host
            node.hostRef = f"{system.name}/{host.name}"
        elif targets:
            self.warn(f"process {process.name} is bound to something that is not a processor", process)
        instance_names: set[str] = set()
        stack = list(reversed(list(process.componentInstances)))
        threads = []
        while stack:
            current = stack.pop()
            category = _enum(current.category)
            if category == "thread":
                threads.append(current)
            elif category == "threadGroup":
                stack.extend(reversed(list(current.componentInstances)))
            elif category != "data":
                self.warn(f"{category} {current.name} in a node has no ROSMOD counterpart; skipped", current)
        for thread in threads:
            comp = self.component(thread)
            if comp is None:
                continue
            relative = _model.instance_path(thread)[len(_model.instance_path(process)) + 1 :]
            inst = _new(
                "ComponentInstance",
                name=_unique(thread.name, relative, instance_names),
                component=comp,
                componentRef=f"{comp.eContainer().name}/{comp.name}",
            )
            node.componentInstances.append(inst)
        return node

    def component(self, thread: EObject) -> EObject | None:
        classifier = thread.classifier or ""
        key = classifier.lower()
        if key and key in self.components:
            return self.components[key]
        pkg_name, _, local = classifier.rpartition("::")
        type_name, _, impl_name = local.partition(".")
        if not type_name:
            pkg_name, type_name = "threads", thread.name
        name = type_name if impl_name in ("", "impl") else f"{type_name}_{impl_name}"
        package = self.package(fwd.aadl_identifier(pkg_name or "threads"))
        comp = _new(
            "Component",
            name=_unique(name, f"{name}_{len(package.components)}", {c.name for c in package.components}),
            datatype="Base",
        )
        package.components.append(comp)
        if key:
            self.components[key] = comp
        dispatch = own_property(thread, "Dispatch_Protocol")
        dispatch_name = str(dispatch).lower() if dispatch is not None else ""
        subscribers = []
        for feature in thread.featureInstances:
            port = self.port(feature, thread)
            if port is None:
                continue
            comp.ports.append(port)
            if port.eClass.name in ("Subscriber", "Server"):
                subscribers.append(port)
        priority = own_property(thread, fwd.PRIORITY)
        priority = priority if isinstance(priority, int) and not isinstance(priority, bool) else None
        deadline = _quantity_seconds(own_property(thread, fwd.DEADLINE))
        if dispatch_name == "periodic":
            comp.timers.append(
                _new(
                    "Timer",
                    name=f"{thread.name}_timer",
                    period=_quantity_seconds(own_property(thread, fwd.PERIOD)),
                    priority=priority,
                    deadline=deadline,
                )
            )
        elif dispatch_name in ("sporadic", "aperiodic") and subscribers:
            for port in subscribers:
                _set(port, priority=priority, deadline=deadline)
        else:
            what = f"dispatch protocol {dispatch}" if dispatch is not None else "no dispatch protocol"
            self.warn(
                f"thread {thread.name} has {what}: neither a timer nor a callback; its component has no "
                "callback for it",
                thread,
            )
        return comp

    def port(self, feature: EObject, thread: EObject) -> EObject | None:
        category = _enum(feature.category)
        direction = _enum(feature.direction)
        access = _enum(feature.access)
        name = feature.name
        if category in _PORT_CATEGORIES:
            if direction not in ("in", "out"):
                self.warn(f"port {name} is 'in out': ROSMOD ports publish or subscribe; skipped", feature)
                return None
            type_name = self.message_type(feature)
            cls = "Publisher" if direction == "out" else "Subscriber"
        elif category == "subprogramAccess":
            type_name = self.message_type(feature)
            cls = "Client" if access == "requires" else "Server"
        else:
            if category != "dataAccess":  # the callback queue and shared data are not ports
                self.warn(f"{category} {name} is not a ROSMOD port; skipped", feature)
            return None
        if type_name is None:
            self.warn(
                f"port {name} of {thread.name} has no data type: its ROSMOD type is left empty", feature
            )
        return _new(cls, name=name, type=type_name)

    def message_type(self, feature: EObject) -> str | None:
        given = own_property(feature, fwd.MESSAGE_TYPE)
        if isinstance(given, str):
            return given
        classifier = feature.classifier
        if not classifier:
            return None
        key = classifier.lower()
        if key in self.messages:
            return self.messages[key]
        target = self.index.classifiers.get(key)
        found = None
        seen = 0
        while target is not None and found is None and seen < 50:
            seen += 1
            found = own_property(target, fwd.MESSAGE_TYPE) or own_property(target, fwd.SERVICE_TYPE)
            unit = self.index.unit_of.get(id(target))
            if found is None and target.eClass.name == "ComponentImplementation" and unit is not None:
                target = self.index.find(target.type, target) if target.type else None
            elif found is None and target.extended and unit is not None:
                target = self.index.find(target.extended, unit)
            else:
                break
        if not isinstance(found, str):
            pkg_name, _, local = classifier.rpartition("::")
            package = self.package(fwd.aadl_identifier(pkg_name or "messages"))
            msg_name = fwd.aadl_identifier(local.replace(".", "_"))
            if _enum(feature.category) == "subprogramAccess":
                if not any(s.name == msg_name for s in package.services):
                    package.services.append(_new("Service", name=msg_name, definition="---\n"))
            elif not any(m.name == msg_name for m in package.messages):
                package.messages.append(_new("Message", name=msg_name, definition=""))
                self.report.warn(
                    f"data type {classifier} has no ROS_Properties::Message_Type: made an empty message "
                    f"{package.name}/{msg_name}",
                    Location(path=classifier),
                )
            found = f"{package.name}/{msg_name}"
        self.messages[key] = found
        return found

    def check_connection(self, conn: EObject) -> None:
        if _enum(conn.kind) != "portConnection":
            return
        source, destination = conn.source, conn.destination
        if not isinstance(source, EObject) or not isinstance(destination, EObject):
            return
        if source.eClass.name != "FeatureInstance" or destination.eClass.name != "FeatureInstance":
            return
        owner_s, owner_d = source.eContainer(), destination.eContainer()
        if (
            _enum(getattr(owner_s, "category", "")) != "thread"
            or _enum(getattr(owner_d, "category", "")) != "thread"
        ):
            self.warn(
                f"connection {conn.name} does not join two threads (ROSMOD topics join publishers and "
                "subscribers of nodes); not kept",
                conn,
            )
            return
        if self.message_type(source) != self.message_type(destination):
            self.warn(
                f"connection {conn.name} joins ports of different types; ROSMOD matches topics by message "
                "type, so it is not kept",
                conn,
            )


def _walk_connections(instance: EObject) -> Iterable[EObject]:
    stack = [instance]
    while stack:
        current = stack.pop()
        yield from current.connectionInstances
        stack.extend(current.componentInstances)


def _quantity_seconds(value: Any) -> Decimal | None:
    if isinstance(value, Quantity):
        return fwd.time_to_seconds(value.value, value.unit)
    return None


def _unique(name: str, fallback: str, taken: set[str]) -> str:
    chosen = name if name not in taken else fwd.aadl_identifier(fallback.replace(".", "_"))
    base, count = chosen, 0
    while chosen in taken:
        count += 1
        chosen = f"{base}_{count}"
    taken.add(chosen)
    return chosen


# =========================================================================== entry point


def aadl_to_rosmod(
    model: EObject,
    *,
    trace: EObject | str | os.PathLike[str] | None = None,
    roots: Sequence[str] | None = None,
    warnings: list[Diagnostic] | None = None,
) -> EObject:
    """A ``rosmod.Project`` from an ``AadlModel`` (see the module documentation).

    ``trace`` is the trace of the forward conversion (a ``trace.Trace`` or the file it was saved
    to): names that the AADL model no longer carries come from it. ``roots`` are the root
    system implementations of a best-effort conversion. Warnings — one per element that could
    not be mapped, located by file and line or instance path — are logged and appended to
    ``warnings``.
    """
    if not isinstance(model, EObject) or model.eClass.name != "AadlModel":
        raise TransformationError("expected an AADL model (AadlModel) to convert to ROSMOD")
    if trace is not None and not isinstance(trace, EObject):
        trace = tracing.load_trace(trace)
    report = _Report(warnings)
    if is_rosmod_convention(model):
        return _Convention(model, trace, report).run()
    chosen = list(roots) if roots is not None else top_level_systems(model)
    return _BestEffort(model, report).run(chosen)


def convert_aadl_files(
    paths: Sequence[str | os.PathLike[str]],
    out_dir: str | os.PathLike[str],
    *,
    trace_file: str | os.PathLike[str] | None = None,
    roots: Sequence[str] | None = None,
    warnings: list[Diagnostic] | None = None,
) -> list[Path]:
    """``rosaadl convert MODEL.aadl... --to rosmod -o OUT_DIR [--trace FILE] [--root ...]``.

    Reads the AADL files and folders with the library, converts them (with the forward
    conversion's trace when ``trace_file`` is given; a best-effort conversion instantiates
    ``roots``, by default the top-level system implementations of the given files) and writes
    a ROSMOD v0.3 project into ``out_dir``; the paths written.
    """
    from rosaadl.exporters.rosmod_text import write_project
    from rosaadl.importers.aadl_text import read_files

    aadl = read_files(paths, warnings=warnings)
    if roots is None and not is_rosmod_convention(aadl):
        given = [Path(p).resolve() for p in paths]

        def is_given(unit: EObject) -> bool:
            source = getattr(unit, "sourceFile", None)
            if not source:
                return False
            resolved = Path(source).resolve()
            return any(resolved == g or g in resolved.parents for g in given)

        roots = top_level_systems(aadl, [u for u in aadl.units if is_given(u)])
    project = aadl_to_rosmod(aadl, trace=trace_file, roots=roots, warnings=warnings)
    return write_project(project, out_dir, warnings=warnings)

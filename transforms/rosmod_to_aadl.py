"""ROSMOD projects (``rosmod.ecore``) → declarative AADL (``aadl.ecore``), with a trace.

:func:`rosmod_to_aadl` applies the rules of :data:`TRANSFORMATION` (the rule engine of
:mod:`rosaadl.transforms.engine`) to a ``rosmod.Project`` and returns an ``AadlModel`` holding
the generated packages; they use the library's ``ros`` package and property sets (read them
with ``read_files(..., include_library=True)``). The mapping (``docs/rosmod-aadl-mapping.md``):

* **software** — one AADL package per ROSMOD package (``Unit_Kind => Software``): a message is
  a ``data`` type with ``ROS_Properties::Message_Type``, its ``.msg`` text
  (``ROSMOD_Properties::Definition``) and ``Data_Size`` when every message of the type has the
  same size; a service is a ``subprogram`` with an ``in parameter`` request and an ``out
  parameter`` response, both ``data`` types; a component is a ``thread group`` type (its ports as
  features: publisher → ``out event data port``, subscriber → ``in event data port``, client →
  ``requires subprogram access``, server → ``provides subprogram access``) and implementation
  holding one ``thread`` per timer (periodic, ``Period``/``Deadline``/``Priority``) and per
  subscriber or server callback (sporadic, ``Deadline``/``Priority``); the callback threads of a
  component share its callback queue (a ``data`` subcomponent of ``ros::callback_queue``, whose
  ``Concurrency_Control_Protocol`` makes them mutually exclusive: one executor per component
  instance). Message types of packages outside the project (``std_msgs/String``) become data
  types of an ``Interfaces`` package named after their ROS package;
* **hardware** — one package per hardware model (``Unit_Kind => Hardware``) with a ``system``
  implementation holding one ``processor`` per host (IP address, user, ssh key, paths,
  ``Hardware_Properties::Architecture``, OS), one ``bus`` per network and one ``bus access``
  connection per link;
* **deployment** — one package per deployment (``Unit_Kind => Deployment``) with one ``process``
  per node (extending ``ros::node``, ``Priority``, the component instances as thread group
  subcomponents) and a ``system`` implementation (the root to instantiate) holding the
  hardware, a ``ros::ROSbus`` virtual bus and the processes, bound with
  ``Actual_Processor_Binding``; topics (a publisher and a subscriber of the same message type,
  and for WebGME ports the same advertised topic) are port connections, bound with
  ``Actual_Connection_Binding`` to the network both hosts are linked to, else to the ROS bus;
  a client is connected to the first server of its service type;
* ROSMOD facts without an AADL counterpart go into ``ROSMOD_Properties`` (IP addresses, users,
  logging, port instances, settings, the project's own data in a ``Project`` package), so that
  :func:`rosaadl.transforms.aadl_to_rosmod.aadl_to_rosmod` gives the project back.

Names: a ROSMOD name that is not an AADL identifier, is a reserved word or repeats another
name of the same AADL namespace (AADL names are case-insensitive) gets a unique identifier
(:class:`NameScope`) and keeps its ROSMOD name in ``ROSMOD_Properties::Name``. Times in seconds
become integer AADL times in ``ms`` or ``us`` (``ns``, ``ps`` when needed), exactly.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from decimal import ROUND_HALF_EVEN, Decimal, InvalidOperation
from functools import lru_cache
from importlib import resources
from typing import Any

from pyecore.ecore import EObject

from rosaadl.bulk import FastBuilder, gc_paused
from rosaadl.errors import RosaadlError, TransformationError
from rosaadl.importers import ros_msg
from rosaadl.transforms.engine import Context, Transformation, source_location

__all__ = [
    "ConversionResult",
    "rosmod_to_aadl",
    "NameScope",
    "aadl_identifier",
    "given",
    "library_unit_names",
    "seconds_to_time",
    "time_to_seconds",
    "plain_seconds",
    "RESERVED_WORDS",
    "TRANSFORMATION",
    "PROPERTY_SET",
]

log = logging.getLogger(__name__)

#: The property set of the ROSMOD-only facts (``library/properties/ROSMOD_Properties.aadl``).
PROPERTY_SET = "ROSMOD_Properties"

_P = PROPERTY_SET + "::"
NAME = _P + "Name"
SETTINGS = _P + "Settings"
UNIT_KIND = _P + "Unit_Kind"
POSITION = _P + "Position"
FORMAT_VERSION = _P + "Format_Version"
PROJECT_PATH = _P + "Project_Path"
SOFTWARE_NAME = _P + "Software_Name"
SOURCE_FILE = _P + "Source_File"
DEFINITION = _P + "Definition"
SERVICE_TYPE = _P + "Service_Type"
DATATYPE = _P + "Datatype"
SCHEDULING_SCHEME = _P + "Scheduling_Scheme"
OPERATION = _P + "Operation"
PERIOD_SECONDS = _P + "Period_Seconds"
DEADLINE_SECONDS = _P + "Deadline_Seconds"
LATCHING = _P + "Latching"
SUBNET = _P + "Subnet"
NETMASK = _P + "Netmask"
IP_ADDRESS = _P + "IP_Address"
USERNAME = _P + "Username"
SSH_KEY = _P + "SSH_Key"
DEPLOYMENT_PATH = _P + "Deployment_Path"
INSTALL_PATH = _P + "Install_Path"
OS = _P + "OS"
SYSTEM_NAME = _P + "System_Name"
HOST_REF = _P + "Host_Ref"
ARGUMENTS = _P + "Arguments"
COMPONENT_REF = _P + "Component_Ref"
LOGGING = _P + "Logging"
PORT_INSTANCES = _P + "Port_Instances"
MESSAGE_TYPE = "ROS_Properties::Message_Type"
TOPIC_NAME = "ROS_Properties::Topic_Name"
ARCHITECTURE = "Hardware_Properties::Architecture"
PERIOD = "Period"
DEADLINE = "Deadline"
PRIORITY = "Priority"
DATA_SIZE = "Data_Size"
PROCESSOR_BINDING = "Actual_Processor_Binding"
CONNECTION_BINDING = "Actual_Connection_Binding"

#: What the name of a generated package adds to the name of its ROSMOD element, by unit kind.
UNIT_SUFFIXES = {"Project": "_project", "Hardware": "_hardware", "Deployment": "_deployment"}

#: Names of the generated callback thread types (one of each per software package that needs it)
#: and the library thread types they extend.
CALLBACK_THREADS = {
    "timer": ("timer_callback", "ros::timer"),
    "subscriber": ("subscriber_callback", "ros::callback"),
    "server": ("server_callback", "ros::service"),
}
#: Feature names of the library's thread types, and of the callback queue access.
SUBSCRIBER_PORT = "cb_msg"
SERVER_ACCESS = "srv"
QUEUE_ACCESS = "callback_queue"
QUEUE_CLASSIFIER = "ros::callback_queue"
ROS_BUS = "ros::ROSbus.impl"
NODE_TYPE = "ros::node"

#: AADL reserved words (SAE AS5506C 15.5); never used as generated names.
_RESERVED_TEXT = """
    aadlboolean aadlinteger aadlreal aadlstring abstract access all and annex applies binding bus
    calls classifier compute connections constant data delta device end enumeration event extends
    false feature features flow flows group implementation in inherit initial inverse is list memory
    mode modes none not of or out package parameter path port private process processor properties
    property prototype prototypes provides public range record reference refined renames requires
    self set sink source subcomponents subprogram system thread to true type units virtual with
"""
RESERVED_WORDS = frozenset(_RESERVED_TEXT.split())

_NOT_ALNUM = re.compile(r"[^A-Za-z0-9]+")


# =========================================================================== names


def aadl_identifier(name: str | None) -> str:
    """An AADL identifier for a ROSMOD name: other characters become single ``_``, a name that
    does not start with a letter gets an ``x`` in front (``3_Sat`` → ``x3_Sat``)."""
    text = _NOT_ALNUM.sub("_", name or "").strip("_")
    if not text:
        return "x"
    if not text[0].isalpha():
        text = "x" + text
    return text


class NameScope:
    """The names of one AADL namespace: :meth:`take` gives each wanted name a unique identifier
    (compared case-insensitively, as AADL does), never a reserved word."""

    def __init__(self, reserved: Iterable[str] = ()) -> None:
        self._taken: set[str] = {w.lower() for w in reserved} | set(RESERVED_WORDS)
        self._counters: dict[str, int] = {}  # base → last suffix tried (no quadratic probing)

    def take(self, wanted: str | None) -> str:
        base = aadl_identifier(wanted)
        name = base
        key = base.lower()
        if key in self._taken:
            count = self._counters.get(key, 0)
            while name.lower() in self._taken:
                count += 1
                name = f"{base}_{count}"
            self._counters[key] = count
        self._taken.add(name.lower())
        return name

    def __contains__(self, name: str) -> bool:
        return name.lower() in self._taken


@lru_cache(maxsize=1)
def library_unit_names() -> frozenset[str]:
    """Lower-case names of the library's units (one per ``.aadl`` file, named like the file),
    which generated packages must not take: a user unit named like a library unit replaces it."""
    names: set[str] = set()
    stack = [resources.files("rosaadl.library")]
    while stack:
        folder = stack.pop()
        for entry in folder.iterdir():
            if entry.is_dir():
                if not entry.name.startswith((".", "__")):
                    stack.append(entry)
            elif entry.name.lower().endswith(".aadl"):
                names.add(entry.name[: -len(".aadl")].lower())
    return frozenset(names)


def given(obj: EObject, feature: str) -> Any:
    """The value of a feature that is set, else None (pyecore answers 0, False or ``Decimal(0)``
    for an unset number or boolean: a ROSMOD priority or deadline that is not given)."""
    return obj.eGet(feature) if obj.eIsSet(feature) else None


# =========================================================================== times


_TIME_SCALES = (
    ("ms", Decimal(10) ** 3),
    ("us", Decimal(10) ** 6),
    ("ns", Decimal(10) ** 9),
    ("ps", Decimal(10) ** 12),
)
_UNIT_SECONDS = {
    "ps": Decimal("1e-12"),
    "ns": Decimal("1e-9"),
    "us": Decimal("1e-6"),
    "ms": Decimal("0.001"),
    "sec": Decimal(1),
    "min": Decimal(60),
    "hr": Decimal(3600),
}


def seconds_to_time(seconds: Decimal | int | str) -> tuple[int, str, bool]:
    """``(value, unit, exact)``: the seconds as an integer AADL time in ``ms`` when that is
    exact, else ``us``, ``ns``, ``ps``; ``exact`` is False when even ``ps`` had to be rounded."""
    value = Decimal(seconds)
    scaled = value
    for unit, scale in _TIME_SCALES:
        scaled = value * scale
        if scaled == scaled.to_integral_value():
            return int(scaled), unit, True
    return int(scaled.to_integral_value(ROUND_HALF_EVEN)), "ps", False


def plain_seconds(value: Decimal | int | str) -> Decimal:
    """The plain decimal of a number of seconds: no exponent, no trailing zeros (``0.500`` →
    ``0.5``, ``10`` stays ``10``); what :func:`time_to_seconds` gives."""
    return Decimal(format(Decimal(value).normalize(), "f"))


def time_to_seconds(value: int | float, unit: str | None) -> Decimal | None:
    """Seconds of an AADL time, exact and plain (:func:`plain_seconds`); None for a unit that is
    not a time unit."""
    factor = _UNIT_SECONDS.get((unit or "").strip().lower() if unit else "")
    if factor is None:
        return None
    try:
        number = Decimal(value) if isinstance(value, int) else Decimal(repr(float(value)))
    except (InvalidOperation, ValueError):
        return None
    return plain_seconds(number * factor)


# =========================================================================== building AADL objects


class _Factory:
    """AADL model objects through :class:`FastBuilder` (the model API's ``new`` is ~7x slower)."""

    def __init__(self) -> None:
        self.fb = FastBuilder()
        fb = self.fb
        self._categories = {
            c: fb.literal("ComponentCategory", c)
            for c in (
                "bus",
                "data",
                "process",
                "processor",
                "subprogram",
                "system",
                "thread",
                "thread group",
                "virtual bus",
            )
        }
        self._features = {
            c: fb.literal("FeatureCategory", c)
            for c in ("event data port", "subprogram access", "bus access", "data access", "parameter")
        }
        self._direction = {d: fb.literal("DirectionType", d) for d in ("in", "out")}
        self._access = {a: fb.literal("AccessType", a) for a in ("provides", "requires")}
        self._connections = {
            "port": fb.literal("ConnectionKind", "port"),
            "access": fb.literal("ConnectionKind", "access"),
        }

    # -- units and classifiers
    def package(self, name: str) -> EObject:
        return self.fb.make("AadlPackage", name=name)

    def ctype(self, category: str, name: str, extended: str | None = None) -> EObject:
        return self.fb.make(
            "ComponentType", name=name, category=self._categories[category], extended=extended
        )

    def cimpl(self, category: str, type_name: str, extended: str | None = None) -> EObject:
        return self.fb.make(
            "ComponentImplementation",
            name=f"{type_name}.impl",
            type=type_name,
            category=self._categories[category],
            extended=extended,
        )

    def feature(
        self,
        name: str,
        category: str,
        *,
        direction: str | None = None,
        access: str | None = None,
        classifier: str | None = None,
    ) -> EObject:
        return self.fb.make(
            "Feature",
            name=name,
            category=self._features[category],
            direction=self._direction[direction] if direction else None,
            access=self._access[access] if access else None,
            classifier=classifier,
        )

    def sub(self, name: str, category: str, classifier: str | None) -> EObject:
        return self.fb.make(
            "Subcomponent", name=name, category=self._categories[category], classifier=classifier
        )

    def conn(
        self, name: str, kind: str, source: str, destination: str, category: str | None = None
    ) -> EObject:
        return self.fb.make(
            "Connection",
            name=name,
            kind=self._connections[kind],
            source=source,
            destination=destination,
            accessCategory=self._categories[category] if category else None,
        )

    def add(self, owner: EObject, feature: str, *children: Any) -> None:
        if children:
            self.fb.add(owner, feature, *children)

    # -- values
    def string(self, value: str) -> EObject:
        return self.fb.make("StringValue", value=value)

    def integer(self, value: int, unit: str | None = None) -> EObject:
        return self.fb.make("IntegerValue", value=int(value), unit=unit)

    def named(self, name: str) -> EObject:
        return self.fb.make("NamedValue", name=name)

    def boolean(self, value: bool) -> EObject:
        return self.fb.make("BooleanValue", value=bool(value))

    def reference(self, path: str) -> EObject:
        return self.fb.make("ReferenceValue", path=path)

    def listing(self, items: Iterable[EObject]) -> EObject:
        value = self.fb.make("ListValue")
        self.add(value, "ownedItems", *items)
        return value

    def record(self, fields: Iterable[tuple[str, EObject]]) -> EObject:
        value = self.fb.make("RecordValue")
        self.add(value, "ownedFields", *(self.fb.make("FieldValue", name=n, value=v) for n, v in fields))
        return value

    def pa(self, holder: EObject, prop: str, value: EObject, applies_to: str | None = None) -> EObject:
        assoc = self.fb.make("PropertyAssociation", property=prop)
        self.fb.add(assoc, "ownedValues", self.fb.make("ModalPropertyValue", value=value))
        if applies_to:
            self.fb.add(assoc, "appliesTo", applies_to)
        self.fb.add(holder, "ownedPropertyAssociations", assoc)
        return assoc

    def text(self, holder: EObject, prop: str, value: str | None) -> None:
        if value is not None:
            self.pa(holder, prop, self.string(value))

    def settings(self, holder: EObject, props: Iterable[EObject], prop: str = SETTINGS) -> None:
        items = [
            self.record((("Key", self.string(p.key or "")), ("Value", self.string(p.value or ""))))
            for p in props
        ]
        if items:
            self.pa(holder, prop, self.listing(items))


# =========================================================================== the naming plan


def _rosmod_type(type_name: str | None) -> tuple[str, str] | None:
    if not type_name or "/" not in type_name:
        return None
    pkg, _, name = type_name.rpartition("/")
    return (pkg, name) if pkg and name else None


@dataclass
class _Interfaces:
    """Data types and subprograms for ROS types of packages outside the project."""

    unit: str
    scope: NameScope
    messages: dict[str, str] = field(default_factory=dict)  # "pkg/T" → classifier name
    services: dict[str, str] = field(default_factory=dict)


class _Plan:
    """Every AADL name of the conversion, chosen before any rule runs (deterministic, and
    independent of the order in which rules run)."""

    def __init__(self, project: EObject) -> None:
        self.names: dict[int, str] = {}  # rosmod element → its AADL name
        self.units: dict[int, str] = {}  # Project/Package/System/Deployment → unit name
        self.positions: dict[int, int] = {}
        self.extra: dict[tuple[int, str], str] = {}  # (element, role) → AADL name
        self.scopes: dict[tuple[int, str], NameScope] = {}
        self.messages: dict[str, tuple[str, str, EObject]] = {}  # "pkg/T" → (unit, classifier, Message)
        self.services: dict[str, tuple[str, str, EObject]] = {}
        self.interfaces: dict[str, _Interfaces] = {}
        self.callback_types: dict[tuple[int, str], str] = {}  # (package, kind) → thread type name
        self.systems: dict[int, EObject] = {}  # host → its System
        units = NameScope(library_unit_names())
        software = project.software
        packages = list(software.packages) if software is not None else []
        position = 1
        for package in packages:
            self.units[id(package)] = units.take(package.name)
            self.positions[id(package)] = position
            position += 1
        project_packages = {p.name for p in packages}
        for package in packages:
            self._software(package)
        # interface packages for the types of packages outside the project (sorted: stable)
        external: dict[str, list[tuple[str, str]]] = {}
        for package in packages:
            for comp in package.components:
                for port in comp.ports:
                    parts = _rosmod_type(port.type)
                    if parts is None or parts[0] in project_packages:
                        continue
                    kind = "message" if port.eClass.name in ("Publisher", "Subscriber") else "service"
                    external.setdefault(parts[0], []).append((kind, port.type))
        for ros_pkg in sorted(external):
            iface = _Interfaces(unit=units.take(ros_pkg), scope=NameScope())
            self.interfaces[ros_pkg] = iface
            for kind, type_name in external[ros_pkg]:
                table = iface.messages if kind == "message" else iface.services
                if type_name not in table:
                    table[type_name] = iface.scope.take(type_name.rpartition("/")[2])
        for system in project.systems:
            self.units[id(system)] = units.take(f"{system.name}{UNIT_SUFFIXES['Hardware']}")
            self.positions[id(system)] = position
            position += 1
            self._system(system)
        for deployment in project.deployments:
            self.units[id(deployment)] = units.take(f"{deployment.name}{UNIT_SUFFIXES['Deployment']}")
            self.positions[id(deployment)] = position
            position += 1
            self._deployment(deployment)
        self.units[id(project)] = units.take(f"{project.name}{UNIT_SUFFIXES['Project']}")
        self.positions[id(project)] = 0

    def scope(self, obj: EObject, role: str = "") -> NameScope:
        key = (id(obj), role)
        found = self.scopes.get(key)
        if found is None:
            found = self.scopes[key] = NameScope()
        return found

    def _software(self, package: EObject) -> None:
        unit = self.units[id(package)]
        classifiers = self.scope(package)
        for msg in package.messages:
            name = self.names[id(msg)] = classifiers.take(msg.name)
            self.messages.setdefault(f"{package.name}/{msg.name}", (unit, name, msg))
        for srv in package.services:
            name = self.names[id(srv)] = classifiers.take(srv.name)
            self.extra[(id(srv), "request")] = classifiers.take(f"{name}_Request")
            self.extra[(id(srv), "response")] = classifiers.take(f"{name}_Response")
            self.services.setdefault(f"{package.name}/{srv.name}", (unit, name, srv))
        kinds: set[str] = set()
        for comp in package.components:
            self.names[id(comp)] = classifiers.take(comp.name)
            members = self.scope(comp)
            for port in comp.ports:
                self.names[id(port)] = members.take(port.name)
            for timer in comp.timers:
                self.names[id(timer)] = members.take(timer.name)
                kinds.add("timer")
            callbacks = [p for p in comp.ports if p.eClass.name in ("Subscriber", "Server")]
            if comp.timers or callbacks:
                self.extra[(id(comp), "queue")] = members.take("callback_queue")
            for port in callbacks:
                self.extra[(id(port), "thread")] = members.take(f"{port.name}_callback")
                kinds.add(port.eClass.name.lower())
            for element in (*comp.timers, *callbacks):
                thread = self.names[id(element)] if element.eClass.name == "Timer" else None
                thread = thread or self.extra[(id(element), "thread")]
                self.extra[(id(element), "queue_conn")] = members.take(f"{thread}_queue")
                if element.eClass.name != "Timer":
                    self.extra[(id(element), "callback_conn")] = members.take(f"{thread}_call")
        for kind in ("timer", "subscriber", "server"):
            if kind in kinds:
                self.callback_types[(id(package), kind)] = classifiers.take(CALLBACK_THREADS[kind][0])

    def _system(self, system: EObject) -> None:
        classifiers = self.scope(system)
        members = self.scope(system, "impl")
        self.extra[(id(system), "type")] = classifiers.take(system.name)
        for host in system.hosts:
            self.systems[id(host)] = system
            self.names[id(host)] = members.take(host.name)
            self.extra[(id(host), "type")] = classifiers.take(host.name)
            features = self.scope(host)
            for interface in host.interfaces:
                self.names[id(interface)] = features.take(interface.name)
        for network in system.networks:
            self.names[id(network)] = members.take(network.name)
            self.extra[(id(network), "type")] = classifiers.take(network.name)
        for link in system.links:
            self.names[id(link)] = members.take(link.name)

    def _deployment(self, deployment: EObject) -> None:
        classifiers = self.scope(deployment)
        members = self.scope(deployment, "impl")
        self.extra[(id(deployment), "type")] = classifiers.take(deployment.name)
        for node in deployment.nodes:
            self.names[id(node)] = members.take(node.name)
            self.extra[(id(node), "type")] = classifiers.take(node.name)
            process = self.scope(node)
            for inst in node.componentInstances:
                self.names[id(inst)] = process.take(inst.name)
        self.extra[(id(deployment), "bus")] = members.take("ROSbus")
        systems: list[EObject] = []
        if deployment.system is not None:
            systems.append(deployment.system)
        for node in deployment.nodes:
            system = self.systems.get(id(node.host)) if node.host is not None else None
            if system is not None and system not in systems:
                systems.append(system)
        for system in systems:
            self.extra[(id(deployment), f"system:{id(system)}")] = members.take(system.name)


# =========================================================================== the rules


@dataclass
class _State:
    """What the rules of one run share (kept in ``ctx.options['state']``: no global state)."""

    project: EObject
    plan: _Plan
    factory: _Factory
    units: dict[int, EObject] = field(default_factory=dict)  # position → unit
    sizes: dict[str, list[ros_msg.FieldSpec]] = field(default_factory=dict)


TRANSFORMATION = Transformation("rosmod2aadl")
_t = TRANSFORMATION


def _state(ctx: Context) -> _State:
    return ctx.options["state"]


def _name_if_changed(f: _Factory, holder: EObject, aadl_name: str, rosmod_name: str | None) -> None:
    if rosmod_name is not None and aadl_name != rosmod_name:
        f.pa(holder, NAME, f.string(rosmod_name))


def _unit_header(st: _State, src: EObject, kind: str) -> EObject:
    f = st.factory
    name = st.plan.units[id(src)]
    pkg = f.package(name)
    f.pa(pkg, UNIT_KIND, f.named(kind))
    f.pa(pkg, POSITION, f.integer(st.plan.positions[id(src)]))
    suffix = UNIT_SUFFIXES.get(kind, "")
    if src.name is not None and name != f"{src.name}{suffix}":
        f.pa(pkg, NAME, f.string(src.name))
    st.units[st.plan.positions[id(src)]] = pkg
    return pkg


def _time(
    ctx: Context, f: _Factory, holder: EObject, prop: str, text_prop: str, seconds: Any, src: EObject
) -> None:
    """``prop`` (an AADL time) for ROSMOD seconds, and ``text_prop`` when the seconds are not
    written plainly (``0.500``), so that the conversion back gives the same text."""
    if seconds is None:
        return
    value, unit, exact = seconds_to_time(seconds)
    if not exact:
        ctx.warn(f"{prop} = {seconds} s is not a whole number of picoseconds; rounded to {value} ps", src)
    f.pa(holder, prop, f.integer(value, unit))
    if exact and str(seconds) != str(plain_seconds(seconds)):
        f.pa(holder, text_prop, f.string(str(seconds)))


# -------------------------------------------------------------------- project


@_t.rule("rosmod.Project", name="project")
def _project(ctx: Context, src: EObject) -> EObject:
    st = _state(ctx)
    f = st.factory
    pkg = _unit_header(st, src, "Project")
    f.text(pkg, FORMAT_VERSION, src.formatVersion)
    f.text(pkg, PROJECT_PATH, src.path)
    if src.software is not None:
        f.text(pkg, SOFTWARE_NAME, src.software.name)
        f.text(pkg, SOURCE_FILE, src.software.sourceFile)
    f.settings(pkg, src.properties)
    return pkg


# -------------------------------------------------------------------- software


@_t.rule("rosmod.Package", name="package")
def _package(ctx: Context, src: EObject) -> EObject:
    st = _state(ctx)
    pkg = _unit_header(st, src, "Software")
    st.factory.settings(pkg, src.properties)
    return pkg


@_package.bind
def _package_bind(ctx: Context, src: EObject, pkg: EObject) -> None:
    st = _state(ctx)
    f = st.factory
    classifiers: list[EObject] = []
    for msg in src.messages:
        classifiers.extend(ctx.resolve(msg))
    for srv in src.services:
        classifiers.extend(ctx.resolve(srv))
    for kind in ("timer", "subscriber", "server"):
        name = st.plan.callback_types.get((id(src), kind))
        if name is None:
            continue
        base = CALLBACK_THREADS[kind][1]
        thread = f.ctype("thread", name, extended=base)
        queue = f.feature(QUEUE_ACCESS, "data access", access="requires", classifier=QUEUE_CLASSIFIER)
        f.add(thread, "features", queue)
        classifiers.append(thread)
        classifiers.append(f.cimpl("thread", name, extended=f"{base}.impl"))
    for comp in src.components:
        classifiers.extend(t for t in ctx.resolve(comp) if t.eClass.name != "Subcomponent")
    f.add(pkg, "classifiers", *classifiers)


def _sizes(st: _State) -> dict[str, list[ros_msg.FieldSpec]]:
    if not st.sizes and st.project.software is not None:
        for package in st.project.software.packages:
            for msg in package.messages:
                st.sizes.setdefault(
                    f"{package.name}/{msg.name}", [ros_msg.field_from_model(x) for x in msg.fields]
                )
    return st.sizes


def _data_size(st: _State, fields: list[ros_msg.FieldSpec], own: str | None) -> int | None:
    spec = ros_msg.MessageSpec(
        name=own.rpartition("/")[2] if own else None,
        package=own.rpartition("/")[0] if own else None,
        fields=tuple(fields),
    )
    return ros_msg.data_size(spec, _sizes(st).get)


@_t.rule("rosmod.Message", name="message")
def _message(ctx: Context, src: EObject) -> EObject:
    st = _state(ctx)
    f = st.factory
    package = src.eContainer()
    name = st.plan.names[id(src)]
    data = f.ctype("data", name)
    _name_if_changed(f, data, name, src.name)
    full = f"{package.name}/{src.name}"
    size = _data_size(st, [ros_msg.field_from_model(x) for x in src.fields], full)
    if size is not None:
        f.pa(data, DATA_SIZE, f.integer(size, "Bytes"))
    f.pa(data, MESSAGE_TYPE, f.string(full))
    f.text(data, DEFINITION, src.definition)
    return data


@_t.rule("rosmod.Service", name="service")
def _service(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    package = src.eContainer()
    name = st.plan.names[id(src)]
    pkg_unit = st.plan.units[id(package)]
    subprogram = f.ctype("subprogram", name)
    out: list[EObject] = []
    for role, direction, fields in (
        ("request", "in", src.requestFields),
        ("response", "out", src.responseFields),
    ):
        data_name = st.plan.extra[(id(src), role)]
        data = f.ctype("data", data_name)
        size = _data_size(st, [ros_msg.field_from_model(x) for x in fields], None)
        if size is not None:
            f.pa(data, DATA_SIZE, f.integer(size, "Bytes"))
        out.append(data)
        f.add(
            subprogram,
            "features",
            f.feature(role, "parameter", direction=direction, classifier=f"{pkg_unit}::{data_name}"),
        )
    _name_if_changed(f, subprogram, name, src.name)
    f.pa(subprogram, SERVICE_TYPE, f.string(f"{package.name}/{src.name}"))
    f.text(subprogram, DEFINITION, src.definition)
    return (*out, subprogram)


@_t.rule("rosmod.Component", name="component")
def _component(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    name = st.plan.names[id(src)]
    group = f.ctype("thread group", name)
    _name_if_changed(f, group, name, src.name)
    f.text(group, DATATYPE, src.datatype)
    if src.eIsSet("schedulingScheme"):
        f.pa(group, SCHEDULING_SCHEME, f.named(src.schedulingScheme.name))
    f.settings(group, src.properties)
    impl = f.cimpl("thread group", name)
    queue_name = st.plan.extra.get((id(src), "queue"))
    if queue_name is None:
        return group, impl
    queue = f.sub(queue_name, "data", QUEUE_CLASSIFIER)
    return group, impl, queue


@_component.bind
def _component_bind(ctx: Context, src: EObject, group: EObject, impl: EObject, *queue: EObject) -> None:
    st = _state(ctx)
    f = st.factory
    features: list[EObject] = []
    threads: list[EObject] = list(queue)
    connections: list[EObject] = []
    for port in src.ports:
        for target in ctx.resolve(port):
            kind = target.eClass.name
            if kind == "Feature":
                features.append(target)
    for element in (*src.timers, *(p for p in src.ports if p.eClass.name in ("Subscriber", "Server"))):
        for target in ctx.resolve(element):
            kind = target.eClass.name
            if kind == "Subcomponent":
                threads.append(target)
            elif kind == "Connection":
                connections.append(target)
    f.add(group, "features", *features)
    f.add(impl, "subcomponents", *threads)
    f.add(impl, "connections", *connections)


def _callback_thread(ctx: Context, src: EObject, kind: str, thread_name: str) -> tuple[EObject, EObject]:
    """The thread subcomponent of a timer or callback, and its connection to the callback queue."""
    st = _state(ctx)
    f = st.factory
    comp = src.eContainer()
    package = comp.eContainer()
    unit = st.plan.units[id(package)]
    type_name = st.plan.callback_types[(id(package), kind)]
    thread = f.sub(thread_name, "thread", f"{unit}::{type_name}.impl")
    if kind == "timer":
        _time(ctx, f, thread, PERIOD, PERIOD_SECONDS, given(src, "period"), src)
    _time(ctx, f, thread, DEADLINE, DEADLINE_SECONDS, given(src, "deadline"), src)
    if given(src, "priority") is not None:
        f.pa(thread, PRIORITY, f.integer(src.priority))
    f.text(thread, OPERATION, src.operation)
    queue = st.plan.extra[(id(comp), "queue")]
    link = f.conn(
        st.plan.extra[(id(src), "queue_conn")], "access", queue, f"{thread_name}.{QUEUE_ACCESS}", "data"
    )
    return thread, link


@_t.rule("rosmod.Timer", name="timer")
def _timer(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    name = st.plan.names[id(src)]
    thread, queue = _callback_thread(ctx, src, "timer", name)
    _name_if_changed(st.factory, thread, name, src.name)
    return thread, queue


def _port_classifier(ctx: Context, src: EObject, kind: str) -> str | None:
    """The AADL classifier of a port's ROS type; a located error for an unknown project type."""
    st = _state(ctx)
    parts = _rosmod_type(src.type)
    if parts is None:
        if src.type:
            ctx.warn(f"{src.eClass.name.lower()} {src.name!r}: type {src.type!r} is not 'package/Type'", src)
        return None
    pkg_name, type_name = parts
    own, other, what, other_what = (
        (st.plan.messages, st.plan.services, "message", "service")
        if kind == "message"
        else (st.plan.services, st.plan.messages, "service", "message")
    )
    found = own.get(src.type)
    if found is not None:
        return f"{found[0]}::{found[1]}"
    iface = st.plan.interfaces.get(pkg_name)
    if iface is not None:
        table = iface.messages if kind == "message" else iface.services
        if src.type in table:
            return f"{iface.unit}::{table[src.type]}"
    if src.type in other:
        raise TransformationError(
            f"{src.eClass.name.lower()} {src.name!r} needs a {what} type, but {src.type!r} is a {other_what}",
            source_location(src),
        )
    raise TransformationError(
        f"unknown {what} type {src.type!r} of {src.eClass.name.lower()} {src.name!r}: package "
        f"{pkg_name!r} defines no {what} {type_name!r}",
        source_location(src),
    )


def _port_feature(ctx: Context, src: EObject) -> EObject:
    st = _state(ctx)
    f = st.factory
    kind = src.eClass.name
    message = kind in ("Publisher", "Subscriber")
    classifier = _port_classifier(ctx, src, "message" if message else "service")
    name = st.plan.names[id(src)]
    if message:
        direction = "out" if kind == "Publisher" else "in"
        feature = f.feature(name, "event data port", direction=direction, classifier=classifier)
    else:
        access = "requires" if kind == "Client" else "provides"
        feature = f.feature(name, "subprogram access", access=access, classifier=classifier)
    _name_if_changed(f, feature, name, src.name)
    if src.type and classifier is None:
        f.pa(feature, MESSAGE_TYPE, f.string(src.type))
    if kind == "Publisher" and given(src, "latching") is not None:
        f.pa(feature, LATCHING, f.boolean(src.latching))
    return feature


@_t.rule("rosmod.Publisher", name="publisher")
def _publisher(ctx: Context, src: EObject) -> EObject:
    return _port_feature(ctx, src)


@_t.rule("rosmod.Client", name="client")
def _client(ctx: Context, src: EObject) -> EObject:
    return _port_feature(ctx, src)


@_t.rule("rosmod.Subscriber", name="subscriber")
def _subscriber(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    feature = _port_feature(ctx, src)
    thread_name = st.plan.extra[(id(src), "thread")]
    thread, queue = _callback_thread(ctx, src, "subscriber", thread_name)
    call = st.factory.conn(
        st.plan.extra[(id(src), "callback_conn")], "port", feature.name, f"{thread_name}.{SUBSCRIBER_PORT}"
    )
    return feature, thread, call, queue


@_t.rule("rosmod.Server", name="server")
def _server(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    feature = _port_feature(ctx, src)
    thread_name = st.plan.extra[(id(src), "thread")]
    thread, queue = _callback_thread(ctx, src, "server", thread_name)
    call = st.factory.conn(
        st.plan.extra[(id(src), "callback_conn")],
        "access",
        f"{thread_name}.{SERVER_ACCESS}",
        feature.name,
        "subprogram",
    )
    return feature, thread, call, queue


# -------------------------------------------------------------------- hardware


@_t.rule("rosmod.System", name="hardware")
def _hardware(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    pkg = _unit_header(st, src, "Hardware")
    f.text(pkg, SOURCE_FILE, src.sourceFile)
    f.settings(pkg, src.properties)
    type_name = st.plan.extra[(id(src), "type")]
    return pkg, f.ctype("system", type_name), f.cimpl("system", type_name)


@_hardware.bind
def _hardware_bind(ctx: Context, src: EObject, pkg: EObject, system: EObject, impl: EObject) -> None:
    st = _state(ctx)
    f = st.factory
    classifiers: list[EObject] = [system, impl]
    subs: list[EObject] = []
    for element in (*src.hosts, *src.networks):
        for target in ctx.resolve(element):
            (subs if target.eClass.name == "Subcomponent" else classifiers).append(target)
    links = [t for link in src.links for t in ctx.resolve(link)]
    f.add(impl, "subcomponents", *subs)
    f.add(impl, "connections", *links)
    f.add(pkg, "classifiers", *classifiers)


@_t.rule("rosmod.Host", name="host")
def _host(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    system = src.eContainer()
    type_name = st.plan.extra[(id(src), "type")]
    processor = f.ctype("processor", type_name)
    for prop, value in (
        (IP_ADDRESS, src.ipAddress),
        (USERNAME, src.username),
        (SSH_KEY, src.sshKey),
        (DEPLOYMENT_PATH, src.deploymentPath),
        (INSTALL_PATH, src.installPath),
        (ARCHITECTURE, src.architecture),
        (OS, src.os),
    ):
        f.text(processor, prop, value)
    f.settings(processor, src.properties)
    name = st.plan.names[id(src)]
    sub = f.sub(name, "processor", f"{st.plan.units[id(system)]}::{type_name}")
    _name_if_changed(f, sub, name, src.name)
    return processor, sub


@_host.bind
def _host_bind(ctx: Context, src: EObject, processor: EObject, sub: EObject) -> None:
    st = _state(ctx)
    st.factory.add(processor, "features", *(t for i in src.interfaces for t in ctx.resolve(i)))


@_t.rule("rosmod.Interface", name="interface")
def _interface(ctx: Context, src: EObject) -> EObject:
    st = _state(ctx)
    f = st.factory
    name = st.plan.names[id(src)]
    feature = f.feature(name, "bus access", access="requires")
    _name_if_changed(f, feature, name, src.name)
    return feature


@_t.rule("rosmod.Network", name="network")
def _network(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    system = src.eContainer()
    type_name = st.plan.extra[(id(src), "type")]
    bus = f.ctype("bus", type_name)
    f.text(bus, SUBNET, src.subnet)
    f.text(bus, NETMASK, src.netmask)
    name = st.plan.names[id(src)]
    sub = f.sub(name, "bus", f"{st.plan.units[id(system)]}::{type_name}")
    _name_if_changed(f, sub, name, src.name)
    return bus, sub


@_t.rule("rosmod.Link", name="link")
def _link(ctx: Context, src: EObject) -> EObject | None:
    st = _state(ctx)
    f = st.factory
    system = src.eContainer()
    host, interface, network = src.host, src.interface, src.network
    if (
        network is None
        or interface is None
        or host is None
        or network.eContainer() is not system
        or host.eContainer() is not system
        or interface.eContainer() is not host
    ):
        raise TransformationError(
            f"link {src.name!r} does not join an interface of a host of {system.name!r} to one of its "
            "networks",
            source_location(src),
        )
    name = st.plan.names[id(src)]
    conn = f.conn(
        name,
        "access",
        st.plan.names[id(network)],
        f"{st.plan.names[id(host)]}.{st.plan.names[id(interface)]}",
        "bus",
    )
    _name_if_changed(f, conn, name, src.name)
    f.text(conn, IP_ADDRESS, src.ip)
    return conn


# -------------------------------------------------------------------- deployment


@_t.rule("rosmod.Deployment", name="deployment")
def _deployment(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    pkg = _unit_header(st, src, "Deployment")
    f.text(pkg, SOURCE_FILE, src.sourceFile)
    f.text(pkg, SYSTEM_NAME, src.systemName)
    f.settings(pkg, src.properties)
    type_name = st.plan.extra[(id(src), "type")]
    system = f.ctype("system", type_name)
    impl = f.cimpl("system", type_name)
    subs: list[EObject] = []
    hardware = [] if src.system is None else [src.system]
    for node in src.nodes:
        system_of = st.plan.systems.get(id(node.host)) if node.host is not None else None
        if system_of is not None and system_of not in hardware:
            hardware.append(system_of)
    for hw in hardware:
        hw_unit = st.plan.units[id(hw)]
        classifier = f"{hw_unit}::{st.plan.extra[(id(hw), 'type')]}.impl"
        subs.append(f.sub(st.plan.extra[(id(src), f"system:{id(hw)}")], "system", classifier))
    subs.append(f.sub(st.plan.extra[(id(src), "bus")], "virtual bus", ROS_BUS))
    return (pkg, system, impl, *subs)


@_t.rule("rosmod.Node", name="node")
def _node(ctx: Context, src: EObject) -> tuple[EObject, ...]:
    st = _state(ctx)
    f = st.factory
    deployment = src.eContainer()
    unit = st.plan.units[id(deployment)]
    type_name = st.plan.extra[(id(src), "type")]
    process = f.ctype("process", type_name, extended=NODE_TYPE)
    if given(src, "priority") is not None:
        f.pa(process, PRIORITY, f.integer(src.priority))
    f.text(process, ARGUMENTS, src.arguments)
    f.text(process, HOST_REF, src.hostRef)
    f.settings(process, src.properties)
    impl = f.cimpl("process", type_name, extended=f"{NODE_TYPE}.impl")
    name = st.plan.names[id(src)]
    sub = f.sub(name, "process", f"{unit}::{type_name}.impl")
    _name_if_changed(f, sub, name, src.name)
    if src.host is None and src.hostRef:
        raise TransformationError(
            f"node {src.name!r} is on host {src.hostRef!r}, which does not resolve to a host of the project",
            source_location(src),
        )
    if src.host is not None and id(src.host) not in st.plan.systems:
        raise TransformationError(
            f"node {src.name!r} is on host {src.host.name!r}, which is not a host of a hardware model of "
            "this project",
            source_location(src),
        )
    return process, impl, sub


@_node.bind
def _node_bind(ctx: Context, src: EObject, process: EObject, impl: EObject, sub: EObject) -> None:
    st = _state(ctx)
    st.factory.add(impl, "subcomponents", *(t for i in src.componentInstances for t in ctx.resolve(i)))


@_t.rule("rosmod.ComponentInstance", name="component_instance")
def _component_instance(ctx: Context, src: EObject) -> EObject:
    st = _state(ctx)
    f = st.factory
    comp = src.component
    if comp is None or id(comp) not in st.plan.names:
        ref = src.componentRef or "?"
        raise TransformationError(
            f"component_instance {src.name!r}: its component {ref!r} is not a component of this project",
            source_location(src),
        )
    package = comp.eContainer()
    classifier = f"{st.plan.units[id(package)]}::{st.plan.names[id(comp)]}.impl"
    name = st.plan.names[id(src)]
    sub = f.sub(name, "thread group", classifier)
    _name_if_changed(f, sub, name, src.name)
    if src.componentRef is not None and src.componentRef != f"{package.name}/{comp.name}":
        f.pa(sub, COMPONENT_REF, f.string(src.componentRef))
    if src.eIsSet("schedulingScheme"):
        f.pa(sub, SCHEDULING_SCHEME, f.named(src.schedulingScheme.name))
    f.settings(sub, src.logging, LOGGING)
    ports = [
        f.record(
            [("Name", f.string(p.name or ""))]
            + ([("Port_Ref", f.string(p.port))] if p.port is not None else [])
            + ([("Group_Name", f.string(p.group))] if p.group is not None else [])
        )
        for p in src.portInstances
    ]
    if ports:
        f.pa(sub, PORT_INSTANCES, f.listing(ports))
    f.settings(sub, src.properties)
    return sub


@_deployment.bind
def _deployment_bind(
    ctx: Context, src: EObject, pkg: EObject, system: EObject, impl: EObject, *subs: EObject
) -> None:
    st = _state(ctx)
    f = st.factory
    plan = st.plan
    classifiers: list[EObject] = [system, impl]
    nodes: list[EObject] = []
    for node in src.nodes:
        process, process_impl, node_sub = ctx.resolve(node, "node")
        classifiers.extend((process, process_impl))
        nodes.append(node_sub)
        if node.host is not None:
            hw = plan.systems[id(node.host)]
            path = f"{plan.extra[(id(src), f'system:{id(hw)}')]}.{plan.names[id(node.host)]}"
            f.pa(impl, PROCESSOR_BINDING, f.listing([f.reference(path)]), applies_to=plan.names[id(node)])
    f.add(impl, "subcomponents", *subs, *nodes)
    _topics(ctx, st, src, impl)
    f.add(pkg, "classifiers", *classifiers)


def _topic_key(port: EObject, settings: dict[str, str]) -> tuple[str | None, str | None]:
    return port.type, settings.get(f"{port.name}.Topic")


def _topics(ctx: Context, st: _State, deployment: EObject, impl: EObject) -> None:
    """Port connections for the topics (and access connections for the services) of a deployment."""
    f = st.factory
    plan = st.plan
    ends: dict[str, list[tuple[EObject, EObject, EObject]]] = {
        "Publisher": [],
        "Subscriber": [],
        "Client": [],
        "Server": [],
    }
    settings: dict[int, dict[str, str]] = {}
    for node in deployment.nodes:
        for inst in node.componentInstances:
            comp = inst.component
            if id(comp) not in settings:
                settings[id(comp)] = {p.key: p.value for p in comp.properties if p.key}
            for port in comp.ports:
                ends[port.eClass.name].append((node, inst, port))
    subscribers: dict[tuple[str | None, str | None], list[tuple[EObject, EObject, EObject]]] = {}
    for end in ends["Subscriber"]:
        key = _topic_key(end[2], settings[id(end[1].component)])
        if key[0]:
            subscribers.setdefault(key, []).append(end)
    servers: dict[tuple[str | None, str | None], list[tuple[EObject, EObject, EObject]]] = {}
    for end in ends["Server"]:
        key = _topic_key(end[2], settings[id(end[1].component)])
        if key[0]:
            servers.setdefault(key, []).append(end)
    members = plan.scope(deployment, "impl")
    bus = plan.extra[(id(deployment), "bus")]
    exported: dict[tuple[int, int, int], str] = {}
    connections: list[EObject] = []
    bindings: list[tuple[str, str]] = []

    def export(node: EObject, inst: EObject, port: EObject, outward: bool, access: str | None) -> str:
        key = (id(node), id(inst), id(port))
        found = exported.get(key)
        if found is not None:
            return found
        process = ctx.resolve(node, "node")
        process_type, process_impl = process[0], process[1]
        scope = plan.scope(node)
        inner = plan.names[id(inst)]
        name = scope.take(f"{inner}_{port.name}")
        source = ctx.resolve(port)[0]
        if access is None:
            feature = f.feature(
                name, "event data port", direction="out" if outward else "in", classifier=source.classifier
            )
            ends_ = (f"{inner}.{source.name}", name) if outward else (name, f"{inner}.{source.name}")
            link = f.conn(scope.take(f"{name}_link"), "port", *ends_)
        else:
            feature = f.feature(name, "subprogram access", access=access, classifier=source.classifier)
            inside = f"{inner}.{source.name}"
            ends_ = (inside, name) if access == "provides" else (name, inside)
            link = f.conn(scope.take(f"{name}_link"), "access", *ends_, "subprogram")
        if port.type and source.classifier is None:
            f.pa(feature, MESSAGE_TYPE, f.string(port.type))
        f.add(process_type, "features", feature)
        f.add(process_impl, "connections", link)
        exported[key] = name
        return name

    def connect(kind: str, source: tuple, destination: tuple, label: str | None) -> None:
        src_node, src_inst, src_port = source
        dst_node, dst_inst, dst_port = destination
        service = kind == "access"
        type_part = (src_port.type or "").rpartition("/")[2]
        if src_node is dst_node:
            scope = plan.scope(src_node)
            name = scope.take(f"{'service' if service else 'topic'}_{type_part}")
            inner_src = f"{plan.names[id(src_inst)]}.{ctx.resolve(src_port)[0].name}"
            inner_dst = f"{plan.names[id(dst_inst)]}.{ctx.resolve(dst_port)[0].name}"
            link = f.conn(name, kind, inner_src, inner_dst, "subprogram" if service else None)
            if label:
                f.pa(link, TOPIC_NAME, f.string(label))
            f.add(ctx.resolve(src_node, "node")[1], "connections", link)
            bindings.append((f"{plan.names[id(src_node)]}.{name}", bus))
            return
        if service:
            out_name = export(src_node, src_inst, src_port, True, "provides")
            in_name = export(dst_node, dst_inst, dst_port, False, "requires")
        else:
            out_name = export(src_node, src_inst, src_port, True, None)
            in_name = export(dst_node, dst_inst, dst_port, False, None)
        name = members.take(f"{'service' if service else 'topic'}_{type_part}")
        link = f.conn(
            name,
            kind,
            f"{plan.names[id(src_node)]}.{out_name}",
            f"{plan.names[id(dst_node)]}.{in_name}",
            "subprogram" if service else None,
        )
        if label:
            f.pa(link, TOPIC_NAME, f.string(label))
        carrier = _carrier(st, deployment, src_node.host, dst_node.host) or bus
        # on the connection itself: a contained association per topic would make every property
        # look-up of the instance scan them all
        f.pa(link, CONNECTION_BINDING, f.listing([f.reference(carrier)]))
        connections.append(link)

    for publisher in ends["Publisher"]:
        key = _topic_key(publisher[2], settings[id(publisher[1].component)])
        for subscriber in subscribers.get(key, []) if key[0] else []:
            connect("port", publisher, subscriber, _topic_label(key))
    for client in ends["Client"]:
        key = _topic_key(client[2], settings[id(client[1].component)])
        candidates = servers.get(key, []) if key[0] else []
        if len(candidates) > 1:
            ctx.warn(
                f"client {client[2].name!r} of {client[1].name!r}: {len(candidates)} servers of "
                f"{client[2].type!r} in deployment {deployment.name!r}; connected to the first",
                client[1],
            )
        if candidates:
            connect("access", candidates[0], client, _topic_label(key))
    f.add(impl, "connections", *connections)
    for applies_to, carrier in bindings:
        f.pa(impl, CONNECTION_BINDING, f.listing([f.reference(carrier)]), applies_to=applies_to)


def _topic_label(key: tuple[str | None, str | None]) -> str | None:
    return key[1].rpartition("/")[2] if key[1] else None


def _carrier(st: _State, deployment: EObject, a: EObject | None, b: EObject | None) -> str | None:
    """``hw.network`` for a network both hosts are linked to (same hardware model), else None."""
    if a is None or b is None or a is b:
        return None
    system = st.plan.systems.get(id(a))
    if system is None or system is not st.plan.systems.get(id(b)):
        return None
    nets_a = [link.network for link in system.links if link.host is a and link.network is not None]
    nets_b = {id(link.network) for link in system.links if link.host is b and link.network is not None}
    for network in nets_a:
        if id(network) in nets_b:
            hw = st.plan.extra[(id(deployment), f"system:{id(system)}")]
            return f"{hw}.{st.plan.names[id(network)]}"
    return None


# =========================================================================== entry point


@dataclass
class ConversionResult:
    """The AADL model made from a ROSMOD project."""

    model: EObject  #: ``AadlModel`` holding the generated packages (not the library)
    roots: dict[str, str]  #: deployment name → root implementation (``Pkg::System.impl``)
    trace: EObject | None  #: the ``trace.Trace`` (ROSMOD element keys → AADL element keys)
    warnings: list[RosaadlError] = field(default_factory=list)

    @property
    def units(self) -> list[EObject]:
        return list(self.model.units)


def _interface_units(st: _State) -> None:
    f = st.factory
    position = max(st.plan.positions.values(), default=0)
    for ros_pkg in sorted(st.plan.interfaces):
        iface = st.plan.interfaces[ros_pkg]
        pkg = f.package(iface.unit)
        f.pa(pkg, UNIT_KIND, f.named("Interfaces"))
        _name_if_changed(f, pkg, iface.unit, ros_pkg)
        classifiers: list[EObject] = []
        for type_name, name in iface.messages.items():
            data = f.ctype("data", name)
            _name_if_changed(f, data, name, type_name.rpartition("/")[2])
            standard = ros_msg.standard_message(type_name)
            size = ros_msg.data_size(standard) if standard is not None else None
            if size is not None:
                f.pa(data, DATA_SIZE, f.integer(size, "Bytes"))
            f.pa(data, MESSAGE_TYPE, f.string(type_name))
            classifiers.append(data)
        for type_name, name in iface.services.items():
            subprogram = f.ctype("subprogram", name)
            _name_if_changed(f, subprogram, name, type_name.rpartition("/")[2])
            f.pa(subprogram, SERVICE_TYPE, f.string(type_name))
            classifiers.append(subprogram)
        f.add(pkg, "classifiers", *classifiers)
        position += 1
        st.units[position] = pkg


class _KeyCache:
    """:func:`rosaadl.transforms.trace.element_key` for many objects of one model, each
    container's key computed once (the targets were made before they had a container, so
    their keys are computed when the model is complete)."""

    def __init__(self) -> None:
        self._keys: dict[int, str] = {}
        self._named: dict[int, bool] = {}

    def key(self, obj: EObject) -> str:
        found = self._keys.get(id(obj))
        if found is not None:
            return found
        container = obj.eContainer()
        if container is None:
            key = "/"
        else:
            eclass = obj.eClass
            named = self._named.get(id(eclass))
            if named is None:
                named = self._named[id(eclass)] = eclass.findEStructuralFeature("name") is not None
            feature = obj.eContainmentFeature()
            name = obj.name if named else None
            if name:
                step = f"{feature.name}[{name}]"
            elif feature.many:
                step = f"{feature.name}.{container.eGet(feature).index(obj)}"
            else:
                step = feature.name
            parent = self.key(container)
            key = f"{parent.rstrip('/')}/{step}"
        self._keys[id(obj)] = key
        return key


_PREDECLARED = frozenset(
    {
        "timing_properties",
        "thread_properties",
        "memory_properties",
        "deployment_properties",
        "communication_properties",
        "programming_properties",
        "modeling_properties",
        "aadl_project",
    }
)


def _withs(unit: EObject) -> list[str]:
    """The packages and property sets a generated unit refers to (its ``with`` clause)."""
    names: set[str] = set()

    def qualifier(text: str | None) -> None:
        if text and "::" in text:
            names.add(text.rpartition("::")[0])

    def associations(holder: EObject) -> None:
        for assoc in holder.ownedPropertyAssociations:
            qualifier(assoc.property)

    associations(unit)
    for classifier in unit.classifiers:
        qualifier(classifier.extended)
        associations(classifier)
        for member_list in ("features", "subcomponents", "connections"):
            feature = classifier.eClass.findEStructuralFeature(member_list)
            if feature is None:
                continue
            for member in classifier.eGet(feature):
                if member_list != "connections":
                    qualifier(member.classifier)
                associations(member)
    names.discard(unit.name)
    return sorted((n for n in names if n.lower() not in _PREDECLARED), key=str.lower)


def rosmod_to_aadl(project: EObject, *, trace: bool = True) -> ConversionResult:
    """Convert a ``rosmod.Project`` into AADL packages (see the module documentation).

    Raises a located :class:`~rosaadl.errors.TransformationError` (rule, element, file and line)
    for what cannot be converted: a component instance whose component is not in the project, a
    node on a host that does not resolve, a port of an unknown type of a project package, a
    link that does not join a host's interface to a network. Warnings (a time rounded to
    picoseconds, a client with several servers) are in ``warnings``.
    """
    if not isinstance(project, EObject) or project.eClass.name != "Project":
        raise TransformationError("expected a rosmod Project to convert")
    with gc_paused():
        plan = _Plan(project)
        state = _State(project=project, plan=plan, factory=_Factory())
        result = TRANSFORMATION.run(project, state=state)
        _interface_units(state)
        f = state.factory
        aadl = f.fb.make("AadlModel", name=plan.units[id(project)])
        units = [state.units[k] for k in sorted(state.units)]
        for unit in units:
            f.add(unit, "withs", *_withs(unit))
        f.add(aadl, "units", *units)
        roots = {
            dep.name: f"{plan.units[id(dep)]}::{plan.extra[(id(dep), 'type')]}.impl"
            for dep in project.deployments
        }
        if trace:
            keys = _KeyCache()
            for link in result.trace.links:
                for end in link.targets:
                    end.path = keys.key(end.object)
    return ConversionResult(
        model=aadl, roots=roots, trace=result.trace if trace else None, warnings=list(result.warnings)
    )

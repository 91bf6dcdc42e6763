"""AADL data classifiers as ROS 2 interfaces (messages and services).

A port's data classifier becomes a ROS 2 message type, a subprogram access's subprogram a
service type, in this order:

1. ``ROS_Properties::Message_Type`` on the feature (the instantiator resolves it from the data
   classifier) or on the classifier and its ``extends`` chain: ``"sensor_msgs/Image"``;
2. the library's standard types: ``ros_data::Image`` → ``sensor_msgs/msg/Image``, ``Twist``,
   ``Point`` … → ``geometry_msgs``, ``std_msgs`` basics, and the Data Modeling Annex's
   ``Base_Types`` (``Float_64`` → ``std_msgs/msg/Float64``);
3. anything else is an interface of the application's ``<app>_interfaces`` package, defined by,
   in this order, the ROSMOD ``.msg``/``.srv`` definition the model came from (a ``rosmod``
   ``Message``/``Service`` linked to the classifier by a transformation trace, or a string
   property ``*::Message_Definition`` / ``*::Service_Definition`` / ``*::Definition``), the
   data implementation's subcomponents (fields; ``Base_Types`` become primitive types), or the
   parameters of a subprogram (``in`` → request, ``out`` → response); a data type with no known
   structure becomes an opaque byte buffer ``uint8[] data``.

An event port (no data) carries ``std_msgs/msg/Empty``.  ROS 1 definitions are rewritten for
ROS 2: ``time``/``duration`` → ``builtin_interfaces``, ``Header`` → ``std_msgs/Header``, field
names in lower snake case, constant names in upper case.
"""

from __future__ import annotations

import logging
import re
from collections.abc import Iterable
from dataclasses import dataclass, field

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import Diagnostic, Location, RosaadlError
from rosaadl.exporters.rclpy import naming
from rosaadl.exporters.rclpy.instances import prop
from rosaadl.importers import ros_msg
from rosaadl.properties import own_property, property_name_matches

__all__ = [
    "InterfaceType",
    "InterfaceDefinition",
    "MessageCatalog",
    "STANDARD_TYPES",
    "BASE_TYPES",
    "EMPTY",
]

log = logging.getLogger(__name__)


@dataclass(frozen=True, order=True)
class InterfaceType:
    """A ROS 2 interface: ``package/kind/name`` (``sensor_msgs/msg/Image``)."""

    package: str
    kind: str  # "msg" | "srv"
    name: str

    @property
    def full_name(self) -> str:
        return f"{self.package}/{self.kind}/{self.name}"

    @property
    def module(self) -> str:
        return f"{self.package}.{self.kind}"

    def __str__(self) -> str:
        return self.full_name


EMPTY = InterfaceType("std_msgs", "msg", "Empty")

#: Local names of the library's ``ros_data`` types that are standard ROS 2 messages.
STANDARD_TYPES: dict[str, str] = {
    "bool": "std_msgs/Bool",
    "byte": "std_msgs/Byte",
    "char": "std_msgs/Char",
    "int8": "std_msgs/Int8",
    "int16": "std_msgs/Int16",
    "int32": "std_msgs/Int32",
    "int64": "std_msgs/Int64",
    "uint8": "std_msgs/UInt8",
    "uint16": "std_msgs/UInt16",
    "uint32": "std_msgs/UInt32",
    "uint64": "std_msgs/UInt64",
    "float32": "std_msgs/Float32",
    "float64": "std_msgs/Float64",
    "string": "std_msgs/String",
    "empty": "std_msgs/Empty",
    "colorrgba": "std_msgs/ColorRGBA",
    "header": "std_msgs/Header",
    "point": "geometry_msgs/Point",
    "point32": "geometry_msgs/Point32",
    "vector3": "geometry_msgs/Vector3",
    "quaternion": "geometry_msgs/Quaternion",
    "pose": "geometry_msgs/Pose",
    "pose2d": "geometry_msgs/Pose2D",
    "posestamped": "geometry_msgs/PoseStamped",
    "twist": "geometry_msgs/Twist",
    "twiststamped": "geometry_msgs/TwistStamped",
    "transform": "geometry_msgs/Transform",
    "transformstamped": "geometry_msgs/TransformStamped",
    "accel": "geometry_msgs/Accel",
    "wrench": "geometry_msgs/Wrench",
    "tfmessage": "tf2_msgs/TFMessage",
    "image": "sensor_msgs/Image",
    "compressedimage": "sensor_msgs/CompressedImage",
    "camerainfo": "sensor_msgs/CameraInfo",
    "imu": "sensor_msgs/Imu",
    "laserscan": "sensor_msgs/LaserScan",
    "pointcloud2": "sensor_msgs/PointCloud2",
    "odometry": "nav_msgs/Odometry",
}
#: Data Modeling Annex ``Base_Types`` as ROS 2 primitive field types.
BASE_TYPES: dict[str, str] = {
    "boolean": "bool",
    "integer": "int64",
    "integer_8": "int8",
    "integer_16": "int16",
    "integer_32": "int32",
    "integer_64": "int64",
    "unsigned_8": "uint8",
    "unsigned_16": "uint16",
    "unsigned_32": "uint32",
    "unsigned_64": "uint64",
    "natural": "uint64",
    "float": "float64",
    "float_32": "float32",
    "float_64": "float64",
    "character": "char",
    "string": "string",
}
_PRIMITIVE_MESSAGES = {
    "bool": "Bool",
    "int8": "Int8",
    "int16": "Int16",
    "int32": "Int32",
    "int64": "Int64",
    "uint8": "UInt8",
    "uint16": "UInt16",
    "uint32": "UInt32",
    "uint64": "UInt64",
    "float32": "Float32",
    "float64": "Float64",
    "char": "Char",
    "string": "String",
}
_STANDARD_PACKAGES = frozenset({"ros_data"})
_BASE_TYPES_PACKAGES = frozenset({"base_types"})
#: Packages whose interfaces every ROS 2 installation has (kept as they are in definitions).
_ROS_INTERFACE_PACKAGES = frozenset(
    {
        "std_msgs",
        "geometry_msgs",
        "sensor_msgs",
        "nav_msgs",
        "builtin_interfaces",
        "tf2_msgs",
        "std_srvs",
        "diagnostic_msgs",
        "shape_msgs",
        "trajectory_msgs",
        "visualization_msgs",
        "stereo_msgs",
        "actionlib_msgs",
    }
)
_DEFINITION_PROPERTIES = ("Message_Definition", "Service_Definition", "Definition")


@dataclass
class InterfaceDefinition:
    """A message or service of the ``<app>_interfaces`` package, ready to be written."""

    type: InterfaceType
    source: str  # what it was made from, for the file's comment
    lines: list[str] = field(default_factory=list)  # .msg lines (fields and constants)
    response: list[str] = field(default_factory=list)  # .srv response lines
    dependencies: set[str] = field(default_factory=set)  # interface packages the fields use

    @property
    def file_name(self) -> str:
        return f"{self.type.name}.{self.type.kind}"


_IDENTIFIER = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def _split_type(text: str, kind: str) -> tuple[str, str, str] | None:
    """``pkg/Type`` or ``pkg/msg/Type`` as (package, kind, name), None when it is not that shape."""
    parts = [p.strip() for p in (text or "").strip().split("/")]
    if len(parts) == 3 and parts[1] in ("msg", "srv", "action"):
        kind, parts = parts[1], [parts[0], parts[2]]
    if len(parts) != 2 or not all(_IDENTIFIER.match(p) for p in parts):
        return None
    return parts[0], kind, parts[1]


def _parse_type(text: str, kind: str) -> InterfaceType | None:
    """``pkg/Type`` or ``pkg/msg/Type`` as an :class:`InterfaceType` when both are valid ROS 2
    names, else None."""
    split = _split_type(text, kind)
    if split is None:
        return None
    package, kind, name = split
    if not naming.is_package_name(package) or not naming.is_message_name(name):
        return None
    return InterfaceType(package, kind, name)


def _local_type_name(qualified: str) -> tuple[str, str]:
    """``ros_data::Image.rgb`` → (``ros_data``, ``Image``)."""
    package, _, local = (qualified or "").rpartition("::")
    return package, local.partition(".")[0]


class MessageCatalog:
    """Maps the data classifiers of one model to ROS 2 interfaces; collects the custom ones.

    ``model`` is the ``AadlModel`` (its ``units`` give the declarative classifiers when there
    are any); ``interfaces_package`` the name of the application's interface package;
    ``trace`` an optional ROSMOD → AADL trace whose live links give the ROSMOD definitions.
    """

    def __init__(self, model: EObject | None, interfaces_package: str, trace: EObject | None = None) -> None:
        self.model = model
        self.interfaces_package = interfaces_package
        self.diagnostics: list[Diagnostic] = []
        self._definitions: dict[str, InterfaceDefinition] = {}  # type name -> definition
        self._by_classifier: dict[tuple[str, str], InterfaceType] = {}
        self._names = naming.NameTable(separator="")
        self._defining: set[tuple[str, str]] = set()  # classifiers whose definition is being made
        self._messages: dict[str, str] | None = None
        self._resolver = None
        self._rosmod: dict[int, EObject] = {}
        if model is not None and getattr(model, "units", None):
            from rosaadl.resolution import Resolver

            self._resolver = Resolver(model)
        if trace is not None:
            self._index_trace(trace)

    # ------------------------------------------------------------------ public

    def for_port(self, feature: EObject) -> InterfaceType:
        """The message type a port instance carries."""
        if _model_enum(feature.category) == "eventPort":
            return EMPTY
        classifier = feature.classifier or ""
        override = self._port_override(feature, classifier, "msg")
        if override is not None:
            return override
        if not classifier:
            classifier = self.classifier_from_declaration(feature)
        if not classifier:
            self._warn(f"port {feature.name!r} has no data classifier; it carries {EMPTY.full_name}", feature)
            return EMPTY
        return self._classifier_type(classifier, "msg", feature)

    def for_access(self, feature: EObject) -> InterfaceType:
        """The service type of a subprogram access instance."""
        classifier = feature.classifier or ""
        override = self._port_override(feature, classifier, "srv")
        if override is not None:
            return override
        if not classifier:
            name = naming.message_name(feature.name or "", fallback="Srv")
            return self._custom(("", f"access:{name}"), name, "srv", feature, lambda d: None)
        return self._classifier_type(classifier, "srv", feature)

    def _port_override(self, feature: EObject, classifier: str, kind: str) -> InterfaceType | None:
        """The type declared on the feature itself, when it is not just its classifier's."""
        value = prop(feature, "Service_Type") if kind == "srv" else None
        if not (isinstance(value, str) and value.strip()):
            value = prop(feature, "Message_Type")
        if not (isinstance(value, str) and value.strip()):
            return None
        found = self._classifier(classifier) if classifier else None
        if found is not None and self._declared_text(found, kind) == value:
            return None  # the classifier's own type: decided with its definition
        declared = _parse_type(value, kind)
        if declared is None:
            self._warn(f"type {value!r} is not a ROS 2 interface name (package/Type); ignored", feature)
        return declared

    def classifier_from_declaration(self, feature: EObject) -> str:
        """The classifier of the feature an untyped thread port is connected to in the declarative
        model (a thread group's port), when no connection instance passes there."""
        resolver = self._resolver
        thread = feature.eContainer()
        parent = thread.eContainer() if thread is not None else None
        if resolver is None or parent is None or not (parent.classifier or ""):
            return ""
        try:
            impl = resolver.classifier(parent.classifier)
            if impl is None:
                return ""
            wanted = f"{thread.name}.{feature.name}".lower()
            outer = {f.name.lower(): f for f in resolver.features(impl) if f.name}
            for connection in resolver.connections(impl):
                ends = [e.lower() for e in resolver.connection_ends(connection)]
                if wanted in ends:
                    other = ends[1 - ends.index(wanted)]
                    declared = outer.get(other)
                    if declared is not None:
                        found = resolver.feature_classifier(declared)
                        if found is not None:
                            return _qualified(found)
        except RosaadlError:
            return ""
        return ""

    def connected_inside(self, feature: EObject) -> bool:
        """Whether a connection declared in the implementation of the component owning
        ``feature`` (a process or thread group) joins it to a subcomponent: a port that only
        passes a thread's port through, not one of the component's own. Unknown (no declarative
        model, or the implementation is not found) counts as connected."""
        resolver = self._resolver
        owner = feature.eContainer()
        if resolver is None or owner is None or not (owner.classifier or ""):
            return True
        try:
            impl = resolver.classifier(owner.classifier)
            if impl is None:
                return True
            name = (feature.name or "").lower()
            return any(
                name in (end.lower() for end in resolver.connection_ends(connection))
                for connection in resolver.connections(impl)
            )
        except RosaadlError:
            return True

    def definitions(self) -> list[InterfaceDefinition]:
        """The interfaces of the ``<app>_interfaces`` package, by kind then name."""
        return sorted(self._definitions.values(), key=lambda d: (d.type.kind, d.type.name))

    # ------------------------------------------------------------------ look-ups

    def _warn(self, message: str, element: EObject | None = None) -> None:
        path = _model.instance_path(element) if element is not None and _is_instance(element) else None
        self.diagnostics.append(Diagnostic("warning", message, Location(path=path)))
        log.warning("%s%s", f"{path}: " if path else "", message)

    def _classifier(self, qualified: str) -> EObject | None:
        if self._resolver is None:
            return None
        try:
            return self._resolver.classifier(qualified)
        except RosaadlError:
            return None

    def _chain(self, classifier: EObject) -> list[EObject]:
        """The implementation chain, then its type chain (nearest first)."""
        resolver = self._resolver
        if resolver is None:
            return [classifier]
        try:
            chain = list(resolver.extends_chain(classifier))
            ctype = resolver.component_type(classifier)
            if ctype is not None and ctype is not classifier:
                chain.extend(resolver.extends_chain(ctype))
        except RosaadlError:
            return [classifier]
        return chain

    def _classifier_property(self, classifier: EObject, name: str) -> object:
        for element in self._chain(classifier):
            value = own_property(element, name)
            if value is not None:
                return value
        return None

    def _definition_property(self, classifier: EObject, feature: EObject) -> str | None:
        for element in [feature, *self._chain(classifier)]:
            for assoc in getattr(element, "ownedPropertyAssociations", ()):
                if assoc.appliesTo:
                    continue
                if any(property_name_matches(assoc.property or "", p) for p in _DEFINITION_PROPERTIES):
                    value = own_property(element, assoc.property)
                    if isinstance(value, str):
                        return value
        return None

    def _classifier_type(self, qualified: str, kind: str, feature: EObject) -> InterfaceType:
        key = (qualified.lower(), kind)
        cached = self._by_classifier.get(key)
        if cached is not None:
            return cached
        found = self._resolve_classifier(qualified, kind, feature)
        self._by_classifier[key] = found
        return found

    def _declared_text(self, classifier: EObject, kind: str) -> object:
        if kind == "srv":
            value = self._classifier_property(classifier, "Service_Type")
            if isinstance(value, str) and value.strip():
                return value
        return self._classifier_property(classifier, "Message_Type")

    def _resolve_classifier(self, qualified: str, kind: str, feature: EObject) -> InterfaceType:
        classifier = self._classifier(qualified)
        name = None
        if classifier is not None:
            declared = self._declared_text(classifier, kind)
            if isinstance(declared, str) and declared.strip():
                found = _parse_type(declared, kind)
                split = _split_type(declared, kind)
                defined_here = (
                    self._rosmod_source(classifier) is not None
                    or self._definition_property(classifier, classifier) is not None
                )
                if found is not None and (found.package in _ROS_INTERFACE_PACKAGES or not defined_here):
                    return found
                if split is not None and defined_here:
                    # a message of the model's own packages: it keeps its name, in ROS 2's spelling
                    name = naming.message_name(split[2], fallback="Msg" if kind == "msg" else "Srv")
                else:
                    self._warn(f"type {declared!r} of {qualified} is not a ROS 2 interface name; ignored")
        package, local = _local_type_name(qualified)
        if kind == "msg":
            standard = self._standard(package, local)
            if standard is not None:
                return standard
        type_key = _type_key(qualified)
        name = name or naming.message_name(local or qualified, fallback="Msg" if kind == "msg" else "Srv")
        return self._custom(type_key, name, kind, feature, lambda d: self._define(d, qualified, classifier))

    def _standard(self, package: str, local: str) -> InterfaceType | None:
        low_pkg, low = package.lower(), local.lower()
        if low_pkg in _STANDARD_PACKAGES and low in STANDARD_TYPES:
            return _parse_type(STANDARD_TYPES[low], "msg")
        if low_pkg in _BASE_TYPES_PACKAGES and low in BASE_TYPES:
            return InterfaceType("std_msgs", "msg", _PRIMITIVE_MESSAGES[BASE_TYPES[low]])
        return None

    def _custom(self, type_key, name: str, kind: str, feature: EObject, define) -> InterfaceType:
        existing = self._by_classifier.get(("custom",) + tuple(type_key) + (kind,))
        if existing is not None:
            return existing
        unique = self._names.unique(name)
        itype = InterfaceType(self.interfaces_package, kind, unique)
        self._by_classifier[("custom",) + tuple(type_key) + (kind,)] = itype
        definition = InterfaceDefinition(type=itype, source=type_key[1] or name)
        self._definitions[unique] = definition
        self._defining.add(tuple(type_key))
        try:
            define(definition)
        finally:
            self._defining.discard(tuple(type_key))
        return itype

    # ------------------------------------------------------------------ definitions

    def _define(self, definition: InterfaceDefinition, qualified: str, classifier: EObject | None) -> None:
        kind = definition.type.kind
        rosmod = self._rosmod_source(classifier)
        if rosmod is not None and self._from_rosmod(definition, rosmod):
            return
        text = self._definition_property(classifier, classifier) if classifier is not None else None
        if text is not None and self._from_text(definition, text, qualified):
            return
        if classifier is not None and kind == "msg" and self._from_subcomponents(definition, classifier):
            return
        if classifier is not None and kind == "srv" and self._from_parameters(definition, classifier):
            return
        if kind == "msg":
            definition.lines = [
                f"# {_comment(qualified)} has no known structure: its content as bytes.",
                "uint8[] data",
            ]
        else:
            definition.lines = []
            definition.response = []

    def _index_trace(self, trace: EObject) -> None:
        for link in getattr(trace, "links", ()):
            sources = [end.object for end in link.sources if end.object is not None]
            rosmod = [s for s in sources if s.eClass.name in ("Message", "Service")]
            if not rosmod:
                continue
            for end in link.targets:
                if end.object is not None:
                    self._rosmod[id(end.object)] = rosmod[0]

    def _rosmod_source(self, classifier: EObject | None) -> EObject | None:
        if classifier is None or not self._rosmod:
            return None
        for element in self._chain(classifier):
            found = self._rosmod.get(id(element))
            if found is not None:
                return found
        return None

    def _from_rosmod(self, definition: InterfaceDefinition, source: EObject) -> bool:
        package = source.eContainer().name if source.eContainer() is not None else None
        try:
            if source.eClass.name == "Message":
                if source.fields:
                    specs = [ros_msg.field_from_model(f) for f in source.fields]
                    definition.lines = self._ros2_lines(specs, package, definition)
                    return True
                if source.definition:
                    return self._from_text(definition, source.definition, f"{package}/{source.name}")
            else:
                if source.requestFields or source.responseFields:
                    definition.lines = self._ros2_lines(
                        [ros_msg.field_from_model(f) for f in source.requestFields], package, definition
                    )
                    definition.response = self._ros2_lines(
                        [ros_msg.field_from_model(f) for f in source.responseFields], package, definition
                    )
                    return True
                if source.definition:
                    return self._from_text(definition, source.definition, f"{package}/{source.name}")
        except RosaadlError as exc:
            self._warn(f"the ROSMOD definition of {source.name!r} is unusable ({exc.message})")
        return False

    def _from_text(self, definition: InterfaceDefinition, text: str, where: str) -> bool:
        package, _, _ = where.rpartition("::") if "::" in where else where.partition("/")
        try:
            if definition.type.kind == "srv":
                spec = ros_msg.parse_srv(text, name=definition.type.name, filename=where)
                definition.lines = self._ros2_lines(spec.request.fields, package or None, definition)
                definition.response = self._ros2_lines(spec.response.fields, package or None, definition)
            else:
                parsed = ros_msg.parse_msg(text, name=definition.type.name, filename=where)
                definition.lines = self._ros2_lines(parsed.fields, package or None, definition)
        except RosaadlError as exc:
            self._warn(f"the definition of {where} does not parse ({exc.message}); not used")
            return False
        return True

    def _ros2_lines(
        self, specs: Iterable[ros_msg.FieldSpec], package: str | None, definition: InterfaceDefinition
    ) -> list[str]:
        lines: list[str] = []
        fields = naming.NameTable()
        for spec in specs:
            base = self._ros2_field_type(spec.type, package, definition)
            text = base
            if spec.string_bound is not None and base in ("string", "wstring"):
                text += f"<={spec.string_bound}"
            if spec.is_array and not base.endswith("]"):  # an unknown type already is bytes
                if spec.array_length is not None:
                    text += f"[{spec.array_length}]"
                elif spec.upper_bound is not None:
                    text += f"[<={spec.upper_bound}]"
                else:
                    text += "[]"
            if spec.is_constant:
                name = fields.unique(naming.constant_name(spec.name))
                value = spec.constant or ""
                if base in ("string", "wstring"):
                    value = "'" + value.replace("\\", "\\\\").replace("'", "\\'") + "'"
                if "#" in value:
                    self._warn(f"constant {spec.name!r}: a value with '#' cannot be written in .msg; dropped")
                    continue
                lines.append(f"{text} {name}={value}")
            else:
                name = fields.unique(naming.field_name(spec.name))
                default = f" {spec.default}" if spec.default is not None and "#" not in spec.default else ""
                lines.append(f"{text} {name}{default}")
        return lines

    def _ros2_field_type(self, type_name: str, package: str | None, definition: InterfaceDefinition) -> str:
        if type_name in ("time", "duration"):
            definition.dependencies.add("builtin_interfaces")
            return f"builtin_interfaces/{type_name.capitalize()}"
        if type_name in ros_msg.PRIMITIVE_TYPES:
            return type_name
        full = ros_msg.normalize_type(type_name, package)
        pkg, _, name = full.partition("/")
        if pkg in _ROS_INTERFACE_PACKAGES and naming.is_message_name(name):
            definition.dependencies.add(pkg)
            return f"{pkg}/{name}"
        # A message of the model's own packages: it lives in the application's package.
        qualified = self._message_index().get(full.lower())
        if qualified is not None:
            return self._field_type_for(qualified, definition)
        nested = naming.message_name(name or full)
        known = self._definitions.get(nested)
        if known is None:
            source = self._rosmod_message(pkg, name)
            if source is not None:
                self._custom(
                    (pkg, f"rosmod:{pkg}/{name}"),
                    nested,
                    "msg",
                    source,
                    lambda d: self._from_rosmod(d, source) or _opaque(d, full),
                )
            else:
                self._warn(f"message type {full} is not known; {definition.type.name} uses it as bytes")
                return "uint8[]"
        return nested

    def _message_index(self) -> dict[str, str]:
        """``pkg/type`` (lower case) → the data classifier declaring it with ``Message_Type``."""
        if self._messages is None:
            self._messages = {}
            for unit in getattr(self.model, "units", ()) if self.model is not None else ():
                for classifier in getattr(unit, "classifiers", ()):
                    if _model_enum(getattr(classifier, "category", "")) != "data":
                        continue
                    value = own_property(classifier, "Message_Type")
                    if isinstance(value, str) and value.strip():
                        self._messages.setdefault(value.strip().lower(), _qualified(classifier))
        return self._messages

    def _rosmod_message(self, package: str, name: str) -> EObject | None:
        for source in self._rosmod.values():
            pkg = source.eContainer()
            if pkg is None:
                continue
            for msg in getattr(pkg, "messages", ()):
                if msg.name == name and (pkg.name or "") == package:
                    return msg
        return None

    def _field_type_for(self, qualified: str, definition: InterfaceDefinition) -> str:
        """The ``.msg`` field type of a data classifier used as a field or a parameter."""
        package, local = _local_type_name(qualified)
        if package.lower() in _BASE_TYPES_PACKAGES and local.lower() in BASE_TYPES:
            return BASE_TYPES[local.lower()]
        classifier = self._classifier(qualified)
        if classifier is not None:
            for element in self._chain(classifier):
                ext_pkg, ext_local = _local_type_name(_qualified(element))
                if ext_pkg.lower() in _BASE_TYPES_PACKAGES and ext_local.lower() in BASE_TYPES:
                    return BASE_TYPES[ext_local.lower()]
        if _type_key(qualified) in self._defining:
            self._warn(f"data type {qualified} contains itself; the nested field is written as bytes")
            return "uint8[]"
        itype = self._classifier_type(qualified, "msg", None)
        if itype.package == self.interfaces_package:
            return itype.name
        definition.dependencies.add(itype.package)
        return f"{itype.package}/{itype.name}"

    def _from_subcomponents(self, definition: InterfaceDefinition, classifier: EObject) -> bool:
        resolver = self._resolver
        impl = classifier
        if resolver is None:
            return False
        if not _model.is_a(impl, "ComponentImplementation"):
            impl = self._first_implementation(classifier)
            if impl is None:
                return False
        try:
            subs = [
                s for s in resolver.subcomponents(impl) if _model_enum(s.category) in ("data", "abstract")
            ]
        except RosaadlError:
            return False
        if not subs:
            return False
        names = naming.NameTable()
        lines: list[str] = []
        for sub in subs:
            sub_classifier = resolver.subcomponent_classifier(sub)
            if sub_classifier is None:
                self._warn(f"{_qualified(impl)}: field {sub.name!r} has no data classifier; written as bytes")
                base = "uint8[]"
            else:
                base = self._field_type_for(_qualified(sub_classifier), definition)
            dims = list(sub.arrayDimensions or ())
            if dims and not base.endswith("]"):
                base += "".join(f"[{d}]" if str(d).strip().isdigit() else "[]" for d in dims[:1])
            lines.append(f"{base} {names.unique(naming.field_name(sub.name or ''))}")
        definition.lines = lines
        return True

    def _first_implementation(self, ctype: EObject) -> EObject | None:
        unit = ctype.eContainer()
        wanted = (ctype.name or "").lower() + "."
        for candidate in getattr(unit, "classifiers", ()):
            if (candidate.name or "").lower().startswith(wanted) and _model.is_a(
                candidate, "ComponentImplementation"
            ):
                subs = self._resolver.subcomponents(candidate) if self._resolver else []
                if subs:
                    return candidate
        return None

    def _from_parameters(self, definition: InterfaceDefinition, classifier: EObject) -> bool:
        resolver = self._resolver
        if resolver is None:
            return False
        ctype = resolver.component_type(classifier) or classifier
        try:
            params = [f for f in resolver.features(ctype) if _model_enum(f.category) in ("parameter",)]
        except RosaadlError:
            return False
        if not params:
            return False
        request, response = naming.NameTable(), naming.NameTable()
        for param in params:
            param_classifier = resolver.feature_classifier(param)
            base = (
                self._field_type_for(_qualified(param_classifier), definition)
                if param_classifier is not None
                else "uint8[]"
            )
            direction = _model_enum(param.direction) or "in"
            if direction in ("in", "inOut"):
                definition.lines.append(f"{base} {request.unique(naming.field_name(param.name or ''))}")
            if direction in ("out", "inOut"):
                definition.response.append(f"{base} {response.unique(naming.field_name(param.name or ''))}")
        return True


def _opaque(definition: InterfaceDefinition, what: str) -> bool:
    definition.lines = [f"# {_comment(what)} has no known structure: its content as bytes.", "uint8[] data"]
    return True


def _comment(text: str) -> str:
    """Text safe for a one-line comment."""
    return " ".join(str(text).split()).replace("#", "")


def _type_key(qualified: str) -> tuple[str, str]:
    package, local = _local_type_name(qualified)
    return (package.lower(), f"{package}::{local}" if package else local)


def _qualified(element: EObject) -> str:
    return _model.qualified_name(element)


def _model_enum(value: object) -> str:
    return str(getattr(value, "name", value) or "")


def _is_instance(element: EObject) -> bool:
    return _model.is_a(element, "InstanceObject")

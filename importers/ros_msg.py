"""ROS message and service definitions (``.msg`` / ``.srv``): parsing, model fields and fixed sizes.

Syntax accepted (ROS 1, plus the ROS 2 additions):

* one field per line, ``TYPE NAME``; ``#`` starts a comment;
* primitive types ``bool byte char int8 uint8 int16 uint16 int32 uint32 int64 uint64 float32
  float64 string time duration`` (and ROS 2's ``wstring``);
* nested types ``pkg/Type`` (``pkg/msg/Type`` is read as ``pkg/Type``), a bare ``Type`` meaning
  the message's own package, and ``Header`` meaning ``std_msgs/Header`` as in ROS 1;
* arrays ``T[]`` (unbounded), ``T[N]`` (fixed) and ``T[<=N]`` (bounded, ROS 2); bounded strings
  ``string<=N`` (ROS 2), also as array elements (``string<=10[<=5]``);
* constants ``TYPE NAME=VALUE`` (for ``string`` constants the value is the rest of the line, as
  in ROS 1, ``#`` included); default values ``TYPE NAME VALUE`` (ROS 2);
* a service is a request and a response separated by a line ``---``.

**Data size convention.** :func:`data_size` gives the size in bytes of one message as ROS 1
serialises it, when that size is the same for every message of the type, and ``None`` otherwise:
``bool byte char int8 uint8`` 1, ``int16 uint16`` 2, ``int32 uint32 float32`` 4, ``int64 uint64
float64`` 8, ``time duration`` 8 (two 32-bit integers); a fixed array ``T[N]`` is ``N`` times
``T`` (ROS 1 writes no length for fixed arrays); a nested message adds its own size; constants
take no space. Any variable-length part makes the whole message unsized: ``string``/``wstring``
(bounded or not: the length prefix and the content vary), unbounded and bounded arrays, and
nested types whose definition is unknown. The few standard messages whose definitions are well
known (``std_msgs``, ``geometry_msgs`` basics, ``builtin_interfaces``) are built in, so that
``geometry_msgs/Point`` counts as 24 bytes.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import CollectedErrors, Location, ParseError

__all__ = [
    "PRIMITIVE_SIZES",
    "PRIMITIVE_TYPES",
    "STANDARD_DEFINITIONS",
    "RosMessageError",
    "FieldSpec",
    "MessageSpec",
    "ServiceSpec",
    "parse_field",
    "parse_msg",
    "parse_srv",
    "normalize_type",
    "data_size",
    "unsized_reason",
    "standard_message",
    "fields_to_model",
    "fill_message",
    "fill_service",
    "field_from_model",
    "message_data_size",
    "MEASURED_SIZE",
    "measured_sizes",
]

#: Serialised size in bytes of the fixed-size primitive types (ROS 1 wire format).
PRIMITIVE_SIZES: dict[str, int] = {
    "bool": 1,
    "byte": 1,
    "char": 1,
    "int8": 1,
    "uint8": 1,
    "int16": 2,
    "uint16": 2,
    "int32": 4,
    "uint32": 4,
    "float32": 4,
    "int64": 8,
    "uint64": 8,
    "float64": 8,
    "time": 8,
    "duration": 8,
}
_STRING_TYPES = frozenset({"string", "wstring"})
#: Every primitive type name (fixed-size ones and the strings).
PRIMITIVE_TYPES: frozenset[str] = frozenset(PRIMITIVE_SIZES) | _STRING_TYPES

_INT_RANGES = {
    "byte": (-(2**7), 2**8 - 1),
    "char": (-(2**7), 2**8 - 1),
    "int8": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}
_FLOATS = frozenset({"float32", "float64"})
_BOOL_LITERALS = frozenset({"true", "false", "True", "False", "1", "0"})

#: Definitions of a few standard ROS messages, for nested types that are not in a project.
STANDARD_DEFINITIONS: dict[str, str] = {
    "std_msgs/Bool": "bool data",
    "std_msgs/Byte": "byte data",
    "std_msgs/Char": "char data",
    "std_msgs/Int8": "int8 data",
    "std_msgs/UInt8": "uint8 data",
    "std_msgs/Int16": "int16 data",
    "std_msgs/UInt16": "uint16 data",
    "std_msgs/Int32": "int32 data",
    "std_msgs/UInt32": "uint32 data",
    "std_msgs/Int64": "int64 data",
    "std_msgs/UInt64": "uint64 data",
    "std_msgs/Float32": "float32 data",
    "std_msgs/Float64": "float64 data",
    "std_msgs/String": "string data",
    "std_msgs/Time": "time data",
    "std_msgs/Duration": "duration data",
    "std_msgs/Empty": "",
    "std_msgs/ColorRGBA": "float32 r\nfloat32 g\nfloat32 b\nfloat32 a",
    "std_msgs/Header": "uint32 seq\ntime stamp\nstring frame_id",
    "builtin_interfaces/Time": "int32 sec\nuint32 nanosec",
    "builtin_interfaces/Duration": "int32 sec\nuint32 nanosec",
    "geometry_msgs/Point": "float64 x\nfloat64 y\nfloat64 z",
    "geometry_msgs/Point32": "float32 x\nfloat32 y\nfloat32 z",
    "geometry_msgs/Vector3": "float64 x\nfloat64 y\nfloat64 z",
    "geometry_msgs/Quaternion": "float64 x\nfloat64 y\nfloat64 z\nfloat64 w",
    "geometry_msgs/Pose": "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation",
    "geometry_msgs/Pose2D": "float64 x\nfloat64 y\nfloat64 theta",
    "geometry_msgs/Transform": "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation",
    "geometry_msgs/Twist": "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular",
    "geometry_msgs/Accel": "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular",
    "geometry_msgs/Wrench": "geometry_msgs/Vector3 force\ngeometry_msgs/Vector3 torque",
    "geometry_msgs/Inertia": "float64 m\ngeometry_msgs/Vector3 com\nfloat64 ixx\nfloat64 ixy\nfloat64 ixz\n"
    "float64 iyy\nfloat64 iyz\nfloat64 izz",
    "geometry_msgs/PoseStamped": "Header header\ngeometry_msgs/Pose pose",
    "geometry_msgs/TwistStamped": "Header header\ngeometry_msgs/Twist twist",
    "geometry_msgs/PointStamped": "Header header\ngeometry_msgs/Point point",
}

_NAME = r"[A-Za-z][A-Za-z0-9_]*"
_TYPE_RE = re.compile(
    rf"(?P<base>{_NAME}(?:/{_NAME}){{0,2}})"
    r"(?:<=(?P<sbound>\d+))?"
    r"(?:\[(?:(?P<bounded><=)?(?P<length>\d+))?\])?"
)
_FIELD_NAME_RE = re.compile(_NAME)


class RosMessageError(CollectedErrors, ParseError):
    """One or more located problems in a message or service definition (``errors`` lists all)."""

    stage = "parse"


@dataclass(frozen=True)
class FieldSpec:
    """One field or constant of a message, as written (types normalised, see :func:`normalize_type`)."""

    name: str
    type: str
    is_array: bool = False
    array_length: int | None = None  # T[N]
    upper_bound: int | None = None  # T[<=N]
    string_bound: int | None = None  # string<=N
    constant: str | None = None  # TYPE NAME=VALUE
    default: str | None = None  # TYPE NAME VALUE (ROS 2)
    line: int | None = None
    column: int | None = None

    @property
    def is_constant(self) -> bool:
        return self.constant is not None

    @property
    def is_primitive(self) -> bool:
        return self.type in PRIMITIVE_TYPES

    @property
    def type_text(self) -> str:
        """The type as ROS writes it: ``uint8[4]``, ``string<=10[<=5]``, ``pkg/Type[]``."""
        text = self.type
        if self.string_bound is not None:
            text += f"<={self.string_bound}"
        if self.is_array:
            if self.array_length is not None:
                text += f"[{self.array_length}]"
            elif self.upper_bound is not None:
                text += f"[<={self.upper_bound}]"
            else:
                text += "[]"
        return text


@dataclass(frozen=True)
class MessageSpec:
    """A parsed message definition: its fields (constants included, in order)."""

    name: str | None = None
    package: str | None = None
    fields: tuple[FieldSpec, ...] = ()
    text: str = ""

    @property
    def full_name(self) -> str | None:
        if self.name is None:
            return None
        return f"{self.package}/{self.name}" if self.package else self.name

    @property
    def data_fields(self) -> tuple[FieldSpec, ...]:
        return tuple(f for f in self.fields if not f.is_constant)

    @property
    def constants(self) -> tuple[FieldSpec, ...]:
        return tuple(f for f in self.fields if f.is_constant)


@dataclass(frozen=True)
class ServiceSpec:
    """A parsed service definition: request and response parts."""

    name: str | None = None
    package: str | None = None
    request: MessageSpec = field(default_factory=MessageSpec)
    response: MessageSpec = field(default_factory=MessageSpec)
    text: str = ""


# --------------------------------------------------------------------------- parsing


def normalize_type(base: str, package: str | None = None) -> str:
    """``Header`` → ``std_msgs/Header``; ``pkg/msg/T`` → ``pkg/T``; bare ``T`` → ``package/T``."""
    if base in PRIMITIVE_TYPES:
        return base
    parts = base.split("/")
    if len(parts) == 3 and parts[1] in ("msg", "srv", "action"):
        return f"{parts[0]}/{parts[2]}"
    if len(parts) == 1:
        if base == "Header":
            return "std_msgs/Header"
        if package:
            return f"{package}/{base}"
    return base


def _error(message: str, filename: str | None, line: int | None, column: int | None, path: str | None):
    return ParseError(message, Location(file=filename, line=line, column=column, path=path))


def _split_comment(text: str) -> str:
    """Drop a ``#`` comment that is not inside a double- or single-quoted string."""
    quote = None
    for index, char in enumerate(text):
        if quote:
            if char == "\\":
                continue
            if char == quote:
                quote = None
        elif char in "\"'":
            quote = char
        elif char == "#":
            return text[:index]
    return text


def _check_constant(spec_type: str, value: str) -> str | None:
    """A reason why ``value`` is not a valid constant of ``spec_type`` (None when valid)."""
    if spec_type in _INT_RANGES:
        try:
            number = int(value, 0)
        except ValueError:
            return f"expected an integer constant for {spec_type}, found {value!r}"
        low, high = _INT_RANGES[spec_type]
        if not low <= number <= high:
            return f"constant {value} is out of range for {spec_type} ({low}..{high})"
    elif spec_type in _FLOATS:
        try:
            float(value)
        except ValueError:
            return f"expected a number constant for {spec_type}, found {value!r}"
    elif spec_type == "bool" and value not in _BOOL_LITERALS:
        return f"expected true or false for a bool constant, found {value!r}"
    return None


def parse_field(
    text: str,
    *,
    package: str | None = None,
    filename: str | None = None,
    line: int | None = None,
    column: int = 1,
    path: str | None = None,
) -> FieldSpec | None:
    """Parse one definition line (``int32[<=5] x``, ``int32 X=1``); ``None`` for blank/comment lines.

    ``column`` is the column of ``text``'s first character in its file, so that errors point at
    the right place. Raises :class:`rosaadl.errors.ParseError` with file, line and column.
    """
    stripped = text.lstrip()
    col = column + (len(text) - len(stripped))
    if not stripped or stripped.startswith("#"):
        return None
    match = _TYPE_RE.match(stripped)
    if not match or (match.end() < len(stripped) and not stripped[match.end()].isspace()):
        bad = stripped.split(None, 1)[0]
        raise _error(
            f"malformed field type {bad!r} (expected a ROS type such as int32, string, pkg/Type, "
            "uint8[], float64[3], int32[<=5], string<=10)",
            filename,
            line,
            col,
            path,
        )
    base = match.group("base")
    sbound = match.group("sbound")
    bracket = "[" in match.group(0)
    length = match.group("length")
    bounded = bool(match.group("bounded"))
    if sbound is not None and base not in _STRING_TYPES:
        raise _error(f"only string types can be bounded with <=, not {base!r}", filename, line, col, path)
    if bounded and length is None:
        raise _error("a bounded array needs its bound: T[<=N]", filename, line, col, path)
    rest = stripped[match.end() :]
    name_offset = match.end() + (len(rest) - len(rest.lstrip()))
    rest = rest.lstrip()
    name_match = _FIELD_NAME_RE.match(rest)
    if not name_match:
        shown = rest.split(None, 1)[0] if rest.strip() else "end of line"
        raise _error(
            f"expected a field name after type {match.group(0)!r}, found {shown!r}",
            filename,
            line,
            col + name_offset,
            path,
        )
    name = name_match.group(0)
    after = rest[name_match.end() :]
    after_col = col + name_offset + name_match.end()
    constant = default = None
    type_name = normalize_type(base, package)
    if after.lstrip().startswith("="):
        raw = after.lstrip()[1:]
        if bracket or base not in PRIMITIVE_TYPES:
            raise _error(
                f"constant {name!r} must have a primitive, non-array type (found {match.group(0)!r})",
                filename,
                line,
                col,
                path,
            )
        constant = raw.strip() if base in _STRING_TYPES else _split_comment(raw).strip()
        if base not in _STRING_TYPES and not constant:
            raise _error(f"constant {name!r} has no value after '='", filename, line, after_col, path)
        problem = _check_constant(base, constant)
        if problem:
            raise _error(problem, filename, line, after_col + 1, path)
    else:
        if after and not after[0].isspace() and not after.startswith("#"):
            raise _error(
                f"unexpected {after.split(None, 1)[0]!r} after field name {name!r}",
                filename,
                line,
                after_col,
                path,
            )
        value = _split_comment(after).strip()
        if value:
            default = value
            if not bracket and base in PRIMITIVE_TYPES and base not in _STRING_TYPES:
                problem = _check_constant(base, value)
                if problem:
                    raise _error(
                        problem.replace("constant", "default value"), filename, line, after_col + 1, path
                    )
            elif bracket and not value.startswith("["):
                raise _error(
                    f"the default value of array field {name!r} must be a list [..], found {value!r}",
                    filename,
                    line,
                    after_col + 1,
                    path,
                )
            elif base not in PRIMITIVE_TYPES:
                raise _error(
                    f"unexpected {value!r} after field {name!r} (nested types take no default value)",
                    filename,
                    line,
                    after_col + 1,
                    path,
                )
    return FieldSpec(
        name=name,
        type=type_name,
        is_array=bracket,
        array_length=int(length) if (length is not None and not bounded) else None,
        upper_bound=int(length) if bounded else None,
        string_bound=int(sbound) if sbound is not None else None,
        constant=constant,
        default=default,
        line=line,
        column=col,
    )


def _parse_lines(
    lines: Iterable[tuple[int, str]],
    package: str | None,
    filename: str | None,
    path: str | None,
    errors: list[ParseError],
) -> tuple[FieldSpec, ...]:
    fields: list[FieldSpec] = []
    seen: dict[str, FieldSpec] = {}
    for number, text in lines:
        try:
            spec = parse_field(text, package=package, filename=filename, line=number, path=path)
        except ParseError as exc:
            errors.append(exc)
            continue
        if spec is None:
            continue
        if spec.name in seen:
            errors.append(
                _error(
                    f"duplicate field name {spec.name!r} (first defined on line {seen[spec.name].line})",
                    filename,
                    number,
                    spec.column,
                    path,
                )
            )
            continue
        seen[spec.name] = spec
        fields.append(spec)
    return tuple(fields)


def _lines(text: str, first_line: int) -> list[tuple[int, str]]:
    return [(first_line + i, line) for i, line in enumerate(text.splitlines())]


def parse_msg(
    text: str,
    *,
    name: str | None = None,
    package: str | None = None,
    filename: str | None = None,
    path: str | None = None,
    first_line: int = 1,
) -> MessageSpec:
    """Parse a ``.msg`` definition; all problems are reported together in :class:`RosMessageError`."""
    errors: list[ParseError] = []
    fields = _parse_lines(_lines(text, first_line), package, filename, path, errors)
    if errors:
        raise RosMessageError(errors)
    return MessageSpec(name=name, package=package, fields=fields, text=text)


_SEPARATOR_RE = re.compile(r"^\s*---\s*(#.*)?$")


def parse_srv(
    text: str,
    *,
    name: str | None = None,
    package: str | None = None,
    filename: str | None = None,
    path: str | None = None,
    first_line: int = 1,
) -> ServiceSpec:
    """Parse a ``.srv`` definition (request ``---`` response)."""
    lines = _lines(text, first_line)
    separators = [i for i, (_, line) in enumerate(lines) if _SEPARATOR_RE.match(line)]
    if len(separators) != 1:
        where = lines[separators[1]][0] if len(separators) > 1 else (lines[-1][0] if lines else first_line)
        found = "none" if not separators else f"{len(separators)}"
        raise RosMessageError(
            [
                _error(
                    f"a service definition needs exactly one '---' line between request and response "
                    f"(found {found})",
                    filename,
                    where,
                    1,
                    path,
                )
            ]
        )
    cut = separators[0]
    errors: list[ParseError] = []
    request = _parse_lines(lines[:cut], package, filename, path, errors)
    response = _parse_lines(lines[cut + 1 :], package, filename, path, errors)
    if errors:
        raise RosMessageError(errors)
    req_text = "\n".join(line for _, line in lines[:cut])
    res_text = "\n".join(line for _, line in lines[cut + 1 :])
    return ServiceSpec(
        name=name,
        package=package,
        request=MessageSpec(
            name=f"{name}Request" if name else None, package=package, fields=request, text=req_text
        ),
        response=MessageSpec(
            name=f"{name}Response" if name else None, package=package, fields=response, text=res_text
        ),
        text=text,
    )


# --------------------------------------------------------------------------- sizes

Resolver = Callable[[str], "Sequence[FieldSpec] | MessageSpec | None"]


def standard_message(type_name: str) -> MessageSpec | None:
    """The built-in definition of a standard message (``geometry_msgs/Point``), or None."""
    text = STANDARD_DEFINITIONS.get(type_name)
    if text is None:
        return None
    package, _, name = type_name.partition("/")
    return parse_msg(text, name=name, package=package)


def _as_fields(found: Sequence[FieldSpec] | MessageSpec | None) -> Sequence[FieldSpec] | None:
    if found is None:
        return None
    if isinstance(found, MessageSpec):
        return found.fields
    return found


#: How deep message types may nest when their size is computed (deeper is not a real message).
_MAX_NESTING = 100


def _size(
    fields: Sequence[FieldSpec], resolve: Resolver | None, stack: tuple[str, ...]
) -> tuple[int | None, str | None]:
    total = 0
    for spec in fields:
        if spec.is_constant:
            continue
        if spec.is_array and spec.array_length is None:
            kind = "a bounded" if spec.upper_bound is not None else "an unbounded"
            return None, f"field {spec.name!r} is {kind} array ({spec.type_text})"
        if spec.type in _STRING_TYPES:
            return None, f"field {spec.name!r} is a {spec.type_text} (variable length)"
        if spec.type in PRIMITIVE_SIZES:
            element = PRIMITIVE_SIZES[spec.type]
        else:
            if spec.type in stack:
                return None, f"field {spec.name!r}: type {spec.type} contains itself"
            if len(stack) > _MAX_NESTING:
                return None, f"field {spec.name!r}: types nested more than {_MAX_NESTING} deep"
            nested = _as_fields(resolve(spec.type)) if resolve is not None else None
            if nested is None:
                std = standard_message(spec.type)
                nested = std.fields if std is not None else None
            if nested is None:
                return None, f"field {spec.name!r}: the definition of {spec.type} is not known"
            element, why = _size(nested, resolve, (*stack, spec.type))
            if element is None:
                return None, f"field {spec.name!r} ({spec.type}): {why}"
        total += element * (spec.array_length if spec.is_array else 1)
    return total, None


def data_size(spec: MessageSpec | Sequence[FieldSpec], resolve: Resolver | None = None) -> int | None:
    """Fixed serialised size in bytes (see the module docstring), or ``None`` when it varies.

    ``resolve(type_name)`` returns the fields (or :class:`MessageSpec`) of a nested type
    ``pkg/Type``; unknown types fall back to the built-in standard messages.
    """
    fields = spec.fields if isinstance(spec, MessageSpec) else spec
    name = spec.full_name if isinstance(spec, MessageSpec) else None
    return _size(fields, resolve, (name,) if name else ())[0]


def unsized_reason(spec: MessageSpec | Sequence[FieldSpec], resolve: Resolver | None = None) -> str | None:
    """Why :func:`data_size` is ``None`` for ``spec`` (``None`` when it has a fixed size)."""
    fields = spec.fields if isinstance(spec, MessageSpec) else spec
    name = spec.full_name if isinstance(spec, MessageSpec) else None
    return _size(fields, resolve, (name,) if name else ())[1]


# --------------------------------------------------------------------------- model


def fill_message(message: EObject, **where: Any) -> None:
    """Parse a ``rosmod.Message``'s ``definition`` into its ``fields`` (``where``: the keyword
    arguments of :func:`parse_msg` — package, filename, path). Raises :class:`RosMessageError`."""
    if message.definition:
        spec = parse_msg(message.definition, name=message.name, **where)
        message.fields.extend(fields_to_model(spec.fields))


def fill_service(service: EObject, **where: Any) -> None:
    """Parse a ``rosmod.Service``'s ``definition`` into its request and response fields."""
    if service.definition:
        spec = parse_srv(service.definition, name=service.name, **where)
        service.requestFields.extend(fields_to_model(spec.request.fields))
        service.responseFields.extend(fields_to_model(spec.response.fields))


def fields_to_model(fields: Iterable[FieldSpec]) -> list[EObject]:
    """``rosmod.Field`` objects for parsed fields (constants included, in order)."""
    out = []
    for spec in fields:
        out.append(
            model.new(
                "rosmod.Field",
                name=spec.name,
                type=spec.type,
                isArray=spec.is_array or None,
                arrayLength=spec.array_length,
                upperBound=spec.upper_bound,
                stringBound=spec.string_bound,
                constantValue=spec.constant,
                defaultValue=spec.default,
                line=spec.line,
                column=spec.column,
            )
        )
    return out


def _set_int(obj: EObject, name: str) -> int | None:
    return getattr(obj, name) if obj.eIsSet(name) else None


def field_from_model(obj: EObject) -> FieldSpec:
    """The :class:`FieldSpec` of a ``rosmod.Field`` (integer features that are not set read as None)."""
    return FieldSpec(
        name=obj.name or "",
        type=obj.type or "",
        is_array=bool(obj.isArray),
        array_length=_set_int(obj, "arrayLength"),
        upper_bound=_set_int(obj, "upperBound"),
        string_bound=_set_int(obj, "stringBound"),
        constant=obj.constantValue,
        default=obj.defaultValue,
        line=_set_int(obj, "line"),
        column=_set_int(obj, "column"),
    )


def message_data_size(message: EObject, project: EObject | None = None) -> int | None:
    """Fixed size in bytes of a ``rosmod.Message`` (nested types looked up in ``project``)."""
    index: dict[str, list[FieldSpec]] = {}
    if project is not None and project.software is not None:
        for package in project.software.packages:
            for msg in package.messages:
                index[f"{package.name}/{msg.name}"] = [field_from_model(f) for f in msg.fields]
    package = message.eContainer()
    own = f"{package.name}/{message.name}" if package is not None else message.name
    fields = [field_from_model(f) for f in message.fields]
    return _size(fields, index.get, (own,))[0]


#: The prefix of a ``rosmod.Project`` property giving a message type's measured size in bytes
#: (``Data_Size:std_msgs/String`` → ``"28"``), set by ``rosaadl import ros2-graph --measure``.
MEASURED_SIZE = "Data_Size:"


def measured_sizes(project: EObject | None) -> dict[str, int]:
    """The measured message sizes a project carries (:data:`MEASURED_SIZE`): type → bytes; a
    value that is not a non-negative integer is ignored."""
    found: dict[str, int] = {}
    for prop in project.properties if project is not None else ():
        key, value = prop.key or "", (prop.value or "").strip()
        if key.startswith(MEASURED_SIZE) and value.isdigit() and len(value) <= 12:
            found[key[len(MEASURED_SIZE) :]] = int(value)
    return found

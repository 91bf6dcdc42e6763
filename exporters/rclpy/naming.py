"""Names for generated ROS 2 code: identifiers, package, node, topic, message and field names.

Every name that reaches a file name, a Python identifier or a ROS name goes through this module,
whatever the model says: ``../../etc`` becomes ``etc``, ``class`` becomes ``class_``, ``caméra``
becomes ``camera`` and a name with no ASCII letter at all (``相机``) becomes a stable name made
from a hash of it (``n_4c7a0e2f``). :class:`NameTable` hands out unique names in a scope, in the
order they are asked for, so the same model always gives the same names.
"""

from __future__ import annotations

import hashlib
import keyword
import re
import sys
import unicodedata
from functools import lru_cache

__all__ = [
    "RESERVED_PACKAGES",
    "MAX_NAME",
    "ascii_words",
    "shorten",
    "identifier",
    "member_name",
    "snake",
    "camel",
    "package_name",
    "module_name",
    "node_name",
    "topic_token",
    "field_name",
    "constant_name",
    "message_name",
    "is_package_name",
    "is_message_name",
    "is_field_name",
    "NameTable",
]

#: Package names a generated package must never take: the packages generated code imports
#: or depends on, and Python's standard library (a package is also a Python package).
RESERVED_PACKAGES: frozenset[str] = frozenset(
    {
        "rclpy",
        "launch",
        "launch_ros",
        "std_msgs",
        "std_srvs",
        "sensor_msgs",
        "geometry_msgs",
        "nav_msgs",
        "tf2_msgs",
        "builtin_interfaces",
        "rosidl_default_generators",
        "rosidl_default_runtime",
        "ament_cmake",
        "ament_copyright",
        "ament_flake8",
        "ament_pep257",
        "setuptools",
        "pytest",
        "test",
        "tests",
    }
    | set(getattr(sys, "stdlib_module_names", ()))
)

_NON_WORD = re.compile(r"[^A-Za-z0-9]+")
_CAMEL_BOUNDARY = re.compile(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])")
_PACKAGE_RE = re.compile(r"^[a-z][a-z0-9]*(_[a-z0-9]+)*$")
_MESSAGE_RE = re.compile(r"^[A-Z][A-Za-z0-9]*$")
_FIELD_RE = re.compile(r"^[a-z][a-z0-9]*(_[a-z0-9]+)*$")
#: Attribute and method names of rclpy's ``Node`` that generated members must not shadow.
_NODE_MEMBERS = frozenset(
    {
        "clients",
        "context",
        "default_callback_group",
        "executor",
        "guards",
        "handle",
        "publishers",
        "services",
        "subscriptions",
        "timers",
        "waitables",
    }
)


def _digest(text: str) -> str:
    return hashlib.sha1(text.encode("utf-8", "surrogatepass")).hexdigest()[:8]


#: Latin letters that Unicode does not decompose into an ASCII letter and an accent.
_LATIN = str.maketrans(
    {
        "ß": "ss",
        "ẞ": "SS",
        "æ": "ae",
        "Æ": "AE",
        "œ": "oe",
        "Œ": "OE",
        "ø": "o",
        "Ø": "O",
        "đ": "d",
        "Đ": "D",
        "ð": "d",
        "Ð": "D",
        "ł": "l",
        "Ł": "L",
        "þ": "th",
        "Þ": "Th",
        "ı": "i",
    }
)


def ascii_words(text: str) -> list[str]:
    return list(_ascii_words(text or ""))


@lru_cache(maxsize=8192)
def _ascii_words(text: str) -> tuple[str, ...]:
    """The ASCII words of ``text``: accents dropped, camel case and punctuation split.

    >>> ascii_words("../../etc")
    ['etc']
    >>> ascii_words("imagePublisher.xu4_a15")
    ['image', 'Publisher', 'xu4', 'a15']
    >>> ascii_words("Größe ünïcødé")
    ['Grosse', 'unicode']
    """
    latin = text.translate(_LATIN)
    folded = unicodedata.normalize("NFKD", latin).encode("ascii", "ignore").decode("ascii")
    words: list[str] = []
    for chunk in _NON_WORD.split(folded):
        if chunk:
            words.extend(w for w in _CAMEL_BOUNDARY.split(chunk) if w)
    return tuple(words)


#: Longest name made from a model name (longer ones keep their start and a hash of the whole),
#: so that generated lines stay within ROS 2's line length.
MAX_NAME = 40


def shorten(name: str, limit: int = MAX_NAME, *, separator: str = "_") -> str:
    """``name`` itself when it is at most ``limit`` characters, else its start and a hash of it."""
    if len(name) <= limit:
        return name
    head = name[: max(1, limit - 9)].rstrip("_")
    return f"{head}{separator}{_digest(name)}"


def snake(text: str, *, fallback: str = "n", limit: int = MAX_NAME) -> str:
    """``lower_snake_case`` made of the ASCII words of ``text``; never empty, never starts with a digit,
    at most ``limit`` characters.

    A text with no ASCII letter or digit gives ``<fallback>_<hash>``, the same for the same text.
    """
    words = [w.lower() for w in ascii_words(text)]
    name = "_".join(words)
    if not name:
        return f"{fallback}_{_digest(text)}"
    if name[0].isdigit():
        name = f"{fallback}_{name}"
    return shorten(name, limit)


def camel(text: str, *, fallback: str = "N", limit: int = MAX_NAME) -> str:
    """``CamelCase`` made of the ASCII words of ``text`` (``video_stream.rgb`` → ``VideoStreamRgb``)."""
    words = ascii_words(text)
    name = "".join(w[:1].upper() + w[1:] for w in words)
    if not name:
        return f"{fallback}{_digest(text)}"
    if name[0].isdigit():
        name = f"{fallback}{name}"
    return shorten(name, limit, separator="X")


def identifier(text: str, *, fallback: str = "n") -> str:
    """A valid Python identifier in snake case that is not a keyword or a builtin."""
    name = snake(text, fallback=fallback)
    if keyword.iskeyword(name) or keyword.issoftkeyword(name):
        name += "_"
    return name


def member_name(text: str, *, fallback: str = "n") -> str:
    """An identifier that also does not shadow a member of rclpy's ``Node``."""
    name = identifier(text, fallback=fallback)
    if name in _NODE_MEMBERS:
        name += "_"
    return name


def package_name(text: str, *, fallback: str = "pkg") -> str:
    """A ROS package name (REP 144: ``[a-z][a-z0-9_]*``, no ``__``, at least two characters)
    that is also a Python package name and does not take a reserved name."""
    name = snake(text, fallback=fallback)
    if name[0].isdigit() or name[0] == "_":
        name = f"{fallback}_{name}"
    if len(name) < 2:
        name = f"{name}_{fallback}"
    if name in RESERVED_PACKAGES or keyword.iskeyword(name) or keyword.issoftkeyword(name):
        name = f"{name}_{fallback}"
    return name


def module_name(text: str, *, fallback: str = "node") -> str:
    """A Python module name (snake case, not a keyword, not a standard-library module)."""
    name = identifier(text, fallback=fallback).rstrip("_")
    if name in RESERVED_PACKAGES or keyword.iskeyword(name) or keyword.issoftkeyword(name):
        name = f"{name}_{fallback}"
    return name


def node_name(text: str, *, fallback: str = "node") -> str:
    """A ROS node name: ``[a-z_][a-z0-9_]*`` (we also keep it lower case and free of ``__``)."""
    return snake(text, fallback=fallback)


def topic_token(text: str, *, fallback: str = "topic") -> str:
    """One token of a ROS topic or service name."""
    return snake(text, fallback=fallback)


def field_name(text: str, *, fallback: str = "field") -> str:
    """A ROS 2 message field name (``[a-z][a-z0-9_]*``, no ``__``, no trailing ``_``), not a keyword."""
    name = snake(text, fallback=fallback)
    if name[0].isdigit():
        name = f"{fallback}_{name}"
    if keyword.iskeyword(name) or keyword.issoftkeyword(name):
        name = f"{name}_value"
    return name


def constant_name(text: str, *, fallback: str = "CONSTANT") -> str:
    """A ROS 2 message constant name (``[A-Z][A-Z0-9_]*``)."""
    name = snake(text, fallback=fallback.lower()).upper()
    if not name[0].isalpha():
        name = f"{fallback}_{name}"
    return name


def message_name(text: str, *, fallback: str = "Msg") -> str:
    """A ROS 2 message or service type name (``[A-Z][A-Za-z0-9]*``)."""
    return camel(text, fallback=fallback)


def is_package_name(text: str) -> bool:
    return bool(_PACKAGE_RE.match(text or ""))


def is_message_name(text: str) -> bool:
    return bool(_MESSAGE_RE.match(text or ""))


def is_field_name(text: str) -> bool:
    return bool(_FIELD_RE.match(text or "")) and not keyword.iskeyword(text)


class NameTable:
    """Unique names in one scope: the first asker gets the name, later ones ``name_2``, ``name_3``…

    ``reserve`` takes names that must not be handed out (imports, members of a base class).
    Suffixes use ``separator`` (``_`` for snake case, ``""`` for camel case).
    """

    def __init__(self, reserved: set[str] | frozenset[str] = frozenset(), *, separator: str = "_") -> None:
        self._taken: set[str] = {r.lower() for r in reserved}
        self._separator = separator

    def reserve(self, name: str) -> None:
        self._taken.add(name.lower())

    def unique(self, name: str) -> str:
        candidate = name
        count = 1
        while candidate.lower() in self._taken:
            count += 1
            candidate = f"{name}{self._separator}{count}"
        self._taken.add(candidate.lower())
        return candidate

    def __contains__(self, name: str) -> bool:
        return name.lower() in self._taken

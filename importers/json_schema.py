"""A JSON value checked against a JSON Schema (the subset rosaadl's own schemas use), and the line
each value of a JSON text starts on, so that a problem is reported at its JSON path and line.

:func:`schema_problems` walks a parsed value and its schema (draft 2020-12 keywords ``type``,
``const``, ``enum``, ``required``, ``properties``, ``additionalProperties: false``, ``items``,
``minimum``, ``exclusiveMinimum``, ``maximum``, ``minLength`` and local ``$ref`` to
``#/$defs/...``; other keywords are documentation) and yields ``(json path, message)`` for
every violation, in document order.
As JSON Schema says, a boolean is not a number and an integer is a number whose value is whole.
:func:`value_lines` gives, for a text :func:`json.loads` accepted, the line where each value at
a JSON path (``$.threads[2].dispatches``) starts.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from typing import Any

__all__ = ["schema_problems", "value_lines"]

_TYPE_CHECKS = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "null": lambda v: v is None,
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "integer": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool) and float(v).is_integer(),
}


def _resolve(schema: dict[str, Any], root: dict[str, Any]) -> dict[str, Any]:
    ref = schema.get("$ref")
    if ref is None:
        return schema
    if not ref.startswith("#/"):
        raise ValueError(f"only local $ref are supported, not {ref!r}")
    target: Any = root
    for part in ref[2:].split("/"):
        target = target[part]
    return _resolve(target, root)


def _kind(value: Any) -> str:
    if isinstance(value, bool):
        return "boolean"
    if value is None:
        return "null"
    for name in ("object", "array", "string", "integer", "number"):
        if _TYPE_CHECKS[name](value):
            return name
    return type(value).__name__


def schema_problems(
    value: Any, schema: dict[str, Any], path: str = "$", root: dict | None = None
) -> Iterator[tuple[str, str]]:
    """Every ``(json path, message)`` where ``value`` breaks ``schema`` (``root``: the schema
    whose ``$defs`` local references name; ``schema`` itself by default)."""
    root = schema if root is None else root
    schema = _resolve(schema, root)
    types = schema.get("type")
    if types is not None:
        allowed = [types] if isinstance(types, str) else list(types)
        if not any(_TYPE_CHECKS[t](value) for t in allowed):
            yield path, f"expected {' or '.join(allowed)}, found {_kind(value)}"
            return
    if "const" in schema and (value != schema["const"] or _kind(value) != _kind(schema["const"])):
        yield path, f"expected {json.dumps(schema['const'])}, found {json.dumps(value)}"
        return
    if "enum" in schema and value not in schema["enum"]:
        yield (
            path,
            f"expected one of {', '.join(json.dumps(e) for e in schema['enum'])}, found {json.dumps(value)}",
        )
        return
    if _TYPE_CHECKS["number"](value):
        if "minimum" in schema and value < schema["minimum"]:
            yield path, f"{value} is below the minimum {schema['minimum']}"
        if "exclusiveMinimum" in schema and value <= schema["exclusiveMinimum"]:
            yield path, f"{value} is not above {schema['exclusiveMinimum']}"
        if "maximum" in schema and value > schema["maximum"]:
            yield path, f"{value} is above the maximum {schema['maximum']}"
    if isinstance(value, str) and len(value) < schema.get("minLength", 0):
        yield path, f"a string of at least {schema['minLength']} characters is expected"
    if isinstance(value, dict):
        for name in schema.get("required", ()):
            if name not in value:
                yield path, f"missing {name!r}"
        properties = schema.get("properties", {})
        for name, item in value.items():
            where = (
                f"{path}.{name}"
                if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name)
                else f"{path}[{json.dumps(name)}]"
            )
            if name in properties:
                yield from schema_problems(item, properties[name], where, root)
            elif schema.get("additionalProperties") is False:
                yield where, f"unknown member {name!r} (expected some of: {', '.join(properties)})"
    if isinstance(value, list) and "items" in schema:
        for index, item in enumerate(value):
            yield from schema_problems(item, schema["items"], f"{path}[{index}]", root)


# =============================================================================== lines

_TOKEN = re.compile(
    r'\s*(?:(?P<open>[\[{])|(?P<close>[\]}])|(?P<comma>,)|(?P<colon>:)|(?P<string>"(?:[^"\\]|\\.)*")|(?P<scalar>[^\s,:\[\]{}"]+))',
    re.DOTALL,
)


def value_lines(text: str) -> dict[str, int]:
    """JSON path → the 1-based line its value starts on, for a ``text`` that is valid JSON.

    Linear in the text; paths are spelled as :func:`schema_problems` spells them.
    """
    lines: dict[str, int] = {}
    stack: list[list[Any]] = []  # [kind, path, next index or pending key, expecting key]
    line = 1
    position = 0
    key_path: str | None = None
    root_done = False
    for match in _TOKEN.finditer(text):
        line += text.count("\n", position, match.start(match.lastgroup or 0))
        position = match.start(match.lastgroup or 0)
        kind = match.lastgroup
        if kind in ("comma", "colon"):
            continue
        if kind == "close":
            stack.pop()
            continue
        # a key of an object, or a value
        if stack and stack[-1][0] == "object" and stack[-1][3]:
            name = json.loads(match.group("string"))
            parent = stack[-1][1]
            plain = re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name)
            key_path = f"{parent}.{name}" if plain else f"{parent}[{json.dumps(name)}]"
            stack[-1][3] = False
            continue
        if not stack:
            if root_done:
                break
            here = "$"
            root_done = True
        elif stack[-1][0] == "array":
            here = f"{stack[-1][1]}[{stack[-1][2]}]"
            stack[-1][2] += 1
        else:
            here = key_path or stack[-1][1]
            stack[-1][3] = True
        lines.setdefault(here, line)
        if kind == "open":
            stack.append(
                ["object" if match.group("open") == "{" else "array", here, 0, match.group("open") == "{"]
            )
    return lines

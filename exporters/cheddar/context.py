"""What the Cheddar writer knows about the instance it exports, and how a value becomes text.

:class:`ExportContext` is the state every step of an export shares: the root instance, the
time unit and format asked for, the warnings and the problems found so far (an export with
problems is refused with all of them listed), and the property values of each instance object
(:class:`Props`, read once per object). :meth:`~ExportContext.text` turns a property value into
the text of a Cheddar field, exactly or not at all: a time that is not a whole number of the
unit is a problem, never a rounding.
"""

from __future__ import annotations

import logging
from fractions import Fraction
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, Location, RosaadlError
from rosaadl.importers.cheddar.vocabulary import CP, Field
from rosaadl.properties import EnumLiteral, Range, python_value
from rosaadl.units import Quantity

__all__ = ["Props", "ExportContext", "instance_objects", "category_of", "component_of", "thread_of"]

log = logging.getLogger("rosaadl.exporters.cheddar")

_TIME_KINDS = ("time", "capacity")


class Props:
    """The property values an instance object holds, by qualified and by short name."""

    __slots__ = ("obj", "_by_name")

    def __init__(self, obj: EObject) -> None:
        self.obj = obj
        self._by_name: dict[str, EObject] = {}
        for assoc in obj.ownedPropertyAssociations:
            # instance objects hold resolved values: no applies-to (instance-model.md)
            modal = assoc.ownedValues
            if not modal:
                continue
            name = (assoc.property or "").lower()
            if len(modal) == 1:
                value = modal[0].value
            else:  # the value outside any mode
                value = next((m.value for m in modal if not m.inModes), modal[0].value)
            self._by_name[name] = value
            short = name.rpartition("::")[2]
            self._by_name.setdefault("::" + short, value)

    def raw(self, name: str) -> EObject | None:
        key = name.lower()
        value = self._by_name.get(key)
        if value is None and "::" in key:
            # an association written without its property set (``Period``)
            value = self._by_name.get(key.rpartition("::")[2])
        if value is None and "::" not in key:
            value = self._by_name.get("::" + key)
        return value

    def get(self, name: str) -> Any:
        value = self.raw(name)
        return python_value(value) if value is not None else None

    def has(self, name: str) -> bool:
        return self.raw(name) is not None


def instance_objects(obj: EObject) -> list[EObject]:
    """``obj`` and the component and connection instances below it, in the order the export
    follows: each component, then its subcomponents (depth first), then the connections it owns.

    :func:`rosaadl.model.component_instances` gives the same components in the same order; this
    walk also places every connection after the subtree of its owner, which fixes the order of
    the buffers, messages and dependencies written for them."""
    out: list[EObject] = []
    stack: list[tuple[EObject, bool]] = [(obj, False)]
    while stack:
        current, done = stack.pop()
        if done:
            out.extend(current.connectionInstances)
            continue
        out.append(current)
        stack.append((current, True))
        stack.extend((child, False) for child in reversed(current.componentInstances))
    return out


def category_of(obj: EObject | None) -> str | None:
    """The category of a component instance (``thread``, ``processor``, ...); None for anything else."""
    if obj is None or not model.is_a(obj, "ComponentInstance") or obj.category is None:
        return None
    return obj.category.name


def component_of(end: EObject | None) -> EObject | None:
    """The component instance a connection end is (or belongs to)."""
    current = end
    while current is not None and not model.is_a(current, "ComponentInstance"):
        current = current.eContainer()
    return current


def thread_of(end: EObject | None) -> EObject | None:
    """The thread a connection end belongs to, or None."""
    component = component_of(end)
    return component if category_of(component) == "thread" else None


class ExportContext:
    """The shared state of one export (see the module docstring)."""

    def __init__(self, root: EObject, unit: str, version: int, diagnostics: list[Diagnostic]) -> None:
        self.root = root
        self.unit = unit
        self.version = version
        self.diagnostics = diagnostics
        self.problems: list[str] = []
        self.time_problems: list[str] = []
        self.cache: dict[int, Props] = {}
        self.everything = instance_objects(root)
        self.connections = [obj for obj in self.everything if model.is_a(obj, "ConnectionInstance")]
        self.order = {id(obj): i for i, obj in enumerate(self.everything)}

    def props(self, obj: EObject) -> Props:
        """The property values of ``obj`` (read once)."""
        found = self.cache.get(id(obj))
        if found is None:
            found = self.cache[id(obj)] = Props(obj)
        return found

    def path(self, obj: EObject) -> str:
        """The instance path of ``obj`` below the root."""
        full = model.instance_path(obj)
        prefix = model.instance_path(self.root) + "."
        return full[len(prefix) :] if full.startswith(prefix) else full

    def name(self, obj: EObject) -> str:
        """The Cheddar name of ``obj``: its ``Cheddar_Name``, else its path below the root."""
        own = self.props(obj).get(CP + "Cheddar_Name")
        return own if isinstance(own, str) and own != "" else self.path(obj)

    def imported(self, obj: EObject) -> bool:
        """Was ``obj`` read from a Cheddar file (it has a ``Cheddar_Name``)?"""
        return self.props(obj).has(CP + "Cheddar_Name")

    def ident(self, obj: EObject, prop: str = CP + "Cheddar_Id") -> str | None:
        """The Cheddar id ``obj`` was read with, or None."""
        value = self.props(obj).get(prop)
        return value if isinstance(value, str) and value else None

    def warn(self, obj: EObject | None, message: str) -> None:
        """A warning about ``obj``, in the diagnostics and the log."""
        where = Location(path=model.instance_path(obj)) if obj is not None else Location()
        diagnostic = Diagnostic("warning", message, where)
        self.diagnostics.append(diagnostic)
        log.warning("%s", diagnostic)

    def problem(self, obj: EObject | None, message: str) -> None:
        """Something that keeps the model from being written (the export is refused)."""
        where = model.instance_path(obj) if obj is not None else model.instance_path(self.root)
        self.problems.append(f"{where}: {message}")

    def time_text(self, obj: EObject, prop: str, value: Any) -> str | None:
        """A time value as a whole number of ``self.unit`` (problems are collected)."""
        if isinstance(value, Range):
            value = value.maximum
        if isinstance(value, Quantity):
            if value.unit is None:
                self.time_problems.append(
                    f"{model.instance_path(obj)}: {prop} = {value.value} has no time unit"
                )
                return None
            try:
                converted = value.to(self.unit)
            except RosaadlError as exc:
                self.time_problems.append(f"{model.instance_path(obj)}: {prop}: {exc.message}")
                return None
            exact = Fraction(converted) if not isinstance(converted, float) else Fraction(str(converted))
            if exact.denominator != 1:
                self.time_problems.append(
                    f"{model.instance_path(obj)}: {prop} = {value} is not a whole number of {self.unit} "
                    f"({float(exact):g} {self.unit})"
                )
                return None
            if exact < 0:
                self.time_problems.append(f"{model.instance_path(obj)}: {prop} = {value} is negative")
                return None
            return str(int(exact))
        if isinstance(value, int) and not isinstance(value, bool):
            self.time_problems.append(f"{model.instance_path(obj)}: {prop} = {value} has no time unit")
            return None
        self.problem(obj, f"{prop} is not a time value ({value!r})")
        return None

    def text(self, obj: EObject, spec: Field, value: Any) -> str | None:
        """The XML text of one field value (None when it cannot be written)."""
        kind = spec.kind
        if kind in _TIME_KINDS:
            return self.time_text(obj, spec.prop, value)
        if kind == "int":
            if isinstance(value, Quantity):
                value = value.value
            if isinstance(value, bool) or not isinstance(value, int):
                self.problem(obj, f"{spec.prop} is not a whole number ({value!r})")
                return None
            if value < 0:
                self.problem(obj, f"{spec.prop} = {value} is negative; Cheddar takes natural numbers")
                return None
            return str(value)
        if kind == "real":
            number = value.value if isinstance(value, Quantity) else value
            if not isinstance(number, (int, float)) or isinstance(number, bool):
                self.problem(obj, f"{spec.prop} is not a number ({value!r})")
                return None
            return str(int(number)) if float(number).is_integer() else repr(float(number))
        if kind == "bool":
            return "TRUE" if value else "FALSE"
        if kind == "preemptive":
            return "PREEMPTIVE" if value else "NOT_PREEMPTIVE"
        if kind.startswith("enum:"):
            return str(value).upper()
        if isinstance(value, EnumLiteral):
            return value.name
        return str(value)

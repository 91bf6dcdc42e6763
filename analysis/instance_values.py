"""Reading an instance for the analyses: system operation modes, exact property values, bindings.

* :class:`SystemMode` / :func:`system_modes`: a system operation mode and what exists in it
  (components whose ``in modes`` exclude it, connections outside it);
* :class:`PropertyReader`: property values of instance objects as exact numbers in a unit, in a
  system mode, with located :class:`~rosaadl.errors.Diagnostic` s instead of exceptions (once
  per object and message), cached for the reader's life;
* :class:`ProcessorBindings` / :func:`bound_processor`: ``Actual_Processor_Binding`` followed
  through virtual processors to the physical processor, as OSATE's ``InstanceModelUtil``.

Every analysis module reads the instance through these, so that they agree on units, modes and
what a binding means.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from rosaadl.errors import Diagnostic, Location, ModelError
from rosaadl.model import instance_path, is_a
from rosaadl.properties import EnumLiteral, Range, Reference, own_association, python_value
from rosaadl.units import Quantity, standard_units

__all__ = [
    "SystemMode",
    "system_modes",
    "instance_root",
    "category_of",
    "relative_path",
    "PropertyReader",
    "ProcessorBindings",
    "bound_processor",
]

# Units that the standard unit system does not know: SEI's instruction volumes (to MIPD) and
# the per-second rate unit of SEI::Data_Rate / SEI::Message_Rate.
_MIPD = {"ipd": Fraction(1, 1_000_000), "kipd": Fraction(1, 1000), "mipd": Fraction(1)}


def instance_root(source: Any) -> Any:
    """The ``SystemInstance`` of ``source`` (an ``AadlModel`` holding instances, or an instance)."""
    if source is None or not hasattr(source, "eClass"):
        raise ModelError(f"expected an instance model, got {type(source).__name__}")
    if is_a(source, "AadlModel"):
        if not source.instances:
            raise ModelError("the model has no system instance")
        return source.instances[0]
    if not is_a(source, "aadl.ComponentInstance"):
        raise ModelError(f"expected an instance model, got a {source.eClass.name}")
    return source


def category_of(obj: Any) -> str:
    """The category literal name of a component or feature instance (``virtualProcessor``)."""
    value = getattr(obj, "category", None)
    return getattr(value, "name", str(value or ""))


def relative_path(obj: Any) -> str:
    """The instance path without the root's segment (OSATE's ``getComponentInstancePath``)."""
    path = instance_path(obj)
    head, dot, rest = path.partition(".")
    return rest if dot else path


def _component_of(obj: Any) -> Any:
    current = obj
    while current is not None and not hasattr(current, "componentInstances"):
        current = current.eContainer()
    return current


def _exact(number: Any) -> Fraction | None:
    if isinstance(number, bool):
        return None
    if isinstance(number, Fraction):
        return number
    if isinstance(number, int):
        return Fraction(number)
    if isinstance(number, float):
        if not math.isfinite(number):
            return None
        return Fraction(repr(number))  # the decimal as written, not its binary rounding
    return None


@dataclass(frozen=True)
class SystemMode:
    """A system operation mode: the mode instances that are current in it.

    ``label`` is OSATE's printable form, ``(theBus.m1, VB3.z1)``, empty for a model without
    modes.
    """

    name: str
    modes: tuple[Any, ...] = ()
    _owners: dict[int, Any] = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for mode in self.modes:
            owner = mode.eContainer()
            if owner is not None:
                self._owners[id(owner)] = mode

    @property
    def label(self) -> str:
        if not self.modes:
            return ""
        return "(" + ", ".join(relative_path(m) for m in self.modes) + ")"

    def current_mode(self, component: Any) -> Any | None:
        """The mode instance of ``component`` that is current in this system mode (None: no modes)."""
        return self._owners.get(id(component))

    def active(self, obj: Any) -> bool:
        """Whether a component, feature or connection instance exists in this system mode."""
        if obj is None:
            return True
        if hasattr(obj, "inSystemOperationModes") and not hasattr(obj, "componentInstances"):
            soms = list(obj.inSystemOperationModes)
            return not soms or not self.modes or any(s.lower() == self.name.lower() for s in soms)
        current = _component_of(obj)
        while current is not None and hasattr(current, "componentInstances"):
            in_modes = list(getattr(current, "inModes", None) or [])
            parent = current.eContainer()
            if in_modes and parent is not None:
                mode = self.current_mode(parent)
                if mode is not None:
                    name = (mode.name or mode.mode or "").lower()
                    if all(m.lower() != name for m in in_modes):
                        return False
            current = parent
        return True

    def mode_names_for(self, obj: Any) -> set[str]:
        """Names of the current modes of ``obj``'s component and of its ancestors."""
        names: set[str] = set()
        current = _component_of(obj)
        while current is not None:
            mode = self.current_mode(current)
            if mode is not None:
                names.add((mode.name or mode.mode or "").lower())
            current = current.eContainer()
        return names


def system_modes(root: Any) -> list[SystemMode]:
    """The system operation modes of an instance, in order (one empty mode when it has none)."""
    soms = list(getattr(root, "systemOperationModes", None) or [])
    result = [SystemMode(som.name or f"som_{i}", tuple(som.currentModes)) for i, som in enumerate(soms)]
    return result or [SystemMode("No Modes")]


class PropertyReader:
    """Reads property values of instance objects exactly, in a unit and a system mode, and
    collects located diagnostics instead of raising."""

    def __init__(self, diagnostics: list[Diagnostic] | None = None) -> None:
        self.units = standard_units()
        self.diagnostics: list[Diagnostic] = diagnostics if diagnostics is not None else []
        self._seen: set[tuple[str, str, str]] = set()
        self._cache: dict[tuple[int, str, str], tuple[Any, Any]] = {}

    # ------------------------------------------------------------------ diagnostics

    def report(self, severity: str, message: str, obj: Any) -> None:
        """Add a diagnostic on ``obj`` (once per severity, object and message)."""
        path = instance_path(obj) if obj is not None and hasattr(obj, "eClass") else ""
        key = (severity, path, message)
        if key in self._seen:
            return
        self._seen.add(key)
        self.diagnostics.append(Diagnostic(severity, message, Location(path=path or None)))

    # ------------------------------------------------------------------ raw values

    def value(self, obj: Any, name: str, mode: SystemMode | None = None) -> Any:
        """The Python value of property ``name`` on ``obj`` (its value in ``mode`` when modal).
        Values are cached for the reader's life: analyses do not change the model they read."""
        key = (id(obj), name.lower(), mode.name if mode is not None and mode.modes else "")
        if key in self._cache:
            return self._cache[key][1]
        value = self._value(obj, name, mode)
        self._cache[key] = (obj, value)  # holding obj keeps its id from being reused
        return value

    def _value(self, obj: Any, name: str, mode: SystemMode | None) -> Any:
        try:
            assoc = own_association(obj, name)
            if assoc is None:
                return None
            expr = None
            default = None
            wanted = mode.mode_names_for(obj) if mode is not None and mode.modes else set()
            for modal in assoc.ownedValues:
                in_modes = [m.lower() for m in (modal.inModes or [])]
                if not in_modes:
                    if default is None:
                        default = modal.value
                elif wanted and any(m in wanted for m in in_modes):
                    expr = modal.value
                    break
            if expr is None:
                expr = default
            if expr is None and assoc.ownedValues and not wanted:
                expr = assoc.ownedValues[0].value
            return python_value(expr)
        except ModelError as exc:
            self.report("error", f"property {name}: {exc.message}", obj)
            return None

    def number(
        self,
        obj: Any,
        name: str,
        unit: str | None = None,
        mode: SystemMode | None = None,
        *,
        part: str = "max",
        value: Any = None,
    ) -> Fraction | None:
        """The value of ``name`` as an exact number, converted to ``unit`` (None when absent or
        unusable, with a diagnostic for the latter). Ranges give their ``part`` (max or min)."""
        raw = value if value is not None else self.value(obj, name, mode)
        if raw is None:
            return None
        return self.convert(obj, name, raw, unit, part=part)

    def convert(
        self, obj: Any, name: str, raw: Any, unit: str | None, *, part: str = "max"
    ) -> Fraction | None:
        if isinstance(raw, Range):
            raw = raw.maximum if part == "max" else raw.minimum
        if isinstance(raw, Quantity):
            number = _exact(raw.value)
            if number is None:
                self.report("error", f"{name} is not a finite number", obj)
                return None
            if unit is None or raw.unit is None:
                return number
            literal = raw.unit.lower()
            if unit.lower() in _MIPD and literal in _MIPD:
                return number * _MIPD[literal] / _MIPD[unit.lower()]
            if unit.lower() == "persecond" and literal == "persecond":
                return number
            try:
                return number * self.units.factor(raw.unit, unit)
            except ModelError as exc:
                self.report("error", f"{name}: {exc.message}", obj)
                return None
        number = _exact(raw)
        if number is None:
            self.report("error", f"{name} is not a number (got {raw!r})", obj)
            return None
        if unit is not None and unit.lower() not in ("persecond",):
            self.report("warning", f"{name} = {raw} has no unit; read as {unit}", obj)
        return number

    def targets(self, obj: Any, name: str, mode: SystemMode | None = None) -> list[Any] | None:
        """Resolved instance objects of a reference (list) property; None when it is not set.
        References that do not resolve are reported as warnings and left out."""
        value = self.value(obj, name, mode)
        if value is None:
            return None
        items = value if isinstance(value, list) else [value]
        result = []
        for item in items:
            if isinstance(item, Reference):
                self.report("warning", f"{name} refers to {item.path}, which does not resolve", obj)
            elif item is not None and hasattr(item, "eClass"):
                result.append(item)
        return result

    def flag(self, obj: Any, name: str, mode: SystemMode | None = None) -> bool:
        value = self.value(obj, name, mode)
        return value is True

    def enum(self, obj: Any, name: str, mode: SystemMode | None = None) -> str | None:
        value = self.value(obj, name, mode)
        if isinstance(value, EnumLiteral):
            return value.name
        if isinstance(value, str):
            return value
        return None

    # ------------------------------------------------------------------ common properties

    def seconds(
        self, obj: Any, name: str, mode: SystemMode | None = None, *, part: str = "max"
    ) -> Fraction | None:
        return self.number(obj, name, "sec", mode, part=part)

    def mips_capacity(self, obj: Any, mode: SystemMode | None = None) -> Fraction:
        """``SEI::MIPSCapacity``, else ``Timing_Properties::Processor_Capacity``, in MIPS (0: none)."""
        capacity = self.number(obj, "SEI::MIPSCapacity", "MIPS", mode)
        if capacity is None:
            capacity = self.number(obj, "Timing_Properties::Processor_Capacity", "MIPS", mode)
        return capacity or Fraction(0)

    def mips_budget(self, obj: Any, mode: SystemMode | None = None) -> Fraction:
        return self.number(obj, "SEI::MIPSBudget", "MIPS", mode) or Fraction(0)

    def size_kbyte(self, obj: Any, name: str, mode: SystemMode | None = None) -> Fraction | None:
        return self.number(obj, name, "KByte", mode)


# =============================================================================== bindings


class ProcessorBindings:
    """Processor bindings as OSATE's InstanceModelUtil follows them."""

    def __init__(self, reader: PropertyReader) -> None:
        self.reader = reader

    def processor_binding(self, ci: Any, mode: SystemMode | None) -> list[Any]:
        """What ``ci`` is directly bound to; a virtual processor without a binding is bound to the
        processor or virtual processor that contains it."""
        bound = self.reader.targets(ci, "Actual_Processor_Binding", mode) or []
        if not bound and category_of(ci) == "virtualProcessor":
            parent = ci.eContainer()
            if parent is not None and category_of(parent) in ("processor", "virtualProcessor"):
                bound = [parent]
        return bound

    def physical_processor(
        self, ci: Any, mode: SystemMode | None, seen: frozenset[int] = frozenset()
    ) -> Any | None:
        """The physical processor ``ci`` runs on (through virtual processors), None when unbound.
        A binding target that is neither a processor nor a virtual processor is reported."""
        if id(ci) in seen:
            self.reader.report("error", "virtual processors are bound in a cycle", ci)
            return None
        for target in self.processor_binding(ci, mode):
            kind = category_of(target)
            if kind == "virtualProcessor":
                found = self.physical_processor(target, mode, seen | {id(ci)})
                if found is not None:
                    return found
            elif kind == "processor":
                return target
            else:
                self.reader.report(
                    "error",
                    f"Actual_Processor_Binding refers to {instance_path(target)} "
                    f"({kind or 'not a component'}), not a processor or virtual processor",
                    ci,
                )
        return None


def bound_processor(
    obj: Any, mode: SystemMode | None = None, reader: PropertyReader | None = None
) -> Any | None:
    """The physical processor a component instance is bound to (``Actual_Processor_Binding``,
    through virtual processors), None when it is not bound to one."""
    return ProcessorBindings(reader or PropertyReader()).physical_processor(obj, mode)

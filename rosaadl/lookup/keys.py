"""The canonical key of a property, whatever way it is named.

An association may name its property ``Period``, ``timing_properties::period`` or (through a
``with`` clause) ``My_Set::X``; the lookup files every association under one key, the lower-case
qualified name of the definition (``timing_properties::period``), or the name as written when
the property set is not loaded. :class:`PropertyKeys` computes those keys once and remembers,
for each key, the ``Property`` definition and the display name (``Timing_Properties::Period``).
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.errors import ModelError
from rosaadl.model import is_a
from rosaadl.resolution import Resolver
from rosaadl.resolution.names import squeeze

__all__ = ["PropertyKeys"]


class PropertyKeys:
    """Keys, definitions and display names of the properties one lookup meets."""

    def __init__(self, resolver: Resolver) -> None:
        self.resolver = resolver
        #: the definition of each key (None when its property set is not loaded)
        self.definitions: dict[str, EObject | None] = {}
        self._displays: dict[str, str] = {}
        self._pa_info: dict[int, tuple[str, str, EObject | None]] = {}

    def pa_info(self, pa: EObject) -> tuple[str, str, EObject | None]:
        """``(key, display name, Property or None)`` of an association (cached)."""
        key = id(pa)
        info = self._pa_info.get(key)
        if info is None:
            prop = self.resolver.association_property(pa)
            display = self.resolver.qualified_name(prop) if prop is not None else squeeze(pa.property)
            info = (display.lower(), display, prop)
            self._pa_info[key] = info
            self._remember(info[0], prop, display)
        return info

    def key(self, name: str | EObject, context: EObject | None = None) -> str:
        """The key of a property given by name (``Period``, ``SEI::MIPSBudget``) or definition."""
        if isinstance(name, EObject):
            if not is_a(name, "Property"):
                raise ModelError(f"a {name.eClass.name} is not a property definition")
            display = self.resolver.qualified_name(name)
            key = display.lower()
            self._remember(key, name, display)
            return key
        if not isinstance(name, str):
            raise ModelError(f"expected a property or its name, got {name!r}")
        prop = self.resolver.property(name, context)
        display = self.resolver.qualified_name(prop) if prop is not None else squeeze(name)
        key = display.lower()
        self._remember(key, prop, display)
        return key

    def _remember(self, key: str, prop: EObject | None, display: str) -> None:
        self.definitions.setdefault(key, prop)
        self._displays.setdefault(key, display)

    def definition(self, key: str) -> EObject | None:
        """The ``Property`` of a key (None when unknown)."""
        return self.definitions.get(key)

    def display_name(self, key: str) -> str:
        """The qualified name of a key's property as declared (the key itself when unknown)."""
        return self._displays.get(key, key)

"""Which objects a property applies to: the owner words of its ``applies to`` list.

A property definition names the kinds of element it may be associated with (``applies to
(thread, thread group, event data port, port connection)``); :func:`accepts` tells whether an
object of a kind (component, feature, connection, flow, mode, ...) described by its AADL words
(``thread group``, ``event data port``, ``port connection``) is one of them, with the general
words AADL allows (``all``, ``port``, ``access``, ``directed feature``, ``feature``, ...).

OSATE decides by the metaclass of the declarative element an instance object comes from
(``NamedElementImpl.acceptsProperty``: an ``applies to`` metaclass that is a supertype of the
element's ``eClass``); a feature then takes its value from its own associations, its
classifier's, and (``inherit``) its component's (``FeatureImpl.getPropertyValueInternal``,
which does not ask whether the property applies to the classifier). The metaclass hierarchy is
OSATE's: from OSATE 2.0.1 to 2.0.8 (aadl2.ecore of osate2 #167, February 2013, until #486 and
#492, October 2014) a bus access was also a ``Bus``, a data access, data port and event data
port a ``Data``, a subprogram (group) access a ``Subprogram`` (``SubprogramGroup``), so that
``applies to (bus)`` held for every bus access feature (:data:`OSATE_2_0_FEATURE_SUPERTYPES`,
``accepts(..., osate_2_0=True)``); since OSATE 2.0.9 a feature is only a feature.
"""

from __future__ import annotations

from pyecore.ecore import EObject

__all__ = ["OSATE_2_0_FEATURE_SUPERTYPES", "accepts"]

_PORT_WORDS = frozenset({"data port", "event port", "event data port"})
_ACCESS_WORDS = frozenset(
    {"bus access", "data access", "subprogram access", "subprogram group access", "virtual bus access"}
)
_UNIVERSAL = frozenset({"all", "named element", "element"})

#: The component metaclass each feature category was also a subclass of in OSATE 2.0.1-2.0.8.
OSATE_2_0_FEATURE_SUPERTYPES = {
    "bus access": "bus",
    "data access": "data",
    "data port": "data",
    "event data port": "data",
    "subprogram access": "subprogram",
    "subprogram group access": "subprogram group",
}


def _words(text: str) -> str:
    return " ".join((text or "").lower().split())


def accepts(prop: EObject | None, kind: str, word: str, *, osate_2_0: bool = False) -> bool:
    """Whether property ``prop`` applies to an object of ``kind`` (``component``, ``feature``,
    ``connection``, ``flow``, ``end to end flow``, ``mode``) described by ``word``
    (``thread group``, ``event data port``, ``port connection``, ...); ``osate_2_0``: with the
    metaclass hierarchy of OSATE 2.0.1-2.0.8 (a bus access feature is also a ``bus``).

    An unknown property (its set is not loaded) applies wherever it has a value.
    """
    if prop is None:
        return True
    supertype = OSATE_2_0_FEATURE_SUPERTYPES.get(word) if osate_2_0 and kind == "feature" else None
    for raw in prop.appliesTo:
        owner = _words(raw)
        if owner in _UNIVERSAL or "::" in owner:
            return True
        if kind == "component":
            if word == "abstract" or owner in (word, "component", f"{word} type", f"{word} implementation"):
                return True
        elif kind == "feature":
            if owner in (word, "feature") or (supertype is not None and owner == supertype):
                return True
            if owner == "port" and word in _PORT_WORDS:
                return True
            if owner == "access" and word in _ACCESS_WORDS:
                return True
            if owner == "directed feature" and (
                word in _PORT_WORDS or word in ("parameter", "abstract feature")
            ):
                return True
            if owner == "feature" or (owner == "abstract feature" and word == "abstract feature"):
                return True
        elif kind == "connection":
            if owner in (word, "connection"):
                return True
        elif kind == "end to end flow":
            if owner in ("end to end flow", "flow"):
                return True
        elif kind == "flow":
            if owner in ("flow", "flow specification", "flow implementation", word):
                return True
        elif kind == "mode":
            if owner in ("mode", word):
                return True
        elif owner == word:
            return True
    return False

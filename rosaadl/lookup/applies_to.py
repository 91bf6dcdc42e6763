"""Which objects a property applies to: the owner words of its ``applies to`` list.

A property definition names the kinds of element it may be associated with (``applies to
(thread, thread group, event data port, port connection)``); :func:`accepts` tells whether an
object of a kind (component, feature, connection, flow, mode, ...) described by its AADL words
(``thread group``, ``event data port``, ``port connection``) is one of them, with the general
words AADL allows (``all``, ``port``, ``access``, ``directed feature``, ``feature``, ...).
"""

from __future__ import annotations

from pyecore.ecore import EObject

__all__ = ["accepts"]

_PORT_WORDS = frozenset({"data port", "event port", "event data port"})
_ACCESS_WORDS = frozenset(
    {"bus access", "data access", "subprogram access", "subprogram group access", "virtual bus access"}
)
_UNIVERSAL = frozenset({"all", "named element", "element"})


def _words(text: str) -> str:
    return " ".join((text or "").lower().split())


def accepts(prop: EObject | None, kind: str, word: str) -> bool:
    """Whether property ``prop`` applies to an object of ``kind`` (``component``, ``feature``,
    ``connection``, ``flow``, ``end to end flow``, ``mode``) described by ``word``
    (``thread group``, ``event data port``, ``port connection``, ...).

    An unknown property (its set is not loaded) applies wherever it has a value.
    """
    if prop is None:
        return True
    for raw in prop.appliesTo:
        owner = _words(raw)
        if owner in _UNIVERSAL or "::" in owner:
            return True
        if kind == "component":
            if word == "abstract" or owner in (word, "component", f"{word} type", f"{word} implementation"):
                return True
        elif kind == "classifier":
            if owner == word:
                return True
        elif kind == "feature":
            if owner in (word, "feature"):
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

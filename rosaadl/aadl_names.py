"""What AADL accepts as a name: identifiers and the reserved words (SAE AS5506C 15.3 and 15.5).

The AADL writer refuses a name that is not an identifier and warns about a reserved word used as
one; the ROSMOD → AADL conversion never makes such names. Both read the rules from here.
"""

from __future__ import annotations

import re

__all__ = ["IDENTIFIER", "RESERVED_WORDS", "is_identifier", "is_reserved"]

#: AS5506C 15.3: ``identifier ::= identifier_letter {[underline] letter_or_digit}*``
IDENTIFIER = r"[A-Za-z](?:_?[A-Za-z0-9])*"
_IDENTIFIER_RE = re.compile(IDENTIFIER + r"\Z")

_RESERVED_TEXT = """
    aadlboolean aadlinteger aadlreal aadlstring abstract access all and annex applies binding bus
    calls classifier compute connections constant data delta device end enumeration event extends
    false feature features flow flows group implementation in inherit initial inverse is list memory
    mode modes none not of or out package parameter path port private process processor properties
    property prototype prototypes provides public range record reference refined renames requires
    self set sink source subcomponents subprogram system thread to true type units virtual with
"""
#: AS5506C 15.5: the reserved words (AADL is not case-sensitive: compare in lower case).
RESERVED_WORDS = frozenset(_RESERVED_TEXT.split())


def is_identifier(text: str) -> bool:
    """Whether ``text`` is an AADL identifier (a reserved word is one too; see :func:`is_reserved`)."""
    return _IDENTIFIER_RE.match(text) is not None


def is_reserved(text: str) -> bool:
    """Whether ``text`` is a reserved word of AADL, in any case."""
    return text.lower() in RESERVED_WORDS

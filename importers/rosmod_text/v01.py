"""ROSMOD v0.1 ``.rosml`` files: a named workspace of v0.2 packages, software only.

A v0.1 file starts with ``workspace W;`` and goes on with packages written as in v0.2
(``messages``, ``services``, ``components``, ``nodes`` blocks, read by :func:`.v02.package`); it
has no hardware or deployment. The workspace statement is what tells v0.1 apart
(:func:`is_v01`), and it names the software model (:func:`workspace_name`).
"""

from __future__ import annotations

from rosaadl.importers.rosmod_text import v02
from rosaadl.importers.rosmod_text.blocks import Stmt
from rosaadl.importers.rosmod_text.statements import name_of

__all__ = ["is_v01", "workspace_name", "package"]

#: A v0.1 package is a v0.2 package.
package = v02.package


def is_v01(stmts: list[Stmt]) -> bool:
    """Does a software model have a ``workspace`` statement?"""
    return any(s.keyword == "workspace" for s in stmts)


def workspace_name(stmt: Stmt, filename: str) -> str:
    """The name of the software model given by ``workspace W;``."""
    return name_of(stmt, filename, "workspace")

"""Helpers of the AADL syntax tests: the parser, and finding nodes in its trees.

The test modules of ``tests/importers`` import it as ``aadl_syntax_helpers`` (their folder is on
pytest's import path)."""

from __future__ import annotations

from pathlib import Path

from lark import Token, Tree

from rosaadl.importers import aadl_syntax

__all__ = ["ROOT", "aadl_syntax", "find", "in_impl", "in_type", "only", "parse", "value_of", "words"]

ROOT = Path(__file__).resolve().parents[2]
parse = aadl_syntax.parse


def find(tree: Tree, name: str) -> list[Tree]:
    return list(tree.find_data(name))


def only(tree: Tree, name: str) -> Tree:
    found = find(tree, name)
    assert len(found) == 1, f"expected one {name!r} node, found {len(found)}:\n{tree.pretty()}"
    return found[0]


def words(node: Tree | Token | None) -> list[str] | None:
    """The texts of the tokens directly under a node; an empty optional slot shows as "None"."""
    if node is None:
        return None
    if isinstance(node, Token):
        return [str(node)]
    return [str(child) for child in node.children if not isinstance(child, Tree)]


def in_type(body: str, category: str = "system") -> Tree:
    return parse(f"package P public\n{category} T\n{body}\nend T;\nend P;\n")


def in_impl(body: str, category: str = "system") -> Tree:
    return parse(
        f"package P public\n{category} T end T;\n{category} implementation T.i\n{body}\nend T.i;\nend P;\n"
    )


def value_of(text: str) -> Tree | Token | None:
    tree = in_type(f"properties\n  X => {text};")
    return only(tree, "property_association").children[3]

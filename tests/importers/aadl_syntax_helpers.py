"""Helpers of the AADL syntax tests: the parser, and finding nodes in its trees.

The test modules of ``tests/importers`` import it as ``aadl_syntax_helpers`` (their folder is on
pytest's import path)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from lark import Token, Tree

__all__ = ["ROOT", "aadl_syntax", "find", "in_impl", "in_type", "only", "parse", "value_of", "words"]

ROOT = Path(__file__).resolve().parents[2]


def _load_module():
    try:
        from rosaadl.importers import aadl_syntax
    except ImportError:  # the rosaadl.importers mapping needs the project installed
        name = "_rosaadl_importers_aadl_syntax"
        spec = importlib.util.spec_from_file_location(name, ROOT / "importers" / "aadl_syntax.py")
        assert spec is not None and spec.loader is not None
        aadl_syntax = importlib.util.module_from_spec(spec)
        sys.modules[name] = aadl_syntax
        spec.loader.exec_module(aadl_syntax)
    return aadl_syntax


aadl_syntax = _load_module()
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

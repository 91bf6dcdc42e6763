"""OSATE's metamodels in pyecore, patched so that OSATE's files load: the other tool the ``.aaxl2``
benchmarks set ours against, and the metamodel the conformance oracle of the tests checks with.

``aadl2.ecore`` and ``instance.ecore`` from the corpus (``osate/metamodel``), with the optional
``ErrorModel.ecore``/``EMV2Instance.ecore`` for files that hold EMV2 annex instances. pyecore
cannot load OSATE's files with them as they come: OSATE's primitive data types ``Integer``,
``Real`` and ``Boolean`` (Java long, double, boolean) have no Python conversion, so pyecore keeps
their values as text, which its own type check then refuses; and the enumerations are written
with their Java literals (``in out``, ``thread group``, ``+``). The resource set is patched for
exactly that and nothing else; a value that is not a number or a boolean is refused.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from pyecore.ecore import EDataType, EEnum
from pyecore.resources import URI, ResourceSet

__all__ = ["java_literal", "osate_metamodels"]

_JAVA_LITERALS = {"plus": "+", "minus": "-"}
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?\d+)?|NaN|Infinity)\Z")


def java_literal(name: str) -> str:
    """``inOut`` → ``in out``, ``threadGroup`` → ``thread group``, ``plus`` → ``+``."""
    return _JAVA_LITERALS.get(name) or re.sub(r"(?<!^)(?=[A-Z])", " ", name).lower()


def _integer(text: str) -> int:
    return int(text)


def _real(text: str) -> float:
    if not _NUMBER.match(text.strip()):
        raise ValueError(text)
    return float(text)


def _boolean(text: str) -> bool:
    if text not in ("true", "false"):
        raise ValueError(text)
    return text == "true"


# OSATE's primitive data types; String needs nothing
_CONVERSIONS = {"Integer": _integer, "Real": _real, "Boolean": _boolean}


def _patch(package: Any) -> None:
    """pyecore conversions for OSATE's numeric data types, Java literals for its enumerations."""
    for classifier in package.eClassifiers:
        if isinstance(classifier, EEnum):
            by_text = {}
            for literal in classifier.eLiterals:
                by_text[literal.name] = literal
                by_text[java_literal(literal.name)] = literal
            classifier.from_string = by_text.__getitem__
        elif isinstance(classifier, EDataType) and classifier.name in _CONVERSIONS:
            classifier.from_string = _CONVERSIONS[classifier.name]
            classifier.to_string = str


def osate_metamodels(metamodel_dir: Path, *, with_emv2: bool = False) -> tuple[ResourceSet, dict[str, Any]]:
    """A new pyecore ``ResourceSet`` with OSATE's metamodels registered and patched, and those
    packages by namespace URI; with the EMV2 metamodels too when ``with_emv2``."""
    folder = Path(metamodel_dir)
    rset = ResourceSet()
    packages = {}
    for name in ("aadl2.ecore", "instance.ecore"):
        package = rset.get_resource(URI(str(folder / name))).contents[0]
        rset.metamodel_registry[package.nsURI] = package
        packages[package.nsURI] = package
    if with_emv2:
        optional = folder / "optional"
        rset.uri_mapper["platform:/resource/org.osate.aadl2/model"] = str(folder)
        rset.uri_mapper["../../org.osate.aadl2/model"] = str(folder)
        rset.uri_mapper["../../org.osate.xtext.aadl2.errormodel/model/generated"] = str(optional)
        for name in ("ErrorModel.ecore", "EMV2Instance.ecore"):
            package = rset.get_resource(URI(str(optional / name))).contents[0]
            rset.metamodel_registry[package.nsURI] = package
            packages[package.nsURI] = package
    for package in packages.values():
        _patch(package)
    return rset, packages

"""The rosaadl metamodels: ``aadl.ecore``, ``rosmod.ecore`` and ``trace.ecore``, loaded with pyecore.

The ``.ecore`` files beside this module are the source of truth. They are read once per process
(the loaded packages are immutable metadata, like Python classes) and are never put into
pyecore's process-wide registry: a :class:`pyecore.resources.ResourceSet` made with
:func:`new_resource_set` knows them.

Three pyecore pitfalls are handled here, once, for every class of every package:

* custom ``EDataType`` s (``rosmod::Seconds``) get real ``from_string``/``to_string``; pyecore
  would otherwise load their values as strings (pyecore issue 133). A custom data type without a
  known conversion is a load-time error, never a silent string;
* ``EEnum`` values serialise as their *literal* (``thread group``), as EMF does, and read back from
  either the literal or the name; pyecore alone writes and reads names only;
* generated classes reject unknown keyword arguments (``ComponentType(nmae="x")``) instead of
  silently creating a stray Python attribute.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from importlib import resources

from pyecore.ecore import EClass, EDataType, EEnum, EPackage, EProxy
from pyecore.resources import URI, ResourceSet

from rosaadl.errors import ModelError

__all__ = [
    "METAMODEL_NAMES",
    "Metamodels",
    "load",
    "aadl",
    "rosmod",
    "trace",
    "new_resource_set",
]

METAMODEL_NAMES = ("aadl", "rosmod", "trace")


def _seconds_from_string(text: str) -> Decimal:
    try:
        value = Decimal(text)
    except InvalidOperation as exc:
        raise ModelError(f"expected a decimal number of seconds, found {text!r}") from exc
    if not value.is_finite():
        raise ModelError(f"expected a finite number of seconds, found {text!r}")
    return value


def _seconds_to_string(value: object) -> str:
    return str(value)


# Conversions for the custom EDataTypes of our metamodels, by (package, name).
_DATATYPE_CONVERSIONS = {
    ("rosmod", "Seconds"): (Decimal, _seconds_from_string, _seconds_to_string),
}


def _install_enum_literals(enum: EEnum) -> None:
    by_text = {}
    for literal in enum.eLiterals:
        by_text[literal.name] = literal
    for literal in enum.eLiterals:
        if literal.literal:
            by_text[literal.literal] = literal

    def from_string(text: str):
        try:
            return by_text[text]
        except KeyError:
            raise ModelError(
                f"{text!r} is not a literal of enumeration {enum.name} "
                f"(expected one of: {', '.join(lit.literal or lit.name for lit in enum.eLiterals)})"
            ) from None

    def to_string(value) -> str:
        literal = value if not isinstance(value, str) else by_text[value]
        return literal.literal or literal.name

    enum.from_string = from_string
    enum.to_string = to_string


def _install_strict_init(eclass: EClass) -> None:
    pyclass = eclass.python_class
    allowed = frozenset(f.name for f in eclass.eAllStructuralFeatures())

    def __init__(self, **kwargs):  # noqa: N807 - replaces pyecore's permissive __init__
        for key, value in kwargs.items():
            if key not in allowed:
                raise ModelError(
                    f"{eclass.name} has no feature {key!r} (expected one of: {', '.join(sorted(allowed))})"
                )
            setattr(self, key, value)

    pyclass.__init__ = __init__
    pyclass._rosaadl_features = allowed


def _unproxy_types(eclass: EClass) -> None:
    """Replace the proxies of feature types (``Ecore#//EString`` hrefs in the .ecore file) by the
    objects they stand for: pyecore checks every value against the type, and a proxy makes
    each check go through a slow ``__getattribute__`` (~4x the cost of creating an object)."""
    for feature in eclass.eStructuralFeatures:
        etype = feature._eType
        if isinstance(etype, EProxy):
            etype.force_resolve()
            feature._eType = etype._wrapped


def _prepare(package: EPackage) -> None:
    for classifier in package.eClassifiers:
        if isinstance(classifier, EClass):
            _unproxy_types(classifier)
    for classifier in package.eClassifiers:
        if isinstance(classifier, EEnum):
            _install_enum_literals(classifier)
        elif isinstance(classifier, EClass):
            _install_strict_init(classifier)
        elif isinstance(classifier, EDataType):
            key = (package.name, classifier.name)
            if key not in _DATATYPE_CONVERSIONS:
                raise ModelError(
                    f"metamodel {package.name}.ecore: data type {classifier.name} has no conversion; "
                    "add one to rosaadl.metamodels"
                )
            etype, from_string, to_string = _DATATYPE_CONVERSIONS[key]
            classifier.eType = etype
            classifier.from_string = from_string
            classifier.to_string = to_string


@dataclass(frozen=True)
class Metamodels:
    """The three loaded metamodel packages."""

    aadl: EPackage
    rosmod: EPackage
    trace: EPackage

    def packages(self) -> tuple[EPackage, ...]:
        return (self.aadl, self.rosmod, self.trace)

    def eclass(self, qualified: str) -> EClass:
        """``"aadl.ComponentType"`` (or a bare class name, searched in order) → EClass."""
        if "." in qualified:
            pkg_name, _, name = qualified.partition(".")
            packages = [p for p in self.packages() if p.name == pkg_name]
        else:
            name, packages = qualified, list(self.packages())
        for pkg in packages:
            found = pkg.getEClassifier(name)
            if isinstance(found, EClass):
                return found
        raise ModelError(f"no metamodel class {qualified!r}")


@functools.lru_cache(maxsize=1)
def load() -> Metamodels:
    """Read the ``.ecore`` files (once per process) and return the prepared packages."""
    rset = ResourceSet()
    loaded = {}
    folder = resources.files(__name__)
    for name in METAMODEL_NAMES:
        path = folder / f"{name}.ecore"
        with resources.as_file(path) as real_path:
            resource = rset.get_resource(URI(str(real_path)))
        package = resource.contents[0]
        _prepare(package)
        loaded[name] = package
    return Metamodels(**loaded)


def aadl() -> EPackage:
    return load().aadl


def rosmod() -> EPackage:
    return load().rosmod


def trace() -> EPackage:
    return load().trace


def new_resource_set() -> ResourceSet:
    """A ResourceSet that knows our metamodels (and nothing process-wide)."""
    rset = ResourceSet()
    for package in load().packages():
        rset.metamodel_registry[package.nsURI] = package
    return rset

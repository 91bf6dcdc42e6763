"""Conformance of ``.aaxl2`` files to OSATE's own metamodel (test helper).

:func:`check` loads a file with pyecore's ``XMIResource`` into OSATE's ``aadl2.ecore`` and
``instance.ecore`` from the corpus (``osate/metamodel``), and, independently of pyecore, walks the
XML against the same metamodel:

* every element and attribute must be a feature of its object's class (a class named by its
  ``xsi:type`` or the feature's type), not derived or transient; every ``xsi:type`` a known,
  non-abstract class conforming to the feature's type; a link into another document (``href``)
  names a concrete class (itself or through ``xsi:type``);
* every attribute value must decode: numbers, booleans, enumeration literals (OSATE writes the
  Java literals ``in out``, ``thread group``, ``+``);
* every intra-file reference (``//@componentInstance.4/@featureInstance.0``, ``/``, ``/1``,
  space-separated lists) must designate an element of the file whose class conforms to the
  reference's type.

pyecore cannot load these files as it comes (OSATE's primitive data types ``Integer``, ``Real``
and ``Boolean`` have no Python conversion, and the enumerations are written with their Java
literals), so the resource set is patched for exactly that and nothing else
(``benchmarks.generators.osate``, shared with the ``.aaxl2`` benchmarks). Files that hold
EMV2 annex instances are loaded with the optional ``EMV2Instance.ecore``/``ErrorModel.ecore``
beside the core metamodels.
"""

from __future__ import annotations

import io
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

from lxml import etree
from pyecore.ecore import EClass, EEnum, EReference
from pyecore.resources import URI, ResourceSet
from pyecore.resources.xmi import XMIResource

from benchmarks.generators.osate import osate_metamodels

__all__ = ["Conformance", "check", "resource_set"]

XMI = "http://www.omg.org/XMI"
XSI = "http://www.w3.org/2001/XMLSchema-instance"
EMV2_INSTANCE = "http://www.osate.org/EMV2Instance"


@cache
def _packages(metamodel_dir: str, with_emv2: bool) -> tuple:
    """(ResourceSet, {nsURI: EPackage}) with OSATE's metamodels, patched (one per process)."""
    return osate_metamodels(Path(metamodel_dir), with_emv2=with_emv2)


def resource_set(metamodel_dir: Path, *, with_emv2: bool = False) -> ResourceSet:
    return _packages(str(metamodel_dir), with_emv2)[0]


@dataclass
class Conformance:
    """What does not conform (empty lists when the file conforms)."""

    load_error: str | None = None
    unknown_classes: list[str] = field(default_factory=list)
    unknown_features: list[str] = field(default_factory=list)
    bad_values: list[str] = field(default_factory=list)
    unresolved: list[str] = field(default_factory=list)
    out_of_order: list[str] = field(default_factory=list)
    elements: int = 0
    references: int = 0
    objects: int = 0

    @property
    def ok(self) -> bool:
        return not (
            self.load_error
            or self.unknown_classes
            or self.unknown_features
            or self.bad_values
            or self.unresolved
            or self.out_of_order
        )

    def summary(self) -> str:
        parts = [f"load: {self.load_error}"] if self.load_error else []
        for name in ("unknown_classes", "unknown_features", "bad_values", "unresolved", "out_of_order"):
            items = getattr(self, name)
            if items:
                parts.append(f"{name} ({len(items)}): " + "; ".join(items[:5]))
        return " | ".join(parts) or "conforms"


def _emf_order(cls: EClass, seen: dict | None = None) -> dict[str, int]:
    """Feature name → position in EMF's ``eAllStructuralFeatures`` (inherited features first,
    supertypes in declaration order), the order EMF's XMI writer follows."""
    order: dict[str, int] = {} if seen is None else seen
    for parent in cls.eSuperTypes:
        _emf_order(parent, order)
    for feature in cls.eStructuralFeatures:
        order.setdefault(feature.name, len(order))
    return order


class _Walker:
    def __init__(self, tree: etree._ElementTree, packages: dict, report: Conformance) -> None:
        self.tree = tree
        self.packages = packages
        self.report = report
        self.nsmap = tree.getroot().nsmap
        self.classes: dict[etree._Element, EClass] = {}  # (keeps the element proxies alive)
        self.refs: list[tuple[etree._Element, str, str, EReference]] = []

    def where(self, element: etree._Element) -> str:
        return f"line {element.sourceline} {self.tree.getpath(element)}"

    def class_named(self, text: str, element: etree._Element) -> EClass | None:
        prefix, _, name = text.rpartition(":")
        uri = element.nsmap.get(prefix or None)
        package = self.packages.get(uri)
        found = package.getEClassifier(name) if package is not None else None
        if not isinstance(found, EClass):
            self.report.unknown_classes.append(f"{text} at {self.where(element)}")
            return None
        return found

    @staticmethod
    def conforms(cls: EClass, expected) -> bool:
        """``cls`` is ``expected`` or a subclass (by package and name: instance.ecore reaches
        aadl2.ecore's classes through its own references)."""
        wanted = (expected.ePackage.nsURI, expected.name)
        return any((c.ePackage.nsURI, c.name) == wanted for c in (cls, *cls.eAllSuperTypes()))

    def root(self, element: etree._Element) -> None:
        qname = etree.QName(element)
        package = self.packages.get(qname.namespace)
        cls = package.getEClassifier(qname.localname) if package is not None else None
        if not isinstance(cls, EClass):
            self.report.unknown_classes.append(f"{element.tag} at {self.where(element)}")
            return
        self.element(element, cls)

    def value(self, element: etree._Element, feature, text: str) -> None:
        etype = feature.eType
        tokens = text.split() if feature.many and not isinstance(etype, EEnum) else [text]
        for token in tokens:
            try:
                etype.from_string(token)
            except Exception:
                self.report.bad_values.append(
                    f"{feature.name}={token!r} ({etype.name}) at {self.where(element)}"
                )

    def element(self, element: etree._Element, cls: EClass) -> None:
        self.report.elements += 1
        self.classes[element] = cls
        if cls.abstract:
            self.report.unknown_classes.append(f"abstract {cls.name} instantiated at {self.where(element)}")
        order = _emf_order(cls)
        self.in_order(
            element,
            cls,
            [etree.QName(k).localname for k in element.attrib if "}" not in k],
            order,
            "attribute",
        )
        children = [etree.QName(c).localname for c in element if isinstance(c.tag, str)]
        self.in_order(element, cls, children, order, "element")
        for key, text in element.attrib.items():
            qname = etree.QName(key)
            if qname.namespace in (XMI, XSI):
                continue
            feature = cls.findEStructuralFeature(qname.localname)
            if feature is None or feature.derived or feature.transient:
                why = "unknown" if feature is None else "derived or transient"
                self.report.unknown_features.append(
                    f"{cls.name}.{qname.localname} ({why}) at {self.where(element)}"
                )
                continue
            if isinstance(feature, EReference):
                if feature.containment:
                    self.report.unknown_features.append(
                        f"containment {cls.name}.{feature.name} written as an attribute at "
                        f"{self.where(element)}"
                    )
                    continue
                self.refs.append((element, key, text, feature))
            else:
                self.value(element, feature, text)
        for child in element:
            if not isinstance(child.tag, str):
                continue
            name = etree.QName(child).localname
            feature = cls.findEStructuralFeature(name)
            if feature is None or feature.derived or feature.transient:
                why = "unknown" if feature is None else "derived or transient"
                self.report.unknown_features.append(f"{cls.name}.{name} ({why}) at {self.where(child)}")
                continue
            if not isinstance(feature, EReference):
                self.value(child, feature, child.text or "")
                continue
            xsi_type = child.get(f"{{{XSI}}}type")
            target = self.class_named(xsi_type, child) if xsi_type else feature.eType
            if target is None:
                continue
            if not self.conforms(target, feature.eType):
                self.report.unknown_classes.append(
                    f"{target.name} does not conform to {cls.name}.{feature.name} ({feature.eType.name}) "
                    f"at {self.where(child)}"
                )
                continue
            if feature.containment:
                self.element(child, target)
            elif child.get("href") is None:
                self.report.unresolved.append(
                    f"{cls.name}.{feature.name} without href at {self.where(child)}"
                )
            elif target.abstract:
                self.report.unknown_classes.append(
                    f"link {cls.name}.{feature.name} to abstract {target.name} without xsi:type at "
                    f"{self.where(child)}"
                )

    def in_order(self, element, cls: EClass, names: list[str], order: dict[str, int], what: str) -> None:
        positions = [order.get(n, -1) for n in names]
        for before, after, name in zip(positions, positions[1:], names[1:], strict=False):
            if after < before:
                self.report.out_of_order.append(
                    f"{what} {name} of {cls.name} out of EMF feature order at {self.where(element)}"
                )
                return

    def resolve(self, roots: list[etree._Element], path: str) -> etree._Element | None:
        text = path[1:] if path.startswith("#") else path
        if not text.startswith("/"):
            return None  # ids are not written by the exporter
        if text.startswith("//"):
            current, rest = roots[0] if roots else None, text[2:]
        else:
            head, _, rest = text[1:].partition("/")
            if head == "":
                current = roots[0] if roots else None
            elif head.isdigit() and int(head) < len(roots):
                current = roots[int(head)]
            else:
                return None
        for step in (s for s in rest.split("/") if s):
            if current is None or not step.startswith("@"):
                return None
            name, _, number = step[1:].partition(".")
            matches = [c for c in current if isinstance(c.tag, str) and etree.QName(c).localname == name]
            position = int(number) if number.isdigit() else 0
            current = matches[position] if position < len(matches) else None
        return current

    def check_references(self, roots: list[etree._Element]) -> None:
        for element, key, text, feature in self.refs:
            for token in text.split() if feature.many else [text.strip()]:
                self.report.references += 1
                target = self.resolve(roots, token)
                cls = self.classes.get(target) if target is not None else None
                if cls is None:
                    self.report.unresolved.append(f"{key}={token!r} at {self.where(element)}")
                elif not self.conforms(cls, feature.eType):
                    self.report.unresolved.append(
                        f"{key}={token!r} designates a {cls.name}, not a {feature.eType.name} at "
                        f"{self.where(element)}"
                    )


def check(data: bytes, metamodel_dir: Path) -> Conformance:
    """Check one ``.aaxl2`` document (bytes) against OSATE's metamodel in ``metamodel_dir``."""
    report = Conformance()
    with_emv2 = EMV2_INSTANCE.encode() in data
    rset, packages = _packages(str(metamodel_dir), with_emv2)
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)
    tree = etree.ElementTree(etree.fromstring(data, parser))
    root = tree.getroot()
    walker = _Walker(tree, packages, report)
    roots = list(root) if root.tag == f"{{{XMI}}}XMI" else [root]
    roots = [r for r in roots if isinstance(r.tag, str)]
    for element in roots:
        walker.root(element)
    walker.check_references(roots)
    # and pyecore's own reader on the same bytes
    try:
        loaded = XMIResource(_BytesURI(data))
        loaded.resource_set = rset
        loaded.load()
        report.objects = sum(1 + sum(1 for _ in r.eAllContents()) for r in loaded.contents)
    except Exception as exc:  # pyecore's failure is the finding here
        report.load_error = f"{type(exc).__name__}: {str(exc).splitlines()[0][:200] if str(exc) else ''}"
    return report


class _BytesURI(URI):
    """An in-memory input stream for pyecore."""

    def __init__(self, data: bytes) -> None:
        super().__init__("memory.aaxl2")
        self._data = data

    def create_instream(self):
        return io.BytesIO(self._data)

    def close_stream(self):
        pass

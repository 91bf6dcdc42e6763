"""The reader of declarative ``.aaxl2`` files: an ``aadl2:Package`` or ``aadl2:PropertySet`` root.

OSATE also serialises packages and property sets as XMI; :class:`DeclarativeReader` turns one
into an ``AadlPackage`` or ``PropertySet`` of our declarative model (classifiers with their
features, subcomponents, connections, modes and flows; property types, properties and
constants). It builds with :func:`rosaadl.model.new` (these files are small) and shares the
:class:`~.document.Reader`'s helpers and property value readers with instance files.
"""

from __future__ import annotations

from pathlib import Path

from lxml import etree
from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import ImportFormatError, RosaadlError

from .document import Reader
from .values import property_association, read_value
from .xmi import (
    CATEGORIES,
    CLASSIFIER_TYPES,
    NS_AADL2,
    ROOT_PACKAGE,
    XMI_ID,
    XSI_TYPE,
    is_positional,
    link_class,
    qualified_name,
    split_ref_attribute,
)

__all__ = ["DeclarativeReader"]


_FEATURE_TAGS = {
    "ownedDataPort": "dataPort",
    "ownedEventPort": "eventPort",
    "ownedEventDataPort": "eventDataPort",
    "ownedParameter": "parameter",
    "ownedBusAccess": "busAccess",
    "ownedDataAccess": "dataAccess",
    "ownedSubprogramAccess": "subprogramAccess",
    "ownedSubprogramGroupAccess": "subprogramGroupAccess",
    "ownedVirtualBusAccess": "virtualBusAccess",
    "ownedFeatureGroup": "featureGroup",
    "ownedAbstractFeature": "abstractFeature",
}
_CONNECTION_TAGS = {
    "ownedPortConnection": "portConnection",
    "ownedAccessConnection": "accessConnection",
    "ownedFeatureConnection": "featureConnection",
    "ownedFeatureGroupConnection": "featureGroupConnection",
    "ownedParameterConnection": "parameterConnection",
}
_CATEGORY_OF = {c.lower(): c[0].lower() + c[1:] for c in CATEGORIES}
# ``owned<Category>Subcomponent`` → the category's class-name stem
_SUBCOMPONENT_TAGS = {f"owned{c}Subcomponent": c for c in CATEGORIES}


class DeclarativeReader:
    """Reads an ``aadl2:Package`` or ``aadl2:PropertySet`` root into our declarative model.

    Classifiers (types, implementations, feature group types) with their features,
    subcomponents, connections, modes, flows, property associations and annex subclauses
    (kept as text); property sets with their property types, properties and constants.
    Intra-file references (``#//@ownedPublicSection/@ownedClassifier.0`` or ``#<xmi:id>``)
    are resolved on the document; references into other files keep qualified names.
    """

    def __init__(self, reader: Reader, root_el: etree._Element) -> None:
        self.r = reader
        self.root = root_el
        self.unit_name = root_el.get("name") or ""
        self.by_id = {el.get(XMI_ID): el for el in root_el.iter() if el.get(XMI_ID) is not None}

    def read(self) -> tuple[EObject, str]:
        if self.root.tag == ROOT_PACKAGE:
            unit, kind = self.package(), "package"
        else:
            unit, kind = self.property_set(), "property set"
        aadl_model = model.new("AadlModel")
        aadl_model.units.append(unit)
        return aadl_model, kind

    # ------------------------------------------------------------------ references

    def located(self, build, element: etree._Element):
        """``build(element)``, with a model error (a bad enumeration literal, say) located there."""
        try:
            return build(element)
        except ImportFormatError:
            raise
        except RosaadlError as exc:
            raise self.r.error(exc.message, element) from None

    def literal(self, enum_name: str, text: str, element: etree._Element, attribute: str):
        """An enumeration literal of our metamodel from its name or AADL spelling (located error)."""
        return self.r.enum(enum_name, text, element, attribute)

    def element_at(self, fragment: str) -> etree._Element | None:
        """The element an intra-file fragment (``//@a/@b.1``, ``/``, or an xmi:id) designates."""
        if not fragment.startswith("/"):
            return self.by_id.get(fragment)
        current = self.root
        for segment in fragment.split("/")[2:]:
            if not segment:
                continue
            if not segment.startswith("@"):
                return None
            tag, _, number = segment[1:].partition(".")
            matches = [child for child in current if child.tag == tag]
            position = int(number) if number.isdigit() else 0
            if position >= len(matches):
                return None
            current = matches[position]
        return current

    def ref_name(self, element: etree._Element, attribute: str, *, qualify: bool) -> str | None:
        text = element.get(attribute)
        if text is None:
            return None
        xsi_type, uri, frag = split_ref_attribute(text)
        self.r.check_fragment(frag, element, attribute)
        if uri:
            if frag and not is_positional(frag):
                name = qualified_name(frag, link_class(xsi_type))
                return name if qualify else name.rpartition("::")[2]
            return f"{uri}#{frag}"
        target = self.element_at(frag)
        if target is None:
            raise self.r.error(
                f"{attribute} refers to {text!r}, which is not an element of this file", element, attribute
            )
        name = target.get("name") or ""
        return f"{self.unit_name}::{name}" if qualify else name

    # ------------------------------------------------------------------ packages

    def package(self) -> EObject:
        pkg = model.new("AadlPackage", name=self.unit_name, sourceFile=self.r.filename)
        for section_tag, visibility, withs_feature in (
            ("ownedPublicSection", "public", "withs"),
            ("ownedPrivateSection", "private", "privateWiths"),
        ):
            for section in (c for c in self.root if c.tag == section_tag):
                getattr(pkg, withs_feature).extend(self.imported_units(section))
                for child in section:
                    if child.tag == "ownedClassifier":
                        classifier = self.located(self.classifier, child)
                        if classifier is not None:
                            classifier.visibility = self.literal(
                                "Visibility", visibility, child, "visibility"
                            )
                            pkg.classifiers.append(classifier)
                    elif child.tag == "ownedAnnexLibrary":
                        pkg.annexLibraries.append(
                            model.new(
                                "AnnexLibrary",
                                name=child.get("name") or "",
                                text=child.get("sourceText") or "",
                            )
                        )
                    elif child.tag in ("importedUnit", "ownedComment"):
                        continue
                    else:
                        self.r.unknown(child, section_tag)
        for child in self.root:
            if child.tag == "ownedPropertyAssociation":
                pkg.ownedPropertyAssociations.append(property_association(self.r, child))
        return pkg

    def imported_units(self, section: etree._Element) -> list[str]:
        names = []
        text = section.get("importedUnit")
        tokens = text.split() if text else []
        refs = [
            tokens[i + 1] if i + 1 < len(tokens) and ":" in tokens[i] else tokens[i]
            for i in range(0, len(tokens), 2)
        ]
        refs += [child.get("href") for child in section if child.tag == "importedUnit" and child.get("href")]
        for ref in refs:
            uri, _, frag = ref.partition("#")
            if frag and not is_positional(frag):
                names.append(qualified_name(frag, "ModelUnit"))
            else:
                names.append(Path(uri).name.rsplit(".", 1)[0])
        return names

    def classifier(self, el: etree._Element) -> EObject | None:
        ns, local = self.r.xsi_type(el)
        if ns != NS_AADL2 or local not in CLASSIFIER_TYPES:
            raise self.r.error(f"unknown classifier type xsi:type={el.get(XSI_TYPE)!r}", el, "xsi:type")
        name = el.get("name") or ""
        if local == "FeatureGroupType":
            obj = model.new("FeatureGroupType", name=name)
        elif local.endswith("Implementation"):
            category = _CATEGORY_OF[local[: -len("Implementation")].lower()]
            obj = model.new("ComponentImplementation", name=name, category=category)
        else:
            category = _CATEGORY_OF[local[: -len("Type")].lower()]
            obj = model.new("ComponentType", name=name, category=category)
        for child in el:
            tag = child.tag
            if tag in _FEATURE_TAGS and obj.eClass.findEStructuralFeature("features") is not None:
                obj.features.append(self.feature(child, _FEATURE_TAGS[tag]))
            elif tag in _SUBCOMPONENT_TAGS and local.endswith("Implementation"):
                obj.subcomponents.append(self.subcomponent(child, _SUBCOMPONENT_TAGS[tag]))
            elif tag in _CONNECTION_TAGS and local.endswith("Implementation"):
                obj.connections.append(self.connection(child, _CONNECTION_TAGS[tag]))
            elif tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(property_association(self.r, child))
            elif tag == "ownedRealization" and local.endswith("Implementation"):
                obj.type = self.ref_name(child, "implemented", qualify=True)
            elif tag == "ownedExtension":
                obj.extended = self.ref_name(child, "extended", qualify=True)
            elif tag == "ownedAnnexSubclause":
                obj.annexSubclauses.append(
                    model.new(
                        "AnnexSubclause", name=child.get("name") or "", text=child.get("sourceText") or ""
                    )
                )
            elif tag == "ownedMode" and obj.eClass.findEStructuralFeature("modes") is not None:
                obj.modes.append(
                    model.new("Mode", name=child.get("name") or "", initial=child.get("initial") == "true")
                )
            elif tag == "ownedFlowSpecification" and local.endswith("Type"):
                obj.flowSpecifications.append(
                    model.new(
                        "FlowSpecification", name=child.get("name") or "", kind=child.get("kind") or "source"
                    )
                )
            elif tag == "ownedEndToEndFlow" and local.endswith("Implementation"):
                obj.endToEndFlows.append(model.new("EndToEndFlow", name=child.get("name") or ""))
            elif tag in (
                "ownedComment",
                "ownedModeTransition",
                "ownedFlowImplementation",
                "ownedPrototype",
                "ownedPrototypeBinding",
                "ownedSubprogramCallSequence",
            ):
                continue
            else:
                self.r.unknown(child, "ownedClassifier")
        return obj

    def feature(self, el: etree._Element, category: str) -> EObject:
        obj = model.new("Feature", name=el.get("name") or "", category=category)
        if category.endswith("Access"):
            obj.access = self.literal("AccessType", el.get("kind") or "provides", el, "kind")
        else:
            obj.direction = self.literal("DirectionType", el.get("direction") or "in", el, "direction")
        for attribute in el.attrib:
            if attribute.endswith("FeatureClassifier") or attribute == "featureType":
                obj.classifier = self.ref_name(el, attribute, qualify=True)
        if el.get("inverse") == "true":
            obj.inverse = True
        for child in el:
            if child.tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(property_association(self.r, child))
            elif child.tag == "arrayDimension":
                obj.arrayDimensions.append(self.array_size(child))
        return obj

    def array_size(self, el: etree._Element) -> str:
        for child in el:
            if child.tag == "size":
                return child.get("size") or ""
        return ""

    def subcomponent(self, el: etree._Element, category: str) -> EObject:
        obj = model.new("Subcomponent", name=el.get("name") or "", category=_CATEGORY_OF[category.lower()])
        for attribute in el.attrib:
            if attribute.endswith("SubcomponentType"):
                obj.classifier = self.ref_name(el, attribute, qualify=True)
        for child in el:
            if child.tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(property_association(self.r, child))
            elif child.tag == "arrayDimension":
                obj.arrayDimensions.append(self.array_size(child))
        return obj

    def connection(self, el: etree._Element, kind: str) -> EObject:
        obj = model.new(
            "Connection",
            name=el.get("name") or "",
            kind=kind,
            bidirectional=el.get("bidirectional") == "true",
        )
        for child in el:
            if child.tag in ("source", "destination"):
                parts = []
                current = child
                while current is not None:
                    context = self.ref_name(current, "context", qualify=False)
                    end = self.ref_name(current, "connectionEnd", qualify=False)
                    parts.extend(p for p in (context, end) if p)
                    current = next((c for c in current if c.tag == "next"), None)
                setattr(obj, child.tag, ".".join(parts))
            elif child.tag == "ownedPropertyAssociation":
                obj.ownedPropertyAssociations.append(property_association(self.r, child))
        return obj

    # ------------------------------------------------------------------ property sets

    def property_set(self) -> EObject:
        pset = model.new("PropertySet", name=self.unit_name, sourceFile=self.r.filename)
        for child in self.root:
            tag = child.tag
            if tag == "ownedPropertyType":
                pset.ownedPropertyTypes.append(self.located(self.property_type, child))
            elif tag == "ownedProperty":
                pset.ownedProperties.append(self.located(self.property, child))
            elif tag == "ownedPropertyConstant":
                pset.ownedPropertyConstants.append(self.located(self.constant, child))
            elif tag == "importedUnit":
                pset.withs.append(Path(child.get("href", "")).name.partition(".")[0])
            elif tag in ("ownedComment", "ownedAnnexSubclause"):
                continue
            else:
                self.r.unknown(child, "aadl2:PropertySet")
        return pset

    def property_type(self, el: etree._Element) -> EObject:
        ns, local = self.r.xsi_type(el)
        name = el.get("name")
        if ns != NS_AADL2:
            raise self.r.error(f"unknown property type xsi:type={el.get(XSI_TYPE)!r}", el, "xsi:type")
        if local in ("AadlBoolean", "AadlString"):
            return model.new(local, name=name)
        if local in ("AadlInteger", "AadlReal"):
            obj = model.new(local, name=name)
            obj.unitsType = self.ref_name(el, "referencedUnitsType", qualify=True)
            for child in el:
                if child.tag == "ownedUnitsType":
                    obj.ownedUnitsType = self.units_type(child)
            return obj
        if local == "UnitsType":
            return self.units_type(el)
        if local == "EnumerationType":
            obj = model.new("EnumerationType", name=name)
            obj.ownedLiterals.extend(
                model.new("EnumerationLiteral", name=c.get("name")) for c in el if c.tag == "ownedLiteral"
            )
            return obj
        if local == "RangeType":
            obj = model.new(
                "RangeType", name=name, numberType=self.ref_name(el, "referencedNumberType", qualify=True)
            )
            for child in el:
                if child.tag == "ownedNumberType":
                    obj.ownedNumberType = self.property_type(child)
            return obj
        if local == "ListType":
            obj = model.new(
                "ListType", name=name, elementType=self.ref_name(el, "referencedElementType", qualify=True)
            )
            for child in el:
                if child.tag == "ownedElementType":
                    obj.ownedElementType = self.property_type(child)
            return obj
        if local == "RecordType":
            obj = model.new("RecordType", name=name)
            for child in el:
                if child.tag == "ownedField":
                    fld = model.new(
                        "RecordField",
                        name=child.get("name"),
                        type=self.ref_name(child, "referencedPropertyType", qualify=True),
                    )
                    for part in child:
                        if part.tag == "ownedPropertyType":
                            fld.ownedType = self.property_type(part)
                    obj.ownedFields.append(fld)
            return obj
        if local in ("ClassifierType", "ReferenceType"):
            obj = model.new(local, name=name)
            for child in el:
                obj.categories.extend(m.text.strip() for m in child if m.tag == "metaclassName" and m.text)
            return obj
        raise self.r.error(f"unknown property type xsi:type={el.get(XSI_TYPE)!r}", el, "xsi:type")

    def units_type(self, el: etree._Element) -> EObject:
        obj = model.new("UnitsType", name=el.get("name"))
        for child in el:
            if child.tag != "ownedLiteral":
                continue
            literal = model.new("UnitLiteral", name=child.get("name"))
            if child.get("baseUnit"):
                literal.baseUnit = self.ref_name(child, "baseUnit", qualify=False)
            for part in child:
                if part.tag == "factor":
                    literal.factor = read_value(self.r, part, None, None)
            obj.ownedLiterals.append(literal)
        return obj

    def property(self, el: etree._Element) -> EObject:
        obj = model.new(
            "Property",
            name=el.get("name"),
            inherit=el.get("inherit") == "true",
            type=self.ref_name(el, "referencedPropertyType", qualify=True),
        )
        for child in el:
            if child.tag == "ownedPropertyType":
                obj.ownedType = self.property_type(child)
            elif child.tag == "appliesTo":
                obj.appliesTo.extend(m.text.strip() for m in child if m.tag == "metaclassName" and m.text)
            elif child.tag == "defaultValue":
                obj.defaultValue = read_value(self.r, child, None, None)
        return obj

    def constant(self, el: etree._Element) -> EObject:
        obj = model.new(
            "PropertyConstant",
            name=el.get("name"),
            type=self.ref_name(el, "referencedPropertyType", qualify=True),
        )
        for child in el:
            if child.tag == "ownedPropertyType":
                obj.ownedType = self.property_type(child)
            elif child.tag == "constantValue":
                obj.value = read_value(self.r, child, None, None)
        return obj

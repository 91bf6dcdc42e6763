"""Where the declarative elements of an instance are, as OSATE's hrefs name them.

An instance file links each instance object to its declaration in the ``.aadl`` sources:
classifiers and properties by qualified name, every ``::`` written ``.`` (``../P.aadl#P.T.impl``,
``../a-b.aadl#a.b.T.impl``: :func:`~.vocabulary.name_fragment`), subcomponents, features,
connections, modes and flows by position, counted the way OSATE's Xtext model holds them
(classifiers per package section, members per containment list of their class:
``#/0/@ownedPublicSection/@ownedClassifier.10/@ownedAbstractSubcomponent.0``).
:class:`Declarations` finds each declaration through the model's
:class:`~rosaadl.resolution.Resolver` and gives its ``(xsi:type, href)``; it records the units
the file refers to (the sidecars to write), the units known only by name, and how many links
it could not make (reported once per kind).
"""

from __future__ import annotations

from typing import Any

from pyecore.ecore import EObject

from rosaadl.importers import osate_eras
from rosaadl.model import is_a

from .emf_text import literal_name
from .osate_sets import osate_set
from .property_types import unit_of
from .vocabulary import (
    CATEGORY_CLASS,
    CLASS_OF_STEP,
    CONNECTION_CLASS,
    ERA,
    FEATURE_CLASS,
    OSATE_PACKAGES,
    OWNED_STEP_RE,
    name_fragment,
)

__all__ = ["Declarations", "find_named"]


def find_named(items: Any, name: str | None) -> EObject | None:
    """The first of ``items`` named ``name`` (AADL names: case-insensitive), or None."""
    wanted = (name or "").lower()
    for item in items:
        if (item.name or "").lower() == wanted:
            return item
    return None


class Declarations:
    """The links of one export into its declarative model (``resolver``; None when the model
    has none, as after reading an ``.aaxl2`` file: then only names are known)."""

    def __init__(self, resolver: Any) -> None:
        self.resolver = resolver
        # what one writing of the document used and missed (see reset)
        self.used_units: dict[int, EObject] = {}
        self.guessed_units: dict[str, str] = {}
        self.missing: dict[str, int] = {}
        # caches, valid for the whole export
        self.classifier_cache: dict[str, EObject | None] = {}
        self.classifier_frag: dict[int, str] = {}
        self.member_frag: dict[int, str] = {}
        self.href_cache: dict[tuple, Any] = {}

    def reset(self) -> None:
        """Forget the units used and the links missed (the document is written again)."""
        self.used_units.clear()
        self.guessed_units.clear()
        self.missing.clear()

    def note_missing(self, what: str) -> None:
        """One more ``what`` link left out (its declaration is not in the model)."""
        self.missing[what] = self.missing.get(what, 0) + 1

    def unit_uri(self, unit: EObject) -> str:
        """The URI of a unit's file: OSATE's for its own sets and packages, else
        ``../<file>.aadl`` beside the instances folder (a sidecar to write)."""
        name = unit.name or ""
        if osate_set(name):
            return osate_eras.predeclared_uri(ERA, name)
        package = OSATE_PACKAGES.get(name.lower())
        if package is not None:
            return package
        from rosaadl.exporters.aadl_text import unit_file_name

        self.used_units.setdefault(id(unit), unit)
        return f"../{unit_file_name(unit)}"

    def uri_for_name(self, unit_name: str) -> str:
        """The URI of a unit known only by name (no declarative model): OSATE's, or ``../X.aadl``."""
        if osate_set(unit_name):
            return osate_eras.predeclared_uri(ERA, unit_name)
        package = OSATE_PACKAGES.get(unit_name.lower())
        if package is not None:
            return package
        self.guessed_units.setdefault(unit_name.lower(), unit_name)
        return "../" + "-".join(part.strip() for part in unit_name.split("::")) + ".aadl"

    def classifier(self, name: str | None) -> EObject | None:
        """The classifier ``name`` of the model (None without one, or for a kept reference)."""
        if not name or self.resolver is None or "#" in name:
            return None
        key = name.lower()
        if key not in self.classifier_cache:
            self.classifier_cache[key] = self.resolver.classifier(name)
        return self.classifier_cache[key]

    def classifier_fragment(self, classifier: EObject) -> str | None:
        """A classifier's path in its package, counted per section
        (``@ownedPublicSection/@ownedClassifier.3``)."""
        found = self.classifier_frag.get(id(classifier))
        if found is not None:
            return found
        package = classifier.eContainer()
        if package is None or not is_a(package, "AadlPackage"):
            return None
        counts = {"public": 0, "private": 0}
        for item in package.classifiers:
            section = "private" if literal_name(item.visibility) == "private" else "public"
            step = "ownedPrivateSection" if section == "private" else "ownedPublicSection"
            self.classifier_frag[id(item)] = f"@{step}/@ownedClassifier.{counts[section]}"
            counts[section] += 1
        return self.classifier_frag.get(id(classifier))

    @staticmethod
    def classifier_class(classifier: EObject) -> str:
        """The aadl2 class of a classifier (``ThreadImplementation``, ``FeatureGroupType``)."""
        if is_a(classifier, "FeatureGroupType"):
            return "FeatureGroupType"
        stem = CATEGORY_CLASS.get(literal_name(classifier.category), "Abstract")
        return stem + ("Implementation" if is_a(classifier, "ComponentImplementation") else "Type")

    def classifier_href(self, name: str | None, category: Any, *, implementation: bool = False):
        """(xsi:type, href) of a classifier named ``name`` (None when there is none)."""
        if not name:
            return None
        key = ("classifier", name, literal_name(category), implementation)
        if key in self.href_cache:
            return self.href_cache[key]
        element = self.classifier(name)
        if element is not None:
            unit = unit_of(element)
            href = f"{self.unit_uri(unit)}#{name_fragment(unit.name, element.name)}"
            found = (f"aadl2:{self.classifier_class(element)}", href)
        elif "#" in name:
            # kept as written by the reader: a positional reference names no kind of classifier
            stem = CATEGORY_CLASS.get(literal_name(category), "Abstract")
            found = (f"aadl2:{stem}Implementation" if implementation else f"aadl2:{stem}Type", name)
        else:
            package, _, local = name.rpartition("::")
            if not package:
                self.note_missing("classifier without a package")
                found = None
            else:
                stem = CATEGORY_CLASS.get(literal_name(category), "Abstract")
                suffix = "Implementation" if "." in local or implementation else "Type"
                href = f"{self.uri_for_name(package)}#{name_fragment(package, local)}"
                found = (f"aadl2:{stem}{suffix}", href)
        self.href_cache[key] = found
        return found

    def member_fragment(self, element: EObject) -> str | None:
        """Path of a feature, subcomponent, connection, mode, transition or flow in its unit."""
        found = self.member_frag.get(id(element))
        if found is not None:
            return found
        owner = element.eContainer()
        if owner is None or not is_a(owner, "Classifier"):
            return None
        head = self.classifier_fragment(owner)
        if head is None:
            return None
        feature = element.eContainmentFeature().name
        counts: dict[str, int] = {}
        for item in getattr(owner, feature):
            cls = self.member_class(item)
            if cls is None:
                continue
            position = counts.get(cls, 0)
            counts[cls] = position + 1
            self.member_frag[id(item)] = f"{head}/@owned{cls}.{position}"
        return self.member_frag.get(id(element))

    @staticmethod
    def member_class(element: EObject) -> str | None:
        """The aadl2 class of a classifier member (``DataPort``, ``ThreadSubcomponent``, ...)."""
        if is_a(element, "Feature"):
            return FEATURE_CLASS.get(literal_name(element.category))
        if is_a(element, "Subcomponent"):
            stem = CATEGORY_CLASS.get(literal_name(element.category))
            return f"{stem}Subcomponent" if stem else None
        if is_a(element, "Connection"):
            return CONNECTION_CLASS.get(literal_name(element.kind))
        kind = element.eClass.name  # these classes have the same name in aadl2
        if kind in ("Mode", "ModeTransition", "FlowSpecification", "EndToEndFlow"):
            return kind
        return None

    def member_href(self, element: EObject | None) -> tuple[str, str] | None:
        """(xsi:type, href) of a classifier member, or None when it cannot be placed."""
        if element is None:
            return None
        fragment = self.member_fragment(element)
        cls = self.member_class(element)
        unit = unit_of(element)
        if fragment is None or cls is None or unit is None:
            return None
        return f"aadl2:{cls}", f"{self.unit_uri(unit)}#{osate_eras.fragment(ERA, fragment)}"

    @staticmethod
    def opaque_href(text: str) -> tuple[str | None, str]:
        """A reference the reader kept as ``uri#fragment``, with the class its last step names."""
        _uri, _, fragment = text.partition("#")
        match = OWNED_STEP_RE.search(fragment)
        cls = match.group(1) if match and match.group(1) in CLASS_OF_STEP else None
        return (f"aadl2:{cls}" if cls else None), text

    def component_classifier(self, ci: EObject | None) -> EObject | None:
        """The classifier of a component instance, from the model."""
        return self.classifier(ci.classifier) if ci is not None else None

    def subcomponent_href(self, ci: EObject) -> tuple[str, str] | None:
        parent = ci.eContainer()
        impl = self.component_classifier(parent) if parent is not None else None
        key = ("sub", id(impl), (ci.subcomponent or ci.name or "").lower())
        if key in self.href_cache:
            return self.href_cache[key]
        found = None
        if impl is not None and is_a(impl, "ComponentImplementation"):
            found = self.member_href(
                find_named(self.resolver.subcomponents(impl), ci.subcomponent or ci.name)
            )
        self.href_cache[key] = found
        return found

    def feature_decl(self, fi: EObject, decls: dict[int, EObject | None]) -> EObject | None:
        """The declaration of a feature instance (the most refined one), or None."""
        parent = fi.eContainer()
        if parent is None or self.resolver is None:
            return None
        if is_a(parent, "FeatureInstance"):
            group = decls.get(id(parent))
            if group is None:
                return None
            fgt = self.resolver.feature_classifier(group)
            if fgt is None or not is_a(fgt, "FeatureGroupType"):
                return None
            members, _inverted = self.resolver.feature_group_features(fgt)
            return find_named(members, fi.feature or fi.name)
        classifier = self.component_classifier(parent)
        if classifier is None:
            return None
        key = ("features", id(classifier))
        members = self.href_cache.get(key)
        if members is None:
            members = self.resolver.features(classifier)
            self.href_cache[key] = members  # type: ignore[assignment]
        return find_named(members, fi.feature or fi.name)  # type: ignore[arg-type]

    def connection_href(self, ref: EObject) -> tuple[str | None, str] | None:
        text = (ref.connection or "").strip()
        if not text:
            return None
        if "#" in text:
            return self.opaque_href(text)
        context = ref.context
        impl = self.component_classifier(context)
        key = ("conn", id(impl), text.lower())
        if key in self.href_cache:
            return self.href_cache[key]
        found = None
        if impl is not None and is_a(impl, "ComponentImplementation"):
            found = self.member_href(find_named(self.resolver.connections(impl), text.rpartition("::")[2]))
        self.href_cache[key] = found
        return found

    def mode_href(self, mi: EObject) -> tuple[str, str] | None:
        owner = mi.eContainer()
        classifier = self.component_classifier(owner)
        if classifier is None:
            return None
        return self.member_href(find_named(self.resolver.modes(classifier), mi.mode or mi.name))

    def transition_href(self, mti: EObject) -> tuple[str, str] | None:
        owner = mti.eContainer()
        classifier = self.component_classifier(owner)
        if classifier is None:
            return None
        transitions = self.resolver.mode_transitions(classifier)
        found = find_named(transitions, mti.name)
        if found is None and mti.source is not None and mti.destination is not None:
            src, dst = (mti.source.name or "").lower(), (mti.destination.name or "").lower()
            candidates = [
                t
                for t in transitions
                if (t.source or "").lower() == src and (t.destination or "").lower() == dst
            ]
            found = candidates[0] if len(candidates) == 1 else None
        return self.member_href(found)

    def flow_spec_href(self, fsi: EObject) -> tuple[str, str] | None:
        classifier = self.component_classifier(fsi.eContainer())
        if classifier is None:
            return None
        return self.member_href(find_named(self.resolver.flow_specifications(classifier), fsi.name))

    def end_to_end_href(self, flow: EObject) -> tuple[str, str] | None:
        impl = self.component_classifier(flow.eContainer())
        if impl is None:
            return None
        return self.member_href(find_named(self.resolver.end_to_end_flows(impl), flow.flow or flow.name))

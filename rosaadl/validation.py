"""Metamodel-level validation of any of our models: multiplicities, dangling references, names."""

from __future__ import annotations

from pyecore.ecore import EObject, EProxy

from rosaadl import model
from rosaadl.element_keys import element_key
from rosaadl.errors import Diagnostic, Location

__all__ = ["validate"]

# Elements AADL requires a name for (property types, connections and modal values may be anonymous)
_NAME_REQUIRED = (
    "aadl.ModelUnit",
    "aadl.Classifier",
    "aadl.Feature",
    "aadl.Subcomponent",
    "aadl.Property",
    "aadl.PropertyConstant",
    "aadl.ComponentInstance",
    "aadl.FeatureInstance",
)


def _where(obj: EObject) -> str:
    return element_key(obj)


def validate(root: EObject, filename: str | None = None) -> list[Diagnostic]:
    """Check every object under ``root``; returns error diagnostics (empty when valid)."""
    problems: list[Diagnostic] = []

    def report(obj: EObject, message: str) -> None:
        line = getattr(obj, "line", None) if obj.eClass.findEStructuralFeature("line") is not None else None
        problems.append(
            Diagnostic("error", message, Location(file=filename, line=line or None, path=_where(obj)))
        )

    for obj in model.walk(root):
        eclass = obj.eClass
        for feature in eclass.eAllStructuralFeatures():
            value = obj.eGet(feature)
            if feature.lowerBound > 0:
                missing = (len(value) < feature.lowerBound) if feature.many else value is None
                if missing:
                    report(obj, f"{eclass.name}.{feature.name} is required (at least {feature.lowerBound})")
            if (
                hasattr(feature, "containment")
                and not getattr(feature, "containment", True)
                and value is not None
            ):
                targets = value if feature.many else [value]
                for target in targets:
                    if isinstance(target, EProxy):
                        try:
                            target.force_resolve()
                        except Exception:
                            report(
                                obj, f"{eclass.name}.{feature.name} refers to an object that does not exist"
                            )
        if any(model.is_a(obj, cls) for cls in _NAME_REQUIRED) and not obj.name:
            report(obj, f"{eclass.name} has no name (expected an AADL identifier)")
    return problems

"""What the ``.aaxl2`` reader needs from ``aadl.ecore``, looked up once per process.

The metamodel classes by name (prepared for :class:`~rosaadl.bulk.FastFactory`, so that the
reader makes their objects with ``object.__new__``), the feature slots it fills, the
enumeration literals by name and by AADL spelling, and the attributes every
:class:`~rosaadl.importers.aaxl2.document.Reader` starts with, copied in one step.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from typing import Any

from pyecore.ecore import EClass, EEnum

from rosaadl import metamodels
from rosaadl.bulk import FastFactory, FeatureSlot
from rosaadl.errors import RosaadlError

__all__ = ["MetamodelFacts", "metamodel_facts"]


@dataclass(frozen=True)
class MetamodelFacts:
    """What the reader needs from aadl.ecore, looked up once per process (immutable metadata)."""

    eclasses: dict[str, EClass]
    enums: dict[str, EEnum]
    classes: dict[str, type]
    slots: dict[str, FeatureSlot]
    enum_literals: dict[tuple[str, str], Any]
    # the attributes every Reader starts with (read-only to it)
    reader_constants: dict[str, Any]


@cache
def metamodel_facts() -> MetamodelFacts:
    mm = metamodels.load().aadl
    eclasses = {c.name: c for c in mm.eClassifiers if isinstance(c, EClass)}
    enums = {c.name: c for c in mm.eClassifiers if isinstance(c, EEnum)}
    classes = {name: ec.python_class for name, ec in eclasses.items()}
    for name, cls in classes.items():
        if not eclasses[name].abstract:
            FastFactory.prepare(cls)  # the reader makes their objects with object.__new__
    factory = FastFactory()
    f = {}
    wanted = {
        "AadlModel": ("name", "instances", "componentInstances", "units"),
        "ComponentInstance": (
            "name",
            "category",
            "classifier",
            "subcomponent",
            "index",
            "componentInstances",
            "featureInstances",
            "connectionInstances",
            "modeInstances",
            "modeTransitionInstances",
            "flowSpecifications",
            "endToEndFlows",
            "inModes",
            "annexInstances",
            "ownedPropertyAssociations",
        ),
        "SystemInstance": ("systemOperationModes",),
        "FeatureInstance": (
            "name",
            "category",
            "direction",
            "feature",
            "index",
            "featureInstances",
            "type",
            "ownedPropertyAssociations",
        ),
        "ConnectionInstance": (
            "name",
            "kind",
            "bidirectional",
            "complete",
            "source",
            "destination",
            "connectionReferences",
            "inSystemOperationModes",
            "ownedPropertyAssociations",
        ),
        "ConnectionReference": ("connection", "context", "source", "destination"),
        "ModeInstance": ("name", "initial", "mode", "ownedPropertyAssociations"),
        "ModeTransitionInstance": (
            "name",
            "source",
            "destination",
            "triggers",
            "ownedPropertyAssociations",
        ),
        "FlowSpecificationInstance": (
            "name",
            "kind",
            "source",
            "destination",
            "ownedPropertyAssociations",
        ),
        "EndToEndFlowInstance": ("name", "flow", "flowElements", "ownedPropertyAssociations"),
        "SystemOperationMode": ("name", "currentModes"),
        "AnnexInstance": ("name", "text"),
        "PropertyAssociation": ("property", "append", "constant", "ownedValues"),
        "ModalPropertyValue": ("value", "inModes"),
        "IntegerValue": ("value", "unit"),
        "RealValue": ("value", "unit"),
        "RangeValue": ("minimum", "maximum", "delta"),
        "BooleanValue": ("value",),
        "StringValue": ("value",),
        "NamedValue": ("name",),
        "ReferenceValue": ("path",),
        "ClassifierValue": ("classifier",),
        "ListValue": ("ownedItems",),
        "RecordValue": ("ownedFields",),
        "FieldValue": ("name", "value"),
        "ComputedValue": ("function",),
        "OperationValue": ("operator", "ownedOperands"),
        "InstanceReferenceValue": ("referencedInstanceObject",),
    }
    for cname, names in wanted.items():
        ec = eclasses[cname]
        for name in names:
            try:
                f[f"{cname}.{name}"] = factory.slot(ec, name)
            except KeyError:
                raise RosaadlError(f"metamodel class {cname} lacks feature {name}") from None
    literals = {}
    for enum in enums.values():
        for literal in enum.eLiterals:
            for text in (literal.name, literal.literal):
                if text:
                    literals[(enum.name, text)] = literal
    constants = {
        "fast": factory,
        # the classes are prepared (above): FastFactory.new without its check
        "new": object.__new__,
        "ec": eclasses,
        "enums": enums,
        "cls": classes,
        "f": f,
        "c_pa": classes["PropertyAssociation"],
        "c_modal": classes["ModalPropertyValue"],
        "c_int": classes["IntegerValue"],
        "c_real": classes["RealValue"],
        "s_pa_property": f["PropertyAssociation.property"],
        "s_pa_values": f["PropertyAssociation.ownedValues"],
        "s_modal_value": f["ModalPropertyValue.value"],
        "s_int_value": f["IntegerValue.value"],
        "s_int_unit": f["IntegerValue.unit"],
        "s_real_value": f["RealValue.value"],
        "s_real_unit": f["RealValue.unit"],
        "s_named_name": f["NamedValue.name"],
        "s_reference_ends": tuple(
            (end, f[f"ConnectionReference.{end}"]) for end in ("context", "source", "destination")
        ),
        "s_connection_ends": tuple(
            (end, f[f"ConnectionInstance.{end}"]) for end in ("source", "destination")
        ),
    }
    return MetamodelFacts(eclasses, enums, classes, f, literals, constants)

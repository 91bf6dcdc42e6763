"""The metamodels: every concept of ARCHITECTURE section 3, the pyecore pitfalls, and persistence."""

from __future__ import annotations

import itertools
from decimal import Decimal

import pytest
from pyecore.ecore import EAttribute, EClass, EEnum, EReference

from rosaadl import metamodels, model
from rosaadl.errors import ModelError

SECTION_3 = {
    "aadl": [
        "AadlModel",
        "AadlPackage",
        "PropertySet",
        "Property",
        "PropertyType",
        "PropertyConstant",
        "ComponentType",
        "ComponentImplementation",
        "FeatureGroupType",
        "Feature",
        "Subcomponent",
        "Connection",
        "FlowSpecification",
        "FlowImplementation",
        "EndToEndFlow",
        "Mode",
        "ModeTransition",
        "PropertyAssociation",
        "ModalPropertyValue",
        "IntegerValue",
        "RealValue",
        "RangeValue",
        "BooleanValue",
        "StringValue",
        "NamedValue",
        "EnumerationType",
        "EnumerationLiteral",
        "UnitsType",
        "UnitLiteral",
        "ReferenceValue",
        "ClassifierValue",
        "ListValue",
        "RecordValue",
        "FieldValue",
        "ComputedValue",
        "SystemInstance",
        "ComponentInstance",
        "FeatureInstance",
        "ConnectionInstance",
        "ConnectionReference",
        "ModeInstance",
        "SystemOperationMode",
        "EndToEndFlowInstance",
        "InstanceReferenceValue",
        "AnnexSubclause",
        "AnnexLibrary",
    ],
    "rosmod": [
        "Project",
        "Software",
        "Package",
        "Message",
        "Service",
        "Component",
        "Timer",
        "Publisher",
        "Subscriber",
        "Client",
        "Server",
        "System",
        "Host",
        "Network",
        "Link",
        "Deployment",
        "Node",
        "ComponentInstance",
    ],
    "trace": ["Trace", "TraceLink", "TraceElement"],
}

CATEGORIES = [
    "abstract",
    "bus",
    "data",
    "device",
    "memory",
    "process",
    "processor",
    "subprogram",
    "subprogram group",
    "system",
    "thread",
    "thread group",
    "virtual bus",
    "virtual processor",
]


@pytest.mark.parametrize(("package", "name"), [(p, n) for p, names in SECTION_3.items() for n in names])
def test_every_section_3_class_exists(package: str, name: str) -> None:
    pkg = getattr(metamodels.load(), package)
    assert isinstance(pkg.getEClassifier(name), EClass), f"{package}.{name} missing"


def test_all_14_categories() -> None:
    enum = metamodels.aadl().getEClassifier("ComponentCategory")
    assert [lit.literal or lit.name for lit in enum.eLiterals] == CATEGORIES


def test_metamodels_are_not_registered_process_wide() -> None:
    from pyecore.resources import global_registry

    for package in metamodels.load().packages():
        assert package.nsURI not in global_registry


def test_enum_literal_spelling_differs_from_name_and_round_trips() -> None:
    ct = model.new("ComponentType", name="T", category="thread group")
    assert ct.category.name == "threadGroup"
    data = model.dumps_xmi(ct)
    assert b'category="thread group"' in data
    assert model.loads_xmi(data).category.name == "threadGroup"
    # the name is accepted on input too
    assert model.loads_xmi(data.replace(b"thread group", b"threadGroup")).category.literal == "thread group"


def test_unknown_enum_literal_is_a_located_error() -> None:
    data = model.dumps_xmi(model.new("ComponentType", name="T", category="thread"))
    bad = data.replace(b'category="thread"', b'category="threed"')
    with pytest.raises(ModelError) as info:
        model.loads_xmi(bad, "bad.xmi")
    assert "threed" in str(info.value) and info.value.location.file == "bad.xmi"
    assert info.value.location.line == 2


def test_custom_datatype_loads_as_decimal_not_string() -> None:
    timer = model.new("rosmod.Timer", name="t", period=Decimal("0.300"), priority=50)
    for dump, load in ((model.dumps_xmi, model.loads_xmi), (model.dumps_json, model.loads_json)):
        back = load(dump(timer))
        assert back.period == Decimal("0.300") and isinstance(back.period, Decimal)
        assert str(back.period) == "0.300"
        assert back.priority == 50 and isinstance(back.priority, int)


def test_numbers_and_booleans_load_typed() -> None:
    value = model.new("IntegerValue", value=2**40, unit="us")
    assert model.loads_xmi(model.dumps_xmi(value)).value == 2**40
    real = model.new("RealValue", value=0.1)
    assert model.loads_json(model.dumps_json(real)).value == 0.1
    flag = model.new("BooleanValue", value=True)
    assert model.loads_xmi(model.dumps_xmi(flag)).value is True


@pytest.mark.parametrize("ctor", ["generated-class", "model-api"])
def test_misspelled_keyword_arguments_are_rejected(ctor: str) -> None:
    with pytest.raises(ModelError, match="nmae"):
        if ctor == "model-api":
            model.new("ComponentType", nmae="x")
        else:
            model.eclass_of("ComponentType")(nmae="x")


def test_abstract_classes_cannot_be_created() -> None:
    with pytest.raises(ModelError, match="abstract"):
        model.new("Classifier", name="x")


# ------------------------------------------------------------------ one object of every class


def _concrete_subclasses(eclass: EClass, all_classes: list[EClass]) -> list[EClass]:
    return [c for c in all_classes if not c.abstract and (c is eclass or eclass in c.eAllSuperTypes())]


def _sample(attr: EAttribute, counter: itertools.count):
    etype = attr.eType
    n = next(counter)
    if isinstance(etype, EEnum):
        return etype.eLiterals[-1 - (n % len(etype.eLiterals))]
    name = etype.name
    if name == "EString":
        return f"{attr.name}_{n} with space & <xml>"
    if name in ("EInt", "ELong"):
        return n * 7 + (2**40 if name == "ELong" else 0)
    if name == "EDouble":
        return n + 0.25
    if name == "EBoolean":
        return True
    if name == "Seconds":
        return Decimal(f"0.{n:03d}")
    raise AssertionError(f"no sample for data type {name}")


def _full_model(root_class: str):
    mm = metamodels.load()
    classes = [c for p in mm.packages() for c in p.eClassifiers if isinstance(c, EClass)]
    counter = itertools.count(1)
    root = model.new(root_class)
    made: dict[str, list] = {}
    queue = [root]
    while queue:
        obj = queue.pop(0)
        made.setdefault(obj.eClass.name, []).append(obj)
        for feature in obj.eClass.eAllStructuralFeatures():
            if isinstance(feature, EAttribute):
                values = [_sample(feature, counter)] + ([_sample(feature, counter)] if feature.many else [])
                if feature.many:
                    obj.eGet(feature).extend(values)
                else:
                    obj.eSet(feature, values[0])
            elif isinstance(feature, EReference) and feature.containment:
                for sub in _concrete_subclasses(feature.eType, classes):
                    if sub.name in made and not feature.lowerBound:
                        continue
                    if not feature.many and obj.eGet(feature) is not None:
                        continue
                    child = sub()
                    made.setdefault(sub.name, [])  # reserve: one of each class is enough
                    if feature.many:
                        obj.eGet(feature).append(child)
                    else:
                        obj.eSet(feature, child)
                    queue.append(child)
    everything = list(model.walk(root))
    for obj in everything:  # non-containment references point at some object of the right class
        for feature in obj.eClass.eAllReferences():
            if feature.containment or feature.transient:
                continue
            target = next(
                (o for o in everything if isinstance(o, feature.eType.python_class) and o is not obj), None
            )
            if target is None:
                continue
            if feature.many:
                obj.eGet(feature).append(target)
            else:
                obj.eSet(feature, target)
    return root, {
        c.name for c in classes if not c.abstract and c.ePackage is model.eclass_of(root_class).ePackage
    }


@pytest.mark.parametrize("root_class", ["aadl.AadlModel", "rosmod.Project", "trace.Trace"])
@pytest.mark.parametrize("fmt", ["xmi", "json"])
def test_model_with_every_class_survives_save_and_load(root_class: str, fmt: str, tmp_path) -> None:
    root, expected = _full_model(root_class)
    present = {o.eClass.name for o in model.walk(root)}
    assert expected <= present, f"classes not reachable by containment: {sorted(expected - present)}"
    path = model.save(root, tmp_path / f"every.{fmt}")
    back = model.load(path)
    assert model.model_differences(root, back) == []
    # deterministic: saving the reloaded model gives the same bytes
    again = model.save(back, tmp_path / f"again.{fmt}")
    assert again.read_bytes() == path.read_bytes()

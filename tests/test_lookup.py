"""Property value lookup on declarative elements and instance objects (rosaadl.lookup)."""

from __future__ import annotations

import pytest

from benchmarks.generators.declarative import (
    deadline_definition,
    period_definition,
    processor_binding_definition,
    time_units,
)
from rosaadl import model
from rosaadl.errors import ModelError
from rosaadl.lookup import PropertyLookup, accepts
from rosaadl.properties import EnumLiteral, Range
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity

new = model.new


def _pa(prop, value, applies_to=(), append=False, in_binding=(), modes=None):
    values = (
        [new("ModalPropertyValue", value=v, inModes=m) for v, m in modes]
        if modes is not None
        else [new("ModalPropertyValue", value=value)]
    )
    return new(
        "PropertyAssociation",
        property=prop,
        appliesTo=list(applies_to),
        append=append,
        inBinding=list(in_binding),
        ownedValues=values,
    )


def _ms(value):
    return new("IntegerValue", value=value, unit="ms")


def _property_sets():
    time = new("AadlInteger", name="Time", unitsType="AADL_Project::Time_Units")
    project = new(
        "PropertySet",
        name="AADL_Project",
        ownedPropertyTypes=[
            time_units("us", "ms"),
            time,
            new("RangeType", name="Time_Range", numberType="AADL_Project::Time"),
        ],
        ownedPropertyConstants=[
            new("PropertyConstant", name="Fast", type="AADL_Project::Time", value=_ms(2))
        ],
    )
    all_components = ["thread", "process", "system", "processor", "device"]
    timing = new(
        "PropertySet",
        name="Timing_Properties",
        ownedProperties=[
            period_definition(all_components),
            deadline_definition(all_components),
            new(
                "Property",
                name="Compute_Execution_Time",
                type="AADL_Project::Time_Range",
                appliesTo=["thread"],
            ),
            new("Property", name="Not_Inherited", type="AADL_Project::Time", appliesTo=all_components),
        ],
    )
    comm = new(
        "PropertySet",
        name="Communication_Properties",
        ownedProperties=[
            new(
                "Property",
                name="Timing",
                ownedType=new(
                    "EnumerationType",
                    ownedLiterals=[
                        new("EnumerationLiteral", name=n) for n in ("sampled", "immediate", "delayed")
                    ],
                ),
                defaultValue=new("NamedValue", name="sampled"),
                appliesTo=["port connection"],
            ),
            new(
                "Property",
                name="Latency",
                type="AADL_Project::Time_Range",
                appliesTo=["connection", "feature"],
            ),
        ],
    )
    memory = new(
        "PropertySet",
        name="Memory_Properties",
        ownedProperties=[new("Property", name="Data_Size", ownedType=new("AadlInteger"), appliesTo=["data"])],
    )
    deployment = new(
        "PropertySet",
        name="Deployment_Properties",
        ownedProperties=[
            processor_binding_definition(["thread", "process", "system"]),
            new(
                "Property",
                name="Source_Names",
                ownedType=new("ListType", ownedElementType=new("AadlString")),
                appliesTo=["thread", "process"],
            ),
        ],
    )
    return [project, timing, comm, memory, deployment]


@pytest.fixture
def ws():
    """sys.i contains proc (p.i) with threads t1 (worker) and t2 (worker.fast); a cpu."""
    ws = new("AadlModel", name="ws")
    ws.units.extend(_property_sets())
    pkg = new("AadlPackage", name="M", sourceFile="m.aadl")
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="msg",
            category="data",
            ownedPropertyAssociations=[_pa("Data_Size", new("IntegerValue", value=16))],
        )
    )
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="base_worker",
            category="thread",
            ownedPropertyAssociations=[_pa("Period", _ms(100)), _pa("Not_Inherited", _ms(1))],
        )
    )
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="worker",
            category="thread",
            extended="base_worker",
            features=[
                new("Feature", name="o", category="event data port", direction="out", classifier="msg"),
                new("Feature", name="i", category="event data port", direction="in", classifier="msg"),
            ],
            ownedPropertyAssociations=[
                _pa("Compute_Execution_Time", new("RangeValue", minimum=_ms(1), maximum=_ms(2))),
                _pa("Source_Names", new("ListValue", ownedItems=[new("StringValue", value="w.c")])),
            ],
        )
    )
    pkg.classifiers.append(
        new(
            "ComponentImplementation",
            name="worker.fast",
            type="worker",
            category="thread",
            ownedPropertyAssociations=[
                _pa("Period", new("NamedValue", name="AADL_Project::Fast")),
                _pa(
                    "Source_Names",
                    new("ListValue", ownedItems=[new("StringValue", value="fast.c")]),
                    append=True,
                ),
            ],
        )
    )
    pkg.classifiers.append(new("ComponentType", name="p", category="process"))
    pkg.classifiers.append(
        new(
            "ComponentImplementation",
            name="p.i",
            type="p",
            category="process",
            subcomponents=[
                new("Subcomponent", name="t1", category="thread", classifier="worker"),
                new(
                    "Subcomponent",
                    name="t2",
                    category="thread",
                    classifier="worker.fast",
                    ownedPropertyAssociations=[
                        _pa("Compute_Execution_Time", new("RangeValue", minimum=_ms(3), maximum=_ms(4)))
                    ],
                ),
            ],
            connections=[
                new(
                    "Connection",
                    name="c",
                    kind="port",
                    source="t1.o",
                    destination="t2.i",
                    ownedPropertyAssociations=[_pa("Timing", new("NamedValue", name="IMMEDIATE"))],
                )
            ],
            ownedPropertyAssociations=[
                _pa("Compute_Execution_Time", new("RangeValue", minimum=_ms(5), maximum=_ms(6)), ["t1"]),
                _pa("Latency", new("RangeValue", minimum=_ms(1), maximum=_ms(1)), ["t1.o"]),
            ],
        )
    )
    pkg.classifiers.append(new("ComponentType", name="cpu", category="processor"))
    pkg.classifiers.append(new("ComponentType", name="sys", category="system"))
    pkg.classifiers.append(
        new(
            "ComponentImplementation",
            name="sys.i",
            type="sys",
            category="system",
            subcomponents=[
                new("Subcomponent", name="proc", category="process", classifier="p.i"),
                new("Subcomponent", name="cpu", category="processor", classifier="cpu"),
            ],
            ownedPropertyAssociations=[
                _pa("Compute_Execution_Time", new("RangeValue", minimum=_ms(7), maximum=_ms(8)), ["proc.t1"]),
                _pa("Period", _ms(50), ["proc"]),
                _pa(
                    "Actual_Processor_Binding",
                    new("ListValue", ownedItems=[new("ReferenceValue", path="cpu")]),
                    ["proc"],
                ),
            ],
        )
    )
    ws.units.append(pkg)
    return ws


def _c(ws, name):
    return model.find_classifier(ws, name)


def test_classifier_chain_and_units(ws):
    lookup = PropertyLookup(ws)
    worker = _c(ws, "M::worker")
    # the type inherits Period from the type it extends
    assert lookup.python_value(worker, "Period") == Quantity(100, "ms")
    # the implementation's own association wins over the type; constants give their value
    fast = _c(ws, "M::worker.fast")
    period = lookup.value(fast, "Timing_Properties::Period")
    assert period.eClass.name == "IntegerValue" and (period.value, period.unit) == (2, "ms")
    assert lookup.python_value(fast, "Compute_Execution_Time") == Range(Quantity(1, "ms"), Quantity(2, "ms"))
    # default values, evaluated in the same context (Deadline => Period)
    assert lookup.python_value(fast, "Deadline") == Quantity(2, "ms")
    assert lookup.value(_c(ws, "M::p"), "Deadline") is None
    assert lookup.python_value(_c(ws, "M::p"), "Deadline", default="none") == "none"
    # +=> appends to the value found further down
    assert lookup.python_value(fast, "Source_Names") == ["w.c", "fast.c"]


def test_subcomponent_and_contained_precedence(ws):
    lookup = PropertyLookup(ws)
    p_impl = _c(ws, "M::p.i")
    t1, t2 = p_impl.subcomponents
    # contained association of the enclosing implementation beats the classifier
    assert lookup.python_value(t1, "Compute_Execution_Time").minimum == Quantity(5, "ms")
    # the subcomponent's own association beats the classifier
    assert lookup.python_value(t2, "Compute_Execution_Time").minimum == Quantity(3, "ms")
    # feature: its classifier's values; contained values from the enclosing implementation
    feature = _c(ws, "M::worker").features[0]
    assert lookup.python_value(feature, "Data_Size") == 16  # from the port's data classifier
    connection = p_impl.connections[0]
    assert lookup.python_value(connection, "Timing") == EnumLiteral("immediate")
    assert str(lookup.python_value(connection, "Timing")) == "immediate"  # declared spelling


def test_instances_carry_resolved_values(ws):
    system = instantiate(ws, "M::sys.i")
    lookup = PropertyLookup(ws)
    t1 = model.find_instance(system, "proc.t1")
    t2 = model.find_instance(system, "proc.t2")
    proc = model.find_instance(system, "proc")
    # the outermost contained association wins over the nearer one
    assert lookup.python_value(t1, "Compute_Execution_Time") == Range(Quantity(7, "ms"), Quantity(8, "ms"))
    # inherit: a contained value on proc reaches its threads that have none ... but a classifier value wins
    assert lookup.python_value(t1, "Period") == Quantity(100, "ms")
    assert lookup.python_value(proc, "Period") == Quantity(50, "ms")
    assert lookup.python_value(proc, "Not_Inherited") is None
    # references become instance objects, inherited by the threads
    cpu = model.find_instance(system, "cpu")
    assert lookup.python_value(t2, "Actual_Processor_Binding") == [cpu]
    # features take their classifier's values
    out = model.find_instance(system, "proc.t1.o")
    assert lookup.python_value(out, "Latency") == Range(Quantity(1, "ms"), Quantity(1, "ms"))
    # connection instances
    conn = system.componentInstances[0].connectionInstances[0]
    assert lookup.python_value(conn, "Timing") == "immediate"


def test_instances_without_values_are_computed(ws):
    system = instantiate(ws, "M::sys.i")
    resolved = {}
    for obj in model.walk(system):
        if obj.eClass.findEStructuralFeature("ownedPropertyAssociations") is not None:
            for pa in obj.ownedPropertyAssociations:
                resolved[(model.instance_path(obj), pa.property)] = model.dumps_json(pa.ownedValues[0].value)
            obj.ownedPropertyAssociations.clear()
    lookup = PropertyLookup(ws)
    recomputed = {}
    for obj in model.walk(system):
        if obj.eClass.name in (
            "SystemInstance",
            "ComponentInstance",
            "FeatureInstance",
            "ConnectionInstance",
        ):
            for path, prop in [k for k in resolved if k[0] == model.instance_path(obj)]:
                value = lookup.value(obj, prop)
                recomputed[(path, prop)] = model.dumps_json(value)
    assert recomputed.keys() == resolved.keys()
    differing = [k for k in resolved if resolved[k] != recomputed[k]]
    # reference values are equal objects only when they point at the same instance (compared by path)
    assert all("Actual_Processor_Binding" in k[1] for k in differing)
    t2 = model.find_instance(system, "proc.t2")
    assert lookup.python_value(t2, "Actual_Processor_Binding") == [model.find_instance(system, "cpu")]


def test_modal_and_binding_values():
    ws = new("AadlModel", name="ws")
    ws.units.extend(_property_sets())
    pkg = new("AadlPackage", name="M")
    arm = new("ComponentType", name="arm", category="processor")
    x86 = new("ComponentType", name="x86", category="processor")
    fast_arm = new("ComponentType", name="fast_arm", category="processor", extended="arm")
    thread = new(
        "ComponentType",
        name="t",
        category="thread",
        modes=[new("Mode", name="a", initial=True), new("Mode", name="b")],
        ownedPropertyAssociations=[
            _pa("Period", None, modes=[(_ms(10), ["a"]), (_ms(20), ["b"]), (_ms(30), [])]),
            _pa(
                "Compute_Execution_Time",
                new("RangeValue", minimum=_ms(1), maximum=_ms(1)),
                in_binding=["arm"],
            ),
            _pa(
                "Compute_Execution_Time",
                new("RangeValue", minimum=_ms(2), maximum=_ms(2)),
                in_binding=["x86"],
            ),
        ],
    )
    pkg.classifiers.extend([arm, x86, fast_arm, thread])
    ws.units.append(pkg)
    lookup = PropertyLookup(ws)
    assert lookup.python_value(thread, "Period", in_mode="B") == Quantity(20, "ms")
    assert lookup.python_value(thread, "Period", in_mode="a") == Quantity(10, "ms")
    assert lookup.python_value(thread, "Period") == Quantity(30, "ms")
    assert lookup.python_value(thread, "Compute_Execution_Time") is None
    assert lookup.python_value(thread, "Compute_Execution_Time", in_binding="M::x86").minimum == Quantity(
        2, "ms"
    )
    # a processor that extends the named classifier matches it
    assert lookup.python_value(thread, "Compute_Execution_Time", in_binding=fast_arm).minimum == Quantity(
        1, "ms"
    )
    with pytest.raises(ModelError):
        lookup.value(thread, "Period", in_binding="M::nope")


def test_accepts_owner_words():
    prop = new("Property", name="P", appliesTo=["thread group", "port", "connection", "Pkg::T"])
    assert accepts(prop, "component", "thread group")
    assert accepts(prop, "feature", "event data port")
    assert accepts(prop, "connection", "access connection")
    only_thread = new("Property", name="Q", appliesTo=["thread", "system implementation"])
    assert accepts(only_thread, "component", "abstract")  # an abstract component takes any
    assert accepts(only_thread, "component", "system")
    assert not accepts(only_thread, "component", "process")
    assert not accepts(only_thread, "feature", "data port")
    assert accepts(new("Property", name="R", appliesTo=["all"]), "mode", "mode")
    assert accepts(None, "feature", "data port")  # unknown property: where it has a value


def test_unresolved_references_stay_reference_values(ws):
    pkg = ws.units[-1]
    pkg.classifiers[-1].ownedPropertyAssociations.append(
        _pa(
            "Actual_Processor_Binding",
            new("ListValue", ownedItems=[new("ReferenceValue", path="nowhere")]),
            ["proc.t1"],
        )
    )
    diagnostics = []
    system = instantiate(ws, "M::sys.i", diagnostics=diagnostics)
    warning = next(d for d in diagnostics if "reference (nowhere)" in d.message)
    assert warning.severity == "warning" and warning.location.path == "sys_i_Instance"
    t1 = model.find_instance(system, "proc.t1")
    value = PropertyLookup(ws).value(t1, "Actual_Processor_Binding")
    assert [item.eClass.name for item in value.ownedItems] == ["ReferenceValue"]
    assert value.ownedItems[0].path == "nowhere"


def test_bad_arguments_are_model_errors(ws):
    lookup = PropertyLookup(ws)
    worker = _c(ws, "M::worker")
    for element, prop, options in (
        (None, "Period", {}),
        ("M::worker", "Period", {}),
        (worker, 5, {}),
        (worker, worker, {}),  # a classifier is not a property definition
        (worker, "Period", {"in_binding": 5}),
    ):
        with pytest.raises(ModelError):
            lookup.value(element, prop, **options)

"""Declarative AADL models built with the model API: property definitions, and two large systems.

* The few standard property definitions the generated models (and the tests' small models) use,
  written out so that no property set has to be read: :func:`time_units`,
  :func:`period_definition`, :func:`deadline_definition`, :func:`dispatch_protocol_definition`,
  :func:`processor_binding_definition`.
* :func:`chained_system`: P processes of T threads chained by port connections, bound to one
  processor (``bench_instantiate``).
* :func:`thread_types_package`: N thread types with features and property associations, and a
  system using them (``bench_aadl_writer``).
"""

from __future__ import annotations

from typing import Any

from pyecore.ecore import EObject

from rosaadl import model

__all__ = [
    "TIME_UNITS",
    "chained_system",
    "chained_system_property_sets",
    "deadline_definition",
    "dispatch_protocol_definition",
    "period_definition",
    "processor_binding_definition",
    "thread_types_package",
    "time_units",
]

# AADL_Project::Time_Units: each literal and its factor to the one before
TIME_UNITS = {"ps": 1, "ns": 1000, "us": 1000, "ms": 1000, "sec": 1000, "min": 60, "hr": 60}


def time_units(*names: str) -> EObject:
    """``Time_Units``: the named literals of ``AADL_Project::Time_Units``, consecutive, the first
    the base unit and each next one its factor times the one before (``time_units("us", "ms")``)."""
    chain = list(TIME_UNITS)
    start = chain.index(names[0])
    if list(names) != chain[start : start + len(names)]:
        raise ValueError(f"not consecutive time units: {names}")
    literals = [model.new("UnitLiteral", name=names[0])]
    for before, name in zip(names, names[1:], strict=False):
        factor = model.new("IntegerValue", value=TIME_UNITS[name])
        literals.append(model.new("UnitLiteral", name=name, baseUnit=before, factor=factor))
    return model.new("UnitsType", name="Time_Units", ownedLiterals=literals)


def period_definition(applies_to: list[str]) -> EObject:
    """``Timing_Properties::Period``: an inherited ``AADL_Project::Time``."""
    return model.new("Property", name="Period", inherit=True, type="AADL_Project::Time", appliesTo=applies_to)


def deadline_definition(applies_to: list[str]) -> EObject:
    """``Timing_Properties::Deadline``: an inherited ``AADL_Project::Time``, the period by default."""
    return model.new(
        "Property",
        name="Deadline",
        inherit=True,
        type="AADL_Project::Time",
        defaultValue=model.new("NamedValue", name="Timing_Properties::Period"),
        appliesTo=applies_to,
    )


def dispatch_protocol_definition(applies_to: list[str]) -> EObject:
    """``Thread_Properties::Dispatch_Protocol``: an enumeration of ``Periodic`` and ``Sporadic``."""
    return model.new(
        "Property",
        name="Dispatch_Protocol",
        ownedType=model.new(
            "EnumerationType",
            ownedLiterals=[model.new("EnumerationLiteral", name=n) for n in ("Periodic", "Sporadic")],
        ),
        appliesTo=applies_to,
    )


def processor_binding_definition(applies_to: list[str], categories: list[str] | None = None) -> EObject:
    """``Deployment_Properties::Actual_Processor_Binding``: an inherited list of references (to
    the given categories only, when given)."""
    # an empty list given to model.new marks the feature as set: leave it out instead
    reference = model.new("ReferenceType", **({"categories": categories} if categories else {}))
    return model.new(
        "Property",
        name="Actual_Processor_Binding",
        inherit=True,
        ownedType=model.new("ListType", ownedElementType=reference),
        appliesTo=applies_to,
    )


# --------------------------------------------------------------------------- the instantiation system


def chained_system_property_sets() -> list[EObject]:
    """The property sets :func:`chained_system` uses: the few definitions it needs."""
    new = model.new
    size_units = new(
        "UnitsType",
        name="Size_Units",
        ownedLiterals=[
            new("UnitLiteral", name="bits"),
            new("UnitLiteral", name="Bytes", baseUnit="bits", factor=new("IntegerValue", value=8)),
        ],
    )
    project = new(
        "PropertySet",
        name="AADL_Project",
        ownedPropertyTypes=[
            time_units("ps", "ns", "us", "ms"),
            size_units,
            new("AadlInteger", name="Time", unitsType="AADL_Project::Time_Units"),
            new("RangeType", name="Time_Range", numberType="AADL_Project::Time"),
            new("AadlInteger", name="Size", unitsType="AADL_Project::Size_Units"),
        ],
    )
    timed = ["thread", "thread group", "process", "system", "device", "virtual processor"]
    timing = new(
        "PropertySet",
        name="Timing_Properties",
        withs=["AADL_Project"],
        ownedProperties=[
            period_definition(timed),
            deadline_definition(timed),
            new(
                "Property",
                name="Compute_Execution_Time",
                type="AADL_Project::Time_Range",
                appliesTo=["thread", "device", "subprogram", "event port", "event data port"],
            ),
        ],
    )
    thread = new(
        "PropertySet",
        name="Thread_Properties",
        ownedProperties=[dispatch_protocol_definition(["thread", "device", "virtual processor"])],
    )
    memory = new(
        "PropertySet",
        name="Memory_Properties",
        withs=["AADL_Project"],
        ownedProperties=[
            new(
                "Property",
                name="Data_Size",
                type="AADL_Project::Size",
                appliesTo=["data", "data port", "event data port", "subprogram", "thread", "process"],
            )
        ],
    )
    bound = ["thread", "thread group", "process", "system", "virtual processor", "device"]
    deployment = new(
        "PropertySet",
        name="Deployment_Properties",
        ownedProperties=[processor_binding_definition(bound, ["processor"])],
    )
    return [project, timing, thread, memory, deployment]


def _pa(prop: str, value: EObject, applies_to: list[str] | None = None) -> EObject:
    return model.new(
        "PropertyAssociation",
        property=prop,
        appliesTo=applies_to or [],
        ownedValues=[model.new("ModalPropertyValue", value=value)],
    )


def _ports() -> list[EObject]:
    return [
        model.new("Feature", name="inp", category="event data port", direction="in", classifier="msg"),
        model.new("Feature", name="outp", category="event data port", direction="out", classifier="msg"),
    ]


def chained_system(processes: int = 100, threads: int = 100) -> EObject:
    """The declarative model of a system of ``processes`` processes of ``threads`` threads each
    (root ``bench::top.impl``).

    Every thread has an in and an out event data port typed by a data type with ``Data_Size``,
    ``Dispatch_Protocol``, ``Period`` and ``Compute_Execution_Time``; the threads of a process
    form a chain of port connections, the processes form a chain too (one semantic connection
    per process boundary), and every process is bound to the processor by a contained
    ``applies to`` association, which its threads inherit."""
    new = model.new
    ws = new("AadlModel", name="bench")
    ws.units.extend(chained_system_property_sets())
    pkg = new("AadlPackage", name="bench", sourceFile="bench.aadl")
    ws.units.append(pkg)
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="msg",
            category="data",
            ownedPropertyAssociations=[_pa("Data_Size", new("IntegerValue", value=8, unit="Bytes"))],
        )
    )
    pkg.classifiers.append(
        new(
            "ComponentType",
            name="worker",
            category="thread",
            features=_ports(),
            ownedPropertyAssociations=[
                _pa("Dispatch_Protocol", new("NamedValue", name="Periodic")),
                _pa("Period", new("IntegerValue", value=10, unit="ms")),
                _pa(
                    "Compute_Execution_Time",
                    new(
                        "RangeValue",
                        minimum=new("IntegerValue", value=1, unit="ms"),
                        maximum=new("IntegerValue", value=2, unit="ms"),
                    ),
                ),
            ],
        )
    )
    pkg.classifiers.append(new("ComponentType", name="node", category="process", features=_ports()))
    node = new("ComponentImplementation", name="node.impl", type="node", category="process")
    node.subcomponents.extend(
        new("Subcomponent", name=f"t{i}", category="thread", classifier="worker")
        for i in range(1, threads + 1)
    )
    node.connections.append(new("Connection", name="cin", kind="port", source="inp", destination="t1.inp"))
    node.connections.extend(
        new("Connection", name=f"c{i}", kind="port", source=f"t{i}.outp", destination=f"t{i + 1}.inp")
        for i in range(1, threads)
    )
    node.connections.append(
        new("Connection", name="cout", kind="port", source=f"t{threads}.outp", destination="outp")
    )
    pkg.classifiers.append(node)
    pkg.classifiers.append(new("ComponentType", name="cpu", category="processor"))
    pkg.classifiers.append(new("ComponentType", name="top", category="system"))
    top = new("ComponentImplementation", name="top.impl", type="top", category="system")
    top.subcomponents.extend(
        new("Subcomponent", name=f"p{i}", category="process", classifier="node.impl")
        for i in range(1, processes + 1)
    )
    top.subcomponents.append(new("Subcomponent", name="cpu", category="processor", classifier="cpu"))
    top.connections.extend(
        new("Connection", name=f"k{i}", kind="port", source=f"p{i}.outp", destination=f"p{i + 1}.inp")
        for i in range(1, processes)
    )
    top.ownedPropertyAssociations.append(
        _pa(
            "Actual_Processor_Binding",
            new("ListValue", ownedItems=[new("ReferenceValue", path="cpu")]),
            [f"p{i}" for i in range(1, processes + 1)],
        )
    )
    pkg.classifiers.append(top)
    return ws


# --------------------------------------------------------------------------- the writer's package


class _FastNew:
    """The metamodel classes called directly, with enumeration values looked up once: ``model.new``
    checks every keyword and would make building, not writing, the slow part of a run."""

    _ENUMERATED = ("category", "direction", "access", "kind")

    def __init__(self) -> None:
        self.classes: dict[str, type] = {}
        self.literals: dict[tuple[str, str, str], object] = {}

    def __call__(self, kind: str, /, **values: Any) -> EObject:
        cls = self.classes.get(kind)
        if cls is None:
            cls = self.classes[kind] = model.eclass_of(kind).python_class
        many = {k: values.pop(k) for k in list(values) if isinstance(values[k], list)}
        obj = cls(**{k: self._enum(kind, k, v) for k, v in values.items()})
        for key, items in many.items():
            getattr(obj, key).extend(items)
        return obj

    def _enum(self, cls: str, key: str, value: Any) -> Any:
        if key not in self._ENUMERATED or not isinstance(value, str):
            return value
        found = self.literals.get((cls, key, value))
        if found is None:
            etype = model.eclass_of(cls).findEStructuralFeature(key).eType
            found = self.literals[(cls, key, value)] = etype.from_string(value)
        return found


def thread_types_package(components: int) -> EObject:
    """An ``AadlModel`` with one package of ``components`` thread types and a system using them.

    Each thread type has three features (one with a property block) and three property
    associations (a number with unit, an enumeration literal, a range); the system
    implementation has a subcomponent per thread and a connection between each two."""
    new = _FastNew()

    def assoc(prop: str, value: EObject) -> EObject:
        return new("PropertyAssociation", property=prop, ownedValues=[new("ModalPropertyValue", value=value)])

    ws = new("AadlModel", name="bench")
    pkg = new("AadlPackage", name="bench::threads", withs=["Base_Types"])
    top_type = new("ComponentType", name="top", category="system")
    top = new("ComponentImplementation", name="top.impl", type="top", category="system")
    for n in range(components):
        thread = new("ComponentType", name=f"worker_{n}", category="thread")
        queue = assoc("Queue_Size", new("IntegerValue", value=4))
        thread.features.extend(
            [
                new(
                    "Feature",
                    name="input",
                    category="event data port",
                    direction="in",
                    classifier="Base_Types::Integer",
                    ownedPropertyAssociations=[queue],
                ),
                new("Feature", name="output", category="data port", direction="out", classifier="D::Float"),
                new("Feature", name="shared", category="data access", access="requires"),
            ]
        )
        execution = new(
            "RangeValue",
            minimum=new("RealValue", value=0.5, unit="ms"),
            maximum=new("RealValue", value=1.25 + n % 7, unit="ms"),
        )
        thread.ownedPropertyAssociations.extend(
            [
                assoc("Timing_Properties::Period", new("IntegerValue", value=10 + n % 90, unit="ms")),
                assoc("Thread_Properties::Dispatch_Protocol", new("NamedValue", name="Periodic")),
                assoc("Timing_Properties::Compute_Execution_Time", execution),
            ]
        )
        pkg.classifiers.append(thread)
        sub = new("Subcomponent", name=f"w{n}", category="thread", classifier=f"worker_{n}")
        top.subcomponents.append(sub)
        if n:
            source, destination = f"w{n - 1}.output", f"w{n}.input"
            conn = new("Connection", name=f"c{n}", kind="port", source=source, destination=destination)
            top.connections.append(conn)
    pkg.classifiers.extend([top_type, top])
    ws.units.append(pkg)
    return ws

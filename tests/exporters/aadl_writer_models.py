"""Model builders shared by the AADL text writer's tests: values, associations, packages, and a
model that uses every construct the writer knows (with the grammar nodes its text must contain).

The writer's test modules import it as ``aadl_writer_models`` (their folder is on pytest's path).
"""

from __future__ import annotations

from lark import Token, Tree

from rosaadl import model
from rosaadl.exporters import aadl_text
from rosaadl.importers.aadl_syntax import parse

__all__ = [
    "N",
    "write_unit",
    "write_units",
    "mv",
    "pa",
    "i",
    "r",
    "s",
    "named",
    "lst",
    "rec",
    "op",
    "package",
    "type_with_props",
    "props_text",
    "node_names",
    "tokens",
    "everything_model",
    "EXPECTED_NODES",
]

N = model.new


def write_unit(unit) -> str:
    """The writer's text, which must always parse with the AADL grammar."""
    text = aadl_text.write_unit(unit)
    parse(text, "written.aadl")
    return text


def write_units(units) -> dict[str, str]:
    texts = aadl_text.write_units(units)
    for name, text in texts.items():
        parse(text, name)
    return texts


# --------------------------------------------------------------------------- model building helpers


def mv(value, modes=None):
    # (an empty list is not passed: model.dumps_xmi writes a set-but-empty string list as "EOrderedSet()")
    return N("ModalPropertyValue", value=value, inModes=modes or None)


def pa(prop: str, *values, **kw):
    """A property association; a ``(value, [modes])`` tuple is a modal value."""
    assoc = N("PropertyAssociation", property=prop, **kw)
    for value in values:
        assoc.ownedValues.append(mv(*value) if isinstance(value, tuple) else mv(value))
    return assoc


def i(value: int, unit: str | None = None):
    return N("IntegerValue", value=value, unit=unit)


def r(value: float, unit: str | None = None):
    return N("RealValue", value=value, unit=unit)


def s(value: str):
    return N("StringValue", value=value)


def named(name: str):
    return N("NamedValue", name=name)


def lst(*items):
    return N("ListValue", ownedItems=list(items))


def rec(**fields):
    return N("RecordValue", ownedFields=[N("FieldValue", name=k, value=v) for k, v in fields.items()])


def op(operator: str, *operands):
    return N("OperationValue", operator=operator, ownedOperands=list(operands))


def package(name: str = "P", *classifiers, **kw):
    pkg = N("AadlPackage", name=name, **kw)
    pkg.classifiers.extend(classifiers)
    return pkg


def type_with_props(*assocs, category: str = "system", name: str = "T"):
    return N("ComponentType", name=name, category=category, ownedPropertyAssociations=list(assocs))


def props_text(*assocs) -> str:
    """The property lines written for a type holding ``assocs``."""
    lines = write_unit(package("P", type_with_props(*assocs))).splitlines()
    start, end = lines.index("    properties"), lines.index("  end T;")
    return "\n".join(line.strip() for line in lines[start + 1 : end])


def node_names(tree: Tree) -> set[str]:
    return {t.data for t in tree.iter_subtrees()}


def tokens(tree: Tree, kind: str) -> list[str]:
    return [str(t) for t in tree.scan_values(lambda v: isinstance(v, Token) and v.type == kind)]


# ------------------------------------------------------------------- a model that uses every construct


def everything_model():
    """An AadlModel using every construct the writer knows (one package, one property set)."""
    ws = N("AadlModel", name="ws")
    pkg = N("AadlPackage", name="robot::nav", withs=["Base_Types", "Nav_Props"], privateWiths=["Data_Model"])
    pkg.renamings.extend(
        [
            N("Renaming", name="BT", kind="package", target="Base_Types"),
            N("Renaming", kind="all", target="Nav_Props"),
            N("Renaming", name="Int", kind="classifier", category="data", target="Base_Types::Integer"),
            N("Renaming", name="Grp", kind="feature group", target="robot::nav::sensors"),
        ]
    )
    pkg.annexLibraries.append(
        N("AnnexLibrary", name="EMV2", text="{** error types Fail: type; end types; **}")
    )

    sensors = N("FeatureGroupType", name="sensors")
    sensors.features.extend(
        [
            N(
                "Feature",
                name="scan",
                category="event data port",
                direction="out",
                classifier="Base_Types::Float",
            ),
            N("Feature", name="odom", category="data port", direction="in", arrayDimensions=["4"]),
        ]
    )
    sensors_inv = N("FeatureGroupType", name="sensors_in", inverseOf="sensors")
    sensors_inv.ownedPropertyAssociations.append(pa("Nav_Props::Kind", named("Input")))

    planner = N("ComponentType", name="planner", category="thread", extended="robot::nav::base_thread")
    planner.prototypes.append(N("Prototype", name="msg", text="data Base_Types::Float"))
    planner.prototypeBindings = "msg => data Base_Types::Integer"  # (the reader keeps the parentheses)
    planner.features.extend(
        [
            N(
                "Feature",
                name="goal",
                category="event data port",
                direction="in",
                classifier="Base_Types::Integer",
                ownedPropertyAssociations=[
                    pa("Queue_Size", i(5)),
                    pa("Overflow_Handling_Protocol", named("DropOldest")),
                ],
            ),
            N("Feature", name="cmd", category="data port", direction="out", classifier="prototype msg"),
            N("Feature", name="tick", category="event port", direction="in"),
            N(
                "Feature",
                name="map",
                category="data access",
                access="requires",
                classifier="robot::nav::map_t",
            ),
            N("Feature", name="svc", category="subprogram access", access="provides"),
            N("Feature", name="grp", category="subprogram group access", access="requires"),
            N(
                "Feature",
                name="fg",
                category="feature group",
                direction="in out",
                classifier="robot::nav::sensors",
                inverse=True,
            ),
            N("Feature", name="fg2", category="feature group", direction="out", classifier="sensors"),
            N("Feature", name="af", category="feature", direction="in"),
            N("Feature", name="tick2", category="event port", direction="in", refined=True),
        ]
    )
    planner.flowSpecifications.extend(
        [
            N("FlowSpecification", name="f_src", kind="source", outEnd="cmd"),
            N("FlowSpecification", name="f_snk", kind="sink", inEnd="goal", inModes=["nominal"]),
            N(
                "FlowSpecification",
                name="f_path",
                kind="path",
                inEnd="goal",
                outEnd="cmd",
                ownedPropertyAssociations=[
                    pa("Latency", N("RangeValue", minimum=i(1, "ms"), maximum=i(5, "ms")))
                ],
            ),
            N("FlowSpecification", name="f_ref", kind="source", refined=True, inModes=["nominal"]),
        ]
    )
    planner.modes.extend(
        [
            N("Mode", name="nominal", initial=True),
            N("Mode", name="degraded", ownedPropertyAssociations=[pa("Nav_Props::Speed", r(0.5, "mps"))]),
        ]
    )
    planner.modeTransitions.extend(
        [
            N(
                "ModeTransition",
                name="fail",
                source="nominal",
                destination="degraded",
                triggers=["tick", "self.ev"],
            ),
            N("ModeTransition", source="degraded", destination="nominal", triggers=["processor.reset"]),
        ]
    )
    planner.ownedPropertyAssociations.extend(
        [
            pa("Period", (i(100, "ms"), ["nominal"]), (i(200, "ms"), ["degraded"])),
            pa("Dispatch_Protocol", named("Periodic")),
        ]
    )
    planner.annexSubclauses.append(
        N("AnnexSubclause", name="EMV2", text=" use types ErrorLibrary; ", inModes=["nominal"])
    )
    planner.annexSubclauses.append(N("AnnexSubclause", name="BA", text=None))

    base = N("ComponentType", name="base_thread", category="thread", requiresModes=True)
    base.modes.append(N("Mode", name="nominal", initial=True))
    base.modes.append(N("Mode", name="degraded"))

    map_t = N("ComponentType", name="map_t", category="data")
    proc_t = N("ComponentType", name="nav_proc", category="process")
    proc_t.features.append(N("Feature", name="goal", category="event data port", direction="in"))

    impl = N("ComponentImplementation", name="nav_proc.impl", type="nav_proc", category="process")
    impl.prototypes.append(N("Prototype", name="worker", text="thread planner", refined=False))
    impl.subcomponents.extend(
        [
            N(
                "Subcomponent",
                name="plan",
                category="thread",
                classifier="planner",
                prototypeBindings="(msg => data Base_Types::Integer)",
                arrayDimensions=["2"],
                arrayElementBindings=["planner", "robot::nav::planner (msg => data Base_Types::Float)"],
                ownedPropertyAssociations=[pa("Priority", i(3))],
                inModes=["nominal"],
            ),
            N("Subcomponent", name="grid", category="data", classifier="map_t", inModes=["a => b"]),
            N("Subcomponent", name="grid2", category="data", refined=True),
            N(
                "Subcomponent",
                name="matrix",
                category="abstract",
                arrayDimensions=["2", "Nav_Props::Size", ""],
            ),
            N("Subcomponent", name="helper", category="subprogram group"),
        ]
    )
    impl.connections.extend(
        [
            N("Connection", name="c_goal", kind="port", source="goal", destination="plan.goal"),
            N("Connection", name="c_map", kind="access", source="grid", destination="plan.map"),
            N("Connection", name="c_fg", kind="feature group", source="plan.fg", destination="plan.fg2"),
            N(
                "Connection",
                name="c_f",
                kind="feature",
                source="plan.af",
                destination="self.x",
                inModes=["nominal"],
                ownedPropertyAssociations=[pa("Timing", named("Immediate"))],
            ),
            N("Connection", name="c_old", kind="port", refined=True, source="goal", destination="plan.tick"),
            N("Connection", kind="port", source="processor.clk", destination="plan.tick"),
        ]
    )
    impl.flowImplementations.append(
        N("FlowImplementation", name="f_path", kind="path", elements=["goal", "c_goal", "plan.f_path", "cmd"])
    )
    impl.endToEndFlows.extend(
        [
            N(
                "EndToEndFlow",
                name="e2e",
                elements=["plan.f_src", "c_goal", "plan.f_snk"],
                ownedPropertyAssociations=[
                    pa("Latency", N("RangeValue", minimum=i(0, "ms"), maximum=i(20, "ms")))
                ],
            ),
            N("EndToEndFlow", name="e2e_old", refined=True, inModes=["nominal"]),
        ]
    )
    impl.modes.append(N("Mode", name="nominal", initial=True))
    impl.ownedPropertyAssociations.extend(
        [
            pa(
                "Actual_Processor_Binding",
                lst(N("ReferenceValue", path="cpu.core[1]")),
                appliesTo=["plan[1]", "a.b[1].c"],
                inBinding=["robot::nav::cpu_t.impl"],
            ),
            pa("Nav_Props::Weights", lst(lst(i(1), i(2)), lst(), lst(r(2.5e-3), r(1e-5))), append=True),
            pa("Nav_Props::Limit", i(-4, "m"), constant=True),
            pa(
                "Nav_Props::Config",
                rec(name=s('the "best" map'), size=i(3), inner=rec(flag=N("BooleanValue", value=True))),
            ),
            pa("Nav_Props::Impl", N("ClassifierValue", classifier="robot::nav::nav_proc.impl")),
            pa("Nav_Props::Dyn", N("ComputedValue", function="speed_fn")),
            pa(
                "Nav_Props::Flag",
                op("or", op("and", named("A"), op("not", named("B"))), N("BooleanValue", value=False)),
            ),
            pa(
                "Nav_Props::Neg",
                N(
                    "RangeValue",
                    minimum=op("-", named("Nav_Props::Max")),
                    maximum=named("Nav_Props::Max"),
                    delta=r(0.5),
                ),
            ),
            pa("Nav_Props::Annexed", i(1), appliesTo=["plan.annex {** EMV2 **}"]),
        ]
    )
    # a subprogram with parameters, called by a thread implementation
    compute = N("ComponentType", name="solve", category="subprogram")
    compute.features.append(N("Feature", name="arg", category="parameter", direction="in out"))
    compute_impl = N("ComponentImplementation", name="solve.impl", type="solve", category="subprogram")
    planner_impl = N("ComponentImplementation", name="planner.impl", type="planner", category="thread")
    seq = N("CallSequence", name="cs", inModes=["nominal"], ownedPropertyAssociations=[pa("Priority", i(1))])
    seq.calls.extend(
        [
            N("SubprogramCall", name="c1", called="robot::nav::solve.impl"),
            N("SubprogramCall", name="c2", called="processor.rt"),
        ]
    )
    planner_impl.callSequences.append(seq)
    planner_impl.connections.append(
        N("Connection", name="c_p", kind="parameter", source="c1.arg", destination="c2.x")
    )
    # hardware: bus and virtual bus access
    radio = N("ComponentType", name="radio", category="device")
    radio.features.append(N("Feature", name="lan", category="bus access", access="requires"))
    radio.features.append(N("Feature", name="vb", category="virtual bus access", access="requires"))
    rig = N("ComponentImplementation", name="rig.impl", category="system", type="rig")
    rig.subcomponents.extend(
        [
            N("Subcomponent", name="net", category="bus"),
            N("Subcomponent", name="vbus", category="virtual bus"),
            N("Subcomponent", name="r", category="device", classifier="radio"),
        ]
    )
    rig.connections.extend(
        [
            N(
                "Connection",
                name="c_lan",
                kind="access",
                source="net",
                destination="r.lan",
                bidirectional=True,
            ),
            N(
                "Connection",
                name="c_vb",
                kind="access",
                accessCategory="virtual bus",
                source="vbus",
                destination="r.vb",
            ),
        ]
    )
    rig_t = N("ComponentType", name="rig", category="system")
    pkg.classifiers.extend([sensors, sensors_inv, planner, base, map_t, proc_t, impl])
    pkg.classifiers.extend([compute, compute_impl, planner_impl, radio, rig_t, rig])
    private_t = N("ComponentType", name="hidden", category="device", visibility="private")
    pkg.classifiers.append(private_t)
    pkg.ownedPropertyAssociations.append(pa("Nav_Props::Version", s("1.0")))

    ps = N("PropertySet", name="Nav_Props", withs=["AADL_Project", "Timing_Properties"])
    length = N("UnitsType", name="Length_Units")
    length.ownedLiterals.extend(
        [
            N("UnitLiteral", name="mm"),
            N("UnitLiteral", name="cm", baseUnit="mm", factor=i(10)),
            N("UnitLiteral", name="m", baseUnit="cm", factor=i(100)),
            N("UnitLiteral", name="inch", baseUnit="mm", factor=r(25.4)),
        ]
    )
    speed_units = N("UnitsType")
    speed_units.ownedLiterals.extend(
        [N("UnitLiteral", name="mps"), N("UnitLiteral", name="kph", baseUnit="mps", factor=r(0.27))]
    )
    ps.ownedPropertyTypes.extend(
        [
            N("AadlBoolean", name="Switch"),
            N("AadlString", name="Label"),
            N(
                "EnumerationType",
                name="Kind",
                ownedLiterals=[N("EnumerationLiteral", name=n) for n in ("Input", "Output")],
            ),
            length,
            N(
                "AadlInteger",
                name="Distance",
                range=N("RangeValue", minimum=i(0), maximum=i(100)),
                unitsType="Length_Units",
            ),
            N("AadlReal", name="Speed", ownedUnitsType=speed_units),
            N("RangeType", name="Span", numberType="Nav_Props::Distance"),
            N("RangeType", name="Span2", ownedNumberType=N("AadlReal")),
            N("ClassifierType", name="Cl", categories=["thread", "thread group", "{emv2}** error type"]),
            N("ReferenceType", name="Ref"),
            N(
                "RecordType",
                name="Pair",
                ownedFields=[
                    N("RecordField", name="first", type="aadlinteger_alias"),
                    N(
                        "RecordField",
                        name="second",
                        ownedType=N("ListType", ownedElementType=N("AadlString")),
                    ),
                ],
            ),
            N("ListType", name="Names", elementType="Nav_Props::Label"),
        ]
    )
    ps.ownedProperties.extend(
        [
            N(
                "Property",
                name="Max_Speed",
                ownedType=N("AadlReal", unitsType="Nav_Props::Length_Units"),
                appliesTo=["thread", "device", "robot::nav::planner"],
            ),
            N(
                "Property",
                name="Weights",
                inherit=True,
                ownedType=N("ListType", ownedElementType=N("ListType", ownedElementType=N("AadlInteger"))),
                defaultValue=lst(),
                appliesTo=["all"],
            ),
            N(
                "Property",
                name="Kind_Of",
                type="Nav_Props::Kind",
                defaultValue=named("Input"),
                appliesTo=["feature group type"],
            ),
        ]
    )
    ps.ownedPropertyConstants.extend(
        [
            N("PropertyConstant", name="Max", type="aadlinteger_alias", value=i(10)),
            N("PropertyConstant", name="Size", ownedType=N("AadlInteger"), value=i(3)),
        ]
    )
    ws.units.extend([pkg, ps])
    return ws


EXPECTED_NODES = {
    "package", "public_section", "private_section", "properties", "with_clause", "package_rename",
    "package_rename_all", "feature_group_type_rename", "component_type_rename", "annex_library",
    "component_type", "component_implementation", "feature_group_type", "extends", "inverse_of",
    "prototype_bindings", "prototypes", "component_prototype", "features", "data_port", "event_port",
    "event_data_port", "parameter", "feature_group", "abstract_feature", "data_access", "bus_access",
    "virtual_bus_access", "subprogram_access", "subprogram_group_access", "prototype_ref", "refined",
    "inverse", "array_dimension", "property_block", "subcomponents", "subcomponent", "array_dimensions",
    "array_element_implementations", "in_modes", "mode_ref", "calls", "call_sequence", "subprogram_call",
    "processor_subprogram", "connections", "port_connection", "access_connection", "feature_group_connection",
    "feature_connection", "parameter_connection", "processor_port", "internal_event", "flow_specs",
    "flow_source_spec", "flow_sink_spec", "flow_path_spec", "flow_impls", "flow_path_impl", "end_to_end_flow",
    "flow_segments", "requires_modes", "modes", "mode", "initial", "mode_transition", "triggers",
    "annex_subclause", "annex_none", "property_association", "append", "constant", "modal_property_value",
    "modal_value", "applies_to", "in_binding", "indexed_element", "annex_element", "array_range",
    "integer_value", "real_value", "named_value", "signed_constant", "boolean_value", "string_value",
    "list_value", "record_value", "field_value", "reference_value", "classifier_value", "computed_value",
    "or_value", "and_value", "not_value", "range_value", "property_set", "property_type_declaration",
    "property_definition", "property_constant", "inherit", "boolean_type", "string_type", "integer_type",
    "real_type", "enumeration_type", "units_type", "unit_conversion", "units_ref", "range_type",
    "classifier_type", "reference_type", "record_type", "record_field", "list_type", "all_owners",
    "metaclass_ref", "classifier_ref", "qname",
}  # fmt: skip

"""Name resolution over the declarative AADL model (rosaadl.resolution)."""

from __future__ import annotations

import pytest

from benchmarks.generators.declarative import dispatch_protocol_definition, period_definition, time_units
from rosaadl import model
from rosaadl.errors import ModelError, NameResolutionError
from rosaadl.resolution import (
    FEATURE_WORDS,
    PREDECLARED_PROPERTY_SETS,
    Resolver,
    feature_category_word,
    split_name,
    split_path,
)

new = model.new


def _time_set() -> list:
    project = new(
        "PropertySet",
        name="AADL_Project",
        sourceFile="AADL_Project.aadl",
        ownedPropertyTypes=[
            time_units("us", "ms"),
            new("AadlInteger", name="Time", unitsType="AADL_Project::Time_Units"),
        ],
        ownedPropertyConstants=[
            new(
                "PropertyConstant",
                name="Max_Time",
                type="AADL_Project::Time",
                value=new("IntegerValue", value=9),
            )
        ],
    )
    timing = new(
        "PropertySet",
        name="Timing_Properties",
        withs=["AADL_Project"],
        ownedProperties=[
            period_definition(["thread"]),
        ],
    )
    thread = new(
        "PropertySet",
        name="Thread_Properties",
        ownedProperties=[dispatch_protocol_definition(["thread"])],
    )
    return [project, timing, thread]


def _pa(prop: str, value, line: int | None = None):
    return new(
        "PropertyAssociation",
        property=prop,
        line=line,
        ownedValues=[new("ModalPropertyValue", value=value)],
    )


@pytest.fixture
def ws():
    ws = new("AadlModel", name="ws")
    ws.units.extend(_time_set())
    lib = new("AadlPackage", name="Lib::Parts", sourceFile="lib.aadl")
    lib.classifiers.append(new("ComponentType", name="Sensor", category="device", line=3))
    lib.classifiers.append(new("ComponentType", name="Hidden", category="device", visibility="private"))
    lib.classifiers.append(
        new("FeatureGroupType", name="Bundle", features=[new("Feature", name="a", category="data port")])
    )
    app = new("AadlPackage", name="App", sourceFile="app.aadl", withs=["Lib::Parts"])
    app.renamings.append(
        new("Renaming", name="Cam", kind="classifier", target="Lib::Parts::Sensor", category="device")
    )
    app.renamings.append(new("Renaming", name="L", kind="package", target="Lib::Parts"))
    base = new(
        "ComponentType",
        name="Base",
        category="thread",
        line=10,
        features=[
            new("Feature", name="p1", category="data port", direction="in"),
            new("Feature", name="p2", category="data port", direction="out"),
            new("Feature", name="p3", category="event port", direction="out"),
        ],
        modes=[new("Mode", name="Init", initial=True)],
    )
    derived = new(
        "ComponentType",
        name="Derived",
        category="thread",
        extended="base",
        line=20,
        features=[
            new("Feature", name="P2", category="data port", direction="out", refined=True, classifier="Cam"),
            new("Feature", name="p4", category="data port", direction="in"),
        ],
        ownedPropertyAssociations=[_pa("Period", new("IntegerValue", value=5, unit="ms"), line=25)],
    )
    impl = new(
        "ComponentImplementation",
        name="Derived.i",
        type="Derived",
        category="thread",
        subcomponents=[new("Subcomponent", name="s", category="data")],
        modes=[new("Mode", name="Run")],
    )
    impl2 = new(
        "ComponentImplementation",
        name="Derived.j",
        type="derived",
        category="thread",
        extended="Derived.i",
        subcomponents=[
            new("Subcomponent", name="s", category="data", refined=True, classifier="Lib::Parts::Sensor"),
            new("Subcomponent", name="t", category="data"),
        ],
    )
    app.classifiers.extend([base, derived, impl, impl2])
    ws.units.extend([lib, app])
    return ws


def test_split_helpers():
    assert split_name("a::b::T.impl") == ("a::b", "T.impl")
    assert split_name("T") == (None, "T")
    segments = split_path("a.b[2].c[1 .. 3]")
    assert [s.name for s in segments] == ["a", "b", "c"]
    assert segments[1].ranges == ((2, 2),) and segments[2].ranges == ((1, 3),)
    assert segments[1].matches([2]) and not segments[1].matches([1])
    assert segments[2].matches(2) and not segments[2].matches(4)
    assert segments[0].matches([7]) and segments[0].matches(None)
    assert str(segments[2]) == "c[1 .. 3]"
    assert split_path(None) == [] and split_path("") == []
    with pytest.raises(ModelError):
        split_path(5)
    with pytest.raises(ModelError):
        segments[1].matches(["2"])


def test_feature_words_cover_every_feature_category():
    enum = model.eclass_of("Feature").findEStructuralFeature("category").eType
    # the words of "applies to" lists: the text syntax's, except "abstract feature" (text: "feature")
    assert {lit.name: lit.literal or lit.name for lit in enum.eLiterals} == {
        **FEATURE_WORDS,
        "abstractFeature": "feature",
    }
    assert feature_category_word(enum.getEEnumLiteral("eventDataPort")) == "event data port"
    assert feature_category_word("abstractFeature") == "abstract feature"


def test_classifier_visibility(ws):
    r = Resolver(ws)
    app = r.unit("app")
    derived = r.classifier("Derived", app)
    assert r.qualified_name(derived) == "App::Derived"
    # case-insensitive, own package, qualified, package alias, classifier alias
    assert r.classifier("derived", derived) is derived
    sensor = r.classifier("lib::parts::SENSOR", derived)
    assert sensor is not None and sensor.name == "Sensor"
    assert r.classifier("L::Sensor", derived) is sensor
    assert r.classifier("Cam", derived) is sensor
    assert r.classifier("Derived.j", derived).name == "Derived.j"
    # private classifiers are visible only in their own package
    assert r.classifier("Lib::Parts::Hidden", derived) is None
    assert r.classifier("Hidden", r.unit("Lib::Parts")) is not None
    # unqualified names never leak out of other packages
    assert r.classifier("Sensor", derived) is None
    assert r.classifier("Nope::T", derived) is None
    with pytest.raises(NameResolutionError) as info:
        r.require_classifier("Missing", derived)
    assert "Missing" in info.value.message and info.value.location.file == "app.aadl"


def test_renames_all():
    ws = new("AadlModel", name="ws")
    lib = new("AadlPackage", name="Lib", classifiers=[new("ComponentType", name="T", category="system")])
    app = new(
        "AadlPackage", name="App", withs=["Lib"], renamings=[new("Renaming", kind="all", target="Lib::all")]
    )
    app.classifiers.append(new("ComponentType", name="U", category="system"))
    ws.units.extend([lib, app])
    r = Resolver(ws)
    assert r.classifier("T", app) is lib.classifiers[0]
    assert r.check() == []


def test_properties_types_constants_literals(ws):
    r = Resolver(ws)
    app = r.unit("App")
    period = r.property("Period", app)
    assert period is not None and r.qualified_name(period) == "Timing_Properties::Period"
    assert r.property("timing_properties::period") is period
    assert r.property("Nowhere::Period") is None
    assert r.missing_property_set("Nowhere::Period") == "Nowhere"
    assert r.missing_property_set("Timing_Properties::Nope") is None
    time = r.property_type("AADL_Project::Time")
    assert r.resolved_type(period) is time
    assert r.unit_literal(time, "MS") == "ms"
    assert r.unit_literal(time, "furlong") is None
    assert r.constant("AADL_Project::Max_Time").value.value == 9
    dispatch = r.property("Dispatch_Protocol")
    assert r.enumeration_literal(r.resolved_type(dispatch), "periodic") == "Periodic"
    assert r.enumeration_literal(r.resolved_type(dispatch), "Hybrid") is None
    key, display = r.property_key("period", app)
    assert (key, display) == ("timing_properties::period", "Timing_Properties::Period")
    assert r.property_key("Sec::Level")[1] == "Sec::Level"
    assert set(PREDECLARED_PROPERTY_SETS) >= {"Timing_Properties", "Thread_Properties"}


def test_effective_members(ws):
    r = Resolver(ws)
    app = r.unit("App")
    derived = r.classifier("Derived", app)
    names = [f.name for f in r.features(derived)]
    assert names == ["p1", "P2", "p3", "p4"]  # the refinement replaces p2 where it was
    refined = r.features(derived)[1]
    assert [f.name for f in r.refinement_chain(refined)] == ["P2", "p2"]
    assert r.feature_classifier(refined).name == "Sensor"
    impl2 = r.classifier("Derived.j", app)
    assert r.implementation_type(impl2) is derived
    assert [f.name for f in r.features(impl2)] == names
    subs = r.subcomponents(impl2)
    assert [s.name for s in subs] == ["s", "t"]
    assert r.subcomponent_classifier(subs[0]).name == "Sensor"
    assert [m.name for m in r.modes(impl2)] == ["Init", "Run"]
    assert [c.name for c in r.extends_chain(impl2)] == ["Derived.j", "Derived.i"]
    bundle = r.classifier("Lib::Parts::Bundle", app)
    assert [f.name for f in r.features(bundle)] == ["a"]


def test_feature_group_inverse_members():
    ws = new("AadlModel", name="ws")
    pkg = new("AadlPackage", name="P")
    a = new(
        "FeatureGroupType",
        name="A",
        features=[new("Feature", name="x", category="data port", direction="out")],
    )
    b = new("FeatureGroupType", name="B", inverseOf="A")
    pkg.classifiers.extend([a, b])
    ws.units.append(pkg)
    r = Resolver(ws)
    assert r.feature_group_features(a) == ([a.features[0]], False)
    members, inverted = r.feature_group_features(b)
    assert [m.name for m in members] == ["x"] and inverted


def test_extends_cycle_is_located_error():
    ws = new("AadlModel", name="ws")
    pkg = new("AadlPackage", name="P", sourceFile="p.aadl")
    pkg.classifiers.append(new("ComponentType", name="A", category="system", extended="B", line=4, column=3))
    pkg.classifiers.append(new("ComponentType", name="B", category="system", extended="A", line=8))
    ws.units.append(pkg)
    r = Resolver(ws)
    with pytest.raises(NameResolutionError) as info:
        r.extends_chain(pkg.classifiers[0])
    assert "extends cycle" in info.value.message
    assert (info.value.location.file, info.value.location.line, info.value.location.column) == (
        "p.aadl",
        4,
        3,
    )
    # check() reports it instead of raising, and never recurses forever
    errors = [d for d in r.check() if "cycle" in d.message]
    assert len(errors) == 2 and all(d.severity == "error" for d in errors)


def test_check_reports_unresolved_names(ws):
    app = ws.units[-1]
    app.withs.append("Unknown_Set")
    bad = new(
        "ComponentImplementation",
        name="Bad.i",
        type="Bad",
        category="system",
        line=40,
        extended="Nope.i",
        subcomponents=[
            new("Subcomponent", name="x", category="system", classifier="Lib::Parts::Nope", line=42)
        ],
        ownedPropertyAssociations=[
            _pa("Timing_Properties::Nope", new("IntegerValue", value=1), line=44),
            _pa("Security::Level", new("IntegerValue", value=1), line=45),
            _pa("Security::Other", new("IntegerValue", value=2), line=46),
            _pa("Dispatch_Protocol", new("ClassifierValue", classifier="Nope::T"), line=47),
        ],
    )
    app.classifiers.append(bad)
    diagnostics = Resolver(ws).check()
    errors = {(d.location.line, d.message) for d in diagnostics if d.severity == "error"}
    warnings = [d for d in diagnostics if d.severity == "warning"]
    assert (40, "extended classifier Nope.i not found") in errors
    assert (40, "component type Bad not found") in errors
    assert (42, "subcomponent classifier Lib::Parts::Nope not found") in errors
    assert (44, "property Timing_Properties::Nope not found") in errors
    assert (47, "classifier Nope::T not found") in errors
    # a missing property set is a warning, once per package, and values stay untyped
    security = [w for w in warnings if "Security" in w.message]
    assert (
        len(security) == 1 and security[0].message == "property set Security not found; values stay untyped"
    )
    assert security[0].location.file == "app.aadl" and security[0].location.line == 45
    assert any("Unknown_Set" in w.message for w in warnings)
    assert all(d.location.file for d in diagnostics)


def test_check_clean_model_has_no_diagnostics(ws):
    assert Resolver(ws).check() == []


def test_check_reports_missing_with_clause(ws):
    app = ws.units[-1]
    app.withs.clear()
    diagnostics = Resolver(ws).check()
    assert [d.message for d in diagnostics] == [
        "package Lib::Parts is used but not named in a with clause of App"
    ]
    assert diagnostics[0].severity == "warning"


def test_check_property_set_types():
    ws = new("AadlModel", name="ws")
    ws.units.append(
        new(
            "PropertySet",
            name="S",
            sourceFile="s.aadl",
            ownedProperties=[
                new("Property", name="A", type="S::Missing", appliesTo=["all"], line=3),
                new("Property", name="B", type="Gone::T", appliesTo=["all"], line=4),
            ],
        )
    )
    diagnostics = Resolver(ws).check()
    assert [(d.severity, d.location.line) for d in diagnostics] == [("error", 3), ("warning", 4)]
    assert diagnostics[0].message == "property type S::Missing not found"


def test_duplicate_units_and_answers_are_cached(ws):
    ws.units.append(new("AadlPackage", name="app", sourceFile="again.aadl"))
    r = Resolver(ws)
    assert r.unit("APP").sourceFile == "app.aadl"
    assert any("declared more than once" in d.message for d in r.check())
    derived = r.classifier("App::Derived")
    assert r.features(derived) is r.features(derived)


def test_prototype_names_are_not_unresolved_classifiers():
    ws = new("AadlModel", name="ws")
    pkg = new("AadlPackage", name="P", sourceFile="p.aadl")
    base = new(
        "ComponentType",
        name="Base",
        category="system",
        prototypes=[new("Prototype", name="Payload", text="data")],
        features=[new("Feature", name="f", category="data port", direction="in", classifier="payload")],
    )
    impl = new(
        "ComponentImplementation",
        name="Base.i",
        type="Base",
        category="system",
        subcomponents=[new("Subcomponent", name="s", category="data", classifier="Payload")],
    )
    derived = new("ComponentType", name="Derived", category="system", extended="Base")
    pkg.classifiers.extend([base, impl, derived])
    ws.units.append(pkg)
    r = Resolver(ws)
    # a prototype of the holding classifier, of an implementation's type, of an extended type
    assert r.is_prototype(base.features[0], "PAYLOAD")
    assert r.is_prototype(impl.subcomponents[0], "Payload")
    assert r.is_prototype(new("Feature", name="g"), "Payload") is False  # held by no classifier
    derived.features.append(new("Feature", name="g", category="data port", classifier="Payload"))
    assert r.is_prototype(derived.features[0], "Payload")
    # qualified names and implementation names are never prototypes
    assert not r.is_prototype(base.features[0], "P::Payload")
    assert not r.is_prototype(base.features[0], "Payload.i")
    assert not r.is_prototype(base.features[0], "Other")
    assert r.check() == []

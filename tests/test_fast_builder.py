"""FastBuilder makes the same objects as model.new: equal models, same bytes, same navigation."""

from __future__ import annotations

import pytest

from rosaadl import model
from rosaadl.errors import ModelError


def _slow():
    ct = model.new("ComponentType", name="T", category="thread group", line=3)
    ct.features.extend(
        [
            model.new("Feature", name="a", category="event data port", direction="out", classifier="P::D"),
            model.new(
                "Feature", name="b", category="data access", access="requires", arrayDimensions=["2", "3"]
            ),
        ]
    )
    pkg = model.new("AadlPackage", name="P", withs=["ros", "ros_data"])
    pkg.classifiers.append(ct)
    si = model.new("SystemInstance", name="top", category="system")
    fi = model.new("FeatureInstance", name="a", category="event data port")
    si.featureInstances.append(fi)
    ci = model.new("ConnectionInstance", name="a -> a", source=fi, destination=fi)
    si.connectionInstances.append(ci)
    return model.new("AadlModel", name="ws", units=[pkg], instances=[si])


def _fast():
    b = model.FastBuilder()
    ct = b.make("ComponentType", name="T", category=b.literal("ComponentCategory", "thread group"), line=3)
    b.add(
        ct,
        "features",
        b.make(
            "Feature",
            name="a",
            category=b.literal("FeatureCategory", "event data port"),
            direction=b.literal("DirectionType", "out"),
            classifier="P::D",
        ),
    )
    second = b.make(
        "Feature",
        name="b",
        category=b.literal("FeatureCategory", "data access"),
        access=b.literal("AccessType", "requires"),
    )
    b.add(second, "arrayDimensions", "2", "3")
    b.add(ct, "features", second)
    pkg = b.make("AadlPackage", name="P")
    b.add(pkg, "withs", "ros", "ros_data")
    b.add(pkg, "classifiers", ct)
    si = b.make("SystemInstance", name="top", category=b.literal("ComponentCategory", "system"))
    fi = b.make("FeatureInstance", name="a", category=b.literal("FeatureCategory", "event data port"))
    b.add(si, "featureInstances", fi)
    b.add(si, "connectionInstances", b.make("ConnectionInstance", name="a -> a", source=fi, destination=fi))
    ws = b.make("AadlModel", name="ws")
    b.add(ws, "units", pkg)
    b.add(ws, "instances", si)
    return ws


def test_fast_and_normal_construction_give_the_same_model_and_bytes() -> None:
    slow, fast = _slow(), _fast()
    assert model.model_differences(slow, fast) == []
    assert model.dumps_xmi(slow) == model.dumps_xmi(fast)
    assert model.dumps_json(slow) == model.dumps_json(fast)
    back = model.loads_xmi(model.dumps_xmi(fast))
    assert model.model_differences(back, slow) == []


def test_fast_objects_navigate_like_normal_ones() -> None:
    ws = _fast()
    feature = ws.units[0].classifiers[0].features[1]
    assert feature.eContainer() is ws.units[0].classifiers[0]
    assert model.root_of(feature) is ws
    assert feature.eIsSet("access") and not feature.eIsSet("direction")
    conn = ws.instances[0].connectionInstances[0]
    assert conn.source is ws.instances[0].featureInstances[0]
    # normal mutation still works afterwards
    feature.name = "renamed"
    ws.units[0].classifiers[0].features.append(model.new("Feature", name="c"))
    assert [f.name for f in ws.units[0].classifiers[0].features] == ["a", "renamed", "c"]


def test_fast_builder_rejects_unknown_features_and_misuse() -> None:
    b = model.FastBuilder()
    with pytest.raises(ModelError, match="nmae"):
        b.make("Feature", nmae="x")
    with pytest.raises(ModelError, match="abstract"):
        b.make("Classifier")
    with pytest.raises(ModelError, match="many-valued"):
        b.make("AadlPackage", withs="x")
    with pytest.raises(ModelError, match="single-valued"):
        b.add(b.make("Feature"), "name", "x")
    with pytest.raises(ModelError, match="not a literal"):
        b.literal("ComponentCategory", "thred")


def test_fast_objects_read_pyecore_s_own_state_and_keep_it_per_object() -> None:
    from pyecore.ecore import EPackage
    from pyecore.resources import URI, ResourceSet

    from rosaadl.bulk import FastFactory

    slow, fast = _slow(), _fast()
    for name in ("_internal_id", "_container", "_containment_feature", "_eresource", "_staticEClass"):
        assert getattr(fast, name) == getattr(slow, name), name
    assert fast.instances[0]._container is fast
    assert fast.instances[0]._containment_feature is slow.instances[0]._containment_feature
    assert fast.eResource is None and fast.instances[0].eContainer() is fast
    # what pyecore writes lands on the object, never on the class defaults
    resource = ResourceSet().create_resource(URI("ws.xmi"))
    resource.append(fast)
    assert fast.eResource is resource and "_eresource" in vars(fast)
    other = _fast()
    assert other.eResource is None and type(other)._eresource is None
    si = fast.instances[0]
    other.instances.append(si)
    assert si.eContainer() is other and si.eResource is None and not fast.instances
    fi = si.featureInstances[0]
    fi.delete()
    assert fi.eContainer() is None and not si.featureInstances
    assert si.connectionInstances[0].source is None
    with pytest.raises(TypeError, match="not a class made from an EClass"):
        FastFactory.new(EPackage)

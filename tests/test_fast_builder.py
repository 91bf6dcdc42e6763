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
    with pytest.raises(ModelError, match="not a class made from an EClass"):
        FastFactory.new(EPackage)


def _inverse_references(root) -> list[set[tuple[int, str]]]:
    """Each object's ``_inverse_rels`` as (position of the owner, feature name) pairs."""
    objects = [root, *root.eAllContents()]
    position = {id(obj): i for i, obj in enumerate(objects)}
    return [{(position[id(owner)], feature.name) for owner, feature in obj._inverse_rels} for obj in objects]


def test_fast_objects_make_pyecore_s_per_object_state_on_first_read() -> None:
    from pyecore.notification import EObserver

    slow, fast = _slow(), _fast()
    assert _inverse_references(fast) == _inverse_references(slow)
    # referred to before it was contained: the containment pair joins the set made by then
    b = model.FastBuilder()
    fi = b.make("FeatureInstance", name="p", category=b.literal("FeatureCategory", "data port"))
    ci = b.make("ConnectionInstance", name="p -> p", source=fi, destination=fi)
    si = b.make("SystemInstance", name="s", category=b.literal("ComponentCategory", "system"))
    b.add(si, "featureInstances", fi)
    b.add(si, "connectionInstances", ci)
    reference = model.new("SystemInstance", name="s", category="system")
    rfi = model.new("FeatureInstance", name="p", category="data port")
    reference.featureInstances.append(rfi)
    reference.connectionInstances.append(
        model.new("ConnectionInstance", name="p -> p", source=rfi, destination=rfi)
    )
    assert _inverse_references(si) == _inverse_references(reference)
    # after moves and removals the sets still match pyecore's own
    for root in (fast, slow):
        component = root.instances[0]
        moved = model.new("SystemInstance", name="other", category="system")
        moved.featureInstances.append(component.featureInstances[0])
        component.featureInstances.append(moved.featureInstances[0])
        root.units[0].classifiers[0].features.remove(root.units[0].classifiers[0].features[1])
    assert _inverse_references(fast) == _inverse_references(slow)
    # listener lists are the object's own, made when first read
    seen = []

    class Observer(EObserver):
        def notifyChanged(self, notification) -> None:
            seen.append(notification.new)

    feature = fast.units[0].classifiers[0].features[0]
    Observer(notifier=feature)
    feature.name = "renamed"
    fast.units[0].classifiers[0].name = "quiet"
    assert seen == ["renamed"]
    # the value holders check types and unset as pyecore's own do
    from pyecore.valuecontainer import BadValueError

    with pytest.raises(BadValueError):
        feature.name = 5
    del feature.classifier
    assert feature.classifier is None and feature.name == "renamed"
    assert feature.listeners is not fast.units[0].classifiers[0].listeners
    assert feature.dyn_inst is feature and "listeners" in vars(feature)


def test_a_subclass_made_after_its_superclass_gets_its_own_defaults() -> None:
    from pyecore.ecore import EClass, EPackage, EReference
    from pyecore.resources import URI, ResourceSet

    from rosaadl.bulk import FastFactory

    # classes no other test has used: the superclass is prepared first
    package = EPackage("fresh", nsURI="urn:test:fresh", nsPrefix="fresh")
    node = EClass("Node")
    node.eStructuralFeatures.append(EReference("children", node, upper=-1, containment=True))
    leaf = EClass("Leaf", superclass=(node,))
    package.eClassifiers.extend([node, leaf])
    parent = FastFactory.new(node.python_class)
    child = FastFactory.new(leaf.python_class)
    for obj, eclass in ((parent, node), (child, leaf)):
        assert obj.dyn_inst is obj
        assert type(obj).dyn_inst is eclass  # pyecore's own class attribute, read on the class
    FastFactory.set_many(child, FastFactory().slot(leaf, "children"), [parent])
    resource = ResourceSet().create_resource(URI("fresh.xmi"))
    resource.append(child)
    assert parent.eResource is resource and child.eResource is resource


def test_fast_ordered_sets_keep_the_first_of_repeated_values_and_work_as_pyecore_s() -> None:
    from pyecore.valuecontainer import EOrderedSet

    from rosaadl.bulk import FastFactory

    b = model.FastBuilder()
    si = b.make("SystemInstance", name="s", category=b.literal("ComponentCategory", "system"))
    a, c, d = (b.make("ComponentInstance", name=n) for n in "acd")
    slot = b.slot(si.eClass, "componentInstances")
    FastFactory.set_many(si, slot, [a, c, a])
    children = si.componentInstances
    assert isinstance(children, EOrderedSet) and children.feature is slot.feature
    assert list(children) == [a, c] and children.index(c) == 1 and children[0] is a
    children.append(d)
    children.remove(a)
    assert list(children) == [c, d] and children.index(d) == 1
    assert a.eContainer() is None and d.eContainer() is si
    assert (si, slot.feature) not in a._inverse_rels and (si, slot.feature) in d._inverse_rels
    reference = model.new("SystemInstance", name="s", category="system")
    reference.componentInstances.extend(model.new("ComponentInstance", name=n) for n in "cd")
    assert model.dumps_json(si) == model.dumps_json(reference)


def test_a_fast_ordered_set_of_one_item_makes_its_index_when_first_read() -> None:
    from rosaadl.bulk import FastFactory

    b = model.FastBuilder()
    si = b.make("SystemInstance", name="s", category=b.literal("ComponentCategory", "system"))
    a, c = (b.make("ComponentInstance", name=n) for n in "ac")
    slot = b.slot(si.eClass, "componentInstances")
    FastFactory.set_many(si, slot, [a])
    children = si.__dict__["componentInstances"]
    assert "map" not in children.__dict__  # no dictionary for the one item until asked
    assert a in children and c not in children and children.index(a) == 0
    assert children.__dict__["map"] == {a: 0}
    children.append(c)
    assert list(children) == [a, c] and children.index(c) == 1
    FastFactory.set_many(si, slot, [c])
    si.componentInstances.remove(c)  # removing reads the index first
    assert list(si.componentInstances) == [] and c.eContainer() is None
    FastFactory.set_many(si, slot, [a])
    si.componentInstances.append(a)  # already there: the set is unchanged
    assert list(si.componentInstances) == [a]


def _with_values(make, literal):
    """A system with a connection and a component holding a property value, built by ``make``
    (see the makers below), to change before any of pyecore's per-object state is read."""
    low, high = make("IntegerValue", value=1, unit="ms"), make("IntegerValue", value=4, unit="ms")
    modal = make("ModalPropertyValue", value=make("RangeValue", minimum=low, maximum=high))
    cet = "Timing_Properties::Compute_Execution_Time"
    pa = make("PropertyAssociation", property=cet, ownedValues=[modal])
    fi = make("FeatureInstance", name="p", category=literal("FeatureCategory", "data port"))
    ci = make(
        "ComponentInstance",
        name="c",
        category=literal("ComponentCategory", "thread"),
        ownedPropertyAssociations=[pa],
    )
    si = make(
        "SystemInstance",
        name="s",
        category=literal("ComponentCategory", "system"),
        featureInstances=[fi],
        componentInstances=[ci],
    )
    make(si, connectionInstances=[make("ConnectionInstance", name="p -> p", source=fi, destination=fi)])
    return si


def _fast_maker():
    """make(class name, **features) or make(object, **lists to append), with FastBuilder."""
    b = model.FastBuilder()

    def make(what, **values):
        single = {name: value for name, value in values.items() if not isinstance(value, list)}
        obj = b.make(what, **single) if isinstance(what, str) else what
        for name, items in values.items():
            if isinstance(items, list):
                b.add(obj, name, *items)
        return obj

    return make, b.literal


def _slow_maker():
    """The same with pyecore's constructors and setters."""

    def make(what, **values):
        if isinstance(what, str):
            return model.new(what, **values)
        for name, items in values.items():
            getattr(what, name).extend(items)
        return what

    return make, lambda _enum, text: text


def _state(root) -> list:
    """Each object's set features (in order) and inverse references, by position."""
    objects = [root, *root.eAllContents()]
    position = {id(obj): i for i, obj in enumerate(objects)}
    return [
        (
            obj.eClass.name,
            [feature.name for feature in obj._isset],
            sorted((position.get(id(owner), -1), feature.name) for owner, feature in obj._inverse_rels),
        )
        for obj in objects
    ]


def test_pyecore_s_changes_before_any_read_of_its_state_leave_the_state_pyecore_s_own_would_be() -> None:
    """_isset and _inverse_rels are made on first read: changes pyecore makes first (removing a
    contained object, unsetting or replacing a single containment, moving, deleting a
    referenced object, reading an unset feature) must leave them as on pyecore's own objects."""
    from rosaadl.bulk import FastFactory

    states = []
    for maker in (_slow_maker, _fast_maker):
        make, literal = maker()
        si = _with_values(make, literal)
        ci = si.componentInstances[0]
        modal = ci.ownedPropertyAssociations[0].ownedValues[0]
        # a single containment replaced, then one unset
        old_range = modal.value
        modal.value = model.new("IntegerValue", value=2, unit="ms")
        old_range.maximum = None
        # a getter's holder for a feature never set is not "set"
        assert ci.classifier is None and not ci.eIsSet("classifier")
        # a contained object removed, and one moved to another container
        other = model.new("SystemInstance", name="other", category="system")
        other.componentInstances.append(ci)
        fi = si.featureInstances[0]
        si.featureInstances.remove(fi)
        si.featureInstances.append(fi)
        # a referenced object deleted: the connection's ends are cleared
        fi.delete()
        assert si.connectionInstances[0].source is None
        states.append((_state(si), _state(other), _state(old_range)))
    assert states[0] == states[1]
    # a feature set by the factory after the state was read joins it
    make, literal = _fast_maker()
    si = _with_values(make, literal)
    assert [f.name for f in si._isset] == [
        "name",
        "category",
        "featureInstances",
        "componentInstances",
        "connectionInstances",
    ]
    FastFactory.set_value(si, FastFactory().slot(si.eClass, "classifier"), "P::S.impl")
    assert "classifier" in [f.name for f in si._isset]
    # appending to a list pyecore's getter made marks it set
    b = model.FastBuilder()
    fi = b.make("FeatureInstance", name="q")
    assert not fi.featureInstances
    b.add(fi, "featureInstances", b.make("FeatureInstance", name="r"))
    assert fi.eIsSet("featureInstances") and fi.featureInstances[0].eContainer() is fi
    assert (fi, fi.eClass.findEStructuralFeature("featureInstances")) in fi.featureInstances[0]._inverse_rels


def test_a_prepared_class_makes_with_object_new_what_fast_new_makes() -> None:
    from pyecore.ecore import EPackage

    from rosaadl import metamodels
    from rosaadl.bulk import FastFactory

    cls = metamodels.load().eclass("ModeInstance").python_class
    FastFactory.prepare(cls)
    FastFactory.prepare(cls)  # once is enough; again changes nothing
    made, fast = object.__new__(cls), FastFactory.new(cls)
    for obj in (made, fast):
        assert obj.eContainer() is None and obj.eResource is None and obj.dyn_inst is obj
        assert not obj._isset and not obj._inverse_rels and obj.listeners == []
        assert obj.name is None and not obj.eIsSet("name")
        obj.name = "m"
        assert obj.eIsSet("name") and [f.name for f in obj._isset] == ["name"]
    with pytest.raises(ModelError, match="not a class made from an EClass"):
        FastFactory.prepare(EPackage)


def test_bulk_refuses_a_pyecore_release_it_was_not_tested_with() -> None:
    import importlib.metadata

    from rosaadl.bulk import check_pyecore_version

    check_pyecore_version(importlib.metadata.version("pyecore"))  # the installed one passes
    check_pyecore_version("0.15.9")
    for other in ("0.16.0", "0.14.3", "1.0"):
        with pytest.raises(ImportError, match=rf"needs pyecore 0\.15\.x .* but pyecore {other} is installed"):
            check_pyecore_version(other)


def test_fast_attributes_are_stored_plain_and_read_and_written_as_pyecore_s() -> None:
    """The factory stores a single-valued attribute without pyecore's value holder (memory);
    reading gives the value, and writing, unsetting, checks and notifications are pyecore's."""
    from pyecore.notification import EObserver
    from pyecore.valuecontainer import BadValueError, EValue

    from rosaadl.bulk import FastFactory, stored_value

    b = model.FastBuilder()
    fi = b.make("FeatureInstance", name="p", category=b.literal("FeatureCategory", "data port"), line=7)
    assert type(fi.__dict__["name"]) is str and type(fi.__dict__["line"]) is int
    assert fi.name == "p" and fi.eGet("line") == 7 and fi.category.name == "dataPort"
    assert type(fi).name is fi.eClass.findEStructuralFeature("name")  # the feature, read on the class
    assert [f.name for f in fi._isset] == ["name", "category", "line"]
    assert stored_value(fi, "name") == "p" and stored_value(fi, "column", 0) == 0
    seen = []

    class Observer(EObserver):
        def notifyChanged(self, notification) -> None:
            seen.append((notification.feature.name, notification.old, notification.new))

    Observer(notifier=fi)
    fi.name = "q"
    fi.eSet("line", 8)
    assert seen == [("name", "p", "q"), ("line", 7, 8)]
    assert isinstance(fi.__dict__["name"], EValue) and stored_value(fi, "name") == "q"
    with pytest.raises(BadValueError):
        fi.column = "x"
    with pytest.raises(BadValueError):
        fi.line = "x"
    del fi.line
    fresh = model.new("FeatureInstance")
    assert fi.line == fresh.line and fi.name == "q"
    assert fi.column == fresh.column and not fi.eIsSet("column")  # never set: pyecore's default
    FastFactory.replace_value(fi, "name", "r")
    other = b.make("FeatureInstance", name="s")
    FastFactory.replace_value(other, "name", "t")
    assert (fi.name, other.name) == ("r", "t")
    slow = model.new("FeatureInstance", name="t")
    assert model.dumps_xmi(other) == model.dumps_xmi(slow) and model.dumps_json(other) == model.dumps_json(
        slow
    )

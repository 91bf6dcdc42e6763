"""The model API: construction, navigation, names, instance paths, properties with units."""

from __future__ import annotations

from fractions import Fraction

import pytest

from rosaadl import model
from rosaadl.errors import ModelError
from rosaadl.properties import EnumLiteral, Range, own_property, property_value
from rosaadl.units import Quantity, standard_units


def _workspace():
    ws = model.new("AadlModel", name="ws")
    pkg = model.new("AadlPackage", name="nd_usb_cam", withs=["ros"])
    ws.units.append(pkg)
    node = model.new("ComponentType", name="usb_cam_nd", category="process", extended="ros::node")
    impl = model.new("ComponentImplementation", name="usb_cam_nd.impl", category="process", type="usb_cam_nd")
    pkg.classifiers.extend([node, impl])
    return ws, pkg, node, impl


def _value(expr):
    return [model.new("ModalPropertyValue", value=expr)]


def _instance():
    top = model.new("SystemInstance", name="top", category="system")
    sw = model.new("ComponentInstance", name="sw", category="system")
    cam = model.new(
        "ComponentInstance", name="cam", category="process", classifier="nd_usb_cam::usb_cam_nd.impl"
    )
    pub = model.new("ComponentInstance", name="publisher", category="thread")
    cpu = model.new("ComponentInstance", name="big_proc1", category="processor")
    arr = [model.new("ComponentInstance", name="core", category="processor", index=[i]) for i in (1, 2)]
    out = model.new("FeatureInstance", name="rgb_out", category="event data port", direction="out")
    top.componentInstances.extend([sw, cpu, *arr])
    sw.componentInstances.append(cam)
    cam.componentInstances.append(pub)
    cam.featureInstances.append(out)
    conn = model.new(
        "ConnectionInstance", name="cam.rgb_out -> cam.rgb_out", kind="port", source=out, destination=out
    )
    sw.connectionInstances.append(conn)
    pub.ownedPropertyAssociations.extend(
        [
            model.new(
                "PropertyAssociation",
                property="Timing_Properties::Period",
                ownedValues=_value(model.new("IntegerValue", value=33333, unit="us")),
            ),
            model.new(
                "PropertyAssociation",
                property="Timing_Properties::Compute_Execution_Time",
                ownedValues=_value(
                    model.new(
                        "RangeValue",
                        minimum=model.new("IntegerValue", value=2319, unit="us"),
                        maximum=model.new("IntegerValue", value=2319, unit="us"),
                    )
                ),
            ),
            model.new(
                "PropertyAssociation",
                property="Thread_Properties::Dispatch_Protocol",
                ownedValues=_value(model.new("NamedValue", name="Periodic")),
            ),
            model.new(
                "PropertyAssociation",
                property="Deployment_Properties::Actual_Processor_Binding",
                ownedValues=_value(
                    model.new(
                        "ListValue",
                        ownedItems=[model.new("InstanceReferenceValue", referencedInstanceObject=cpu)],
                    )
                ),
            ),
        ]
    )
    return top, sw, cam, pub, cpu, out, conn, arr


def test_new_coerces_enums_and_lists_and_rejects_bad_values() -> None:
    ct = model.new("ComponentType", name="t", category="virtual processor")
    assert ct.category.name == "virtualProcessor"
    pkg = model.new("AadlPackage", name="p", withs=("a", "b"))
    assert list(pkg.withs) == ["a", "b"]
    with pytest.raises(ModelError, match="many-valued"):
        model.new("AadlPackage", withs="a")
    with pytest.raises(ModelError, match="not a literal"):
        model.new("ComponentType", category="thred")
    with pytest.raises(ModelError, match="line"):
        model.new("ComponentType", line="twelve")


def test_navigation_and_qualified_names() -> None:
    ws, pkg, node, impl = _workspace()
    assert model.children(pkg) == [node, impl]
    assert model.parent(impl) is pkg and model.root_of(impl) is ws
    assert [o.eClass.name for o in model.walk(ws)] == [
        "AadlModel",
        "AadlPackage",
        "ComponentType",
        "ComponentImplementation",
    ]
    assert model.qualified_name(impl) == "nd_usb_cam::usb_cam_nd.impl"
    assert model.find_classifier(ws, "ND_USB_CAM::usb_cam_nd.IMPL") is impl  # AADL is case-insensitive
    assert model.find_classifier(ws, "usb_cam_nd", context=impl) is node
    assert model.find_classifier(ws, "nd_usb_cam::missing") is None
    assert model.find_classifier(ws, "nope::usb_cam_nd") is None
    assert model.split_qualified("a::b::T.i") == ("a::b", "T.i")


def test_instance_paths_round_trip() -> None:
    top, sw, cam, pub, cpu, out, conn, arr = _instance()
    assert model.instance_path(pub) == "top.sw.cam.publisher"
    assert model.instance_path(out) == "top.sw.cam.rgb_out"
    assert model.instance_path(arr[1]) == "top.core[2]"
    for obj in (pub, out, cpu, arr[0], arr[1], conn, top):
        assert model.find_instance(top, model.instance_path(obj)) is obj
    assert model.find_instance(top, "sw.cam.publisher") is pub  # root name optional
    assert model.find_instance(top, "TOP.SW.CAM") is cam
    assert model.find_instance(top, "top.sw.cam.rgb_out -> cam.rgb_out") is conn
    with pytest.raises(ModelError) as info:
        model.find_instance(top, "top.sw.camera.publisher")
    assert "camera" in str(info.value) and info.value.location.path == "top.sw.camera.publisher"


def test_property_lookup_with_units() -> None:
    top, sw, cam, pub, cpu, out, conn, arr = _instance()
    period = property_value(pub, "Period")
    assert period == Quantity(33333, "us")
    assert period.to("ms") == pytest.approx(33.333)
    assert period.to("ns") == 33333000 and isinstance(period.to("ns"), int)
    cet = property_value(pub, "Timing_Properties::Compute_Execution_Time")
    assert isinstance(cet, Range) and cet.maximum.to("us") == 2319
    assert own_property(pub, "dispatch_protocol") == EnumLiteral("Periodic") == "periodic"
    assert property_value(pub, "Actual_Processor_Binding") == [cpu]
    assert property_value(pub, "Deadline") is None
    with pytest.raises(ModelError) as info:
        property_value(pub, "Deadline", required=True)
    assert info.value.location.path == "top.sw.cam.publisher"


def test_units_conversion_rules() -> None:
    units = standard_units()
    assert units.convert(921, "KByte", "Bytes") == 921000
    assert units.convert(1, "MBytesps", "bitsps") == 8_000_000
    assert units.factor("GIPS", "MIPS") == Fraction(1000)
    with pytest.raises(ModelError, match="cannot convert"):
        units.convert(1, "ms", "Bytes")
    with pytest.raises(ModelError, match="unknown unit"):
        units.convert(1, "fortnight", "ms")
    with pytest.raises(ModelError, match="no unit"):
        Quantity(5).to("ms")


def test_model_files_by_extension(tmp_path) -> None:
    ws, *_ = _workspace()
    with pytest.raises(ModelError, match="xmi or .json"):
        model.save(ws, tmp_path / "ws.txt")
    for name in ("ws.xmi", "ws.json"):
        path = model.save(ws, tmp_path / name)
        assert model.model_equal(model.load(path), ws)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ws.json", "ws.xmi"]  # no temp files left


def test_model_differences_sees_every_kind_of_attribute() -> None:
    a = model.new("Feature", name="f", category="event data port", direction="out")
    for change in ({"category": "data port"}, {"direction": "in out"}, {"name": "g"}, {"refined": True}):
        b = model.new("Feature", **{"name": "f", "category": "event data port", "direction": "out", **change})
        assert model.model_differences(a, b), change
    timer = model.new("rosmod.Timer", name="t", period=__import__("decimal").Decimal("0.5"))
    other = model.new("rosmod.Timer", name="t", period=__import__("decimal").Decimal("0.25"))
    assert model.model_differences(timer, other)


def test_children_come_in_feature_order_in_every_process() -> None:
    """The containment order is the metamodel's feature order, not the order of a set of
    references (which changes from one Python process to the next, with the hash seeds)."""
    import subprocess
    import sys

    script = (
        "from rosaadl import model\n"
        "ci = model.new('ComponentInstance', name='c', category='system')\n"
        "ci.featureInstances.append(model.new('FeatureInstance', name='f'))\n"
        "ci.componentInstances.append(model.new('ComponentInstance', name='s', category='thread'))\n"
        "ci.connectionInstances.append(model.new('ConnectionInstance', name='k'))\n"
        "ci.modeInstances.append(model.new('ModeInstance', name='m'))\n"
        "print([c.eClass.name for c in model.children(ci)])\n"
    )
    runs = {
        subprocess.run(
            [sys.executable, "-c", script],
            capture_output=True,
            text=True,
            check=True,
            env={**__import__("os").environ, "PYTHONHASHSEED": str(seed)},
        ).stdout
        for seed in range(6)
    }
    assert len(runs) == 1, runs
    eclass = model.eclass_of("ComponentInstance")
    order = [f.name for f in eclass.eAllStructuralFeatures() if getattr(f, "containment", False)]
    names = {"featureInstances": "FeatureInstance", "componentInstances": "ComponentInstance"}
    names |= {"connectionInstances": "ConnectionInstance", "modeInstances": "ModeInstance"}
    expected = [names[f] for f in order if f in names]
    assert runs.pop().strip() == str(expected)

"""AADL data classifiers as ROS 2 messages and services: standard types, Base_Types, structures,
ROSMOD definitions (property text or a live conversion trace), subprogram parameters."""

from __future__ import annotations

from test_rclpy_models import (
    _workspace,
    access,
    cimpl,
    ctype,
    lit,
    pa,
    package,
    param,
    port,
    sub,
    text,
    us,
)

from rosaadl import model
from rosaadl.exporters.rclpy import GenerationOptions, InterfaceType, plan_workspace
from rosaadl.exporters.rclpy.messages import MessageCatalog
from rosaadl.transforms.instantiate import instantiate

OPTIONS = GenerationOptions(year=2024)


def one_node(*data_units, port_classifier=None, ports=(), accesses=(), data_package="msgs"):
    """A system with one process whose periodic thread has the given ports and accesses."""
    thread = ctype(
        "worker",
        "thread",
        *(ports or [port("out", "out", port_classifier)]),
        *accesses,
        props=[
            pa("Thread_Properties::Dispatch_Protocol", lit("Periodic")),
            pa("Timing_Properties::Period", us(1000)),
        ],
    )
    app = package(
        "app",
        thread,
        ctype("node", "process"),
        cimpl("node.impl", "process", subs=[sub("worker", "thread", "worker")]),
        ctype("top", "system"),
        cimpl("top.impl", "system", subs=[sub("n", "process", "node.impl")]),
        withs=[data_package, "ROS_Properties"],
    )
    ws = _workspace(*data_units, app)
    return ws, instantiate(ws, "app::top.impl")


def definitions(plan):
    return {d.file_name: d for d in (plan.interfaces.definitions if plan.interfaces else [])}


def test_library_names_map_to_standard_messages_without_properties():
    data = package(
        "ros_data",
        ctype("Image", "data"),
        cimpl("Image.rgb", "data"),
        ctype("Twist", "data"),
        ctype("TFMessage", "data"),
    )
    ws, instance = one_node(
        data,
        ports=[
            port("a", "out", "ros_data::Image.rgb"),
            port("b", "out", "ros_data::Twist"),
            port("c", "out", "ros_data::TFMessage"),
        ],
        data_package="ros_data",
    )
    plan = plan_workspace(instance, options=OPTIONS)
    (cls,) = plan.classes
    assert [p.msg.full_name for p in cls.ports] == [
        "sensor_msgs/msg/Image",
        "geometry_msgs/msg/Twist",
        "tf2_msgs/msg/TFMessage",
    ]
    assert plan.interfaces is None
    assert plan.packages[0].depends == ["rclpy", "geometry_msgs", "sensor_msgs", "tf2_msgs"]


def test_structures_become_messages_with_fields():
    base = package(
        "Base_Types", ctype("Float_64", "data"), ctype("Unsigned_8", "data"), ctype("Boolean", "data")
    )
    data = package(
        "msgs",
        ctype("Pixel", "data"),
        cimpl(
            "Pixel.impl",
            "data",
            subs=[sub("Red", "data", "Base_Types::Unsigned_8"), sub("on", "data", "Base_Types::Boolean")],
        ),
        ctype("Frame", "data"),
        cimpl(
            "Frame.impl",
            "data",
            subs=[
                sub("stamp", "data", "Base_Types::Float_64"),
                sub("pixels", "data", "Pixel.impl", dims=["16"]),
                sub("raw", "data"),
            ],
        ),
        ctype("Loop", "data"),
        cimpl("Loop.impl", "data", subs=[sub("next", "data", "Loop.impl")]),
        withs=["Base_Types"],
    )
    ws, instance = one_node(
        base, data, ports=[port("frame", "out", "msgs::Frame.impl"), port("loop", "out", "msgs::Loop.impl")]
    )
    plan = plan_workspace(instance, options=OPTIONS)
    found = definitions(plan)
    assert sorted(found) == ["Frame.msg", "Loop.msg", "Pixel.msg"]
    assert found["Frame.msg"].lines == ["float64 stamp", "Pixel[16] pixels", "uint8[] raw"]
    assert found["Pixel.msg"].lines == ["uint8 red", "bool on"]
    assert found["Loop.msg"].lines == ["uint8[] next"]  # a type that contains itself: bytes
    assert any("contains itself" in d.message for d in plan.diagnostics)
    assert any("'raw' has no data classifier" in d.message for d in plan.diagnostics)


def test_rosmod_definitions_from_the_property_text():
    definition = (
        "Header header\ntime stamp\nint32 MaxSpeed=10\nstring NAME=abc\nfloat64[3] Position\nother/Thing x\n"
    )
    data = package(
        "msgs",
        ctype(
            "vesselState",
            "data",
            props=[
                pa("ROS_Properties::Message_Type", text("rover_pkg/vessel_state")),
                pa("ROSMOD_Properties::Definition", text(definition)),
            ],
        ),
        ctype("Chatter", "data", props=[pa("ROS_Properties::Message_Type", text("std_msgs/String"))]),
    )
    ws, instance = one_node(
        data, ports=[port("state", "out", "msgs::vesselState"), port("talk", "out", "msgs::Chatter")]
    )
    plan = plan_workspace(instance, options=OPTIONS)
    (cls,) = plan.classes
    assert [p.msg.full_name for p in cls.ports] == ["top_interfaces/msg/VesselState", "std_msgs/msg/String"]
    found = definitions(plan)["VesselState.msg"]
    assert found.lines == [
        "std_msgs/Header header",
        "builtin_interfaces/Time stamp",
        "int32 MAX_SPEED=10",
        "string NAME='abc'",
        "float64[3] position",
        "uint8[] x",
    ]
    assert found.dependencies == {"std_msgs", "builtin_interfaces"}
    assert plan.interfaces.depends == ["builtin_interfaces", "std_msgs"]
    assert any("other/Thing is not known" in d.message for d in plan.diagnostics)


def test_rosmod_definitions_from_a_live_conversion_trace():
    data = package("msgs", ctype("Status", "data"))
    ws, instance = one_node(data, port_classifier="msgs::Status")
    rosmod = model.new("rosmod.Package", name="pkg")
    message = model.new(
        "rosmod.Message",
        name="Status",
        fields=[
            model.new("rosmod.Field", name="level", type="uint8"),
            model.new("rosmod.Field", name="Text", type="string"),
        ],
    )
    rosmod.messages.append(message)
    trace = model.new("trace.Trace", transformation="rosmod_to_aadl")
    link = model.new("trace.TraceLink", rule="message")
    link.sources.append(model.new("trace.TraceElement", object=message))
    link.targets.append(model.new("trace.TraceElement", object=model.find_classifier(ws, "msgs::Status")))
    trace.links.append(link)
    plan = plan_workspace(instance, options=OPTIONS, rosmod_trace=trace)
    assert definitions(plan)["Status.msg"].lines == ["uint8 level", "string text"]


def test_services_from_parameters_and_from_definitions():
    base = package("Base_Types", ctype("Integer_32", "data"))
    data = package(
        "msgs",
        ctype(
            "Add",
            "subprogram",
            param("a", "in", "Base_Types::Integer_32"),
            param("b", "in", "Base_Types::Integer_32"),
            param("sum", "out", "Base_Types::Integer_32"),
        ),
        ctype(
            "Trigger",
            "subprogram",
            props=[
                pa("ROSMOD_Properties::Service_Type", text("pkg/trigger")),
                pa("ROSMOD_Properties::Definition", text("bool now\n---\nbool Done\nstring message\n")),
            ],
        ),
        ctype("Reset", "subprogram", props=[pa("ROSMOD_Properties::Service_Type", text("std_srvs/Empty"))]),
        withs=["Base_Types"],
    )
    ws, instance = one_node(
        base,
        data,
        ports=[port("out", "out", category="event port")],
        accesses=[
            access("add", "provides", "msgs::Add"),
            access("trigger", "requires", "msgs::Trigger"),
            access("reset", "requires", "msgs::Reset"),
        ],
    )
    plan = plan_workspace(instance, options=OPTIONS)
    (cls,) = plan.classes
    assert [s.srv.full_name for s in cls.services] == [
        "top_interfaces/srv/Add",
        "top_interfaces/srv/Trigger",
        "std_srvs/srv/Empty",
    ]
    assert cls.ports[0].msg == InterfaceType("std_msgs", "msg", "Empty")  # an event port
    found = definitions(plan)
    assert (found["Add.srv"].lines, found["Add.srv"].response) == (["int32 a", "int32 b"], ["int32 sum"])
    assert (found["Trigger.srv"].lines, found["Trigger.srv"].response) == (
        ["bool now"],
        ["bool done", "string message"],
    )
    text_out = plan.file("top_interfaces/srv/Trigger.srv").text
    assert "bool now\n" in text_out and "\n---\nbool done\nstring message\n" in text_out


def test_invalid_declared_types_are_reported_and_not_used():
    data = package(
        "msgs", ctype("Bad", "data", props=[pa("ROS_Properties::Message_Type", text("../../etc/passwd"))])
    )
    ws, instance = one_node(data, port_classifier="msgs::Bad")
    plan = plan_workspace(instance, options=OPTIONS)
    assert plan.classes[0].ports[0].msg == InterfaceType("top_interfaces", "msg", "Bad")
    assert any("is not a ROS 2 interface name" in d.message for d in plan.diagnostics)


def test_imports_never_collide():
    data = package(
        "msgs",
        ctype("String", "data"),
        cimpl("String.impl", "data", subs=[sub("s", "data")]),
        ctype("Std", "data", props=[pa("ROS_Properties::Message_Type", text("std_msgs/String"))]),
        ctype("Node", "data"),
    )
    ws, instance = one_node(
        data,
        ports=[
            port("a", "out", "msgs::String.impl"),
            port("b", "out", "msgs::Std"),
            port("c", "out", "msgs::Node"),
        ],
    )
    plan = plan_workspace(instance, options=OPTIONS)
    (cls,) = plan.classes
    assert [p.msg_class for p in cls.ports] == ["TopInterfacesString", "StdMsgsString", "TopInterfacesNode"]
    source = plan.file(f"{cls.package}/{cls.package}/{cls.module}.py").text
    assert "from std_msgs.msg import String as StdMsgsString" in source
    assert "from top_interfaces.msg import Node as TopInterfacesNode, String as TopInterfacesString" in source


def test_catalog_without_a_declarative_model():
    _, instance = one_node(package("msgs", ctype("Image", "data")), port_classifier="msgs::Image")
    catalog = MessageCatalog(None, "x_interfaces")
    feature = instance.componentInstances[0].componentInstances[0].featureInstances[0]
    assert catalog.for_port(feature) == InterfaceType("x_interfaces", "msg", "Image")
    assert [d.lines for d in catalog.definitions()] == [
        ["# msgs::Image has no known structure: its content as bytes.", "uint8[] data"]
    ]

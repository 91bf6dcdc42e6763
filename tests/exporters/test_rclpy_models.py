"""Declarative AADL models for the rclpy generator tests, instantiated by the real instantiator.

``tracking_model()`` mirrors the library's tracking application (``sw_tracking``/``sys_tracking``:
usb_cam → ocv_color_tracking → pos_to_cmd on the cores of an Exynos 5422), written with the
model API so that the generator tests run before (and independently of) the AADL text reader.
``services_model()`` adds what the library does not exercise: services and clients, data ports,
a thread array, threads sharing a protected callback queue, thread groups, SCHED_FIFO priorities.
``hostile_model()`` names everything in the ways a generator must survive.

The tests at the end check that these instances follow the instance-model conventions the
generator relies on.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from rosaadl import model
from rosaadl.properties import property_value
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity

new = model.new

__all__ = [
    "ros_python",
    "ros_environment",
    "tracking_model",
    "tracking_instance",
    "services_model",
    "services_instance",
    "hostile_model",
    "hostile_instance",
]


# --------------------------------------------------------------------------- ROS tools


def ros_python(*tools: str) -> str | None:
    """The Python interpreter of the installed ROS tools (from the first tool script found)."""
    for tool in tools or ("colcon", "ament_flake8", "rosidl"):
        script = shutil.which(tool)
        if script is None:
            continue
        try:
            first = Path(script).read_bytes()[:200].split(b"\n", 1)[0].decode("utf-8", "replace")
        except OSError:
            continue
        if first.startswith("#!"):
            parts = first[2:].split()
            if parts and parts[0].endswith("env") and len(parts) > 1:
                return shutil.which(parts[1])
            if parts:
                return parts[0]
    return None


def ros_environment(python: str) -> dict[str, str]:
    """The environment for the ROS tools: their own Python first on PATH (CMake's python3), no
    virtual environment."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["PATH"] = os.pathsep.join([str(Path(python).parent), env.get("PATH", "")])
    return env


# --------------------------------------------------------------------------- builders


def _many(items):
    return list(items) or None


def pa(prop, value, *applies_to):
    return new(
        "PropertyAssociation",
        property=prop,
        appliesTo=_many(applies_to),
        ownedValues=[new("ModalPropertyValue", value=value)],
    )


def us(value):
    return new("IntegerValue", value=value, unit="us")


def cet(value):
    return new("RangeValue", minimum=us(value), maximum=us(value))


def lit(name):
    return new("NamedValue", name=name)


def text(value):
    return new("StringValue", value=value)


def integer(value):
    return new("IntegerValue", value=value)


def refs(*paths):
    return new("ListValue", ownedItems=[new("ReferenceValue", path=p) for p in paths])


def port(name, direction, classifier=None, category="event data port", props=()):
    return new(
        "Feature",
        name=name,
        category=category,
        direction=direction,
        classifier=classifier,
        ownedPropertyAssociations=_many(props),
    )


def access(name, kind, classifier=None, category="subprogram access"):
    return new("Feature", name=name, category=category, access=kind, classifier=classifier)


def param(name, direction, classifier):
    return new("Feature", name=name, category="parameter", direction=direction, classifier=classifier)


def sub(name, category, classifier=None, dims=(), refined=False):
    return new(
        "Subcomponent",
        name=name,
        category=category,
        classifier=classifier,
        arrayDimensions=_many(dims),
        refined=refined or None,
    )


def conn(name, source, destination, kind="port", bidirectional=False):
    return new(
        "Connection",
        name=name,
        kind=kind,
        source=source,
        destination=destination,
        bidirectional=bidirectional,
    )


def ctype(name, category, *features, props=(), extended=None):
    return new(
        "ComponentType",
        name=name,
        category=category,
        features=_many(features),
        ownedPropertyAssociations=_many(props),
        extended=extended,
    )


def cimpl(name, category, subs=(), conns=(), props=(), extended=None):
    return new(
        "ComponentImplementation",
        name=name,
        type=name.partition(".")[0],
        category=category,
        subcomponents=_many(subs),
        connections=_many(conns),
        ownedPropertyAssociations=_many(props),
        extended=extended,
    )


def package(name, *classifiers, withs=()):
    return new("AadlPackage", name=name, withs=_many(withs), classifiers=_many(classifiers))


def _enum(name, *literals):
    return new(
        "EnumerationType", name=name, ownedLiterals=[new("EnumerationLiteral", name=n) for n in literals]
    )


def _prop(name, type_name=None, owned=None, applies=(), inherit=False, default=None):
    return new(
        "Property",
        name=name,
        type=type_name,
        ownedType=owned,
        appliesTo=list(applies),
        inherit=inherit or None,
        defaultValue=default,
    )


def property_sets():
    """The definitions of the properties these models use (as in the standard and the library)."""
    time_units = new(
        "UnitsType",
        name="Time_Units",
        ownedLiterals=[
            new("UnitLiteral", name="ps"),
            new("UnitLiteral", name="ns", baseUnit="ps", factor=integer(1000)),
            new("UnitLiteral", name="us", baseUnit="ns", factor=integer(1000)),
            new("UnitLiteral", name="ms", baseUnit="us", factor=integer(1000)),
            new("UnitLiteral", name="sec", baseUnit="ms", factor=integer(1000)),
        ],
    )
    project = new(
        "PropertySet",
        name="AADL_Project",
        ownedPropertyTypes=[
            time_units,
            new("AadlInteger", name="Time", unitsType="AADL_Project::Time_Units"),
            new("RangeType", name="Time_Range", numberType="AADL_Project::Time"),
            _enum(
                "Supported_Dispatch_Protocols",
                "Periodic",
                "Sporadic",
                "Aperiodic",
                "Timed",
                "Hybrid",
                "Background",
            ),
            _enum(
                "Supported_Concurrency_Control_Protocols", "None_Specified", "Semaphore", "Priority_Ceiling"
            ),
            _enum("Supported_POSIX_Scheduling_Policies", "SCHED_FIFO", "SCHED_RR", "SCHED_OTHERS"),
        ],
    )
    threads = ["thread", "thread group", "process", "system", "device"]
    timing = new(
        "PropertySet",
        name="Timing_Properties",
        ownedProperties=[
            _prop("Period", "AADL_Project::Time", applies=threads, inherit=True),
            _prop("Deadline", "AADL_Project::Time", applies=threads, inherit=True),
            _prop("Compute_Execution_Time", "AADL_Project::Time_Range", applies=["thread", "device"]),
        ],
    )
    thread_props = new(
        "PropertySet",
        name="Thread_Properties",
        ownedProperties=[
            _prop(
                "Dispatch_Protocol",
                "AADL_Project::Supported_Dispatch_Protocols",
                applies=["thread", "device"],
            ),
            _prop(
                "Priority", owned=new("AadlInteger"), applies=["thread", "process", "device"], inherit=True
            ),
            _prop(
                "POSIX_Scheduling_Policy",
                "AADL_Project::Supported_POSIX_Scheduling_Policies",
                applies=["thread", "thread group", "process"],
                inherit=True,
            ),
            _prop(
                "Concurrency_Control_Protocol",
                "AADL_Project::Supported_Concurrency_Control_Protocols",
                applies=["data"],
            ),
        ],
    )
    comm = new(
        "PropertySet",
        name="Communication_Properties",
        ownedProperties=[
            _prop("Queue_Size", owned=new("AadlInteger"), applies=["event port", "event data port"])
        ],
    )
    deployment = new(
        "PropertySet",
        name="Deployment_Properties",
        ownedProperties=[
            _prop(
                "Actual_Processor_Binding",
                owned=new("ListType", ownedElementType=new("ReferenceType")),
                applies=["thread", "thread group", "process", "system", "virtual processor"],
                inherit=True,
            ),
            _prop(
                "Actual_Connection_Binding",
                owned=new("ListType", ownedElementType=new("ReferenceType")),
                applies=["connection"],
                inherit=True,
            ),
        ],
    )
    ros = new(
        "PropertySet",
        name="ROS_Properties",
        ownedProperties=[
            _prop("Node_Name", owned=new("AadlString"), applies=["process"]),
            _prop("Namespace", owned=new("AadlString"), applies=["system", "process"], inherit=True),
            _prop("Package_Name", owned=new("AadlString"), applies=["process"]),
            _prop("Executable", owned=new("AadlString"), applies=["process"]),
            _prop("Topic_Name", owned=new("AadlString"), applies=["port", "subprogram access", "connection"]),
            _prop("Message_Type", owned=new("AadlString"), applies=["data", "port", "subprogram access"]),
            _prop("QoS_Depth", owned=new("AadlInteger"), applies=["port", "connection"]),
        ],
    )
    hardware = new(
        "PropertySet",
        name="Hardware_Properties",
        ownedProperties=[_prop("Architecture", owned=new("AadlString"), applies=["system", "processor"])],
    )
    return [project, timing, thread_props, comm, deployment, ros, hardware]


def _workspace(*packages):
    ws = new("AadlModel", name="ws")
    ws.units.extend(property_sets())
    ws.units.extend(packages)
    return ws


# --------------------------------------------------------------------------- shared packages


def _ros_data():
    return package(
        "ros_data",
        ctype("Point", "data", props=[pa("ROS_Properties::Message_Type", text("geometry_msgs/Point"))]),
        cimpl("Point.impl", "data"),
        ctype("Twist", "data", props=[pa("ROS_Properties::Message_Type", text("geometry_msgs/Twist"))]),
        ctype("Image", "data", props=[pa("ROS_Properties::Message_Type", text("sensor_msgs/Image"))]),
        cimpl("Image.impl", "data"),
        cimpl("Image.rgb", "data", extended="Image.impl"),
        ctype("video_stream", "data"),
        cimpl("video_stream.impl", "data"),
        cimpl("video_stream.rgb", "data", extended="video_stream.impl"),
    )


def _ros():
    dispatch = "Thread_Properties::Dispatch_Protocol"
    policy = "Thread_Properties::POSIX_Scheduling_Policy"
    return package(
        "ros",
        ctype("node", "process"),
        cimpl("node.impl", "process"),
        ctype(
            "subscriber",
            "thread",
            port("sub_msg", "in"),
            props=[pa(dispatch, lit("Sporadic")), pa(policy, lit("SCHED_OTHERS"))],
        ),
        ctype("spinner", "thread", props=[pa(dispatch, lit("Sporadic")), pa(policy, lit("SCHED_OTHERS"))]),
        ctype(
            "callback",
            "thread",
            port("cb_msg", "in"),
            props=[pa(dispatch, lit("Sporadic")), pa(policy, lit("SCHED_OTHERS"))],
        ),
        ctype(
            "publisher",
            "thread",
            port("pub_msg", "out"),
            props=[pa(dispatch, lit("Periodic")), pa(policy, lit("SCHED_OTHERS"))],
        ),
        ctype(
            "callback_queue",
            "data",
            props=[pa("Thread_Properties::Concurrency_Control_Protocol", lit("Semaphore"))],
        ),
        ctype("ROSbus", "virtual bus"),
        cimpl("ROSbus.impl", "virtual bus"),
        withs=["ros_data", "ROS_Properties"],
    )


def _hardware():
    arch = "Hardware_Properties::Architecture"
    return package(
        "hw",
        ctype("ARM_A15", "processor", props=[pa(arch, text("ARM Cortex-A15"))]),
        cimpl("ARM_A15.impl", "processor"),
        ctype("ARM_A7", "processor", props=[pa(arch, text("ARM Cortex-A7"))]),
        cimpl("ARM_A7.impl", "processor"),
        ctype("A15_cluster", "system"),
        cimpl(
            "A15_cluster.impl",
            "system",
            subs=[sub(f"big_proc{i}", "processor", "ARM_A15.impl") for i in range(1, 5)],
        ),
        ctype("A7_cluster", "system"),
        cimpl(
            "A7_cluster.impl",
            "system",
            subs=[sub(f"little_proc{i}", "processor", "ARM_A7.impl") for i in range(1, 5)],
        ),
        ctype("Exynos_5422", "system", props=[pa(arch, text("Octo core ARM15 / ARM7"))]),
        cimpl(
            "Exynos_5422.impl",
            "system",
            subs=[
                sub("big_procs_cluster", "system", "A15_cluster.impl"),
                sub("little_procs_cluster", "system", "A7_cluster.impl"),
            ],
        ),
        ctype("Odroid_XU4", "system"),
        cimpl("Odroid_XU4.impl", "system", subs=[sub("Exynos_SOC", "system", "Exynos_5422.impl")]),
        ctype("camera", "device", port("rgb_stream_out", "out", "ros_data::video_stream.rgb")),
        ctype("base", "device", port("cmd_vel_in", "in", "ros_data::Twist")),
        ctype(
            "Pioneer_3DX",
            "system",
            port("rgb_stream_out", "out", "ros_data::video_stream.rgb"),
            port("cmd_vel_in", "in", "ros_data::Twist"),
        ),
        cimpl(
            "Pioneer_3DX.impl",
            "system",
            subs=[
                sub("OdroidXU4", "system", "Odroid_XU4.impl"),
                sub("cam", "device", "camera"),
                sub("drive", "device", "base"),
            ],
            conns=[
                conn("c1", "cam.rgb_stream_out", "rgb_stream_out"),
                conn("c2", "cmd_vel_in", "drive.cmd_vel_in"),
            ],
        ),
        withs=["ros_data", "Hardware_Properties"],
    )


# --------------------------------------------------------------------------- tracking


def _node_packages():
    period = "Timing_Properties::Period"
    compute = "Timing_Properties::Compute_Execution_Time"
    node = "ROS_Properties::Node_Name"
    usb_cam = package(
        "nd_usb_cam",
        ctype(
            "usb_cam_nd",
            "process",
            port("rgb_stream_in", "in", "ros_data::video_stream.rgb"),
            port("rgb_image_raw_out", "out", "ros_data::Image.rgb"),
            extended="ros::node",
            props=[
                pa(node, text("usb_cam")),
                pa("ROS_Properties::Package_Name", text("usb_cam")),
                pa("ROS_Properties::Topic_Name", text("/usb_cam/image_raw"), "rgb_image_raw_out"),
            ],
        ),
        cimpl(
            "usb_cam_nd.impl",
            "process",
            extended="ros::node.impl",
            subs=[
                sub("image_broadcaster", "thread", "imagePublisher.impl"),
                sub("usbSpinner", "thread", "usbcam_spinner.impl"),
            ],
            conns=[
                conn("con1", "image_broadcaster.pub_msg", "rgb_image_raw_out"),
                conn("con2", "rgb_stream_in", "usbSpinner.rgb_stream_in"),
            ],
            props=[pa(period, us(33333))],
        ),
        ctype(
            "imagePublisher",
            "thread",
            new(
                "Feature",
                name="pub_msg",
                category="event data port",
                direction="out",
                classifier="ros_data::Image.rgb",
                refined=True,
            ),
            extended="ros::publisher",
        ),
        cimpl("imagePublisher.impl", "thread", props=[pa(period, us(33333))]),
        ctype(
            "usbcam_spinner",
            "thread",
            port("rgb_stream_in", "in", "ros_data::video_stream.rgb"),
            extended="ros::spinner",
        ),
        cimpl("usbcam_spinner.impl", "thread", props=[pa(period, us(33333))]),
        cimpl(
            "usb_cam_nd.xu4_a15",
            "process",
            extended="usb_cam_nd.impl",
            subs=[sub("image_broadcaster", "thread", "imagePublisher.xu4_a15", refined=True)],
        ),
        cimpl(
            "imagePublisher.xu4_a15",
            "thread",
            extended="imagePublisher.impl",
            props=[
                pa(compute, cet(2319)),
                pa("Communication_Properties::Queue_Size", integer(512), "pub_msg"),
            ],
        ),
        withs=["ros", "ros_data", "ROS_Properties"],
    )
    tracker = package(
        "nd_ocv_color_tracking",
        ctype(
            "ocv_color_tracking_nd",
            "process",
            port("image_in", "in", "ros_data::Image.rgb"),
            port("point_out", "out", "ros_data::Point.impl"),
            extended="ros::node",
            props=[pa(node, text("ocv_color_tracking"))],
        ),
        cimpl(
            "ocv_color_tracking_nd.impl",
            "process",
            extended="ros::node.impl",
            subs=[
                sub("image_tracker", "thread", "colorTracker.impl"),
                sub("point_broadcaster", "thread", "pointPublisher.impl"),
            ],
            conns=[
                conn("con1", "image_in", "image_tracker.cb_msg"),
                conn("con2", "point_broadcaster.pub_msg", "point_out"),
            ],
            props=[pa(period, us(33333))],
        ),
        ctype(
            "colorTracker",
            "thread",
            new(
                "Feature",
                name="cb_msg",
                category="event data port",
                direction="in",
                classifier="ros_data::Image.rgb",
                refined=True,
            ),
            extended="ros::callback",
        ),
        cimpl("colorTracker.impl", "thread", props=[pa(period, us(33333))]),
        ctype(
            "pointPublisher",
            "thread",
            new(
                "Feature",
                name="pub_msg",
                category="event data port",
                direction="out",
                classifier="ros_data::Point.impl",
                refined=True,
            ),
            extended="ros::publisher",
        ),
        cimpl("pointPublisher.impl", "thread", props=[pa(period, us(100000))]),
        cimpl(
            "ocv_color_tracking_nd.xu4_a15",
            "process",
            extended="ocv_color_tracking_nd.impl",
            subs=[sub("image_tracker", "thread", "colorTracker.xu4_a15", refined=True)],
        ),
        cimpl(
            "colorTracker.xu4_a15", "thread", extended="colorTracker.impl", props=[pa(compute, cet(37000))]
        ),
        withs=["ros", "ros_data", "ROS_Properties"],
    )
    poscmd = package(
        "nd_pos_to_cmd",
        ctype(
            "pos_to_cmd_nd",
            "process",
            port("point_in", "in", "ros_data::Point.impl"),
            port("cmd_vel_out", "out", "ros_data::Twist"),
            extended="ros::node",
            props=[pa(node, text("pos_to_cmd"))],
        ),
        cimpl(
            "pos_to_cmd_nd.impl",
            "process",
            extended="ros::node.impl",
            subs=[
                sub("point_receiver", "thread", "pointSubscriber.impl"),
                sub("cmd_publisher", "thread", "cmdPublisher.impl"),
            ],
            conns=[
                conn("con1", "point_in", "point_receiver.sub_msg"),
                conn("con2", "cmd_publisher.pub_msg", "cmd_vel_out"),
            ],
            props=[pa(period, us(100000))],
        ),
        ctype(
            "pointSubscriber",
            "thread",
            new(
                "Feature",
                name="sub_msg",
                category="event data port",
                direction="in",
                classifier="ros_data::Point.impl",
                refined=True,
            ),
            extended="ros::subscriber",
        ),
        cimpl("pointSubscriber.impl", "thread", props=[pa(period, us(100000))]),
        ctype(
            "cmdPublisher",
            "thread",
            new(
                "Feature",
                name="pub_msg",
                category="event data port",
                direction="out",
                classifier="ros_data::Twist",
                refined=True,
            ),
            extended="ros::publisher",
        ),
        cimpl("cmdPublisher.impl", "thread", props=[pa(period, us(100000))]),
        cimpl(
            "pos_to_cmd_nd.xu4_a7",
            "process",
            extended="pos_to_cmd_nd.impl",
            subs=[sub("cmd_publisher", "thread", "cmdPublisher.xu4_a7", refined=True)],
        ),
        cimpl("cmdPublisher.xu4_a7", "thread", extended="cmdPublisher.impl", props=[pa(compute, cet(1060))]),
        withs=["ros", "ros_data", "ROS_Properties"],
    )
    return usb_cam, tracker, poscmd


def tracking_model():
    """sw_tracking/sys_tracking as in the library: three nodes on three cores of an Odroid XU4."""
    sw = package(
        "sw_tracking",
        ctype(
            "tracking_sw",
            "system",
            port("rgb_stream_in", "in", "ros_data::video_stream.rgb"),
            port("cmd_vel_out", "out", "ros_data::Twist"),
        ),
        cimpl(
            "tracking_sw.impl",
            "system",
            subs=[
                sub("usbcam", "process", "nd_usb_cam::usb_cam_nd.impl"),
                sub("tracker", "process", "nd_ocv_color_tracking::ocv_color_tracking_nd.impl"),
                sub("poscmd", "process", "nd_pos_to_cmd::pos_to_cmd_nd.impl"),
            ],
            conns=[
                conn("con1", "rgb_stream_in", "usbcam.rgb_stream_in"),
                conn("con6", "usbcam.rgb_image_raw_out", "tracker.image_in"),
                conn("con7", "tracker.point_out", "poscmd.point_in"),
                conn("con8", "poscmd.cmd_vel_out", "cmd_vel_out"),
            ],
        ),
        cimpl(
            "tracking_sw.xu4",
            "system",
            extended="tracking_sw.impl",
            subs=[
                sub("usbcam", "process", "nd_usb_cam::usb_cam_nd.xu4_a15", refined=True),
                sub(
                    "tracker", "process", "nd_ocv_color_tracking::ocv_color_tracking_nd.xu4_a15", refined=True
                ),
                sub("poscmd", "process", "nd_pos_to_cmd::pos_to_cmd_nd.xu4_a7", refined=True),
            ],
        ),
        withs=["ros_data", "nd_usb_cam", "nd_ocv_color_tracking", "nd_pos_to_cmd"],
    )
    binding = "Deployment_Properties::Actual_Processor_Binding"
    soc = "p3DX.OdroidXU4.Exynos_SOC"
    system = package(
        "sys_tracking",
        ctype("tracking", "system"),
        cimpl(
            "tracking.impl",
            "system",
            subs=[
                sub("rem_trk_sw", "system", "sw_tracking::tracking_sw.xu4"),
                sub("p3DX", "system", "hw::Pioneer_3DX.impl"),
                sub("ROSbus", "virtual bus", "ros::ROSbus.impl"),
            ],
            conns=[
                conn("cam_stream", "p3DX.rgb_stream_out", "rem_trk_sw.rgb_stream_in"),
                conn("base_cmd", "rem_trk_sw.cmd_vel_out", "p3DX.cmd_vel_in"),
            ],
            props=[
                pa(binding, refs(f"{soc}.big_procs_cluster.big_proc1"), "rem_trk_sw.usbcam"),
                pa(binding, refs(f"{soc}.big_procs_cluster.big_proc2"), "rem_trk_sw.tracker"),
                pa(binding, refs(f"{soc}.little_procs_cluster.little_proc1"), "rem_trk_sw.poscmd"),
            ],
        ),
        withs=["ros", "sw_tracking", "hw"],
    )
    return _workspace(_ros_data(), _ros(), _hardware(), *_node_packages(), sw, system)


def tracking_instance():
    ws = tracking_model()
    return ws, instantiate(ws, "sys_tracking::tracking.impl")


# --------------------------------------------------------------------------- services & co


def services_model():
    """A ROSMOD-like application: a planner component (timer + server + client sharing a callback
    queue), a worker pool (thread array), a monitor with a data port, SCHED_FIFO priorities."""
    dispatch = "Thread_Properties::Dispatch_Protocol"
    period = "Timing_Properties::Period"
    deadline = "Timing_Properties::Deadline"
    prio = "Thread_Properties::Priority"
    app = package(
        "planning",
        ctype("Pose", "data"),
        cimpl(
            "Pose.impl",
            "data",
            subs=[
                sub("x", "data", "Base_Types::Float_64"),
                sub("y", "data", "Base_Types::Float_64"),
                sub("heading", "data", "ros_data::Point"),
            ],
        ),
        ctype("Status", "data", props=[pa("ROS_Properties::Message_Type", text("std_msgs/String"))]),
        ctype(
            "GetPlan",
            "subprogram",
            param("goal", "in", "Pose.impl"),
            param("steps", "out", "Base_Types::Unsigned_32"),
        ),
        ctype(
            "planner_timer",
            "thread",
            port("pose_out", "out", "Pose.impl"),
            access("plan", "requires", "GetPlan"),
            new(
                "Feature",
                name="queue",
                category="data access",
                access="requires",
                classifier="ros::callback_queue",
            ),
            props=[
                pa(dispatch, lit("Periodic")),
                pa(period, us(50000)),
                pa(deadline, us(20000)),
                pa(prio, integer(60)),
            ],
        ),
        ctype(
            "planner_server",
            "thread",
            access("get_plan", "provides", "GetPlan"),
            new(
                "Feature",
                name="queue",
                category="data access",
                access="requires",
                classifier="ros::callback_queue",
            ),
            props=[pa(dispatch, lit("Sporadic")), pa(period, us(10000)), pa(prio, integer(55))],
        ),
        ctype(
            "worker",
            "thread",
            port("job", "in", "Pose.impl", props=[pa("Communication_Properties::Queue_Size", integer(8))]),
            props=[pa(dispatch, lit("Sporadic")), pa(period, us(5000))],
        ),
        ctype(
            "monitor",
            "thread",
            port("status", "in", "Status", category="data port"),
            port("logs", "in", "Status"),
            port("alarm", "out", category="event port"),
            props=[pa(dispatch, lit("Periodic")), pa(period, us(200000))],
        ),
        ctype(
            "component",
            "thread group",
            port("pose_out", "out", "Pose.impl"),
            port("log_out", "out", "Status"),
            access("plan", "requires", "GetPlan"),
            access("get_plan", "provides", "GetPlan"),
        ),
        cimpl(
            "component.impl",
            "thread group",
            subs=[
                sub("timer", "thread", "planner_timer"),
                sub("server", "thread", "planner_server"),
                sub("queue", "data", "ros::callback_queue"),
            ],
            conns=[
                conn("q1", "queue", "timer.queue", kind="access"),
                conn("q2", "queue", "server.queue", kind="access"),
                conn("p1", "timer.pose_out", "pose_out"),
                conn("a1", "plan", "timer.plan", kind="access"),
                conn("a2", "server.get_plan", "get_plan", kind="access"),
            ],
        ),
        ctype(
            "planner_node",
            "process",
            port("pose_out", "out", "Pose.impl"),
            port("log_out", "out", "Status"),
            access("plan", "requires", "GetPlan"),
            access("get_plan", "provides", "GetPlan"),
            props=[pa(prio, integer(70))],
        ),
        cimpl(
            "planner_node.impl",
            "process",
            subs=[sub("comp", "thread group", "component.impl")],
            conns=[
                conn("p1", "comp.pose_out", "pose_out"),
                conn("l1", "comp.log_out", "log_out"),
                conn("a1", "plan", "comp.plan", kind="access"),
                conn("a2", "comp.get_plan", "get_plan", kind="access"),
            ],
        ),
        ctype(
            "pool_node",
            "process",
            port("jobs", "in", "Pose.impl"),
            port("logs_in", "in", "Status"),
            port("status_in", "in", "Status", category="data port"),
            port("alarm_out", "out", category="event port"),
        ),
        cimpl(
            "pool_node.impl",
            "process",
            subs=[sub("workers", "thread", "worker", dims=["3"]), sub("mon", "thread", "monitor")],
            conns=[
                conn("j", "jobs", "workers.job"),
                conn("s", "status_in", "mon.status"),
                conn("lg", "logs_in", "mon.logs"),
                conn("al", "mon.alarm", "alarm_out"),
            ],
        ),
        ctype("status_node", "process", port("status_out", "out", "Status", category="data port")),
        ctype("cpu", "processor"),
        ctype("app", "system"),
        cimpl(
            "app.impl",
            "system",
            subs=[
                sub("planner", "process", "planner_node.impl"),
                sub("pool", "process", "pool_node.impl"),
                sub("status", "process", "status_node"),
                sub("host1", "processor", "cpu"),
                sub("host2", "processor", "cpu"),
            ],
            conns=[
                conn("poses", "planner.pose_out", "pool.jobs"),
                conn("calls", "planner.get_plan", "planner.plan", kind="access"),
                conn("st", "status.status_out", "pool.status_in"),
                conn("logs", "planner.log_out", "pool.logs_in"),
            ],
            props=[
                pa("Deployment_Properties::Actual_Processor_Binding", refs("host1"), "planner"),
                pa("Deployment_Properties::Actual_Processor_Binding", refs("host2"), "pool"),
                pa("ROS_Properties::Topic_Name", text("/plan/poses"), "poses"),
            ],
        ),
        withs=["ros", "ros_data", "Base_Types", "ROS_Properties"],
    )
    base_types = package(
        "Base_Types",
        ctype("Float_64", "data"),
        ctype("Unsigned_32", "data"),
    )
    return _workspace(_ros_data(), _ros(), base_types, app)


def services_instance():
    ws = services_model()
    return ws, instantiate(ws, "planning::app.impl")


# --------------------------------------------------------------------------- hostile names


def hostile_model():
    """Names with path tricks, quotes, keywords and non-ASCII letters, as AADL names and as
    property values (node names, topic names, message types, package names)."""
    dispatch = "Thread_Properties::Dispatch_Protocol"
    period = "Timing_Properties::Period"
    app = package(
        "class",
        ctype("données", "data"),
        cimpl(
            "données.impl",
            "data",
            subs=[
                sub("import", "data", "Base_Types::Float_64"),
                sub("Größe", "data", "Base_Types::Float_64"),
            ],
        ),
        ctype(
            "def",
            "thread",
            port(
                "lambda",
                "out",
                "données.impl",
                props=[pa("ROS_Properties::Topic_Name", text("/../../etc/pa'ss\"wd"))],
            ),
            port("相机", "in", "données.impl"),
            props=[pa(dispatch, lit("Periodic")), pa(period, us(1000))],
        ),
        ctype(
            "node",
            "process",
            props=[
                pa("ROS_Properties::Node_Name", text("../../etc/passwd")),
                pa("ROS_Properties::Package_Name", text('../../evil"pkg')),
                pa("ROS_Properties::Executable", text("rm -rf /")),
            ],
        ),
        cimpl(
            "node.impl",
            "process",
            subs=[
                sub("def", "thread", "def"),
                sub("for", "thread", "def"),
                sub("ünïcødé", "thread", "def"),
                sub("an_extremely_long_thread_name_that_goes_on_" * 4 + "end", "thread", "def"),
            ],
        ),
        ctype("système", "system"),
        cimpl(
            "système.impl",
            "system",
            subs=[sub("a", "process", "node.impl"), sub("b", "process", "node.impl")],
            conns=[conn("c", "a.def.lambda", "b.for.相机")],
            props=[pa("ROS_Properties::Namespace", text("/" + "a_rather_long_namespace_segment/" * 6), "b")],
        ),
        withs=["Base_Types", "ROS_Properties"],
    )
    return _workspace(package("Base_Types", ctype("Float_64", "data")), app)


def hostile_instance():
    ws = hostile_model()
    return ws, instantiate(ws, "class::système.impl", strict=False)


# --------------------------------------------------------------------------- conventions


def test_tracking_instance_follows_the_conventions():
    ws, system = tracking_instance()
    assert system.name == "tracking_impl_Instance"
    tracker = model.find_instance(system, "rem_trk_sw.tracker")
    assert tracker.classifier == "nd_ocv_color_tracking::ocv_color_tracking_nd.xu4_a15"
    thread = model.find_instance(system, "rem_trk_sw.tracker.image_tracker")
    assert str(property_value(thread, "Dispatch_Protocol")) == "Sporadic"
    assert property_value(thread, "Period") == Quantity(33333, "us")
    image = model.find_instance(system, "rem_trk_sw.tracker.image_tracker.cb_msg")
    assert image.classifier == "ros_data::Image.rgb"
    bound = property_value(tracker, "Actual_Processor_Binding")
    assert [model.instance_path(b) for b in bound] == [
        "tracking_impl_Instance.p3DX.OdroidXU4.Exynos_SOC.big_procs_cluster.big_proc2"
    ]
    names = sorted(c.name for c in model.walk(system) if c.eClass.name == "ConnectionInstance")
    assert "usbcam.image_broadcaster.pub_msg -> tracker.image_tracker.cb_msg" in names


def test_services_instance_follows_the_conventions():
    ws, system = services_instance()
    workers = [c for c in model.find_instance(system, "pool").componentInstances if c.name == "workers"]
    assert [list(w.index) for w in workers] == [[1], [2], [3]]
    kinds = sorted({c.kind.name for c in model.walk(system) if c.eClass.name == "ConnectionInstance"})
    assert kinds == ["accessConnection", "portConnection"]

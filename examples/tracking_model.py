"""The paper's target-tracking application as a ROSMOD model, built through the model API.

camera → usb_cam → ocv_color_tracking → pos_to_cmd → robot base, deployed on one host. Used by
``rosaadl demo`` until the textual ROSMOD project of the same application is read by the ROSMOD
importer.
"""

from __future__ import annotations

from decimal import Decimal

from pyecore.ecore import EObject

from rosaadl import model

__all__ = ["tracking_project"]


def tracking_project() -> EObject:
    new = model.new
    pkg = new("rosmod.Package", name="tracking")
    pkg.messages.extend(
        [
            new("rosmod.Message", name="Image", definition="uint32 height\nuint32 width\nuint8[] data\n"),
            new("rosmod.Message", name="Point", definition="float64 x\nfloat64 y\nfloat64 z\n"),
            new("rosmod.Message", name="Twist", definition="float64[3] linear\nfloat64[3] angular\n"),
        ]
    )
    usb_cam = new("rosmod.Component", name="usb_cam", datatype="Base", schedulingScheme="FIFO")
    usb_cam.timers.append(
        new(
            "rosmod.Timer", name="grab", period=Decimal("0.033333"), priority=50, deadline=Decimal("0.033333")
        )
    )
    usb_cam.ports.append(new("rosmod.Publisher", name="image_raw", type="tracking/Image"))
    tracker = new("rosmod.Component", name="ocv_color_tracking", datatype="Base", schedulingScheme="FIFO")
    tracker.ports.extend(
        [
            new(
                "rosmod.Subscriber",
                name="image_in",
                type="tracking/Image",
                priority=50,
                deadline=Decimal("0.033333"),
            ),
            new("rosmod.Publisher", name="target", type="tracking/Point"),
        ]
    )
    pos_to_cmd = new("rosmod.Component", name="pos_to_cmd", datatype="Base", schedulingScheme="FIFO")
    pos_to_cmd.ports.extend(
        [
            new(
                "rosmod.Subscriber",
                name="target_in",
                type="tracking/Point",
                priority=50,
                deadline=Decimal("0.1"),
            ),
            new("rosmod.Publisher", name="cmd_vel", type="tracking/Twist"),
        ]
    )
    pkg.components.extend([usb_cam, tracker, pos_to_cmd])
    software = new("rosmod.Software", name="software", packages=[pkg])
    host = new(
        "rosmod.Host", name="odroid_xu4", ipAddress="10.0.0.2", username="odroid", architecture="armv7l"
    )
    system = new("rosmod.System", name="pioneer3dx", hosts=[host])
    deployment = new("rosmod.Deployment", name="pioneer", system=system, systemName="pioneer3dx")
    for index, component in enumerate((usb_cam, tracker, pos_to_cmd)):
        node = new(
            "rosmod.Node",
            name=f"{component.name}_node",
            host=host,
            hostRef="pioneer3dx/odroid_xu4",
            priority=50 + index,
        )
        node.componentInstances.append(
            new(
                "rosmod.ComponentInstance",
                name=f"{component.name}_i",
                component=component,
                componentRef=f"tracking/{component.name}",
                schedulingScheme="FIFO",
            )
        )
        deployment.nodes.append(node)
    return new(
        "rosmod.Project",
        name="tracking",
        formatVersion="0.3",
        software=software,
        systems=[system],
        deployments=[deployment],
    )

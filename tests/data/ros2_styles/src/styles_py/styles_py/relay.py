"""Topics given to the constructor, QoS profiles bound to names first."""

import rclpy
from rclpy.node import Node
from rclpy.qos import QoSPresetProfiles, QoSProfile, QoSReliabilityPolicy
from sensor_msgs.msg import Imu as ImuMsg

FAST = QoSPresetProfiles.SENSOR_DATA.value


class Relay(Node):
    def __init__(self, source, sink="relayed", node_name="relay"):
        super().__init__(node_name)
        lossy = QoSProfile(depth=3, reliability=QoSReliabilityPolicy.RMW_QOS_POLICY_RELIABILITY_BEST_EFFORT)
        self.inbox = self.create_subscription(ImuMsg, source, self.forward, lossy)
        self.outbox = self.create_publisher(ImuMsg, sink, qos_profile=FAST)
        tuned = QoSProfile(depth=2)
        tuned.depth = 7
        self.audit = self.create_publisher(ImuMsg, "audit", tuned)

    def forward(self, msg):
        self.outbox.publish(msg)


def main():
    rclpy.init()
    upstream = "imu/raw"
    rclpy.spin(Relay(upstream))

"""A lifecycle node named by its caller, its rate a class attribute."""

import rclpy
import std_msgs.msg
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn


class Beacon(LifecycleNode):
    RATE_HZ = 4

    def __init__(self, name, **kwargs):
        super().__init__(name, namespace="fleet", **kwargs)

    def on_configure(self, state):
        self.out = self.create_lifecycle_publisher(std_msgs.msg.Header, "beacon", 1)
        self.tick = self.create_timer(1.0 / self.RATE_HZ, self.send)
        return TransitionCallbackReturn.SUCCESS

    def send(self):
        self.out.publish(std_msgs.msg.Header())


def main():
    rclpy.init()
    rclpy.spin(Beacon("lighthouse"))

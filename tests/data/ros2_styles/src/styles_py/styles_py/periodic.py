"""A base node class of the package: a heartbeat and a timer at the period it is given."""

from rclpy.node import Node
from std_msgs.msg import Empty

BEAT_TOPIC = "alive"


class Periodic(Node):
    def __init__(self, name, period=1.0):
        super().__init__(name)
        self.alive = self.create_publisher(Empty, BEAT_TOPIC, 1)
        self.step_timer = self.create_timer(period, self.step)

    def step(self):
        self.alive.publish(Empty())

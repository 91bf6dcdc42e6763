# Patterns a static reader cannot decide: publishers made in a loop, a timer of unknown period.
import random

import rclpy
from rclpy.node import Node
from std_msgs.msg import String

TOPICS = ['a', 'b']


class FanOut(Node):

    def __init__(self, message_type=String):
        super().__init__('fan_out')
        self.pubs = []
        for name in TOPICS:
            self.pubs.append(self.create_publisher(String, name, 10))
        self.jitter = self.create_timer(random.random(), self.tick)
        self.other = self.create_publisher(message_type, 'other', 10)

    def tick(self):
        pass


def main():
    rclpy.init()
    rclpy.spin(FanOut())

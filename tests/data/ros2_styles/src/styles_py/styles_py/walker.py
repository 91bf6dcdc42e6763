"""A node deriving from a node class of another module of its package."""

import rclpy
from geometry_msgs.msg import Twist

from .periodic import Periodic


class Walker(Periodic):
    def __init__(self):
        super().__init__("walker", period=0.05)
        self.cmd = self.create_publisher(Twist, "cmd_vel", 10)


def main():
    rclpy.init()
    rclpy.spin(Walker())

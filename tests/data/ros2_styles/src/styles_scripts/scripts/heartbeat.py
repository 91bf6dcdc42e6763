#!/usr/bin/env python3
"""A script with its node at module level, its period a parameter."""

import rclpy
from std_msgs.msg import Empty

if __name__ == "__main__":
    rclpy.init()
    node = rclpy.create_node("heartbeat")
    period = node.declare_parameter("period", 2.0).value
    node.create_publisher(Empty, "pulse", 1)
    node.create_timer(period, lambda: None)
    rclpy.spin(node)

"""Two nodes made in one main, one of them in a namespace."""

import rclpy
from std_msgs.msg import String


def main():
    rclpy.init()
    ping = rclpy.create_node("ping")
    pong = rclpy.create_node("pong", namespace="court")
    ping.create_publisher(String, "ball", 10)
    pong.create_subscription(String, "ball", lambda msg: None, 10)
    ping.create_timer(0.25, lambda: None)
    rclpy.spin(ping)

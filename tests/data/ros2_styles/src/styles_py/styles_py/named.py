"""Topic names from parameters, which a launch file may set."""

import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class Named(Node):
    def __init__(self):
        super().__init__("named")
        self.declare_parameter("out_topic", "status")
        topic = self.get_parameter("out_topic").get_parameter_value().string_value
        self.status = self.create_publisher(String, topic, 10)
        prefix = self.declare_parameter("prefix", "diag").value
        self.diag = self.create_publisher(String, prefix + "/level", 10)


def main():
    rclpy.init()
    rclpy.spin(Named())

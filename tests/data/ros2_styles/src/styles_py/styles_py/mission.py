"""An action server and an action client, beside a plain service."""

import rclpy
from example_interfaces.action import Fibonacci
from example_interfaces.srv import Trigger
from rclpy.action import ActionClient, ActionServer
from rclpy.node import Node


class Mission(Node):
    def __init__(self):
        super().__init__("mission")
        self.goals = ActionServer(self, Fibonacci, "plan", self.execute)
        self.helper = ActionClient(self, Fibonacci, "replan")
        self.abort = self.create_service(Trigger, "abort", self.on_abort)

    def execute(self, goal):
        return Fibonacci.Result()

    def on_abort(self, request, response):
        return response


def main():
    rclpy.init()
    rclpy.spin(Mission())

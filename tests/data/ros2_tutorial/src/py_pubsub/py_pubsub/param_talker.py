# Parameters as in "Using parameters in a class (Python)", with the period a parameter too.
import rclpy
import rclpy.node
from rclpy.qos import qos_profile_sensor_data

from sensor_msgs.msg import Imu

PERIOD_PARAMETER = 'period'


class MinimalParam(rclpy.node.Node):
    def __init__(self):
        super().__init__('minimal_param_node')
        self.declare_parameter('my_parameter', 'world')
        self.declare_parameter(PERIOD_PARAMETER, 0.2)
        self.declare_parameter('topic')
        period = self.get_parameter(PERIOD_PARAMETER).get_parameter_value().double_value
        self.timer = self.create_timer(period, self.timer_callback)
        self.slow_timer = self.create_timer(2 * period, self.timer_callback)
        self.imu = self.create_publisher(Imu, 'imu', qos_profile_sensor_data)
        topic = self.get_parameter('topic').value
        self.dynamic = self.create_publisher(Imu, topic, 10)

    def timer_callback(self):
        my_param = self.get_parameter('my_parameter').get_parameter_value().string_value
        self.get_logger().info('Hello %s!' % my_param)


def main():
    rclpy.init()
    node = MinimalParam()
    rclpy.spin(node)

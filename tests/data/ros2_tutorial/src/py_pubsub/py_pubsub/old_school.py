# The "old school" publisher of the ROS 2 examples: a node made in a function.
import rclpy
from std_msgs.msg import String


def main(args=None):
    rclpy.init(args=args)
    node = rclpy.create_node('minimal_publisher_old_school')
    publisher = node.create_publisher(String, 'topic', 10)
    msg = String()
    i = 0
    while rclpy.ok():
        msg.data = 'Hello World: %d' % i
        i += 1
        publisher.publish(msg)
    node.destroy_node()
    rclpy.shutdown()

from launch import LaunchDescription
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(
            package='py_pubsub',
            executable='talker',
            name='talker',
            namespace='demo',
            remappings=[('topic', 'chatter')],
        ),
        Node(
            package='py_pubsub',
            executable='listener',
            name='listener',
            namespace='demo',
            remappings=[('topic', '/demo/chatter'), ('other', LaunchConfiguration('other'))],
        ),
        Node(
            package='py_pubsub',
            executable='param_talker',
            parameters=[{'period': 0.1, 'topic': 'imu_raw'}],
        ),
        Node(package='py_srvcli', executable='service', name='adder'),
        Node(package='py_srvcli', executable='client'),
        Node(package='turtlesim', executable='turtlesim_node'),
    ])

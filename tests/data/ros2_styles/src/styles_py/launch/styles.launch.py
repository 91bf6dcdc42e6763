from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, GroupAction, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import LifecycleNode, Node, PushRosNamespace


def generate_launch_description():
    robot = LaunchConfiguration("robot")
    relay = Node(package="styles_py", executable="relay", name="imu_relay")
    return LaunchDescription(
        [
            DeclareLaunchArgument("robot", default_value="rover"),
            DeclareLaunchArgument("beat", default_value="0.5"),
            GroupAction(
                [
                    PushRosNamespace(robot),
                    relay,
                    Node(
                        package="styles_scripts",
                        executable="heartbeat.py",
                        parameters=[{"period": LaunchConfiguration("beat")}],
                    ),
                ]
            ),
            Node(package="styles_py", executable="pair", condition=IfCondition("true")),
            IncludeLaunchDescription(PythonLaunchDescriptionSource("more.launch.py")),
            LifecycleNode(package="styles_py", executable="beacon", name="beacon", namespace=""),
            ExecuteProcess(cmd=["ros2", "bag", "record", "-a"]),
            Node(
                package="styles_py",
                executable="named",
                parameters=[{"out_topic": "health", "prefix": "x"}],
            ),
        ]
    )

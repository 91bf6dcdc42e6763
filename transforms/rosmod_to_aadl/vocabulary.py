"""The names the ROSMOD → AADL mapping writes and the library names it refers to.

The properties of ``ROSMOD_Properties`` (``library/properties/ROSMOD_Properties.aadl``) that keep
ROSMOD facts without an AADL counterpart, the standard and ROS property names it sets, the
suffixes of the generated package names, and the classifiers and features of the library's
``ros`` package that generated threads, processes and buses use. The inverse mapping
(:mod:`rosaadl.transforms.aadl_to_rosmod`) reads the same names.
"""

from __future__ import annotations

__all__ = [
    "PROPERTY_SET",
    "NAME",
    "SETTINGS",
    "UNIT_KIND",
    "POSITION",
    "FORMAT_VERSION",
    "PROJECT_PATH",
    "SOFTWARE_NAME",
    "SOURCE_FILE",
    "DEFINITION",
    "SERVICE_TYPE",
    "DATATYPE",
    "SCHEDULING_SCHEME",
    "OPERATION",
    "PERIOD_SECONDS",
    "DEADLINE_SECONDS",
    "LATCHING",
    "SUBNET",
    "NETMASK",
    "IP_ADDRESS",
    "USERNAME",
    "SSH_KEY",
    "DEPLOYMENT_PATH",
    "INSTALL_PATH",
    "OS",
    "SYSTEM_NAME",
    "HOST_REF",
    "ARGUMENTS",
    "COMPONENT_REF",
    "LOGGING",
    "PORT_INSTANCES",
    "MESSAGE_TYPE",
    "TOPIC_NAME",
    "ARCHITECTURE",
    "PERIOD",
    "DEADLINE",
    "PRIORITY",
    "DATA_SIZE",
    "PROCESSOR_BINDING",
    "CONNECTION_BINDING",
    "UNIT_SUFFIXES",
    "CALLBACK_THREADS",
    "SUBSCRIBER_PORT",
    "SERVER_ACCESS",
    "QUEUE_ACCESS",
    "QUEUE_CLASSIFIER",
    "ROS_BUS",
    "NODE_TYPE",
]

#: The property set of the ROSMOD-only facts (``library/properties/ROSMOD_Properties.aadl``).
PROPERTY_SET = "ROSMOD_Properties"

_P = PROPERTY_SET + "::"
NAME = _P + "Name"
SETTINGS = _P + "Settings"
UNIT_KIND = _P + "Unit_Kind"
POSITION = _P + "Position"
FORMAT_VERSION = _P + "Format_Version"
PROJECT_PATH = _P + "Project_Path"
SOFTWARE_NAME = _P + "Software_Name"
SOURCE_FILE = _P + "Source_File"
DEFINITION = _P + "Definition"
SERVICE_TYPE = _P + "Service_Type"
DATATYPE = _P + "Datatype"
SCHEDULING_SCHEME = _P + "Scheduling_Scheme"
OPERATION = _P + "Operation"
PERIOD_SECONDS = _P + "Period_Seconds"
DEADLINE_SECONDS = _P + "Deadline_Seconds"
LATCHING = _P + "Latching"
SUBNET = _P + "Subnet"
NETMASK = _P + "Netmask"
IP_ADDRESS = _P + "IP_Address"
USERNAME = _P + "Username"
SSH_KEY = _P + "SSH_Key"
DEPLOYMENT_PATH = _P + "Deployment_Path"
INSTALL_PATH = _P + "Install_Path"
OS = _P + "OS"
SYSTEM_NAME = _P + "System_Name"
HOST_REF = _P + "Host_Ref"
ARGUMENTS = _P + "Arguments"
COMPONENT_REF = _P + "Component_Ref"
LOGGING = _P + "Logging"
PORT_INSTANCES = _P + "Port_Instances"
MESSAGE_TYPE = "ROS_Properties::Message_Type"
TOPIC_NAME = "ROS_Properties::Topic_Name"
ARCHITECTURE = "Hardware_Properties::Architecture"
PERIOD = "Period"
DEADLINE = "Deadline"
PRIORITY = "Priority"
DATA_SIZE = "Data_Size"
PROCESSOR_BINDING = "Actual_Processor_Binding"
CONNECTION_BINDING = "Actual_Connection_Binding"

#: What the name of a generated package adds to the name of its ROSMOD element, by unit kind.
UNIT_SUFFIXES = {"Project": "_project", "Hardware": "_hardware", "Deployment": "_deployment"}

#: Names of the generated callback thread types (one of each per software package that needs it)
#: and the library thread types they extend.
CALLBACK_THREADS = {
    "timer": ("timer_callback", "ros::timer"),
    "subscriber": ("subscriber_callback", "ros::callback"),
    "server": ("server_callback", "ros::service"),
}
#: Feature names of the library's thread types, and of the callback queue access.
SUBSCRIBER_PORT = "cb_msg"
SERVER_ACCESS = "srv"
QUEUE_ACCESS = "callback_queue"
QUEUE_CLASSIFIER = "ros::callback_queue"
ROS_BUS = "ros::ROSbus.impl"
NODE_TYPE = "ros::node"

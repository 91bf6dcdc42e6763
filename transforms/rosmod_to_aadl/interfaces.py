"""The interface packages: data types and subprograms for the ROS types of packages outside the
project (``std_msgs/String`` → ``std_msgs::String``, ``Unit_Kind => Interfaces``), with the
``Data_Size`` of a standard message of fixed size, else the size measured on a running graph
(the project property ``Data_Size:<pkg/Type>``, :func:`rosaadl.importers.ros_msg.measured_sizes`).
"""

from __future__ import annotations

from pyecore.ecore import EObject

from rosaadl.importers import ros_msg
from rosaadl.transforms.rosmod_to_aadl.rules import State, name_if_changed
from rosaadl.transforms.rosmod_to_aadl.vocabulary import DATA_SIZE, MESSAGE_TYPE, SERVICE_TYPE, UNIT_KIND

__all__ = ["interface_units"]


def interface_units(st: State) -> None:
    """The interface packages of the plan, after the units of the project."""
    f = st.factory
    position = max(st.plan.positions.values(), default=0)
    measured = ros_msg.measured_sizes(st.project)
    for ros_pkg in sorted(st.plan.interfaces):
        iface = st.plan.interfaces[ros_pkg]
        pkg = f.package(iface.unit)
        f.pa(pkg, UNIT_KIND, f.named("Interfaces"))
        name_if_changed(f, pkg, iface.unit, ros_pkg)
        classifiers: list[EObject] = []
        for type_name, name in iface.messages.items():
            data = f.ctype("data", name)
            name_if_changed(f, data, name, type_name.rpartition("/")[2])
            standard = ros_msg.standard_message(type_name)
            size = ros_msg.data_size(standard) if standard is not None else None
            if size is None:
                size = measured.get(type_name)
            if size is not None:
                f.pa(data, DATA_SIZE, f.integer(size, "Bytes"))
            f.pa(data, MESSAGE_TYPE, f.string(type_name))
            classifiers.append(data)
        for type_name, name in iface.services.items():
            subprogram = f.ctype("subprogram", name)
            name_if_changed(f, subprogram, name, type_name.rpartition("/")[2])
            f.pa(subprogram, SERVICE_TYPE, f.string(type_name))
            classifiers.append(subprogram)
        f.add(pkg, "classifiers", *classifiers)
        position += 1
        st.units[position] = pkg

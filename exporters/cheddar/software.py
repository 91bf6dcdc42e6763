"""The software of the instance as Cheddar entities: address spaces, tasks, resources,
buffers and messages, and the dependencies imported from Cheddar.

Processes are address spaces (threads outside any process get one per processor); threads are
tasks of the kind their ``Dispatch_Protocol`` says, on the processor they are bound to; ``data``
with a ``Cheddar_Properties::Data_Role`` is the resource, buffer or message it was read as, and
``data`` with a ``Concurrency_Control_Protocol`` a resource whose critical sections are the whole
execution of the threads that use it. A thread with no ``Compute_Execution_Time`` is left out
(with a warning): Cheddar would have no capacity to schedule.
"""

from __future__ import annotations

from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.exporters.cheddar.context import category_of, component_of, thread_of
from rosaadl.exporters.cheddar.hardware import binding_target, cpu_names
from rosaadl.exporters.cheddar.system import AddressSpace, Collection, Dependency, SharedObject, Task
from rosaadl.importers.cheddar.vocabulary import (
    AADL_TO_RESOURCE_PROTOCOL,
    CCP,
    CET,
    CP,
    DEPENDENCY_ENDS,
    DISPATCH,
    DISPATCH_TO_TASK_TYPE,
    PERIOD,
)
from rosaadl.properties import EnumLiteral, Reference

__all__ = ["space", "task", "task_name", "data_component", "imported_dependency"]


def space(c: Collection, obj: EObject) -> None:
    """A process as an address space, on the processor it (or its threads) is bound to."""
    cpu, _ = cpu_names(c, binding_target(c, obj))
    imported = c.ctx.imported(obj)
    if cpu is None:
        threads = [t for t in model.component_instances(obj) if category_of(t) == "thread"]
        cpus = []
        for thread in threads:
            name, _ = cpu_names(c, binding_target(c, thread))
            if name is not None and name not in cpus:
                cpus.append(name)
        if not cpus:
            if imported:
                c.ctx.problem(obj, "the address space is bound to no processor")
            return
        cpu = cpus[0]
    entity = AddressSpace(c.ctx.name(obj), c.ctx.ident(obj), obj, cpu, imported)
    c.space_of_process[id(obj)] = entity
    c.system.spaces.append(entity)


def _space_for(c: Collection, thread: EObject, cpu: str) -> AddressSpace:
    """The address space of a thread: its process (split by processor when needed)."""
    current = thread.eContainer()
    while current is not None and model.is_a(current, "ComponentInstance"):
        if current.category is not None and current.category.name == "process":
            break
        current = current.eContainer()
    if current is not None and model.is_a(current, "ComponentInstance"):
        space = c.space_of_process.get(id(current))
        if space is not None and (space.cpu == cpu or space.imported):
            return space
        if space is not None:
            key = f"{space.name}_on_{cpu}"
            base = space
        else:
            key = c.ctx.path(current)
            base = None
        made = c.synthetic_spaces.get(key)
        if made is None:
            made = AddressSpace(key, None, None, cpu, False)
            c.synthetic_spaces[key] = made
            c.system.spaces.append(made)
            if base is not None:
                c.ctx.warn(
                    current,
                    f"its threads run on several processors; address space {key!r} holds those on {cpu}",
                )
        return made
    key = f"{cpu}.address_space"
    made = c.synthetic_spaces.get(key)
    if made is None:
        made = AddressSpace(key, None, None, cpu, False)
        c.synthetic_spaces[key] = made
        c.system.spaces.append(made)
    return made


def task(c: Collection, thread: EObject) -> None:
    """A thread as a task (left out, with a warning, when it has no execution time)."""
    props = c.ctx.props(thread)
    imported = c.ctx.imported(thread)
    cpu, core = cpu_names(c, binding_target(c, thread))
    if cpu is None:
        c.ctx.problem(thread, "the thread is bound to no processor (set Actual_Processor_Binding)")
        return
    if core is None:
        own_core = props.get(CP + "Core_Name")
        if isinstance(own_core, str):
            core = own_core
    task_type = props.get(CP + "Task_Type")
    if task_type is None:
        dispatch = props.get(DISPATCH)
        if dispatch is None:
            dispatch = EnumLiteral("Periodic" if props.has(PERIOD) else "Aperiodic")
            c.ctx.warn(thread, f"no Dispatch_Protocol; written as a {str(dispatch).lower()} task")
        task_type = DISPATCH_TO_TASK_TYPE.get(str(dispatch).lower())
        if task_type is None:
            c.ctx.problem(thread, f"Dispatch_Protocol {dispatch} has no Cheddar task kind")
            return
    task_type = str(task_type).upper()
    if imported:
        space_name = None
        container = thread.eContainer()
        if container is not None and id(container) in c.space_of_process:
            space_name = c.space_of_process[id(container)].name
        lost = props.get(CP + "Address_Space_Name")
        if isinstance(lost, str):
            space_name = lost
    else:
        space_name = _space_for(c, thread, cpu).name
        if not props.has(CET):
            # a thread with no execution time (a ROS spinner the profile did not measure) has
            # nothing for Cheddar to schedule: it is left out, and said so
            c.ctx.warn(
                thread,
                "not exported as a task: Compute_Execution_Time is not set, so Cheddar "
                "would have no capacity for it",
            )
            return
        if task_type in ("PERIODIC_TYPE", "SPORADIC_TYPE") and not props.has(PERIOD):
            c.ctx.problem(thread, "Period is not set (a periodic or sporadic task needs one)")
    entity = Task(c.ctx.name(thread), c.ctx.ident(thread), thread, cpu, core, space_name, task_type, imported)
    c.task_of_thread[id(thread)] = entity
    c.system.tasks.append(entity)


def task_name(c: Collection, target: Any) -> str | None:
    """The task name a record field refers to (a thread, or an unresolved name)."""
    if isinstance(target, Reference):
        return target.path
    if isinstance(target, EObject):
        found = c.task_of_thread.get(id(target))
        return found.name if found is not None else c.ctx.name(target)
    return None


def _location_of(c: Collection, data: EObject) -> tuple[str | None, str | None]:
    """(cpu_name, address space name) of an imported resource, buffer or message."""
    props = c.ctx.props(data)
    space_name = None
    cpu = None
    container = data.eContainer()
    if container is not None and id(container) in c.space_of_process:
        space = c.space_of_process[id(container)]
        space_name, cpu = space.name, space.cpu
    lost = props.get(CP + "Address_Space_Name")
    if isinstance(lost, str):
        space_name = lost
    own_cpu = props.get(CP + "Cpu_Name")
    if isinstance(own_cpu, str):
        cpu = own_cpu
    return cpu, space_name


def data_component(c: Collection, data: EObject) -> None:
    """A data component as the resource, buffer or message it stands for (or nothing)."""
    props = c.ctx.props(data)
    role = props.get(CP + "Data_Role")
    role = str(role).lower() if role is not None else None
    if role is None and props.has(CCP):
        role = "resource"
    if role is None:
        return
    imported = c.ctx.imported(data)
    if role == "message":
        entity = SharedObject("message", c.ctx.name(data), c.ctx.ident(data), data, None, None, imported)
        c.shared_of_data[id(data)] = entity
        c.system.messages.append(entity)
        return
    if role == "buffer":
        cpu, space = _location_of(c, data)
        entity = SharedObject("buffer", c.ctx.name(data), c.ctx.ident(data), data, cpu, space, imported)
        c.shared_of_data[id(data)] = entity
        c.system.buffers.append(entity)
        return
    if role != "resource":
        c.ctx.problem(data, f"Cheddar_Properties::Data_Role {role} is not a Cheddar entity")
        return
    protocol = props.get(CP + "Resource_Protocol")
    if protocol is None:
        ccp = props.get(CCP)
        protocol = AADL_TO_RESOURCE_PROTOCOL.get(str(ccp).lower()) if ccp is not None else "NO_PROTOCOL"
        if protocol is None:
            c.ctx.problem(data, f"Concurrency_Control_Protocol {ccp} has no Cheddar protocol")
            return
    if imported:
        cpu, space = _location_of(c, data)
        entity = SharedObject(
            "resource", c.ctx.name(data), c.ctx.ident(data), data, cpu, space, True, str(protocol).upper()
        )
    else:
        entity = _made_resource(c, data, str(protocol).upper())
        if entity is None:
            return
    c.shared_of_data[id(data)] = entity
    c.system.resources.append(entity)


def _made_resource(c: Collection, data: EObject, protocol: str) -> SharedObject | None:
    """A resource for a shared data component: its users hold it for their whole execution."""
    users = _users_of(c, data)
    if not users:
        c.ctx.warn(data, "shared data with Concurrency_Control_Protocol that no thread uses; not written")
        return None
    cpus = {c.task_of_thread[id(u)].cpu for u in users if id(u) in c.task_of_thread}
    if len(cpus) != 1:
        c.ctx.problem(
            data,
            "threads on several processors share it; a Cheddar resource lives on one processor "
            f"({', '.join(sorted(cpus)) or 'none bound'})",
        )
        return None
    cpu = cpus.pop()
    container = data.eContainer()
    space = None
    while container is not None and model.is_a(container, "ComponentInstance"):
        if id(container) in c.space_of_process and c.space_of_process[id(container)].cpu == cpu:
            space = c.space_of_process[id(container)].name
            break
        container = container.eContainer()
    if space is None:
        space = c.task_of_thread[id(users[0])].space
    entity = SharedObject("resource", c.ctx.name(data), None, data, cpu, space, False, protocol)
    for user in users:
        task = c.task_of_thread[id(user)]
        cet = c.ctx.props(user).get(CET)
        end = c.ctx.time_text(user, "Compute_Execution_Time", cet) if cet is not None else None
        if end is None:
            continue
        entity.sections.append((task.name, 1, int(end), None))
    return entity


def _users_of(c: Collection, data: EObject) -> list[EObject]:
    """Threads that access ``data``: through access connections, else those beside it."""
    users: list[EObject] = []
    for connection in c.ctx.connections:
        ends = [connection.source, connection.destination]
        if not any(component_of(e) is data for e in ends if e is not None):
            continue
        for end in ends:
            thread = thread_of(end)
            if thread is not None and thread not in users:
                users.append(thread)
    if not users and data.eContainer() is not None:
        for obj in model.component_instances(data.eContainer()):
            if category_of(obj) == "thread" and obj not in users:
                users.append(obj)
    return [u for u in sorted(users, key=lambda o: c.ctx.order[id(o)]) if id(u) in c.task_of_thread]


def imported_dependency(c: Collection, connection: EObject) -> None:
    """A connection read from a Cheddar dependency, as that dependency again."""
    props = c.ctx.props(connection)
    kind = str(props.get(CP + "Dependency_Type")).upper()
    if kind not in DEPENDENCY_ENDS:
        c.ctx.problem(connection, f"Dependency_Type {kind} is not a Cheddar dependency")
        return
    first_tag, first_kind, orient_tag, second_tag, second_kind, extras = DEPENDENCY_ENDS[kind]
    source, destination = connection.source, connection.destination
    if first_kind == "task" and second_kind == "task":
        src, dst = thread_of(source), thread_of(destination)
        if src is None or dst is None or id(src) not in c.task_of_thread or id(dst) not in c.task_of_thread:
            c.ctx.problem(connection, "a task-to-task dependency must join two exported threads")
            return
        src_name, dst_name = c.task_of_thread[id(src)].name, c.task_of_thread[id(dst)].name
        if kind in ("PRECEDENCE_DEPENDENCY", "TIME_TRIGGERED_COMMUNICATION_DEPENDENCY"):
            first, second = ("task", dst_name), ("task", src_name)
        else:
            first, second = ("task", src_name), ("task", dst_name)
        dependency = Dependency(kind, first, second)
    else:
        thread = thread_of(source) or thread_of(destination)
        thing = component_of(destination if thread_of(source) is not None else source)
        if thread is None or thing is None or id(thread) not in c.task_of_thread:
            c.ctx.problem(connection, "the dependency must join a thread and a data component")
            return
        shared = c.shared_of_data.get(id(thing))
        object_kind = first_kind if first_kind != "task" else second_kind
        if shared is None or shared.kind != object_kind:
            c.ctx.problem(connection, f"the {kind} must join a thread and a {object_kind}")
            return
        task_end = ("task", c.task_of_thread[id(thread)].name)
        thing_end = (object_kind, shared.name)
        first, second = (task_end, thing_end) if first_kind == "task" else (thing_end, task_end)
        orientation = None
        if orient_tag is not None:
            orientation = "FROM_TASK_TO_OBJECT" if thread_of(source) is not None else "FROM_OBJECT_TO_TASK"
        dependency = Dependency(kind, first, second, orientation)
    for tag, prop, _enum in extras:
        value = props.get(prop)
        if value is not None:
            dependency.extras.append((tag, str(value).upper()))
    c.system.dependencies.append(dependency)

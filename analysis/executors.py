"""The executors of an instance: which callbacks each one runs, of which kind, in which order.

A ROS callback is an AADL thread (the library's convention, ``docs/instance-model.md``); the
threads of one executor are grouped here by how the model states its executor:

* a ROSMOD component instance (a thread group whose threads share its ``callback_queue`` data,
  or that carries ``ROSMOD_Properties::Scheduling_Scheme``) is one executor thread taking its
  queue in ``FIFO``, ``PFIFO`` or ``EDF`` order, non-preemptively (the ROSMOD paper, section
  II.A); the scheme defaults to ``FIFO``;
* any other process is one ROS 2 node spun by its own executor:
  ``ROS_Properties::Executor_Kind`` (``Single_Threaded``, ``Multi_Threaded``), default
  ``Multi_Threaded`` as the generated rclpy nodes run (one thread per callback thread, unless
  ``ROS_Properties::Executor_Threads`` says otherwise); ``ROS_Properties::Callback_Group`` names
  a thread's mutually exclusive callback group (default: a group of its own; the callbacks of a
  ROSMOD callback queue share one); ``ROS_Properties::Client_Library`` (``rclpy``, the default,
  or ``rclcpp``) gives the order in which a single-threaded executor runs a snapshot.

The kind of a callback comes from ``ROS_Properties::Thread_Kind``: ``Timer``, ``Publisher`` and
``TF_Broadcaster`` threads are timers; ``Subscriber`` and ``Callback`` threads subscriptions;
``Service`` threads services; ``Main`` and ``Spinner`` threads are the executor itself, not
callbacks. Without a kind, a thread that provides a subprogram access is a service, one that
requires one a client, a periodic thread a timer and any other a subscription.

A callback's ``ROS_Properties::Dispatch_Latency`` (on the thread, else inherited from its process
or a system around it; default 0) is the longest time its executor takes, idle, from the
callback's release to its start; the analysis adds it to the callback's response time.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.instance_values import PropertyReader, SystemMode, bound_processor, category_of
from rosaadl.errors import Diagnostic

__all__ = [
    "CALLBACK_KINDS",
    "KIND_ORDER",
    "Callback",
    "Executor",
    "executors_from_instance",
]

CALLBACK_KINDS = ("timer", "subscription", "service", "client", "waitable")

#: The order in which the single-threaded executor runs the callbacks of one snapshot, per client
#: library: rclpy's ``Executor._wait_for_ready_callbacks`` yields waitables, then per node timers,
#: subscriptions, guard conditions, clients and services; rclcpp's ``get_next_ready_executable``
#: takes timers, subscriptions, services, clients, then waitables.
KIND_ORDER = {
    "rclpy": ("waitable", "timer", "subscription", "client", "service"),
    "rclcpp": ("timer", "subscription", "service", "client", "waitable"),
}

_THREAD_KINDS = {
    "timer": "timer",
    "publisher": "timer",
    "tf_broadcaster": "timer",
    "subscriber": "subscription",
    "callback": "subscription",
    "service": "service",
    "main": "",
    "spinner": "",
}
_US = 1_000_000


@dataclass(frozen=True)
class Callback:
    """One callback: times in microseconds (``period``: its timer period or minimum
    inter-arrival time, None when it has none), ``group`` its mutually exclusive group."""

    path: str
    executor: str
    kind: str
    period: Fraction | None
    wcet: Fraction
    deadline: Fraction | None
    priority: int
    group: str
    order: int  #: registration order inside its executor (model order)
    periodic: bool
    thread: Any = None
    #: minimum inter-arrival times (µs) of further release streams: a subscription fed over
    #: several topics is released by each of them (``executor_analysis`` sets them)
    streams: tuple[Fraction, ...] = ()
    #: release jitter (µs) of each stream, ``period`` first (the response times of the callbacks
    #: whose messages release it; ``executor_analysis`` sets them)
    jitters: tuple[Fraction, ...] = ()
    #: the executor's latency (µs) from its release to its start, idle (``Dispatch_Latency``)
    dispatch_latency: Fraction = Fraction(0)
    #: the model gives its Compute_Execution_Time (else ``wcet`` is 0: the bound is an estimate)
    timed: bool = True


@dataclass(frozen=True)
class Executor:
    """An executor: ``kind`` is ``rosmod``, ``single_threaded`` or ``multi_threaded``; ``scheme``
    the ROSMOD queue order (FIFO, PFIFO, EDF); ``priority`` its OS priority; ``processor`` the
    path of the core it runs on ("" when unbound)."""

    path: str
    kind: str
    scheme: str
    threads: int
    client_library: str
    priority: int
    processor: str
    callbacks: tuple[Callback, ...]

    @property
    def policy(self) -> str:
        """The dispatch rule of :mod:`rosaadl.analysis.executor_simulation`."""
        if self.kind == "rosmod":
            return self.scheme.lower()
        return "polling" if self.kind == "single_threaded" else "multi"

    @property
    def label(self) -> str:
        if self.kind == "rosmod":
            return f"ROSMOD {self.scheme}"
        if self.kind == "single_threaded":
            return f"ROS 2 single-threaded ({self.client_library})"
        plural = "s" if self.threads != 1 else ""
        return f"ROS 2 multi-threaded, {self.threads} thread{plural} ({self.client_library})"

    def rank(self, callback: Callback) -> int:
        """Its place in the dispatch order of a snapshot: kind, then registration."""
        order = KIND_ORDER.get(self.client_library, KIND_ORDER["rclpy"])
        return order.index(callback.kind) * 100_000 + callback.order


def _path(obj: Any) -> str:
    from rosaadl.model import instance_path

    return instance_path(obj)


def _threads(component: Any) -> Iterable[Any]:
    for child in component.componentInstances:
        if category_of(child) == "thread":
            yield child
        elif category_of(child) in ("threadGroup", "thread group"):
            yield from _threads(child)


class _Reader:
    def __init__(self, root: Any, diagnostics: list[Diagnostic], mode: SystemMode | None) -> None:
        self.root = root
        self.props = PropertyReader(diagnostics)
        self.mode = mode

    @staticmethod
    def _nearest(obj: Any, read: Any) -> Any:
        """``read(component)`` of ``obj``, else of the nearest component around it that has it."""
        current = obj
        while current is not None:
            value = read(current)
            if value is not None:
                return value
            current = current.eContainer()
        return None

    def inherited(self, obj: Any, name: str) -> Any:
        return self._nearest(
            obj, lambda c: self.props.enum(c, name, self.mode) or self.props.value(c, name, self.mode)
        )

    def us(self, obj: Any, name: str) -> Fraction | None:
        value = self.props.seconds(obj, name, self.mode)
        return value * _US if value is not None else None

    def inherited_us(self, obj: Any, name: str) -> Fraction | None:
        """``name`` (a time, µs) on ``obj``, else on the nearest component around it that has it."""
        return self._nearest(obj, lambda c: self.us(c, name))

    def kind(self, thread: Any) -> str | None:
        stated = self.props.enum(thread, "ROS_Properties::Thread_Kind", self.mode)
        if stated:
            return _THREAD_KINDS.get(stated.lower(), "subscription") or None
        features = [f for f in thread.featureInstances if "subprogram" in str(getattr(f, "category", ""))]
        for feature in features:
            direction = str(getattr(feature, "direction", "")).lower()
            if "provides" in direction or "provides" in str(getattr(feature, "kind", "")).lower():
                return "service"
            return "client"
        dispatch = (self.props.enum(thread, "Thread_Properties::Dispatch_Protocol", self.mode) or "").lower()
        return "timer" if dispatch == "periodic" else "subscription"

    def queue_of(self, thread: Any) -> Any | None:
        """The ROSMOD component instance whose callback queue the thread takes its jobs from."""
        parent = thread.eContainer()
        if parent is None or category_of(parent) not in ("threadGroup", "thread group"):
            return None
        has_queue = any(category_of(c) == "data" for c in parent.componentInstances)
        scheme = self.inherited(parent, "ROSMOD_Properties::Scheduling_Scheme")
        return parent if has_queue or scheme else None

    def callback(self, thread: Any, executor: str, order: int, group: str) -> Callback | None:
        kind = self.kind(thread)
        if kind is None:
            return None
        wcet = self.us(thread, "Timing_Properties::Compute_Execution_Time")
        timed = wcet is not None
        if wcet is None:
            self.props.report(
                "warning", "callback has no Compute_Execution_Time; its execution counts as 0", thread
            )
            wcet = Fraction(0)
        period = self.us(thread, "Timing_Properties::Period")
        deadline = self.us(thread, "Timing_Properties::Deadline") or period
        priority = self.props.value(thread, "Thread_Properties::Priority", self.mode)
        stated = self.props.value(thread, "ROS_Properties::Callback_Group", self.mode)
        dispatch = (self.props.enum(thread, "Thread_Properties::Dispatch_Protocol", self.mode) or "").lower()
        latency = self.inherited_us(thread, "ROS_Properties::Dispatch_Latency")
        if latency is not None and latency < 0:
            self.props.report("error", "Dispatch_Latency must not be negative; 0 assumed", thread)
            latency = None
        return Callback(
            path=_path(thread),
            executor=executor,
            kind=kind,
            period=period if period and period > 0 else None,
            wcet=wcet,
            deadline=deadline,
            priority=priority if isinstance(priority, int) and not isinstance(priority, bool) else 0,
            group=str(stated) if stated else group,
            order=order,
            periodic=dispatch == "periodic",
            thread=thread,
            dispatch_latency=latency or Fraction(0),
            timed=timed,
        )

    def executor(self, owner: Any, threads: list[Any], rosmod: bool) -> Executor | None:
        path = _path(owner)
        callbacks = []
        for order, thread in enumerate(threads):
            queue = self.queue_of(thread)
            group = _path(queue) if queue is not None else _path(thread)
            callback = self.callback(thread, path, order, group)
            if callback is not None:
                callbacks.append(callback)
        if not callbacks:
            return None
        process = owner
        while process is not None and category_of(process) != "process":
            process = process.eContainer()
        priority = self.props.value(process if process is not None else owner, "Thread_Properties::Priority")
        if not isinstance(priority, int) or isinstance(priority, bool):
            priority = max(c.priority for c in callbacks)
        core = bound_processor(callbacks[0].thread, self.mode, self.props)
        library = str(self.inherited(owner, "ROS_Properties::Client_Library") or "rclpy").lower()
        if rosmod:
            scheme = str(self.inherited(owner, "ROSMOD_Properties::Scheduling_Scheme") or "FIFO").upper()
            if scheme not in ("FIFO", "PFIFO", "EDF"):
                self.props.report("warning", f"unknown scheduling scheme {scheme}; FIFO assumed", owner)
                scheme = "FIFO"
            return Executor(path, "rosmod", scheme, 1, library, priority, _core(core), tuple(callbacks))
        stated = str(self.inherited(owner, "ROS_Properties::Executor_Kind") or "Multi_Threaded").lower()
        kind = (
            "single_threaded"
            if stated.startswith("single") or stated.startswith("static")
            else "multi_threaded"
        )
        count = self.inherited(owner, "ROS_Properties::Executor_Threads")
        threads_n = count if isinstance(count, int) and count > 0 else len(callbacks)
        return Executor(
            path, kind, "", 1 if kind == "single_threaded" else threads_n, library, priority, _core(core),
            tuple(callbacks),
        )  # fmt: skip


def _core(processor: Any) -> str:
    return _path(processor) if processor is not None else ""


def executors_from_instance(
    root: Any, diagnostics: list[Diagnostic], mode: SystemMode | None = None
) -> tuple[Executor, ...]:
    """Every executor of the instance with its callbacks, in model order (see the module doc)."""
    from rosaadl.model import component_instances

    reader = _Reader(root, diagnostics, mode)
    result = []
    for process in component_instances(root):
        if category_of(process) != "process":
            continue
        plain: list[Any] = []
        queues: dict[int, tuple[Any, list[Any]]] = {}
        for thread in _threads(process):
            queue = reader.queue_of(thread)
            if queue is None:
                plain.append(thread)
            else:
                queues.setdefault(id(queue), (queue, []))[1].append(thread)
        for queue, threads in queues.values():
            executor = reader.executor(queue, threads, rosmod=True)
            if executor is not None:
                result.append(executor)
        if plain:
            executor = reader.executor(process, plain, rosmod=False)
            if executor is not None:
                result.append(executor)
    return tuple(result)

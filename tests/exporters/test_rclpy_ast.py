"""The generated node modules, read as Python ASTs: every rclpy call binds to the rclpy API
(humble/jazzy signatures), and every AADL thread and port of the model has its construct."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest
from test_rclpy_models import hostile_instance, services_instance, tracking_instance

from rosaadl import model
from rosaadl.exporters.rclpy import GenerationOptions, generate_workspace, naming
from rosaadl.properties import property_value


# The rclpy API the generated code may use (``Node`` methods and constructors), as in the issue.
def create_publisher(msg_type, topic, qos_profile, *, callback_group=None): ...
def create_subscription(msg_type, topic, callback, qos_profile, *, callback_group=None): ...
def create_timer(timer_period_sec, callback, callback_group=None, clock=None): ...
def create_service(srv_type, srv_name, callback, *, qos_profile=None, callback_group=None): ...
def create_client(srv_type, srv_name, *, qos_profile=None, callback_group=None): ...
def declare_parameter(name, value=None, descriptor=None, ignore_override=False): ...
def qos_profile(*, history=None, depth=None, reliability=None, durability=None): ...
def executor(*, num_threads=None, context=None): ...
def callback_group(): ...


SIGNATURES = {
    "create_publisher": inspect.signature(create_publisher),
    "create_subscription": inspect.signature(create_subscription),
    "create_timer": inspect.signature(create_timer),
    "create_service": inspect.signature(create_service),
    "create_client": inspect.signature(create_client),
    "declare_parameter": inspect.signature(declare_parameter),
    "QoSProfile": inspect.signature(qos_profile),
    "MultiThreadedExecutor": inspect.signature(executor),
    "MutuallyExclusiveCallbackGroup": inspect.signature(callback_group),
    "ReentrantCallbackGroup": inspect.signature(callback_group),
}
QOS_ENUMS = {
    "QoSHistoryPolicy": {"KEEP_LAST", "KEEP_ALL"},
    "QoSReliabilityPolicy": {"RELIABLE", "BEST_EFFORT"},
    "QoSDurabilityPolicy": {"VOLATILE", "TRANSIENT_LOCAL"},
}


def _name(func: ast.expr) -> str:
    if isinstance(func, ast.Attribute):
        return func.attr
    if isinstance(func, ast.Name):
        return func.id
    return ""


def _bind(call: ast.Call):
    signature = SIGNATURES[_name(call.func)]
    assert not any(isinstance(a, ast.Starred) for a in call.args), ast.unparse(call)
    assert all(k.arg is not None for k in call.keywords), ast.unparse(call)
    try:
        return signature.bind(*call.args, **{k.arg: k.value for k in call.keywords})
    except TypeError as exc:
        raise AssertionError(f"{ast.unparse(call)} does not match {signature}: {exc}") from None


def _attr_of(node: ast.expr) -> str | None:
    """``self.x`` → ``x``."""
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self":
        return node.attr
    return None


class Module:
    """What a generated node module creates."""

    def __init__(self, path: Path) -> None:
        self.tree = ast.parse(path.read_text(), str(path))
        self.imports: dict[str, str] = {}
        for node in ast.walk(self.tree):
            if isinstance(node, ast.ImportFrom):
                for alias in node.names:
                    self.imports[alias.asname or alias.name] = f"{node.module}.{alias.name}"
        self.calls = [
            n for n in ast.walk(self.tree) if isinstance(n, ast.Call) and _name(n.func) in SIGNATURES
        ]
        self.assigned: dict[str, ast.Call] = {}
        for node in ast.walk(self.tree):
            if isinstance(node, ast.Assign) and isinstance(node.value, ast.Call):
                for target in node.targets:
                    attr = _attr_of(target)
                    if attr:
                        self.assigned[attr] = node.value
        self.methods = {n.name for n in ast.walk(self.tree) if isinstance(n, ast.FunctionDef)}

    def created(self, kind: str) -> list[inspect.BoundArguments]:
        return [_bind(c) for c in self.calls if _name(c.func) == kind]

    def group_of(self, bound: inspect.BoundArguments) -> str:
        group = _attr_of(bound.arguments["callback_group"])
        assert group and _name(self.assigned[group].func) in (
            "MutuallyExclusiveCallbackGroup",
            "ReentrantCallbackGroup",
        )
        return group


@pytest.fixture(scope="module", params=["tracking", "services", "hostile"])
def generated(request, tmp_path_factory):
    make = {"tracking": tracking_instance, "services": services_instance, "hostile": hostile_instance}[
        request.param
    ]
    ws, instance = make()
    out = tmp_path_factory.mktemp(request.param)
    result = generate_workspace(instance, out, options=GenerationOptions(year=2024))
    return request.param, instance, out, result


def test_every_rclpy_call_matches_the_api(generated):
    _, _, out, result = generated
    modules = [
        out / p for p in result.written if p.endswith(".py") and "/test/" not in p and "launch" not in p
    ]
    assert check_rclpy_calls(modules) > 10


def _threads(process):
    found = []
    stack = list(process.componentInstances)
    while stack:
        child = stack.pop(0)
        if child.category.name == "thread":
            found.append(child)
        elif child.category.name == "threadGroup":
            stack[:0] = list(child.componentInstances)
    return found


def _containers(process):
    found = [process]
    stack = list(process.componentInstances)
    while stack:
        child = stack.pop(0)
        if child.category.name == "threadGroup":
            found.append(child)
            stack[:0] = list(child.componentInstances)
    return found


def _ident(thread, process):
    parts = []
    current = thread
    while current is not process:
        parts.append(current.name)
        current = current.eContainer()
    return naming.identifier("_".join(reversed(parts))) if parts else None


def _ends(instance) -> set[int]:
    ends = set()
    for conn in (o for o in model.walk(instance) if o.eClass.name == "ConnectionInstance"):
        ends.update({id(conn.source), id(conn.destination)})
    return ends


def check_rclpy_calls(paths: list[Path]) -> int:
    """Every rclpy call of the modules binds to the rclpy API; returns how many were checked."""
    checked = 0
    for path in paths:
        module = Module(path)
        for call in module.calls:
            bound = _bind(call)
            checked += 1
            kind = _name(call.func)
            if kind in ("create_publisher", "create_subscription"):
                assert isinstance(bound.arguments["topic"], ast.Constant)
                qos = bound.arguments["qos_profile"]
                assert isinstance(qos, ast.Call) and _name(qos.func) == "QoSProfile"
            if kind == "QoSProfile":
                for key, value in bound.arguments.items():
                    if key == "depth":
                        assert isinstance(value, ast.Constant) and value.value >= 1
                    else:
                        enum = value.value.id if isinstance(value, ast.Attribute) else None
                        assert enum in QOS_ENUMS and value.attr in QOS_ENUMS[enum], ast.unparse(value)
            if kind in ("create_subscription", "create_timer", "create_service"):
                callback = _attr_of(bound.arguments["callback"])
                assert callback in module.methods, f"{callback} is not a method of {path.name}"
            if kind in ("create_publisher", "create_subscription", "create_service", "create_client"):
                type_name = bound.arguments["msg_type" if "msg_type" in bound.arguments else "srv_type"]
                assert isinstance(type_name, ast.Name) and type_name.id in module.imports
            if kind == "create_timer" or "callback_group" in bound.arguments:
                module.group_of(bound)
    return checked


def check_constructs(instance, result, out: Path) -> int:
    """Every AADL thread and port of the processes of ``instance`` has its rclpy construct in the
    generated module of its process; returns how many elements were checked."""
    ends = _ends(instance)
    seen_classes = set()
    checked = 0
    processes = [
        o
        for o in model.walk(instance)
        if o.eClass.name == "ComponentInstance" and o.category.name == "process"
    ]
    for process in processes:
        cls = next(c for c in result.plan.classes if process in c.instances)
        if id(cls) in seen_classes:
            continue
        seen_classes.add(id(cls))
        module = Module(out / cls.package / cls.package / f"{cls.module}.py")
        threads = _threads(process)
        count = ast.literal_eval(
            next(
                n.value
                for n in module.tree.body
                if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "THREAD_COUNT"
            )
        )
        assert count == max(1, len(threads)) and len(module.created("MultiThreadedExecutor")) == 1
        timers = {
            _attr_of(b.arguments["callback"]): module.group_of(b) for b in module.created("create_timer")
        }
        subs = {_attr_of(b.arguments["callback"]): b for b in module.created("create_subscription")}
        pubs = {
            attr: _bind(call)
            for attr, call in module.assigned.items()
            if _name(call.func) == "create_publisher"
        }
        services = {_attr_of(b.arguments["callback"]): b for b in module.created("create_service")}
        clients = {
            attr: _bind(call) for attr, call in module.assigned.items() if _name(call.func) == "create_client"
        }
        owners = [(t, _ident(t, process), True) for t in threads]
        owners += [(c, _ident(c, process) or cls.module, False) for c in _containers(process) if threads]
        if not threads:
            owners = [(process, cls.module, True)]
        groups_by_thread: dict[str, set[str]] = {}
        for owner, ident, is_thread in owners:
            constructs = groups_by_thread.setdefault(ident, set())
            if is_thread and str(property_value(owner, "Dispatch_Protocol")) == "Periodic":
                assert f"on_{ident}" in timers, f"periodic thread {ident} has no timer"
                constructs.add(timers[f"on_{ident}"])
                checked += 1
            for feature in owner.featureInstances:
                if not is_thread and id(feature) not in ends:
                    continue  # a component's port that one of its threads handles
                category = feature.category.name
                base = naming.shorten(f"{ident}_{naming.identifier(feature.name)}")
                if category in ("eventDataPort", "eventPort", "dataPort") and feature.direction.name == "in":
                    assert f"on_{base}" in subs, f"in port {base} has no subscription"
                    bound = subs[f"on_{base}"]
                    constructs.add(module.group_of(bound))
                    _check_message(module, bound.arguments["msg_type"], feature)
                    queue = property_value(feature, "Queue_Size")
                    qos = {k.arg: k.value for k in bound.arguments["qos_profile"].keywords}
                    expected = 1 if category == "dataPort" or queue is None else queue
                    assert qos["depth"].value == expected
                elif category in ("eventDataPort", "eventPort", "dataPort"):
                    assert f"pub_{base}" in pubs, f"out port {base} has no publisher"
                    bound = pubs[f"pub_{base}"]
                    constructs.add(module.group_of(bound))
                    _check_message(module, bound.arguments["msg_type"], feature)
                elif category == "subprogramAccess" and feature.access.name == "provides":
                    assert f"on_{base}" in services, f"provided access {base} has no service"
                    constructs.add(module.group_of(services[f"on_{base}"]))
                elif category == "subprogramAccess":
                    assert f"cli_{base}" in clients, f"required access {base} has no client"
                    constructs.add(module.group_of(clients[f"cli_{base}"]))
                    assert f"call_{base}" in module.methods
                else:
                    continue
                checked += 1
            assert len(constructs) <= 1, f"{ident}: constructs in several callback groups {constructs}"
        plain = [t for t in threads if not any(f.category.name == "dataAccess" for f in t.featureInstances)]
        idents = {_ident(t, process) for t in plain}
        distinct = {next(iter(groups_by_thread[i])) for i in idents if groups_by_thread[i]}
        assert len(distinct) == len([i for i in idents if groups_by_thread[i]])
    return checked


@pytest.mark.parametrize("make", [tracking_instance, services_instance], ids=["tracking", "services"])
def test_every_thread_and_port_has_its_construct(make, tmp_path):
    ws, instance = make()
    result = generate_workspace(instance, tmp_path, options=GenerationOptions(year=2024))
    assert check_constructs(instance, result, tmp_path) >= 6


def _check_message(module: Module, type_node: ast.expr, feature) -> None:
    imported = module.imports[type_node.id]
    declared = property_value(feature, "Message_Type")
    if declared:
        package, _, name = declared.partition("/")
        if package in ("std_msgs", "geometry_msgs", "sensor_msgs", "tf2_msgs", "builtin_interfaces"):
            assert imported == f"{package}.msg.{name}", (imported, declared)
        else:  # a message of the model itself, in the application's interface package
            assert imported.endswith(f".msg.{naming.message_name(name)}"), (imported, declared)
    elif feature.category.name == "eventPort":
        assert imported == "std_msgs.msg.Empty"

"""The deployment solver's longest chain latency objective and its pinned units
(rosaadl.analysis.deployment_links): a chain's latency is its fixed part plus the transmission of
the topics that cross boards; a unit that talks to a device stays on the device's board."""

from __future__ import annotations

from fractions import Fraction

from instance_builders import num, pa, ref
from test_deployment import core, process, thread
from test_deployment_solver import _board, _boards_system, _topic

from rosaadl import model
from rosaadl.analysis.deployment_infeasibility import explain_infeasibility
from rosaadl.analysis.deployment_problem import deployment_problem
from rosaadl.analysis.deployment_proposal import propose_deployment
from rosaadl.analysis.deployment_solver import solve_deployment

new = model.new


def _allowed(unit, target):
    unit.ownedPropertyAssociations.append(pa("Deployment_Properties::Allowed_Processor_Binding", ref(target)))


def _chain_model():
    """a (left) -> b -> c (right): b goes left or right at the same core and bus load; the topic
    a -> b has a 5 ms Latency of its own, so b on the left makes the shorter chain; b is bound on
    the right now (the moves objective would keep it there)."""
    a = process("a", thread("t", 1000, 300))
    b = process("b", thread("t", 1000, 100))
    c = process("c", thread("t", 1000, 300))
    boards = [_board("left", [core("c0")]), _board("right", [core("c0")])]
    root = _boards_system(boards, [a, b, c], bus_kbyteps=10_000)
    _allowed(a, boards[0])
    _allowed(c, boards[1])
    b.ownedPropertyAssociations.append(
        pa("Deployment_Properties::Actual_Processor_Binding", ref(boards[1].componentInstances[0]))
    )
    _topic(root, a, b, 1)  # 1 KByte at 1 kHz either way: 1000 KByte/s on the bus
    _topic(root, b, c, 1)
    root.connectionInstances[0].ownedPropertyAssociations.append(
        pa("Communication_Properties::Latency", num(5, "ms"))
    )
    return root


def test_the_shorter_chain_breaks_a_tie_of_core_and_bus_load():
    problem = deployment_problem(_chain_model())
    (chain,) = problem.chains
    # fixed: the three execution times (subscriptions: no sampling period); each topic across
    # the 10 000 KByte/s bus takes 1 KByte / 10 000 KByte/s = 100 us, a -> b 5 ms more
    assert chain.fixed_us == 700
    assert chain.links == ((0, 1, Fraction(5100)), (1, 2, Fraction(100)))
    outcome = solve_deployment(problem, deterministic=True, time_limit=5)
    best = outcome.best
    assert outcome.status == "optimal"
    assert best.assignment == (0, 0, 1)  # b beside a, one move from its current core
    assert best.evaluation.max_load == Fraction(2, 5) and best.evaluation.bus_kbyteps == 1000
    assert best.evaluation.moves == 1
    latency = {o.name: o for o in best.objectives}["longest_chain_latency"]
    assert latency.value == 800 == latency.bound and latency.gap_percent == 0 and latency.unit == "us"
    # the other binding ties on the first two objectives and has the longer chain
    other = problem.evaluate((0, 1, 1))
    assert (other.max_load, other.bus_kbyteps) == (best.evaluation.max_load, best.evaluation.bus_kbyteps)
    assert other.latency_us == 5800 and other.moves == 0


def _device(name, *ports):
    device = new("ComponentInstance", name=name, category="device")
    for port in ports:
        device.featureInstances.append(port)
    return device


def _wire(root, device, unit):
    """A port connection from a new out port of ``device`` to a new in port of ``unit``'s thread."""
    out = new("FeatureInstance", name="data", feature="data", category="data port", direction="out")
    device.featureInstances.append(out)
    into = new("FeatureInstance", name=device.name, feature=device.name, category="data port", direction="in")
    unit.componentInstances[0].featureInstances.append(into)
    root.connectionInstances.append(
        new(
            "ConnectionInstance",
            name=f"{device.name}->{unit.name}",
            kind="portConnection",
            source=out,
            destination=into,
        )
    )


def test_a_device_driver_is_pinned_to_its_board():
    driver = process("driver", thread("t", 1000, 100))
    other = process("other", thread("t", 1000, 100))
    boards = [_board("left", [core("c0"), core("c1")]), _board("right", [core("c0")])]
    camera = _device("camera")
    boards[1].componentInstances.append(camera)
    root = _boards_system(boards, [driver, other])
    _wire(root, camera, driver)
    _allowed(other, boards[0].componentInstances[1])
    problem = deployment_problem(root)
    assert problem.allowed == [[2], [1]]
    proposal = propose_deployment(problem, deterministic=True, time_limit=2)
    assert proposal.binding() == [
        ("r_i_Instance.driver", "r_i_Instance.right.c0"),
        ("r_i_Instance.other", "r_i_Instance.left.c1"),
    ]
    assert proposal.as_dict()["pins"] == [
        {"path": "r_i_Instance.driver", "to": "r_i_Instance.right", "by": "device r_i_Instance.right.camera"},
        {"path": "r_i_Instance.other", "to": "r_i_Instance.left.c1", "by": "Allowed_Processor_Binding"},
    ]
    text = "\n".join(proposal.text())
    assert "pinned unit" in text and "device right.camera" in text


def test_a_driver_of_devices_on_two_boards_is_explained():
    driver = process("driver", thread("t", 1000, 100))
    boards = [_board("left", [core("c0")]), _board("right", [core("c0")])]
    camera, lidar = _device("camera"), _device("lidar")
    boards[0].componentInstances.append(camera)
    boards[1].componentInstances.append(lidar)
    root = _boards_system(boards, [driver])
    _wire(root, camera, driver)
    _wire(root, lidar, driver)
    problem = deployment_problem(root)
    assert problem.allowed == [[]]
    (reason,) = explain_infeasibility(problem)
    assert reason.constraint == "pinned" and reason.path == "r_i_Instance.driver"
    assert reason.message == (
        "driver is pinned to left by device left.camera and to right by device right.lidar: no core is both"
    )
    proposal = propose_deployment(problem, deterministic=True, time_limit=1)
    assert not proposal.feasible and proposal.as_dict()["explanation"][0]["constraint"] == "pinned"


def test_a_device_outside_every_board_pins_nothing():
    driver = process("driver", thread("t", 1000, 100))
    root = _boards_system([_board("left", [core("c0")]), _board("right", [core("c0")])], [driver])
    sensor = _device("sensor")
    root.componentInstances.append(sensor)
    _wire(root, sensor, driver)
    problem = deployment_problem(root)
    assert problem.allowed == [[0, 1]] and problem.pins == []


def test_thread_granularity_pins_the_threads_behind_a_process_port():
    driver = process("driver", thread("t1", 1000, 100), thread("t2", 1000, 100))
    boards = [_board("left", [core("c0")]), _board("right", [core("c0")])]
    camera = _device("camera")
    boards[0].componentInstances.append(camera)
    root = _boards_system(boards, [driver])
    out = new("FeatureInstance", name="data", feature="data", category="data port", direction="out")
    camera.featureInstances.append(out)
    into = new("FeatureInstance", name="image", feature="image", category="data port", direction="in")
    driver.featureInstances.append(into)
    root.connectionInstances.append(
        new("ConnectionInstance", name="camera->driver", kind="portConnection", source=out, destination=into)
    )
    problem = deployment_problem(root, granularity="thread")
    assert problem.allowed == [[0], [0]]
    assert [(p.unit, p.board) for p in problem.pins] == [(0, "r_i_Instance.left"), (1, "r_i_Instance.left")]

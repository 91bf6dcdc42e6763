"""Executors on small instances: grouping, kinds, ROSMOD queues, ROS 2 kinds, bad values."""

from __future__ import annotations

from fractions import Fraction

from instance_builders import component, num, pa, ref, span

from rosaadl import model
from rosaadl.analysis.executor_analysis import analyze_executors

new = model.new


def enum(name):
    return new("NamedValue", name=name)


def callback(name, period, cet, *, kind=None, dispatch="Periodic", priority=None, deadline=None):
    props = [pa("Thread_Properties::Dispatch_Protocol", enum(dispatch))]
    if period is not None:
        props.append(pa("Timing_Properties::Period", num(period, "us")))
    if cet is not None:
        props.append(pa("Timing_Properties::Compute_Execution_Time", span(cet, cet)))
    if kind:
        props.append(pa("ROS_Properties::Thread_Kind", enum(kind)))
    if priority is not None:
        props.append(pa("Thread_Properties::Priority", new("IntegerValue", value=priority)))
    if deadline is not None:
        props.append(pa("Timing_Properties::Deadline", num(deadline, "us")))
    return component(name, "thread", props=props)


def system(*processes):
    """A system of ``processes`` whose threads are all bound to one processor."""
    cpu = component("cpu", "processor")
    root = new("SystemInstance", name="app_i_Instance", category="system")
    root.componentInstances.append(cpu)
    root.componentInstances.extend(processes)
    for process in processes:
        for ci in model.component_instances(process):
            if (
                ci.componentInstances is not None
                and not ci.componentInstances
                and ci.name not in ("callback_queue",)
            ):
                ci.ownedPropertyAssociations.append(
                    pa("Deployment_Properties::Actual_Processor_Binding", ref(cpu))
                )
    return root


def rosmod_component(scheme):
    """A ROSMOD component instance: a (T=10, C=4, D=10, P=2) and b (T=15, C=5, D=8, P=1) in ms."""
    a = callback("a", 10_000, 4_000, priority=2)
    b = callback("b", 15_000, 5_000, dispatch="Sporadic", priority=1, deadline=8_000)
    props = [pa("ROSMOD_Properties::Scheduling_Scheme", enum(scheme))] if scheme else []
    group = component("comp", "threadGroup", component("callback_queue", "data"), a, b, props=props)
    return component("node", "process", group)


def wcrts(result):
    return {c.path.rpartition(".")[2]: c.wcrt for c in result.callbacks}


def test_rosmod_component_queues_give_the_hand_checked_bounds():
    """The worked example of test_executor_response, in ms here: the blocking by a job that
    started just before is one time unit (1 µs) short of its WCET, hence 8999."""
    expected = {"FIFO": (9000, 9000), "PFIFO": (8999, 9000), "EDF": (9000, 8999), None: (9000, 9000)}
    for scheme, (a, b) in expected.items():
        result = analyze_executors(system(rosmod_component(scheme)))
        (executor,) = result.executors
        assert executor.kind == "rosmod" and executor.scheme == (scheme or "FIFO")
        assert wcrts(result) == {"a": a, "b": b}


def test_unknown_scheme_is_a_located_warning_and_fifo():
    result = analyze_executors(system(rosmod_component("LIFO")))
    assert result.executors[0].scheme == "FIFO"
    assert any(
        "scheduling scheme" in d.message and d.location.path.endswith("comp") for d in result.diagnostics
    )


def test_ros2_node_kinds_order_and_single_threaded_bound():
    timer = callback("tick", 10_000, 2_000, kind="Timer")
    sub = callback("on_msg", 20_000, 3_000, kind="Subscriber", dispatch="Sporadic")
    spinner = callback("spin", 10_000, 1_000, kind="Spinner", dispatch="Sporadic")
    node = component("node", "process", timer, sub, spinner,
                     props=[pa("ROS_Properties::Executor_Kind", enum("Single_Threaded"))])  # fmt: skip
    result = analyze_executors(system(node))
    (executor,) = result.executors
    assert executor.kind == "single_threaded" and executor.threads == 1
    assert [(c.path.rpartition(".")[2], c.kind) for c in executor.callbacks] == [
        ("tick", "timer"), ("on_msg", "subscription"),
    ]  # fmt: skip
    assert wcrts(result) == {"tick": 5000, "on_msg": 5000}
    # the same node, multi-threaded (the default): the busy window, 5 ms for both
    node.ownedPropertyAssociations.clear()
    result = analyze_executors(system(node))
    assert result.executors[0].kind == "multi_threaded"
    assert wcrts(result) == {"tick": 5000, "on_msg": 5000}


def test_an_overloaded_executor_has_no_bound_and_says_so():
    a = callback("a", 10_000, 6_000)
    b = callback("b", 10_000, 6_000)
    result = analyze_executors(system(component("node", "process", a, b)))
    assert wcrts(result) == {"a": None, "b": None}
    assert not result.ok
    assert any("overloaded" in d.message and d.location.path.endswith(".a") for d in result.diagnostics)


def test_a_higher_priority_node_on_the_core_preempts_the_executor():
    low = component("low", "process", callback("a", 10_000, 2_000),
                    props=[pa("Thread_Properties::Priority", new("IntegerValue", value=1))])  # fmt: skip
    high = component("high", "process", callback("h", 7_000, 1_000),
                     props=[pa("Thread_Properties::Priority", new("IntegerValue", value=5))])  # fmt: skip
    result = analyze_executors(system(low, high))
    assert wcrts(result) == {"a": 3000, "h": 1000}
    assert Fraction(3000) == result.callbacks[0].wcrt


def test_an_end_to_end_flow_is_a_chain_with_its_latency_as_deadline():
    """Timer a (T=10 ms, C=2 ms) publishes to subscription b (C=3 ms) of a node of lower priority
    on the same core (so R_b = 3 + 2 = 5 ms): reaction time = data age = T_a + R_a + R_b =
    10 + 2 + 5 = 17 ms, over a 12 ms Latency: an error."""
    out = new("FeatureInstance", name="o", feature="o", category="event data port", direction="out")
    inp = new("FeatureInstance", name="i", feature="i", category="event data port", direction="in")
    a = callback("a", 10_000, 2_000, kind="Timer")
    a.featureInstances.append(out)
    b = callback("b", None, 3_000, kind="Subscriber", dispatch="Sporadic")
    b.featureInstances.append(inp)
    high = [pa("Thread_Properties::Priority", new("IntegerValue", value=5))]
    root = system(component("n1", "process", a, props=high), component("n2", "process", b))
    conn = new(
        "ConnectionInstance", name="n1.a.o -> n2.b.i", kind="portConnection", source=out, destination=inp
    )
    root.connectionInstances.append(conn)
    flow = new("EndToEndFlowInstance", name="e2e", flow="e2e")
    flow.flowElements.extend([a, conn, b])
    flow.ownedPropertyAssociations.append(pa("Communication_Properties::Latency", span(0, 12_000)))
    root.endToEndFlows.append(flow)
    result = analyze_executors(root)
    assert wcrts(result) == {"a": 2000, "b": 5000}  # b's arrivals: one per period of a
    chains = {c.name: c for c in result.chains}
    assert chains["e2e"].reaction_time == chains["e2e"].data_age == 17_000
    assert chains["e2e"].met is False
    assert any("exceeds its Latency 12000 us" in d.message for d in result.diagnostics)
    assert chains["n1.a -> n2.b"].reaction_time == 17_000


def test_a_subscription_fed_by_two_topics_counts_a_message_of_each():
    """Two timers (T = 100 ms, C = 1 ms) of a lower-priority node publish on two connections to
    one subscription (C = 10 ms, no Period) alone in its node: one message of each can arrive
    within 1 ms, and the executor runs them one after the other, so the second completes up to
    20 ms after the first arrived (19 ms after its own arrival). Its arrivals are the two
    publishers' streams together (Casini et al., ECRTS 2019: the move_base case study's
    sensor2mem, fed by /scan and /tF, an OR-join of the two event models), not the faster one's
    period alone, which would claim 10 ms."""
    root = system(
        component("pubs", "process", callback("a1", 100_000, 1_000, kind="Timer"),
                  callback("a2", 100_000, 1_000, kind="Timer")),
        component("node", "process", callback("s", None, 10_000, kind="Subscriber", dispatch="Sporadic"),
                  props=[pa("Thread_Properties::Priority", new("IntegerValue", value=5)),
                         pa("ROS_Properties::Executor_Kind", enum("Single_Threaded"))]),
    )  # fmt: skip
    pubs, node = root.componentInstances[1:]
    inp = new("FeatureInstance", name="i", feature="i", category="event data port", direction="in")
    node.componentInstances[0].featureInstances.append(inp)
    for publisher in pubs.componentInstances:
        out = new("FeatureInstance", name="o", feature="o", category="event data port", direction="out")
        publisher.featureInstances.append(out)
        root.connectionInstances.append(
            new("ConnectionInstance", name=f"{publisher.name}.o -> s.i", kind="portConnection",
                source=out, destination=inp)
        )  # fmt: skip
    assert wcrts(analyze_executors(root))["s"] == 20_000


def two_nodes(publishers, writer, subscriber, props=()):
    """Node ``pub`` (``publishers``) on cpu0 and node ``sub`` (``subscriber``) on cpu1, each with
    ``props``; ``writer`` publishes to ``subscriber`` over one connection."""
    cpus = [component(f"cpu{k}", "processor") for k in range(2)]
    pub = component("pub", "process", *publishers, props=list(props))
    sub = component("sub", "process", subscriber, props=list(props))
    root = new("SystemInstance", name="app_i_Instance", category="system")
    root.componentInstances.extend([*cpus, pub, sub])
    binding = "Deployment_Properties::Actual_Processor_Binding"
    for thread in publishers:
        thread.ownedPropertyAssociations.append(pa(binding, ref(cpus[0])))
    subscriber.ownedPropertyAssociations.append(pa(binding, ref(cpus[1])))
    out = new("FeatureInstance", name="o", feature="o", category="event data port", direction="out")
    inp = new("FeatureInstance", name="i", feature="i", category="event data port", direction="in")
    writer.featureInstances.append(out)
    subscriber.featureInstances.append(inp)
    name = f"pub.{writer.name}.o -> sub.{subscriber.name}.i"
    root.connectionInstances.append(
        new("ConnectionInstance", name=name, kind="portConnection", source=out, destination=inp)
    )
    return root


def test_a_subscription_counts_the_release_jitter_its_publisher_passes_on():
    """Timer p (T = 100 ms, C = 1 ms) shares its node with timer q (C = 60 ms, registered
    before it), so p publishes between 1 and 61 ms after its release; subscription s (C = 50 ms,
    no Period) alone in a node on another core gets p's messages as little as 39 ms apart (at
    61, then 101): a message can wait for the previous one. Its release jitter is p's bound, 61
    (Tindell & Clark's holistic analysis; pyCPA propagates it so in Casini et al.'s artefact):
    ``rbf_s(t) = ceil((t + 61) / 100) * 50`` gives 61 for the job released at 39 behind the one
    at 0, where the publisher's period alone claims 50. The chain p -> s: 100 + 61 + 61."""
    q = callback("q", 100_000, 60_000, kind="Timer")
    p = callback("p", 100_000, 1_000, kind="Timer")
    s = callback("s", None, 50_000, kind="Subscriber", dispatch="Sporadic")
    single = pa("ROS_Properties::Executor_Kind", enum("Single_Threaded"))
    result = analyze_executors(two_nodes([q, p], p, s, [single]))
    assert wcrts(result) == {"q": 61_000, "p": 61_000, "s": 61_000}
    assert {c.name: c.reaction_time for c in result.chains}["pub.p -> sub.s"] == 100_000 + 61_000 + 61_000


def test_a_subscription_of_a_publisher_without_bound_has_none_and_says_why():
    """The publisher's executor is overloaded (two callbacks of 6 ms every 10 ms): the release
    jitter of its subscriber on another core is unknown, so the subscriber has no bound either."""
    a, b = callback("a", 10_000, 6_000, kind="Timer"), callback("b", 10_000, 6_000, kind="Timer")
    s = callback("s", None, 1_000, kind="Subscriber", dispatch="Sporadic")
    result = analyze_executors(two_nodes([a, b], a, s))
    assert wcrts(result) == {"a": None, "b": None, "s": None}
    (why,) = [d for d in result.diagnostics if d.location.path.endswith(".s")]
    assert why.severity == "error" and "whose messages release it has no bound" in why.message


def test_the_dispatch_latency_of_an_executor_adds_to_its_callbacks_and_what_they_release():
    """``ROS_Properties::Dispatch_Latency`` 2 ms on node ``pub`` (inherited by its timer p,
    T = 100 ms, C = 1 ms) and 0.5 ms on subscription s itself (C = 50 ms, another core): p starts
    at most 2 ms after its release, so its bound is 3 ms, and s gets p's messages with a release
    jitter of 3 ms; s's bound is 50 + 0.5. The chain: p's period, then 3 + 50.5."""
    p = callback("p", 100_000, 1_000, kind="Timer")
    s = callback("s", None, 50_000, kind="Subscriber", dispatch="Sporadic")
    s.ownedPropertyAssociations.append(pa("ROS_Properties::Dispatch_Latency", num(500, "us")))
    root = two_nodes([p], p, s)
    pub = next(c for c in root.componentInstances if c.name == "pub")
    pub.ownedPropertyAssociations.append(pa("ROS_Properties::Dispatch_Latency", num(2, "ms")))
    result = analyze_executors(root)
    assert wcrts(result) == {"p": 3_000, "s": 50_500}
    assert {c.name: c.reaction_time for c in result.chains}["pub.p -> sub.s"] == 100_000 + 3_000 + 50_500
    assert not [d for d in result.diagnostics if d.severity == "error"]


def test_a_negative_dispatch_latency_is_a_located_error_and_counts_as_none():
    p = callback("p", 100_000, 1_000, kind="Timer")
    p.ownedPropertyAssociations.append(pa("ROS_Properties::Dispatch_Latency", num(-1, "ms")))
    result = analyze_executors(system(component("node", "process", p)))
    assert wcrts(result) == {"p": 1_000}
    (error,) = [d for d in result.diagnostics if d.severity == "error"]
    assert "Dispatch_Latency" in error.message and error.location.path.endswith("node.p")


def test_a_placement_puts_the_executors_of_processes_on_the_cores_a_run_used():
    """Timers p (pub, cpu0) and q (sub, cpu1) of 10 ms every 100 ms: bound 10 ms each on their
    own cores; placed on one core (as a run on a smaller machine may place them), each executor
    is preempted by the other's (equal OS priority): 20 ms."""
    p = callback("p", 100_000, 10_000, kind="Timer")
    q = callback("q", 100_000, 10_000, kind="Timer")
    root = two_nodes([p], p, q)
    assert wcrts(analyze_executors(root)) == {"p": 10_000, "q": 10_000}
    placement = {"app_i_Instance.pub": "CPU 0", "app_i_Instance.sub": "CPU 0"}
    assert wcrts(analyze_executors(root, placement=placement)) == {"p": 20_000, "q": 20_000}

"""End-to-end latency of thread chains (rosaadl.analysis.latency)."""

from __future__ import annotations

from fractions import Fraction

import pytest
from instance_builders import component, num, pa, ref, span

from rosaadl import model
from rosaadl.analysis.latency import analyze_latency, thread_chains
from rosaadl.analysis.schedulability import analyze_schedulability

new = model.new


def port(name, direction, size=1000):
    fi = new("FeatureInstance", name=name, feature=name, category="event data port", direction=direction)
    fi.ownedPropertyAssociations.append(pa("Memory_Properties::Data_Size", num(size, "Bytes")))
    return fi


def thread(name, period, cet, dispatch="Periodic", priority=None, ports=()):
    props = [
        pa("Timing_Properties::Period", num(period, "us")),
        pa("Thread_Properties::Dispatch_Protocol", new("NamedValue", name=dispatch)),
    ]
    if cet is not None:
        low, high = cet if isinstance(cet, tuple) else (cet, cet)
        props.append(pa("Timing_Properties::Compute_Execution_Time", span(low, high)))
    if priority is not None:
        props.append(pa("Thread_Properties::Priority", new("IntegerValue", value=priority)))
    ci = new("ComponentInstance", name=name, category="thread")
    ci.ownedPropertyAssociations.extend(props)
    ci.featureInstances.extend(ports)
    return ci


def connect(root, src, dst, name, bus=None):
    conn = new("ConnectionInstance", name=name, kind="portConnection", source=src, destination=dst)
    if bus is not None:
        conn.ownedPropertyAssociations.append(
            pa("Deployment_Properties::Actual_Connection_Binding", ref(bus))
        )
    root.connectionInstances.append(conn)
    return conn


def pipeline(bound=True, rta=True):
    """camera (periodic 33333 us) -> tracker (sporadic) -> command (periodic 100000 us), the last hop
    over an Ethernet-like bus of 12 500 KB/s with a 20-byte overhead virtual bus."""
    root = new("SystemInstance", name="app_i_Instance", category="system")
    cam = thread("cam", 33333, (1000, 2000), priority=3, ports=[port("o", "out")])
    trk = thread(
        "trk", 33333, (5000, 10000), "Sporadic", priority=2, ports=[port("i", "in"), port("o", "out")]
    )
    cmd = thread("cmd", 100000, 700, priority=1, ports=[port("i", "in")])
    cpu1 = component("cpu1", "processor")
    cpu2 = component("cpu2", "processor")
    for c in (cpu1, cpu2):
        c.ownedPropertyAssociations.append(
            pa(
                "Deployment_Properties::Scheduling_Protocol",
                new("NamedValue", name="POSIX_1003_HIGHEST_PRIORITY_FIRST_PROTOCOL"),
            )
        )
    net = component("net", "bus", props=[pa("SEI::BandWidthCapacity", num(100, "Mbps"))])
    ros = component("ros", "virtual bus", props=[pa("Memory_Properties::Data_Size", num(20, "Bytes"))])
    ros.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Connection_Binding", ref(net)))
    n1 = component("n1", "process", cam, trk)
    n2 = component("n2", "process", cmd)
    root.componentInstances.extend([cpu1, cpu2, net, ros, n1, n2])
    if rta:
        for t in (cam, trk):
            t.ownedPropertyAssociations.append(
                pa("Deployment_Properties::Actual_Processor_Binding", ref(cpu1))
            )
        cmd.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Processor_Binding", ref(cpu2)))
    connect(root, cam.featureInstances[0], trk.featureInstances[0], "n1.cam.o -> n1.trk.i")
    connect(
        root, trk.featureInstances[1], cmd.featureInstances[0], "n1.trk.o -> n2.cmd.i", ros if bound else None
    )
    return root


def async_chains(result):
    return [c for c in result.chains if c.mode == "async"]


def hop(chain, kind, name):
    return next(h for h in chain.hops if h.kind == kind and h.path.rpartition(".")[2] == name)


def test_chain_found_and_summed():
    root = pipeline()
    result = analyze_latency(root)
    (chain,) = async_chains(result)
    assert [c.mode for c in result.chains] == ["async", "sync"]
    assert chain.threads == ("app_i_Instance.n1.cam", "app_i_Instance.n1.trk", "app_i_Instance.n2.cmd")
    kinds = [(h.kind, h.label, h.worst_method) for h in chain.hops]
    assert kinds == [
        ("sampling", "thread n1.cam", "first sampling"),  # OSATE does not add the initial delay
        ("processing", "thread n1.cam", "response time"),
        ("connection", "connection n1.cam.o -> n1.trk.i", "no sampling/queuing latency"),
        ("processing", "thread n1.trk", "response time"),  # sporadic: no sampling delay
        ("transmission", "bus net", "transmission time"),
        # the virtual bus and the bus are not periodic: the connection may wait for the others
        ("queuing", "protocol ros", "queued"),
        ("sampling", "protocol ros", "sampling protocol/bus"),
        ("queuing", "bus net", "queued"),
        ("sampling", "bus net", "sampling protocol/bus"),
        ("connection", "connection n1.trk.o -> n2.cmd.i", "no sampling/queuing latency"),
        # an event data port is queued, not sampled (OSATE); without a Queue_Size, no delay
        ("processing", "thread n2.cmd", "response time"),
    ]
    # processing: best = min CET, worst = WCRT (cam 2000; trk 10000 + one cam job = 12000; cmd 700)
    # transmission: (1000 + 20 bytes) / 12 500 KB/s = 81.6 us
    transmission = Fraction(1020, 12_500_000) * 1_000_000
    assert chain.best_us == 1000 + 5000 + transmission + 700
    assert chain.worst_us == 2000 + 12000 + transmission + 700
    assert chain.met is None and result.ok


def test_queue_size_of_a_periodic_reader_waits_its_periods():
    """OSATE: an event data port with an assigned Queue_Size waits Queue_Size periods at worst
    for a periodic or sporadic reader, nothing at best with an empty queue (EQ)."""
    root = pipeline()
    cmd = root.componentInstances[5].componentInstances[0]
    cmd.featureInstances[0].ownedPropertyAssociations.append(
        pa("Communication_Properties::Queue_Size", new("IntegerValue", value=2))
    )
    (chain,) = async_chains(analyze_latency(root))
    queued = hop(chain, "queuing", "cmd")
    assert (queued.best_us, queued.worst_us, queued.worst_method) == (0, 200_000, "queued")


def test_worst_case_uses_the_given_schedulability():
    root = pipeline()
    sched = analyze_schedulability(root)
    wcrt = {t.path: t.wcrt for d in sched.domains for t in d.tasks}
    assert wcrt["app_i_Instance.n1.trk"] == 12000
    chain = analyze_latency(root, schedulability=sched).chains[0]
    assert hop(chain, "processing", "trk").worst_us == 12000


def test_without_a_scheduling_domain_the_cet_counts():
    chain = analyze_latency(pipeline(rta=False)).chains[0]
    trk = hop(chain, "processing", "trk")
    assert trk.worst_us == 10000 and trk.worst_method == "processing time"


def test_unbound_connection_transmits_in_no_time():
    chain = analyze_latency(pipeline(bound=False)).chains[0]
    assert [h.kind for h in chain.hops].count("transmission") == 0


def test_explicit_chain_and_flow_with_expected_latency():
    root = pipeline()
    result = analyze_latency(root, [["n1.cam", "n1.trk"]])
    (chain,) = async_chains(result)
    assert chain.name == "n1.cam -> n1.trk" and chain.worst_us == 2000 + 12000
    flow = new("EndToEndFlowInstance", name="track", flow="track")
    conn = root.connectionInstances[1]
    flow.flowElements.extend(
        [root.componentInstances[4].componentInstances[1], conn, root.componentInstances[5]]
    )
    # trk's execution time (10 ms; an end-to-end flow takes no response time from the
    # schedulability analysis) and the transmission exceed 5 ms
    flow.ownedPropertyAssociations.append(pa("Communication_Properties::Latency", span(0, 5, "ms")))
    root.endToEndFlows.append(flow)
    result = analyze_latency(root)
    (chain,) = async_chains(result)
    assert chain.name == "track" and chain.threads[-1] == "app_i_Instance.n2.cmd"
    assert chain.expected_us == 5_000 and chain.met is False
    assert not result.ok and "exceeds its Latency" in result.diagnostics[-1].message


def test_transmission_time_property_wins_over_capacity():
    root = pipeline()
    net = root.componentInstances[2]
    record = new(
        "RecordValue",
        ownedFields=[
            new("FieldValue", name="Fixed", value=span(10, 20)),
            new("FieldValue", name="PerByte", value=span(0.1, 0.2)),
        ],
    )
    net.ownedPropertyAssociations.append(pa("Communication_Properties::Transmission_Time", record))
    hop = [h for h in analyze_latency(root).chains[0].hops if h.kind == "transmission"][0]
    assert hop.best_us == 10 + Fraction(1, 10) * 1020 and hop.worst_us == 20 + Fraction(2, 10) * 1020


def test_chains_of_a_graph():
    root = pipeline()
    extra = thread("log", 50000, 100, ports=[port("i", "in")])
    root.componentInstances[5].componentInstances.append(extra)
    trk = root.componentInstances[4].componentInstances[1]
    connect(root, trk.featureInstances[1], extra.featureInstances[0], "n1.trk.o -> n2.log.i")
    names = [[t.name for t in chain] for chain in thread_chains(root)]
    assert names == [["cam", "trk", "cmd"], ["cam", "trk", "log"]]


@pytest.mark.parametrize(
    ("chain", "text"),
    [(["n1.cam", "nowhere"], "no instance"), (["n1", "n1.trk"], "not a thread")],
)
def test_bad_chains_are_diagnosed(chain, text):
    result = analyze_latency(pipeline(), [chain])
    assert not result.chains and any(text in d.message for d in result.diagnostics)


def test_missing_period_and_cet_are_diagnosed_not_fatal():
    root = pipeline()
    cmd = root.componentInstances[5].componentInstances[0]
    cmd.ownedPropertyAssociations.remove(cmd.ownedPropertyAssociations[0])  # Period
    cmd.ownedPropertyAssociations.remove(cmd.ownedPropertyAssociations[1])  # Compute_Execution_Time
    result = analyze_latency(root)
    found = {(d.severity, d.location.path) for d in result.diagnostics}
    assert ("error", "app_i_Instance.n2.cmd") in found and ("warning", "app_i_Instance.n2.cmd") in found
    assert result.chains[0].worst_us > 0


def test_flow_through_node_processes_is_refined_by_their_threads():
    """A ROS end-to-end flow named at the node (process) level, whose flow specifications have no
    implementation nor Latency, is walked through the threads its topics reach, with their
    response times (OSATE would count the processes as adding nothing)."""
    root = pipeline()
    n1, n2 = root.componentInstances[4], root.componentInstances[5]
    out_spec = new("FlowSpecificationInstance", name="f_out", kind="source")
    in_spec = new("FlowSpecificationInstance", name="f_in", kind="sink")
    n1.flowSpecifications.append(out_spec)
    n2.flowSpecifications.append(in_spec)
    flow = new("EndToEndFlowInstance", name="nodes", flow="nodes")
    flow.flowElements.extend([out_spec, root.connectionInstances[1], in_spec])
    root.endToEndFlows.append(flow)
    (chain,) = async_chains(analyze_latency(root))
    assert chain.threads == ("app_i_Instance.n1.trk", "app_i_Instance.n2.cmd")
    transmission = Fraction(1020, 12_500_000) * 1_000_000
    assert chain.worst_us == 12000 + transmission + 700  # trk's WCRT, the bus, cmd's CET
    assert hop(chain, "processing", "trk").worst_method == "response time"

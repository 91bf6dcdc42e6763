"""OSATE's flow latency rules of today, each on a small instance of its own shape.

The corpus reports (``test_latency_osate``) check the 2014 and 2016-2018 rules; these check
what they do not show: a synchronous round-up over a shared processor, the partition output
delay (``MF``/``PE``), the worst case as deadline (``DL``), a full queue (``FQ``), periodic
protocols and the waiting on a shared bus.
"""

from __future__ import annotations

from fractions import Fraction

import pytest
from instance_builders import component, num, pa, ref, span

from rosaadl import model
from rosaadl.analysis.latency import LatencyPreferences, analyze_latency
from rosaadl.analysis.latency.totals import round_up, round_up_diff

new = model.new


def port(name, direction, category="data port"):
    return new("FeatureInstance", name=name, feature=name, category=category, direction=direction)


def thread(name, period_ms, cet_ms, *ports, deadline_ms=None, dispatch="Periodic"):
    props = [
        pa("Timing_Properties::Period", num(period_ms, "ms")),
        pa("Thread_Properties::Dispatch_Protocol", new("NamedValue", name=dispatch)),
        pa("Timing_Properties::Compute_Execution_Time", span(cet_ms[0], cet_ms[1], "ms")),
    ]
    if deadline_ms is not None:
        props.append(pa("Timing_Properties::Deadline", num(deadline_ms, "ms")))
    ci = component(name, "thread", props=props)
    ci.featureInstances.extend(ports)
    return ci


def flow_system(bind=None, receiver_ports=None, sender_period=15, **receiver):
    """a (periodic 15 ms, 1..2 ms) -> b (periodic 50 ms, 3..4 ms) over one data port connection,
    as an end-to-end flow; ``bind(root, a, b, conn)`` adds bindings."""
    root = new("SystemInstance", name="s_i_Instance", category="system", classifier="p::s.i")
    a = thread("a", sender_period, (1, 2), port("o", "out"))
    b = thread("b", receiver.pop("period", 50), (3, 4), *(receiver_ports or [port("i", "in")]), **receiver)
    root.componentInstances.extend([a, b])
    conn = new("ConnectionInstance", name="a.o -> b.i", kind="portConnection")
    conn.source, conn.destination = a.featureInstances[0], b.featureInstances[0]
    root.connectionInstances.append(conn)
    flow = new("EndToEndFlowInstance", name="f", flow="f")
    flow.flowElements.extend([a, conn, b])
    root.endToEndFlows.append(flow)
    if bind is not None:
        bind(root, a, b, conn)
    return root


def chain(result, mode):
    return next(c for c in result.chains if c.mode == mode)


def test_round_up_helpers():
    assert round_up(Fraction(7), Fraction(50)) == 50 and round_up(Fraction(0), Fraction(50)) == 50
    assert round_up_diff(Fraction(7), Fraction(50)) == 43 and round_up_diff(Fraction(0), Fraction(50)) == 50
    assert round_up_diff(Fraction(100), Fraction(50)) == 0
    # the end of a 10 ms window in a 50 ms frame: 3 ms in -> 7 ms; 12 ms in -> next frame's window end
    assert round_up_diff(Fraction(3), Fraction(50), Fraction(10)) == 7
    assert round_up_diff(Fraction(12), Fraction(50), Fraction(10)) == 58


def test_sampling_async_adds_the_period_to_the_worst_case_only():
    asynchronous = chain(analyze_latency(flow_system()), "async")
    assert (asynchronous.best_us, asynchronous.worst_us) == (1000 + 3000, 2000 + 50_000 + 4000)
    # b's period (50) is a multiple of a's (10): OSATE samples at a's period (under-sampling)
    under = chain(analyze_latency(flow_system(sender_period=10)), "async")
    sampling = next(h for h in under.hops if h.worst_method == "sampling")
    assert sampling.worst_us == 10_000 and under.worst_us == 2000 + 10_000 + 4000


def test_synchronous_system_rounds_up_to_the_period():
    result = analyze_latency(flow_system(period=40))
    synchronous = chain(result, "sync")
    # unbound threads: the connection's clock is unknown, so a synchronous system rounds up:
    # 2 ms since a's dispatch, up to b's period 40 ms -> 38 ms at worst, 0 at best
    assert (synchronous.best_us, synchronous.worst_us) == (1000 + 3000, 2000 + 38_000 + 4000)
    assert chain(result, "async").worst_us == 2000 + 40_000 + 4000


def test_same_processor_is_synchronous_in_both_kinds():
    def bind(root, a, b, conn):
        cpu = component("cpu", "processor")
        root.componentInstances.append(cpu)
        for t in (a, b):
            t.ownedPropertyAssociations.append(
                pa("Deployment_Properties::Actual_Processor_Binding", ref(cpu))
            )

    result = analyze_latency(flow_system(bind, period=40))
    assert chain(result, "async").worst_us == chain(result, "sync").worst_us == 2000 + 38_000 + 4000


def test_worst_case_as_deadline():
    root = flow_system(deadline_ms=6)
    et = chain(analyze_latency(root), "async")
    dl = chain(analyze_latency(root, preferences=LatencyPreferences(worst_case_deadline=True)), "async")
    assert dl.worst_us - et.worst_us == 6000 - 4000
    assert [h.worst_method for h in dl.hops if h.label == "thread b"][-1] == "deadline"


@pytest.mark.parametrize(("empty", "best"), [(True, 0), (False, 3 * 50_000)])
def test_queue_best_case_empty_or_full(empty, best):
    queue = port("i", "in", "event data port")
    queue.ownedPropertyAssociations.append(
        pa("Communication_Properties::Queue_Size", new("IntegerValue", value=3))
    )
    root = flow_system(receiver_ports=[queue], dispatch="Sporadic")
    result = analyze_latency(root, preferences=LatencyPreferences(best_case_empty_queue=empty))
    queued = next(h for h in chain(result, "async").hops if h.kind == "queuing")
    assert (queued.best_us, queued.worst_us) == (best, 3 * 50_000)


def _partitions(major_frame_ms=20):
    def bind(root, a, b, conn):
        p1 = component("p1", "virtual processor")
        p2 = component("p2", "virtual processor")
        cpu = component("cpu", "processor", p1, p2)
        windows = new(
            "ListValue",
            ownedItems=[
                new(
                    "RecordValue",
                    ownedFields=[
                        new(
                            "FieldValue",
                            name="Partition",
                            value=new("InstanceReferenceValue", referencedInstanceObject=p),
                        ),
                        new("FieldValue", name="Duration", value=num(5, "ms")),
                    ],
                )
                for p in (p1, p2)
            ],
        )
        cpu.ownedPropertyAssociations.append(pa("ARINC653::Module_Major_Frame", num(major_frame_ms, "ms")))
        cpu.ownedPropertyAssociations.append(pa("ARINC653::Module_Schedule", windows))
        root.componentInstances.append(cpu)
        a.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Processor_Binding", ref(p1)))
        b.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Processor_Binding", ref(p2)))

    return bind


def test_partition_output_at_major_frame_or_partition_end():
    root = flow_system(_partitions())
    major = chain(analyze_latency(root), "async")
    end = chain(analyze_latency(root, preferences=LatencyPreferences(major_frame=False)), "async")
    kinds = [h.kind for h in major.hops]
    assert "partition output" in kinds and kinds.count("partition") == 1
    out_mf = next(h for h in major.hops if h.kind == "partition output")
    out_pe = next(h for h in end.hops if h.kind == "partition output")
    # a's output (2 ms at worst) leaves at the next major frame (20 ms) or at its window's end (5 ms)
    assert out_mf.worst_us == 18_000 and out_pe.worst_us == 3_000
    # OSATE's word names the preference (LatencyContributor.mapMethodToString, since 2014-09)
    assert out_mf.worst_method == "partition output (MF)"
    assert out_pe.worst_method == "partition output (PE)"


def test_periodic_protocol_samples_and_shared_bus_waits():
    def bind(root, a, b, conn):
        bus = component("net", "bus")
        bus.ownedPropertyAssociations.append(pa("Communication_Properties::Latency", span(1, 2, "ms")))
        vb = component("tdma", "virtual bus", props=[pa("Timing_Properties::Period", num(5, "ms"))])
        vb.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Connection_Binding", ref(bus)))
        root.componentInstances.extend([bus, vb])
        conn.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Connection_Binding", ref(vb)))

    result = analyze_latency(flow_system(bind))
    hops = chain(result, "async").hops
    under = [(h.label, h.kind, h.worst_method, h.worst_us) for h in hops if h.depth]
    assert ("protocol tdma", "sampling", "sampling protocol/bus", 5000) in under  # its period at worst
    assert ("bus net", "transmission", "specified", 2000) in under  # no Transmission_Time: its Latency
    assert ("bus net", "queuing", "queued", 0) in under  # the only connection on the bus
    connection = next(h for h in hops if h.kind == "connection")
    assert connection.worst_us == 5000 + 2000


def test_bad_bindings_do_not_crash():
    def bind(root, a, b, conn):
        v1 = component("v1", "virtual bus")
        v2 = component("v2", "virtual bus")
        v1.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Connection_Binding", ref(v2)))
        v2.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Connection_Binding", ref(v1)))
        v1.ownedPropertyAssociations.append(pa("Communication_Properties::Transmission_Time", num(3, "ms")))
        root.componentInstances.extend([v1, v2])
        conn.ownedPropertyAssociations.append(pa("Deployment_Properties::Actual_Connection_Binding", ref(v1)))

    result = analyze_latency(flow_system(bind))
    assert any("cycle" in d.message for d in result.diagnostics)
    assert chain(result, "async").worst_us > 0


def test_unknown_revision_is_refused():
    from rosaadl.errors import ModelError

    with pytest.raises(ModelError, match="revision"):
        LatencyPreferences(revision="1999")
    assert LatencyPreferences().code(True) == "SS-MF-ET-EQ"
    prefs, synchronous = LatencyPreferences.from_code("as-pe-dl-fq")
    assert (prefs.code(synchronous), synchronous) == ("AS-PE-DL-FQ", False)

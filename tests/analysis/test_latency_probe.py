"""OSATE's flow latency rules on forms of models its own tests exercise and the corpus reports
do not: each test reads a small AADL model of its own, instantiates it and checks the rows and
totals OSATE's ``FlowLatencyAnalysisSwitch`` gives (the rule is named in each test).
"""

from __future__ import annotations

import pytest

from rosaadl.analysis.latency import LatencyPreferences, analyze_latency
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.aadl_text.reading import library_files
from rosaadl.transforms.instantiate import instantiate

_DL = LatencyPreferences(worst_case_deadline=True)
#: the predeclared property sets (their default values matter here), without the rest of the library
_PREDECLARED = {
    "AADL_Project",
    "Communication_Properties",
    "Deployment_Properties",
    "Memory_Properties",
    "Modeling_Properties",
    "Programming_Properties",
    "Thread_Properties",
    "Timing_Properties",
}


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    """Every model of this module, read once with the predeclared property sets."""
    folder = tmp_path_factory.mktemp("latency_probe")
    for name, text in _models().items():
        (folder / f"{name}.aadl").write_text(text, encoding="utf-8")
    files = sorted(folder.glob("*.aadl")) + [f for f in library_files() if f.stem in _PREDECLARED]
    return read_files(files, include_library=False)


def _flow(workspace, root: str, name: str, preferences: LatencyPreferences = _DL, mode: str = "async"):
    system = instantiate(workspace, root)
    return analyze_latency(system, preferences=preferences).chain(name, mode)


def _rows(chain):
    return [(h.depth, h.kind, h.best_us, h.worst_us, h.best_method, h.worst_method) for h in chain.hops]


#: one emitter and one receiver, linked in three ways: over a processor, over a bus whose
#: transmission time is negative, into a partition that has a window but no period
_LINKS = """
package Links
public
  abstract emitter
    features o: out feature;
    flows src: flow source o {Latency => 1 ms .. 2 ms;};
  end emitter;
  abstract receiver
    features i: in feature;
    flows snk: flow sink i {Latency => 1 ms .. 2 ms;};
  end receiver;
  system top
  end top;
  system implementation top.common
    subcomponents
      e: abstract emitter;
      r: abstract receiver;
    connections
      link: feature e.o -> r.i;
    flows
      path: end to end flow e.src -> link -> r.snk;
  end top.common;
  system implementation top.carried extends top.common
    subcomponents
      board: processor {Latency => 4 ms .. 6 ms;};
    properties
      Actual_Connection_Binding => (reference (board)) applies to link;
  end top.carried;
  system implementation top.backwards extends top.common
    subcomponents
      wire: bus {Transmission_Time => [Fixed => -4 ms .. -3 ms;];};
    properties
      Actual_Connection_Binding => (reference (wire)) applies to link;
  end top.backwards;
  system implementation top.window extends top.common
    subcomponents
      slot: virtual processor {Execution_Time => 8 ms;};
    properties
      Actual_Processor_Binding => (reference (slot)) applies to r;
  end top.window;
end Links;
"""


def test_connection_bound_to_a_processor_adds_its_latency(workspace):
    """``processActualConnectionBindingsTransmission`` takes every target of
    ``Actual_Connection_Binding``, not only buses: a processor carrying the message adds its
    ``Latency`` (*specified*), then waits (*queued*) and samples (*sampling protocol/bus*) as an
    aperiodic bus does."""
    chain = _flow(workspace, "Links::top.carried", "path")
    assert _rows(chain)[1:4] == [
        (1, "transmission", 4000, 6000, "specified", "specified"),
        (1, "queuing", 0, 0, "queued", "queued"),
        (1, "sampling", 0, 0, "sampling protocol/bus", "sampling protocol/bus"),
    ]
    assert _rows(chain)[4][:4] == (0, "connection", 4000, 6000)
    assert (chain.best_us, chain.worst_us) == (6000, 10000)


def test_negative_transmission_time_gives_an_unknown_row(workspace):
    """``processTransmissionTime``: a bus whose transfer time is not 0 gets a row; a negative one
    adds nothing and its method is unknown (*no sampling/queuing latency*), not *specified*."""
    chain = _flow(workspace, "Links::top.backwards", "path")
    bus = next(h for h in chain.hops if h.kind == "transmission")
    unknown = "no sampling/queuing latency"
    assert (bus.best_us, bus.worst_us, bus.best_method, bus.worst_method) == (0, 0, unknown, unknown)
    assert (chain.best_us, chain.worst_us) == (2000, 4000)


def test_partition_without_period_repeats_after_its_duration(workspace):
    """``mapConnectionInstance``: a partition the flow enters, with a window duration but neither
    a major frame nor a period, samples at its duration ("No partition period. Using partition
    duration"): the worst case waits a whole window."""
    chain = _flow(workspace, "Links::top.window", "path")
    entered = next(h for h in chain.hops if h.kind == "partition")
    assert (entered.best_us, entered.worst_us, entered.worst_method) == (0, 8000, "partition offset")
    assert "No partition period. Using partition duration" in entered.note
    assert (chain.best_us, chain.worst_us) == (2000, 12000)


_DEFAULTED = """
package Defaulted
public
  thread sensor
    features o: out data port;
    flows src: flow source o;
    properties Period => 10 ms;
  end sensor;
  thread filter
    features i: in data port; o: out data port;
    flows through: flow path i -> o;
    properties Period => 20 ms; Compute_Execution_Time => 2 ms .. 4 ms;
  end filter;
  thread actuator
    features i: in data port;
    flows snk: flow sink i;
    properties Period => 20 ms; Deadline => 20 ms; Compute_Execution_Time => 1 ms .. 3 ms;
  end actuator;
  process loop
  end loop;
  process implementation loop.i
    subcomponents
      s: thread sensor;
      f: thread filter;
      a: thread actuator;
    connections
      c1: port s.o -> f.i;
      c2: port f.o -> a.i;
    flows
      path: end to end flow s.src -> c1 -> f.through -> c2 -> a.snk;
  end loop.i;
  abstract mailbox
    features i: in event port {Queue_Size => 1;};
    flows snk: flow sink i {Latency => 1 ms .. 2 ms;};
    properties Dispatch_Protocol => Sporadic; Period => 10 ms;
  end mailbox;
  abstract poster
    features o: out event port;
    flows src: flow source o {Latency => 1 ms .. 1 ms;};
  end poster;
  system top
  end top;
  system implementation top.i
    subcomponents
      p: abstract poster;
      m: abstract mailbox;
    connections
      c: port p.o -> m.i;
    flows
      post: end to end flow p.src -> c -> m.snk;
  end top.i;
end Defaulted;
"""


def test_deadline_defaulted_to_the_period_is_not_assigned(workspace):
    """``isAssignedDeadline``: under ``DL`` only a ``Deadline`` an association gives replaces the
    execution time; the default (the period) does not (the filter takes its 4 ms execution
    time, "Using execution time as deadline was not set"), an explicit one equal to the period
    does (the actuator's 20 ms), and with neither execution time nor flow latency the default
    deadline is the worst case (the sensor's 10 ms)."""
    chain = _flow(workspace, "Defaulted::loop.i", "path")
    processing = [(h.label, h.worst_us, h.worst_method) for h in chain.hops if h.kind == "processing"]
    assert processing == [
        ("thread s", 10000, "deadline"),
        ("thread f", 4000, "processing time"),
        ("thread a", 20000, "deadline"),
    ]
    assert (chain.best_us, chain.worst_us) == (3000, 64000)
    with_et = _flow(workspace, "Defaulted::loop.i", "path", LatencyPreferences())
    assert [h.worst_us for h in with_et.hops if h.kind == "processing"] == [10000, 4000, 3000]


def test_queue_size_of_one_assigned_is_a_queue(workspace):
    """``hasAssignedPropertyValue(Queue_Size)``: an event port given ``Queue_Size => 1`` queues
    one message of a sporadic receiver: ``1 × Period`` at worst, 0 with an empty queue (``EQ``),
    the period with a full one (``FQ``)."""
    chain = _flow(workspace, "Defaulted::top.i", "post")
    (queued,) = [h for h in chain.hops if h.kind == "queuing"]
    assert (queued.best_us, queued.worst_us, queued.worst_method) == (0, 10000, "queued")
    assert (chain.best_us, chain.worst_us) == (2000, 13000)
    full = _flow(workspace, "Defaulted::top.i", "post", LatencyPreferences(best_case_empty_queue=False))
    assert (full.best_us, full.worst_us) == (12000, 13000)


_SCALED = """
package Scaled
public
  processor slow
    properties Processor_Capacity => 100.0 MIPS;
  end slow;
  processor fast
    properties Processor_Capacity => 500.0 MIPS;
  end fast;
  thread worker
    features i: in event port; o: out event port;
    flows through: flow path i -> o;
    properties
      Dispatch_Protocol => Sporadic;
      Period => 50 ms;
      Compute_Execution_Time => 10 ms .. 20 ms;
  end worker;
  process app
    features i: in event port; o: out event port;
    properties Reference_Processor => classifier (Scaled::slow);
  end app;
  process implementation app.i
    subcomponents
      first: thread worker;
      second: thread worker;
    connections
      c0: port i -> first.i;
      c1: port first.o -> second.i;
      c2: port second.o -> o;
    flows
      chain: end to end flow first.through -> c1 -> second.through;
  end app.i;
  system top
  end top;
  system implementation top.i
    subcomponents
      a: process app.i;
      cpu: processor fast;
    properties
      Actual_Processor_Binding => (reference (cpu)) applies to a;
  end top.i;
end Scaled;
"""


def test_execution_time_scales_to_the_bound_processor(workspace):
    """``AnalysisUtils.scaleTimeRange``: execution times written for the ``Reference_Processor``
    (100 MIPS) take ``100 / 500`` of their value on the 500 MIPS processor the threads run on."""
    chain = _flow(workspace, "Scaled::top.i", "a.chain", LatencyPreferences())
    processing = [(h.best_us, h.worst_us, h.worst_method) for h in chain.hops if h.kind == "processing"]
    assert processing == [(2000, 4000, "processing time"), (2000, 4000, "processing time")]


_WRAPPED = """
package Wrapped
public
  data msg
    properties Data_Size => 100 Bytes;
  end msg;
  virtual bus frame
    properties Data_Size => 20 Bytes; Latency => 1 ms .. 1 ms; Period => 10 ms;
  end frame;
  virtual bus secure
    properties
      Required_Virtual_Bus_Class => (classifier (Wrapped::frame));
      Data_Size => 30 Bytes;
      Transmission_Time => [Fixed => 1 ms .. 1 ms; PerByte => 0.01 ms .. 0.01 ms;];
  end secure;
  bus wire
    properties Transmission_Time => [Fixed => 0 ms .. 0 ms; PerByte => 0.02 ms .. 0.02 ms;];
  end wire;
  abstract sender
    features o: out data port msg;
    flows src: flow source o {Latency => 1 ms .. 1 ms;};
  end sender;
  abstract listener
    features i: in data port msg;
    flows snk: flow sink i {Latency => 1 ms .. 1 ms;};
  end listener;
  system top
  end top;
  system implementation top.i
    subcomponents
      s: abstract sender;
      l: abstract listener;
      net: bus wire;
    connections
      bound: port s.o -> l.i {
        Required_Virtual_Bus_Class => (classifier (Wrapped::secure));
        Actual_Connection_Binding => (reference (net));
      };
      loose: port s.o -> l.i {Required_Virtual_Bus_Class => (classifier (Wrapped::secure));};
    flows
      over_net: end to end flow s.src -> bound -> l.snk;
      unbound: end to end flow s.src -> loose -> l.snk;
  end top.i;
end Wrapped;
"""


def test_required_protocols_wrap_the_message(workspace):
    """``processActualConnectionBindings*`` and ``computeTotalDataSize``: the protocols a
    connection requires by classifier (``secure``, which requires ``frame``) sample when
    periodic, transmit the message wrapped in the protocols above them (secure: 1 ms + 130 bytes
    × 0.01 ms), and the bus carries the message with every overhead (150 bytes × 0.02 ms); a
    connection bound to nothing transmits nothing, but samples."""
    chain = _flow(workspace, "Wrapped::top.i", "over_net", LatencyPreferences())
    under = [(h.label, h.best_us, h.worst_us, h.worst_method) for h in chain.hops if h.depth == 1]
    assert under == [
        ("protocol Wrapped::frame", 0, 10000, "sampling protocol/bus"),
        ("protocol Wrapped::frame", 0, 0, "queued"),
        ("protocol Wrapped::secure", 2300, 2300, "transmission time"),
        ("protocol Wrapped::frame", 1000, 1000, "specified"),
        ("bus net", 3000, 3000, "transmission time"),
        ("bus net", 0, 0, "queued"),
        ("bus net", 0, 0, "sampling protocol/bus"),
    ]
    assert (chain.best_us, chain.worst_us) == (8300, 18300)
    loose = _flow(workspace, "Wrapped::top.i", "unbound", LatencyPreferences())
    assert [h.worst_method for h in loose.hops if h.depth == 1] == ["sampling protocol/bus", "queued"]
    assert (loose.best_us, loose.worst_us) == (2000, 12000)


_MODAL = """
package Modal
public
  with Links;
  system top
    modes
      normal: initial mode;
      degraded: mode;
  end top;
  system implementation top.i
    subcomponents
      cam: abstract Links::emitter;
      screen: abstract Links::receiver;
    connections
      live: feature cam.o -> screen.i in modes (normal);
      still: feature cam.o -> screen.i;
    flows
      video: end to end flow cam.src -> live -> screen.snk;
      snapshot: end to end flow cam.src -> still -> screen.snk in modes (degraded);
  end top.i;
end Modal;
"""


def test_flows_exist_in_the_modes_of_their_declaration_and_elements(workspace):
    """OSATE instantiates an end-to-end flow in the system operation modes where its declaration
    is (``in modes``) and all its elements are: the video over a connection of the normal mode
    only, the snapshot in the degraded mode only."""
    from rosaadl.analysis.instance_values import system_modes

    system = instantiate(workspace, "Modal::top.i")
    current = {som.name: som.modes[0].name for som in system_modes(system)}
    result = analyze_latency(system)
    found = sorted((c.name, current[c.system_mode]) for c in result.chains if c.mode == "async")
    assert found == [("snapshot", "degraded"), ("video", "normal")]


_NO_DEADLINE = """
package Undated
public
  thread ticker
    features o: out data port;
    flows src: flow source o;
  end ticker;
  thread logger
    features i: in data port;
    flows snk: flow sink i {Latency => 0 ms .. 0 ms;};
  end logger;
  process pair
  end pair;
  process implementation pair.i
    subcomponents
      t: thread ticker {Period => 40 ms;};
      l: thread logger {Period => 40 ms;};
    connections
      c: port t.o -> l.i {Timing => Delayed;};
    flows
      tick: end to end flow t.src -> c -> l.snk;
  end pair.i;
end Undated;
"""


def test_a_model_without_any_deadline_takes_the_default(tmp_path):
    """``mapComponentInstance``: with neither execution time nor flow latency, the worst case is
    the ``Deadline``, whose default is the ``Period`` ("Using deadline as execution time was not
    set"), also in a model that associates ``Deadline`` nowhere (its instances carry none)."""
    (tmp_path / "Undated.aadl").write_text(_NO_DEADLINE, encoding="utf-8")
    files = [tmp_path / "Undated.aadl"] + [f for f in library_files() if f.stem in _PREDECLARED]
    chain = _flow(read_files(files, include_library=False), "Undated::pair.i", "tick", LatencyPreferences())
    processing = [(h.label, h.worst_us, h.worst_method) for h in chain.hops if h.kind == "processing"]
    assert processing == [("thread t", 40000, "deadline"), ("thread l", 40000, "deadline")]
    assert (chain.best_us, chain.worst_us) == (40000, 120000)


def test_a_model_without_flows_says_so(workspace):
    """``FlowLatencyAnalysisSwitch.invoke``: "No end-to-end flow instances were found" (OSATE's
    error; a warning here) for a model with neither end-to-end flows nor topic chains."""
    system = instantiate(workspace, "Links::top.common")
    system.endToEndFlows.clear()
    result = analyze_latency(system)
    assert result.chains == ()
    assert [(d.severity, d.message) for d in result.diagnostics] == [
        ("warning", "No end-to-end flow instances were found")
    ]


def _models() -> dict[str, str]:
    return {
        "Links": _LINKS,
        "Defaulted": _DEFAULTED,
        "Scaled": _SCALED,
        "Wrapped": _WRAPPED,
        "Modal": _MODAL,
    }

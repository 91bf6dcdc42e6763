"""OSATE's flow latency rules on forms of models its own tests exercise and the corpus reports
do not: each test reads a small AADL model of its own, instantiates it and checks the rows and
totals OSATE's ``FlowLatencyAnalysisSwitch`` gives (the rule is named in each test).
"""

from __future__ import annotations

from rosaadl.analysis.latency import LatencyPreferences, analyze_latency
from rosaadl.importers.aadl_text import read_string
from rosaadl.transforms.instantiate import instantiate

_DL = LatencyPreferences(worst_case_deadline=True)


def _flow(text: str, root: str, name: str, preferences: LatencyPreferences = _DL, mode: str = "async"):
    system = instantiate(read_string(text, root.partition("::")[0] + ".aadl"), root)
    return analyze_latency(system, preferences=preferences).chain(name, mode)


def _rows(chain):
    return [(h.depth, h.kind, h.best_us, h.worst_us, h.best_method, h.worst_method) for h in chain.hops]


_CARRIED_BY_CPU = """
package Carried
public
  abstract emitter
    features o: out feature;
    flows src: flow source o {Latency => 2 ms .. 3 ms;};
  end emitter;
  abstract receiver
    features i: in feature;
    flows snk: flow sink i {Latency => 1 ms .. 1 ms;};
  end receiver;
  system top
  end top;
  system implementation top.i
    subcomponents
      e: abstract emitter;
      r: abstract receiver;
      board: processor {Latency => 4 ms .. 6 ms;};
    connections
      link: feature e.o -> r.i;
    flows
      path: end to end flow e.src -> link -> r.snk {Latency => 0 ms .. 20 ms;};
    properties
      Actual_Connection_Binding => (reference (board)) applies to link;
  end top.i;
end Carried;
"""


def test_connection_bound_to_a_processor_adds_its_latency():
    """``processActualConnectionBindingsTransmission`` takes every target of
    ``Actual_Connection_Binding``, not only buses: a processor carrying the message adds its
    ``Latency`` (*specified*), then waits (*queued*) and samples (*sampling protocol/bus*) as an
    aperiodic bus does."""
    chain = _flow(_CARRIED_BY_CPU, "Carried::top.i", "path")
    assert _rows(chain)[1:4] == [
        (1, "transmission", 4000, 6000, "specified", "specified"),
        (1, "queuing", 0, 0, "queued", "queued"),
        (1, "sampling", 0, 0, "sampling protocol/bus", "sampling protocol/bus"),
    ]
    assert _rows(chain)[4][:4] == (0, "connection", 4000, 6000)
    assert (chain.best_us, chain.worst_us) == (7000, 10000)


_NEGATIVE_BUS = """
package Backwards
public
  abstract emitter
    features o: out feature;
    flows src: flow source o {Latency => 1 ms .. 2 ms;};
  end emitter;
  abstract receiver
    features i: in feature;
    flows snk: flow sink i {Latency => 2 ms .. 2 ms;};
  end receiver;
  system top
  end top;
  system implementation top.i
    subcomponents
      e: abstract emitter;
      r: abstract receiver;
      wire: bus {Transmission_Time => [Fixed => -4 ms .. -3 ms;];};
    connections
      link: feature e.o -> r.i;
    flows
      path: end to end flow e.src -> link -> r.snk;
    properties
      Actual_Connection_Binding => (reference (wire)) applies to link;
  end top.i;
end Backwards;
"""


def test_negative_transmission_time_gives_an_unknown_row():
    """``processTransmissionTime``: a bus whose transfer time is not 0 gets a row; a negative one
    adds nothing and its method is unknown (*no sampling/queuing latency*), not *specified*."""
    chain = _flow(_NEGATIVE_BUS, "Backwards::top.i", "path")
    bus = next(h for h in chain.hops if h.kind == "transmission")
    unknown = "no sampling/queuing latency"
    assert (bus.best_us, bus.worst_us, bus.best_method, bus.worst_method) == (0, 0, unknown, unknown)
    assert (chain.best_us, chain.worst_us) == (3000, 4000)


_WINDOW_ONLY = """
package Window
public
  abstract emitter
    features o: out feature;
    flows src: flow source o {Latency => 1 ms .. 2 ms;};
  end emitter;
  abstract receiver
    features i: in feature;
    flows snk: flow sink i {Latency => 1 ms .. 3 ms;};
  end receiver;
  system top
  end top;
  system implementation top.i
    subcomponents
      e: abstract emitter;
      r: abstract receiver;
      slot: virtual processor {Execution_Time => 8 ms;};
    connections
      link: feature e.o -> r.i;
    flows
      path: end to end flow e.src -> link -> r.snk;
    properties
      Actual_Processor_Binding => (reference (slot)) applies to r;
  end top.i;
end Window;
"""


def test_partition_without_period_repeats_after_its_duration():
    """``mapConnectionInstance``: a partition the flow enters, with a window duration but neither
    a major frame nor a period, samples at its duration ("No partition period. Using partition
    duration"): the worst case waits a whole window."""
    chain = _flow(_WINDOW_ONLY, "Window::top.i", "path")
    entered = next(h for h in chain.hops if h.kind == "partition")
    assert (entered.best_us, entered.worst_us, entered.worst_method) == (0, 8000, "partition offset")
    assert "No partition period. Using partition duration" in entered.note
    assert (chain.best_us, chain.worst_us) == (2000, 13000)

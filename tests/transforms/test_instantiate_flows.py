"""End-to-end flows through shared data (rosaadl.transforms.instantiate.flows).

OSATE's rule (``CreateEndToEndFlowsSwitch.processAccess``): a data or subprogram access feature
named in an end-to-end flow stands for the component it gives access to. The connections before
it become the connection instance that ends at that data component, then comes the data
component's instance, then the connection instance back from it, through the rest of the first
instance's declarations and the flow's next connections. A data subcomponent named between two
connections (at the top level) is a flow element like any other subcomponent.
"""

from __future__ import annotations

import pytest

from rosaadl.analysis.latency import LatencyPreferences, analyze_latency
from rosaadl.importers.aadl_text import read_files
from rosaadl.importers.aadl_text.reading import library_files
from rosaadl.transforms.instantiate import instantiate

_SHARED = """
package Shared_Store
public
  abstract writer
    features w: requires data access;
    flows produce: flow source w {Latency => 1 ms .. 2 ms;};
  end writer;
  abstract reader
    features r: requires data access;
    flows consume: flow sink r {Latency => 1 ms .. 2 ms;};
  end reader;
  system cell
    features store: requires data access;
  end cell;
  system implementation cell.impl
    subcomponents
      w1: abstract writer;
      r1: abstract reader;
    connections
      put: data access w1.w -> store;
      get: data access store -> r1.r;
    flows
      through_store: end to end flow w1.produce -> put -> store -> get -> r1.consume
        {Latency => 4 ms .. 8 ms;};
      into_store: end to end flow w1.produce -> put -> store;
  end cell.impl;
  system top
  end top;
  system implementation top.impl
    subcomponents
      board: data;
      c: system cell.impl;
    connections
      share: data access c.store <-> board {Latency => 1 ms .. 2 ms;};
  end top.impl;
  system flat
  end flat;
  system implementation flat.impl
    subcomponents
      board: data;
      w1: abstract writer;
      r1: abstract reader;
    connections
      put: data access w1.w -> board {Latency => 1 ms .. 2 ms;};
      get: data access board -> r1.r {Latency => 1 ms .. 2 ms;};
    flows
      through_board: end to end flow w1.produce -> put -> board -> get -> r1.consume;
  end flat.impl;
end Shared_Store;
"""


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    folder = tmp_path_factory.mktemp("shared_store")
    (folder / "Shared_Store.aadl").write_text(_SHARED, encoding="utf-8")
    library = [f for f in library_files() if f.stem in ("AADL_Project", "Communication_Properties")]
    return read_files([folder / "Shared_Store.aadl", *library], include_library=False)


def _flow(component, name):
    return next(f for f in component.endToEndFlows if f.name == name)


def test_flow_through_an_access_feature_goes_through_the_shared_data(workspace):
    system = instantiate(workspace, "Shared_Store::top.impl")
    board, cell = system.componentInstances
    elements = _flow(cell, "through_store").flowElements
    assert [e.name for e in elements] == [
        "produce",
        "c.w1.w -> board",
        "board",
        "board -> c.r1.r",
        "consume",
    ]
    assert elements[2] is board
    assert list(elements[1:4:2]) == list(system.connectionInstances)[::-1]


def test_flow_ending_at_an_access_feature_ends_at_the_shared_data(workspace):
    system = instantiate(workspace, "Shared_Store::top.impl")
    cell = system.componentInstances[1]
    assert [e.name for e in _flow(cell, "into_store").flowElements] == ["produce", "c.w1.w -> board", "board"]


def test_flow_through_a_data_subcomponent_at_the_top_level(workspace):
    system = instantiate(workspace, "Shared_Store::flat.impl")
    assert [e.name for e in _flow(system, "through_board").flowElements] == [
        "produce",
        "w1.w -> board",
        "board",
        "board -> r1.r",
        "consume",
    ]


def test_latency_counts_both_connections_through_the_shared_data(workspace):
    # OSATE gives 4..8 ms on its own model of this shape (connect_to_subcomponent)
    system = instantiate(workspace, "Shared_Store::top.impl")
    chain = analyze_latency(system, preferences=LatencyPreferences(worst_case_deadline=True)).chain(
        "c.through_store", "async"
    )
    assert (chain.best_us, chain.worst_us) == (4000, 8000)

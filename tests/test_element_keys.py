"""Stable element keys (``rosaadl.element_keys``): one key builder for traces, diagnostics and
the code generator's manifest, with and without a cache."""

from __future__ import annotations

from rosaadl import model
from rosaadl.element_keys import element_key, find_by_key
from rosaadl.importers.aadl_text import read_string
from rosaadl.transforms import trace as tracing

TEXT = """
package sw
public
  thread worker
    features
      inp: in event data port;
  end worker;
  thread implementation worker.impl
    properties
      Period => 10 ms;
      Priority => 3;
  end worker.impl;
end sw;
"""


def test_keys_name_named_elements_and_number_the_others():
    aadl = read_string(TEXT)
    impl = model.find_classifier(aadl, "sw::worker.impl")
    assert element_key(aadl) == "/"
    key = element_key(impl)
    assert key.startswith("/units[sw]/") and key.endswith("[worker.impl]")
    second = impl.ownedPropertyAssociations[1]
    assert element_key(second).endswith("/ownedPropertyAssociations.1")
    assert find_by_key(aadl, key) is impl and find_by_key(aadl, element_key(second)) is second


def test_a_cached_key_is_the_key_and_is_remembered():
    aadl = read_string(TEXT)
    cache: dict[int, str] = {}
    every = list(model.walk(aadl))
    assert [element_key(o, cache) for o in every] == [element_key(o) for o in every]
    assert len(cache) == len(every)


def test_a_key_that_no_longer_matches_finds_nothing():
    aadl = read_string(TEXT)
    assert find_by_key(aadl, "/units[sw]/nothing[x]") is None
    assert find_by_key(aadl, "/units[gone]") is None
    assert find_by_key(aadl, "/units.x") is None
    assert find_by_key(aadl, "/units.99") is None


def test_the_trace_keys_are_these_keys():
    assert tracing.element_key is element_key and tracing.find_by_key is find_by_key

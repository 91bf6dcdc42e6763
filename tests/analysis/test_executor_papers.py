"""Worked examples of the cited papers, with the numbers the papers (or their artefacts) give.

* Teper, Günzel, Ueter, von der Brüggen & Chen, "End-To-End Timing Analysis in ROS2", RTSS
  2022: its case study (Section VIII), whose system and numbers are those of the paper's
  artefact (github.com/HarunTeper/ros2-end-to-end, ``simulation_and_analysis/main.py``,
  experiment ``case_study under SS``).
* Blaß, Casini, Bozhko & Brandenburg, RTSS 2021: the hand-checked example of its reference
  implementation, the ``ros2::rr`` and ``ros2::bw`` modules of the ``response-time-analysis``
  crate (github.com/brandenburg/response-time-analysis-rs, ``src/ros2/tests.rs``,
  ``ros2_rr_subchain_analysis`` and ``ros2_bw_subchain_analysis``), whose numbers the test
  comments there derive by hand.

The other papers' worked examples (Casini et al., ECRTS 2019, Figure 3; Günzel et al., ECRTS
2023) are figures whose numbers are in no public text or artefact we could read; see
``docs/executors.md``.
"""

from __future__ import annotations

from fractions import Fraction

from rosaadl.analysis.cause_effect import ChainLink, chain_bound, release_gaps
from rosaadl.analysis.executor_response import CallbackTiming, polling_response_time
from rosaadl.analysis.executor_simulation import simulate_executor
from rosaadl.analysis.executors import Callback

# Teper et al., RTSS 2022, Section VIII (case study, under-utilised, all links subscriptions):
# one node, one single-threaded executor, time in ms. Two sensors (timers, phase 0, period 360),
# a filter per sensor, a fusion node of two subscriptions (the one fed by process1 triggers the
# fusion, the one fed by process2 only stores its message), a filter and an actuator
# (subscriptions). Registration order = the artefact's priorities 0..7.
PERIOD = 360
CASE_STUDY = [  # (name, kind, wcet)
    ("sensor1", "timer", 10),
    ("sensor2", "timer", 20),
    ("process1", "subscription", 10),
    ("process2", "subscription", 20),
    ("fusion_passive", "subscription", 30),
    ("fusion", "subscription", 30),
    ("filter3", "subscription", 30),
    ("actuator", "subscription", 30),
]
#: the paper's chain sensor1 -> process1 -> fusion -> filter3 -> actuator (artefact ids 0,2,5,6,7)
CHAIN = ("sensor1", "process1", "fusion", "filter3", "actuator")
#: Section VIII's numbers for that chain: the simulated maximum reaction time and data age
#: (the artefact's executor simulation, a lower bound on the worst case) and the upper bound.
SIMULATED_REACTION_TIME = 540
SIMULATED_DATA_AGE = 540
PAPER_UPPER_BOUND = 1430


def _timings():
    return [
        CallbackTiming(name, PERIOD, wcet, PERIOD, 0, rank) for rank, (name, _, wcet) in enumerate(CASE_STUDY)
    ]


def _callbacks():
    return {
        name: Callback(
            f"node1.{name}",
            "node1",
            kind,
            Fraction(PERIOD),
            Fraction(wcet),
            Fraction(PERIOD),
            0,
            name,
            rank,
            kind == "timer",
        )
        for rank, (name, kind, wcet) in enumerate(CASE_STUDY)
    }


def test_teper_rtss2022_case_study_paper_bound_from_its_equation():
    """The paper's own bound (Section VII, processing windows): with ``W`` the sum of the WCETs
    of all callbacks of the executor (180), a chain starting at a timer costs ``T + (W - C) + W``
    for the timer and one window ``W`` for each following subscription: 360 + 170 + 180 + 4 *
    180 = 1430, the number of Section VIII."""
    window = sum(wcet for _, _, wcet in CASE_STUDY)
    assert window == 180
    first = {n: w for n, _, w in CASE_STUDY}["sensor1"]
    assert PERIOD + (window - first) + window + (len(CHAIN) - 1) * window == PAPER_UPPER_BOUND


def test_teper_rtss2022_case_study_our_bound():
    """Our bound on the same system: every callback's response time under the single-threaded
    executor is 180 (Casini et al., ECRTS 2019, eq. (6): at most one job of every other callback
    — one release each per 360 — runs before it, so ``R = W``), and the chain's reaction time
    and data age are ``T_sensor1 + sum R`` = 360 + 5 * 180 = 1260 (Davare et al. with Teper et
    al.'s event-triggered links; Günzel et al., ECRTS 2023: data age = reaction time).

    1260 lies between the simulated 540 and the paper's 1430. Ours is tighter because the
    per-callback response time counts the work of the *jobs* that can run before the callback
    (one per other callback within a period of 360, rbf), whereas the paper's processing-window
    argument charges a full window ``W`` of every callback for the timer's wait *and* for its
    own window (``T + (W - C) + W`` = 710 against our ``T + R`` = 540): it does not use that a
    callback that ran in the window under way cannot run again in the next one within its
    period. Both charge one ``W`` (180) per subscription hop.
    """
    timings = _timings()
    responses = {c.name: polling_response_time(timings, i) for i, c in enumerate(timings)}
    assert set(responses.values()) == {180}
    callbacks = _callbacks()
    on_chain = [callbacks[name] for name in CHAIN]
    # every hop of the case study is a topic: each subscription is released by the chain's message
    links = [ChainLink(a, b, f"{a.path}->{b.path}") for a, b in zip(on_chain, on_chain[1:], strict=False)]
    bound = chain_bound(
        "case_study",
        on_chain,
        links,
        lambda cb: Fraction(responses[cb.path.split(".")[1]]),
        lambda _: Fraction(0),
    )
    assert bound.reaction_time == 1260
    assert bound.data_age == bound.reaction_time
    assert SIMULATED_REACTION_TIME <= bound.reaction_time <= PAPER_UPPER_BOUND
    assert bound.data_age >= SIMULATED_DATA_AGE


# Blaß et al., RTSS 2021, through its reference implementation's hand-checked example: three
# callbacks of one single-threaded executor on a dedicated processor, order unknown
# (``PolledUnknownPrio``: equal ranks here), (T, C) = (100, 10), (10000, 230), (1000, 190).
STARVATION_FREE = [
    CallbackTiming("a", 100, 10, 100),
    CallbackTiming("b", 10000, 230, 10000),
    CallbackTiming("c", 1000, 190, 1000),
]
#: the round-robin analysis: "(before polling point) + (own polling point)"
ROUND_ROBIN = (10 * 10 + (190 + 230 + 10), 10 + (10 + 190 + 230), 10 + (10 + 230 + 190))
#: the busy-window analysis
BUSY_WINDOW = (190 + 230 + 10, 3 * 10 + 190 + 230 - 1, 3 * 10 + 190 + 230 - 1)


def test_blass_rtss2021_reference_example():
    """Ours is the least of the two analyses for every callback: 430, 440, 440.

    ``a`` (T = 100 < its bound): no starvation argument applies (a job of ``a`` may still be
    pending when the next is released); Casini et al.'s eq. (6) gives one job of ``b`` and ``c``
    and ``a``'s own: 430, the busy-window number (the round-robin one, 530, charges ten rounds
    of ``a``). ``b`` and ``c``: the two-round bound with the arrival cap: in 440 time units ``c``
    (resp. ``b``) releases one job, ``a`` runs at most once per round (twice): 20 + 190 + 230 =
    440, the round-robin number (the busy-window one, 449, counts three jobs of ``a``). The
    simulation reaches 439 for ``b`` and ``c`` (released one unit after ``a`` and the other one).
    """
    ours = tuple(polling_response_time(STARVATION_FREE, i) for i in range(3))
    assert ROUND_ROBIN == (530, 440, 440) and BUSY_WINDOW == (430, 449, 449)
    assert ours == tuple(map(min, ROUND_ROBIN, BUSY_WINDOW)) == (430, 440, 440)
    a_releases = list(range(0, 2000, 100))
    for late in (1, 2):
        releases = [a_releases, [1 if late == 1 else 0], [1 if late == 2 else 0]]
        worst = simulate_executor(STARVATION_FREE, "polling", releases).worst
        assert worst[late] == 439 <= ours[late]


def _callback(name: str, kind: str, period: int) -> Callback:
    timer = kind == "timer"
    span = Fraction(period)
    return Callback(f"n.{name}", "n", kind, span, Fraction(1), span, 0, name, 0, timer)


def test_a_stored_link_waits_for_the_readers_next_release():
    """Teper et al., RTSS 2022, second chain of Section VIII's case study, in its smallest shape:
    a subscription ``b`` stores the data of the chain for ``c``, which another topic (from the
    timer ``d``) releases. The data waits at most until ``c``'s next release: ``c``'s longest
    gap between releases is ``d``'s period plus ``d``'s response time (the jitter ``d`` passes
    on), so the chain costs ``(T_a + R_a) + R_b + (T_d + R_d) + R_c`` = 110 + 5 + 70 + 7 = 192.
    Charging ``c`` its response time only (7) would claim 122, below what can happen."""
    a, b, c, d = (_callback("a", "timer", 100), _callback("b", "subscription", 100),
                  _callback("c", "subscription", 50), _callback("d", "timer", 50))  # fmt: skip
    responses = {a.path: 10, b.path: 5, c.path: 7, d.path: 20}
    every_link = [ChainLink(a, b, "a->b"), ChainLink(b, c), ChainLink(d, c, "d->c")]
    gaps = release_gaps(every_link, lambda cb: Fraction(responses[cb.path]))
    assert gaps(c) == 70 and gaps(b) == 110 and gaps(d) == 50
    bound = chain_bound(
        "stored", [a, b, c], every_link[:2], lambda cb: Fraction(responses[cb.path]), lambda _: Fraction(0),
        gaps=gaps,
    )  # fmt: skip
    assert bound.reaction_time == 192 == bound.data_age
    # a cycle of subscriptions has no longest gap, so a chain stored into it has no bound
    looped = [ChainLink(a, b, "a->b"), ChainLink(b, c), ChainLink(c, b, "c->b"), ChainLink(b, c, "b->c")]
    assert release_gaps(looped, lambda cb: Fraction(responses[cb.path]))(c) is None

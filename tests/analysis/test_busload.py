"""Bus load (rosaadl.analysis.busload) against OSATE's semantics and OSATE's own CSV reports.

Two kinds of checks against the reports in ``osate/busload`` of the corpus:

* instance models built here by hand after the corpus models' structure (buses, virtual buses,
  bindings, budgets, rates), compared line for line with OSATE's CSV — these run now;
* the corpus ``.aadl`` files themselves, read with the AADL reader and instantiated for every
  root OSATE analysed — these skip until the reader is available.
"""

from __future__ import annotations

import csv
import io
import re
from fractions import Fraction
from pathlib import Path

import pytest
from conftest import corpus_dir
from instance_builders import component, num, pa, ref

from rosaadl import model
from rosaadl.analysis.busload import analyze_bus_load, java_double, message_rate, port_loads
from rosaadl.analysis.instance_values import PropertyReader
from rosaadl.errors import AnalysisError

new = model.new


# =============================================================================== builders


def rate_spec(low, high, unit="PerSecond"):
    return new(
        "RecordValue",
        ownedFields=[
            new(
                "FieldValue",
                name="Value_Range",
                value=new(
                    "RangeValue", minimum=new("RealValue", value=low), maximum=new("RealValue", value=high)
                ),
            ),
            new("FieldValue", name="Rate_Unit", value=new("NamedValue", name=unit)),
        ],
    )


def port(name, direction, size=8, rate=None, category="data port"):
    props = []
    if size is not None:
        props.append(pa("Memory_Properties::Data_Size", num(size, "Bytes")))
    if rate is not None:
        props.append(pa("Communication_Properties::Output_Rate", rate))
    fi = new("FeatureInstance", name=name, feature=name, category=category, direction=direction)
    fi.ownedPropertyAssociations.extend(props)
    return fi


def bus(name, category="bus", size=None, budget=None, capacity=None, broadcast=None):
    props = []
    if size is not None:
        props.append(pa("Memory_Properties::Data_Size", num(size, "Bytes")))
    if budget is not None:
        props.append(pa("SEI::BandWidthBudget", num(budget, "KBytesps")))
    if capacity is not None:
        props.append(pa("SEI::BandWidthCapacity", num(capacity, "KBytesps")))
    if broadcast is not None:
        props.append(pa("SEI::Broadcast_Protocol", new("BooleanValue", value=broadcast)))
    return component(name, category, props=props)


def bind(obj, *targets):
    obj.ownedPropertyAssociations.append(
        pa("Deployment_Properties::Actual_Connection_Binding", ref(*targets))
    )


class System:
    """A root system with communicating subsystems, buses and bound connections."""

    def __init__(self, name):
        self.root = new("SystemInstance", name=name, category="system")
        self.parts = {}

    def add(self, ci):
        self.root.componentInstances.append(ci)
        self.parts[ci.name] = ci
        return ci

    def feature(self, owner, name, direction, **kwargs):
        sub = self.parts.get(owner) or self.add(component(owner, "system"))
        for fi in sub.featureInstances:
            if fi.name == name:
                return fi
        if direction == "out":
            kwargs.setdefault("rate", rate_spec(800.0, 1000.0))
        fi = port(name, direction, **kwargs)
        sub.featureInstances.append(fi)
        return fi

    def connect(self, src, dst, budget=None, bound=None):
        s_owner, s_port = src.split(".")
        d_owner, d_port = dst.split(".")
        conn = new(
            "ConnectionInstance",
            name=f"{src} -> {dst}",
            kind="portConnection",
            source=self.feature(s_owner, s_port, "out"),
            destination=self.feature(d_owner, d_port, "in"),
        )
        if bound is not None:
            bind(conn, self.parts[bound])
        if budget is not None:
            conn.ownedPropertyAssociations.append(pa("SEI::BandWidthBudget", num(budget, "KBytesps")))
        self.root.connectionInstances.append(conn)
        return conn


def overhead_system(name="top_i_Instance"):
    """A bus and three nested virtual buses with data overheads, one connection on each."""
    s = System(name)
    for i in range(1, 5):
        s.feature("sub1", f"out{i}", "out")
    for i in range(1, 5):
        s.feature("sub2", f"in{i}", "in")
    s.add(bus("theBus", size=8, budget=512.0, capacity=768.0))
    s.add(bus("VB1", "virtual bus", 16, 384.0, 512.0))
    s.add(bus("VB2", "virtual bus", 24, 256.0, 384.0))
    s.add(bus("VB3", "virtual bus", 32, 128.0, 256.0))
    bind(s.parts["VB1"], s.parts["theBus"])
    bind(s.parts["VB2"], s.parts["VB1"])
    bind(s.parts["VB3"], s.parts["VB2"])
    for i, (target, budget) in enumerate([("theBus", 20.0), ("VB1", 40.0), ("VB2", 64.0), ("VB3", 96.0)], 1):
        s.connect(f"sub1.out{i}", f"sub2.in{i}", budget, target)
    return s


def add_modes(s):
    """theBus in modes m1/m2 (overhead 8/16 bytes), VB3 in modes z1/z2 (32/64 bytes)."""
    found = {}
    for owner, sizes in (("theBus", (("m1", 8), ("m2", 16))), ("VB3", (("z1", 32), ("z2", 64)))):
        ci = s.parts[owner]
        for assoc in list(ci.ownedPropertyAssociations):
            if assoc.property.endswith("Data_Size"):
                ci.ownedPropertyAssociations.remove(assoc)
        ci.ownedPropertyAssociations.append(
            pa("Memory_Properties::Data_Size", [(num(size, "Bytes"), [mode]) for mode, size in sizes])
        )
        for i, (mode, _size) in enumerate(sizes):
            mi = new("ModeInstance", name=mode, mode=mode, initial=i == 0)
            ci.modeInstances.append(mi)
            found[mode] = mi
    number = 0
    for a in ("m1", "m2"):
        for b in ("z1", "z2"):
            s.root.systemOperationModes.append(
                new("SystemOperationMode", name=f"som_{number}", currentModes=[found[a], found[b]])
            )
            number += 1
    return s


def broadcast_system():
    s = System("top_i_Instance")
    s.add(bus("noBroadcastBus", budget=64.0, capacity=96.0))
    s.add(bus("broadcastBus", budget=64.0, capacity=96.0, broadcast=True))
    for a, b, target in (("sub1", "sub2", "noBroadcastBus"), ("sub3", "sub4", "broadcastBus")):
        for src, dst in (("out1", "in1"), ("out1", "in2"), ("out1", "in3"), ("out2", "in4")):
            s.connect(f"{a}.{src}", f"{b}.{dst}", 8.0, target)
    # the subsystems declared in the order sub1, sub2, noBroadcastBus, sub3, sub4, broadcastBus
    order = ["sub1", "sub2", "noBroadcastBus", "sub3", "sub4", "broadcastBus"]
    s.root.componentInstances.clear()
    s.root.componentInstances.extend(s.parts[n] for n in order)
    return s


def calculations_system(impl, vb_props, bus_props):
    s = System(f"top_{impl}_Instance")
    for i in range(1, 4):
        s.feature("sub1", f"out{i}", "out")
    for i in range(1, 4):
        s.feature("sub2", f"in{i}", "in")
    s.add(bus("theBus", capacity=bus_props[0], budget=bus_props[1]))
    s.add(bus("vb1", "virtual bus", capacity=vb_props[0], budget=vb_props[1]))
    bind(s.parts["vb1"], s.parts["theBus"])
    s.connect("sub1.out1", "sub2.in1", 12.0, "vb1")
    s.connect("sub1.out2", "sub2.in2", 12.0, "vb1")
    s.connect("sub1.out3", "sub2.in3", 12.0, "theBus")
    return s


def properties_system(impl, vb, the_bus):
    s = System(f"top_{impl}_Instance")
    s.feature("sub1", "out1", "out")
    s.feature("sub2", "in1", "in")
    s.add(bus("theBus", **the_bus))
    s.add(bus("VB1", "virtual bus", **vb))
    bind(s.parts["VB1"], s.parts["theBus"])
    s.connect("sub1.out1", "sub2.in1", 16.0, "VB1")
    return s


BUILT = {
    "TestDataOverhead_top_i_Instance__BusLoad.csv": lambda: overhead_system(),
    "TestDataOverhead_SOM_top_i_Instance__BusLoad.csv": lambda: add_modes(overhead_system()),
    "TestBroadcast_top_i_Instance__BusLoad.csv": broadcast_system,
    "TestCalculations_top_requiredBudgetLessThanBudget_Instance__BusLoad.csv": lambda: calculations_system(
        "requiredBudgetLessThanBudget", (48.0, 32.0), (64.0, 48.0)
    ),
    "TestCalculations_top_requiredBudgetGreaterThanBudget_Instance__BusLoad.csv": lambda: calculations_system(
        "requiredBudgetGreaterThanBudget", (48.0, 16.0), (64.0, 24.0)
    ),
    "TestCalculations_top_actualGreaterThanCapacity_Instance__BusLoad.csv": lambda: calculations_system(
        "actualGreaterThanCapacity", (12.0, 12.0), (16.0, 16.0)
    ),
    "TestBusProperties_top_noCapacity_noBudget_Instance__BusLoad.csv": lambda: properties_system(
        "noCapacity_noBudget", {}, {}
    ),
    "TestBusProperties_top_noCapacity_Instance__BusLoad.csv": lambda: properties_system(
        "noCapacity", {"budget": 32.0}, {"budget": 48.0}
    ),
    "TestBusProperties_top_noBudget_Instance__BusLoad.csv": lambda: properties_system(
        "noBudget", {"capacity": 48.0}, {"capacity": 64.0}
    ),
    "TestBusProperties_top_budgetLessThanCapacity_Instance__BusLoad.csv": lambda: properties_system(
        "budgetLessThanCapacity", {"budget": 32.0, "capacity": 48.0}, {"budget": 48.0, "capacity": 64.0}
    ),
    "TestBusProperties_top_budgetGreaterThanCapacity_Instance__BusLoad.csv": lambda: properties_system(
        "budgetGreaterThanCapacity", {"budget": 32.0, "capacity": 24.0}, {"budget": 56.0, "capacity": 48.0}
    ),
}


# =============================================================================== CSV comparison

_NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:E-?\d+)?")


def _close(ours: str, theirs: str) -> bool:
    """Equal, or the same number at the precision OSATE printed."""
    if ours == theirs:
        return True
    if not (_NUMBER.fullmatch(ours) and _NUMBER.fullmatch(theirs)):
        return False
    printed = theirs.split("E")[0]
    decimals = len(printed.partition(".")[2])
    return abs(Fraction(ours) - Fraction(theirs)) <= Fraction(1, 2 * 10**decimals) * (
        10 ** int(theirs.split("E")[1]) if "E" in theirs else 1
    )


def _cells(text: str) -> list[list[str]]:
    return [row for row in csv.reader(io.StringIO(text))]


def assert_same_report(ours: str, theirs: str) -> None:
    """Same lines, same cells; numbers (also inside messages) equal at OSATE's printed precision."""
    a, b = _cells(ours), _cells(theirs)
    assert len(a) == len(b), f"{len(a)} lines, OSATE has {len(b)}"
    for n, (row_a, row_b) in enumerate(zip(a, b, strict=True), 1):
        assert len(row_a) == len(row_b), f"line {n}: {row_a} vs OSATE {row_b}"
        for cell_a, cell_b in zip(row_a, row_b, strict=True):
            words_a, words_b = _NUMBER.split(cell_a), _NUMBER.split(cell_b)
            nums_a, nums_b = _NUMBER.findall(cell_a), _NUMBER.findall(cell_b)
            assert words_a == words_b and len(nums_a) == len(nums_b), (
                f"line {n}: {cell_a!r} vs OSATE {cell_b!r}"
            )
            for x, y in zip(nums_a, nums_b, strict=True):
                assert _close(x, y), f"line {n}: {cell_a!r} vs OSATE {cell_b!r}"


@pytest.mark.parametrize("report", sorted(BUILT))
def test_built_instances_reproduce_osate_reports(corpus, report):
    expected = (corpus / "osate" / "busload" / report).read_text(encoding="utf-8")
    result = analyze_bus_load(BUILT[report]().root)
    text = result.csv_text()
    assert_same_report(text, expected)
    assert text == expected  # and, here, byte for byte


def test_every_corpus_report_has_a_built_instance(corpus):
    reports = sorted(p.name for p in (corpus / "osate" / "busload").glob("*__BusLoad.csv"))
    assert reports and set(reports) == set(BUILT)


# =============================================================================== corpus models


def _corpus_cases() -> list[tuple[str, str, str]]:
    """(aadl file, root implementation, report) for each report whose model is in the corpus."""
    folder = corpus_dir() / "osate" / "busload"
    cases = []
    if not folder.is_dir():
        return cases
    models = {p.stem: p.name for p in folder.glob("*.aadl")}
    for report in sorted(p.name for p in folder.glob("*__BusLoad.csv")):
        stem, _, rest = report.partition("_top_")
        impl = rest.removesuffix("_Instance__BusLoad.csv")
        if stem in models:
            cases.append((models[stem], f"{stem}::top.{impl}", report))
    return cases


def _reader():
    from rosaadl.importers import aadl_text

    return aadl_text


@pytest.fixture(scope="module")
def corpus_workspace(corpus):
    """Every bus load model of the corpus, read once (with the library's property sets)."""
    aadl_text = _reader()
    folder = corpus / "osate" / "busload"
    return aadl_text.read_files(sorted(folder.glob("*.aadl")), include_library=True)


@pytest.mark.parametrize(("aadl", "root", "report"), _corpus_cases() or [("-", "-", "-")])
def test_corpus_models_match_osate_reports(corpus, corpus_workspace, aadl, root, report):
    """For each model and root OSATE analysed: capacity, budget, required budget and actual of
    every bus, virtual bus, broadcast and connection, and the diagnostics, equal OSATE's CSV."""
    if aadl == "-":
        pytest.skip("no bus load models in the corpus")
    from rosaadl.transforms.instantiate import instantiate

    system = instantiate(corpus_workspace, root)
    result = analyze_bus_load(system)
    expected = (corpus / "osate" / "busload" / report).read_text(encoding="utf-8")
    assert_same_report(result.csv_text(), expected)


def test_osate_help_example_has_its_one_error(corpus_workspace):
    """The help's example: one error, on the fourth connection, in system operation mode (VB3.z2)."""
    from rosaadl.transforms.instantiate import instantiate

    result = analyze_bus_load(instantiate(corpus_workspace, "Example::top.i"))
    assert [m.label for m in result.modes] == ["(VB3.z1)", "(VB3.z2)"]
    (error,) = [d for d in result.diagnostics if d.severity == "error"]
    assert error.location.path == "top_i_Instance.sub1.out4 -> sub2.in4"
    assert error.message.endswith("120.0 KB/s > 96.0 KB/s in modes (VB3.z2)")


def test_the_som_report_has_no_model_in_the_corpus(corpus):
    """TestDataOverhead_SOM comes from a modal variant of TestDataOverhead that the corpus does not
    hold; the built modal instance above covers it."""
    folder = corpus / "osate" / "busload"
    assert (folder / "TestDataOverhead_SOM_top_i_Instance__BusLoad.csv").is_file()
    assert not (folder / "TestDataOverhead_SOM.aadl").exists()


# =============================================================================== semantics


def test_overheads_accumulate_through_nested_virtual_buses():
    result = analyze_bus_load(overhead_system().root)
    the_bus = result.bus("top_i_Instance.theBus")
    assert [b.overhead_bytes for b in the_bus.walk()] == [8, 24, 48, 80]
    # (8 bytes + overhead) x 1000 messages/s, in KB/s
    assert [c.actual_kbps for b in the_bus.walk() for c in b.connections] == [16, 32, 56, 88]
    with pytest.raises(AnalysisError, match="no bus or virtual bus 'top_i_Instance.nothing'"):
        result.bus("top_i_Instance.nothing")
    assert the_bus.actual_kbps == 192 and the_bus.required_kbps == 404  # 20 + VB1's budget 384
    assert result.ok


def test_modal_overheads_give_one_result_per_system_mode():
    result = analyze_bus_load(add_modes(overhead_system()).root)
    assert [m.label for m in result.modes] == [
        "(theBus.m1, VB3.z1)",
        "(theBus.m1, VB3.z2)",
        "(theBus.m2, VB3.z1)",
        "(theBus.m2, VB3.z2)",
    ]
    actual = [m.buses[0].actual_kbps for m in result.modes]
    assert actual == [192, 224, 224, 256]
    errors = [d for d in result.diagnostics if d.severity == "error"]
    assert len(errors) == 4 and all("in modes (" in d.message for d in errors)
    assert errors[0].location.path == "top_i_Instance.sub1.out4 -> sub2.in4"


def test_broadcast_groups_count_once_with_the_largest_budget():
    s = broadcast_system()
    conns = list(s.root.connectionInstances)
    conns[5].ownedPropertyAssociations[-1].ownedValues[0].value = num(12.0, "KBytesps")
    result = analyze_bus_load(s.root)
    plain = result.bus("top_i_Instance.noBroadcastBus")
    shared = result.bus("top_i_Instance.broadcastBus")
    assert plain.actual_kbps == 32 and len(plain.connections) == 4 and not plain.broadcasts
    assert shared.actual_kbps == 16 and len(shared.connections) == 1
    (group,) = shared.broadcasts
    assert group.source == "top_i_Instance.sub3.out1" and group.budget_kbps == 12
    assert [c.budget_kbps for c in group.connections] == [8, 12, 8]
    assert len(group.diagnostics) == 3 and "using maximum" in group.diagnostics[0].message


def test_virtual_bus_inside_a_bus_is_bound_to_it():
    s = System("t_Instance")
    outer = s.add(bus("net", capacity=100.0, budget=50.0))
    inner = bus("ros", "virtual bus", size=4, capacity=50.0, budget=10.0)
    outer.componentInstances.append(inner)
    conn = s.connect("a.o", "b.i", 10.0)
    bind(conn, inner)
    result = analyze_bus_load(s.root)
    net = result.bus("t_Instance.net")
    assert [vb.path for vb in net.virtual_buses] == ["t_Instance.net.ros"]
    assert net.virtual_buses[0].connections[0].actual_kbps == 12  # (8 + 4) bytes x 1000 /s


@pytest.mark.parametrize(
    ("props", "expected"),
    [
        ([("SEI::Data_Rate", num(50.0, "perSecond"))], 50),
        ([("SEI::Message_Rate", num(20, "perSecond")), ("SEI::Data_Rate", num(5.0, "perSecond"))], 5),
        ([("SEI::Message_Rate", num(20, "perSecond"))], 20),
        ([("Communication_Properties::Output_Rate", rate_spec(1.0, 2.0, "PerDispatch"))], 200),
        ([("Communication_Properties::Output_Rate", rate_spec(0.0, 0.0, "PerSecond"))], 100),
        ([], 100),
    ],
)
def test_rate_precedence(props, expected):
    """Data_Rate, then Message_Rate, then Output_Rate (PerDispatch: per Period), then 1/Period."""
    fi = port("o", "out", size=8)
    fi.ownedPropertyAssociations.extend(pa(p, v) for p, v in props)
    thread = component("t", "thread", props=[pa("Timing_Properties::Period", num(10, "ms"))], features=[fi])
    root = new("SystemInstance", name="r", category="system")
    root.componentInstances.append(thread)
    assert message_rate(PropertyReader(), fi) == expected


def test_source_data_size_and_units():
    s = System("u_Instance")
    out = s.feature("a", "o", "out", size=None, rate=rate_spec(10.0, 10.0))
    out.ownedPropertyAssociations.append(pa("Memory_Properties::Source_Data_Size", num(2, "KByte")))
    s.add(bus("net", capacity=100, budget=None))
    s.parts["net"].ownedPropertyAssociations[0].ownedValues[0].value = num(8, "Mbps")  # 1000 KB/s
    s.connect("a.o", "b.i", 30.0, "net")
    result = analyze_bus_load(s.root)
    net = result.bus("u_Instance.net")
    assert net.capacity_kbps == 1000 and net.actual_kbps == 20
    assert any("no bandwidth budget" in d.message for d in result.diagnostics)


def test_json_rows():
    data = analyze_bus_load(overhead_system().root).as_dict()
    (row,) = data["buses"]
    assert list(row)[:6] == [
        "path",
        "capacity_kbps",
        "budget_kbps",
        "required_kbps",
        "actual_kbps",
        "overhead_bytes",
    ]
    assert row["connections"] == [
        {"path": "top_i_Instance.sub1.out1 -> sub2.in1", "budget_kbps": 20, "actual_kbps": 16}
    ]
    assert row["virtual_buses"][0]["path"] == "top_i_Instance.VB1"


def test_port_loads_are_data_size_over_period():
    fi = port("pub", "out", size=None, category="event data port")
    fi.ownedPropertyAssociations.append(pa("Memory_Properties::Data_Size", num(921, "KByte")))
    thread = component(
        "pub", "thread", props=[pa("Timing_Properties::Period", num(33333, "us"))], features=[fi]
    )
    root = new("SystemInstance", name="r", category="system")
    root.componentInstances.append(component("node", "process", thread))
    (row,) = port_loads(root)
    assert row.path == "r.node.pub.pub"
    assert row.kbytesps == Fraction(921_000, 1000) * Fraction(1_000_000, 33333)


def test_bad_bindings_and_cycles_do_not_crash():
    s = System("c_Instance")
    net = s.add(bus("net", capacity=10.0, budget=5.0))
    a = s.add(bus("va", "virtual bus"))
    b = s.add(bus("vb", "virtual bus"))
    bind(a, net, b)
    bind(b, a)
    conn = s.connect("x.o", "y.i", 1.0)
    conn.ownedPropertyAssociations.append(
        pa(
            "Deployment_Properties::Actual_Connection_Binding",
            new("ListValue", ownedItems=[new("ReferenceValue", path="nowhere")]),
        )
    )
    result = analyze_bus_load(s.root)
    messages = [d.message for d in result.diagnostics]
    assert any("does not resolve" in m for m in messages)
    assert any("bound in a cycle" in m for m in messages)
    assert result.bus("c_Instance.net").virtual_buses[0].path == "c_Instance.va"


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (16, "16.0"),
        (Fraction(1, 8), "0.125"),
        (10**7, "1.0E7"),
        (Fraction(1, 10**4), "1.0E-4"),
        (0, "0.0"),
        (-2.5, "-2.5"),
    ],
)
def test_java_double(value, text):
    assert java_double(value) == text


def test_csv_is_written_by_the_report(tmp_path: Path):
    from rosaadl.analysis.report import run_analyses

    report = run_analyses(overhead_system().root, "bus")
    files = report.write_csv(tmp_path)
    assert [f.name for f in files] == ["top_i_Instance__BusLoad.csv"]
    assert files[0].read_text(encoding="utf-8").startswith("Bus load analysis of top_i_Instance\n")

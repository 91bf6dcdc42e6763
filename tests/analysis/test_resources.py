"""Bound resource allocation and not-bound budgets (rosaadl.analysis.resources), OSATE semantics,
the paper's Table 2 on the component library, and bad input."""

from __future__ import annotations

from fractions import Fraction

import pytest
from instance_builders import component, num, pa, ref, span

from rosaadl import model
from rosaadl.analysis.budgets import analyze_budgets
from rosaadl.analysis.busload import port_loads
from rosaadl.analysis.instance_values import PropertyReader, SystemMode, bound_processor, system_modes
from rosaadl.analysis.resources import analyze_resources
from rosaadl.errors import ModelError

new = model.new


# =============================================================================== builders


def processor(name, mips=None, *cores, category="processor", budget=None):
    props = []
    if mips is not None:
        props.append(pa("SEI::MIPSCapacity", num(float(mips), "MIPS")))
    if budget is not None:
        props.append(pa("SEI::MIPSBudget", num(float(budget), "MIPS")))
    return component(name, category, *cores, props=props)


def thread(name, period=None, cet=None, unit="us", props=()):
    out = []
    if period is not None:
        out.append(pa("Timing_Properties::Period", num(period, unit)))
    if cet is not None:
        low, high = cet if isinstance(cet, tuple) else (cet, cet)
        out.append(pa("Timing_Properties::Compute_Execution_Time", span(low, high, unit)))
    return component(name, "thread", props=[*out, *props])


def bind(obj, *targets, prop="Deployment_Properties::Actual_Processor_Binding"):
    obj.ownedPropertyAssociations.append(pa(prop, ref(*targets)))
    return obj


def system(*children, name="sys_i_Instance"):
    root = new("SystemInstance", name=name, category="system")
    root.componentInstances.extend(children)
    return root


def messages(result, severity=None):
    return [(d.location.path, d.message) for d in result.diagnostics if severity in (None, d.severity)]


# =============================================================================== CPU and MIPS


def test_thread_mips_is_cet_over_period_times_the_bound_processor_mips():
    t1, t2 = thread("t1", 10, 2, "ms"), thread("t2", 20, 5, "ms")
    cpu = processor("cpu", 2000)
    node = bind(component("node", "process", t1, t2), cpu)
    for t in (t1, t2):
        bind(t, cpu)  # inherited onto the threads, as instantiation resolves it
    result = analyze_resources(system(cpu, node))
    row = result.processor("sys_i_Instance.cpu")
    assert row.capacity_mips == 2000 and row.demand_mips == 900 and row.load_percent == 45
    assert row.utilization == Fraction(45, 100)
    assert [(t.path, t.mips, t.load_percent, t.period_us, t.cet_us) for t in row.threads] == [
        ("sys_i_Instance.node.t1", 400, 20, 10_000, 2000),
        ("sys_i_Instance.node.t2", 500, 25, 20_000, 5000),
    ]
    # the process is the outermost bound component: one row for it, then its threads
    assert [(c.path, c.actual) for c in row.components] == [
        ("sys_i_Instance.node", 900),
        ("sys_i_Instance.node.t1", 400),
        ("sys_i_Instance.node.t2", 500),
    ]
    assert result.ok


def test_overload_is_an_error_on_the_processor():
    cpu = processor("core", 1100)
    t = bind(thread("work", 33333, 40000), cpu)
    result = analyze_resources(system(cpu, component("n", "process", t)))
    row = result.processor("sys_i_Instance.core")
    assert row.load_percent == Fraction(40000, 33333) * 100
    assert row.demand_mips == Fraction(40000, 33333) * 1100
    assert row.overloaded and not result.ok
    (path, message), *_ = messages(result, "error")
    assert path == "sys_i_Instance.core" and "exceeds MIPS capacity" in message


def test_processor_capacity_when_there_is_no_mips_capacity():
    cpu = component("cpu", "processor", props=[pa("Timing_Properties::Processor_Capacity", num(1.5, "GIPS"))])
    t = bind(thread("t", 10, 1, "ms"), cpu)
    row = analyze_resources(system(cpu, component("p", "process", t))).processors[0]
    assert row.capacity_mips == 1500 and row.demand_mips == 150


def test_decimal_values_are_exact():
    cpu = processor("cpu", 99.36)
    t = bind(thread("t", 0.1, 0.03, "sec"), cpu)
    row = analyze_resources(system(cpu, component("p", "process", t))).processors[0]
    assert row.demand_mips == Fraction(3, 10) * Fraction(9936, 100)
    assert row.threads[0].period_us == 100_000 and row.threads[0].cet_us == 30_000


def test_virtual_processors_pass_the_load_to_their_processor():
    cpu = processor("cpu", 1000)
    vp = bind(processor("vp", None, category="virtual processor", budget=300), cpu)
    inner = processor("part", None, category="virtual processor", budget=100)
    cpu.componentInstances.append(inner)  # contained, not bound: runs on cpu
    a = bind(thread("a", 10, 1, "ms"), vp)
    b = bind(thread("b", 10, 2, "ms"), inner)
    result = analyze_resources(system(cpu, vp, component("p", "process", a, b)))
    assert result.processor("sys_i_Instance.cpu").demand_mips == 300  # (0.1 + 0.2) x 1000
    vp_row = result.processor("sys_i_Instance.vp")
    assert vp_row.capacity_mips == 300 and vp_row.demand_mips == 100
    assert result.processor("sys_i_Instance.cpu.part").demand_mips == 200
    assert result.processor("sys_i_Instance.cpu.part").overloaded
    assert bound_processor(b) is cpu and bound_processor(a) is cpu


def test_cores_and_their_multi_core_processor():
    c1, c2 = processor("c1", 1500), processor("c2", 1500)
    soc = processor("soc", None, c1, c2)
    t1 = bind(thread("t1", 100, 25, "ms"), c1)
    t2 = bind(thread("t2", 100, 50, "ms"), c2)
    result = analyze_resources(system(soc, component("p", "process", t1, t2)))
    assert result.processor("sys_i_Instance.soc.c1").load_percent == 25
    assert result.processor("sys_i_Instance.soc.c2").load_percent == 50
    whole = result.processor("sys_i_Instance.soc")
    assert whole.capacity_mips == 3000 and whole.demand_mips == 1125 and whole.load_percent == Fraction(75, 2)
    assert whole.cores == ("sys_i_Instance.soc.c1", "sys_i_Instance.soc.c2")
    # rows in model order: the processor, then its cores
    assert [p.path for p in result.processors][:3] == [
        "sys_i_Instance.soc",
        "sys_i_Instance.soc.c1",
        "sys_i_Instance.soc.c2",
    ]


def test_instructions_per_dispatch_and_budgets_without_cet():
    cpu = processor("cpu", 500)
    ipd = thread("ipd", 10, None, "ms", props=[pa("SEI::InstructionsPerDispatch", span(1, 2, "MIPD"))])
    idle = thread("idle", 10, None, "ms")
    node = bind(component("n", "process", ipd, props=[pa("SEI::MIPSBudget", num(50.0, "MIPS"))]), cpu)
    quiet = bind(component("q", "process", idle, props=[pa("SEI::MIPSBudget", num(30.0, "MIPS"))]), cpu)
    for t, owner in ((ipd, node), (idle, quiet)):
        bind(t, cpu)
        assert t.eContainer() is owner
    result = analyze_resources(system(cpu, node, quiet))
    row = result.processor("sys_i_Instance.cpu")
    # 2 MIPD every 10 ms = 200 MIPS (over the 50 MIPS budget); the quiet node counts its budget
    assert row.demand_mips == 230
    assert (
        "sys_i_Instance.n",
        "process needs 200.000 MIPS, more than its SEI::MIPSBudget 50.000 MIPS",
    ) in messages(result, "error")
    assert any("no Compute_Execution_Time" in m for _p, m in messages(result, "warning"))


def test_reference_processor_from_the_declarative_model():
    ws = new("AadlModel", name="ws")
    arm = new(
        "ComponentType",
        name="ARM",
        category="processor",
        ownedPropertyAssociations=[pa("SEI::MIPSCapacity", num(1000.0, "MIPS"))],
    )
    ws.units.append(new("AadlPackage", name="Chips", classifiers=[arm]))
    cpu = processor("cpu", 2000)
    t = thread(
        "t",
        10,
        2,
        "ms",
        props=[pa("Timing_Properties::Reference_Processor", new("ClassifierValue", classifier="Chips::ARM"))],
    )
    root = system(cpu, component("p", "process", bind(t, cpu)))
    ws.instances.append(root)
    row = analyze_resources(ws).processor("sys_i_Instance.cpu")
    assert row.demand_mips == 200 and row.load_percent == 10  # measured on a 1000 MIPS core


# =============================================================================== memory


def test_memory_loads():
    ram = component(
        "ram",
        "memory",
        props=[
            pa("SEI::RAMCapacity", num(64, "KByte")),
            pa("Memory_Properties::Memory_Size", num(1, "MByte")),
        ],
    )
    t = thread(
        "t",
        10,
        1,
        "ms",
        props=[
            pa("Memory_Properties::Stack_Size", num(40, "KByte")),
            pa("Memory_Properties::Code_Size", num(100, "KByte")),
        ],
    )
    node = component("p", "process", t, props=[pa("Memory_Properties::Data_Size", num(32, "KByte"))])
    bind(node, ram, prop="Deployment_Properties::Actual_Memory_Binding")
    bind(t, ram, prop="Deployment_Properties::Actual_Memory_Binding")
    result = analyze_resources(system(ram, node))
    loads = {m.kind: m for m in result.memories}
    assert loads["RAM"].demand_kbyte == 72 and loads["RAM"].capacity_kbyte == 64
    assert loads["Memory"].demand_kbyte == 172 and loads["Memory"].capacity_kbyte == 1000
    assert [c.path for c in loads["RAM"].components] == ["sys_i_Instance.p"]
    assert any("exceeds the RAM capacity" in m for _p, m in messages(result, "error"))


# =============================================================================== not bound


def test_not_bound_budgets():
    cpus = [processor("a", 1000), processor("b", None)]
    n1 = component(
        "n1",
        "process",
        thread("w", 10, 5, "ms", props=[pa("SEI::MIPSBudget", num(10.0, "MIPS"))]),
        props=[pa("SEI::MIPSBudget", num(600.0, "MIPS"))],
    )
    n2 = component(
        "n2", "process", thread("x", 10, None, "ms"), props=[pa("SEI::MIPSBudget", num(700.0, "MIPS"))]
    )
    root = system(*cpus, n1, n2)
    bind(n1.componentInstances[0], cpus[0])
    result = analyze_budgets(root)
    total = result.total("MIPS")
    assert total.capacity == 1000 and total.resources == 2 and total.resources_with_capacity == 1
    # n1: its thread demands 0.5 x 1000 = 500 (over the thread's 10 MIPS budget, under n1's 600)
    rows = {r.path: r for r in total.rows}
    assert rows["sys_i_Instance.n1"].actual == 500 and "slack" in rows["sys_i_Instance.n1"].note
    assert rows["sys_i_Instance.n1.w"].actual == 500
    # n2: nothing below it demands MIPS: its row shows 0, and its budget counts in the total
    assert rows["sys_i_Instance.n2"].actual == 0 and rows["sys_i_Instance.n2"].budget == 700
    assert total.budget == 1200 and total.over_capacity
    errors = messages(result, "error")
    assert (
        "sys_i_Instance.n1.w",
        "thread needs 500.000 MIPS, more than its SEI::MIPSBudget 10.000 MIPS",
    ) in errors
    assert any("budgets over capacity" in m for _p, m in errors)
    assert any("1 out of 2 with MIPS capacity" in m for _p, m in messages(result, "warning"))
    assert result.as_dict()["totals"][0]["budget_mips"] == 1200


# =============================================================================== modes


def test_modal_threads_and_values():
    cpu = processor("cpu", 1000)
    fast = bind(thread("fast", 10, 1, "ms"), cpu)
    fast.ownedPropertyAssociations[-2].ownedValues.clear()
    fast.ownedPropertyAssociations[-2].ownedValues.extend(
        [
            new("ModalPropertyValue", value=span(1, 1, "ms"), inModes=["nominal"]),
            new("ModalPropertyValue", value=span(4, 4, "ms"), inModes=["degraded"]),
        ]
    )
    extra = bind(thread("extra", 10, 5, "ms"), cpu)
    extra.inModes.append("degraded")
    node = component("p", "process", fast, extra)
    modes = [new("ModeInstance", name=n, mode=n, initial=n == "nominal") for n in ("nominal", "degraded")]
    node.modeInstances.extend(modes)
    root = system(cpu, node)
    root.systemOperationModes.extend(
        new("SystemOperationMode", name=f"som_{i}", currentModes=[m]) for i, m in enumerate(modes)
    )
    assert [m.label for m in system_modes(root)] == ["(p.nominal)", "(p.degraded)"]
    result = analyze_resources(root)
    nominal, degraded = (result.processor("sys_i_Instance.cpu", m) for m in ("(p.nominal)", "(p.degraded)"))
    assert nominal.demand_mips == 100 and [t.path for t in nominal.threads] == ["sys_i_Instance.p.fast"]
    assert degraded.demand_mips == 900 and len(degraded.threads) == 2
    assert result.as_dict()["processors"][0]["mode"] == "(p.nominal)"


def test_property_reader_conversions():
    reader = PropertyReader()
    holder = component(
        "x",
        "system",
        props=[
            pa("Timing_Properties::Period", num(33333, "us")),
            pa("SEI::BandWidthCapacity", num(480, "Mbps")),
            pa("Memory_Properties::Data_Size", num(921, "KByte")),
            pa("SEI::MIPSCapacity", num(2.5, "GIPS")),
        ],
    )
    assert reader.seconds(holder, "Period") == Fraction(33333, 1_000_000)
    assert reader.number(holder, "SEI::BandWidthCapacity", "KBytesps") == 60_000
    assert reader.size_kbyte(holder, "Data_Size") == 921
    assert reader.mips_capacity(holder) == 2500
    assert reader.number(holder, "Period", "KByte") is None  # a time is not a size: diagnosed
    assert reader.diagnostics and reader.diagnostics[0].location.path == "x"
    assert SystemMode("No Modes").label == ""


# =============================================================================== bad input


def _bad_models():
    cpu = processor("cpu", 1000)
    mem = component("mem", "memory")

    def case(t, *extra):
        return system(cpu, mem, component("p", "process", t), *extra)

    no_period = bind(thread("t", None, 5, "ms"), cpu)
    no_cet = bind(thread("t", 10, None, "ms"), cpu)
    zero = bind(thread("t", 0, 1, "ms"), cpu)
    to_memory = bind(thread("t", 10, 1, "ms"), mem)
    to_process = thread("t", 10, 1, "ms")
    unresolved = thread("t", 10, 1, "ms")
    unresolved.ownedPropertyAssociations.append(
        pa(
            "Deployment_Properties::Actual_Processor_Binding",
            new("ListValue", ownedItems=[new("ReferenceValue", path="gone")]),
        )
    )
    text_period = thread(
        "t", None, 1, "ms", props=[pa("Timing_Properties::Period", new("StringValue", value="fast"))]
    )
    bind(text_period, cpu)
    root_to_process = case(to_process)
    bind(to_process, root_to_process.componentInstances[2])
    return {
        "missing Period": (case(no_period), "error", "has no Period"),
        "missing Compute_Execution_Time": (case(no_cet), "warning", "no Compute_Execution_Time"),
        "zero period": (case(zero), "error", "Period is 0 us"),
        "binding to a memory": (case(to_memory), "error", "not a processor"),
        "binding to a process": (root_to_process, "error", "not a processor"),
        "unresolved binding": (case(unresolved), "warning", "does not resolve"),
        "period that is not a number": (case(text_period), "error", "is not a number"),
    }


@pytest.mark.parametrize("case", sorted(_bad_models()))
@pytest.mark.parametrize("analysis", [analyze_resources, analyze_budgets])
def test_bad_input_gives_a_diagnostic_naming_the_thread(case, analysis):
    root, severity, text = _bad_models()[case]
    result = analysis(root)
    found = [d for d in result.diagnostics if text in d.message]
    if analysis is analyze_budgets and case in (
        "binding to a memory",
        "binding to a process",
        "unresolved binding",
    ):
        return  # bindings do not matter to not-bound budgets; it must simply not crash
    assert found, f"{case}: {messages(result)}"
    assert found[0].severity == severity
    assert found[0].location.path == "sys_i_Instance.p.t"


def test_not_an_instance():
    with pytest.raises(ModelError):
        analyze_resources(new("AadlModel", name="empty"))
    with pytest.raises(ModelError):
        analyze_resources("not a model")


def test_json_shape_is_the_issues():
    cpu = processor("cpu", 2000)
    t = bind(thread("t", 33333, 2319), cpu)
    data = analyze_resources(system(cpu, component("n", "process", t))).as_dict()
    (row,) = data["processors"]
    assert list(row) == ["path", "capacity_mips", "demand_mips", "load_percent", "threads"]
    assert list(row["threads"][0]) == ["path", "period_us", "cet_us", "load_percent", "mips_demand"]
    assert row["threads"][0]["mips_demand"] == pytest.approx(2319 / 33333 * 2000)


# =============================================================================== Table 2

# (node package, process, publisher thread, work thread Period, publisher Period, bandwidth in KB/s
# as the paper prints it) and the paper's figures per PDM:
# (CPU load %, MIPS demand as the paper prints it or None) for xu4_a15, xu4_a7, xavier_carmel, rpi4_a72
TABLE2 = {
    ("nd_usb_cam", "usb_cam_nd", "image_broadcaster", 33333, 33333, "27630"): [
        ("6.96", 139),
        ("55.50", 610),
        ("7.59", 182),
        ("25.23", 378),
    ],
    ("nd_pos_to_cmd", "pos_to_cmd_nd", "cmd_publisher", 100000, 100000, "0.48"): [
        ("0.70", None),
        ("1.06", None),
        ("0.29", None),
        ("0.10", None),
    ],
    ("nd_ocv_color_tracking", "ocv_color_tracking_nd", "point_broadcaster", 33333, 100000, "0.24"): [
        ("111.00", None),
        ("120.00", None),
        ("12.38", None),
        ("21.85", None),
    ],
}
CORES = [
    ("xu4_a15", "Exynos_5422", "ARM_A15", 2000),
    ("xu4_a7", "Exynos_5422", "ARM_A7", 1100),
    ("xavier_carmel", "Carmel", "Carmel_core", 2400),
    ("rpi4_a72", "BCM2711", "Cortex_A72", 1500),
]


def _table2_text() -> str:
    withs = sorted({k[0] for k in TABLE2} | {c[1] for c in CORES})
    lines = [
        "package table2_deployments",
        "public",
        f"  with {', '.join(withs)};",
        "  system top",
        "  end top;",
    ]
    for package, process, _publisher, _period, _publishing, _bw in TABLE2:
        for pdm, soc, core, _mips in CORES:
            lines += [
                f"  system implementation top.{process}_{pdm}",
                "    subcomponents",
                f"      core: processor {soc}::{core}.impl;",
                f"      node: process {package}::{process}.{pdm};",
                "    properties",
                "      Actual_Processor_Binding => (reference (core)) applies to node;",
                f"  end top.{process}_{pdm};",
            ]
    lines.append("end table2_deployments;")
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def table2_workspace(tmp_path_factory):
    from rosaadl.importers import aadl_text

    path = tmp_path_factory.mktemp("table2") / "table2_deployments.aadl"
    path.write_text(_table2_text(), encoding="utf-8")
    return aadl_text.read_files([path], include_library=True)


@pytest.mark.parametrize("node", sorted(TABLE2), ids=lambda k: k[1])
def test_paper_table2_single_node_deployments(table2_workspace, node):
    """CPU load % = CET / Period, MIPS demand = load x MIPSCapacity, bandwidth = Data_Size / Period,
    for each library node on each of the four cores, as the paper computes them."""
    from rosaadl.transforms.instantiate import instantiate

    _package, process, publisher, period_us, publisher_period_us, bandwidth = node
    for (pdm, _soc, _core, mips), (load_text, paper_mips) in zip(CORES, TABLE2[node], strict=True):
        root = instantiate(table2_workspace, f"table2_deployments::top.{process}_{pdm}")
        result = analyze_resources(root)
        row = result.processor(f"{root.name}.core")
        work = [t for t in row.threads if t.cet_us is not None]
        assert len(work) == 1, f"{process}.{pdm}: one thread with Compute_Execution_Time"
        (thread_row,) = work
        assert thread_row.period_us == period_us
        load = thread_row.cet_us / thread_row.period_us
        assert thread_row.utilization == load
        assert row.capacity_mips == mips
        assert row.load_percent == load * 100  # the node's only measured thread
        assert row.demand_mips == load * mips
        assert f"{float(load * 100):.2f}" == load_text, f"{process}.{pdm}"
        if paper_mips is not None:
            assert int(row.demand_mips) == paper_mips  # the paper drops the decimals
        ports = {p.path.rpartition(".")[0].rpartition(".")[2]: p for p in port_loads(root)}
        published = ports[publisher]
        assert published.kbytesps == published.data_size_bytes / 1000 / (
            Fraction(publisher_period_us) / 1_000_000
        )
        printed = (
            f"{float(published.kbytesps):.2f}" if published.kbytesps < 1 else str(int(published.kbytesps))
        )
        assert printed == bandwidth

"""The data behind the report: what the page draws and what ``report.json`` holds.

:func:`build_view` reads an instance and its :class:`~rosaadl.analysis.report.AnalysisReport`
once and returns plain, JSON-ready data (numbers as ``int``/``float``, no model objects), in a
fixed order, so that the HTML page and ``report.json`` always agree and the same input gives the
same bytes:

* ``findings``: the verdict, the headline figures (highest core load, overloaded cores, highest
  bus load, schedulable domains, deadline misses, worst end-to-end latency) and the errors and
  warnings of the analyses;
* ``cpu``: one row per processor (core, virtual processor) with its capacity, demand, load and
  the share of every thread bound to it;
* ``bus``: one row per bus and virtual bus (capacity, budget, required, actual, load);
* ``schedule``: the simulated schedule over one hyperperiod (see :func:`schedule_view`);
* ``architecture``: the ROS nodes (processes) and devices, the topics between them (port
  connections, with the topic name, data type, bandwidth and bus), the hardware tree down to the
  cores, and the bindings of nodes to cores.

Every node gets one colour, used for its threads in the CPU bars, the Gantt chart and the
architecture diagram alike.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.rendering import as_float, short_path
from rosaadl.errors import Diagnostic, RosaadlError
from rosaadl.model import component_instances

__all__ = [
    "MAX_GANTT_JOBS",
    "NODE_PALETTE",
    "DEVICE_COLOUR",
    "build_view",
    "schedule_view",
    "short_path",
    "number",
]

log = logging.getLogger(__name__)

#: At most this many jobs are simulated for the Gantt chart (a longer hyperperiod is cut short).
MAX_GANTT_JOBS = 2000

#: Node colours (Tableau 10 without its red, which marks overloads and misses), in node order.
NODE_PALETTE = (
    "#4e79a7",
    "#f28e2b",
    "#59a14f",
    "#b07aa1",
    "#76b7b2",
    "#edc948",
    "#9c755f",
    "#ff9da7",
    "#2f4b7c",
    "#a0cbe8",
)
DEVICE_COLOUR = "#8c8c8c"


# =============================================================================== small helpers


def number(value: Any) -> int | float | None:
    """An exact or float value as JSON number (``Fraction(3, 1)`` → ``3``); None stays None."""
    if value is None or isinstance(value, bool):
        return None
    if isinstance(value, int):
        return value
    if isinstance(value, Fraction):
        if value.denominator == 1:
            return value.numerator
        value = as_float(value)  # beyond the float range: an infinity, shown as no number
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    return None


def _category(obj: Any) -> str:
    value = getattr(obj, "category", None)
    return getattr(value, "name", str(value or ""))


def _tint(colour: str, amount: float) -> str:
    """``colour`` mixed with white (``amount`` 0 → itself, 1 → white)."""
    r, g, b = (int(colour[i : i + 2], 16) for i in (1, 3, 5))
    mix = [round(c + (255 - c) * amount) for c in (r, g, b)]
    return "#{:02x}{:02x}{:02x}".format(*mix)


_THREAD_TINTS = (0.0, 0.38, 0.62, 0.2, 0.5)


def _diag(d: Diagnostic) -> dict[str, Any]:
    return {
        "severity": d.severity,
        "message": d.message,
        "path": d.location.path or "",
        "file": d.location.file,
    }


# =============================================================================== nodes


@dataclass
class _Node:
    key: str
    name: str
    kind: str  # "process" | "device"
    classifier: str
    colour: str
    threads: list[str]
    order: int


class _Nodes:
    """Processes (ROS nodes) and devices of the instance, with their colours."""

    def __init__(self, components: list[Any]) -> None:
        from rosaadl.model import instance_path

        self.nodes: list[_Node] = []
        self.by_key: dict[str, _Node] = {}
        self.owner: dict[int, _Node] = {}  # id(component instance) → its node
        self.thread_colour: dict[str, str] = {}
        palette_index = 0
        for ci in components:
            kind = _category(ci)
            if kind not in ("process", "device"):
                continue
            path = instance_path(ci)
            if kind == "process":
                colour = NODE_PALETTE[palette_index % len(NODE_PALETTE)]
                palette_index += 1
            else:
                colour = DEVICE_COLOUR
            node = _Node(path, ci.name or "", kind, ci.classifier or "", colour, [], len(self.nodes))
            self.nodes.append(node)
            self.by_key[path] = node
            for sub in component_instances(ci):
                self.owner.setdefault(id(sub), node)
                if _category(sub) == "thread":
                    node.threads.append(instance_path(sub))
        self._tinted: dict[str, int] = {}

    def node_of_path(self, path: str) -> _Node | None:
        """The node whose instance path is ``path`` or a prefix of it."""
        best = None
        for node in self.nodes:
            if (path == node.key or path.startswith(node.key + ".")) and (
                best is None or len(node.key) > len(best.key)
            ):
                best = node
        return best

    def colour_of(self, path: str) -> str:
        """The colour of a thread: its node's, lightened for the node's second, third, … thread
        in the order they are first asked for (the threads that appear in the charts); with a
        single node, the palette's colours in that order."""
        colour = self.thread_colour.get(path)
        if colour is not None:
            return colour
        node = self.node_of_path(path)
        if node is None:
            return DEVICE_COLOUR
        if path == node.key:
            return node.colour
        index = self._tinted.get(node.key, 0)
        self._tinted[node.key] = index + 1
        if sum(1 for n in self.nodes if n.kind == "process") == 1:
            # one node (a Cheddar address space, a single process): its threads get the palette
            colour = NODE_PALETTE[index % len(NODE_PALETTE)]
        else:
            colour = _tint(node.colour, _THREAD_TINTS[index % len(_THREAD_TINTS)])
        self.thread_colour[path] = colour
        return colour

    def owner_of(self, obj: Any) -> _Node | None:
        current = obj
        while current is not None:
            node = self.owner.get(id(current))
            if node is not None:
                return node
            current = current.eContainer()
        return None


# =============================================================================== cpu and bus


def _cpu_rows(report: Any, nodes: _Nodes) -> list[dict[str, Any]]:
    if report.cpu is None:
        return []
    rows = []
    for p in report.cpu.processors:
        capacity = p.capacity_mips
        segments = []
        for t in p.threads:
            if t.mips <= 0 and not t.utilization:
                continue
            if capacity > 0:
                percent = t.mips / capacity * 100
            elif t.utilization is not None:
                percent = t.utilization * 100
            else:
                continue
            node = nodes.node_of_path(t.path)
            segments.append(
                {
                    "thread": t.path,
                    "node": node.key if node is not None else "",
                    "node_label": short_path(node.key) if node is not None else "",
                    "node_colour": node.colour if node is not None else DEVICE_COLOUR,
                    "percent": number(percent),
                    "mips": number(t.mips),
                    "colour": nodes.colour_of(t.path),
                }
            )
        load = p.load_percent
        if load is None and p.utilization:
            load = p.utilization * 100
        rows.append(
            {
                "path": p.path,
                "label": short_path(p.path),
                "category": p.category,
                "mode": p.mode,
                "capacity_mips": number(capacity),
                "demand_mips": number(p.demand_mips),
                "load_percent": number(load),
                "utilization_percent": number(p.utilization * 100),
                "overloaded": bool(p.overloaded or (load is not None and load > 100)),
                "cores": list(p.cores),
                "segments": segments,
            }
        )
    return rows


def _bus_rows(report: Any) -> list[dict[str, Any]]:
    if report.bus is None:
        return []
    rows = []
    for som in report.bus.modes:

        def add(bus: Any, depth: int, mode: str = som.label) -> None:
            rows.append(
                {
                    "path": bus.path,
                    "label": short_path(bus.path),
                    "virtual": bus.virtual,
                    "depth": depth,
                    "mode": mode,
                    "capacity_kbps": number(bus.capacity_kbps),
                    "budget_kbps": number(bus.budget_kbps),
                    "required_kbps": number(bus.required_kbps),
                    "actual_kbps": number(bus.actual_kbps),
                    "load_percent": number(bus.load_percent),
                    "overloaded": bool(bus.capacity_kbps > 0 and bus.actual_kbps > bus.capacity_kbps),
                    "connections": [
                        {
                            "name": c.name,
                            "budget_kbps": number(c.budget_kbps),
                            "actual_kbps": number(c.actual_kbps),
                        }
                        for c in bus.connections
                    ]
                    + [
                        {
                            "name": b.label,
                            "budget_kbps": number(b.budget_kbps),
                            "actual_kbps": number(b.actual_kbps),
                        }
                        for b in bus.broadcasts
                    ],
                }
            )
            for vb in bus.virtual_buses:
                add(vb, depth + 1)

        for bus in som.buses:
            add(bus, 0)
    return rows


# =============================================================================== schedule


def _choose_horizon(taskset: Any, schedulability: Any = None) -> tuple[Any, str]:
    """The simulated window: one hyperperiod of the whole task set when it is short enough to
    draw, else the longest feasibility interval of one core (as the schedulability analysis
    found it, when it ran), else as many jobs as fit."""
    from rosaadl.analysis.schedulability import feasibility_interval, hyperperiod
    from rosaadl.analysis.simulation import job_count
    from rosaadl.analysis.tasks import exact_time

    unit = taskset.time_unit
    periods = [t.period for t in taskset.tasks if t.period is not None]
    tasks = list(taskset.tasks)
    if not periods:
        end = max(Fraction(t.offset) + Fraction(t.deadline or t.capacity) for t in tasks)
        return exact_time(end), "until every job has reached its deadline"
    whole = hyperperiod(periods)
    if job_count(tasks, Fraction(whole)) <= MAX_GANTT_JOBS:
        return whole, "one hyperperiod of the task set"
    per_core = []
    if schedulability is not None:
        per_core = [d.feasibility_interval.length for d in schedulability.domains if d.feasibility_interval]
    else:
        for processor, _core, domain_tasks in taskset.domains():
            if not domain_tasks:
                continue
            interval = feasibility_interval(domain_tasks, processor.scheduler)
            if interval is not None:
                per_core.append(interval.length)
    longest = max(per_core, default=None)
    if longest is not None and job_count(tasks, Fraction(longest)) <= MAX_GANTT_JOBS:
        return longest, (
            "the longest hyperperiod of one core; "
            f"the whole task set's hyperperiod, {_time_text(whole, unit)}, "
            f"would release {_count(job_count(tasks, Fraction(whole)))} jobs"
        )
    rate = sum((Fraction(1) / Fraction(p) for p in periods), Fraction(0))
    length = exact_time(Fraction(max(1, math.floor(MAX_GANTT_JOBS / rate))))
    return length, (
        f"the first {_time_text(length, unit)} only; one hyperperiod, {_time_text(whole, unit)}, "
        f"would release {_count(job_count(tasks, Fraction(whole)))} jobs"
    )


def _clip(text: str, size: int) -> str:
    return text if len(text) <= size else text[: size - 1] + "…"


def _count(value: int) -> str:
    """An integer with thin spaces between thousands (233\u2009333)."""
    return f"{value:,}".replace(",", "\u2009")


def _time_text(value: Any, unit: str) -> str:
    scale = {
        "ps": Fraction(1, 10**12),
        "ns": Fraction(1, 10**9),
        "us": Fraction(1, 10**6),
        "ms": Fraction(1, 1000),
    }
    factor = scale.get(unit)
    if factor is None:
        return f"{float(value):g} {unit}"
    seconds = Fraction(value) * factor
    for name, size in (("s", Fraction(1)), ("ms", Fraction(1, 1000)), ("us", Fraction(1, 10**6))):
        if seconds >= size:
            return f"{float(seconds / size):.4g} {name}"
    return f"{float(seconds * 10**9):.4g} ns"


def schedule_view(
    root: Any,
    nodes: _Nodes | None = None,
    simulation: Any = None,
    *,
    taskset: Any = None,
    schedulability: Any = None,
) -> dict[str, Any]:
    """The Gantt chart's data: rows (one per core with tasks), intervals, releases and missed
    deadlines, over the window of ``simulation`` when it recorded its schedule, else over one
    hyperperiod simulated here (see :func:`_choose_horizon`). ``taskset`` and ``schedulability``:
    what the analyses already extracted and found (else extracted and computed here)."""
    from rosaadl.analysis.simulation import simulate
    from rosaadl.analysis.tasks import taskset_from_instance

    nodes = nodes or _Nodes(component_instances(root))
    empty: dict[str, Any] = {
        "available": False,
        "reason": "",
        "time_unit": "us",
        "horizon": 0,
        "note": "",
        "rows": [],
        "tasks": [],
        "intervals": [],
        "misses": [],
        "releases": [],
        "deadline_misses": 0,
    }
    if taskset is None:
        try:
            taskset = taskset_from_instance(root)
        except RosaadlError as exc:
            return {**empty, "reason": f"no task set: {exc.message}"}
    if not taskset.tasks:
        return {**empty, "reason": "no thread has both a period (or dispatch) and an execution time"}
    if simulation is not None and simulation.schedule:
        note = "as simulated by the analyses"
        result = simulation
    else:
        horizon, note = _choose_horizon(taskset, schedulability)
        try:
            result = simulate(taskset, horizon=horizon, max_jobs=MAX_GANTT_JOBS * 2)
        except RosaadlError as exc:
            return {**empty, "reason": f"simulation failed: {exc.message}"}
    horizon_all = max(result.horizons.values(), default=0)
    rows = []
    for processor, core, domain_tasks in taskset.domains():
        if not domain_tasks:
            continue
        key = (processor.name, core)
        label = short_path(processor.path) + (f".{core}" if core else "")
        rows.append(
            {
                "processor": processor.name,
                "core": core,
                "label": label,
                "scheduler": processor.scheduler.value,
                "horizon": number(result.horizons.get(key, horizon_all)),
                "tasks": [t.name for t in domain_tasks],
            }
        )
    tasks = []
    for task in taskset.tasks:
        node = nodes.node_of_path(task.path)
        tasks.append(
            {
                "name": task.name,
                "path": task.path,
                "label": short_path(task.path),
                "node": node.key if node is not None else "",
                "node_label": short_path(node.key) if node is not None else "",
                "node_colour": node.colour if node is not None else DEVICE_COLOUR,
                "colour": nodes.colour_of(task.path),
                "period": number(task.period),
                "capacity": number(task.capacity),
                "deadline": number(task.deadline),
                "priority": task.priority,
            }
        )
    intervals = [
        [number(i.start), number(i.end), i.task, i.job, i.processor, i.core] for i in result.schedule
    ]
    misses = []
    releases = []
    domain_of = {t.name: (t.processor, t.core) for t in taskset.tasks}
    for job in result.jobs:
        releases.append([job.task, number(job.release)])
        horizon = result.horizons.get(domain_of.get(job.task, ("", "")), horizon_all)
        missed = job.missed
        if missed is None and job.deadline is not None and job.deadline <= horizon:
            missed = True  # unfinished at its deadline
        if missed:
            misses.append(
                {
                    "task": job.task,
                    "job": job.job,
                    "release": number(job.release),
                    "deadline": number(job.deadline),
                    "completion": number(job.completion),
                }
            )
    return {
        "available": True,
        "reason": "",
        "time_unit": result.time_unit,
        "horizon": number(horizon_all),
        "horizon_text": _time_text(horizon_all, result.time_unit),
        "note": note,
        "rows": rows,
        "tasks": tasks,
        "intervals": intervals,
        "misses": misses,
        "releases": releases,
        "deadline_misses": len(misses),
    }


# =============================================================================== architecture


def _topic_label(reader: Any, conn: Any) -> tuple[str, str]:
    """(topic name or "", data type) of a port connection instance."""
    topic = ""
    data_type = ""
    ends = [conn.source]
    for ref in conn.connectionReferences:
        ends += [ref.source, ref.destination]
    for end in ends:
        if end is None or not hasattr(end, "featureInstances"):
            continue
        if not topic:
            value = reader.value(end, "ROS_Properties::Topic_Name")
            if isinstance(value, str) and value:
                topic = value
        if not data_type and getattr(end, "classifier", None):
            data_type = end.classifier.rpartition("::")[2]
    return topic, data_type


def _hardware(root: Any, components: list[Any]) -> tuple[list[dict[str, Any]], dict[str, str]]:
    """The hardware tree down to the cores (processors without processor children), with
    single-child chains folded into one box; and core path → path of its top box."""
    from rosaadl.model import instance_path

    cores = [
        ci
        for ci in components
        if _category(ci) == "processor"
        and not any(_category(c) == "processor" for c in ci.componentInstances)
    ]
    tree: dict[int, dict[str, Any]] = {}
    top: list[dict[str, Any]] = []
    loose: dict[str, Any] | None = None
    for core in cores:
        chain = []
        current = core.eContainer()
        while current is not None and current is not root and hasattr(current, "componentInstances"):
            chain.append(current)
            current = current.eContainer()
        chain.reverse()
        entry = {"path": instance_path(core), "name": core.name or "", "classifier": core.classifier or ""}
        if not chain:
            if loose is None:
                loose = {"path": "", "name": "processors", "classifier": "", "children": [], "cores": []}
                top.append(loose)
            loose["cores"].append(entry)
            continue
        parent_box: dict[str, Any] | None = None
        for ci in chain:
            box = tree.get(id(ci))
            if box is None:
                box = {
                    "path": instance_path(ci),
                    "name": ci.name or "",
                    "classifier": ci.classifier or "",
                    "children": [],
                    "cores": [],
                }
                tree[id(ci)] = box
                (parent_box["children"] if parent_box is not None else top).append(box)
            parent_box = box
        assert parent_box is not None
        parent_box["cores"].append(entry)

    def fold(box: dict[str, Any]) -> dict[str, Any]:
        while not box["cores"] and len(box["children"]) == 1:
            child = box["children"][0]
            box = {
                **child,
                "name": f"{box['name']} › {child['name']}",
                "classifier": child["classifier"] or box["classifier"],
            }
        box["children"] = [fold(c) for c in box["children"]]
        return box

    boxes = [fold(b) for b in top]
    owner: dict[str, str] = {}

    def collect(box: dict[str, Any], top_path: str) -> None:
        for c in box["cores"]:
            owner[c["path"]] = top_path
        for child in box["children"]:
            collect(child, top_path)

    for box in boxes:
        collect(box, box["path"])
    return boxes, owner


def _architecture(root: Any, components: list[Any], nodes: _Nodes, report: Any) -> dict[str, Any]:
    from rosaadl.analysis.instance_values import PropertyReader, bound_processor
    from rosaadl.model import instance_path

    reader = PropertyReader([])
    port_kbps: dict[str, Any] = {}
    if report.bus is not None:
        for port in report.bus.ports:
            port_kbps[port.path] = port.kbytesps
    topics: dict[tuple[str, str, str], dict[str, Any]] = {}
    connected: set[str] = set()
    for ci in components:
        for conn in ci.connectionInstances:
            kind = getattr(conn.kind, "name", str(conn.kind or ""))
            if kind != "portConnection" or conn.source is None or conn.destination is None:
                continue
            src = nodes.owner_of(conn.source)
            dst = nodes.owner_of(conn.destination)
            if src is None or dst is None or src is dst:
                continue
            topic, data_type = _topic_label(reader, conn)
            label = topic or data_type or conn.name or ""
            key = (src.key, dst.key, label)
            buses = [instance_path(b) for b in (reader.targets(conn, "Actual_Connection_Binding") or [])]
            kbps = port_kbps.get(instance_path(conn.source))
            entry = topics.get(key)
            if entry is None:
                topics[key] = {
                    "source": src.key,
                    "target": dst.key,
                    "topic": topic,
                    "data_type": data_type,
                    "label": label,
                    "kbps": number(kbps),
                    "buses": [short_path(b) for b in buses],
                    "connections": [conn.name or ""],
                }
            else:
                entry["connections"].append(conn.name or "")
                for b in buses:
                    if short_path(b) not in entry["buses"]:
                        entry["buses"].append(short_path(b))
            connected.update((src.key, dst.key))
    hardware, _owner = _hardware(root, components)
    bindings = []
    by_path = {instance_path(ci): ci for ci in components if _category(ci) == "process"}
    for node in nodes.nodes:
        if node.kind != "process":
            continue
        targets: list[str] = []
        candidates = [by_path[node.key]]
        candidates += [ci for ci in component_instances(by_path[node.key]) if _category(ci) == "thread"]
        for ci in candidates:
            try:
                processor = bound_processor(ci, None, reader)
            except RosaadlError:
                processor = None
            if processor is not None:
                path = instance_path(processor)
                if path not in targets:
                    targets.append(path)
        for target in targets:
            bindings.append({"node": node.key, "processor": target})
    node_rows = [
        {
            "key": n.key,
            "name": n.name,
            "label": short_path(n.key),
            "kind": n.kind,
            "classifier": n.classifier,
            "colour": n.colour,
            "threads": [short_path(t) for t in n.threads],
        }
        for n in nodes.nodes
        if n.kind == "process" or n.key in connected
    ]
    return {
        "nodes": node_rows,
        "topics": list(topics.values()),
        "hardware": hardware,
        "bindings": bindings,
    }


# =============================================================================== findings


def _findings(report: Any, cpu: list[dict], bus: list[dict], schedule: dict[str, Any]) -> dict[str, Any]:
    headlines = []
    loaded = [r for r in cpu if r["load_percent"] is not None and not r["cores"]]
    if loaded:
        top = max(loaded, key=lambda r: r["load_percent"])
        over = [r for r in cpu if r["overloaded"]]
        headlines.append(
            {
                "key": "cpu",
                "title": "Highest core load",
                "value": f"{top['load_percent']:.1f} %",
                "detail": (
                    f"{top['label'].rpartition('.')[2]}; "
                    + (f"{len(over)} overloaded" if over else "no core over capacity")
                ),
                "status": "error" if over else ("warning" if top["load_percent"] > 90 else "ok"),
            }
        )
    loaded_buses = [r for r in bus if r["load_percent"] is not None]
    if loaded_buses:
        top = max(loaded_buses, key=lambda r: r["load_percent"])
        over = [r for r in bus if r["overloaded"]]
        headlines.append(
            {
                "key": "bus",
                "title": "Highest bus load",
                "value": f"{top['load_percent']:.1f} %",
                "detail": top["label"].rpartition(".")[2]
                + (f"; {len(over)} over capacity" if over else "; within capacity"),
                "status": "error" if over else ("warning" if top["load_percent"] > 90 else "ok"),
            }
        )
    if report.schedulability is not None and report.schedulability.domains:
        domains = report.schedulability.domains
        good = sum(1 for d in domains if d.schedulable)
        bad = sum(1 for d in domains if d.schedulable is False)
        headlines.append(
            {
                "key": "sched",
                "title": "Schedulable cores",
                "value": f"{good} of {len(domains)}",
                "detail": f"{bad} not schedulable" if bad else "every core meets its deadlines",
                "status": "error" if bad else "ok",
            }
        )
    if schedule.get("available"):
        misses = schedule["deadline_misses"]
        headlines.append(
            {
                "key": "schedule",
                "title": "Deadline misses",
                "value": str(misses),
                "detail": f"simulated over {schedule['horizon_text']}",
                "status": "error" if misses else "ok",
            }
        )
    if report.latency is not None and report.latency.chains:
        worst = max(report.latency.chains, key=lambda c: c.worst_us)
        failed = [c for c in report.latency.chains if c.met is False]
        headlines.append(
            {
                "key": "latency",
                "title": "Worst end-to-end latency",
                "value": _time_text(worst.worst_us, "us"),
                "detail": _clip(worst.name, 60) + (f"; {len(failed)} over their bound" if failed else ""),
                "status": "error" if failed else ("ok" if worst.met else "info"),
            }
        )
    if report.deployment is not None:
        dep = report.deployment
        headlines.append(
            {
                "key": "deploy",
                "title": "Proposed deployment",
                "value": "feasible" if dep.feasible else "none found",
                "detail": f"highest core load {float(dep.max_load * 100):.1f} %",
                "status": "ok" if dep.feasible else "error",
            }
        )
    errors = [_diag(d) for d in report.errors]
    warnings = [_diag(d) for d in report.warnings]
    return {
        "ok": bool(report.ok),
        "verdict": "All analyses pass"
        if report.ok
        else f"{len(errors)} problem{'s' if len(errors) != 1 else ''} found",
        "headlines": headlines,
        "errors": errors,
        "warnings": warnings,
    }


# =============================================================================== the view


def build_view(
    instance: Any, report: Any, *, simulation: Any = None, title: str | None = None
) -> dict[str, Any]:
    """Everything the report shows, as JSON-ready data (see the module documentation)."""
    from rosaadl.analysis.instance_values import instance_root

    root = instance_root(instance)
    components = component_instances(root)
    nodes = _Nodes(components)
    cpu = _cpu_rows(report, nodes)
    bus = _bus_rows(report)
    schedule = schedule_view(
        root, nodes, simulation, taskset=report.taskset, schedulability=report.schedulability
    )
    architecture = _architecture(root, components, nodes, report)
    findings = _findings(report, cpu, bus, schedule)
    name = root.name or report.instance or "instance"
    return {
        "title": title or f"Analysis of {name}",
        "instance": name,
        "classifier": root.classifier or "",
        "ok": bool(report.ok),
        "findings": findings,
        "cpu": cpu,
        "bus": bus,
        "schedule": schedule,
        "architecture": architecture,
        "analyses": _finite(report.as_dict()["analyses"]),
    }


def _finite(value: Any) -> Any:
    """``value`` with every infinite or NaN float replaced by None (JSON has no such numbers)."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value

"""``rosaadl run --emulate`` on a real ROS 2 runtime (``make ros``), 15 s per application: the
tracking example on the demo's proposed deployment, and two ROSMOD projects of the corpus
converted to AADL (``client-server``: services, with an interface package of ``.srv``;
``publish-subscribe``: a custom message, with an interface package of ``.msg``).

Each application is generated, built and run once for the module (the three runs and builds take
about two minutes on 2 cores); the tests read the verb's JSON report. During each run, once every
node is up, ``rosaadl import ros2-graph --measure`` reads the live graph on the run's ROS domain
(the round trip through real ROS 2: its nodes, topics, types, publisher/subscriber pairs and
measured rates against the run plan's). Then SIGINT is sent to every
node of the tracking application 20 times while the workload twin loads the machine.
"""

from __future__ import annotations

import json
import re
import signal
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import pytest
from conftest import corpus_dir
from ros_runtime import runtime_marks

from rosaadl.workflow.run import load_plan
from rosaadl.workflow.run.cores import machine, node_prefix, shared_cpus
from rosaadl.workflow.run.environment import run_environment
from rosaadl.workflow.run.monitor import nodes_up, start_monitor, stop_monitor
from rosaadl.workflow.run.processes import node_command, start_node, stop_nodes

pytestmark = [*runtime_marks(), pytest.mark.slow]

DURATION = 15
#: Seconds of discovery and of rate sampling of the live graph's import, inside the run's 15 s.
GRAPH_WAIT = 5
GRAPH_MEASURE = 6
#: Seconds the import's measuring subscriptions may take to match the publishers.
GRAPH_MATCHING = 2
#: Relative error allowed between a measured and a modelled rate (the issue's acceptance).
RATE_TOLERANCE = 0.10
SIGINT_ROUNDS = 20
CORPUS = corpus_dir() / "rosmod" / "textual-v0.3"
#: case -> (ROSMOD project of the corpus, root); None: the demo's proposed deployment
CASES = {
    "tracking": None,
    "services": ("client-server", "Benchmark_deployment::Benchmark.impl"),
    "messages": ("publish-subscribe", "Publisher_Benchmark_deployment::Publisher_Benchmark.impl"),
}


def _rosaadl(*args: str, timeout: int = 900) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "rosaadl", *args], capture_output=True, text=True, timeout=timeout
    )


def _model(case: str, folder: Path) -> tuple[Path, str]:
    """The AADL folder and root of a case."""
    if CASES[case] is None:
        done = _rosaadl("-q", "demo", "-o", str(folder / "demo"), timeout=300)
        assert done.returncode == 0, done.stderr[-3000:]
        return folder / "demo" / "aadl", "pioneer_3dx_proposed::tracking.impl"
    project, root = CASES[case]
    if not (CORPUS / project).is_dir():
        pytest.skip(f"the corpus project {project} is not at {CORPUS}")
    done = _rosaadl("-q", "convert", str(CORPUS / project), "-o", str(folder / "aadl"), timeout=300)
    assert done.returncode == 0, done.stderr[-3000:]
    return folder / "aadl", root


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """``case -> (exit code, JSON report, stderr, run folder)``, each case run once, when first asked.

    While it runs, once every node is up (the ``running`` progress line), the live graph is
    imported on the run's ROS domain (``import ros2-graph --measure``, :data:`GRAPH_WAIT` +
    :data:`GRAPH_MEASURE` seconds, inside the run's 15 s) into ``RUN_DIR/graph.json``, its JSON
    report into ``RUN_DIR/graph-report.json``."""
    done: dict[str, tuple[int, dict, str, Path]] = {}

    def run(case: str) -> tuple[int, dict, str, Path]:
        if case not in done:
            folder = tmp_path_factory.mktemp(case)
            aadl, root = _model(case, folder)
            out = folder / "run"
            began = time.monotonic()
            command = ["run", str(aadl), "--root", root, "--duration", str(DURATION), "--emulate"]
            code, stdout, stderr = _run_importing_graph([*command, "-o", str(out), "--format", "json"], out)
            print(f"{case}: rosaadl run took {time.monotonic() - began:.1f} s")
            report = json.loads(stdout) if stdout.strip() else {}
            done[case] = (code, report, stderr, out)
        return done[case]

    return run


def _run_importing_graph(args: list[str], out: Path) -> tuple[int, str, str]:
    """``rosaadl ARGS`` (a run writing into ``out``), the live graph imported while it runs."""
    process = subprocess.Popen(
        [sys.executable, "-m", "rosaadl", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        stdin=subprocess.DEVNULL,
        text=True,
    )
    importer = None
    lines: list[str] = []
    try:
        domain = None
        for line in process.stderr:
            lines.append(line)
            found = re.match(r"ROS domain (\d+) \((\w+)\)", line)
            if found:
                domain, reach = found.groups()
            if line.startswith("running ") and domain is not None:
                importer = _import_graph(out, domain, reach)
                break
        stdout, stderr = process.communicate(timeout=900)
        if importer is not None:
            report, err = importer.communicate(timeout=120)
            (out / "graph-report.json").write_text(report or json.dumps({"stderr": err}))
    finally:
        for child in (process, importer):
            if child is not None and child.poll() is None:
                child.kill()
                child.wait()
    return process.returncode, stdout, "".join(lines) + stderr


def _import_graph(out: Path, domain: str, reach: str) -> subprocess.Popen:
    """``rosaadl import ros2-graph`` of the run's domain, as a user joins it: the run's discovery
    range, its workspace sourced (the types of its interface packages, to measure their topics)."""
    env = {**run_environment(out / "install"), "ROS_AUTOMATIC_DISCOVERY_RANGE": reach}
    command = ["--format", "json", "import", "ros2-graph", "--domain-id", domain]
    command += ["--wait", str(GRAPH_WAIT), "--measure", str(GRAPH_MEASURE), "-o", str(out / "graph.json")]
    return subprocess.Popen(
        [sys.executable, "-m", "rosaadl", *command],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        stdin=subprocess.DEVNULL,
        text=True,
        env=env,
    )


@pytest.mark.parametrize("case", CASES)
def test_every_node_starts_and_exits_0_on_stop(runs, case):
    code, report, err, _ = runs(case)
    assert report, err[-4000:]
    assert report["nodes"], report
    for node in report["nodes"]:
        assert node["started"] and node["exit_code"] == 0, (node, err[-4000:])
    assert code == 0 and report["ok"], (report["errors"], err[-4000:])
    assert f"ROS domain {report['ros_domain_id']} (LOCALHOST)" in err


@pytest.mark.parametrize("case", CASES)
def test_every_topic_carries_its_modelled_rate(runs, case):
    _, report, err, _ = runs(case)
    published = [t for t in report["topics"] if t["model_rate_hz"]]
    for topic in published:
        assert topic["messages"] > 0, (topic, err[-4000:])
        off = abs(topic["rate_hz"] - topic["model_rate_hz"]) / topic["model_rate_hz"]
        assert off <= RATE_TOLERANCE, topic
    # every topic a node of the model publishes on carried messages (else the run is not ok)
    assert not [e for e in report["errors"] if "no message" in e["message"]]


def test_image_messages_carry_the_modelled_data_size(runs):
    _, report, _, _ = runs("tracking")
    image = next(t for t in report["topics"] if t["type"] == "sensor_msgs/msg/Image")
    assert image["model_bytes"] and image["messages"] > 0, image
    # the serialized message: the payload of Data_Size bytes, plus the header and the fields' CDR
    assert image["model_bytes"] <= image["bytes_per_message"] <= image["model_bytes"] + 256, image


def test_sigint_stops_every_node_with_exit_0_under_load(runs):
    """The built tracking application, its nodes started with the workload twin and stopped with
    SIGINT once they are up in the ROS graph, 20 times: every node exits 0 every time."""
    _, _, _, folder = runs("tracking")
    plan = load_plan(folder)
    install = folder / "install"
    env = run_environment(install)
    here = machine()
    shared = shared_cpus(plan.nodes, here)
    logs = folder / "sigint"
    logs.mkdir(exist_ok=True)
    # each round in a namespace of its own: its nodes are new names in the ROS graph
    rounds = [[replace(n, namespace=f"/sigint_{r}") for n in plan.nodes] for r in range(SIGINT_ROUNDS)]
    graph = logs / "graph.json"
    monitor = start_monitor([], sorted(n.full_name for nodes in rounds for n in nodes), graph, env, folder)
    failures = []
    try:
        for round_, nodes in enumerate(rounds):
            names = {n.full_name for n in nodes}
            started = []
            try:
                for node in nodes:
                    prefix, _ = node_prefix(node, here, shared)
                    command = node_command(node, install, prefix, [("rosaadl.emulate", True)])
                    started.append(start_node(node, command, env, logs, folder))
                _wait_for(lambda names=names: names <= nodes_up(graph), f"round {round_}: not all up")
                time.sleep(0.3)  # spinning, publishing, burning
            finally:
                stop_nodes(started)
            failures += [
                (round_, p.node.full_name, p.exit_code, p.stopped_by, p.log.read_text()[-1500:])
                for p in started
                if p.exit_code != 0 or p.stopped_by != "SIGINT"
            ]
    finally:
        stop_monitor(monitor)
    assert not failures, failures


def _wait_for(condition, message: str, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, message
        time.sleep(0.05)


def test_ctrl_c_of_rosaadl_run_stops_the_nodes_and_exits_130(runs):
    _, _, _, folder = runs("tracking")
    process = subprocess.Popen(
        [sys.executable, "-m", "rosaadl", "run", str(folder), "--no-build", "--duration", "300"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        lines = []
        for line in process.stderr:
            lines.append(line)
            if line.startswith("running "):
                break
        assert lines and lines[-1].startswith("running "), "".join(lines)
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=60)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    assert process.returncode == 130, "".join(lines) + err
    install = str(folder / "install")
    left = [pid for pid in _pids() if install in _cmdline(pid)]
    assert not left, [_cmdline(pid) for pid in left]


def _pids() -> list[int]:
    return [int(p.name) for p in Path("/proc").iterdir() if p.name.isdigit()]


def _cmdline(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


def test_a_node_that_crashes_is_a_located_error(runs):
    """A node whose code raises at start (its installed module edited): exit 1, the node and the
    end of its log in the report, never a traceback of rosaadl."""
    _, report, _, folder = runs("services")
    name = report["nodes"][0]["name"].rsplit("/", 1)[1]
    plan = load_plan(folder)
    node = next(n for n in plan.nodes if n.name == name)
    site = next((folder / "install" / "lib").glob("python3*/site-packages"))
    entry_points = next(site.glob(f"{node.package}-*.egg-info/entry_points.txt")).read_text()
    target = next(
        line.split("=", 1)[1].strip()
        for line in entry_points.splitlines()
        if line.split("=")[0].strip() == node.executable
    )
    module = site / (target.split(":")[0].replace(".", "/") + ".py")
    text = module.read_text()
    crash = "def main(args=None):\n    raise SystemExit('boom: broken on purpose')\n"
    module.write_text(text.replace("def main(args=None):\n", crash, 1))
    try:
        done = _rosaadl("run", str(folder), "--no-build", "--duration", "2", "--format", "json", timeout=300)
    finally:
        module.write_text(text)
    assert done.returncode == 1, done.stderr[-3000:]
    assert "Traceback" not in done.stderr
    again = json.loads(done.stdout)
    crashed = next(n for n in again["nodes"] if n["name"] == node.full_name)
    assert (crashed["started"], crashed["exit_code"]) == (False, 1)
    error = next(e for e in again["errors"] if node.full_name in e["message"])
    assert "did not start: it exited with code 1" in error["message"] and "boom" in error["message"]


def test_a_run_folder_given_relative_to_the_working_directory(runs):
    """``rosaadl run FOLDER`` with FOLDER relative to where it is started: the nodes and the
    topic monitor run in folders of their own and still find the run's files."""
    _, _, _, folder = runs("messages")
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "rosaadl",
            "--format",
            "json",
            "run",
            folder.name,
            "--no-build",
            "--duration",
            "2",
        ],
        cwd=folder.parent,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr[-3000:]
    report = json.loads(done.stdout)
    assert report["ok"] and all(n["exit_code"] == 0 for n in report["nodes"]), report["errors"]


def test_a_failed_build_is_a_located_error(runs):
    """A message definition colcon cannot build: exit 1, the end of the build log in the report."""
    _, _, _, folder = runs("messages")
    broken = next((folder / "src").glob("*_interfaces/msg")) / "Broken.msg"
    cmake = broken.parent.parent / "CMakeLists.txt"
    text = cmake.read_text()
    cmake.write_text(text.replace('"msg/', '"msg/Broken.msg"\n  "msg/', 1))
    broken.write_text("not a field definition at all\n")
    try:
        done = _rosaadl("run", str(folder), "--duration", "2", "--format", "json", timeout=600)
    finally:
        broken.unlink()
        cmake.write_text(text)
    assert done.returncode == 1, done.stderr[-3000:]
    assert "Traceback" not in done.stderr
    report = json.loads(done.stdout)
    assert report["ok"] is False and report["nodes"] == []
    assert "colcon build failed" in report["errors"][0]["message"]
    assert report["errors"][0]["file"] == str(folder / "src")


# --------------------------------------------------------------------------- the live graph


def _graph(folder: Path):
    """The ROSMOD project imported from the live graph during the run, and the import's report."""
    from rosaadl import model

    report_file = folder / "graph-report.json"
    assert report_file.is_file(), "the live graph was not imported (no `running` line?)"
    report = json.loads(report_file.read_text())
    assert report.get("ok"), report
    return model.load(folder / "graph.json"), report


def _measurable(rate_hz: float) -> bool:
    """Whether the import's measurement must give a topic of this model rate a period: the
    rate's gaps fit :data:`~rosaadl.workflow.ros2_graph.MIN_SAMPLES` messages into the sampling
    less :data:`GRAPH_MATCHING` seconds."""
    from rosaadl.workflow.ros2_graph import MIN_SAMPLES

    return rate_hz * (GRAPH_MEASURE - GRAPH_MATCHING) >= MIN_SAMPLES


def _token(topic: str) -> str:
    """The name part the graph import gives the timer of a measured periodic topic."""
    return topic.strip("/").replace("/", "_") or "topic"


def _imported_graph(project) -> tuple[set[str], dict, dict, list[str]]:
    """(node full names, topic -> (type, publishers, subscribers), topic -> measured Hz, the
    service ends) of the imported graph. Every node of these applications is in the root
    namespace (asserted on the plan): the ROSMOD node's name under ``/`` is its full name."""
    nodes: set[str] = set()
    topics: dict[str, tuple[set, set, set]] = {}
    rates: dict[str, float] = {}
    services: list[str] = []
    for deployment in project.deployments:
        for node in deployment.nodes:
            full = f"/{node.name}"
            nodes.add(full)
            for instance in node.componentInstances:
                component = instance.component
                names = {p.key: p.value for p in component.properties}
                for port in component.ports:
                    topic = names[f"{port.name}.Topic"]
                    if port.eClass.name not in ("Publisher", "Subscriber"):
                        services.append(f"{port.eClass.name} {topic} ({port.type}) of {full}")
                        continue
                    types, pubs, subs = topics.setdefault(topic, (set(), set(), set()))
                    types.add(port.type)
                    (pubs if port.eClass.name == "Publisher" else subs).add(full)
                for timer in component.timers:
                    rates[timer.name.removesuffix("_timer")] = 1 / float(timer.period)
    return nodes, {t: (sorted(a), sorted(b), sorted(c)) for t, (a, b, c) in topics.items()}, rates, services


@pytest.mark.parametrize("case", CASES)
def test_the_live_graph_imports_as_the_model(runs, case, record_property):
    """Round trip through real ROS 2: the graph imported while the application runs has the
    model's nodes, topics, message types and publisher/subscriber pairs, and every periodic
    publisher measured gets the model's rate within 10 % (one fast enough to give the import's
    fewest samples in its sampling must be measured). What cannot be compared is recorded
    (``record_property``) and printed: services and clients (the run plan lists topics only)
    and the rate of a topic no node of the model publishes on, whose model rate is unknown, with
    several publishers, or too slow to measure (``publish-subscribe``'s 0.5 Hz in 6 s)."""
    from rosaadl.workflow.ros2_graph import ros_type

    code, _, err, folder = runs(case)
    plan = load_plan(folder)
    assert code == 0, err[-4000:]
    project, report = _graph(folder)
    assert all(n.namespace.strip("/") == "" for n in plan.nodes), plan.nodes
    nodes, topics, rates, services = _imported_graph(project)
    assert nodes == {n.full_name for n in plan.nodes}, (report["warnings"], err[-3000:])
    expected = {
        t.name: ([ros_type(t.type)], sorted(t.publishers), sorted(t.subscribers)) for t in plan.topics
    }
    assert topics == expected, report["warnings"]
    by_token = {_token(t.name): t for t in plan.topics}
    measured = {by_token[token].name: hz for token, hz in rates.items()}
    periodic = [t for t in plan.topics if t.model_rate_hz and len(t.publishers) == 1]
    for topic in periodic:  # measured: within 10 %; fast enough to be measured: it must be
        if topic.name in measured:
            off = abs(measured[topic.name] - topic.model_rate_hz) / topic.model_rate_hz
            assert off <= RATE_TOLERANCE, (topic.name, measured[topic.name], topic.model_rate_hz)
        else:
            assert not _measurable(topic.model_rate_hz), (topic, report["warnings"])
    assert set(measured) <= {t.name for t in periodic}, (measured, periodic)
    not_compared = services + [
        f"rate of {t.name}: "
        + (
            "no node of the model publishes on it"
            if not t.publishers
            else "its model rate is not known"
            if not t.model_rate_hz
            else "several publishers"
            if len(t.publishers) > 1
            else f"{t.model_rate_hz:g} Hz, too slow to measure in {GRAPH_MEASURE} s"
        )
        for t in plan.topics
        if t.name not in measured
    ]
    record_property("not_compared", not_compared)
    print(f"{case}: measured {measured}; not compared: {not_compared}")

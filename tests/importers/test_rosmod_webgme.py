"""WebGME ROSMOD exports (.webgmex): archive safety, WebGME inheritance rules, mapping, corpus counts."""

from __future__ import annotations

import copy
import json
import random
import tempfile
import zipfile
from decimal import Decimal
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosaadl import model
from rosaadl.errors import Diagnostic, ImportFormatError, RosaadlError
from rosaadl.importers import rosmod_webgme
from rosaadl.importers.rosmod_text import SUMMARY_KEYS, RosmodImportError, summarize
from rosaadl.importers.rosmod_webgme import load_project_json, project_names, read_webgmex

# --------------------------------------------------------------------------- a small export, built here

META = {
    "P": "Project",
    "S": "Software",
    "Pk": "Package",
    "M": "Message",
    "V": "Service",
    "C": "Component",
    "T": "Timer",
    "Pub": "Publisher",
    "Sub": "Subscriber",
    "Cl": "Client",
    "Sr": "Server",
    "Ys": "Systems",
    "Y": "System",
    "H": "Host",
    "I": "Interface",
    "N": "Network",
    "L": "Link",
    "U": "User",
    "Ds": "Deployments",
    "D": "Deployment",
    "Ct": "Container",
    "Nd": "Node",
    "Es": "Experiments",
    "E": "Experiment",
    "Ps": "Projects",
    "EN": "External Node",
}
META_DEFAULTS = {
    "C": {"SchedulingScheme": "FIFO", "Logging_UserEnable": False, "Logging_UserUnit": 1000},
    "T": {"Priority": 50, "Deadline": 0, "Period": 0},
    "Sub": {"Priority": 50, "Deadline": 0},
    "Sr": {"Priority": 50, "Deadline": 0},
    "Pub": {"Latching": True},
    "H": {"Architecture": "armv7l", "OS": "Linux"},
    "Nd": {"Priority": 50, "Arguments": "{\n}"},
    "M": {"Definition": ""},
}


def _n(name: str, kind: str | None = None, children: dict | None = None, **atr) -> dict:
    return {"name": name, "kind": kind, "atr": atr, "children": children or {}}


def demo_tree() -> dict:
    """The tree of a small project; ``kind`` gives the META base (explicit 'base' pointer)."""
    planner = _n(
        "Planner",
        "C",
        {
            "t": _n("tick", "T", Period=0.1, Priority=60, Deadline=0.05, Operation="tick();"),
            "o": _n("goal_pub", "Pub"),
            "i": _n("goal_sub", "Sub", Deadline=0.2),
            "r": _n("plan_srv", "Sr"),
            "l": _n("plan_cli", "Cl"),
        },
        SchedulingScheme="PFIFO",
        Forwards="#include <x>",
    )
    package = _n(
        "nav",
        "Pk",
        {
            "g": _n("Goal", "M", Definition="float64 x\nfloat64 y\n"),
            "v": _n("Plan", "V", Definition="nav/Goal goal\n---\nbool ok\n"),
            "c": planner,
        },
    )
    package["ovr"] = {
        "/c/o": {"Message": "/g"},
        "/c/i": {"Message": "/g"},
        "/c/r": {"Service": "/v"},
        "/c/l": {"Service": "/v"},
    }
    host = _n("board", "H", {"e": _n("eth0", "I")}, Architecture="x86_64", **{"Device ID": "rev B"})
    host["sets"] = {"Users": ["u1"]}
    system = _n(
        "Lab",
        "Y",
        {
            "h": host,
            "n": _n("net", "N", Subnet="10.0.0.0", Netmask="255.255.255.0"),
            "k": _n("link", "L", IP="10.0.0.5"),
            "u": _n("robot", "U", Key="~/.ssh/id", Directory="/home/robot"),
        },
    )
    system["ovr"] = {"/k": {"src": "/h/e", "dst": "/n"}, "/h/_sets/Users/u1": {"member": "/u"}}
    instance = _n(
        "planner_i",
        None,
        {"t": {"atr": {"Period": 0.2}, "children": {}, "inherited": True}},
        Logging_UserEnable=True,
    )
    deployment = _n(
        "Field",
        "D",
        {
            "c": _n(
                "box",
                "Ct",
                {
                    "n": _n("planner_node", "Nd", {"i": instance}, Priority=70),
                    "x": _n("rviz", "EN", Package="rviz"),
                },
            )
        },
    )
    project = _n(
        "Demo",
        "P",
        {
            "s": _n("Software", "S", {"p": package}),
            "y": _n("Systems", "Ys", {"s": system}),
            "d": _n("Deployments", "Ds", {"x": deployment}),
            "e": _n("Experiments", "Es", {"e": _n("run", "E")}),
        },
        Authors="someone",
    )
    project["ovr"] = {"/d/x/c/n/i": {"base": "/s/p/c"}, "/e/e": {"Deployment": "/d/x", "System": "/y/s"}}
    return _n("Projects", "Ps", {"a": project})


def build_export(tree: dict | None = None, *, shards: int = 2) -> dict:
    """A project.json (content-addressed objects) for ``tree`` plus a META under /m."""
    tree = demo_tree() if tree is None else tree
    objects: list[dict] = []
    counter = [0]

    def store(data: dict) -> str:
        counter[0] += 1
        data["_id"] = f"#{counter[0]:040x}"
        objects.append(data)
        return data["_id"]

    root_ovr: dict[str, dict] = {"": {"base": "/_nullptr"}, "/1": {"base": "/_nullptr"}}
    meta_children = {}
    for index, (relid, name) in enumerate(META.items()):
        root_ovr[f"/m/{relid}"] = {"base": "/1"}
        root_ovr[f"/_sets/MetaAspectSet/{index}"] = {"member": f"/m/{relid}"}
        atr = {"name": name, **META_DEFAULTS.get(relid, {})}
        meta_children[relid] = store({"atr": atr, "reg": {}})
    root_ovr["/_sets/MetaAspectSet/fco"] = {"member": "/1"}
    root_ovr["/m"] = {"base": "/1"}

    def emit(node: dict, path: str) -> str:
        data: dict = {"atr": dict(node["atr"]), "reg": {}}
        if "name" in node:
            data["atr"]["name"] = node["name"]
        if node.get("kind"):
            root_ovr[path] = {"base": f"/m/{node['kind']}"}
        if node.get("ovr"):
            data["ovr"] = node["ovr"]
        if node.get("sets"):
            data["_sets"] = {k: {m: {"reg": {}} for m in v} for k, v in node["sets"].items()}
        for relid, child in node["children"].items():
            data[relid] = emit(child, f"{path}/{relid}")
        return store(data)

    projects = emit(tree, "/v")
    fco = store({"atr": {"name": "FCO"}, "reg": {}})
    meta = store({"atr": {"name": "META"}, "reg": {}, **meta_children})
    items = sorted(root_ovr.items())
    shard_refs = {}
    for k in range(shards):
        part = dict(items[k::shards])
        shard_refs[f"s{k}"] = store({"type": "shard", "itemCount": len(part), "items": part})
    root = {
        "atr": {"name": "ROOT"},
        "reg": {},
        "1": fco,
        "m": meta,
        "v": projects,
        "ovr": {"sharded": True, **shard_refs},
        "_sets": {"MetaAspectSet": {}},
    }
    root_hash = store(root)
    return {"rootHash": root_hash, "projectId": "test", "objects": objects}


def write_export(path: Path, doc: dict | bytes, extra: dict[str, bytes] | None = None) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("project.json", doc if isinstance(doc, bytes) else json.dumps(doc))
        for name, data in (extra or {}).items():
            archive.writestr(name, data)
    return path


def import_error(path: Path, **kwargs) -> list[RosaadlError]:
    with pytest.raises(RosmodImportError) as info:
        read_webgmex(path, **kwargs)
    assert isinstance(info.value, ImportFormatError) and isinstance(info.value, RosaadlError)
    for err in info.value.errors:
        assert err.location.file == str(path)
    return info.value.errors


# --------------------------------------------------------------------------- mapping


def test_demo_export_maps_to_the_rosmod_model(tmp_path):
    path = write_export(tmp_path / "demo.webgmex", build_export())
    warnings: list[Diagnostic] = []
    (project,) = read_webgmex(path, warnings=warnings)
    assert warnings == []
    assert (project.name, project.formatVersion) == ("Demo", "webgme")
    assert [(p.key, p.value) for p in project.properties] == [("Authors", "someone")]
    (nav,) = project.software.packages
    assert [(f.name, f.type) for f in nav.messages[0].fields] == [("x", "float64"), ("y", "float64")]
    assert [f.type for f in nav.services[0].requestFields] == ["nav/Goal"]
    (planner,) = nav.components
    assert planner.schedulingScheme.name == "PFIFO"
    assert [(p.key, p.value) for p in planner.properties] == [("Forwards", "#include <x>")]
    (tick,) = planner.timers
    assert (tick.period, tick.priority, tick.deadline, tick.operation) == (
        Decimal("0.1"),
        60,
        Decimal("0.05"),
        "tick();",
    )
    ports = {p.name: p for p in planner.ports}
    assert {n: (p.eClass.name, p.type) for n, p in ports.items()} == {
        "goal_pub": ("Publisher", "nav/Goal"),
        "goal_sub": ("Subscriber", "nav/Goal"),
        "plan_cli": ("Client", "nav/Plan"),
        "plan_srv": ("Server", "nav/Plan"),
    }
    assert ports["goal_sub"].priority == 50 and ports["goal_sub"].deadline == Decimal("0.2")  # META default
    assert ports["goal_pub"].latching is True

    (system,) = project.systems
    (board,) = system.hosts
    assert (
        board.architecture,
        board.os,
        board.username,
        board.sshKey,
        board.deploymentPath,
        board.ipAddress,
    ) == (
        "x86_64",
        "Linux",
        "robot",
        "~/.ssh/id",
        "/home/robot",
        "10.0.0.5",
    )
    assert [(p.key, p.value) for p in board.properties] == [("Device ID", "rev B")]
    (link,) = system.links
    assert (link.interface, link.host, link.network) == (board.interfaces[0], board, system.networks[0])
    assert system.networks[0].netmask == "255.255.255.0"
    assert [p.key for p in system.properties] == ["User:robot"]

    (deployment,) = project.deployments
    assert deployment.system is system and deployment.systemName == "Lab"
    props = {p.key: json.loads(p.value) for p in deployment.properties}
    assert props == {
        "Container:box": {},
        "External Node:rviz": {"Package": "rviz"},
        "Experiment:run": {"System": "Lab"},
    }
    (node,) = deployment.nodes
    assert (node.name, node.priority, node.arguments, node.host) == ("planner_node", 70, "{\n}", None)
    assert [(p.key, p.value) for p in node.properties] == [("container", "box")]
    (inst,) = node.componentInstances
    assert (inst.name, inst.component, inst.componentRef) == ("planner_i", planner, "nav/Planner")
    assert inst.schedulingScheme.name == "PFIFO"  # inherited from the software component
    assert [(p.key, p.value) for p in inst.logging] == [
        ("Logging_UserEnable", "true"),
        ("Logging_UserUnit", "1000"),
    ]
    assert [(p.key, p.value) for p in inst.properties] == [("tick.Period", "0.2")]
    assert summarize(project)["containers"] == 1


def test_same_export_twice_is_equal_and_saves_and_reloads(tmp_path):
    path = write_export(tmp_path / "demo.webgmex", build_export())
    (first,), (second,) = read_webgmex(path), read_webgmex(path)
    assert model.model_differences(first, second) == []
    for name in ("p.xmi", "p.json"):
        model.save(first, tmp_path / name)
        assert model.model_differences(first, model.load(tmp_path / name), ignore=()) == []


def test_unsharded_overlays_and_project_selection(tmp_path):
    doc = build_export(shards=1)
    root = next(o for o in doc["objects"] if o["_id"] == doc["rootHash"])
    shard = next(o for o in doc["objects"] if o["_id"] == root["ovr"]["s0"])
    root["ovr"] = shard["items"]  # the older layout: overlays inline
    path = write_export(tmp_path / "flat.webgmex", doc)
    assert project_names(path) == ["Demo"]
    assert [p.name for p in read_webgmex(path, project="Demo")] == ["Demo"]
    (err,) = import_error(path, project="Nope")
    assert "no project 'Nope'" in err.message and "'Demo'" in err.message


def test_message_definition_errors_are_located(tmp_path):
    tree = demo_tree()
    goal = tree["children"]["a"]["children"]["s"]["children"]["p"]["children"]["g"]
    goal["atr"]["Definition"] = "float64 x\nfloat64[q] y\n"
    (err,) = import_error(write_export(tmp_path / "bad.webgmex", build_export(tree)))
    assert err.location.path == "Projects/Demo/Software/nav/Goal" and err.location.line == 2
    assert "Definition: malformed field type" in err.message


@pytest.mark.parametrize(
    ("period", "fragment"),
    [
        ("1e309", "out of range: a time is at most"),  # a finite decimal that overflows as a float
        ("1e-400", "out of range: a non-zero time is at least"),
        ("Infinity", "expected a non-negative number of seconds"),
    ],
)
def test_times_out_of_the_float_range_are_located_errors(tmp_path, period, fragment):
    tree = demo_tree()
    tick = tree["children"]["a"]["children"]["s"]["children"]["p"]["children"]["c"]["children"]["t"]
    tick["atr"]["Period"] = period
    (err,) = import_error(write_export(tmp_path / "bad.webgmex", build_export(tree)))
    assert err.location.path == "Projects/Demo/Software/nav/Planner/tick"
    assert err.message.startswith(f"Period = {period!r}: ") and fragment in err.message, err.message


def test_a_json_number_that_overflows_is_a_located_error(tmp_path):
    text = json.dumps(build_export()).replace('"Period": 0.1', '"Period": 1e309', 1)
    assert "1e309" in text
    (err,) = import_error(write_export(tmp_path / "bad.webgmex", text.encode()))
    assert err.location.path == "Projects/Demo/Software/nav/Planner/tick" and "Period = inf" in err.message


def test_instance_of_no_software_component(tmp_path):
    tree = demo_tree()
    project = tree["children"]["a"]
    project["ovr"] = {"/e/e": {"Deployment": "/d/x"}}  # the instance loses its base
    inst = project["children"]["d"]["children"]["x"]["children"]["c"]["children"]["n"]["children"]["i"]
    inst["kind"] = "C"
    inst["children"] = {}
    (err,) = import_error(write_export(tmp_path / "bad.webgmex", build_export(tree)))
    assert "is not an instance of a software component" in err.message
    assert err.location.path.endswith("planner_node/planner_i")


def test_broken_object_graphs(tmp_path):
    doc = build_export()
    victim = next(o for o in doc["objects"] if o.get("atr", {}).get("name") == "tick")
    missing = copy.deepcopy(doc)
    missing["objects"] = [o for o in missing["objects"] if o["_id"] != victim["_id"]]
    (err,) = import_error(write_export(tmp_path / "missing.webgmex", missing))
    assert "is missing from project.json" in err.message

    tree = demo_tree()
    tree["children"]["a"]["children"]["s"]["children"]["p"]["ovr"]["/c/o"] = {"Message": "/zz"}
    (err,) = import_error(write_export(tmp_path / "dangling.webgmex", build_export(tree)))
    assert "does not exist" in err.message

    tree = demo_tree()
    project = tree["children"]["a"]
    software = project["children"]["s"]
    software["children"]["q"] = _n("loop_a", None)
    software["children"]["r"] = _n("loop_b", None)
    software["ovr"] = {"/q": {"base": "/r"}, "/r": {"base": "/q"}}
    (err,) = import_error(write_export(tmp_path / "loop.webgmex", build_export(tree)))
    assert "loops" in err.message


# --------------------------------------------------------------------------- hostile archives


def test_not_a_zip_archive(tmp_path):
    path = tmp_path / "text.webgmex"
    path.write_text('{"rootHash": "#1", "objects": []}')
    (err,) = import_error(path)
    assert "not a zip archive" in err.message


def test_five_megabytes_of_garbage(tmp_path):
    path = tmp_path / "garbage.webgmex"
    path.write_bytes(random.Random(3).randbytes(5 * 1024 * 1024))
    (err,) = import_error(path)
    assert "zip" in err.message


@pytest.mark.parametrize("member", ["../../x", "/etc/evil", "a/../../b", "..\\..\\x", "C:/x"])
def test_member_names_outside_the_archive(tmp_path, member):
    path = write_export(tmp_path / "evil.webgmex", build_export(), {member: b"boom"})
    (err,) = import_error(path)
    assert "outside the archive" in err.message and err.location.path == member
    assert not (tmp_path.parent / "x").exists() and not (tmp_path / "x").exists()


def test_truncated_archive(tmp_path):
    whole = write_export(tmp_path / "whole.webgmex", build_export()).read_bytes()
    for cut in (len(whole) // 2, len(whole) - 30, 40):
        path = tmp_path / f"cut{cut}.webgmex"
        path.write_bytes(whole[:cut])
        (err,) = import_error(path)
        assert "zip" in err.message


def test_corrupt_member_data(tmp_path):
    whole = bytearray(write_export(tmp_path / "whole.webgmex", build_export()).read_bytes())
    whole[60:90] = bytes(30)  # inside the compressed project.json
    path = tmp_path / "corrupt.webgmex"
    path.write_bytes(bytes(whole))
    (err,) = import_error(path)
    assert "corrupt or truncated" in err.message or "malformed" in err.message


def test_size_and_member_caps(tmp_path, monkeypatch):
    path = write_export(tmp_path / "big.webgmex", build_export(), {"blob.content": bytes(100_000)})
    monkeypatch.setattr(rosmod_webgme.archive, "MAX_TOTAL_BYTES", 50_000)
    (err,) = import_error(path)
    assert "would unpack to" in err.message
    monkeypatch.setattr(rosmod_webgme.archive, "MAX_TOTAL_BYTES", 200 * 1024 * 1024)
    monkeypatch.setattr(rosmod_webgme.archive, "MAX_MEMBERS", 1)
    (err,) = import_error(path)
    assert "members" in err.message


@pytest.mark.parametrize(
    ("payload", "fragment", "line"),
    [
        (b'{"rootHash": "#1",\n "objects": [}', "malformed project.json", 2),
        (b"[1, 2]", "not a WebGME export", None),
        (b'{"rootHash": "#nope", "objects": []}', "root object", None),
        (b'{"rootHash": "#1", "objects": [{"atr": {}}]}', "has no '_id'", None),
        (b"\xff\xfe", "not UTF-8", None),
        (b"[" * 100_000 + b"]" * 100_000, "nested too deeply", None),
    ],
)
def test_bad_project_json(tmp_path, payload, fragment, line):
    (err,) = import_error(write_export(tmp_path / "bad.webgmex", payload))
    assert fragment in err.message
    if line is not None:
        assert err.location.line == line


def test_no_project_json(tmp_path):
    path = tmp_path / "other.webgmex"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("readme.txt", "hi")
    (err,) = import_error(path)
    assert "no project.json" in err.message
    with pytest.raises(ImportFormatError):
        load_project_json(path)


# --------------------------------------------------------------------------- corpus

# INDEX.md's WebGME table: packages, messages, services, actions, components, timers,
# publishers, subscribers, clients, servers, action clients, action servers, systems, hosts,
# deployments, containers, nodes, component instances. (The External Node of "Introduction to
# ROSMOD" is not a ROSMOD node: it is kept as a deployment property, as INDEX counts it apart.)
EXPECTED = {
    ("2018", "AGSE"): (3, 10, 8, 0, 8, 6, 6, 13, 9, 8, 0, 0, 2, 4, 1, 3, 4, 7),
    ("2018", "Introduction to ROSMOD"): (1, 1, 1, 1, 3, 3, 4, 3, 2, 2, 1, 1, 1, 1, 2, 4, 6, 6),
    ("2018", "KSP Flight Controller"): (1, 3, 0, 0, 4, 3, 3, 4, 0, 0, 0, 0, 1, 1, 1, 1, 4, 4),
    ("2018", "KSP Rover Controller"): (1, 3, 0, 0, 4, 3, 3, 4, 0, 0, 0, 0, 1, 1, 2, 2, 2, 5),
    ("2016", "AGSE Pub-Sub"): (3, 19, 0, 0, 8, 6, 15, 21, 0, 0, 0, 0, 1, 3, 0, 0, 0, 0),
    ("2016", "Integration Test"): (1, 1, 1, 0, 3, 3, 2, 1, 1, 1, 0, 0, 2, 29, 1, 3, 3, 3),
    ("2016", "Client Server"): (1, 0, 1, 0, 2, 1, 0, 0, 1, 1, 0, 0, 2, 34, 1, 1, 1, 2),
    ("2016", "Periodic Timer"): (1, 0, 0, 0, 6, 10, 0, 0, 0, 0, 0, 0, 2, 34, 0, 0, 0, 0),
    ("2016", "Blinking LEDs"): (1, 1, 0, 0, 1, 0, 1, 1, 0, 0, 0, 0, 2, 34, 0, 0, 0, 0),
    ("2016", "Publish Subscribe"): (1, 1, 0, 0, 2, 1, 1, 1, 0, 0, 0, 0, 2, 34, 1, 1, 1, 2),
}
# the columns of INDEX.md's WebGME table: the counts of summarize, in order, but for the maxima
_KEYS = tuple(k for k in SUMMARY_KEYS if not k.startswith("max_"))
assert len(_KEYS) == 18
SEEDS = {"2018": "samples-2018-05-19_noTLC.webgmex", "2016": "samples-2016-06-13_noTLC.webgmex"}


@pytest.fixture(scope="module")
def seeds(corpus):
    out = {}
    for year, name in SEEDS.items():
        warnings: list[Diagnostic] = []
        out[year] = (
            {p.name: p for p in read_webgmex(corpus / "rosmod" / "webgme" / name, warnings=warnings)},
            warnings,
        )
    return out


@pytest.mark.corpus
@pytest.mark.parametrize(("year", "name"), sorted(EXPECTED))
def test_corpus_counts(seeds, year, name):
    counts = summarize(seeds[year][0][name])
    assert tuple(counts[k] for k in _KEYS) == EXPECTED[(year, name)]


@pytest.mark.corpus
def test_every_corpus_project_imports(seeds, corpus):
    assert sorted(seeds["2018"][0]) == [
        "AGSE",
        "Introduction to ROSMOD",
        "KSP Flight Controller",
        "KSP Rover Controller",
    ]
    # the 2016 seed also holds 2016 versions of four projects that INDEX.md does not tabulate
    assert len(seeds["2016"][0]) == 10
    for projects, _warnings in seeds.values():
        for project in projects.values():
            for deployment in project.deployments:
                for node in deployment.nodes:
                    assert all(i.component is not None for i in node.componentInstances)
    # the only warnings: 2016 capability nodes whose META type no longer exists (WebGME drops them)
    assert seeds["2018"][1] == []
    assert {w.message for w in seeds["2016"][1]} == {"node without a base (WebGME drops such nodes); skipped"}
    meta_only = corpus / "rosmod" / "webgme" / "meta-2018-07.webgmex"
    assert read_webgmex(meta_only) == [] and project_names(meta_only) == []


def _decoded_instances(node: dict, trail: tuple = ()) -> set:
    found = set()
    if node.get("type") == "Component" and node.get("instance_of"):
        found.add((*trail[-3:-1], node["name"], "/".join(node["instance_of"].split("/")[-2:])))
        return found
    for child in node.get("children", []):
        found |= _decoded_instances(child, (*trail, node["name"]))
    return found


def _decoded_ports(node: dict, package: str = "") -> set:
    found = set()
    if node.get("type") == "Package":
        package = node["name"]
    kinds = {"Publisher": "Message", "Subscriber": "Message", "Client": "Service", "Server": "Service"}
    if node.get("type") in kinds and package and not node.get("instance_of"):
        target = (node.get("pointers") or {}).get(kinds[node["type"]]) or ""
        found.add((package, node["type"], node["name"], target.split("/")[-1]))
    for child in node.get("children", []):
        if not child.get("instance_of"):
            found |= _decoded_ports(child, package)
    return found


@pytest.mark.corpus
@pytest.mark.parametrize(("year", "name"), sorted(EXPECTED))
def test_corpus_matches_the_decoded_trees(seeds, corpus, year, name):
    decoded = json.loads(
        (corpus / "rosmod" / "webgme" / "decoded" / year / f"{name.replace(' ', '_')}.json").read_text()
    )
    project = seeds[year][0][name]
    ours = {
        (d.name, next(p.value for p in n.properties if p.key == "container"), n.name, i.name)
        + (i.componentRef,)
        for d in project.deployments
        for n in d.nodes
        for i in n.componentInstances
    }
    theirs = {(dep, cont, node, inst, ref) for (dep, cont, node, inst, ref) in _with_deployment(decoded)}
    assert ours == theirs
    # a port that uses an Advertised Message/Service has the advertised (topic) name in
    # "<port>.Topic"; the decoded tree names that node, we resolve it to the real ROS type
    ports = {
        (pkg.name, port.eClass.name, port.name, _topic(comp, port).split("/")[-1])
        for pkg in project.software.packages
        for comp in pkg.components
        for port in comp.ports
    }
    assert ports == _decoded_ports(decoded)


def _topic(comp, port) -> str:
    topic = next((p.value for p in comp.properties if p.key == f"{port.name}.Topic"), None)
    return topic or port.type or ""


def _with_deployment(decoded: dict) -> set:
    out = set()
    for folder in decoded.get("children", []):
        if folder.get("type") != "Deployments":
            continue
        for dep in folder.get("children", []):
            for container in dep.get("children", []):
                for node in container.get("children", []):
                    if node.get("type") != "Node":
                        continue
                    for inst in node.get("children", []):
                        if inst.get("type") == "Component":
                            ref = "/".join(inst["instance_of"].split("/")[-2:])
                            out.add((dep["name"], container["name"], node["name"], inst["name"], ref))
    return out


@pytest.mark.corpus
def test_corpus_projects_are_stable_and_save(seeds, corpus, tmp_path):
    again = {p.name: p for p in read_webgmex(corpus / "rosmod" / "webgme" / SEEDS["2018"])}
    for name, project in seeds["2018"][0].items():
        assert model.model_differences(project, again[name]) == []
        model.save(project, tmp_path / "p.json")
        assert model.model_differences(project, model.load(tmp_path / "p.json"), ignore=()) == []


@pytest.mark.corpus
def test_corpus_details(seeds):
    intro = seeds["2018"][0]["Introduction to ROSMOD"]
    comp2 = next(c for c in intro.software.packages[0].components if c.name == "Component_2")
    types = {p.name: p.type for p in comp2.ports}
    assert types["externalSub"] == "std_msgs/ColorRGBA"  # an External Message
    assert types["ColorRGBASubscriber"] == "std_msgs/ColorRGBA"  # through an Advertised Message
    topic = {p.key: p.value for p in comp2.properties}["ColorRGBASubscriber.Topic"]
    assert topic == "three_component_example/ComponentColor"
    assert [p.key for p in comp2.properties if p.key.startswith("Action Server:")] == [
        "Action Server:moveToPositionServer"
    ]
    deployment = next(d for d in intro.deployments if d.name == "1 Container Deployment")
    assert deployment.system.name == "Intro System"
    agse = seeds["2018"][0]["AGSE"]
    jetson = next(h for s in agse.systems for h in s.hosts if h.name == "Jetson")
    assert jetson.username == "root" and jetson.ipAddress


_JSON = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=8),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=4), inner, max_size=3),
    max_leaves=6,
)


@given(st.data())
@settings(max_examples=120, deadline=None)
def test_mutated_exports_fail_cleanly(data):
    doc = build_export(shards=2)
    for _ in range(data.draw(st.integers(min_value=1, max_value=4))):
        obj = data.draw(st.sampled_from(doc["objects"]))
        keys = sorted(obj) + ["atr", "ovr", "_sets", "zz"]
        key = data.draw(st.sampled_from(keys))
        if key == "_id":
            continue
        if key in obj and isinstance(obj[key], dict) and obj[key] and data.draw(st.booleans()):
            inner = data.draw(st.sampled_from(sorted(obj[key])))
            obj[key][inner] = data.draw(_JSON)
        else:
            obj[key] = data.draw(_JSON)
    with tempfile.TemporaryDirectory() as tmp:
        path = write_export(Path(tmp) / "m.webgmex", doc)
        try:
            read_webgmex(path)
        except RosmodImportError as exc:
            assert all(e.location.file == str(path) for e in exc.errors)

"""Metamodel benchmark: build, save and load a 100 000-object instance model (XMI and JSON).

Side by side in one run:
  * the raw lxml parse of the same XMI file (the floor a loader cannot beat);
  * our dynamic metamodel (``metamodels/*.ecore`` loaded by pyecore, the shipped choice);
  * static classes generated from the same ``.ecore`` by pyecoregen (the alternative).

Each phase runs in its own subprocess so that its peak memory (max RSS) is its own.
Usage: ``python -m benchmarks.bench_metamodel [--objects N]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PER_UNIT = 11  # objects made per component instance (see _build)


def _static_package(workdir: Path):
    """Generate static classes for aadl.ecore with pyecoregen and import them."""
    out = workdir / "static"
    if not (out / "aadl").exists():
        ecore = Path(__file__).resolve().parent.parent / "metamodels" / "aadl.ecore"
        exe = Path(sys.executable).with_name("pyecoregen")
        subprocess.run([str(exe), "-e", str(ecore), "-o", str(out)], check=True, capture_output=True)
    sys.path.insert(0, str(out))
    import aadl as static_aadl  # type: ignore[import-not-found]

    return static_aadl


def _classes(mode: str, workdir: Path):
    if mode == "dynamic":
        from rosaadl import metamodels

        mm = metamodels.load().aadl
        get = mm.getEClassifier
        return mm, {n: get(n) for n in _NAMES}
    pkg = _static_package(workdir)
    return pkg, {n: getattr(pkg, n) for n in _NAMES}


_NAMES = (
    "SystemInstance",
    "ComponentInstance",
    "FeatureInstance",
    "ConnectionInstance",
    "PropertyAssociation",
    "ModalPropertyValue",
    "IntegerValue",
)


def _build(classes: dict, objects: int):
    C = classes
    units = max(1, objects // PER_UNIT)
    root = C["SystemInstance"](name="top")
    for i in range(units):
        comp = C["ComponentInstance"](name=f"t{i}")
        root.componentInstances.append(comp)
        feats = [C["FeatureInstance"](name=f"p{j}") for j in range(3)]
        comp.featureInstances.extend(feats)
        for prop, value in (("Timing_Properties::Period", 33333), ("Timing_Properties::Deadline", 30000)):
            pa = C["PropertyAssociation"](property=prop)
            mv = C["ModalPropertyValue"]()
            mv.value = C["IntegerValue"](value=value, unit="us")
            pa.ownedValues.append(mv)
            comp.ownedPropertyAssociations.append(pa)
        conn = C["ConnectionInstance"](name=f"t{i}.p0 -> t{i}.p1")
        conn.source = feats[0]
        conn.destination = feats[1]
        root.connectionInstances.append(conn)
    return root, units * PER_UNIT + 1


def _save(root, pkg, path: Path, kind: str) -> None:
    from pyecore.resources import URI, ResourceSet
    from pyecore.resources.json import JsonResource
    from pyecore.resources.xmi import XMIResource

    rset = ResourceSet()
    rset.metamodel_registry[pkg.nsURI] = pkg
    res = (XMIResource if kind == "xmi" else JsonResource)(URI(str(path)))
    rset.resources[str(path)] = res
    res.resource_set = rset
    res.append(root)
    res.save()


def _load(pkg, path: Path):
    from pyecore.resources import URI, ResourceSet

    rset = ResourceSet()
    rset.metamodel_registry[pkg.nsURI] = pkg
    res = rset.get_resource(URI(str(path)))
    return res.contents[0]


def _phase(args) -> dict:
    workdir = Path(args.workdir)
    if args.phase == "lxml":
        from lxml import etree

        path = workdir / "dynamic.xmi"
        start = time.perf_counter()
        tree = etree.parse(str(path))
        count = sum(1 for _ in tree.iter())
        seconds = time.perf_counter() - start
        return {"seconds": seconds, "objects": count}
    pkg, classes = _classes(args.mode, workdir)
    start = time.perf_counter()
    if args.phase == "build":
        _, count = _build(classes, args.objects)
    elif args.phase.startswith("save"):
        root, count = _build(classes, args.objects)
        start = time.perf_counter()
        _save(root, pkg, workdir / f"{args.mode}.{args.phase[5:]}", args.phase[5:])
    elif args.phase.startswith("load"):
        root = _load(pkg, workdir / f"{args.mode}.{args.phase[5:]}")
        count = sum(1 for _ in root.eAllContents()) + 1
    else:
        raise SystemExit(f"unknown phase {args.phase}")
    seconds = time.perf_counter() - start
    return {"seconds": seconds, "objects": count}


def _peak_mb() -> float:
    """This process's peak resident memory. ``VmHWM`` belongs to the process image, so it starts
    afresh at exec; ``ru_maxrss`` would carry the parent's high-water mark into the child."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def _run_phase(phase: str, mode: str, objects: int, workdir: Path) -> dict:
    cmd = [
        sys.executable,
        "-m",
        "benchmarks.bench_metamodel",
        "--phase",
        phase,
        "--mode",
        mode,
        "--objects",
        str(objects),
        "--workdir",
        str(workdir),
    ]
    root = Path(__file__).resolve().parent.parent
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, cwd=root)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--objects", type=int, default=100_000)
    parser.add_argument("--phase")
    parser.add_argument("--mode", default="dynamic")
    parser.add_argument("--workdir")
    parser.add_argument("--static", action=argparse.BooleanOptionalAction, default=True)
    args = parser.parse_args(argv)
    if args.phase:
        result = _phase(args)
        result["max_rss_mb"] = _peak_mb()
        print(json.dumps(result))
        return 0

    modes = ["dynamic"] + (["static"] if args.static else [])
    with tempfile.TemporaryDirectory(prefix="rosaadl-bench-") as tmp:
        workdir = Path(tmp)
        rows = []
        for mode in modes:
            for phase in ("build", "save-xmi", "save-json", "load-xmi", "load-json"):
                rows.append((mode, phase, _run_phase(phase, mode, args.objects, workdir)))
        floor = _run_phase("lxml", "dynamic", args.objects, workdir)
        size_mb = os.path.getsize(workdir / "dynamic.xmi") / 1e6
    print(f"metamodel benchmark: {args.objects} objects requested; XMI file {size_mb:.1f} MB")
    print(
        f"{'mode':8} {'phase':10} {'objects':>8} {'seconds':>8} {'obj/s':>10} {'x floor':>8} {'peak MB':>8}"
    )
    print(
        f"{'lxml':8} {'parse-xmi':10} {floor['objects']:8d} {floor['seconds']:8.3f} "
        f"{floor['objects'] / floor['seconds']:10.0f} {1.0:8.1f} {floor['max_rss_mb']:8.0f}"
    )
    for mode, phase, r in rows:
        ratio = r["seconds"] / floor["seconds"] if phase == "load-xmi" else float("nan")
        print(
            f"{mode:8} {phase:10} {r['objects']:8d} {r['seconds']:8.3f} "
            f"{r['objects'] / r['seconds']:10.0f} {ratio:8.1f} {r['max_rss_mb']:8.0f}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

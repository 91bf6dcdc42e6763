"""Metamodel benchmark: build, save and load a 100 000-object instance model (XMI and JSON).

Side by side in one run:
  * the raw lxml parse of the same XMI file (the floor a loader cannot beat);
  * our dynamic metamodel (``metamodels/*.ecore`` loaded by pyecore, the shipped choice);
  * static classes generated from the same ``.ecore`` by pyecoregen (the alternative).

The objects are ``benchmarks.generators.instances.flat_instance``. Each phase runs in its own
subprocess so that its peak memory (the whole phase process's, ``harness.process_peak_mib``) is
its own; its time is one call measured by ``harness.best_of``.
Usage: ``python -m benchmarks.bench_metamodel [--objects N]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from benchmarks.generators.instances import FLAT_CLASSES, flat_instance
from benchmarks.harness import Report, best_of, process_peak_mib

__all__ = ["main"]

PHASES = ("build", "save-xmi", "save-json", "load-xmi", "load-json")


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
        return mm, {n: get(n) for n in FLAT_CLASSES}
    pkg = _static_package(workdir)
    return pkg, {n: getattr(pkg, n) for n in FLAT_CLASSES}


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


def _load(pkg, path: Path) -> int:
    from pyecore.resources import URI, ResourceSet

    rset = ResourceSet()
    rset.metamodel_registry[pkg.nsURI] = pkg
    res = rset.get_resource(URI(str(path)))
    return sum(1 for _ in res.contents[0].eAllContents()) + 1


def _lxml(path: Path) -> int:
    from lxml import etree

    return sum(1 for _ in etree.parse(str(path)).iter())


def _phase(args) -> dict:
    workdir = Path(args.workdir)
    if args.phase == "lxml":
        timing = best_of(lambda: _lxml(workdir / "dynamic.xmi"), 1, memory=False)
        count = timing.result
    else:
        pkg, classes = _classes(args.mode, workdir)
        if args.phase == "build":
            timing = best_of(lambda: flat_instance(classes, args.objects), 1, memory=False)
            _, count = timing.result
        elif args.phase.startswith("save"):
            root, count = flat_instance(classes, args.objects)
            kind = args.phase[5:]
            timing = best_of(lambda: _save(root, pkg, workdir / f"{args.mode}.{kind}", kind), 1, memory=False)
        elif args.phase.startswith("load"):
            path = workdir / f"{args.mode}.{args.phase[5:]}"
            timing = best_of(lambda: _load(pkg, path), 1, memory=False)
            count = timing.result
        else:
            raise SystemExit(f"unknown phase {args.phase}")
    return {"cpu": timing.cpu, "wall": timing.wall, "objects": count}


def _run_phase(phase: str, mode: str, objects: int, workdir: Path) -> dict:
    cmd = [sys.executable, "-m", "benchmarks.bench_metamodel", "--phase", phase, "--mode", mode]
    cmd += ["--objects", str(objects), "--workdir", str(workdir)]
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
        result["max_rss_mb"] = process_peak_mib()
        print(json.dumps(result))
        return 0

    modes = ["dynamic"] + (["static"] if args.static else [])
    with tempfile.TemporaryDirectory(prefix="rosaadl-bench-") as tmp:
        workdir = Path(tmp)
        rows = []
        for mode in modes:
            for phase in PHASES:
                rows.append((mode, phase, _run_phase(phase, mode, args.objects, workdir)))
        floor = _run_phase("lxml", "dynamic", args.objects, workdir)
        size_mb = os.path.getsize(workdir / "dynamic.xmi") / 1e6
    print(f"metamodel benchmark: {args.objects} objects requested; XMI file {size_mb:.1f} MB")
    report = Report("metamodel")
    report.add(
        "lxml parse-xmi",
        floor["cpu"],
        wall=floor["wall"],
        peak_mib=floor["max_rss_mb"],
        note=f"{floor['objects']} elements, {floor['objects'] / floor['cpu']:.0f}/s",
    )
    for mode, phase, r in rows:
        report.add(
            f"{mode} {phase}",
            r["cpu"],
            reference=floor["cpu"] if phase == "load-xmi" else None,
            against="lxml parse" if phase == "load-xmi" else "",
            wall=r["wall"],
            peak_mib=r["max_rss_mb"],
            note=f"{r['objects']} objects, {r['objects'] / r['cpu']:.0f}/s",
            detail=mode != "dynamic",
        )
    print("(peak MiB: the resident memory of the phase's whole process)")
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

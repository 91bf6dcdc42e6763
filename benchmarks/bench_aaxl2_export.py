"""OSATE ``.aaxl2`` export benchmark, and the reading cases ``bench_aaxl2`` leaves out.

Export, side by side in one run (CPU time, best of R):
  * ours: :func:`rosaadl.exporters.aaxl2.export_aaxl2` (the ``.aaxl2`` bytes and the ``.aadl``
    sidecar texts);
  * the floor: lxml serialising the same document from a tree already in memory (what writing
    that XML costs at the least);
  * pyecore: pyecore's own XMI writer saving the same instance objects (``model.dumps_xmi``, in
    this project's metamodel; pyecore cannot save them in OSATE's, whose cross-document
    references into ``.aadl`` files it cannot resolve).
Cases: every corpus instance file as read by the importer (no declarative model: opaque
references kept), every corpus instance whose sources instantiate (hrefs into the sidecars
computed), a generated instance file of 50 000 objects read back, and a generated AADL model of
50 000 instance objects instantiated and exported.

Reading, the cases ``bench_aaxl2`` cannot compare with pyecore: the corpus file with EMV2 annex
instances (pyecore needs OSATE's optional EMV2 metamodels, loaded here), and our own export of
the generated instantiated model (current era, hrefs into sidecars), against the raw lxml parse
and pyecore's ``XMIResource`` with OSATE's metamodel.

Usage: ``python -m benchmarks.bench_aaxl2_export [--objects N] [--repeat R] [--corpus DIR]``.
"""

from __future__ import annotations

import argparse
import gc
import hashlib
import io
import logging
import os
import re
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["main", "generate_model"]


def _best(func, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        gc.collect()
        start = time.process_time()
        func()
        best = min(best, time.process_time() - start)
    return best


# --------------------------------------------------------------------------- generated model


def generate_model(objects: int = 50_000, threads_per_process: int = 40) -> str:
    """AADL text whose instance has about ``objects`` instance objects and values.

    Processors, and processes of periodic threads with an in and an out port, chained by port
    connections, every thread with Period, Compute_Execution_Time, Dispatch_Protocol, a
    user-property-set enumeration and units, every process bound to a processor.
    """
    # per thread: the component, 2 features with their inherited values, 6 associations with
    # their values, a connection with its reference: about 50 objects (measured)
    per_process = threads_per_process * 50 + 34
    processes = max(1, -(-objects // per_process))  # at least ``objects``
    lines = [
        "property set gen_props is",
        "  Size_Units: type units (B, KB => B * 1000);",
        "  Level: enumeration (low, mid, high) applies to (all);",
        "  Budget: aadlinteger units gen_props::Size_Units applies to (all);",
        "end gen_props;",
        "",
        "package gen",
        "public",
        "  with gen_props;",
        "  data msg",
        "    properties",
        "      Data_Size => 16 Bytes;",
        "  end msg;",
        "  thread worker",
        "    features",
        "      inp: in event data port msg;",
        "      outp: out event data port msg;",
        "    properties",
        "      Dispatch_Protocol => Periodic;",
        "      Period => 20 ms;",
        "      Compute_Execution_Time => 1 ms .. 3 ms;",
        "      gen_props::Level => mid;",
        "      gen_props::Budget => 4 KB;",
        "  end worker;",
        "  thread implementation worker.impl",
        "  end worker.impl;",
        "  processor cpu",
        "  end cpu;",
        "  process app",
        "    features",
        "      inp: in event data port msg;",
        "      outp: out event data port msg;",
        "  end app;",
        "  process implementation app.impl",
        "    subcomponents",
    ]
    lines += [f"      t{i}: thread worker.impl;" for i in range(threads_per_process)]
    lines += ["    connections", "      cin: port inp -> t0.inp;"]
    lines += [f"      c{i}: port t{i}.outp -> t{i + 1}.inp;" for i in range(threads_per_process - 1)]
    lines += [f"      cout: port t{threads_per_process - 1}.outp -> outp;", "  end app.impl;"]
    lines += ["  system top", "  end top;", "  system implementation top.impl", "    subcomponents"]
    lines += [f"      p{i}: process app.impl;" for i in range(processes)]
    lines += [f"      cpu{i}: processor cpu;" for i in range(processes)]
    lines += ["    connections"]
    lines += [f"      x{i}: port p{i}.outp -> p{i + 1}.inp;" for i in range(processes - 1)]
    lines += ["    properties"]
    lines += [
        f"      Actual_Processor_Binding => (reference (cpu{i})) applies to p{i};" for i in range(processes)
    ]
    lines += ["  end top.impl;", "end gen;", ""]
    return "\n".join(lines)


# --------------------------------------------------------------------------- measuring


def _floor(data: bytes) -> float:
    from lxml import etree

    tree = etree.ElementTree(etree.fromstring(data))
    return lambda: etree.tostring(tree, xml_declaration=True, encoding="ASCII")  # type: ignore[return-value]


def _export_row(subject, repeat: int) -> dict:
    from rosaadl import model
    from rosaadl.exporters.aaxl2 import export_aaxl2

    result = export_aaxl2(subject)
    system = result.instance
    objects = sum(1 for _ in model.walk(system))
    ours = _best(lambda: export_aaxl2(subject), repeat)
    floor = _best(_floor(result.data), repeat)  # type: ignore[arg-type]
    pyecore = _best(lambda: model.dumps_xmi(system), 1 if objects > 10_000 else repeat)
    return {
        "objects": objects,
        "ours": ours,
        "floor": floor,
        "pyecore": pyecore,
        "kib": len(result.data) // 1024,
        "sidecars": len(result.sidecars),
        "data": result.data,
    }


def _sources(folder: Path) -> list[Path]:
    seen, out = set(), []
    for path in sorted(folder.rglob("*")):
        if path.suffix.lower() in (".aadl", ".aadl2") and path.is_file():
            digest = hashlib.sha1(path.read_bytes()).hexdigest()
            if digest not in seen:
                seen.add(digest)
                out.append(path)
    return out


def _instantiable(path: Path, folder: Path):
    """The instance OSATE made from the corpus sources, made by us; None when it cannot be."""
    from rosaadl.errors import RosaadlError
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    text = path.read_text(encoding="ascii", errors="replace")
    match = re.search(r'<(componentImplementation|systemImplementation)[^>]*href="([^"#]*)#([^"]+)"', text)
    sources = _sources(folder)
    if match is None or not sources:
        return None
    try:
        workspace = read_files(sources, warnings=[], check=False)
        fragment = match.group(3)
        if fragment.startswith("/"):
            target = (path.parent / match.group(2)).resolve()
            unit = next(u for u in workspace.units if u.sourceFile and Path(u.sourceFile).resolve() == target)
            public = [c for c in unit.classifiers if c.visibility.name != "private"]
            root = f"{unit.name}::{public[int(fragment.rpartition('.')[2])].name}"
        else:
            package, _, local = fragment.partition(".")
            root = f"{package}::{local}"
        legacy = match.group(1) == "systemImplementation"
        return instantiate(workspace, root, strict=False, compatibility="osate-2.0" if legacy else "current")
    except (RosaadlError, StopIteration):
        return None


def _pyecore_resource_set(metamodel_dir: Path, with_emv2: bool):
    """OSATE's metamodels in pyecore, patched as ``bench_aaxl2`` does (numbers, Java literals),
    with the optional EMV2 metamodels when asked."""
    from pyecore.resources import URI

    from benchmarks.bench_aaxl2 import _osate_resource_set

    rset = _osate_resource_set(metamodel_dir)
    if with_emv2:
        optional = metamodel_dir / "optional"
        rset.uri_mapper["platform:/resource/org.osate.aadl2/model"] = str(metamodel_dir)
        rset.uri_mapper["../../org.osate.aadl2/model"] = str(metamodel_dir)
        rset.uri_mapper["../../org.osate.xtext.aadl2.errormodel/model/generated"] = str(optional)
        for name in ("ErrorModel.ecore", "EMV2Instance.ecore"):
            package = rset.get_resource(URI(str(optional / name))).contents[0]
            rset.metamodel_registry[package.nsURI] = package
    return rset


def _pyecore_read(metamodel_dir: Path, data: bytes, with_emv2: bool) -> float:
    from pyecore.resources import URI
    from pyecore.resources.xmi import XMIResource

    class Memory(URI):
        def create_instream(self):
            return io.BytesIO(data)

        def close_stream(self):
            pass

    rset = _pyecore_resource_set(metamodel_dir, with_emv2)
    gc.collect()
    start = time.process_time()
    resource = XMIResource(Memory("memory.aaxl2"))
    resource.resource_set = rset
    resource.load()
    return time.process_time() - start


def _read_row(data: bytes, metamodel_dir: Path | None, repeat: int, with_emv2: bool = False) -> dict:
    from rosaadl import model
    from rosaadl.fileio import parse_xml_bytes
    from rosaadl.importers.aaxl2 import loads_aaxl2

    objects = sum(1 for _ in model.walk(loads_aaxl2(data).model))
    floor = _best(lambda: parse_xml_bytes(data, "<bench>"), repeat)
    ours = _best(lambda: loads_aaxl2(data), repeat)
    pyecore, note = None, ""
    if metamodel_dir is not None:
        try:
            pyecore = min(
                _pyecore_read(metamodel_dir, data, with_emv2) for _ in range(1 if objects > 10_000 else 3)
            )
        except Exception as exc:  # pyecore's failure is a result here
            note = f"pyecore fails: {type(exc).__name__}: {str(exc).splitlines()[0][:50]}"
    return {"objects": objects, "floor": floor, "ours": ours, "pyecore": pyecore, "note": note}


# --------------------------------------------------------------------------- report


def _print_export(rows: list[tuple[str, dict]]) -> None:
    print(
        f"{'export (ours: .aaxl2 and sidecars)':40s} {'objects':>8s} {'KiB':>6s} {'ours ms':>8s} "
        f"{'floor ms':>9s} {'/floor':>7s} "
        f"{'pyecore ms':>11s} {'pyecore/ours':>13s}"
    )
    for label, row in rows:
        print(
            f"{label[:40]:40s} {row['objects']:8d} {row['kib']:6d} {row['ours'] * 1000:8.2f} "
            f"{row['floor'] * 1000:9.2f} {row['ours'] / row['floor']:6.1f}x {row['pyecore'] * 1000:11.2f} "
            f"{row['pyecore'] / row['ours']:12.1f}x"
        )


def _print_read(rows: list[tuple[str, dict]]) -> None:
    print(
        f"{'read':40s} {'objects':>8s} {'floor ms':>9s} {'ours ms':>8s} {'/floor':>7s} "
        f"{'pyecore ms':>11s} {'pyecore/ours':>13s}"
    )
    for label, row in rows:
        py = f"{row['pyecore'] * 1000:11.2f}" if row["pyecore"] is not None else f"{'n/a':>11s}"
        speed = f"{row['pyecore'] / row['ours']:12.1f}x" if row["pyecore"] is not None else f"{'':>13s}"
        print(
            f"{label[:40]:40s} {row['objects']:8d} {row['floor'] * 1000:9.2f} {row['ours'] * 1000:8.2f} "
            f"{row['ours'] / row['floor']:6.1f}x {py} {speed} {row['note']}"
        )


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_aaxl2_export", description=__doc__.splitlines()[0])
    parser.add_argument("--objects", type=int, default=50_000)
    parser.add_argument("--repeat", type=int, default=3)
    default_corpus = os.environ.get("ROSAADL_CORPUS") or str(
        Path(__file__).resolve().parents[2] / "shared" / "corpus"
    )
    parser.add_argument("--corpus", default=default_corpus)
    args = parser.parse_args(argv)
    logging.disable(logging.WARNING)  # the exporter's warnings about corpus files are expected
    try:
        return _run(args)
    finally:
        logging.disable(logging.NOTSET)


def _run(args) -> int:
    from benchmarks.bench_aaxl2 import generate_instance
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.importers.aaxl2 import loads_aaxl2, read_aaxl2
    from rosaadl.transforms.instantiate import instantiate

    corpus = Path(args.corpus)
    metamodel_dir = corpus / "osate" / "metamodel"
    if not (metamodel_dir / "instance.ecore").is_file():
        metamodel_dir = None
        print("OSATE metamodel not found: the pyecore reading column is left out", file=sys.stderr)
    files = []
    if (corpus / "osate" / "aaxl2").is_dir():
        for path in sorted((corpus / "osate" / "aaxl2").rglob("*.aaxl2")):
            if b"instance:SystemInstance" in path.read_bytes()[:800]:
                files.append(path)
    export_rows: list[tuple[str, dict]] = []
    read_rows: list[tuple[str, dict]] = []
    for path in files:
        short = path.relative_to(corpus / "osate" / "aaxl2").parts[0]
        export_rows.append((f"{short} (imported)", _export_row(read_aaxl2(path).model, args.repeat)))
    for path in files:
        short = path.relative_to(corpus / "osate" / "aaxl2").parts[0]
        system = _instantiable(path, corpus / "osate" / "aaxl2" / short)
        if system is not None:
            export_rows.append((f"{short} (instantiated)", _export_row(system, args.repeat)))
    with tempfile.TemporaryDirectory() as tmp:
        generated = Path(tmp) / "generated_Instance.aaxl2"
        generate_instance(generated, int(args.objects * 1.02))
        imported = read_aaxl2(generated)
        export_rows.append(("generated instance file (imported)", _export_row(imported.model, 2)))
        (Path(tmp) / "gen.aadl").write_text(generate_model(args.objects), encoding="utf-8")
        workspace = read_files([Path(tmp) / "gen.aadl"], warnings=[])
        start = time.process_time()
        system = instantiate(workspace, "gen::top.impl")
        instantiated_s = time.process_time() - start
        row = _export_row(system, 2)
        export_rows.append(("generated AADL model (instantiated)", row))
        emv2 = [p for p in files if b"EMV2Instance" in p.read_bytes()[:2000]]
        for path in emv2:
            short = path.relative_to(corpus / "osate" / "aaxl2").parts[0]
            read_rows.append(
                (f"{short} (EMV2 metamodels)", _read_row(path.read_bytes(), metamodel_dir, 5, True))
            )
        read_rows.append(("our export of the generated model", _read_row(row["data"], metamodel_dir, 2)))
        again = loads_aaxl2(row["data"])
    _print_export(export_rows)
    total_ours = sum(r["ours"] for _, r in export_rows)
    total_floor = sum(r["floor"] for _, r in export_rows)
    big = export_rows[-1][1]
    print(
        f"{'all exports':40s} {sum(r['objects'] for _, r in export_rows):8d} {'':6s} "
        f"{total_ours * 1000:8.2f} {total_floor * 1000:9.2f} {total_ours / total_floor:6.1f}x"
    )
    print(
        f"generated model: {big['objects']} instance objects (instantiated in {instantiated_s:.2f} s), "
        f"exported in {big['ours'] * 1000:.0f} ms with {big['sidecars']} sidecar(s): "
        f"{big['ours'] / big['floor']:.1f}x the lxml floor, {big['pyecore'] / big['ours']:.1f}x faster "
        "than pyecore's XMI writer on the same objects"
    )
    print()
    _print_read(read_rows)
    print(f"(the generated export reads back with {len(again.warnings)} warning(s), era {again.era})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

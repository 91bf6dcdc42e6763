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
computed), a generated instance file of 50 000 objects read back
(``benchmarks.generators.aaxl2.write_aaxl2_instance``), and a generated AADL model of 50 000
instance objects (``benchmarks.generators.aadl_text.instantiable_package_text``) instantiated
and exported.

Reading, the cases ``bench_aaxl2`` cannot compare with pyecore: the corpus file with EMV2 annex
instances (pyecore needs OSATE's optional EMV2 metamodels, loaded here), and our own export of
the generated instantiated model (current era, hrefs into sidecars), against the raw lxml parse
and pyecore's ``XMIResource`` with OSATE's metamodel (``benchmarks.generators.osate``).

Usage: ``python -m benchmarks.bench_aaxl2_export [--objects N] [--repeat R] [--corpus DIR]``.
"""

from __future__ import annotations

import argparse
import io
import logging
import re
import sys
import tempfile
from pathlib import Path

from benchmarks.generators.aadl_text import instantiable_package_text
from benchmarks.generators.aaxl2 import write_aaxl2_instance
from benchmarks.generators.corpus import aadl_sources, aaxl2_instance_files, corpus_dir
from benchmarks.generators.osate import osate_metamodels
from benchmarks.harness import Report, Timing, best_of

__all__ = ["main"]


# --------------------------------------------------------------------------- measuring


def _serialise(data: bytes):
    from lxml import etree

    tree = etree.ElementTree(etree.fromstring(data))
    return lambda: etree.tostring(tree, xml_declaration=True, encoding="ASCII")


def _export_row(subject, repeat: int) -> dict:
    from rosaadl import model
    from rosaadl.exporters.aaxl2 import export_aaxl2

    result = export_aaxl2(subject)
    system = result.instance
    objects = sum(1 for _ in model.walk(system))
    return {
        "objects": objects,
        "ours": best_of(lambda: export_aaxl2(subject), repeat, keep=False),
        "floor": best_of(_serialise(result.data), repeat, keep=False),
        "pyecore": best_of(lambda: model.dumps_xmi(system), 1 if objects > 10_000 else repeat, keep=False),
        "kib": len(result.data) // 1024,
        "sidecars": len(result.sidecars),
        "data": result.data,
    }


def _instantiable(path: Path, folder: Path):
    """The instance OSATE made from the corpus sources, made by us; None when it cannot be."""
    from rosaadl.errors import RosaadlError
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    text = path.read_text(encoding="ascii", errors="replace")
    match = re.search(r'<(componentImplementation|systemImplementation)[^>]*href="([^"#]*)#([^"]+)"', text)
    sources = aadl_sources(folder)
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


def _pyecore_read(metamodel_dir: Path, data: bytes, with_emv2: bool, rounds: int) -> Timing:
    """pyecore's ``XMIResource`` loading ``data`` with OSATE's metamodels; their preparation is
    not part of it (a new resource set before each round)."""
    from pyecore.resources import URI
    from pyecore.resources.xmi import XMIResource

    class Memory(URI):
        def create_instream(self):
            return io.BytesIO(data)

        def close_stream(self):
            pass

    def load(rset) -> None:
        resource = XMIResource(Memory("memory.aaxl2"))
        resource.resource_set = rset
        resource.load()

    return best_of(
        load, rounds, setup=lambda: osate_metamodels(metamodel_dir, with_emv2=with_emv2)[0], keep=False
    )


def _read_row(data: bytes, metamodel_dir: Path | None, repeat: int, with_emv2: bool = False) -> dict:
    from rosaadl import model
    from rosaadl.fileio import parse_xml_bytes
    from rosaadl.importers.aaxl2 import loads_aaxl2

    objects = sum(1 for _ in model.walk(loads_aaxl2(data).model))
    floor = best_of(lambda: parse_xml_bytes(data, "<bench>"), repeat, keep=False)
    ours = best_of(lambda: loads_aaxl2(data), repeat, keep=False)
    pyecore, note = None, ""
    if metamodel_dir is not None:
        try:
            pyecore = _pyecore_read(metamodel_dir, data, with_emv2, 1 if objects > 10_000 else 3)
        except Exception as exc:  # pyecore's failure is a result here
            note = f"pyecore fails: {type(exc).__name__}: {str(exc).splitlines()[0][:50]}"
    return {"objects": objects, "floor": floor, "ours": ours, "pyecore": pyecore, "note": note}


# --------------------------------------------------------------------------- report


def _report_export(report: Report, label: str, row: dict, detail: bool) -> None:
    what = f"{row['objects']} objects, {row['kib']} KiB"
    pyecore = f"pyecore {row['pyecore'].cpu * 1000:.2f} ms, {row['pyecore'].cpu / row['ours'].cpu:.1f}x ours"
    report.time(
        f"export {label}",
        row["ours"],
        row["floor"],
        against="lxml write",
        note=f"{what}; {pyecore}",
        detail=detail,
    )
    if not detail:
        report.time(f"export {label}", row["ours"], row["pyecore"], against="pyecore", note=what)


def _report_read(report: Report, label: str, row: dict) -> None:
    note = f"{row['objects']} objects" + (f"; {row['note']}" if row["note"] else "")
    report.time(f"read {label}", row["ours"], row["floor"], against="lxml parse", note=note)
    if row["pyecore"] is not None:
        report.time(f"read {label}", row["ours"], row["pyecore"], against="pyecore")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="bench_aaxl2_export", description=__doc__.splitlines()[0])
    parser.add_argument("--objects", type=int, default=50_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--corpus", default=str(corpus_dir()))
    args = parser.parse_args(argv)
    logging.disable(logging.WARNING)  # the exporter's warnings about corpus files are expected
    try:
        return _run(args)
    finally:
        logging.disable(logging.NOTSET)


def _run(args) -> int:
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.importers.aaxl2 import loads_aaxl2, read_aaxl2
    from rosaadl.transforms.instantiate import instantiate

    corpus = Path(args.corpus)
    metamodel_dir: Path | None = corpus / "osate" / "metamodel"
    if not (metamodel_dir / "instance.ecore").is_file():
        metamodel_dir = None
        print("OSATE metamodel not found: the pyecore reading column is left out", file=sys.stderr)
    files = aaxl2_instance_files(corpus)
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
        write_aaxl2_instance(generated, int(args.objects * 1.02))
        imported = read_aaxl2(generated)
        export_rows.append(("generated instance file (imported)", _export_row(imported.model, 2)))
        (Path(tmp) / "gen.aadl").write_text(instantiable_package_text(args.objects), encoding="utf-8")
        workspace = read_files([Path(tmp) / "gen.aadl"], warnings=[])
        instantiated = best_of(lambda: instantiate(workspace, "gen::top.impl"), 1)
        row = _export_row(instantiated.result, 2)
        export_rows.append(("generated AADL model (instantiated)", row))
        emv2 = [p for p in files if b"EMV2Instance" in p.read_bytes()[:2000]]
        for path in emv2:
            short = path.relative_to(corpus / "osate" / "aaxl2").parts[0]
            read_rows.append(
                (f"{short} (EMV2 metamodels)", _read_row(path.read_bytes(), metamodel_dir, 5, True))
            )
        read_rows.append(("our export of the generated model", _read_row(row["data"], metamodel_dir, 2)))
        again = loads_aaxl2(row["data"])

    report = Report("aaxl2_export")
    for label, export in export_rows:
        _report_export(report, label, export, detail=not label.startswith("generated"))
    report.add(
        "export, all cases",
        sum(r["ours"].cpu for _, r in export_rows),
        reference=sum(r["floor"].cpu for _, r in export_rows),
        against="lxml write",
        note=f"{sum(r['objects'] for _, r in export_rows)} objects, {len(export_rows)} cases",
    )
    report.time(
        "instantiate the generated AADL model",
        instantiated,
        note=f"{row['objects']} instance objects, exported with {row['sidecars']} sidecar(s)",
        detail=True,
    )
    for label, read in read_rows:
        _report_read(report, label, read)
    print(f"(the generated export reads back with {len(again.warnings)} warning(s), era {again.era})")
    return report.finish()


if __name__ == "__main__":
    raise SystemExit(main())

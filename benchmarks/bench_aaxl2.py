"""OSATE ``.aaxl2`` import benchmark: every corpus instance file and a generated 50 000-object one.

Side by side in one run, on the same bytes already in memory:
  * the floor: the raw (hardened) lxml parse of the file, which any importer must do first;
  * ours: :func:`rosaadl.importers.aaxl2.loads_aaxl2` (parse, build, resolve, decode);
  * pyecore's own ``XMIResource`` loading the file with OSATE's ``aadl2.ecore`` +
    ``instance.ecore`` from the corpus, patched minimally so that it loads: the numeric and
    boolean EDataTypes get conversions, and the enumerations accept the Java literals OSATE
    writes (``in out``, ``thread group``). Files that still do not load (2014 files use
    features the current metamodel no longer has) are marked as such.

Goals (issue 5): ours within 5x of the floor, and at least 3x faster than pyecore.
Usage: ``python -m benchmarks.bench_aaxl2 [--objects N] [--repeat R] [--corpus DIR]``.
"""

from __future__ import annotations

import argparse
import gc
import io
import os
import re
import sys
import tempfile
import time
from pathlib import Path

__all__ = ["main", "generate_instance"]

_HEADER = (
    '<?xml version="1.0" encoding="ASCII"?>\n'
    '<instance:SystemInstance xmi:version="2.0" xmlns:xmi="http://www.omg.org/XMI" '
    'xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xmlns:aadl2="http://aadl.info/AADL/2.0" '
    'xmlns:instance="http://aadl.info/AADL/2.0/instance" name="gen_impl_Instance" category="system">\n'
)
_PS = "platform:/plugin/org.osate.aadl2.contrib/resources/properties/Predeclared_Property_Sets/"
_AADL = "../gen.aadl#/0/@ownedPublicSection/@ownedClassifier."


def _pa(prop: str, value: str, indent: str) -> str:
    return (
        f'{indent}<ownedPropertyAssociation xsi:type="instance:PropertyAssociationInstance">\n'
        f'{indent}  <property href="{_PS}{prop}"/>\n'
        f"{indent}  <ownedValue>\n{value}{indent}  </ownedValue>\n"
        f"{indent}</ownedPropertyAssociation>\n"
    )


def _integer(value: int, unit: str, indent: str, tag: str = "ownedValue") -> str:
    return (
        f'{indent}<{tag} xsi:type="aadl2:IntegerLiteral" value="{value}">\n'
        f'{indent}  <unit href="{_PS}AADL_Project.aadl#/0/@ownedPropertyType.{unit}"/>\n'
        f"{indent}</{tag}>\n"
    )


_MS = "16/@ownedLiteral.3"
_BYTES = "15/@ownedLiteral.1"
# objects our importer makes per thread (component, 2 features, 5 property associations with
# their values, 1 connection with 2 references) and per process / processor.
_PER_THREAD = 1 + 2 + (3 + 3 + 5 + 4) + 3 + 3
_PER_PROCESS = 1 + 4
_PER_PROCESSOR = 1


def generate_instance(
    path: str | os.PathLike[str], objects: int = 50_000, threads_per_process: int = 50
) -> int:
    """Write a realistic current-era instance file with about ``objects`` objects; return the count.

    Processors, processes bound to them and periodic threads with Period, Dispatch_Protocol,
    Compute_Execution_Time, Actual_Processor_Binding and Data_Size, chained by port connections.
    """
    per_process = _PER_PROCESS + threads_per_process * _PER_THREAD + _PER_PROCESSOR
    processes = max(1, (objects - 3) // per_process)
    out = io.StringIO()
    out.write(_HEADER)
    for p in range(processes):
        out.write(f'  <componentInstance name="cpu{p}" category="processor">\n')
        out.write(
            '    <subcomponent xsi:type="aadl2:ProcessorSubcomponent" '
            f'href="{_AADL}9/@ownedProcessorSubcomponent.{p}"/>\n'
        )
        out.write("    <index>0</index>\n")
        out.write('    <classifier xsi:type="aadl2:ProcessorType" href="../gen.aadl#gen.cpu"/>\n')
        out.write("  </componentInstance>\n")
    for p in range(processes):
        cpu = f"//@componentInstance.{p}"
        out.write(f'  <componentInstance name="proc{p}" category="process">\n')
        binding = (
            '        <ownedValue xsi:type="aadl2:ListValue">\n'
            '          <ownedListElement xsi:type="instance:InstanceReferenceValue" '
            f'referencedInstanceObject="{cpu}"/>\n'
            "        </ownedValue>\n"
        )
        out.write(
            _pa("Deployment_Properties.aadl#Deployment_Properties.Actual_Processor_Binding", binding, "    ")
        )
        for t in range(threads_per_process):
            out.write(f'    <componentInstance name="t{t}" category="thread">\n')
            ind = "      "
            out.write(
                _pa(
                    "Timing_Properties.aadl#Timing_Properties.Period",
                    _integer(10 * (t + 1), _MS, ind + "    "),
                    ind,
                )
            )
            dispatch = (
                f'{ind}    <ownedValue xsi:type="aadl2:NamedValue">\n'
                f'{ind}      <namedValue xsi:type="aadl2:EnumerationLiteral" '
                f'href="{_PS}AADL_Project.aadl#/0/@ownedPropertyType.3/@ownedLiteral.0"/>\n'
                f"{ind}    </ownedValue>\n"
            )
            out.write(_pa("Thread_Properties.aadl#Thread_Properties.Dispatch_Protocol", dispatch, ind))
            cet = (
                f'{ind}    <ownedValue xsi:type="aadl2:RangeValue">\n'
                + _integer(1, _MS, ind + "      ", "minimum")
                + _integer(t % 7 + 2, _MS, ind + "      ", "maximum")
                + f"{ind}    </ownedValue>\n"
            )
            out.write(_pa("Timing_Properties.aadl#Timing_Properties.Compute_Execution_Time", cet, ind))
            out.write(
                _pa(
                    "Deployment_Properties.aadl#Deployment_Properties.Actual_Processor_Binding",
                    binding.replace("        ", ind + "    "),
                    ind,
                )
            )
            out.write(f'{ind}<featureInstance name="inp" category="eventDataPort">\n')
            out.write(
                f'{ind}  <feature xsi:type="aadl2:EventDataPort" href="{_AADL}1/@ownedEventDataPort.0"/>\n'
            )
            out.write(f"{ind}</featureInstance>\n")
            out.write(f'{ind}<featureInstance name="outp" category="eventDataPort" direction="out">\n')
            out.write(
                _pa(
                    "Memory_Properties.aadl#Memory_Properties.Data_Size",
                    _integer(64 * (t + 1), _BYTES, ind + "      "),
                    ind + "  ",
                )
            )
            out.write(
                f'{ind}  <feature xsi:type="aadl2:EventDataPort" href="{_AADL}1/@ownedEventDataPort.1"/>\n'
            )
            out.write(f"{ind}</featureInstance>\n")
            out.write(
                f'{ind}<subcomponent xsi:type="aadl2:ThreadSubcomponent" '
                f'href="{_AADL}3/@ownedThreadSubcomponent.{t}"/>\n'
            )
            out.write(f"{ind}<index>0</index>\n")
            out.write(
                f'{ind}<classifier xsi:type="aadl2:ThreadImplementation" '
                'href="../gen.aadl#gen.worker.impl"/>\n'
            )
            out.write("    </componentInstance>\n")
        for t in range(threads_per_process):
            src = f"//@componentInstance.{processes + p}/@componentInstance.{t}/@featureInstance.1"
            dst_t = (t + 1) % threads_per_process
            dst = f"//@componentInstance.{processes + p}/@componentInstance.{dst_t}/@featureInstance.0"
            out.write(
                f'    <connectionInstance name="t{t}.outp -> t{dst_t}.inp" '
                'complete="true" kind="portConnection" '
                f'destination="{dst}" source="{src}">\n'
            )
            for _ in range(2):
                out.write(
                    f'      <connectionReference context="//@componentInstance.{processes + p}" '
                    f'source="{src}" destination="{dst}">\n'
                    '        <connection xsi:type="aadl2:PortConnection" '
                    f'href="{_AADL}3/@ownedPortConnection.{t}"/>\n'
                    "      </connectionReference>\n"
                )
            out.write("    </connectionInstance>\n")
        out.write(
            '    <subcomponent xsi:type="aadl2:ProcessSubcomponent" '
            f'href="{_AADL}5/@ownedProcessSubcomponent.{p}"/>\n'
        )
        out.write("    <index>0</index>\n")
        out.write(
            '    <classifier xsi:type="aadl2:ProcessImplementation" href="../gen.aadl#gen.app.impl"/>\n'
        )
        out.write("  </componentInstance>\n")
    out.write('  <systemOperationMode name="No Modes"/>\n')
    out.write(
        '  <componentImplementation xsi:type="aadl2:SystemImplementation" href="../gen.aadl#gen.top.impl"/>\n'
    )
    out.write("</instance:SystemInstance>\n")
    Path(path).write_text(out.getvalue(), encoding="ascii")
    # the AadlModel, the root, its operation mode, and what each process brings
    return 3 + processes * per_process


# --------------------------------------------------------------------------- pyecore with OSATE's metamodel


def _osate_resource_set(metamodel_dir: Path):
    """A pyecore ResourceSet with OSATE's metamodels, patched minimally so that files load."""
    from pyecore.ecore import EDataType, EEnum
    from pyecore.resources import URI, ResourceSet

    rset = ResourceSet()
    packages = []
    for name in ("aadl2.ecore", "instance.ecore"):
        package = rset.get_resource(URI(str(metamodel_dir / name))).contents[0]
        rset.metamodel_registry[package.nsURI] = package
        packages.append(package)
    conversions = {"Integer": int, "Real": float, "Boolean": lambda s: s == "true", "String": str}
    for package in packages:
        for classifier in package.eClassifiers:
            if isinstance(classifier, EEnum):
                by_text = {}
                for literal in classifier.eLiterals:
                    by_text[literal.name] = literal
                    by_text[re.sub(r"(?<!^)(?=[A-Z])", " ", literal.name).lower()] = literal
                classifier.from_string = by_text.__getitem__
            elif isinstance(classifier, EDataType) and classifier.name in conversions:
                convert = conversions[classifier.name]
                classifier.from_string = convert
                classifier.to_string = str
    return rset


def _pyecore_load(metamodel_dir: Path, path: Path) -> int:
    from pyecore.resources import URI

    rset = _osate_resource_set(metamodel_dir)
    # the metamodel preparation is not part of the load
    gc.collect()
    start = time.process_time()
    resource = rset.get_resource(URI(str(path)))
    _pyecore_load.seconds = time.process_time() - start  # type: ignore[attr-defined]
    return sum(1 + sum(1 for _ in root.eAllContents()) for root in resource.contents)


# --------------------------------------------------------------------------- timing


def _best_pair(floor_func, ours_func, repeat: int, min_seconds: float = 0.1) -> dict[str, float]:
    """Best CPU times (process time: other processes do not count) of the floor and of ours.

    Each is measured in blocks of back-to-back calls; the blocks alternate (floor, ours, floor,
    ours, ...), four rounds, so that both see the same drift of the machine's speed. A floor
    block is at least ``repeat`` calls, more for small files, until ``min_seconds`` (at most
    1000); the ours block that follows makes as many calls. Both bests are minima, and a
    minimum over more calls is lower only for having had more draws: on a sub-millisecond
    file, whose times spread over 2-3x on this kind of machine, the floor given 3-4x the
    calls of ours (as a time budget per block gives it) came out up to 10 % lower than over
    as many calls as ours, in the same run. ``gc.collect()`` before each call starts every
    measurement from the same state; collections a call triggers count.

    Two bests per function: ``floor``/``ours``, over every call, and ``floor_settled``/
    ``ours_settled``, over the calls that follow a call of the same function (each block but
    its first call). They differ for large files: the first parse after an import runs on
    memory the import left consolidated, while back to back, each parse pays glibc's merge of
    the previous tree's freed nodes (for the generated file, about 55-80 against 100-110 ms).
    ``floor``, the lowest, is the one the goal is judged against.
    """
    best = {
        "floor": float("inf"),
        "ours": float("inf"),
        "floor_settled": float("inf"),
        "ours_settled": float("inf"),
    }
    for _round in range(4):
        floor_calls = None  # how many calls the floor made in this round: ours makes as many
        for key, func in (("floor", floor_func), ("ours", ours_func)):
            spent, calls = 0.0, 0
            while True:
                if floor_calls is None:
                    if calls >= repeat and (spent >= min_seconds or calls >= 1000):
                        break
                elif calls >= floor_calls:
                    break
                gc.collect()
                start = time.process_time()
                func()
                elapsed = time.process_time() - start
                best[key] = min(best[key], elapsed)
                if calls:
                    best[f"{key}_settled"] = min(best[f"{key}_settled"], elapsed)
                spent += elapsed
                calls += 1
            floor_calls = calls
    return best


def _measure(path: Path, metamodel_dir: Path | None, repeat: int) -> dict:
    from rosaadl import model
    from rosaadl.fileio import parse_xml_bytes
    from rosaadl.importers.aaxl2 import loads_aaxl2

    data = path.read_bytes()
    # the first parse of the file in the run, before the allocator holds memory freed by an
    # import of it: slower than the steady-state floor below, for large files by about half
    gc.collect()
    start = time.process_time()
    parse_xml_bytes(data, str(path))
    first_parse = time.process_time() - start
    result = loads_aaxl2(data, str(path))
    objects = sum(1 for _ in model.walk(result.model))
    del result
    best = _best_pair(lambda: parse_xml_bytes(data, str(path)), lambda: loads_aaxl2(data, str(path)), repeat)
    floor, ours = best["floor"], best["ours"]
    pyecore_s = None
    note = ""
    if metamodel_dir is not None:
        times = []
        try:
            for _ in range(max(1, repeat // 2)):
                gc.collect()
                _pyecore_load(metamodel_dir, path)
                times.append(_pyecore_load.seconds)  # type: ignore[attr-defined]
            pyecore_s = min(times)
        except Exception as exc:  # pyecore's own failure is a result here, not an error
            note = f"pyecore fails: {type(exc).__name__}: {str(exc).splitlines()[0][:60]}"
    return {
        "objects": objects,
        "floor": floor,
        "first_parse": first_parse,
        "floor_settled": best["floor_settled"],
        "ours": ours,
        "ours_settled": best["ours_settled"],
        "pyecore": pyecore_s,
        "note": note,
    }


def _breakdown(path: Path) -> dict[str, float]:
    """Where our time goes on one file: parse, build, resolve, decode, and the collection of the
    young objects once the garbage collector is enabled again (best of 3, CPU time)."""
    from rosaadl.bulk import gc_paused
    from rosaadl.fileio import parse_xml_bytes
    from rosaadl.importers.aaxl2.document import Reader
    from rosaadl.importers.aaxl2.instances import read_instance_roots
    from rosaadl.importers.aaxl2.literals import decode_literals
    from rosaadl.importers.aaxl2.references import resolve_pending

    data = path.read_bytes()
    best: dict[str, float] = {}
    for _ in range(3):
        gc.collect()
        times = {}
        start = time.process_time()
        with gc_paused():
            tree = parse_xml_bytes(data, str(path), remove_blank_text=True)  # as the import parses
            times["parse"] = time.process_time() - start
            reader = Reader(str(path), tree, strict=False)
            mark = time.process_time()
            read_instance_roots(reader, tree.getroot())
            times["build"] = time.process_time() - mark
            mark = time.process_time()
            resolve_pending(reader)
            times["resolve"] = time.process_time() - mark
            mark = time.process_time()
            decode_literals(reader)
            times["decode"] = time.process_time() - mark
            mark = time.process_time()
        _ = [[] for _ in range(1000)]  # the first allocations after the pause trigger the collection
        times["gc"] = time.process_time() - mark
        for key, value in times.items():
            best[key] = min(best.get(key, value), value)
        del reader, tree
    return best


def _corpus_files(corpus: Path) -> list[Path]:
    files = []
    for path in sorted((corpus / "osate" / "aaxl2").rglob("*.aaxl2")):
        head = path.read_bytes()[:600]
        if b"instance:SystemInstance" in head or b"xmi:XMI" in head:
            files.append(path)
    return files


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="bench_aaxl2", description=__doc__.splitlines()[0])
    parser.add_argument("--objects", type=int, default=50_000)
    parser.add_argument("--repeat", type=int, default=5)
    default_corpus = os.environ.get("ROSAADL_CORPUS") or str(
        Path(__file__).resolve().parents[2] / "shared" / "corpus"
    )
    parser.add_argument("--corpus", default=default_corpus)
    args = parser.parse_args(argv)
    corpus = Path(args.corpus)
    metamodel_dir = corpus / "osate" / "metamodel"
    if not (metamodel_dir / "instance.ecore").is_file():
        metamodel_dir = None
        print("OSATE metamodel not found: the pyecore column is left out", file=sys.stderr)
    rows = []
    files = _corpus_files(corpus) if corpus.is_dir() else []
    with tempfile.TemporaryDirectory() as tmp:
        generated = Path(tmp) / "generated_Instance.aaxl2"
        expected = generate_instance(generated, args.objects)
        for path in files:
            label = path.relative_to(corpus / "osate" / "aaxl2").parts[0]
            rows.append((label, _measure(path, metamodel_dir, args.repeat)))
        generated_row = _measure(generated, metamodel_dir, max(3, args.repeat // 2))
        generated_row["breakdown"] = _breakdown(generated)
        if generated_row["objects"] != expected:
            print(f"generated file: {generated_row['objects']} objects, expected {expected}", file=sys.stderr)
        rows.append((f"generated ({generated.stat().st_size // 1024} KiB)", generated_row))

    print(
        f"{'file':38s} {'objects':>8s} {'floor ms':>9s} {'ours ms':>8s} {'/floor':>7s} "
        f"{'pyecore ms':>11s} {'pyecore/ours':>13s}"
    )
    for label, row in rows:
        py = f"{row['pyecore'] * 1000:11.2f}" if row["pyecore"] is not None else f"{'n/a':>11s}"
        speed = f"{row['pyecore'] / row['ours']:12.1f}x" if row["pyecore"] is not None else f"{'':>13s}"
        print(
            f"{label[:38]:38s} {row['objects']:8d} {row['floor'] * 1000:9.2f} {row['ours'] * 1000:8.2f} "
            f"{row['ours'] / row['floor']:6.1f}x {py} {speed} {row['note']}"
        )
    total_floor = sum(r["floor"] for _, r in rows)
    total_ours = sum(r["ours"] for _, r in rows)
    loaded = [r for _, r in rows if r["pyecore"] is not None]
    print(
        f"{'all files':38s} {sum(r['objects'] for _, r in rows):8d} "
        f"{total_floor * 1000:9.2f} {total_ours * 1000:8.2f} "
        f"{total_ours / total_floor:6.1f}x"
    )
    big_parts = dict(rows[-1][1].get("breakdown", {}))
    if big_parts:
        floor = rows[-1][1]["floor"]
        # what the phases leave out: freeing the parsed document (libxml2's many small frees, which
        # the C allocator consolidates at the next large allocation) and the result's assembly
        big_parts["rest"] = max(0.0, rows[-1][1]["ours"] - sum(big_parts.values()))
        print(
            "generated file, where our time goes (x floor): "
            + ", ".join(
                f"{key} {value * 1000:.0f} ms ({value / floor:.1f}x)" for key, value in big_parts.items()
            )
        )
    big = rows[-1][1]
    worst = max(r["ours"] / r["floor"] for _, r in rows[:-1]) if len(rows) > 1 else float("nan")
    print(
        f"generated file, each back to back: floor {big['floor_settled'] * 1000:.1f} ms, ours "
        f"{big['ours_settled'] * 1000:.1f} ms ({big['ours_settled'] / big['floor_settled']:.1f}x); "
        f"the first parse in the run {big['first_parse'] * 1000:.1f} ms"
    )
    print(
        f"goal ours <= 5x floor: generated {big['ours'] / big['floor']:.1f}x the lowest parse "
        f"({big['ours'] / big['first_parse']:.1f}x its first parse in the run), "
        f"worst corpus file {worst:.1f}x"
    )
    if loaded:
        slowest = min(r["pyecore"] / r["ours"] for r in loaded)
        gen_speedup = f"{big['pyecore'] / big['ours']:.1f}x" if big["pyecore"] is not None else "n/a"
        print(
            f"goal >= 3x faster than pyecore: generated {gen_speedup}, "
            f"least on a loadable file {slowest:.1f}x "
            f"({len(loaded)} of {len(rows)} files load in pyecore)"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

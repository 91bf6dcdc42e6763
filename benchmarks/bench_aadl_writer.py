"""AADL text writer benchmark: throughput (MB/s of text produced) on a generated package.

The package holds N thread types (default 10 000), each with three features (one with a property
block) and three property associations (a number with unit, an enumeration literal, a range), and
one system implementation with a subcomponent and a connection per thread. Side by side in one run:

  * ``walk``: visiting every object once through the reflective model API (``model.walk``),
    for scale: the writer reads the same objects through their typed attributes;
  * ``write_unit``: the writer, text in memory;
  * ``write_model``: the writer plus the atomic file write;
  * ``parse``: reading the produced text back with the AADL grammar (``aadl_syntax.parse``).

Usage: ``python -m benchmarks.bench_aadl_writer [--components N] [--repeat R]``.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

__all__ = ["build_package", "main"]


def build_package(components: int):
    """An ``AadlModel`` with one package of ``components`` thread types and a system using them."""
    from rosaadl import model

    classes: dict[str, type] = {}

    def new(kind: str, /, **values):
        # the metamodel classes directly, with enumeration values looked up once: model.new
        # checks every keyword and would make building, not writing, the slow part of the run
        cls = classes.get(kind)
        if cls is None:
            cls = classes[kind] = model.eclass_of(kind).python_class
        many = {k: values.pop(k) for k in list(values) if isinstance(values[k], list)}
        obj = cls(**{k: _enum(kind, k, v) for k, v in values.items()})
        for key, items in many.items():
            getattr(obj, key).extend(items)
        return obj

    literals: dict[tuple[str, str, str], object] = {}

    def _enum(cls: str, key: str, value):
        if key not in ("category", "direction", "access", "kind") or not isinstance(value, str):
            return value
        found = literals.get((cls, key, value))
        if found is None:
            etype = model.eclass_of(cls).findEStructuralFeature(key).eType
            found = literals[(cls, key, value)] = etype.from_string(value)
        return found

    def assoc(prop: str, value) -> object:
        return new("PropertyAssociation", property=prop, ownedValues=[new("ModalPropertyValue", value=value)])

    ws = new("AadlModel", name="bench")
    pkg = new("AadlPackage", name="bench::threads", withs=["Base_Types"])
    top_type = new("ComponentType", name="top", category="system")
    top = new("ComponentImplementation", name="top.impl", type="top", category="system")
    for n in range(components):
        thread = new("ComponentType", name=f"worker_{n}", category="thread")
        queue = assoc("Queue_Size", new("IntegerValue", value=4))
        thread.features.extend(
            [
                new(
                    "Feature",
                    name="input",
                    category="event data port",
                    direction="in",
                    classifier="Base_Types::Integer",
                    ownedPropertyAssociations=[queue],
                ),
                new("Feature", name="output", category="data port", direction="out", classifier="D::Float"),
                new("Feature", name="shared", category="data access", access="requires"),
            ]
        )
        execution = new(
            "RangeValue",
            minimum=new("RealValue", value=0.5, unit="ms"),
            maximum=new("RealValue", value=1.25 + n % 7, unit="ms"),
        )
        thread.ownedPropertyAssociations.extend(
            [
                assoc("Timing_Properties::Period", new("IntegerValue", value=10 + n % 90, unit="ms")),
                assoc("Thread_Properties::Dispatch_Protocol", new("NamedValue", name="Periodic")),
                assoc("Timing_Properties::Compute_Execution_Time", execution),
            ]
        )
        pkg.classifiers.append(thread)
        sub = new("Subcomponent", name=f"w{n}", category="thread", classifier=f"worker_{n}")
        top.subcomponents.append(sub)
        if n:
            source, destination = f"w{n - 1}.output", f"w{n}.input"
            conn = new("Connection", name=f"c{n}", kind="port", source=source, destination=destination)
            top.connections.append(conn)
    pkg.classifiers.extend([top_type, top])
    ws.units.append(pkg)
    return ws


def _best(func: Callable[[], object], repeat: int) -> tuple[float, object]:
    best, result = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        result = func()
        best = min(best, time.perf_counter() - start)
    return best, result


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--components", type=int, default=10_000)
    parser.add_argument("--repeat", type=int, default=3, help="runs per phase; the best is shown")
    args = parser.parse_args(argv)

    from rosaadl import model
    from rosaadl.exporters.aadl_text import write_model, write_unit
    from rosaadl.importers.aadl_syntax import parse

    start = time.perf_counter()
    ws = build_package(args.components)
    build_seconds = time.perf_counter() - start
    pkg = ws.units[0]
    objects = sum(1 for _ in model.walk(ws))

    walk_seconds, _ = _best(lambda: sum(1 for _ in model.walk(ws)), args.repeat)
    write_seconds, text = _best(lambda: write_unit(pkg), args.repeat)
    size_mb = len(text.encode("utf-8")) / 1e6
    with tempfile.TemporaryDirectory(prefix="rosaadl-bench-") as tmp:
        files_seconds, _ = _best(lambda: write_model(ws, Path(tmp)), args.repeat)
    parse_seconds, _ = _best(lambda: parse(text, "bench.aadl"), 1)

    print(
        f"AADL writer benchmark: {args.components} thread types, {objects} model objects, "
        f"{size_mb:.2f} MB of text, {text.count(chr(10))} lines (model built in {build_seconds:.2f} s)"
    )
    print(f"{'phase':12} {'seconds':>8} {'MB/s':>8} {'x walk':>7}")
    for phase, seconds in (
        ("walk", walk_seconds),
        ("write_unit", write_seconds),
        ("write_model", files_seconds),
        ("parse", parse_seconds),
    ):
        print(f"{phase:12} {seconds:8.3f} {size_mb / seconds:8.2f} {seconds / walk_seconds:7.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

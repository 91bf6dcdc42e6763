"""``rosaadl library add-profile``: measurements in a CSV file, or a measured run's
``measurements.json`` (:mod:`.library_run_profile`), become profile packages in a folder.

:func:`add_profiles` reads the measurements (:mod:`.library_measurements`), the library with the
AADL inputs (:func:`.library_catalog.read_library`) and the profile packages an earlier run wrote
into the output folder, builds the packages (:mod:`.library_profiles`), and writes them only when
the whole file is good: every problem of the file is reported at once, located at its line and
column (:class:`~rosaadl.workflow.library_measurements.MeasurementError`). Before writing, the
texts are read back into the model, resolved, each new PDM instantiated and checked to carry the
measured values; then each file is written atomically.
"""

from __future__ import annotations

import logging
import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import fileio, model
from rosaadl.arguments import checked, expect_path
from rosaadl.errors import Diagnostic, ExportError, ModelError, ParseError, RosaadlError
from rosaadl.exporters.aadl_text import unit_file_name, write_units
from rosaadl.importers.aadl_text import read_string
from rosaadl.properties import Range
from rosaadl.resolution import Resolver
from rosaadl.transforms.instantiate import instantiate
from rosaadl.units import Quantity
from rosaadl.workflow.library_catalog import read_library
from rosaadl.workflow.library_measurements import (
    MAX_FILE_BYTES,
    MeasurementError,
    file_error,
    parse_measurements,
)
from rosaadl.workflow.library_nodes import bytes_of, instance_value, ns_of, us_text
from rosaadl.workflow.library_profiles import (
    CPU_SPEED,
    DISPATCH_LATENCY,
    PROFILE_SUFFIX,
    TWIN_EXECUTION_TIME,
    ExpectedValues,
    ProfileBuilder,
    ProfiledImplementation,
)
from rosaadl.workflow.library_run_profile import run_measurement_rows

__all__ = ["ProfileResult", "add_profiles"]

log = logging.getLogger(__name__)


@dataclass
class ProfileResult:
    """What :func:`build_profiles` / :func:`add_profiles` made: texts by file name, the PDMs."""

    texts: dict[str, str] = field(default_factory=dict)
    packages: list[str] = field(default_factory=list)
    implementations: list[ProfiledImplementation] = field(default_factory=list)
    warnings: list[Diagnostic] = field(default_factory=list)
    files: list[Path] = field(default_factory=list)

    def as_dict(self) -> dict[str, Any]:
        return {
            "files": [str(path) for path in self.files],
            "packages": list(self.packages),
            "implementations": [impl.as_dict() for impl in self.implementations],
        }


def _header_comment(unit: EObject, source_name: str, merged: bool) -> str:
    nodes = unit.name.removesuffix(PROFILE_SUFFIX)
    source = f"{source_name} and earlier measurements" if merged else source_name
    if not source_name.lower().endswith(".json"):
        carried = "-- Compute_Execution_Time, the process its SEI::MIPSBudget (= Raw_MIPS / IPC).\n\n"
    else:
        carried = "-- Compute_Execution_Time (a measured run: no instruction rate, no MIPSBudget)"
        if _carries(unit, DISPATCH_LATENCY):
            carried += ",\n-- a timer thread its measured ROS_Properties::Dispatch_Latency"
        if _carries(unit, CPU_SPEED):
            carried += (
                ",\n-- the CPU time the workload twin held and the speed of the CPUs it ran on\n"
                "-- (ROS_Properties::Twin_Execution_Time, Profiled_CPU_Speed)"
            )
        carried += ".\n\n"
    return (
        f"-- {unit.name}: platform-dependent implementations (PDM) of the nodes\n"
        f"-- of {nodes}, made by `rosaadl library add-profile` from {source}.\n"
        "-- Each PDM extends the node's PIM; its threads carry the measured\n" + carried
    )


def _carries(unit: EObject, prop: str) -> bool:
    """Whether a classifier of ``unit`` carries the property ``prop``."""
    return any(
        (pa.property or "").lower() == prop.lower()
        for classifier in unit.classifiers
        for pa in classifier.ownedPropertyAssociations
    )


def _existing_outputs(
    workspace: EObject, out_dir: Path, names: Iterable[str]
) -> tuple[dict[str, EObject], list[RosaadlError]]:
    """Profile packages already written in ``out_dir`` (read from there) or given as inputs."""
    found: dict[str, EObject] = {}
    errors: list[RosaadlError] = []
    for name in names:
        unit = model.find_unit(workspace, name)
        if unit is not None:
            found[name.lower()] = unit
            continue
        probe = model.new("AadlPackage", name=name)
        target = out_dir / unit_file_name(probe)
        if not target.is_file():
            continue
        try:
            scratch = read_string(target.read_bytes(), str(target))
        except RosaadlError as exc:
            errors.append(exc)
            continue
        except OSError as exc:
            errors.append(ParseError(f"cannot read the file: {exc.strerror or exc}", file=str(target)))
            continue
        units = list(scratch.units)
        if len(units) != 1 or (units[0].name or "").lower() != name.lower():
            held = ", ".join(u.name for u in units) or "nothing"
            errors.append(
                ExportError(
                    f"would replace {target.name}, which holds {held}, not package {name}",
                    file=str(target),
                )
            )
            continue
        found[name.lower()] = units[0]
    return found, errors


@checked
def add_profiles(
    measurements: str | os.PathLike[str],
    out_dir: str | os.PathLike[str],
    *,
    inputs: Iterable[str | os.PathLike[str]] = (),
    warnings: list[Diagnostic] | None = None,
) -> ProfileResult:
    """Turn a measurements CSV into profile packages written into ``out_dir``.

    ``inputs`` are AADL files or folders read with the library (nodes that are not in the
    library). Raises :class:`MeasurementError` listing every problem of the file (nothing is
    written then); reader errors of the inputs propagate as they are.
    """
    csv_path = expect_path(measurements, "measurements")
    target_dir = expect_path(out_dir, "out_dir")
    try:
        with csv_path.open("rb") as handle:  # no more than the limit is read, whatever the file
            data = handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ParseError(f"cannot read the measurements: {exc.strerror or exc}", file=str(csv_path)) from None
    if csv_path.suffix.lower() == ".json":  # a measured run of the generated application
        rows, errors, notes = run_measurement_rows(data, str(csv_path))
    else:
        rows, errors, notes = parse_measurements(data, str(csv_path))
    if fileio.existing(target_dir, ExportError) and not target_dir.is_dir():
        errors.append(MeasurementError("the output exists and is not a folder", file=str(target_dir)))
    notes_all: list[Diagnostic] = list(notes)
    read_notes: list[Diagnostic] = []
    workspace = read_library(inputs, warnings=read_notes)
    notes_all.extend(read_notes)
    builder = ProfileBuilder(workspace)
    units: list[EObject] = []
    implementations: list[ProfiledImplementation] = []
    rows_of: dict[str, list[ExpectedValues]] = {}
    existing: dict[str, EObject] = {}
    if rows:
        # which packages the rows go to, to find earlier profiles in the output folder
        names = []
        for m in rows:
            types, _ = builder.nodes.process_types(m.node)
            if len(types) == 1:
                unit = builder.resolver.unit_of(types[0])
                names.append(f"{unit.name}{PROFILE_SUFFIX}")
        existing, problems = _existing_outputs(workspace, target_dir, sorted(set(names), key=str.lower))
        errors.extend(problems)  # type: ignore[arg-type]
        units, implementations, rows_of = builder.build(rows, existing)
        errors.extend(builder.errors)  # type: ignore[arg-type]
        notes_all.extend(builder.warnings)
    if errors:
        if warnings is not None:
            warnings.extend(notes_all)
        raise file_error(errors)
    merged = {name.lower() for name in existing}
    texts = {
        name: _header_comment(unit, csv_path.name, unit.name.lower() in merged) + text
        for (name, text), unit in zip(write_units(units).items(), units, strict=True)
    }
    targets = {name: fileio.safe_join(target_dir, name) for name in texts}
    _verify(workspace, units, texts, targets, implementations, rows_of, notes_all)
    written = []
    for name, text in texts.items():
        try:
            fileio.atomic_write_text(targets[name], text)
        except OSError as exc:
            raise ExportError(
                f"cannot write the file: {exc.strerror or exc}", file=str(targets[name])
            ) from None
        written.append(targets[name])
    log.info("wrote %d profile package(s) to %s", len(written), target_dir)
    if warnings is not None:
        warnings.extend(notes_all)
    return ProfileResult(texts, [u.name for u in units], implementations, notes_all, written)


def _verify(
    workspace: EObject,
    units: list[EObject],
    texts: dict[str, str],
    targets: dict[str, Path],
    implementations: list[ProfiledImplementation],
    rows_of: dict[str, list[ExpectedValues]],
    notes: list[Diagnostic],
) -> None:
    """Read the texts back into the workspace, resolve, instantiate each new PDM and check that it
    carries the measured values; any difference is an error and nothing is written."""

    for unit in units:
        old = model.find_unit(workspace, unit.name)
        if old is not None:
            workspace.units.remove(old)
    for name, text in texts.items():
        read_string(text, str(targets[name]), model=workspace)
    resolver = Resolver(workspace)
    problems = [d for d in resolver.check() if d.severity == "error"]
    if problems:
        listing = "\n".join(f"  {d}" for d in problems)
        raise ExportError(f"the profile packages do not resolve (a defect of rosaadl):\n{listing}")
    errors: list[RosaadlError] = []
    for impl in implementations:
        diagnostics: list[Diagnostic] = []
        instance = instantiate(workspace, impl.process, resolver=resolver, diagnostics=diagnostics)
        try:
            notes.extend(d for d in diagnostics if d.severity == "warning")
            errors.extend(_check_values(instance, impl, rows_of.get(impl.process.lower(), [])))
        finally:
            workspace.instances.remove(instance)
    if errors:
        raise file_error(errors)


def _check_values(
    instance: EObject, impl: ProfiledImplementation, expected: list[ExpectedValues]
) -> list[RosaadlError]:
    """Differences between what the rows say and what the instance of the new PDM carries."""

    errors: list[RosaadlError] = []
    if not expected:
        return errors
    budget = instance_value(instance, "SEI::MIPSBudget")
    if impl.mips_budget is not None and (
        not isinstance(budget, Quantity) or abs(float(budget.to("MIPS")) - impl.mips_budget) > 1e-9
    ):
        errors.append(
            expected[0].m.error(
                "mips_raw",
                f"{impl.process} does not carry SEI::MIPSBudget => {impl.mips_budget} MIPS (it has {budget})",
            )
        )
    for item in expected:
        m = item.m
        try:
            thread = model.find_instance(instance, item.thread)
        except ModelError:
            thread = None
        if thread is None:
            errors.append(m.error("thread", f"{impl.process} has no thread {item.thread}"))
            continue
        overridden = "; a contained property association of the PIM overrides it"
        cet = instance_value(thread, "Compute_Execution_Time")
        if not isinstance(cet, Range) or ns_of(cet.minimum) != m.cet_ns or ns_of(cet.maximum) != m.cet_ns:
            errors.append(
                m.error(
                    "cet_us",
                    f"thread {item.thread} of {impl.process} does not carry Compute_Execution_Time => "
                    f"{us_text(m.cet_ns)} .. {us_text(m.cet_ns)} (it has {cet}){overridden}",
                )
            )
        period = instance_value(thread, "Period")
        if m.period_ns is not None and ns_of(period) != m.period_ns:
            errors.append(
                m.error(
                    "period_us",
                    f"thread {item.thread} of {impl.process} has the Period {period}, "
                    f"not {us_text(m.period_ns)}{overridden}",
                )
            )
        latency = instance_value(thread, DISPATCH_LATENCY)
        if m.dispatch_latency_ns is not None and ns_of(latency) != m.dispatch_latency_ns:
            errors.append(
                m.error(
                    "dispatch_latency_us",
                    f"thread {item.thread} of {impl.process} does not carry {DISPATCH_LATENCY} => "
                    f"{us_text(m.dispatch_latency_ns)} (it has {latency}){overridden}",
                )
            )
        burned, speed = instance_value(thread, TWIN_EXECUTION_TIME), instance_value(thread, CPU_SPEED)
        if m.cpu_speed is not None and (ns_of(burned) != m.twin_execution_time_ns or speed != m.cpu_speed):
            errors.append(
                m.error(
                    "twin",
                    f"thread {item.thread} of {impl.process} does not carry {TWIN_EXECUTION_TIME} => "
                    f"{us_text(m.twin_execution_time_ns)} and {CPU_SPEED} => {m.cpu_speed!r} "
                    f"(it has {burned} and {speed}){overridden}",
                )
            )
        if item.port is not None and m.data_size is not None:
            port = next(
                (f for f in thread.featureInstances if (f.name or "").lower() == item.port.lower()), None
            )
            size = instance_value(port, "Data_Size")
            if bytes_of(size) != m.data_size:
                errors.append(
                    m.error(
                        "data_size_bytes",
                        f"port {item.port} of thread {item.thread} of {impl.process} has the Data_Size "
                        f"{size}, not {m.data_size} Bytes{overridden}",
                    )
                )
    return errors

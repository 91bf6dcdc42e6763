"""Platform-dependent implementations (PDM) of library nodes, made from measurements.

:func:`build_profiles` turns good measurement rows into one AADL package
``<node package>_profiles`` per node package, in the style of the library's own node packages::

    process implementation usb_cam_nd.le376_atom extends nd_usb_cam::usb_cam_nd.impl
      subcomponents
        image_broadcaster: refined to thread imagePublisher.le376_atom;
      properties
        SEI::MIPSBudget => 500.0 MIPS;
        ROS_Profiling::Raw_MIPS => 310.0 MIPS;
        ROS_Profiling::IPC => 0.62;
        Reference_Processor => classifier (Atom_D510::Atom_core);
    end usb_cam_nd.le376_atom;

    thread implementation imagePublisher.le376_atom extends nd_usb_cam::imagePublisher.impl
      properties
        Compute_Execution_Time => 6100 us .. 6100 us;
    end imagePublisher.le376_atom;

A measured run (``measurements.json``) gives a timer thread's PDM its measured executor latency
too, ``ROS_Properties::Dispatch_Latency => 1843 us;`` (:data:`DISPATCH_LATENCY`), and the
threads of a process whose CPUs the run gauged what of their CET the workload twin held and
the CPUs' speed,
``ROS_Properties::Twin_Execution_Time => 3750 us; ROS_Properties::Profiled_CPU_Speed => 331.2;``
(:data:`TWIN_EXECUTION_TIME`, :data:`CPU_SPEED`).

The package names the node's types with ``renames`` (an implementation is declared in the
package of its type or of an alias of it). A package of earlier profiles keeps what it holds
except the PDMs measured again. The packages are models only: writing them is
:func:`rosaadl.workflow.library_add_profile.add_profiles`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from decimal import Decimal
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model
from rosaadl.errors import Diagnostic, Location, RosaadlError
from rosaadl.exporters.aadl_text.lexical import literal
from rosaadl.model import is_a
from rosaadl.property_text import format_value
from rosaadl.workflow.library_measurements import Measurement
from rosaadl.workflow.library_nodes import (
    MeasuredNode,
    MeasuredThread,
    NodeFinder,
    bytes_of,
    instance_value,
    ns_of,
    us_text,
)

__all__ = [
    "PROFILE_SUFFIX",
    "DISPATCH_LATENCY",
    "TWIN_EXECUTION_TIME",
    "CPU_SPEED",
    "ProfiledImplementation",
    "ExpectedValues",
    "ProfileBuilder",
    "build_profiles",
]

#: The profiles of the nodes of package ``P`` go to package ``P`` + this suffix.
PROFILE_SUFFIX = "_profiles"
#: The property a thread PDM of a measured run gets its executor's dispatch latency in.
DISPATCH_LATENCY = "ROS_Properties::Dispatch_Latency"
#: The properties a thread PDM of a measured run gets the time its workload twin held and the
#: speed of its CPUs in.
TWIN_EXECUTION_TIME = "ROS_Properties::Twin_Execution_Time"
CPU_SPEED = "ROS_Properties::Profiled_CPU_Speed"

_DATA_PORTS = ("dataPort", "eventDataPort")


@dataclass
class ProfiledImplementation:
    """One PDM made from the measurements: the process implementation and its thread ones."""

    node: str  # the node's process type, qualified
    process: str  # the new process implementation, qualified
    threads: list[str]  # the new thread implementations, qualified
    rows: list[int]
    mips_budget: float | None  #: None: no instruction rate was measured (no MIPS properties)
    reference_processor: str | None

    def as_dict(self) -> dict[str, Any]:
        return {
            "node": self.node,
            "process": self.process,
            "threads": list(self.threads),
            "rows": list(self.rows),
            "mips_budget": self.mips_budget,
            "reference_processor": self.reference_processor,
        }


@dataclass(frozen=True)
class ExpectedValues:
    """What one row puts into a PDM, checked on the instance of the PDM before writing."""

    m: Measurement
    thread: str  # the thread's path in the node (its subcomponent, or thread groups and it, dotted)
    port: str | None


class ProfileBuilder:
    """Builds the profile packages of measurement rows; the nodes they name are found by
    ``nodes`` (:class:`NodeFinder`), whose ``errors`` and ``warnings`` collect every problem."""

    def __init__(self, workspace: EObject) -> None:
        self.nodes = NodeFinder(workspace)
        self.resolver = self.nodes.resolver
        self.errors = self.nodes.errors
        self.warnings = self.nodes.warnings

    def build(
        self, measurements: Sequence[Measurement], existing: dict[str, EObject]
    ) -> tuple[list[EObject], list[ProfiledImplementation], dict[str, list[ExpectedValues]]]:
        """``(packages, PDMs, expected values by lower-case process PDM name)`` of the rows;
        ``existing``: earlier profile packages by lower-case name, merged into the new ones."""
        rows = []
        for m in measurements:
            node = self.nodes.node(m)
            if node is None:
                continue
            row = self.nodes.thread(m, node)
            if row is not None:
                rows.append(row)
        self._check_duplicates(rows)
        by_package: dict[int, list[MeasuredThread]] = {}  # the nodes of one package: one package
        for row in rows:
            by_package.setdefault(id(row.node.package), []).append(row)
        units = []
        implementations: list[ProfiledImplementation] = []
        rows_of: dict[str, list[ExpectedValues]] = {}
        for group in sorted(by_package.values(), key=lambda g: (g[0].node.package.name or "").lower()):
            unit = self._package(group, existing, implementations, rows_of)
            if unit is not None:
                units.append(unit)
        return units, implementations, rows_of

    def _check_duplicates(self, rows: list[MeasuredThread]) -> None:
        seen: dict[tuple[int, str, str], Measurement] = {}
        for row in rows:
            key = (id(row.node.ctype), row.key, row.m.pdm.lower())
            first = seen.get(key)
            if first is None:
                seen[key] = row.m
                continue
            self.errors.append(
                row.m.error(
                    "node, thread, board, core",
                    f"duplicate measurement of thread {row.path} of "
                    f"{self.resolver.qualified_name(row.node.ctype)} on {row.m.pdm}: "
                    f"row {first.row} (line {first.line}) already gives it",
                )
            )

    def _package(
        self,
        group: list[MeasuredThread],
        existing: dict[str, EObject],
        implementations: list[ProfiledImplementation],
        rows_of: dict[str, list[ExpectedValues]],
    ) -> EObject | None:
        resolver = self.resolver
        node = group[0].node
        ctype = node.ctype
        package_name = f"{node.package.name}{PROFILE_SUFFIX}"
        if resolver.unit(package_name) is not None and package_name.lower() not in existing:
            other = resolver.unit(package_name)
            self.errors.append(
                group[0].m.error(
                    "node",
                    f"the profiles of {resolver.qualified_name(ctype)} go to package {package_name}, "
                    f"but the library or the inputs already hold a unit of that name ({other.sourceFile})",
                )
            )
            return None
        before = len(self.errors)
        withs: list[str] = [node.package.name]
        aliases: dict[str, tuple[str, str]] = {}  # lower alias -> (alias, target)

        def alias_for(target_type: EObject, m: Measurement, column: str) -> str | None:
            alias = target_type.name
            target = resolver.qualified_name(target_type)
            known = aliases.get(alias.lower())
            if known is not None and known[1].lower() != target.lower():
                self.errors.append(
                    m.error(
                        column,
                        f"{target} and {known[1]} have the same name {alias}; one package of "
                        "profiles cannot name both",
                    )
                )
                return None
            aliases[alias.lower()] = (alias, target)
            owner = resolver.unit_of(target_type)
            if owner is not None and owner.name not in withs:
                withs.append(owner.name)
            return alias

        by_pdm: dict[tuple[str, str], list[MeasuredThread]] = {}  # (node, PDM) -> its rows
        for row in group:
            name = resolver.qualified_name(row.node.ctype).lower()
            by_pdm.setdefault((name, row.m.pdm.lower()), []).append(row)
        classifiers: list[EObject] = []
        made: list[ProfiledImplementation] = []
        node_aliases: dict[int, str | None] = {}
        for key in sorted(by_pdm):
            pdm_rows = by_pdm[key]
            node = pdm_rows[0].node
            if id(node.ctype) not in node_aliases:
                node_aliases[id(node.ctype)] = alias_for(node.ctype, pdm_rows[0].m, "node")
            result = self._pdm(node, node_aliases[id(node.ctype)], pdm_rows, alias_for, withs)
            if result is not None:
                impls, summary = result
                classifiers.extend(impls)
                made.append(summary)
                rows_of[summary.process.lower()] = [ExpectedValues(r.m, r.path, r.port) for r in pdm_rows]
        if len(self.errors) > before:
            return None
        unit = model.new(
            "AadlPackage",
            name=package_name,
            withs=withs,
            renamings=[
                model.new(
                    "Renaming",
                    name=alias,
                    kind="classifier",
                    target=target,
                    category=literal(resolver.classifier(target).category),
                )
                for alias, target in aliases.values()
            ],
        )
        old = existing.get(package_name.lower())
        if old is not None:
            again = set()  # what the nodes measured again had on those PDMs: theirs, their threads'
            names_of: dict[int, list[str | None]] = {}  # per node: its alias, its thread types
            for (_node, pdm), pdm_rows in by_pdm.items():
                node = pdm_rows[0].node
                key = id(node.ctype)
                if key not in names_of:
                    names_of[key] = [node_aliases.get(key), *self._thread_type_names(node)]
                again |= {f"{(name or '').lower()}.{pdm}" for name in names_of[key]}
            classifiers = self._merge(unit, old, classifiers, again)
        unit.classifiers.extend(sorted(classifiers, key=_pdm_order))
        implementations.extend(made)
        return unit

    def _thread_type_names(self, node: MeasuredNode) -> list[str]:
        """The names of the thread types of every thread of ``node``'s PIM."""
        names = []
        for sub in node.threads.values():
            ctype = self.resolver.component_type(self.resolver.subcomponent_classifier(sub))
            if ctype is not None:
                names.append(ctype.name or "")
        return names

    def _merge(self, unit: EObject, old: EObject, new: list[EObject], again: set[str]) -> list[EObject]:
        """Keep what an earlier profiles package held, except the PDMs measured again (``again``:
        the lower-case names of the measured nodes' and their threads' PDMs, ``<type>.<pdm>``;
        a package may hold several nodes, each measured or not); the classifiers of the new
        package."""
        made = {(c.name or "").lower(): c for c in new}
        kept = []
        for classifier in list(old.classifiers):
            name = (classifier.name or "").lower()
            if name in made or name in again:
                replacement = made.get(name)
                if replacement is None or _signature(replacement) != _signature(classifier):
                    self.warnings.append(
                        Diagnostic(
                            "warning",
                            f"{old.name}::{classifier.name} of the earlier profiles is replaced by the "
                            "new measurements",
                            Location(file=old.sourceFile or None, line=classifier.line or None),
                        )
                    )
                continue
            kept.append(classifier)
        for with_name in old.withs:
            if with_name.lower() not in {w.lower() for w in unit.withs}:
                unit.withs.append(with_name)
        known = {(r.name or "").lower() for r in unit.renamings}
        for ren in list(old.renamings):
            if (ren.name or "").lower() not in known:
                unit.renamings.append(ren)
        return [*kept, *new]

    def _pdm(self, node: MeasuredNode, node_alias, rows: list[MeasuredThread], alias_for, withs: list[str]):
        resolver = self.resolver
        first = rows[0].m
        pdm = first.pdm
        before = len(self.errors)
        for row in rows[1:]:
            for column, a, b in (("mips_raw", first.mips_raw, row.m.mips_raw), ("ipc", first.ipc, row.m.ipc)):
                if a != b:
                    self.errors.append(
                        row.m.error(
                            column,
                            f"{b} differs from row {first.row} ({a}): the {column} of "
                            f"{resolver.qualified_name(node.ctype)} on {pdm} is one measurement of "
                            "the whole node",
                        )
                    )
        processors = {r.m.processor.lower(): r.m for r in rows if r.m.processor}
        if len(processors) > 1:
            later = list(processors.values())[1]
            self.errors.append(
                later.error("processor", f"{later.processor} differs from another row of {pdm}")
            )
        reference = None
        if processors:
            reference = self.nodes.reference_processor(next(iter(processors.values())))
        else:
            reference, candidates = self.nodes.known_reference_processor(pdm)
            if reference is None:
                reason = (
                    f"the library's {pdm} PDMs name several ({', '.join(candidates)})"
                    if candidates
                    else f"no PDM of the library or the inputs is named {pdm}"
                )
                self.warnings.append(
                    Diagnostic(
                        "warning",
                        f"row {first.row}: no Reference_Processor for "
                        f"{resolver.qualified_name(node.ctype)}.{pdm}: {reason}; "
                        "give the core's classifier in a processor column",
                        first.where("board"),
                    )
                )
        existing = resolver.classifier(f"{node.ctype.name}.{pdm}", node.ctype)
        if existing is not None:
            self.warnings.append(
                Diagnostic(
                    "warning",
                    f"row {first.row}: {resolver.qualified_name(existing)} already exists; the new PDM is a "
                    f"separate implementation in {node.package.name}{PROFILE_SUFFIX}",
                    first.where("board"),
                )
            )
        # thread PDMs, one per thread type
        threads: dict[str, tuple[EObject, MeasuredThread]] = {}
        refinements = []
        nested: list[EObject] = []  # the values of threads in thread groups, applied to their paths
        order = {key: index for index, key in enumerate(node.threads)}
        for row in sorted(rows, key=lambda r: order.get(r.key, 0)):
            if row.nested:
                found = self._thread_properties(row, row.path)
                nested.extend(found or ())
                continue
            alias = alias_for(row.thread_type, row.m, "thread")
            if alias is None:
                continue
            impl = self._thread_pdm(row, alias, pdm)
            if impl is None:
                continue
            key = (impl.name or "").lower()
            shared = threads.get(key)
            if shared is not None:
                if _signature(shared[0]) != _signature(impl):
                    self.errors.append(
                        row.m.error(
                            "thread",
                            f"threads {shared[1].sub.name} and {row.sub.name} share the type "
                            f"{alias}, so they share the PDM {impl.name}; their measurements must agree "
                            f"(row {shared[1].m.row} differs)",
                        )
                    )
                    continue
            else:
                threads[key] = (impl, row)
            refinements.append(
                model.new(
                    "Subcomponent", name=row.sub.name, category="thread", classifier=impl.name, refined=True
                )
            )
        if len(self.errors) > before or node_alias is None:
            return None
        properties: list[EObject] = []
        ros = any(r.m.dispatch_latency_ns is not None or r.m.cpu_speed is not None for r in rows)
        if ros and "ROS_Properties" not in withs:
            withs.append("ROS_Properties")
        budget = first.mips_budget
        if budget is not None:  # a run without hardware counters measures no instruction rate
            properties += [
                _association("SEI::MIPSBudget", _real(budget, "MIPS")),
                _association("ROS_Profiling::Raw_MIPS", _real(first.mips_raw, "MIPS")),
                _association("ROS_Profiling::IPC", _real(first.ipc, None)),
            ]
            for name in ("SEI", "ROS_Profiling"):
                if name not in withs:
                    withs.append(name)
        reference_name = None
        if reference is not None:
            reference_name = resolver.qualified_name(reference)
            properties.append(
                _association("Reference_Processor", model.new("ClassifierValue", classifier=reference_name))
            )
            owner = resolver.unit_of(reference)
            if owner is not None and owner.name not in withs:
                withs.append(owner.name)
        process = model.new(
            "ComponentImplementation",
            name=f"{node_alias}.{pdm}",
            type=node_alias,
            category="process",
            extended=resolver.qualified_name(node.pim),
            subcomponents=refinements,
            ownedPropertyAssociations=[*properties, *nested],
        )
        package = f"{node.package.name}{PROFILE_SUFFIX}"
        summary = ProfiledImplementation(
            node=resolver.qualified_name(node.ctype),
            process=f"{package}::{process.name}",
            threads=[f"{package}::{impl.name}" for impl, _ in threads.values()],
            rows=[r.m.row for r in rows],
            mips_budget=None if budget is None else float(budget),
            reference_processor=reference_name,
        )
        return [process, *(impl for impl, _ in threads.values())], summary

    def _thread_pdm(self, row: MeasuredThread, alias: str, pdm: str) -> EObject | None:
        properties = self._thread_properties(row)
        if properties is None:
            return None
        extended = None
        if is_a(row.thread_classifier, "ComponentImplementation"):
            extended = self.resolver.qualified_name(row.thread_classifier)
        return model.new(
            "ComponentImplementation",
            name=f"{alias}.{pdm}",
            type=alias,
            category="thread",
            extended=extended,
            ownedPropertyAssociations=properties,
        )

    def _thread_properties(self, row: MeasuredThread, path: str = "") -> list[EObject] | None:
        """The measured values of a thread: for its thread PDM, or with ``path`` (a thread in a
        thread group) for its node's process PDM, each applied to ``path`` or to its port there;
        None when its Data_Size belongs to no one port (an error)."""
        m = row.m
        instance = row.node.instances.get(row.key)

        def value(prop: str, item: EObject, port: str | None = None) -> EObject:
            target = ".".join(p for p in (path, port) if p)
            return _association(prop, item, [target] if target else [])

        properties = [value("Compute_Execution_Time", _time_range(m.cet_ns))]
        if m.dispatch_latency_ns is not None:
            properties.append(value(DISPATCH_LATENCY, _time(m.dispatch_latency_ns)))
        if m.twin_execution_time_ns is not None and m.cpu_speed is not None:
            properties.append(value(TWIN_EXECUTION_TIME, _time(m.twin_execution_time_ns)))
            properties.append(value(CPU_SPEED, _real(Decimal(str(m.cpu_speed)), None)))
        pim_period = ns_of(instance_value(instance, "Period"))
        if m.period_ns is not None and pim_period != m.period_ns:
            properties.append(value("Period", _time(m.period_ns)))
            if pim_period is not None:
                self.warnings.append(
                    Diagnostic(
                        "warning",
                        f"row {m.row}, column period_us: {us_text(m.period_ns)} differs from the Period "
                        f"of {row.path} in the PIM ({us_text(pim_period)}); the PDM sets the thread's "
                        "own Period",
                        m.where("period_us"),
                    )
                )
        if m.data_size is not None:
            port = self._data_port(row, instance)
            if port is None:
                return None
            row.port = port.name
            if bytes_of(instance_value(port, "Data_Size")) != m.data_size:
                measured = model.new("IntegerValue", value=m.data_size, unit="Bytes")
                properties.append(value("Data_Size", measured, port.name))
        return properties

    def _data_port(self, row: MeasuredThread, instance: EObject | None) -> EObject | None:
        ports = [
            fi
            for fi in (instance.featureInstances if instance is not None else ())
            if fi.category is not None and fi.category.name in _DATA_PORTS
        ]
        outgoing = [p for p in ports if literal(p.direction) in ("out", "in out")]
        incoming = [p for p in ports if literal(p.direction) == "in"]
        candidates = outgoing or incoming
        if len(candidates) == 1:
            return candidates[0]
        names = ", ".join(p.name for p in candidates) or "none"
        self.errors.append(
            row.m.error(
                "data_size_bytes",
                f"thread {row.path} has {len(candidates)} {'outgoing' if outgoing else 'incoming'} data "
                f"ports ({names}); the data size must belong to exactly one (leave the cell empty)",
            )
        )
        return None


def _signature(impl: EObject) -> tuple:
    """What a classifier says, for comparing two of them (names, extends, members, values)."""
    return (
        (impl.name or "").lower(),
        (impl.extended or "").lower(),
        tuple(
            ((sub.name or "").lower(), (sub.classifier or "").lower())
            for sub in getattr(impl, "subcomponents", ())
        ),
        tuple(
            (
                (pa.property or "").lower(),
                tuple(t.lower() for t in pa.appliesTo),
                tuple(format_value(mv.value) for mv in pa.ownedValues),
            )
            for pa in impl.ownedPropertyAssociations
        ),
    )


def _pdm_order(classifier: EObject) -> tuple[str, int, str]:
    """Profiles grouped by board and core, the process implementation before its threads."""
    name = (classifier.name or "").lower()
    category = literal(getattr(classifier, "category", "")) if is_a(classifier, "ComponentClassifier") else ""
    return (name.rpartition(".")[2], 0 if category == "process" else 1, name)


def _time(ns: int) -> EObject:
    if ns % 1000 == 0:
        return model.new("IntegerValue", value=ns // 1000, unit="us")
    return model.new("IntegerValue", value=ns, unit="ns")


def _time_range(ns: int) -> EObject:
    return model.new("RangeValue", minimum=_time(ns), maximum=_time(ns))


def _real(value: Decimal, unit: str | None) -> EObject:
    return model.new("RealValue", value=float(value), unit=unit)


def _association(prop: str, value: EObject, applies_to: Sequence[str] = ()) -> EObject:
    return model.new(
        "PropertyAssociation",
        property=prop,
        appliesTo=list(applies_to),
        ownedValues=[model.new("ModalPropertyValue", value=value)],
    )


def build_profiles(
    workspace: EObject,
    measurements: Sequence[Measurement],
    *,
    existing: dict[str, EObject] | None = None,
) -> tuple[list[EObject], list[ProfiledImplementation], list[RosaadlError], list[Diagnostic]]:
    """The profile packages for ``measurements`` resolved against ``workspace``:
    ``(packages, implementations, errors, warnings)``; no package when there are errors.

    ``existing`` maps lower-case package names to profile packages of an earlier run: what they
    hold is kept, except the PDMs (``*.<board>_<core>``) measured again.
    """
    builder = ProfileBuilder(workspace)
    units, implementations, _ = builder.build(measurements, existing or {})
    if builder.errors:
        return [], [], builder.errors, builder.warnings
    return units, implementations, [], builder.warnings

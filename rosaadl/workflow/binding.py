"""Binding ROSMOD deployments to the library's robots, with what that needs of files and analyses.

:mod:`rosaadl.transforms.bind` makes the bound AADL package from the project, a bindings file's
entry and the library, model to model. The workflow adds the rest: reading the bindings file
(:func:`read_bindings`) and the library (:func:`bind_project`), writing a bound package as AADL
(:func:`write_bound`), and searching a better binding of an overloaded deployment over the cores
of its own robot (:func:`propose_binding`: the constraint solver of
:func:`rosaadl.analysis.deployment_proposal.propose_deployment`, where a node's demand on a core is
the execution time of its PDM for that core type), bound again with the cores found.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass, replace
from fractions import Fraction
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.analysis.deployment import DeploymentResult
from rosaadl.analysis.deployment_proposal import propose_deployment
from rosaadl.analysis.instance_values import PropertyReader
from rosaadl.arguments import checked, expect_path
from rosaadl.errors import ParseError
from rosaadl.exporters.aadl_text import write_model, write_unit
from rosaadl.importers.aadl_text import read_files, read_string
from rosaadl.transforms.bind import (
    MAX_BINDINGS_BYTES,
    ROBOT,
    BindingError,
    BindingsFile,
    BoundDeployment,
    Core,
    bind_deployment,
    parse_bindings,
)
from rosaadl.transforms.bind.library import Catalogue, literal
from rosaadl.transforms.instantiate import instantiate
from rosaadl.transforms.rosmod_to_aadl import aadl_identifier

__all__ = ["Proposal", "bind_project", "propose_binding", "read_bindings", "write_bound"]

log = logging.getLogger(__name__)


@checked
def read_bindings(path: str | os.PathLike[str]) -> BindingsFile:
    """Read a bindings file (:func:`~rosaadl.transforms.bind.parse_bindings`); a missing or
    unreadable file is a located :class:`~rosaadl.errors.ParseError`."""
    source = expect_path(path)
    try:
        size = source.stat().st_size
        if size > MAX_BINDINGS_BYTES:
            raise ParseError(f"bindings file larger than {MAX_BINDINGS_BYTES} bytes", file=str(source))
        data = source.read_bytes()
    except OSError as exc:
        raise ParseError(f"cannot read the bindings file: {exc.strerror or exc}", file=str(source)) from None
    return parse_bindings(data, str(source))


@checked
def bind_project(
    project: EObject, bindings: BindingsFile, library: EObject | None = None
) -> dict[str, BoundDeployment]:
    """Every deployment of the bindings file, bound
    (:func:`~rosaadl.transforms.bind.bind_deployment`), in file order; ``library`` is an
    ``AadlModel`` holding the component library (read when None)."""
    if library is None:
        library = read_files([], include_library=True)
    return {name: bind_deployment(project, spec, library) for name, spec in bindings.deployments.items()}


def write_bound(bound: BoundDeployment, folder: str | os.PathLike[str]) -> Path:
    """Write the package of a bound deployment as AADL text into ``folder``; the path written."""
    (path,) = write_model([bound.package], folder)
    return path


# =========================================================================== a better binding


@dataclass
class Proposal:
    """What the deployment search proposes for a bound deployment."""

    search: DeploymentResult
    cores: dict[str, str]  #: process → core path inside the robot (empty when nothing passes)
    bound: BoundDeployment | None  #: the deployment bound to those cores (None when nothing passes)
    demands: dict[str, dict[str, Fraction]]  #: process → core path → its load there (1 = 100 %)

    @property
    def feasible(self) -> bool:
        return bool(self.search.feasible) and self.bound is not None


def _execution_times(
    project: EObject, bound: BoundDeployment, model: EObject
) -> dict[str, dict[str, dict[str, Fraction]]]:
    """process → core path (in the robot) → thread (relative) → CET in seconds, for every core
    whose type the node has a PDM for: the deployment bound, per core type, to a core of that type
    for every node that can run there, instantiated, its execution times read."""
    catalogue = Catalogue(model)
    by_type: dict[str, list[Core]] = {}
    for core in bound.cores:
        by_type.setdefault(core.types[0] if core.types else core.classifier.lower(), []).append(core)
    out: dict[str, dict[str, dict[str, Fraction]]] = {node.process: {} for node in bound.nodes}
    taken = {u.name.lower() for u in model.units}
    for index, (_type, cores) in enumerate(sorted(by_type.items())):
        able = {}
        for node in bound.nodes:
            library = catalogue.node(node.library)
            if library is not None and any(ref in cores[0].types for _impl, ref in library.pdms):
                able[node.process] = node
        if not able:
            continue
        nodes = {
            n.spec.key: replace(n.spec, core=cores[0].path, library=n.library)
            if n.process in able
            else n.spec
            for n in bound.nodes
        }
        name = f"{bound.package.name}_on_{index}"
        while name.lower() in taken:
            name += "_"
        variant = bind_deployment(project, replace(bound.spec, nodes=nodes), model, package_name=name)
        read_string(write_unit(variant.package), f"<{name}>", model=model)
        unit = _model.find_unit(model, name)
        system = None
        try:
            system = instantiate(model, variant.root, diagnostics=[])
            reader = PropertyReader()
            prefix = f"{system.name}."
            for process in system.componentInstances:
                if process.name not in able:
                    continue
                times: dict[str, Fraction] = {}
                for obj in _model.component_instances(process, include_root=False):
                    if literal(obj.category) != "thread":
                        continue
                    cet = reader.seconds(obj, "Timing_Properties::Compute_Execution_Time")
                    if cet is not None:
                        relative = (
                            _model.instance_path(obj).removeprefix(prefix).removeprefix(process.name + ".")
                        )
                        times[relative] = cet
                for core in cores:
                    out[process.name][core.path] = times
        finally:
            if system is not None:
                model.instances.remove(system)
            if unit is not None:
                model.units.remove(unit)
    log.debug("execution times per core type: %s", {p: len(c) for p, c in out.items()})
    return out


def _demands(
    instance: EObject, times: dict[str, dict[str, dict[str, Fraction]]]
) -> dict[str, dict[str, Fraction]]:
    """process → core → Σ CET / Period: the load each process would put on each core."""
    reader = PropertyReader()
    root = f"{instance.name}."
    periods: dict[str, Fraction] = {}
    for obj in _model.component_instances(instance):
        if literal(obj.category) == "thread":
            period = reader.seconds(obj, "Timing_Properties::Period")
            if period:
                periods[_model.instance_path(obj).removeprefix(root)] = period
    return {
        process: {
            core: sum(
                (cet / periods[f"{process}.{t}"] for t, cet in cets.items() if f"{process}.{t}" in periods),
                Fraction(0),
            )
            for core, cets in per_core.items()
        }
        for process, per_core in times.items()
    }


@checked
def propose_binding(
    project: EObject,
    bound: BoundDeployment,
    instance: EObject,
    *,
    package_name: str | None = None,
    **search: Any,
) -> Proposal:
    """Search the cores of the deployment's robot for a binding of its nodes that passes the CPU
    load and schedulability checks (the constraint solver,
    :func:`~rosaadl.analysis.deployment_proposal.propose_deployment`, deterministic: the least
    highest core load, then bus load, then moves; each node's execution times on each core taken
    from its PDM for that core type), and bind
    the deployment to the cores found, in the package ``package_name`` (default
    ``<deployment>_proposed``).

    ``instance`` is the instance of ``bound`` (its model, which holds the library, is used to read
    the other PDMs); ``search`` passes keyword arguments to the solver (``time_limit``, ``keep``).
    """
    model = instance.eContainer()
    if not _model.is_a(model, "AadlModel"):
        raise BindingError("the instance of the bound deployment is not in an AadlModel with the library")
    root = instance.name or ""
    times = _execution_times(project, bound, model)
    processes = [f"{root}.{node.process}" for node in bound.nodes]
    processors = [f"{root}.{ROBOT}.{core.path}" for core in bound.cores]
    given_times = {
        f"{root}.{process}": {f"{root}.{ROBOT}.{core}": cets for core, cets in per_core.items()}
        for process, per_core in times.items()
    }
    solved = propose_deployment(
        instance,
        processes=processes,
        processors=processors,
        execution_times=given_times,
        **{"deterministic": True, **search},
    )
    result = solved.as_result()
    prefix = f"{root}.{ROBOT}."
    demands = _demands(instance, times)
    if not result.feasible:
        return Proposal(result, {}, None, demands)
    cores = {p.process.removeprefix(root + "."): p.processor.removeprefix(prefix) for p in result.placements}
    nodes = {
        node.spec.key: replace(node.spec, core=cores[node.process], library=node.library)
        for node in bound.nodes
    }
    name = package_name or f"{aadl_identifier(bound.name)}_proposed"
    proposed = bind_deployment(project, replace(bound.spec, nodes=nodes), model, package_name=name)
    return Proposal(result, cores, proposed, demands)

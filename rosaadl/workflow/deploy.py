"""``rosaadl deploy``'s work: solve the deployment of an instance and write the binding as AADL.

:func:`deploy_instance` runs the constraint solver
(:func:`~rosaadl.analysis.deployment_proposal.propose_deployment`) on an instance and, when a
binding passes, writes ``<package>_proposed.aadl``: the package of the root implementation under
the name ``<package>_proposed``, its root implementation carrying one
``Actual_Processor_Binding => (reference (core)) applies to unit;`` per unit (the ones it had
for those units replaced: a contained association of the root implementation overrides the ones
declared deeper, so the instance takes the proposed cores). The text is made before anything is
written and written atomically (:func:`~rosaadl.fileio.atomic_write_bytes`); the model is
left as it was. :func:`check_proposed` reads the written package back with the other inputs,
instantiates the proposed root and runs every analysis on it.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.analysis.deployment_proposal import DeploymentProposal, propose_deployment
from rosaadl.analysis.instance_values import category_of
from rosaadl.errors import Location, ModelError
from rosaadl.fileio import atomic_write_bytes, cannot_write
from rosaadl.model import component_instances

__all__ = ["DeployRun", "check_proposed", "deploy_instance", "proposed_package_name"]

_BINDING = "Actual_Processor_Binding"


@dataclass
class DeployRun:
    """A deployment solved, and where its binding was written (None: nothing passes)."""

    proposal: DeploymentProposal
    output: Path | None
    package: str | None
    root: str | None  #: the proposed root implementation, ``Pkg_proposed::Sys.impl``

    def as_dict(self) -> dict[str, Any]:
        data = self.proposal.as_dict(str(self.output) if self.output is not None else None)
        data["root"] = self.root
        return data


def proposed_package_name(package: str, model: EObject) -> str:
    """``<package>_proposed``, made unique among the model's units."""
    name = f"{package}_proposed"
    while _model.find_unit(model, name) is not None:
        name += "_1"
    return name


def _root_implementation(instance: EObject, model: EObject) -> EObject:
    classifier = instance.classifier
    found = _model.find_classifier(model, classifier) if isinstance(classifier, str) else classifier
    if found is None or found.eContainer() is None:
        raise ModelError(
            f"the root implementation {classifier!r} of {instance.name} is not in the model: "
            "give the AADL text it was instantiated from"
        )
    return found


def _association(target: str, unit: str) -> EObject:
    value = _model.new("ListValue")
    value.ownedItems.append(_model.new("ReferenceValue", path=target))
    assoc = _model.new("PropertyAssociation", property=_BINDING)
    assoc.ownedValues.append(_model.new("ModalPropertyValue", value=value))
    assoc.appliesTo.append(unit)
    return assoc


def _proposed_text(proposal: DeploymentProposal, implementation: EObject, name: str) -> tuple[str, str]:
    """(file name, AADL text) of the package holding ``implementation``, renamed ``name``, with
    the proposed bindings; the package is restored before returning."""
    from rosaadl.exporters.aadl_text import unit_file_name, write_unit

    package = implementation.eContainer()
    problem = proposal.problem
    root = problem.root + "."
    pairs = []
    for u, (unit, core) in enumerate(proposal.binding()):
        pairs.append((unit.removeprefix(root), core.removeprefix(root)))
        # a thread bound otherwise than its process keeps its own binding unless restated
        pairs += [(t.removeprefix(root), core.removeprefix(root)) for t in problem.bound_inside.get(u, ())]
    units = {u.lower() for u, _c in pairs}

    def rebound(path: object) -> bool:
        """``path`` is a unit bound anew or lies inside one (a dotted prefix of it is)."""
        parts = str(path).lower().split(".")
        return any(".".join(parts[:i]) in units for i in range(1, len(parts) + 1))

    owned = implementation.ownedPropertyAssociations
    kept = list(owned)
    bindings = [a for a in kept if (a.property or "").rpartition("::")[2].lower() == _BINDING.lower()]
    applied = {id(a): list(a.appliesTo) for a in bindings}  # what the writing changes, to put back
    added = [_association(c, u) for u, c in pairs]
    old_name = package.name
    try:
        # the root's associations for what is bound anew go; one that also applies to other
        # elements stays for those
        for a in bindings:
            left = [p for p in a.appliesTo if not rebound(p)]
            if not left:
                owned.remove(a)
            elif len(left) < len(a.appliesTo):
                a.appliesTo.clear()
                a.appliesTo.extend(left)
        owned.extend(added)
        package.name = name
        return unit_file_name(package), write_unit(package)
    finally:
        package.name = old_name
        for a in added:
            owned.remove(a)
        owned.clear()
        owned.extend(kept)
        for a in bindings:
            if list(a.appliesTo) != applied[id(a)]:
                a.appliesTo.clear()
                a.appliesTo.extend(applied[id(a)])


def deploy_instance(
    instance: EObject,
    folder: str | os.PathLike[str],
    *,
    time_limit: float = 10.0,
    keep: int = 1,
    granularity: str = "process",
    deterministic: bool = False,
) -> DeployRun:
    """Solve the deployment of ``instance`` (its model must hold the declarative units it was
    instantiated from) and write the best binding as ``<package>_proposed.aadl`` in ``folder``."""
    model = instance.eContainer()
    category = category_of(instance) or "system"
    if category != "system":
        raise ModelError(
            f"the root {instance.classifier or instance.name} is a {category}, not a system: "
            "deploy binds the processes of a system implementation to its processors",
            Location(path=instance.name),
        )
    proposal = propose_deployment(
        instance, time_limit=time_limit, keep=keep, granularity=granularity, deterministic=deterministic
    )
    if not proposal.problem.units:
        idle = [p for p in component_instances(instance) if category_of(p) == "process"]
        raise ModelError(
            f"{instance.name} has no process to bind: no active process with threads, an "
            "SEI::MIPSBudget or an SEI::RAMBudget in its first mode"
            + (f" ({len(idle)} processes without either are left as they are bound)" if idle else ""),
            Location(path=instance.name),
        )
    if not proposal.feasible:
        return DeployRun(proposal, None, None, None)
    implementation = _root_implementation(instance, model)
    package = implementation.eContainer()
    name = proposed_package_name(package.name, model)
    file_name, text = _proposed_text(proposal, implementation, name)
    path = Path(folder) / file_name
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise cannot_write(path.parent, exc) from None
    atomic_write_bytes(path, text.encode("utf-8"))
    return DeployRun(proposal, path, name, f"{name}::{implementation.name}")


def check_proposed(inputs: list[Path], run: DeployRun) -> tuple[EObject, Any]:
    """Read ``inputs`` and the written package, instantiate the proposed root and run every
    analysis (:func:`~rosaadl.analysis.report.run_analyses`): (instance, report)."""
    from rosaadl.analysis.report import run_analyses
    from rosaadl.importers.aadl_text import read_files
    from rosaadl.transforms.instantiate import instantiate

    if run.output is None or run.root is None:
        raise ModelError("no proposed binding was written")
    loaded = read_files([*inputs, run.output])
    instance = instantiate(loaded, run.root, diagnostics=[])
    return instance, run_analyses(instance)

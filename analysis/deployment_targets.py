"""What a unit may be bound to, as an AADL model writes it: the binding targets of the deployment.

AS5506C's deployment properties, read the way OSATE's binding check reads them:

* ``Allowed_Processor_Binding`` and ``Actual_Processor_Binding`` name processors, systems (the
  cores inside) and virtual processors (the core the virtual processor runs on: its
  ``Actual_Processor_Binding``, else the processor containing it, as OSATE's InstanceModelUtil
  follows it) — :func:`covered_cores`; both are inherited, so a unit without one takes its
  nearest container's (:func:`declared_up`);
* ``Allowed_Processor_Binding_Class`` names processor, virtual processor and system classifiers:
  a core qualifies when its classifier (or a component holding it) is the same as or extends one
  listed, an implementation also matching its type (OSATE's ``checkBindingConstraints`` with
  ``AadlUtil.isSameOrExtends`` and ``isSubClassifier``) — :func:`classes_up`, :func:`of_class`;
* a thread's own ``Actual_Processor_Binding`` beats the one it inherits from its process
  (:func:`bound_inside`: the threads a proposal must restate).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from rosaadl.analysis.instance_values import ProcessorBindings, PropertyReader, category_of
from rosaadl.errors import RosaadlError
from rosaadl.model import component_instances, instance_path, is_a, qualified_name, root_of
from rosaadl.transforms.bind.library import classifier_named, impl_chain, type_chain

__all__ = ["bound_inside", "classes_up", "classifier_name", "covered_cores", "declared_up", "of_class"]


def classifier_name(obj: Any) -> str:
    """The name of the classifier of a component instance (empty when it has none)."""
    classifier = getattr(obj, "classifier", None)
    text = classifier if isinstance(classifier, str) else getattr(classifier, "name", None)
    return str(text) if text else ""


def covered_cores(
    targets: Iterable[Any], index: dict[str, int], bindings: ProcessorBindings, mode: Any
) -> dict[int, str | None]:
    """The candidate cores a list of binding targets stands for: a core, the cores inside a
    processor or system, or the core a virtual processor runs on (``Actual_Processor_Binding``,
    else the processor containing it, as OSATE's InstanceModelUtil follows it). Core index ->
    the virtual processor to name in the binding (None: the core itself; a core named itself
    wins over a virtual processor on it)."""
    out: dict[int, str | None] = {}

    def inside(path: str) -> list[int]:
        if path in index:
            return [index[path]]
        return [i for p, i in index.items() if p.startswith(path + ".")]

    for target in targets:
        path = instance_path(target)
        if category_of(target) == "virtualProcessor":
            host = bindings.physical_processor(target, mode)
            for k in inside(instance_path(host)) if host is not None else []:
                out.setdefault(k, path)
        else:
            for k in inside(path):
                out[k] = None
    return out


def _lineage(holder: Any, name: str) -> set[str]:
    """The classifier ``name`` and every classifier it is or extends, lower-case and qualified;
    an implementation also stands for its type (OSATE's ``AadlUtil.isSubClassifier``): the
    binding transform's ``impl_chain`` and ``type_chain``. A classifier named only as text
    (``Pkg::T.impl`` the model does not hold) stands for itself and its type ``Pkg::T``."""
    found = _classifier(holder, name)
    if found is None:
        key = name.lower()
        package, _sep, local = key.rpartition("::")
        own_type = local.partition(".")[0]
        return {key, f"{package}::{own_type}" if package else own_type}
    chain = impl_chain(holder, found) if is_a(found, "ComponentImplementation") else []
    return {qualified_name(c).lower() for c in chain + type_chain(holder, found)}


def of_class(root: Any, classes: list[Any], mode: Any) -> list[Any]:
    """The processors, virtual processors and systems below ``root`` whose classifier is or
    extends one of ``classes`` (``Allowed_Processor_Binding_Class``: AS5506C's processor,
    virtual processor or system classifiers; OSATE's binding check accepts a bound component
    whose classifier is the same as or extends one of them, an implementation also matching
    its type)."""
    holder = root_of(root)
    wanted: set[str] = set()
    for item in classes:
        text = item if isinstance(item, str) else getattr(item, "classifier", None) or str(item)
        wanted.add(_canonical(holder, str(text)))
    found = []
    lineages: dict[str, set[str]] = {}  # one lineage per classifier, however many cores have it
    for ci in component_instances(root, include_root=False):
        if category_of(ci) not in ("processor", "virtualProcessor", "system") or not mode.active(ci):
            continue
        classifier = classifier_name(ci)
        if classifier and classifier not in lineages:
            lineages[classifier] = _lineage(holder, classifier)
        if classifier and lineages[classifier] & wanted:
            found.append(ci)
    return found


def _classifier(holder: Any, name: str) -> Any:
    """The classifier ``name`` of the declarative model ``holder``; None where it holds none."""
    if not getattr(holder, "units", None):
        return None
    try:
        return classifier_named(holder, name)
    except (RosaadlError, LookupError, AttributeError, TypeError, ValueError):
        return None


def _canonical(holder: Any, name: str) -> str:
    """``name`` qualified and lower-case (as declared when the model holds it)."""
    found = _classifier(holder, name)
    return (qualified_name(found) if found is not None else name).lower()


def _inherited(obj: Any, root: Any, read: Any) -> list[Any]:
    """``read(obj)``, else ``read`` of its nearest container below ``root`` that gives a value."""
    while obj is not None and obj is not root:
        found = read(obj)
        if found:
            return found
        obj = obj.eContainer()
    return []


def declared_up(reader: PropertyReader, obj: Any, name: str, mode: Any, root: Any) -> list[Any]:
    """The targets of a binding property on ``obj``, else on its nearest container that has one."""
    return _inherited(obj, root, lambda o: reader.targets(o, name, mode))


def bound_inside(
    reader: PropertyReader, threads: list[Any], own: list[Any], mode: Any
) -> list[tuple[Any, list[Any]]]:
    """The ``threads`` of a unit whose ``Actual_Processor_Binding`` is not the unit's (``own``:
    their own value, which beats the one a thread inherits from its process), with their
    targets."""
    mine = [instance_path(t) for t in own]
    out = []
    for thread in threads:
        found = reader.targets(thread, "Actual_Processor_Binding", mode) or []
        if found and [instance_path(t) for t in found] != mine:
            out.append((thread, found))
    return out


def classes_up(reader: PropertyReader, obj: Any, mode: Any, root: Any) -> list[Any]:
    """``Allowed_Processor_Binding_Class`` of ``obj``, else of its nearest container that has one
    (the property is inherited)."""

    def classes(o: Any) -> list[Any]:
        value = reader.value(o, "Deployment_Properties::Allowed_Processor_Binding_Class", mode)
        return value if isinstance(value, list) else [value] if value is not None else []

    return _inherited(obj, root, classes)

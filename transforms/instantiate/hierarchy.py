"""The component hierarchy: one component instance per subcomponent (per element of an array).

:func:`populate` builds a component and, depth first, everything below it: its mode instances,
its subcomponents in OSATE's order (a subcomponent typed by a prototype takes the bound actual),
its feature instances, mode transitions and flow specifications. Containment cycles and
classifiers that do not resolve are recorded as errors, raised together once the tree is built.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from typing import TYPE_CHECKING

from pyecore.ecore import EObject

from rosaadl import model as _model
from rosaadl.errors import ModelError

from .arrays import array_sizes
from .features import instantiate_features
from .flows import flow_specifications
from .mirrors import ComponentMirror, LazyPath, enum_name, literal
from .modes import mode_instances, mode_transitions
from .order import SUBCOMPONENT_ORDER, in_osate_order

if TYPE_CHECKING:
    from .instantiator import Instantiator

__all__ = ["MAX_COMPONENT_INSTANCES", "MAX_HIERARCHY_DEPTH", "populate"]

#: Upper bound on component instances, so that a mistyped array size fails instead of hanging.
MAX_COMPONENT_INSTANCES = 2_000_000

#: Upper bound on the nesting of component instances: the deepest instance model rosaadl makes,
#: and so the deepest it must read back (:data:`rosaadl.model.MAX_MODEL_DEPTH` leaves room).
MAX_HIERARCHY_DEPTH = 1_000


def populate(st: Instantiator, ci: ComponentMirror, ancestry: list[EObject]) -> None:
    """Make what component ``ci`` holds, and its subcomponents' (``ancestry``: the subcomponents
    above it, to find containment cycles).

    Depth first without recursion: each component's work is a generator that yields the
    children to build before it goes on, and a stack of those generators replaces Python's, so
    the depth of a hierarchy is bounded by :data:`MAX_HIERARCHY_DEPTH`, not by the interpreter.
    """
    stack = [_populate_steps(st, ci, ancestry)]
    while stack:
        step = next(stack[-1], None)
        if step is None:
            stack.pop()
        else:
            stack.append(_populate_steps(st, *step))


def _populate_steps(
    st: Instantiator, ci: ComponentMirror, ancestry: list[EObject]
) -> Iterator[tuple[ComponentMirror, list[EObject]]]:
    st.components.append(ci)  # in preorder
    resolver = st.resolver
    classifier = ci.node.classifier
    impl = ci.node.impl
    mode_instances(st, ci)  # first: modal subcomponents refer to them
    if impl is not None:
        subs = in_osate_order(
            resolver,
            impl,
            resolver.subcomponents(impl),
            lambda sub: sub,
            lambda sub: literal(sub.category),
            SUBCOMPONENT_ORDER,
        )
        for sub in subs:
            yield from _instantiate_subcomponent(st, ci, sub, ancestry)
        st.factory.extend(ci.obj, "componentInstances", [child.obj for child in ci.children])
    if ci.node.ctype is not None or (classifier is not None and _model.is_a(classifier, "ComponentType")):
        instantiate_features(st, ci)
    mode_transitions(st, ci)
    flow_specifications(st, ci)


def _instantiate_subcomponent(
    st: Instantiator, ci: ComponentMirror, sub: EObject, ancestry: list[EObject]
) -> Iterator[tuple[ComponentMirror, list[EObject]]]:
    """Make the instances of ``sub`` in ``ci``; yield each with its ancestry, to be populated."""
    resolver = st.resolver
    parent_path = LazyPath(ci)
    if len(ancestry) >= MAX_HIERARCHY_DEPTH:
        raise ModelError(
            f"the component hierarchy is deeper than {MAX_HIERARCHY_DEPTH} levels",
            resolver.location(sub, path=f"{parent_path}.{sub.name}"),
        )
    if any(sub is a for a in ancestry):
        st.error(
            f"containment cycle: subcomponent {sub.name} contains itself",
            f"{parent_path}.{sub.name}",
            sub,
        )
        return
    classifier_name = resolver.subcomponent_classifier_name(sub)
    classifier = resolver.subcomponent_classifier(sub)
    if classifier_name and classifier is None:
        classifier = _prototype_classifier(st, ci, sub, classifier_name)
        if classifier is None:
            message = f"classifier {classifier_name} of subcomponent {sub.name} not found"
            if st.strict:
                st.error(message, f"{parent_path}.{sub.name}", sub)
                return
            st.warn(message + "; instantiated without a classifier", f"{parent_path}.{sub.name}", sub)
    if classifier is not None and not _model.is_a(classifier, "ComponentClassifier"):
        st.error(
            f"classifier {classifier_name} of subcomponent {sub.name} is not a component classifier",
            f"{parent_path}.{sub.name}",
            sub,
        )
        return
    dims = list(resolver.effective_attribute(sub, "arrayDimensions") or [])
    sizes = array_sizes(st, dims, sub, f"{parent_path}.{sub.name}") if dims else []
    indices: list[tuple[int, ...]] = (
        [tuple(combo) for combo in itertools.product(*(range(1, n + 1) for n in sizes))] if sizes else [()]
    )
    qualified = resolver.qualified_name(classifier) if classifier is not None else None
    in_modes = [
        m.split("=>")[0].strip().lower() for m in (resolver.effective_attribute(sub, "inModes") or [])
    ]
    parent_modes = [ci.modes[m] for m in in_modes if m in ci.modes]
    key = (sub.name or "").lower()
    factory = st.factory
    for index in indices:
        st.count += 1
        if st.count > MAX_COMPONENT_INSTANCES:
            raise ModelError(
                f"more than {MAX_COMPONENT_INSTANCES} component instances; check the array sizes",
                resolver.location(sub, path=f"{parent_path}.{sub.name}"),
            )
        category = classifier.category if classifier is not None else sub.category
        if classifier is not None and enum_name(classifier.category) == "abstract":
            category = sub.category
        obj = factory.new(
            "ComponentInstance",
            name=sub.name,
            subcomponent=sub.name,
            classifier=qualified,
            category=category,
        )
        if index:
            factory.extend(obj, "index", index)
        if parent_modes:
            factory.extend(obj, "inModes", [m.name for m in parent_modes])
        node = st.lookup.child_node(ci.node, sub, classifier, obj, index, sub.name)
        child = ComponentMirror(
            obj,
            node,
            ci,
            sub,
            key,
            literal(category),
            index,
            in_modes=parent_modes,
            segment=(sub.name or "") + "".join(f"[{i}]" for i in index),
        )
        ci.children.append(child)
        ci.by_sub.setdefault(key, []).append(child)
        yield child, [*ancestry, sub]


def _prototype_classifier(st: Instantiator, ci: ComponentMirror, sub: EObject, name: str) -> EObject | None:
    """A subcomponent typed by a prototype: the actual bound where the containing component is
    declared, else the prototype's constraining classifier."""
    if "::" in name or "." in name:
        return None
    resolver = st.resolver
    wanted = name.lower()
    bindings: list[tuple[str, EObject]] = []
    if ci.sub is not None and ci.sub.prototypeBindings:
        bindings.append((ci.sub.prototypeBindings, ci.sub))
    for classifier in (ci.node.impl, ci.node.ctype):
        if classifier is None:
            continue
        for c in resolver.extends_chain(classifier):
            if c.prototypeBindings:
                bindings.append((c.prototypeBindings, c))
    for text, context in bindings:
        for part in text.strip("() ").split(","):
            left, sep, right = part.partition("=>")
            if sep and left.strip().lower() == wanted:
                words = right.split()
                if words:
                    found = resolver.classifier(words[-1], context)
                    if found is not None:
                        return found
    for classifier in (ci.node.impl, ci.node.ctype):
        if classifier is None:
            continue
        for c in resolver.extends_chain(classifier):
            for proto in c.prototypes:
                if (proto.name or "").lower() == wanted and proto.text:
                    words = proto.text.replace(";", " ").split()
                    for word in reversed(words):
                        found = resolver.classifier(word, c)
                        if found is not None:
                            return found
    return None

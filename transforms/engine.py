"""A small model-to-model rule engine on pyecore, with a trace.

What it offers (after ATL, QVT-o and Epsilon ETL)::

    t = Transformation("rosmod2aadl")

    @t.rule("rosmod.Component", when=lambda ctx, c: c.name)
    def component(ctx, src):               # create phase: make the targets, return them
        return model.new("ComponentType", name=src.name)

    @component.bind
    def component_bind(ctx, src, tgt):     # bind phase: cross references via ctx.resolve
        ...

    result = t.run([project])              # result.trace, result.warnings, result.context

* rules are plain functions with an explicit :class:`Context` argument (no injected globals);
  a create part returns its targets (an object, a tuple of them, or None for none);
* most-specific dispatch: a rule on ``Subscriber`` wins over a rule on ``CallbackPort`` for a
  subscriber; ``when=`` guards choose between rules on one class, and ``where=(key, value)``
  does so for the rules that share a key (asked once per object: where an element sits, its
  category); two equally specific rules that both match are an error, not a coin toss;
* ``lazy=True`` rules run only when asked (``ctx.lazy(rule, *sources)``), and are *unique*: the
  same sources give the same target — one rule can so map a pair of elements (a node and one of
  its component instances) where a matched rule sees one;
* create-then-bind: every create part runs before any bind part, so a bind part finds every
  target with ``ctx.resolve(src)``;
* the run visits the source models' objects in document order, or in the order a
  transformation's ``walk=`` gives (the elements it maps, in the order its warnings should
  come);
* the trace is a ``trace.ecore`` model: one link per rule application, its ends keyed when the
  rule ran (a transformation whose targets get their containers later keys them again once its
  target model is complete: :func:`rosaadl.transforms.trace.key_targets`);
* any failure inside a rule becomes a :class:`~rosaadl.errors.TransformationError` naming the
  rule, the source element and, where known, its file and line.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Hashable, Iterable
from dataclasses import dataclass, field
from typing import Any

from pyecore.ecore import EClass, EObject

from rosaadl import model
from rosaadl.bulk import FastBuilder
from rosaadl.errors import Location, RosaadlError, TransformationError
from rosaadl.transforms import trace as tracing

__all__ = ["Rule", "Transformation", "Context", "TransformationResult", "source_location", "describe"]

log = logging.getLogger(__name__)

Guard = Callable[["Context", EObject], bool]
Key = Callable[["Context", EObject], Hashable]
Walk = Callable[[EObject], Iterable[EObject]]


def source_location(obj: EObject) -> Location:
    """File and line of a model element, from its ``line``/``column`` and the nearest ``sourceFile``."""
    line = getattr(obj, "line", None) or None
    column = getattr(obj, "column", None) or None
    file = None
    current = obj
    while current is not None:
        feature = current.eClass.findEStructuralFeature("sourceFile")
        if feature is not None and current.eGet(feature):
            file = current.eGet(feature)
            break
        current = current.eContainer()
    return Location(file=file, line=line, column=column, path=tracing.element_key(obj))


def describe(obj: EObject) -> str:
    name = getattr(obj, "name", None) if obj.eClass.findEStructuralFeature("name") is not None else None
    return f"{obj.eClass.name} {name!r}" if name else obj.eClass.name


@dataclass
class Rule:
    """One transformation rule: source class, guard, create and bind parts."""

    name: str
    source: EClass
    create: Callable[..., Any]
    when: Guard | None = None
    where: tuple[Key, Hashable] | None = None
    lazy: bool = False
    bind_fn: Callable[..., Any] | None = None

    def bind(self, fn: Callable[..., Any]) -> Callable[..., Any]:
        """Decorator: the bind part of this rule (runs after every create part)."""
        self.bind_fn = fn
        return fn

    def matches(self, ctx: Context, obj: EObject) -> bool:
        try:
            if self.where is not None and self.where[0](ctx, obj) != self.where[1]:
                return False
            return self.when is None or bool(self.when(ctx, obj))
        except RosaadlError:
            raise
        except Exception as exc:
            raise TransformationError(
                f"guard failed: {exc}", source_location(obj), rule=self.name, source=describe(obj)
            ) from exc

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.create(*args, **kwargs)


@dataclass(slots=True)
class _Application:
    rule: Rule
    sources: tuple[EObject, ...]
    targets: tuple[EObject, ...]
    bound: bool = False


class Context:
    """What a rule sees: resolution, lazy rules, shared options and diagnostics."""

    def __init__(self, transformation: Transformation, options: dict[str, Any], trace: bool) -> None:
        self.transformation = transformation
        self.options = dict(options)
        self.trace = tracing.new_trace(transformation.name) if trace else None
        self.warnings: list[RosaadlError] = []
        self._builder = FastBuilder()  # bulk construction of the trace's links
        self._applications: list[_Application] = []
        self._by_source: dict[int, list[_Application]] = {}
        self._lazy_cache: dict[tuple[str, tuple[int, ...]], _Application] = {}
        self._phase = "create"
        self._current_rule: str | None = None

    def resolve(self, source: EObject, rule: str | Rule | None = None) -> list[EObject]:
        """Every target made from ``source`` (optionally by one rule), in creation order."""
        rule_name = rule.name if isinstance(rule, Rule) else rule
        out: list[EObject] = []
        for app in self._by_source.get(id(source), ()):
            if rule_name is None or app.rule.name == rule_name:
                out.extend(app.targets)
        return out

    def resolve_all(self, sources: Iterable[EObject], rule: str | Rule | None = None) -> list[EObject]:
        """Every target made from each of ``sources`` (optionally by one rule), in their order."""
        return [target for source in sources for target in self.resolve(source, rule)]

    def lazy(self, rule: str | Rule, *sources: EObject) -> EObject | None:
        """Apply a lazy rule to ``sources``; the same sources always give the same application.
        Its first target (None when it made none); ``resolve`` gives them all."""
        chosen = self.transformation.get_rule(rule)
        key = (chosen.name, tuple(map(id, sources)))
        app = self._lazy_cache.get(key)
        if app is None:
            current = self._current_rule
            app = self.transformation._apply(self, chosen, sources)
            self._current_rule = current
            self._lazy_cache[key] = app
            if self._phase == "bind":
                self.transformation._bind(self, app)
                self._current_rule = current
        return app.targets[0] if app.targets else None

    def warn(self, message: str, obj: EObject | None = None) -> None:
        location = source_location(obj) if obj is not None else Location()
        self.warnings.append(TransformationError(message, location, rule=self._current_rule))
        log.warning("%s", message)


@dataclass
class TransformationResult:
    trace: EObject | None  #: the ``trace.Trace`` (None when the run was asked for none)
    warnings: list[RosaadlError] = field(default_factory=list)
    context: Context | None = None  #: for ``context.resolve`` after the run


class _Dispatch:
    """The rules that may apply to the objects of one class: those without a ``where`` key, and
    per key function those of each value."""

    def __init__(self, rules: list[Rule]) -> None:
        self.rules = rules
        self.unkeyed = [r for r in rules if r.where is None]
        keyed: dict[Key, dict[Hashable, list[Rule]]] = {}
        for rule in rules:
            if rule.where is not None:
                key, value = rule.where
                keyed.setdefault(key, {}).setdefault(value, []).append(rule)
        self.keyed = list(keyed.items())


class Transformation:
    """A named set of rules applied to the objects of one or more source models."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._rules: list[Rule] = []
        self._by_name: dict[str, Rule] = {}
        self._dispatch_cache: dict[EClass, _Dispatch] = {}

    # -- declaration --------------------------------------------------------------------------
    def rule(
        self,
        source: str | EClass,
        *,
        when: Guard | None = None,
        where: tuple[Key, Hashable] | None = None,
        lazy: bool = False,
        name: str | None = None,
    ) -> Callable[[Callable[..., Any]], Rule]:
        """Decorator declaring a rule on ``source`` objects (a metamodel class or its name).

        ``when`` is a guard; ``where=(key, value)`` a guard of the form ``key(ctx, obj) ==
        value``, which rules on one class can share: the engine asks ``key`` once per object
        and goes straight to the rules of its value.
        """
        eclass = model.eclass_of(source)

        def decorate(fn: Callable[..., Any]) -> Rule:
            rule_name = name or fn.__name__
            if rule_name in self._by_name:
                raise TransformationError(f"transformation {self.name}: rule {rule_name!r} is declared twice")
            created = Rule(name=rule_name, source=eclass, create=fn, when=when, where=where, lazy=lazy)
            self._rules.append(created)
            self._by_name[rule_name] = created
            self._dispatch_cache.clear()
            return created

        return decorate

    def get_rule(self, rule: str | Rule) -> Rule:
        if isinstance(rule, Rule):
            return rule
        try:
            return self._by_name[rule]
        except KeyError:
            raise TransformationError(f"no rule named {rule!r} in transformation {self.name}") from None

    # -- dispatch -----------------------------------------------------------------------------
    def _dispatch(self, eclass: EClass) -> _Dispatch:
        cached = self._dispatch_cache.get(eclass)
        if cached is None:
            cls = eclass.python_class
            rules = [r for r in self._rules if not r.lazy and issubclass(cls, r.source.python_class)]
            cached = self._dispatch_cache[eclass] = _Dispatch(rules)
        return cached

    def select(self, ctx: Context, obj: EObject) -> Rule | None:
        """The most specific non-lazy rule whose class and guards match ``obj`` (None if none)."""
        dispatch = self._dispatch(obj.eClass)
        try:
            matching = [r for r in dispatch.unkeyed if r.when is None or r.when(ctx, obj)]
            for key, by_value in dispatch.keyed:
                for r in by_value.get(key(ctx, obj), ()):
                    if r.when is None or r.when(ctx, obj):
                        matching.append(r)
        except RosaadlError:
            raise
        except Exception:
            matching = [r for r in dispatch.rules if r.matches(ctx, obj)]  # names the guard that failed
        if len(matching) < 2:
            return matching[0] if matching else None
        # drop every rule whose source class is a strict supertype of another matching rule's
        specific = [
            r
            for r in matching
            if not any(
                o is not r
                and o.source is not r.source
                and issubclass(o.source.python_class, r.source.python_class)
                for o in matching
            )
        ]
        if len(specific) > 1:
            names = ", ".join(repr(r.name) for r in specific)
            raise TransformationError(
                f"ambiguous: rules {names} all match with the same specificity; make their guards exclusive",
                source_location(obj),
                source=describe(obj),
            )
        return specific[0]

    # -- execution ----------------------------------------------------------------------------
    def _apply(self, ctx: Context, rule: Rule, sources: tuple[EObject, ...]) -> _Application:
        ctx._current_rule = rule.name
        try:
            result = rule.create(ctx, *sources)
            if result is None:
                targets: tuple[EObject, ...] = ()
            elif isinstance(result, EObject):
                targets = (result,)
            else:
                targets = tuple(result)
        except TransformationError as exc:
            if exc.rule is None:
                raise TransformationError(
                    exc.message, exc.location, rule=rule.name, source=describe(sources[0])
                ) from exc
            raise
        except RosaadlError as exc:
            raise TransformationError(
                exc.message, _best_location(exc, sources[0]), rule=rule.name, source=describe(sources[0])
            ) from exc
        except Exception as exc:
            raise TransformationError(
                f"{exc.__class__.__name__}: {exc}",
                source_location(sources[0]),
                rule=rule.name,
                source=describe(sources[0]),
            ) from exc
        finally:
            ctx._current_rule = None
        app = _Application(rule, tuple(sources), targets)
        ctx._applications.append(app)
        for src in sources:
            ctx._by_source.setdefault(id(src), []).append(app)
        if ctx.trace is not None:
            tracing.add_link(ctx.trace, rule.name, sources, targets, builder=ctx._builder)
        return app

    def _bind(self, ctx: Context, app: _Application) -> None:
        if app.bound or app.rule.bind_fn is None:
            app.bound = True
            return
        app.bound = True
        ctx._current_rule = app.rule.name
        try:
            app.rule.bind_fn(ctx, *app.sources, *app.targets)
        except TransformationError:
            raise
        except RosaadlError as exc:
            raise TransformationError(
                exc.message,
                _best_location(exc, app.sources[0]),
                rule=app.rule.name,
                source=describe(app.sources[0]),
            ) from exc
        except Exception as exc:
            raise TransformationError(
                f"{exc.__class__.__name__}: {exc}",
                source_location(app.sources[0]),
                rule=app.rule.name,
                source=describe(app.sources[0]),
            ) from exc
        finally:
            ctx._current_rule = None

    def run(
        self,
        sources: Iterable[EObject] | EObject,
        *,
        walk: Walk | None = None,
        trace: bool = True,
        **options: Any,
    ) -> TransformationResult:
        """Apply the rules to the objects of the source models (every contained object, or what
        ``walk`` gives for each of them): create phase, then bind phase. ``options`` are the
        context's; ``trace=False`` records no trace."""
        roots = [sources] if isinstance(sources, EObject) else list(sources)
        ctx = Context(self, options, trace)
        visit = walk or model.walk
        for root in roots:
            for obj in visit(root):
                rule = self.select(ctx, obj)
                if rule is not None:
                    self._apply(ctx, rule, (obj,))
        ctx._phase = "bind"
        index = 0
        applications = ctx._applications
        while index < len(applications):  # lazy rules may add applications while binding
            app = applications[index]
            if app.rule.bind_fn is not None:
                self._bind(ctx, app)
            index += 1
        return TransformationResult(trace=ctx.trace, warnings=list(ctx.warnings), context=ctx)


def _best_location(exc: RosaadlError, obj: EObject) -> Location:
    if exc.location.file or exc.location.line or exc.location.path:
        return exc.location
    return source_location(obj)

"""A small model-to-model rule engine on pyecore, with a trace.

What it offers (after ATL, QVT-o and Epsilon ETL)::

    t = Transformation("rosmod2aadl")

    @t.rule("rosmod.Component", to="ComponentType", when=lambda ctx, c: c.name)
    def component(ctx, src, tgt):          # create phase: attributes, contained objects
        tgt.name = src.name

    @component.bind
    def component_bind(ctx, src, tgt):     # bind phase: cross references via ctx.resolve
        ...

    result = t.run([project])              # result.targets, result.trace

* rules are plain functions with an explicit :class:`Context` argument (no injected globals);
* most-specific dispatch: a rule on ``Subscriber`` wins over a rule on ``CallbackPort`` for a
  subscriber; two equally specific rules that both match are an error, not a coin toss;
* ``lazy=True`` rules run only when asked (``ctx.lazy(rule, src)``), and are *unique*: the same
  source gives the same target;
* create-then-bind: every create part runs before any bind part, so rules never depend on order;
* ``ctx.resolve(src)`` / ``ctx.resolve_one(src, "Target")`` read the trace;
* any failure inside a rule becomes a :class:`~rosaadl.errors.TransformationError` naming the
  rule, the source element and, where known, its file and line.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Sequence
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


def _as_eclass(spec: str | EClass | type) -> EClass:
    if isinstance(spec, EClass):
        return spec
    if isinstance(spec, str):
        return model.eclass_of(spec)
    eclass = getattr(spec, "eClass", None)
    if isinstance(eclass, EClass):
        return eclass
    raise TypeError(f"not a metamodel class: {spec!r}")


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
    """One transformation rule: source class, guard, targets, create and bind parts."""

    name: str
    source: EClass
    create: Callable[..., Any]
    to: tuple[Any, ...] = ()
    when: Guard | None = None
    lazy: bool = False
    bind_fn: Callable[..., Any] | None = None
    depth: int = 0  # number of supertypes of ``source``: larger is more specific

    def bind(self, fn: Callable[..., Any]) -> Callable[..., Any]:
        """Decorator: the bind part of this rule (runs after every create part)."""
        self.bind_fn = fn
        return fn

    def matches(self, ctx: Context, obj: EObject) -> bool:
        if not isinstance(obj, self.source.python_class):
            return False
        if self.when is None:
            return True
        try:
            return bool(self.when(ctx, obj))
        except RosaadlError:
            raise
        except Exception as exc:
            raise TransformationError(
                f"guard failed: {exc}", source_location(obj), rule=self.name, source=describe(obj)
            ) from exc

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.create(*args, **kwargs)


@dataclass
class _Application:
    rule: Rule
    sources: tuple[EObject, ...]
    targets: tuple[EObject, ...]
    bound: bool = False


class Context:
    """What a rule sees: the trace so far, resolution, lazy rules, shared options and diagnostics."""

    def __init__(self, transformation: Transformation, options: dict[str, Any]) -> None:
        self.transformation = transformation
        self.options = dict(options)
        self.trace = tracing.new_trace(transformation.name)
        self.builder = FastBuilder()  # bulk construction for the trace and for rules that want it
        self.warnings: list[RosaadlError] = []
        self._applications: list[_Application] = []
        self._by_source: dict[int, list[_Application]] = {}
        self._lazy_cache: dict[tuple[str, tuple[int, ...]], _Application] = {}
        self._phase = "create"
        self.roots: list[EObject] = []

    # -- resolution ---------------------------------------------------------------------------
    def resolve(self, source: EObject, rule: str | Rule | None = None) -> list[EObject]:
        """Every target made from ``source`` (optionally by one rule), in creation order."""
        rule_name = rule.name if isinstance(rule, Rule) else rule
        out: list[EObject] = []
        for app in self._by_source.get(id(source), []):
            if rule_name is None or app.rule.name == rule_name:
                out.extend(app.targets)
        return out

    def resolve_one(self, source: EObject, target_class: str | EClass | None = None) -> EObject:
        """The single target of ``source`` (of ``target_class`` when given); an error otherwise."""
        targets = self.resolve(source)
        if target_class is not None:
            cls = _as_eclass(target_class).python_class
            targets = [t for t in targets if isinstance(t, cls)]
        if len(targets) != 1:
            wanted = f" of class {_as_eclass(target_class).name}" if target_class is not None else ""
            hint = (
                " (resolve in a bind part: every create part runs first)" if self._phase == "create" else ""
            )
            raise TransformationError(
                f"expected exactly one target{wanted}, found {len(targets)}{hint}",
                source_location(source),
                rule=self._current_rule_name(),
                source=describe(source),
            )
        return targets[0]

    def resolve_optional(self, source: EObject, target_class: str | EClass | None = None) -> EObject | None:
        targets = self.resolve(source)
        if target_class is not None:
            cls = _as_eclass(target_class).python_class
            targets = [t for t in targets if isinstance(t, cls)]
        return targets[0] if targets else None

    def lazy(self, rule: str | Rule, *sources: EObject) -> EObject | tuple[EObject, ...]:
        """Apply a lazy rule; the same sources always give the same target(s)."""
        chosen = self.transformation.get_rule(rule)
        key = (chosen.name, tuple(id(s) for s in sources))
        app = self._lazy_cache.get(key)
        if app is None:
            app = self.transformation._apply(self, chosen, sources)
            self._lazy_cache[key] = app
            if self._phase == "bind":
                self.transformation._bind(self, app)
        return app.targets[0] if len(app.targets) == 1 else app.targets

    def warn(self, message: str, obj: EObject | None = None) -> None:
        location = source_location(obj) if obj is not None else Location()
        self.warnings.append(TransformationError(message, location, rule=self._current_rule_name()))
        log.warning("%s", message)

    def _current_rule_name(self) -> str | None:
        return getattr(self, "_current_rule", None)


@dataclass
class TransformationResult:
    roots: list[EObject]
    trace: EObject
    warnings: list[RosaadlError] = field(default_factory=list)
    context: Context | None = None


class Transformation:
    """A named set of rules applied to the objects of one or more source models."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._rules: list[Rule] = []
        self._by_name: dict[str, Rule] = {}
        self._dispatch_cache: dict[EClass, list[Rule]] = {}

    # -- declaration --------------------------------------------------------------------------
    def rule(
        self,
        source: str | EClass | type,
        *,
        to: Any = None,
        when: Guard | None = None,
        lazy: bool = False,
        name: str | None = None,
    ) -> Callable[[Callable[..., Any]], Rule]:
        """Decorator declaring a rule from ``source`` objects to new ``to`` objects.

        ``to`` is a metamodel class (name or EClass), a tuple of them (several targets, passed to
        the function in order), or None (the function creates and returns its targets itself).
        """
        eclass = _as_eclass(source)
        targets = () if to is None else tuple(to) if isinstance(to, (tuple, list)) else (to,)

        def decorate(fn: Callable[..., Any]) -> Rule:
            rule_name = name or fn.__name__
            if rule_name in self._by_name:
                raise ValueError(f"transformation {self.name}: rule {rule_name!r} is declared twice")
            created = Rule(
                name=rule_name,
                source=eclass,
                create=fn,
                to=tuple(_as_eclass(t) for t in targets),
                when=when,
                lazy=lazy,
                depth=len(list(eclass.eAllSuperTypes())),
            )
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

    @property
    def rules(self) -> Sequence[Rule]:
        return tuple(self._rules)

    # -- dispatch -----------------------------------------------------------------------------
    def _candidates(self, eclass: EClass) -> list[Rule]:
        cached = self._dispatch_cache.get(eclass)
        if cached is None:
            cls = eclass.python_class
            cached = [r for r in self._rules if not r.lazy and issubclass(cls, r.source.python_class)]
            self._dispatch_cache[eclass] = cached
        return cached

    def select(self, ctx: Context, obj: EObject) -> Rule | None:
        """The most specific non-lazy rule whose class and guard match ``obj`` (None if none)."""
        matching = [r for r in self._candidates(obj.eClass) if r.matches(ctx, obj)]
        if not matching:
            return None
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
            targets = tuple(model.new(t) for t in rule.to)
            result = rule.create(ctx, *sources, *targets)
            if not rule.to:
                if result is None:
                    targets = ()
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
        tracing.add_link(ctx.trace, rule.name, sources, targets, builder=ctx.builder)
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

    def run(self, sources: Iterable[EObject] | EObject, **options: Any) -> TransformationResult:
        """Apply the rules to every object of the source models: create phase, then bind phase."""
        roots = [sources] if isinstance(sources, EObject) else list(sources)
        ctx = Context(self, options)
        ctx.roots = roots
        for root in roots:
            for obj in model.walk(root):
                rule = self.select(ctx, obj)
                if rule is not None:
                    self._apply(ctx, rule, (obj,))
        ctx._phase = "bind"
        index = 0
        while index < len(ctx._applications):  # lazy rules may add applications while binding
            self._bind(ctx, ctx._applications[index])
            index += 1
        produced = [t for app in ctx._applications for t in app.targets if t.eContainer() is None]
        return TransformationResult(roots=produced, trace=ctx.trace, warnings=list(ctx.warnings), context=ctx)


def _best_location(exc: RosaadlError, obj: EObject) -> Location:
    if exc.location.file or exc.location.line or exc.location.path:
        return exc.location
    return source_location(obj)

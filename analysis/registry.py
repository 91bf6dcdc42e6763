"""The analyses rosaadl knows: each one registers itself here, and the report and the CLI read them.

An analysis is one module of this package that ends with one registration::

    register(Analysis(
        name="cpu",                       # what ``--only`` selects
        json_key="cpu",                   # its key under "analyses" in the JSON report
        order=10,                         # its place in every report
        run=lambda context: analyze_resources(context.root),
        text=cpu_text,                    # result -> lines of the text report
        csv=cpu_csv,                      # (result, instance file name) -> {file name: CSV text}
    ))

Its result has ``ok``, ``diagnostics`` and ``as_dict()`` (the JSON document); ``verdicts`` may
turn a result into report errors (a domain found not schedulable). The modules of this package
are imported the first time the registry is read, so a new module needs no other edit.

What the analyses share while they run (the task set extracted from the instance, the results
of the analyses another one reads, such as the response times the latency analysis uses) is
kept in one :class:`AnalysisContext` per run; nothing is kept between runs.
"""

from __future__ import annotations

import importlib
import logging
import pkgutil
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from rosaadl.errors import Diagnostic, RosaadlError, UsageError

__all__ = [
    "Analysis",
    "AnalysisContext",
    "register",
    "registered",
    "analyses",
    "analysis",
    "default_analyses",
    "parse_only",
]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Analysis:
    """One analysis: how to select it, run it, and render its result."""

    name: str
    json_key: str
    order: int
    run: Callable[[AnalysisContext], Any]  #: the result, or None when there was nothing to analyse
    text: Callable[[Any], list[str]]
    csv: Callable[[Any, str], dict[str, str]] = lambda result, base: {}
    verdicts: Callable[[Any], list[Diagnostic]] = lambda result: []
    aliases: tuple[str, ...] = ()
    default: bool = True  #: runs when nothing is selected
    description: str = ""


class _Registry:
    """Analyses by name. One per process (:data:`_REGISTRY`); the package's own modules fill it
    when it is first read."""

    def __init__(self) -> None:
        self._by_name: dict[str, Analysis] = {}
        self._discovered = False

    def add(self, item: Analysis) -> None:
        taken = {n for a in self._by_name.values() if a.name != item.name for n in (a.name, *a.aliases)}
        clash = sorted(taken & {item.name, *item.aliases})
        if clash:
            raise UsageError(f"analysis name {', '.join(clash)} is taken")
        self._by_name[item.name] = item

    def remove(self, name: str) -> None:
        self._by_name.pop(name, None)

    def all(self) -> tuple[Analysis, ...]:
        if not self._discovered:
            self._discovered = True
            _import_package_modules()
        return tuple(sorted(self._by_name.values(), key=lambda a: (a.order, a.name)))


_REGISTRY = _Registry()


def _import_package_modules() -> None:
    """Import every module of this package: each registers the analysis it holds."""
    package = __name__.rpartition(".")[0]
    for info in pkgutil.iter_modules(importlib.import_module(package).__path__, package + "."):
        importlib.import_module(info.name)


def register(item: Analysis) -> Analysis:
    """Make ``item`` known to the report and the CLI (a name or alias already taken is an error)."""
    _REGISTRY.add(item)
    return item


@contextmanager
def registered(item: Analysis) -> Iterator[Analysis]:
    """``item`` registered for the duration of a ``with`` block (tests, plug-ins tried out)."""
    register(item)
    try:
        yield item
    finally:
        _REGISTRY.remove(item.name)


def analyses() -> tuple[Analysis, ...]:
    """Every registered analysis, in report order."""
    return _REGISTRY.all()


def analysis(name: str) -> Analysis:
    """The analysis called ``name`` (or one of its aliases); a :class:`UsageError` otherwise."""
    wanted = name.strip().lower()
    for item in analyses():
        if wanted == item.name or wanted in item.aliases:
            return item
    raise UsageError(f"unknown analysis {name} (expected some of: {', '.join(a.name for a in analyses())})")


def default_analyses() -> tuple[str, ...]:
    """What runs when nothing is selected, in report order."""
    return tuple(a.name for a in analyses() if a.default)


def parse_only(text: str | Iterable[str] | None) -> tuple[str, ...]:
    """``"cpu,bus"`` (or a list) → the selected analyses in report order; a located
    :class:`UsageError` for an unknown name."""
    if text is None:
        return default_analyses()
    items = text.split(",") if isinstance(text, str) else list(text)
    names = {item.strip().lower() for item in items if item.strip()}
    known = analyses()
    expected = ", ".join(a.name for a in known)
    chosen = set()
    unknown = []
    for name in names:
        match = next((a.name for a in known if name == a.name or name in a.aliases), None)
        if match is None:
            unknown.append(name)
        else:
            chosen.add(match)
    if unknown:
        raise UsageError(f"unknown analysis {', '.join(sorted(unknown))} (expected some of: {expected})")
    if not chosen:
        raise UsageError(f"no analysis selected (expected some of: {expected})")
    return tuple(a.name for a in known if a.name in chosen)


@dataclass
class AnalysisContext:
    """One run of the analyses on one instance: what they share and what went wrong.

    ``options`` holds keyword arguments of :func:`~rosaadl.analysis.report.run_analyses`
    (``latency_chains``, ``deployment``, ``simulation_horizon``) for the analyses that take them.
    """

    root: Any
    options: dict[str, Any] = field(default_factory=dict)
    failures: list[Diagnostic] = field(default_factory=list)
    _results: dict[str, Any] = field(default_factory=dict)
    _taskset: Any = None
    _taskset_tried: bool = False

    @property
    def taskset(self) -> Any:
        """The task set of the instance, extracted once (None, with a failure, when it cannot be)."""
        if not self._taskset_tried:
            self._taskset_tried = True
            from rosaadl.analysis.tasks import taskset_from_instance

            try:
                self._taskset = taskset_from_instance(self.root)
            except RosaadlError as exc:
                self.failures.append(Diagnostic("error", f"task extraction: {exc.message}", exc.location))
        return self._taskset

    @property
    def taskset_if_extracted(self) -> Any:
        """The task set if an analysis extracted it (None otherwise; nothing is extracted here)."""
        return self._taskset

    def result(self, name: str) -> Any:
        """The result of the analysis ``name``, run now if it has not run yet (once per run; a
        failure to run is recorded once and gives None)."""
        if name not in self._results:
            item = analysis(name)
            try:
                self._results[name] = item.run(self)
            except RosaadlError as exc:
                log.debug("analysis %s failed: %s", name, exc)
                self._results[name] = None
                self.failures.append(Diagnostic("error", f"{name} analysis: {exc.message}", exc.location))
        return self._results[name]

"""A proposed deployment: the solver's best bindings beside the current one and the baselines.

:func:`propose_deployment` reads the problem (:mod:`~rosaadl.analysis.deployment_problem`), packs
it with first-, best- and worst-fit decreasing (:mod:`~rosaadl.analysis.deployment_baselines`),
solves it (:mod:`~rosaadl.analysis.deployment_solver`, the worst-fit bindings as hints) and, when
no binding exists, explains why (:mod:`~rosaadl.analysis.deployment_infeasibility`). The
:class:`DeploymentProposal` renders as JSON (``ok``, ``feasible``, ``objectives`` with value,
bound and gap, ``binding``, ``baseline``) and as text (the objectives, then a table of each
unit's core now and proposed), and as the :class:`~rosaadl.analysis.deployment.DeploymentResult`
the reports show.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from rosaadl.analysis.deployment import CoreLoad, DeploymentResult, Placement
from rosaadl.analysis.deployment_baselines import (
    Baseline,
    best_fit_decreasing,
    first_fit_decreasing,
    worst_fit_decreasing,
)
from rosaadl.analysis.deployment_infeasibility import Infeasibility, explain_infeasibility
from rosaadl.analysis.deployment_problem import DeploymentProblem, Evaluation, deployment_problem
from rosaadl.analysis.deployment_solver import SolverOutcome, solve_deployment
from rosaadl.analysis.rendering import table
from rosaadl.errors import Diagnostic, Location

__all__ = ["DeploymentProposal", "propose_deployment"]


@dataclass(frozen=True)
class DeploymentProposal:
    """The outcome of a deployment search by the constraint solver."""

    problem: DeploymentProblem
    outcome: SolverOutcome
    baselines: tuple[Baseline, ...]
    current: Evaluation | None
    explanation: tuple[Infeasibility, ...]
    baseline_seconds: float

    @property
    def feasible(self) -> bool:
        return self.outcome.feasible

    def binding(self, index: int = 0) -> list[tuple[str, str]]:
        """(unit path, binding target) of the ``index``-th best binding: the core, or the virtual
        processor on it that the unit's ``Allowed_Processor_Binding`` names."""
        chosen = self.outcome.bindings[index]
        p = self.problem
        return [(p.units[u].path, p.target(u, c)) for u, c in enumerate(chosen.assignment)]

    def pins(self) -> list[dict[str, str]]:
        """The units held to some cores: ``{"path", "to", "by"}``, ``by`` a device or
        ``Allowed_Processor_Binding``."""
        p = self.problem
        return [{"path": p.units[pin.unit].path, "to": pin.board, "by": pin.reason} for pin in p.pins]

    def as_dict(self, output: str | None = None) -> dict[str, Any]:
        p = self.problem
        best = self.outcome.best
        data: dict[str, Any] = {
            "ok": self.feasible,
            "feasible": self.feasible,
            "status": self.outcome.status,
            "granularity_units": len(p.units),
            "cores": len(p.cores),
            "objectives": [o.as_dict() for o in best.objectives] if best else [],
            "binding": [{"path": u, "processor": c} for u, c in self.binding()] if best else [],
            "baseline": {b.name: b.as_dict(p) for b in self.baselines},
            "pins": self.pins(),
            "output": output,
            "solver": {
                "seconds": round(self.outcome.seconds, 3),
                "load_scale": self.outcome.scale,
                "exact_scale": self.outcome.exact_scale,
                "cuts": self.outcome.cuts,
                "solves": self.outcome.solves,
            },
        }
        if self.current is not None:
            data["current"] = {
                "feasible": self.current.feasible,
                "max_load_percent": float(self.current.max_load * 100),
                "bus_kbyteps": float(self.current.bus_kbyteps),
                "violations": list(self.current.violations),
            }
        if len(self.outcome.bindings) > 1:
            data["alternatives"] = [
                {
                    "objectives": [o.as_dict() for o in other.objectives],
                    "binding": [{"path": u, "processor": c} for u, c in self.binding(i + 1)],
                }
                for i, other in enumerate(self.outcome.bindings[1:])
            ]
        if self.explanation:
            data["explanation"] = [e.as_dict() for e in self.explanation]
        return data

    def text(self) -> list[str]:
        p = self.problem
        best = self.outcome.best
        pins = [
            [_short(p, pin["path"]), pin["to"].replace(p.root + ".", ""), pin["by"].replace(p.root + ".", "")]
            for pin in self.pins()
        ]
        pinned = [""] + table(["pinned unit", "to", "by"], pins) if pins else []
        if best is None:
            lines = [f"no feasible binding ({self.outcome.status}):"]
            lines += [f"  {e}" for e in self.explanation]
            return lines + pinned
        lines = [f"deployment proposal ({self.outcome.status}, {len(p.units)} units on {len(p.cores)} cores)"]
        rows = [
            [
                o.name,
                "-" if o.value is None else f"{float(o.value):g}",
                o.unit,
                _num(o.bound),
                _num(o.gap_percent),
            ]
            for o in best.objectives
        ]
        lines += table(["objective", "value", "unit", "bound", "gap %"], rows)
        lines += pinned
        lines.append("")
        base = [
            [
                b.name,
                f"{float(b.evaluation.max_load * 100):.3f}",
                f"{float(b.evaluation.bus_kbyteps):g}",
                b.feasible,
            ]
            for b in self.baselines
        ]
        if self.current is not None:
            base.insert(
                0,
                [
                    "current",
                    f"{float(self.current.max_load * 100):.3f}",
                    f"{float(self.current.bus_kbyteps):g}",
                    self.current.feasible,
                ],
            )
        base.append(
            [
                "proposed",
                f"{float(best.evaluation.max_load * 100):.3f}",
                f"{float(best.evaluation.bus_kbyteps):g}",
                True,
            ]
        )
        lines += table(["binding", "max core load %", "bus KByte/s", "passes"], base)
        lines.append("")
        moved = []
        for u, c in enumerate(best.assignment):
            now = sorted(p.current[u])
            if len(p.units) <= 40 or (now and c not in now):
                moved.append(
                    [
                        _short(p, p.units[u].path),
                        ", ".join(_short(p, p.target(u, k)) for k in now) or "-",
                        _short(p, p.target(u, c)),
                    ]
                )
        lines += table(["unit", "current", "proposed"], moved)
        return lines

    def as_result(self) -> DeploymentResult:
        """The best binding as the deployment search's result (what the reports show)."""
        p = self.problem
        best = self.outcome.best
        diagnostics = list(p.diagnostics)
        if best is None:
            for e in self.explanation:
                diagnostics.append(Diagnostic("error", e.message, Location(path=e.path)))
            return DeploymentResult(p.root, "cp-sat", False, False, (), (), (), 0, tuple(diagnostics))
        placements = tuple(
            Placement(p.units[u].path, p.cores[c].path, p.load[u][c] or Fraction(0))
            for u, c in enumerate(best.assignment)
        )
        cores = []
        for c, members in enumerate(p.members(best.assignment)):
            cores.append(
                CoreLoad(
                    p.cores[c].path,
                    p.cores[c].capacity,
                    best.evaluation.loads[c],
                    tuple(p.units[u].path for u in members),
                    (p.schedulable(c, members) if p.check_schedulability else True) if members else None,
                )
            )
        return DeploymentResult(
            p.root,
            "cp-sat",
            best.optimal,
            True,
            placements,
            tuple(cores),
            (),
            self.outcome.solves,
            tuple(diagnostics),
        )


def _num(value: Any) -> str:
    return "-" if value is None else f"{float(value):g}"


def _short(problem: DeploymentProblem, path: str) -> str:
    return path.removeprefix(problem.root + ".")


def propose_deployment(
    source: Any,
    *,
    time_limit: float = 10.0,
    keep: int = 1,
    deterministic: bool = False,
    seed: int = 0,
    **problem_options: Any,
) -> DeploymentProposal:
    """Read the deployment problem of ``source`` (an instance, or a
    :class:`~rosaadl.analysis.deployment_problem.DeploymentProblem`; ``problem_options`` go to
    :func:`~rosaadl.analysis.deployment_problem.deployment_problem`), solve it and compare."""
    problem = (
        source if isinstance(source, DeploymentProblem) else deployment_problem(source, **problem_options)
    )
    start = time.perf_counter()
    baselines = (first_fit_decreasing(problem), best_fit_decreasing(problem), worst_fit_decreasing(problem))
    baseline_seconds = time.perf_counter() - start
    hints = [worst_fit_decreasing(problem, keep_boards=True).assignment, baselines[2].assignment]
    hints += [b.assignment for b in baselines[:2]]
    outcome = solve_deployment(
        problem, time_limit=time_limit, keep=keep, seed=seed, hints=hints, deterministic=deterministic
    )
    current = None
    if all(problem.current):
        current = problem.evaluate([min(c) for c in problem.current])
    explanation: tuple[Infeasibility, ...] = ()
    if not outcome.feasible:
        explanation = tuple(explain_infeasibility(problem, time_limit=max(0.5, time_limit / 4)))
    return DeploymentProposal(problem, outcome, baselines, current, explanation, baseline_seconds)

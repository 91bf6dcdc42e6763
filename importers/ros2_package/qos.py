"""The QoS a publisher or subscription is created with, read from the source (never run).

Known forms, as ``rclpy.qos`` defines them:

- a history depth (``10``, or a name bound to it): keep-last, reliable, volatile (rclpy turns an
  ``int`` into ``QoSProfile(depth=n)``, whose other policies are ``rmw_qos_profile_default``'s);
- a preset: ``qos_profile_sensor_data`` (best effort, volatile, depth 5),
  ``qos_profile_system_default``, ``qos_profile_services_default``, ``qos_profile_parameters``,
  ``qos_profile_parameter_events``, or the same through ``QoSPresetProfiles.SENSOR_DATA.value``;
- ``QoSProfile(depth=..., history=..., reliability=..., durability=...)`` with keywords (rclpy's
  ``QoSProfile`` takes keywords only; a policy not given is ``rmw_qos_profile_default``'s:
  reliable, volatile); with ``history=KEEP_ALL`` a depth is kept only when written. Policies may be named
  ``ReliabilityPolicy.BEST_EFFORT`` or by the older ``QoSReliabilityPolicy.
  RMW_QOS_POLICY_RELIABILITY_BEST_EFFORT`` spelling.

Each form may be bound to a name first (``qos = QoSProfile(depth=5)``); the readers keep such a
name as a :class:`QosValue`. Anything else is not known: the caller names it in a warning.
"""

from __future__ import annotations

import ast
from collections.abc import Callable
from dataclasses import dataclass

from rosaadl.importers.ros2_package.evaluation import Known, Scope, evaluate

__all__ = ["QosValue", "PRESETS", "read_qos"]

#: The presets of ``rclpy.qos`` (rmw_qos_profiles.h): reliability, durability, depth.
PRESETS = {
    "qos_profile_sensor_data": ("best_effort", "volatile", "5"),
    "qos_profile_system_default": ("system_default", "system_default", ""),
    "qos_profile_services_default": ("reliable", "volatile", "10"),
    "qos_profile_parameters": ("reliable", "volatile", "1000"),
    "qos_profile_parameter_events": ("reliable", "volatile", "1000"),
}
#: ``QoSPresetProfiles`` members → the preset they hold.
_PRESET_MEMBERS = {
    "SENSOR_DATA": "qos_profile_sensor_data",
    "SYSTEM_DEFAULT": "qos_profile_system_default",
    "SERVICES_DEFAULT": "qos_profile_services_default",
    "PARAMETERS": "qos_profile_parameters",
    "PARAMETER_EVENTS": "qos_profile_parameter_events",
}
_POLICIES = {
    "reliability": ("reliable", "best_effort", "system_default", "best_available"),
    "durability": ("volatile", "transient_local", "system_default", "best_available"),
    "history": ("keep_last", "keep_all", "system_default"),
}
#: ``rmw_qos_profile_default``: what a ``QoSProfile`` keyword left out is.
_DEFAULT = {"reliability": "reliable", "durability": "volatile"}


@dataclass(frozen=True)
class QosValue:
    """A QoS profile known from the source: ``(("depth", "10"), ("reliability", "reliable"), ...)``."""

    items: tuple[tuple[str, str], ...]

    def as_dict(self) -> dict[str, str]:
        return dict(self.items)


def _policy(kind: str, node: ast.expr) -> str | None:
    """``best_effort`` for ``ReliabilityPolicy.BEST_EFFORT`` (or the ``RMW_QOS_POLICY_...``
    spelling); None for anything not a policy member."""
    if not isinstance(node, ast.Attribute):
        return None
    value = node.attr.lower().removeprefix(f"rmw_qos_policy_{kind}_")
    return value if value in _POLICIES[kind] else None


def _profile(call: ast.Call, scope: Scope) -> dict[str, str] | None:
    if call.args or any(k.arg is None for k in call.keywords):
        return None
    found = dict(_DEFAULT)
    keywords = {k.arg: k.value for k in call.keywords}
    for kind in _POLICIES:
        if kind in keywords:
            policy = _policy(kind, keywords[kind])  # type: ignore[arg-type]
            if policy is None:
                return None
            found[kind] = policy
    keep_all = found.pop("history", None) == "keep_all"
    if "depth" in keywords:
        depth = evaluate(keywords["depth"], scope)
        if not (
            isinstance(depth, Known) and isinstance(depth.value, int) and not isinstance(depth.value, bool)
        ):
            return None
        found["depth"] = str(depth.value)
    elif not keep_all:
        return None  # rclpy refuses keep-last without a depth
    return found


def read_qos(
    expr: ast.expr | None, scope: Scope, dotted: Callable[[ast.expr], str | None]
) -> QosValue | None:
    """The QoS ``expr`` stands for (see the module docstring), or None when the source does not
    say it; ``dotted`` names an expression by what it was imported as."""
    if expr is None:
        return None
    value = evaluate(expr, scope)
    if isinstance(value, Known):
        if isinstance(value.value, QosValue):
            return value.value
        if isinstance(value.value, int) and not isinstance(value.value, bool) and value.value >= 0:
            return QosValue((("depth", str(value.value)), *_DEFAULT.items()))
        return None
    if isinstance(expr, ast.Attribute) and expr.attr == "value":
        member = dotted(expr.value) or ""
        if member.rpartition(".")[0].endswith("QoSPresetProfiles"):
            preset = _PRESET_MEMBERS.get(member.rpartition(".")[2])
            expr = ast.Name(preset) if preset else expr
    name = expr.id if isinstance(expr, ast.Name) and expr.id in PRESETS else dotted(expr)
    preset_values = PRESETS.get((name or "").rpartition(".")[2])
    if preset_values:
        pairs = zip(("reliability", "durability", "depth"), preset_values, strict=True)
        return QosValue(tuple((k, v) for k, v in pairs if v))
    if isinstance(expr, ast.Call) and (dotted(expr.func) or "").endswith("QoSProfile"):
        found = _profile(expr, scope)
        return QosValue(tuple(sorted(found.items()))) if found is not None else None
    return None

"""The arguments of rosaadl's public functions: a wrong one is a :class:`UsageError` that names it.

A public function called with an argument of the wrong kind (None where a model is expected, a
string where a list is, a ROSMOD project where an AADL model is) raises a :class:`UsageError`
naming the function, the argument and what it expected, never a ``TypeError`` or
``AttributeError`` from deep inside.

:func:`checked` does this at no cost on the normal path. Only when a call fails with one of the
exceptions a wrong argument causes does it compare each argument with its annotation: one that
does not conform is reported as a :class:`UsageError`; when all conform, the exception is a bug
of rosaadl and propagates unchanged (exit code 3 on the command line). ``@checked(model=
"AadlModel")`` also checks before the call that ``model`` is an object of one of the named
metamodel classes (a check an annotation cannot express).

Values a type does not describe (a path that names something, a finite positive time) are
checked by :func:`expect_path` and :func:`expect_number` where they enter.
"""

from __future__ import annotations

import collections.abc
import functools
import inspect
import math
import numbers
import os
import types
import typing
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from typing import Any, TypeVar

from rosaadl.errors import RosaadlError, UsageError

__all__ = ["checked", "describe", "expect_path", "expect_number", "BAD_ARGUMENT_ERRORS"]

#: What a wrong argument makes Python raise somewhere inside a function.
BAD_ARGUMENT_ERRORS = (
    TypeError,
    AttributeError,
    ValueError,
    KeyError,
    IndexError,
    ZeroDivisionError,
    OverflowError,
    RecursionError,
)

F = TypeVar("F", bound=Callable[..., Any])


def describe(value: object) -> str:
    """A short phrase for a value in a message: ``None``, ``a Project``, ``str 'x'``."""
    if value is None:
        return "None"
    eclass = getattr(type(value), "eClass", None)
    if eclass is not None and hasattr(eclass, "name"):
        return _article(eclass.name)
    shown = repr(value)
    if len(shown) > 60:
        shown = shown[:57] + "..."
    return f"{type(value).__name__} {shown}"


def _article(name: str) -> str:
    return f"{'an' if name[:1].lower() in 'aeiou' else 'a'} {name}"


def checked(
    function: F | None = None, /, *, error: type[RosaadlError] = UsageError, **classes: str | tuple[str, ...]
):
    """Decorate a public function so that a wrong argument is an ``error`` naming it.

    ``classes`` maps parameter names to metamodel class names (``model="AadlModel"``,
    ``root=("SystemInstance", "ComponentInstance")``) checked before each call with
    :func:`rosaadl.model.is_a`; None passes where the parameter's default is None.
    """

    def decorate(fn: F) -> F:
        if inspect.isgeneratorfunction(fn):
            raise TypeError(f"{fn.__qualname__}: a generator fails when iterated; check it in its body")
        signature = inspect.signature(fn)
        name = f"{fn.__qualname__}()"
        annotations: dict[str, Any] | None = None

        def conforming(args: tuple, kwargs: dict) -> str | None:
            """What is wrong with the arguments of this call (None: nothing)."""
            nonlocal annotations
            try:
                bound = signature.bind(*args, **kwargs)
            except TypeError as exc:
                return str(exc)
            if annotations is None:
                annotations = _annotations(fn)
            for parameter, value in bound.arguments.items():
                hint = annotations.get(parameter, Any)
                kind = signature.parameters[parameter].kind
                if kind is inspect.Parameter.VAR_POSITIONAL:
                    values = list(value)
                elif kind is inspect.Parameter.VAR_KEYWORD:
                    values = list(value.values())
                else:
                    values = [value]
                for item in values:
                    if not _conforms(item, hint):
                        written = fn.__annotations__.get(parameter, "")
                        expected = (
                            written if isinstance(written, str) else getattr(written, "__name__", written)
                        )
                        return f"{parameter} must be {expected}, not {describe(item)}"
            return None

        eager = tuple((_position(signature, key), key, _names(value)) for key, value in classes.items())
        defaults = {key: signature.parameters[key].default for _, key, _ in eager}

        def failed(exc: BaseException, args: tuple, kwargs: dict) -> None:
            problem = conforming(args, kwargs)
            if problem is not None:
                raise error(f"{name}: {problem}") from exc

        if not eager:

            @functools.wraps(fn)
            def wrapper(*args, **kwargs):
                try:
                    return fn(*args, **kwargs)
                except BAD_ARGUMENT_ERRORS as exc:
                    failed(exc, args, kwargs)
                    raise

        else:

            @functools.wraps(fn)
            def wrapper(*args, **kwargs):
                for position, key, names in eager:
                    if position is not None and position < len(args):
                        value = args[position]
                    else:
                        value = kwargs.get(key, defaults[key])
                    if value is inspect.Parameter.empty or (value is None and defaults[key] is None):
                        continue
                    if not _is_a(value, *names):
                        wanted = " or ".join(_article(n.rpartition(".")[2]) for n in names)
                        raise error(f"{name}: {key} must be {wanted}, not {describe(value)}")
                try:
                    return fn(*args, **kwargs)
                except BAD_ARGUMENT_ERRORS as exc:
                    failed(exc, args, kwargs)
                    raise

        return typing.cast(F, wrapper)

    return decorate(function) if function is not None else decorate


def _is_a(value: object, *names: str) -> bool:
    from rosaadl.model import is_a  # the façade imports this module

    return is_a(value, *names)


def _names(value: str | tuple[str, ...]) -> tuple[str, ...]:
    return (value,) if isinstance(value, str) else tuple(value)


def _position(signature: inspect.Signature, key: str) -> int | None:
    if key not in signature.parameters:
        raise TypeError(f"checked: no parameter {key!r}")
    for index, parameter in enumerate(signature.parameters.values()):
        if parameter.name == key:
            positional = (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
            return index if parameter.kind in positional else None
    return None  # pragma: no cover - the key is a parameter


def _annotations(fn: Callable[..., Any]) -> dict[str, Any]:
    """The parameters' annotations as objects (one that does not evaluate counts as ``Any``)."""
    namespace = dict(getattr(inspect.unwrap(fn), "__globals__", {}))
    namespace.setdefault("os", os)
    out: dict[str, Any] = {}
    for parameter, written in getattr(fn, "__annotations__", {}).items():
        if parameter == "return":
            continue
        if isinstance(written, str):
            try:
                written = eval(written, namespace)  # noqa: S307 - our own annotations
            except Exception:  # noqa: BLE001 - a name only imported for type checkers
                written = Any
        out[parameter] = written
    return out


_SIZED = (list, tuple, set, frozenset)


def _conforms(value: object, hint: Any) -> bool:
    """Does ``value`` conform to the annotation ``hint``? (Unknown kinds of hints conform.)"""
    if hint is Any or hint is object:
        return True
    if hint is None or hint is type(None):
        return value is None
    origin = typing.get_origin(hint)
    arguments = typing.get_args(hint)
    if origin is typing.Union or origin is types.UnionType:
        return any(_conforms(value, h) for h in arguments)
    if origin is typing.Literal:
        return value in arguments
    if origin is not None:
        if origin is collections.abc.Callable:
            return callable(value)
        if not isinstance(origin, type):
            return True
        if not isinstance(value, origin):
            return False
        if origin is tuple and arguments and arguments[-1] is not Ellipsis:
            return len(value) == len(arguments) and all(  # type: ignore[arg-type]
                _conforms(v, h)
                for v, h in zip(value, arguments, strict=True)  # type: ignore[call-overload]
            )
        if isinstance(value, dict) and len(arguments) == 2:
            return all(_conforms(k, arguments[0]) and _conforms(v, arguments[1]) for k, v in value.items())
        if isinstance(value, _SIZED) and arguments:
            return all(_conforms(v, arguments[0]) for v in value)
        return True
    if isinstance(hint, type):
        if hint is float:
            return isinstance(value, numbers.Real) and not isinstance(value, bool)
        if hint is Fraction:
            return isinstance(value, numbers.Rational) and not isinstance(value, bool)
        return isinstance(value, hint)
    return True  # a TypeVar, a string that did not evaluate, a protocol: not checked


def expect_path(value: object, what: str = "path", *, error: type[RosaadlError] = UsageError) -> Path:
    """``value`` as a :class:`~pathlib.Path`: a non-empty string or path-like without NUL."""
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise error(f"{what} must be a path (a str or os.PathLike), not {describe(value)}")
    if not value or "\x00" in value:
        raise error(f"{what} must name a file or folder, not {value!r}")
    return Path(value)


def expect_number(
    value: object,
    what: str,
    *,
    positive: bool = False,
    minimum: float | None = None,
    integer: bool = False,
    error: type[RosaadlError] = UsageError,
) -> Any:
    """``value`` if it is a finite number (an integer if ``integer``), positive or at least
    ``minimum`` when asked; an ``error`` naming ``what`` otherwise."""
    kind = "an integer" if integer else "a number"
    if isinstance(value, bool) or not isinstance(value, numbers.Integral if integer else numbers.Real):
        raise error(f"{what} must be {kind}, not {describe(value)}")
    if not isinstance(value, numbers.Rational) and not math.isfinite(value):  # type: ignore[arg-type]
        raise error(f"{what} must be finite, not {value}")
    if positive and value <= 0:  # type: ignore[operator]
        raise error(f"{what} must be positive, not {value}")
    if minimum is not None and value < minimum:  # type: ignore[operator]
        raise error(f"{what} must be at least {minimum}, not {value}")
    return value

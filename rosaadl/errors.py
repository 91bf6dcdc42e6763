"""One exception root for everything rosaadl reports to a user.

Every error carries a :class:`Location` (file:line:column for text formats, an element
path for XML, an instance path for models) and a message that says what was expected.
The command line turns a :class:`RosaadlError` into exit code 1 and a one-line report;
anything else is an internal error (exit code 3).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

__all__ = [
    "Location",
    "Diagnostic",
    "RosaadlError",
    "ModelError",
    "ValidationError",
    "ParseError",
    "AadlSyntaxError",
    "NameResolutionError",
    "ImportFormatError",
    "TransformationError",
    "AnalysisError",
    "ExportError",
    "GenerationError",
    "UsageError",
    "CollectedErrors",
]


@dataclass(frozen=True)
class Location:
    """Where something is: a file with line/column, an XML element path, or a model path."""

    file: str | None = None
    line: int | None = None
    column: int | None = None
    path: str | None = None  # XML element path (/cheddar/tasks/periodic_task[2]) or instance path

    def __str__(self) -> str:
        parts: list[str] = []
        if self.file:
            text = self.file
            if self.line is not None:
                text += f":{self.line}"
                if self.column is not None:
                    text += f":{self.column}"
            parts.append(text)
        if self.path:
            parts.append(self.path)
        return " ".join(parts)

    def as_dict(self) -> dict[str, object]:
        return {"file": self.file, "line": self.line, "column": self.column, "path": self.path}


@dataclass(frozen=True)
class Diagnostic:
    """A located finding that is not (yet) an exception: warnings, analysis results."""

    severity: str  # "error" | "warning" | "info"
    message: str
    location: Location = field(default_factory=Location)

    def __str__(self) -> str:
        where = str(self.location)
        return f"{where}: {self.severity}: {self.message}" if where else f"{self.severity}: {self.message}"

    def as_dict(self) -> dict[str, object]:
        return {"severity": self.severity, "message": self.message, **self.location.as_dict()}


class RosaadlError(Exception):
    """Root of every error rosaadl reports to a user.

    An error that stands for several problems found together lists them in ``errors``.
    """

    stage = "model"

    def __init__(
        self,
        message: str,
        location: Location | None = None,
        *,
        file: str | None = None,
        line: int | None = None,
        column: int | None = None,
        path: str | None = None,
        errors: list[RosaadlError | Diagnostic] | None = None,
    ) -> None:
        if location is None:
            location = Location(file=file, line=line, column=column, path=path)
        self.message = message
        self.location = location
        #: every located problem, when one error reports several (a reader that collects them)
        self.errors: list[RosaadlError | Diagnostic] = list(errors) if errors else []
        super().__init__(str(self))

    def __str__(self) -> str:
        where = str(self.location)
        return f"{where}: {self.message}" if where else self.message

    def as_dict(self) -> dict[str, object]:
        return {"message": self.message, "stage": self.stage, **self.location.as_dict()}

    def as_diagnostic(self) -> Diagnostic:
        return Diagnostic("error", self.message, self.location)


class ModelError(RosaadlError):
    """A model is inconsistent, or an API call on it is wrong (unknown feature, bad value)."""

    stage = "model"


class ValidationError(ModelError):
    """A model file does not conform to its metamodel."""

    stage = "validation"


class ParseError(RosaadlError):
    """An input file cannot be read (syntax, encoding, truncation)."""

    stage = "parse"


class AadlSyntaxError(ParseError):
    """AADL text does not follow the grammar; the message lists the expected tokens."""

    stage = "parse"


class NameResolutionError(RosaadlError):
    """A qualified name, classifier, property or path does not resolve."""

    stage = "resolve"


class ImportFormatError(ParseError):
    """An XML/zip/JSON input (aaxl2, Cheddar, WebGME) is malformed, hostile or unsupported."""

    stage = "import"


class TransformationError(RosaadlError):
    """A transformation rule failed; names the rule and the source element."""

    stage = "transform"

    def __init__(
        self,
        message: str,
        location: Location | None = None,
        *,
        rule: str | None = None,
        source: str | None = None,
        **kwargs: object,
    ) -> None:
        self.rule = rule
        self.source = source
        prefix = []
        if rule:
            prefix.append(f"rule {rule!r}")
        if source:
            prefix.append(f"on {source}")
        if prefix:
            message = f"{' '.join(prefix)}: {message}"
        super().__init__(message, location, **kwargs)  # type: ignore[arg-type]


class AnalysisError(RosaadlError):
    """An analysis cannot run on the given instance (missing root, unusable model)."""

    stage = "analysis"


class ExportError(RosaadlError):
    """A model cannot be written in the requested format."""

    stage = "export"


class GenerationError(ExportError):
    """Code generation failed (unsafe names, lost user code, conflicting files)."""

    stage = "generate"


class UsageError(RosaadlError):
    """The command line or API was called wrongly (exit code 2 on the CLI)."""

    stage = "usage"


class CollectedErrors:
    """Mixin of an error that stands for several located errors found together.

    Its message and location are those of the first one (with how many more), ``errors`` lists
    every one and ``str()`` gives one line each. Put it before a :class:`RosaadlError` subclass:
    ``class RosMessageError(CollectedErrors, ParseError)``, as the ROS message and ROSMOD readers do.
    """

    errors: list

    def __init__(self, errors: Sequence[RosaadlError]) -> None:
        if (
            not isinstance(errors, Sequence)
            or not all(isinstance(e, RosaadlError) for e in errors)
            or not errors
        ):
            shown = f"{errors!r:.80}"
            raise UsageError(f"{type(self).__name__} stands for one or more located errors, not {shown}")
        first = errors[0]
        more = len(errors) - 1
        message = first.message if not more else f"{first.message} (and {more} more)"
        super().__init__(message, first.location, errors=list(errors))  # type: ignore[call-arg]

    def __str__(self) -> str:
        return "\n".join(str(e) for e in self.errors)

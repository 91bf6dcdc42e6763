"""Measurements of ROS nodes on boards and cores: the CSV file ``rosaadl library add-profile`` reads.

:func:`parse_measurements` checks a file alone (no model needed) and returns its good rows as
:class:`Measurement` (times exact, in nanoseconds; MIPS and IPC as written), every problem as a
:class:`MeasurementError` located at file:line:column and naming the row and the column, and
warnings (unknown columns). :data:`COLUMNS` are the columns a file must have,
:data:`OPTIONAL_COLUMNS` those it may have; limits keep a hostile file from exhausting memory or
overflowing the model's 64-bit integers. :func:`file_error` makes one error of all the problems
of a file. See ``docs/library.md`` for the columns.
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from decimal import ROUND_HALF_EVEN, ROUND_HALF_UP, Decimal, InvalidOperation
from typing import Any

from rosaadl.errors import Diagnostic, Location, ParseError, RosaadlError, UsageError

__all__ = [
    "COLUMNS",
    "OPTIONAL_COLUMNS",
    "MAX_FILE_BYTES",
    "MAX_ROWS",
    "MeasurementError",
    "Measurement",
    "parse_measurements",
    "file_error",
]

#: The columns a measurements file must have (its header line names them, in any order).
COLUMNS: tuple[str, ...] = (
    "node",
    "thread",
    "board",
    "core",
    "period_us",
    "cet_us",
    "mips_raw",
    "ipc",
    "data_size_bytes",
)
#: Columns a measurements file may have: ``processor``, the classifier of the core measured on.
OPTIONAL_COLUMNS: tuple[str, ...] = ("processor",)

# limits that keep a hostile file from exhausting memory or overflowing the model's 64-bit integers
MAX_FILE_BYTES = 16 * 1024 * 1024
MAX_ROWS = 100_000
_MAX_TIME_NS = 10**18  # about 31 years
_MAX_MIPS = Decimal(10) ** 9
_MAX_IPC = Decimal(1000)
_MIN_IPC = Decimal("0.000001")
_MAX_SIZE = 2**53

_IDENTIFIER = re.compile(r"[A-Za-z](?:_?[A-Za-z0-9])*\Z")
_PART = re.compile(r"[A-Za-z0-9](?:_?[A-Za-z0-9])*\Z")
_CLASSIFIER = re.compile(
    r"[A-Za-z](?:_?[A-Za-z0-9])*(?:::[A-Za-z](?:_?[A-Za-z0-9])*)+(?:\.[A-Za-z](?:_?[A-Za-z0-9])*)?\Z"
)
#: A thread of a node: its name, or its path through thread groups (``Client.client_timer``).
_THREAD_PATH = re.compile(r"[A-Za-z](?:_?[A-Za-z0-9])*(?:\.[A-Za-z](?:_?[A-Za-z0-9])*)*\Z")
_NODE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z][A-Za-z0-9_]*)*\Z")
_CENT = Decimal("0.01")


class MeasurementError(ParseError):
    """A measurements file is malformed or does not match the library; located at file:line
    (and the column's position), naming the row and the column. The error raised for a whole file
    lists every problem in ``errors``."""

    stage = "profile"

    def __init__(self, message: str, location: Location | None = None, **kwargs: Any) -> None:
        self.errors: list[RosaadlError] = []
        super().__init__(message, location, **kwargs)


@dataclass(frozen=True)
class Measurement:
    """One good row of a measurements file. Times are in nanoseconds (exact), MIPS and IPC as
    written; ``columns`` maps each column name to its 1-based position."""

    file: str
    row: int
    line: int
    node: str
    thread: str
    board: str
    core: str
    period_ns: int | None  #: None: the thread keeps the PIM's Period (a measured run)
    cet_ns: int
    mips_raw: Decimal | None  #: None: not measured (a run without hardware counters)
    ipc: Decimal | None
    data_size: int | None
    processor: str | None
    columns: tuple[tuple[str, int], ...] = ()
    #: the executor's measured dispatch latency, whole µs in ns (a measured run's
    #: ``dispatch_latency_us`` max, rounded up); None: not measured (no CSV column gives it)
    dispatch_latency_ns: int | None = None
    #: the workload twin's CPU time per dispatch (ns, 0: no twin) and the speed of the process's
    #: CPUs (a measured run's ``twin_execution_time_us`` and ``cpu_speed``); None: not gauged
    twin_execution_time_ns: int | None = None
    cpu_speed: float | None = None

    @property
    def pdm(self) -> str:
        """The implementation name of the PDM: ``<board>_<core>``."""
        return f"{self.board}_{self.core}"

    @property
    def mips_budget(self) -> Decimal | None:
        """``mips_raw / ipc`` rounded half up to 2 decimals, as the paper's Table 2 gives it
        (None when either was not measured)."""
        if self.mips_raw is None or self.ipc is None:
            return None
        return (self.mips_raw / self.ipc).quantize(_CENT, rounding=ROUND_HALF_UP)

    def where(self, column: str | None = None) -> Location:
        position = dict(self.columns).get(column) if column else None
        return Location(file=self.file, line=self.line, column=position)

    def error(self, column: str | None, message: str) -> MeasurementError:
        """An error at this row; ``column`` names one column (or several, comma-separated)."""
        if column:
            what = f"row {self.row}, {'columns' if ',' in column else 'column'} {column}"
        else:
            what = f"row {self.row}"
        return MeasurementError(f"{what}: {message}", self.where(column))


def _lines(text: str) -> Iterator[str]:
    """The physical lines of ``text`` (terminators kept), comment lines (``#`` first) emptied."""
    for line in io.StringIO(text, newline=""):
        yield "\n" if line.startswith("#") else line


def _number(text: str) -> Decimal | None:
    try:
        value = Decimal(text)
    except (InvalidOperation, ValueError):
        return None
    return value if value.is_finite() else None


def _describe_cell(text: str) -> str:
    shown = text if len(text) <= 40 else text[:37] + "..."
    return repr(shown)


def parse_measurements(
    data: str | bytes, filename: str = "<measurements>", *, max_rows: int = MAX_ROWS
) -> tuple[list[Measurement], list[MeasurementError], list[Diagnostic]]:
    """Read a measurements file: ``(good rows, errors, warnings)``. Every row is checked; a row
    with any error gives no :class:`Measurement`. See :data:`COLUMNS` and ``docs/library.md``."""
    errors: list[MeasurementError] = []
    warnings: list[Diagnostic] = []

    def fail(message: str, line: int | None = None, column: int | None = None) -> None:
        errors.append(MeasurementError(message, Location(file=filename, line=line, column=column)))

    if isinstance(data, (bytes, bytearray, memoryview)):
        raw = bytes(data)
        if len(raw) > MAX_FILE_BYTES:
            fail(f"the file is larger than {MAX_FILE_BYTES} bytes, the limit for a measurements file")
            return [], errors, warnings
        try:
            text = raw.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            fail(f"not UTF-8 text ({exc.reason}); expected a CSV file", raw[: exc.start].count(b"\n") + 1)
            return [], errors, warnings
    else:
        text = data[1:] if data.startswith("\ufeff") else data
        if len(text) > MAX_FILE_BYTES:
            fail(f"the text is {len(text)} characters; measurements files are limited to {MAX_FILE_BYTES}")
            return [], errors, warnings
    if "\x00" in text:
        fail("the file contains a NUL byte; expected CSV text", text[: text.index("\x00")].count("\n") + 1)
        return [], errors, warnings
    if not text.strip():
        fail(f"the file is empty; expected a header line naming the columns {', '.join(COLUMNS)}", 1)
        return [], errors, warnings

    reader = csv.reader(_lines(text), strict=True, skipinitialspace=True)
    header: dict[str, int] | None = None
    header_line = 1
    rows: list[Measurement] = []
    previous_end = 0
    row_number = 0
    try:
        for record in reader:
            start = previous_end + 1
            previous_end = reader.line_num
            cells = [cell.strip() for cell in record]
            if not any(cells):
                continue  # blank lines, comments and rows of empty cells
            if header is None:
                header_line = start
                header = _read_header(cells, filename, start, errors, warnings)
                continue
            row_number += 1
            if row_number > max_rows:
                fail(f"more than {max_rows} rows; split the measurements into several files", start)
                break
            measurement = _read_row(cells, header, filename, row_number, start, errors)
            if measurement is not None:
                rows.append(measurement)
    except csv.Error as exc:
        fail(f"malformed CSV: {exc}", reader.line_num or 1)
    if header is None and not errors:
        fail(f"the file holds no header line; expected one naming the columns {', '.join(COLUMNS)}", 1)
    elif header is not None and row_number == 0 and not errors:
        fail("the file has a header but no measurement rows", header_line)
    return rows, errors, warnings


def _read_header(
    cells: list[str], filename: str, line: int, errors: list[MeasurementError], warnings: list[Diagnostic]
) -> dict[str, int]:
    header: dict[str, int] = {}
    for position, cell in enumerate(cells, start=1):
        name = cell.lower()
        where = Location(file=filename, line=line, column=position)
        if not name:
            errors.append(MeasurementError(f"header: column {position} has no name", where))
        elif name in header:
            errors.append(
                MeasurementError(
                    f"header: column {name} is named twice (columns {header[name]} and {position})", where
                )
            )
        else:
            header[name] = position
            if name not in COLUMNS and name not in OPTIONAL_COLUMNS:
                warnings.append(
                    Diagnostic(
                        "warning",
                        f"header: column {cell!r} is not a measurement column and is ignored "
                        f"(columns: {', '.join(COLUMNS + OPTIONAL_COLUMNS)})",
                        where,
                    )
                )
    for name in COLUMNS:
        if name not in header:
            errors.append(
                MeasurementError(
                    f"header: missing column {name} (the header must name {', '.join(COLUMNS)})",
                    Location(file=filename, line=line),
                )
            )
    return header


def _read_row(
    cells: list[str],
    header: dict[str, int],
    filename: str,
    row: int,
    line: int,
    errors: list[MeasurementError],
) -> Measurement | None:
    before = len(errors)

    def fail(column: str | None, message: str, position: int | None = None) -> None:
        if position is None and column is not None:
            position = header.get(column)
        what = f"row {row}, column {column}" if column else f"row {row}"
        errors.append(
            MeasurementError(f"{what}: {message}", Location(file=filename, line=line, column=position))
        )

    width = max(header.values(), default=0)
    if len(cells) > width:
        fail(None, f"the row has {len(cells)} fields, the header names {width} columns", width + 1)
    short = [c for c in COLUMNS if c in header and header[c] > len(cells) and c != "data_size_bytes"]
    if short:
        fail(
            short[0],
            f"the row has {len(cells)} fields, the header names {width} columns: no value for "
            + ", ".join(short),
        )

    def cell(column: str) -> str | None:
        position = header.get(column)
        if position is None:
            return None  # a missing column, reported once with the header
        if position > len(cells):
            # a missing required value is reported above; optional ones may be left off the end
            return None if column in short else ""
        return cells[position - 1]

    def name(column: str, pattern: re.Pattern[str], what: str) -> str | None:
        value = cell(column)
        if value is None:
            return None
        if not value:
            fail(column, f"empty; expected {what}")
            return None
        if len(value) > 200 or not pattern.match(value):
            fail(column, f"{_describe_cell(value)} is not {what}")
            return None
        return value

    def time_ns(column: str, what: str) -> int | None:
        value = cell(column)
        if value is None:
            return None
        number = _number(value)
        if number is None:
            fail(column, f"{_describe_cell(value) if value else 'empty'}: expected a number of microseconds")
            return None
        if number <= 0:
            fail(column, f"{value} us: {what} must be positive")
            return None
        if number > Decimal(_MAX_TIME_NS) / 1000:
            fail(column, f"{value} us is out of range (at most {_MAX_TIME_NS // 1000} us)")
            return None
        ns = int((number * 1000).quantize(Decimal(1), rounding=ROUND_HALF_EVEN))
        if ns <= 0:
            fail(column, f"{value} us is below a nanosecond: {what} must be positive")
            return None
        return ns

    def positive(column: str, what: str, limit: Decimal) -> Decimal | None:
        value = cell(column)
        if value is None:
            return None
        number = _number(value)
        if number is None:
            fail(column, f"{_describe_cell(value) if value else 'empty'}: expected a number ({what})")
            return None
        if number == 0 and column == "ipc":
            fail(column, "the IPC is zero: MIPSBudget = mips_raw / ipc is undefined")
            return None
        if number <= 0:
            fail(column, f"{value}: {what} must be positive")
            return None
        if number > limit:
            fail(column, f"{value} is out of range (at most {limit})")
            return None
        if column == "ipc" and number < _MIN_IPC:
            fail(column, f"{value} is out of range (at least {_MIN_IPC})")
            return None
        return number

    node = name(
        "node", _NODE_NAME, "a node (its package nd_x, its process x_nd, Pkg::x_nd or its ROS node name)"
    )
    thread = name(
        "thread",
        _THREAD_PATH,
        "a thread (the name of a thread of the node's PIM, its path through thread groups "
        "Group.thread, or its thread type)",
    )
    board = name(
        "board", _IDENTIFIER, "a board name (letters, digits and single underscores, starting with a letter)"
    )
    core = name("core", _PART, "a core name (letters, digits and single underscores)")
    if board is not None and core is not None and not _IDENTIFIER.match(f"{board}_{core}"):
        fail("core", f"{board}_{core} is not an AADL identifier")
    period = time_ns("period_us", "a period")
    cet = time_ns("cet_us", "a compute execution time")
    mips = positive("mips_raw", "the raw MIPS rate", _MAX_MIPS)
    ipc = positive("ipc", "the instructions per cycle", _MAX_IPC)
    size: int | None = None
    raw_size = cell("data_size_bytes")
    if raw_size:
        number = _number(raw_size)
        if number is not None and number > _MAX_SIZE:
            fail("data_size_bytes", f"{raw_size} is out of range (at most {_MAX_SIZE})")
        elif number is None or number != number.to_integral_value():
            fail(
                "data_size_bytes",
                f"{_describe_cell(raw_size)}: expected a whole number of bytes (or nothing)",
            )
        elif number < 0:
            fail("data_size_bytes", f"{raw_size}: a data size cannot be negative")
        else:
            size = int(number)
    processor = None
    raw_processor = cell("processor") if "processor" in header else None
    if raw_processor:
        if len(raw_processor) > 200 or not _CLASSIFIER.match(raw_processor):
            fail("processor", f"{_describe_cell(raw_processor)} is not a classifier name (Pkg::Core)")
        else:
            processor = raw_processor
    if len(errors) > before or None in (node, thread, board, core, period, cet, mips, ipc):
        return None
    columns = tuple(sorted(header.items(), key=lambda item: item[1]))
    return Measurement(
        filename, row, line, node, thread, board, core, period, cet, mips, ipc, size, processor, columns
    )


def file_error(errors: Sequence[RosaadlError], what: str = "problems") -> MeasurementError:
    """One error for a whole file: every problem, in file and line order, in ``errors``."""
    if not errors:
        raise UsageError("file_error(): errors must list one or more problems")
    errors = sorted(
        errors,
        key=lambda e: (e.location.file or "", e.location.line or 0, e.location.column or 0),
    )
    first = errors[0]
    if len(errors) == 1 and isinstance(first, MeasurementError):
        first.errors = [first]
        return first
    listing = "\n".join(f"  {e}" for e in errors)
    exc = MeasurementError(f"{first.message}\n{len(errors)} {what}:\n{listing}", first.location)
    exc.errors = list(errors)
    return exc

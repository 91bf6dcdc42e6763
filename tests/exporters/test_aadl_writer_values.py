"""The AADL text writer: property values and associations (numbers, ranges, modal values,
records, operations)."""

from __future__ import annotations

import math
import re

import pytest
from aadl_writer_models import (
    N,
    i,
    lst,
    named,
    op,
    pa,
    package,
    props_text,
    r,
    rec,
    s,
    tokens,
    type_with_props,
    write_unit,
)
from hypothesis import given
from hypothesis import strategies as st

from rosaadl.errors import ExportError
from rosaadl.exporters.aadl_text import format_real
from rosaadl.importers.aadl_syntax import parse

# --------------------------------------------------------------------------- property values


def test_string_escaping() -> None:
    text = props_text(pa("Source_Text", s('a "quoted" word')), pa("Doc", s("")), pa("Path", s("C:\\dir\\")))
    assert 'Source_Text => "a ""quoted"" word";' in text
    assert 'Doc => "";' in text
    assert 'Path => "C:\\\\dir\\\\";' in text


@pytest.mark.parametrize(
    ("value", "expected"),
    [
        (1.0, "1.0"),
        (2.5e-3, "0.0025"),
        (1e-5, "1.0e-5"),
        (1.5e-7, "1.5e-7"),
        (1e16, "1.0e16"),
        (-3.25, "-3.25"),
        (0.1, "0.1"),
        (123456789.0, "123456789.0"),
        (5e-324, "5.0e-324"),
        (1.7976931348623157e308, "1.7976931348623157e308"),
    ],
)
def test_real_literals(value: float, expected: str) -> None:
    assert format_real(value) == expected
    assert float(expected) == value


REAL_TOKEN = re.compile(r"-?[0-9](?:_?[0-9])*\.[0-9](?:_?[0-9])*(?:[eE][+-]?[0-9]+)?\Z")


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_real_literals_read_back_equal(value: float) -> None:
    text = format_real(value)
    assert REAL_TOKEN.match(text), text
    assert float(text) == value


def test_reals_in_text_are_real_tokens() -> None:
    text = write_unit(package("P", type_with_props(pa("X", r(1e-5, "ms")), pa("Y", r(-7.0)))))
    reals = tokens(parse(text), "REAL")
    assert reals == ["1.0e-5", "7.0"]
    assert "Y => -7.0;" in text


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan])
def test_non_finite_reals_are_refused(bad: float) -> None:
    with pytest.raises(ExportError, match=r"no AADL literal") as info:
        write_unit(package("P", type_with_props(pa("Weight", r(bad)))))
    assert "T" in str(info.value) and "Weight" in str(info.value)


def test_ranges() -> None:
    text = props_text(
        pa("A", N("RangeValue", minimum=i(1, "ms"), maximum=i(2, "ms"))),
        pa("B", N("RangeValue", minimum=r(0.5), maximum=r(1.5), delta=r(0.25))),
        pa("C", N("RangeValue", minimum=i(-3), maximum=named("PS::Max"))),
    )
    assert text.splitlines() == ["A => 1 ms .. 2 ms;", "B => 0.5 .. 1.5 delta 0.25;", "C => -3 .. PS::Max;"]


def test_modal_values() -> None:
    text = props_text(
        pa("Period", (i(10, "ms"), ["fast"]), (i(50, "ms"), ["slow", "idle"]), i(100, "ms")),
        pa("Priority", (i(1), ["fast"])),
    )
    assert text.splitlines() == [
        "Period => (10 ms in modes (fast), 50 ms in modes (slow, idle), 100 ms);",
        "Priority => (1 in modes (fast));",
    ]
    tree = parse(write_unit(package("P", type_with_props(pa("Period", (i(1), ["a"]), i(2))))))
    assert len(list(tree.find_data("modal_value"))) == 2


def test_default_modal_value_goes_last() -> None:
    text = props_text(pa("Period", i(100, "ms"), (i(10, "ms"), ["fast"])))
    assert text == "Period => (10 ms in modes (fast), 100 ms);"
    with pytest.raises(ExportError, match="only one value without 'in modes'"):
        props_text(pa("Period", i(1), i(2)))


def test_records_and_lists_of_lists() -> None:
    text = props_text(
        pa("R", rec(a=i(1), b=lst(s("x"), s("y")), c=rec(d=N("BooleanValue", value=False)))),
        pa("L", lst(lst(i(1), i(2)), lst(lst(i(3))), lst())),
        pa("E", rec()),
    )
    assert text.splitlines() == [
        'R => [a => 1; b => ("x", "y"); c => [d => false;];];',
        "L => ((1, 2), ((3)), ());",
        "E => [];",
    ]


def test_append_constant_applies_to_and_in_binding() -> None:
    text = props_text(
        pa("Actual_Connection_Binding", lst(N("ReferenceValue", path="hw.bus[2]")), append=True,
           appliesTo=["a.b[1].c", "sw.cam[1 .. 3].pub"], inBinding=["hw::cpu.impl", "hw::board"]),
        pa("K", i(1), constant=True),
    )  # fmt: skip
    assert text.splitlines() == [
        "Actual_Connection_Binding +=> (reference (hw.bus[2]))",
        "applies to a.b[1].c, sw.cam[1 .. 3].pub in binding (hw::cpu.impl, hw::board);",
        "K => constant 1;",
    ]
    tree = parse(
        write_unit(package("P", type_with_props(pa("X", i(1), append=True, appliesTo=["a.b[1].c"]))))
    )
    assert list(tree.find_data("append")) and list(tree.find_data("indexed_element"))


def test_boolean_operations_keep_their_structure() -> None:
    a, b, c = named("A"), named("B"), named("C")
    text = props_text(
        pa("X1", op("and", op("or", a, b), c)),
        pa("X2", op("not", op("and", named("A"), named("B")))),
        pa(
            "X3",
            op("or", named("A"), op("and", named("B"), named("C")), op("not", N("BooleanValue", value=True))),
        ),
        pa("X4", op("or", op("or", named("A"), named("B")), named("C"))),
        pa("X5", op("minus", i(5, "ms"))),
    )
    assert text.splitlines() == [
        "X1 => (A or B) and C;",
        "X2 => not (A and B);",
        "X3 => A or B and C or not true;",
        "X4 => (A or B) or C;",
        "X5 => -5 ms;",
    ]


def test_bad_operations_are_refused() -> None:
    with pytest.raises(ExportError, match="unknown operator"):
        props_text(pa("X", op("xor", named("A"), named("B"))))
    with pytest.raises(ExportError, match="needs at least two operands"):
        props_text(pa("X", op("and", named("A"))))
    with pytest.raises(ExportError, match="signed"):
        props_text(pa("X", op("-", i(-5))))


def test_instance_reference_value_is_refused() -> None:
    with pytest.raises(ExportError, match="InstanceReferenceValue has no AADL text form"):
        props_text(pa("Actual_Processor_Binding", N("InstanceReferenceValue")))


def test_association_without_value_is_refused() -> None:
    with pytest.raises(ExportError, match="needs a value"):
        props_text(N("PropertyAssociation", property="Period"))

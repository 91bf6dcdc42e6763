"""The one printer of property values as AADL text (``rosaadl.property_text``).

The AADL text writer uses it with rules that check every name and refuse what has no AADL form
(its own tests are in ``tests/exporters/test_aadl_writer_values.py``); ``format_value`` uses it
leniently for showing a model (``rosaadl library show``), instance references included.
"""

from __future__ import annotations

import math

import pytest

from rosaadl import model
from rosaadl.errors import ModelError, RosaadlError
from rosaadl.importers.aadl_text import read_string
from rosaadl.property_text import LenientNames, ValuePrinter, format_real, format_value, string_literal

N = model.new


def test_format_value_covers_every_value_kind() -> None:
    text = """
package values_pkg
public
  with SEI;
  system s
    properties
      Period => 10 ms;
      SEI::MIPSBudget => 1.5 MIPS;
      Compute_Execution_Time => 1 us .. 2 us;
      Source_Name => "a ""quoted"" name";
      Dispatch_Protocol => Periodic;
      Actual_Processor_Binding => (reference (a.b), reference (c));
      Reference_Processor => classifier (P::Q);
      Priority => -3;
  end s;
end values_pkg;
"""
    unit = read_string(text, "v.aadl").units[0]
    shown = [format_value(pa.ownedValues[0].value) for pa in unit.classifiers[0].ownedPropertyAssociations]
    assert shown == [
        "10 ms",
        "1.5 MIPS",
        "1 us .. 2 us",
        '"a ""quoted"" name"',
        "Periodic",
        "(reference (a.b), reference (c))",
        "classifier (P::Q)",
        "-3",
    ]
    boolean = model.new("BooleanValue", value=True)
    assert format_value(boolean) == "true" and format_value(None) == ""


def test_instance_references_are_shown_by_their_path() -> None:
    root = N("SystemInstance", name="top")
    board = N("ComponentInstance", name="board", category="system")
    cpu = N("ComponentInstance", name="cpu", category="processor")
    board.componentInstances.append(cpu)
    root.componentInstances.append(board)
    value = N("ListValue", ownedItems=[N("InstanceReferenceValue", referencedInstanceObject=cpu)])
    assert format_value(value) == f"(reference ({model.instance_path(cpu)}))"
    assert format_value(N("InstanceReferenceValue")) == "reference (?)"


@pytest.mark.parametrize(
    ("value", "shown"),
    [
        (N("RangeValue", maximum=N("IntegerValue", value=5)), " .. 5"),
        (N("RealValue", value=math.inf, unit="ms"), "inf ms"),
        (
            N(
                "OperationValue",
                operator="xor",
                ownedOperands=[N("NamedValue", name="A"), N("NamedValue", name="B")],
            ),
            "A xor B",
        ),
        (
            N(
                "OperationValue",
                operator="-",
                ownedOperands=[N("IntegerValue", value=1), N("IntegerValue", value=2)],
            ),
            "1 - 2",
        ),
        (N("OperationValue", operator="-", ownedOperands=[N("IntegerValue", value=-5)]), "--5"),
        (N("StringValue", value="C:\\dir"), '"C:\\\\dir"'),
        (N("NamedValue"), ""),
        (N("IntegerValue"), "0"),
    ],
    ids=[
        "open-range",
        "infinite",
        "unknown-operator",
        "binary-minus",
        "signed-negative",
        "backslash",
        "no-name",
        "no-number",
    ],
)
def test_what_has_no_aadl_form_is_still_shown(value, shown: str) -> None:
    assert format_value(value) == shown


def test_boolean_operations_keep_their_structure() -> None:
    a, b, c = (N("NamedValue", name=x) for x in "ABC")
    either = N("OperationValue", operator="or", ownedOperands=[a, b])
    both = N("OperationValue", operator="AND", ownedOperands=[either, c])
    assert format_value(both) == "(A or B) and C"
    assert format_value(N("OperationValue", operator="not", ownedOperands=[both])) == "not ((A or B) and C)"


class _Refusing(LenientNames):
    """Rules of a strict printer: names upper-cased, anything without an AADL form refused."""

    def ident(self, name, what, element=None):
        return (name or "").upper()

    qname = path = classifier_ref = ident

    def refuse(self, message, element=None):
        raise ModelError(message)


def test_the_rules_decide_names_and_refusals() -> None:
    printer = ValuePrinter(_Refusing())
    value = N(
        "RecordValue",
        ownedFields=[
            N("FieldValue", name="speed", value=N("IntegerValue", value=3, unit="kph")),
            N("FieldValue", name="impl", value=N("ClassifierValue", classifier="p::t.i")),
            N("FieldValue", name="at", value=N("ReferenceValue", path="a.b")),
        ],
    )
    assert printer.text(value) == "[SPEED => 3 KPH; IMPL => classifier (P::T.I); AT => reference (A.B);]"
    with pytest.raises(ModelError, match="InstanceReferenceValue has no AADL text form"):
        printer.text(N("InstanceReferenceValue"))
    with pytest.raises(ModelError, match="a property value is missing"):
        printer.text(None)
    with pytest.raises(ModelError, match="a range needs a minimum and a maximum"):
        printer.text(N("RangeValue", minimum=N("IntegerValue", value=1)))
    with pytest.raises(ModelError, match="range bound must be a number"):
        printer.text(N("RangeValue", minimum=N("StringValue", value="x"), maximum=N("IntegerValue")))


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan, "x", None])
def test_format_real_refuses_what_is_not_a_finite_number(bad) -> None:
    with pytest.raises(ModelError) as info:
        format_real(bad)
    assert isinstance(info.value, RosaadlError)


def test_string_literal_doubles_quotes_and_escapes_backslashes() -> None:
    assert string_literal('a "b" \\ c') == '"a ""b"" \\\\ c"'

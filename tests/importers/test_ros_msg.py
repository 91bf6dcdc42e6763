"""ROS .msg/.srv parsing, located errors, model fields and the fixed Data_Size convention."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rosaadl import model
from rosaadl.errors import ParseError, RosaadlError
from rosaadl.importers import ros_msg
from rosaadl.importers.ros_msg import data_size, parse_field, parse_msg, parse_srv, unsized_reason


def field(text: str, package: str | None = "pkg") -> ros_msg.FieldSpec:
    spec = parse_field(text, package=package, filename="t.msg", line=1)
    assert spec is not None
    return spec


# --------------------------------------------------------------------------- field syntax


@pytest.mark.parametrize(
    ("text", "type_", "is_array", "length", "bound", "sbound"),
    [
        ("int32 x", "int32", False, None, None, None),
        ("uint8[] data", "uint8", True, None, None, None),
        ("float64[9] covariance", "float64", True, 9, None, None),
        ("int32[<=5] window", "int32", True, None, 5, None),
        ("string<=10 label", "string", False, None, None, 10),
        ("string<=10[<=5] labels", "string", True, None, 5, 10),
        ("geometry_msgs/Point p", "geometry_msgs/Point", False, None, None, None),
        ("geometry_msgs/msg/Point p", "geometry_msgs/Point", False, None, None, None),
        ("Point[4] corners", "pkg/Point", True, 4, None, None),
        ("Header header", "std_msgs/Header", False, None, None, None),
        ("time stamp", "time", False, None, None, None),
    ],
)
def test_field_types(text, type_, is_array, length, bound, sbound):
    spec = field(text)
    assert (spec.type, spec.is_array, spec.array_length, spec.upper_bound, spec.string_bound) == (
        type_,
        is_array,
        length,
        bound,
        sbound,
    )
    assert spec.constant is None and spec.default is None


def test_type_text_round_trips_the_spelling():
    for text in ("uint8[]", "float64[9]", "int32[<=5]", "string<=10", "string<=10[<=5]", "pkg/T[]"):
        assert field(f"{text} x").type_text == text


def test_constants_and_comments():
    assert field("int32 MAX=10 # the maximum").constant == "10"
    assert field("uint8 MODE = 0x1").constant == "0x1"
    assert field("bool ON=true").constant == "true"
    # ROS 1: a string constant is the rest of the line, '#' included
    spec = field("string GREETING=hello # world")
    assert spec.constant == "hello # world"
    assert spec.is_constant and spec.is_primitive
    assert field("float32 x  # a comment").constant is None
    assert parse_field("   # only a comment", line=3) is None
    assert parse_field("", line=3) is None


def test_ros2_default_values():
    assert field("int32 x 5").default == "5"
    assert field('string name "a # b"').default == '"a # b"'
    assert field("int32[] xs [1, 2, 3]").default == "[1, 2, 3]"
    assert field("float64 gain 0.5  # tuned").default == "0.5"


@pytest.mark.parametrize(
    ("text", "column", "fragment"),
    [
        ("int32[x] a", 1, "malformed field type"),
        ("int32", 6, "expected a field name"),
        ("  int32 9abc", 9, "expected a field name"),
        ("int32[] X=1", 1, "must have a primitive, non-array type"),
        ("pkg/T X=1", 1, "must have a primitive, non-array type"),
        ("uint8 X=300", 9, "out of range"),
        ("int32 X=", 8, "has no value"),
        ("bool B=maybe", 8, "expected true or false"),
        ("int32 x y", 9, "expected an integer"),
        ("int32[] xs 5", 12, "must be a list"),
        ("pkg/T t 5", 9, "nested types take no default"),
        ("int32<=5 x", 1, "only string types can be bounded"),
        ("int32[<=] x", 1, "malformed field type"),
        ("int32 x$", 8, "unexpected"),
    ],
)
def test_field_errors_are_located(text, column, fragment):
    with pytest.raises(ParseError) as info:
        parse_field(text, filename="bad.msg", line=7)
    err = info.value
    assert isinstance(err, RosaadlError)
    assert fragment in err.message
    assert (err.location.file, err.location.line, err.location.column) == ("bad.msg", 7, column)


def test_parse_msg_reports_every_error_and_duplicates():
    text = "int32 a\nint32[x] b\nfloat64 a\nstring ok\nbool c=maybe\n"
    with pytest.raises(ros_msg.RosMessageError) as info:
        parse_msg(text, filename="m.msg")
    errors = info.value.errors
    assert [e.location.line for e in errors] == [2, 3, 5]
    assert "duplicate field name 'a'" in errors[1].message
    assert "(and 2 more)" in info.value.message
    assert str(info.value).count("m.msg:") == 3


def test_parse_msg_keeps_order_constants_and_text():
    text = "# header comment\nint32 A=1\r\nfloat64 x\n\nstring s\n"
    spec = parse_msg(text, name="M", package="p")
    assert [f.name for f in spec.fields] == ["A", "x", "s"]
    assert [f.name for f in spec.constants] == ["A"]
    assert [f.name for f in spec.data_fields] == ["x", "s"]
    assert spec.full_name == "p/M" and spec.text == text
    assert spec.fields[1].line == 3


def test_parse_srv():
    spec = parse_srv("int64 goal\nbool update\n---\nint64 current\n", name="Pos", package="motors")
    assert [f.name for f in spec.request.fields] == ["goal", "update"]
    assert [f.name for f in spec.response.fields] == ["current"]
    assert spec.request.name == "PosRequest" and spec.response.package == "motors"
    empty = parse_srv("---\n")
    assert empty.request.fields == () and empty.response.fields == ()


@pytest.mark.parametrize("text", ["int32 a\n", "int32 a\n---\nint32 b\n---\nint32 c\n"])
def test_srv_needs_exactly_one_separator(text):
    with pytest.raises(ros_msg.RosMessageError, match="exactly one '---'"):
        parse_srv(text, filename="s.srv")


def test_srv_errors_in_both_parts_are_collected():
    with pytest.raises(ros_msg.RosMessageError) as info:
        parse_srv("int32[x] a\n---\nbool b=2\n", filename="s.srv")
    assert [e.location.line for e in info.value.errors] == [1, 3]


# --------------------------------------------------------------------------- sizes


@pytest.mark.parametrize(
    ("text", "size"),
    [
        ("bool a\nint8 b\nuint8 c\nbyte d\nchar e", 5),
        ("int16 a\nuint16 b", 4),
        ("int32 a\nuint32 b\nfloat32 c", 12),
        ("int64 a\nuint64 b\nfloat64 c", 24),
        ("time t\nduration d", 16),
        ("float64[9] covariance", 72),
        ("uint8[3] rgb\nint32 X=5\nstring NAME=not counted", 3),
        ("geometry_msgs/Pose pose", 56),
        ("geometry_msgs/Point[2] segment", 48),
        ("", 0),
    ],
)
def test_fixed_sizes(text, size):
    assert data_size(parse_msg(text, package="pkg")) == size
    assert unsized_reason(parse_msg(text, package="pkg")) is None


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("string s", "variable length"),
        ("string<=8 s", "variable length"),
        ("uint8[] data", "unbounded array"),
        ("int32[<=4] w", "bounded array"),
        ("Header header", "std_msgs/Header"),
        ("other_pkg/Unknown u", "is not known"),
        ("geometry_msgs/PoseStamped p", "string"),
    ],
)
def test_unsized(text, reason):
    spec = parse_msg(text, package="pkg")
    assert data_size(spec) is None
    assert reason in unsized_reason(spec)


def test_nested_project_types_and_recursion():
    inner = parse_msg("float32 x\nfloat32 y", name="Vec", package="pkg")
    outer = parse_msg("Vec[2] pair\nuint8 flag", name="Outer", package="pkg")
    table = {"pkg/Vec": inner, "pkg/Outer": outer}
    assert data_size(outer, table.get) == 17
    looped = parse_msg("Loop next", name="Loop", package="pkg")
    assert data_size(looped, {"pkg/Loop": looped}.get) is None
    assert "contains itself" in unsized_reason(looped, {"pkg/Loop": looped}.get)


def test_standard_definitions_parse():
    for name in ros_msg.STANDARD_DEFINITIONS:
        assert ros_msg.standard_message(name) is not None
    assert data_size(ros_msg.standard_message("geometry_msgs/Twist")) == 48
    assert data_size(ros_msg.standard_message("std_msgs/String")) is None
    assert ros_msg.standard_message("nope/Nope") is None


# --------------------------------------------------------------------------- model


def test_fields_to_model_and_back():
    spec = parse_msg("int32 A=1\nfloat64[3] v\nint32[<=5] w\nstring<=4 s\nuint8 k 7", package="p")
    objs = ros_msg.fields_to_model(spec.fields)
    assert [o.eClass.name for o in objs] == ["Field"] * 5
    assert objs[1].isArray and objs[1].arrayLength == 3
    assert objs[2].upperBound == 5 and objs[3].stringBound == 4 and objs[4].defaultValue == "7"
    back = [ros_msg.field_from_model(o) for o in objs]
    assert back == list(spec.fields)


def test_message_data_size_on_a_project():
    project = model.new("rosmod.Project", name="p")
    project.software = model.new("rosmod.Software", name="sw")
    pkg = model.new("rosmod.Package", name="nav")
    project.software.packages.append(pkg)
    for name, text in (
        ("Vec", "float64 x\nfloat64 y"),
        ("Seg", "Vec a\nVec b\nint8 k"),
        ("Named", "string n"),
    ):
        msg = model.new("rosmod.Message", name=name, definition=text)
        msg.fields.extend(ros_msg.fields_to_model(parse_msg(text, package="nav").fields))
        pkg.messages.append(msg)
    sizes = {m.name: ros_msg.message_data_size(m, project) for m in pkg.messages}
    assert sizes == {"Vec": 16, "Seg": 33, "Named": None}


# --------------------------------------------------------------------------- properties

_PRIMS = sorted(ros_msg.PRIMITIVE_SIZES)


@st.composite
def _fixed_fields(draw):
    count = draw(st.integers(min_value=0, max_value=12))
    fields = []
    for index in range(count):
        type_ = draw(st.sampled_from(_PRIMS))
        length = draw(st.one_of(st.none(), st.integers(min_value=0, max_value=16)))
        fields.append((f"f{index}", type_, length))
    return fields


@given(_fixed_fields())
@settings(max_examples=150, deadline=None)
def test_generated_fixed_messages_round_trip(fields):
    text = "".join(f"{t}{'' if n is None else f'[{n}]'} {name}  # c\n" for name, t, n in fields)
    spec = parse_msg(text, package="gen")
    assert [(f.name, f.type, f.array_length) for f in spec.fields] == fields
    expected = sum(ros_msg.PRIMITIVE_SIZES[t] * (1 if n is None else n) for _, t, n in fields)
    assert data_size(spec) == expected


@given(st.text(max_size=200))
@settings(max_examples=200, deadline=None)
def test_arbitrary_text_never_crashes(text):
    try:
        spec = parse_msg(text, filename="fuzz.msg")
    except ros_msg.RosMessageError as exc:
        assert all(e.location.file == "fuzz.msg" and e.location.line for e in exc.errors)
    else:
        data_size(spec)


# --------------------------------------------------------------------------- corpus


def _corpus_rosmod() -> Path:
    env = os.environ.get("ROSAADL_CORPUS")
    return (Path(env) if env else Path(__file__).resolve().parents[3] / "shared" / "corpus") / "rosmod"


def _corpus_interfaces():
    root = _corpus_rosmod()
    if not root.is_dir():
        return []
    return sorted(p for p in root.rglob("*") if p.suffix in (".msg", ".srv"))


@pytest.mark.corpus
@pytest.mark.parametrize("path", _corpus_interfaces(), ids=lambda p: "/".join(Path(p).parts[-4:]))
def test_corpus_definitions_parse(corpus, path):
    text = path.read_text()
    package, name = path.name.split(".")[:2]
    if path.suffix == ".msg":
        spec = parse_msg(text, name=name, package=package, filename=str(path))
        assert spec.fields, "every corpus message has at least one field"
        size = data_size(spec)
        assert size is None or size > 0
    else:
        parse_srv(text, name=name, package=package, filename=str(path))

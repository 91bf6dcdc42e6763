"""The AADL text reader on text it must refuse or warn about: the legality rules that the
grammar leaves to the builder (located errors, all of a text together), names declared twice,
AADL v1 syntax, and bad input (syntax errors, bytes that are not UTF-8, garbage, deep nesting)."""

from __future__ import annotations

import random
import time

import pytest

from rosaadl.errors import AadlSyntaxError, RosaadlError, ValidationError
from rosaadl.importers import aadl_text
from rosaadl.importers.aadl_text import read_string

# --------------------------------------------------------------------------- legality rules


def _pkg(body: str) -> str:
    return f"package P\npublic\n{body}\nend P;\n"


LEGALITY = [
    (
        "thread T end T;\nthread implementation T.i subcomponents\n b: bus; end T.i;",
        "a thread implementation cannot contain bus subcomponents (b)",
        5,
        2,
    ),
    (
        "process T end T;\nprocess implementation T.i subcomponents\n x: process; end T.i;",
        "a process implementation cannot contain process subcomponents (x)",
        5,
        2,
    ),
    (
        "system T end T;\nsystem implementation T.i subcomponents\n t: thread; end T.i;",
        "a system implementation cannot contain thread subcomponents (t)",
        5,
        2,
    ),
    (
        "process T features\n b: requires bus access; end T;",
        "a process cannot have bus access features (b)",
        4,
        2,
    ),
    ("data D features\n p: in data port; end D;", "a data cannot have data port features (p)", 4, 2),
    ("thread T features\n p: in parameter; end T;", "a thread cannot have parameter features (p)", 4, 2),
    (
        "bus B features\n s: provides subprogram access; end B;",
        "a bus cannot have subprogram access features",
        4,
        2,
    ),
    (
        "process T end T;\nprocess implementation T.i calls\n s: { c: subprogram X; }; end T.i;",
        "a process implementation cannot have subprogram calls",
        5,
        2,
    ),
    (
        "system T end T;\nsystem implementation T.i connections\n c: parameter a -> b; end T.i;",
        "a system implementation cannot have parameter connections (c)",
        5,
        2,
    ),
    (
        "bus T end T;\nbus implementation T.i connections\n c: port a -> b; end T.i;",
        "a bus implementation cannot have port connections (c)",
        5,
        2,
    ),
    ("memory M flows\n f: flow source p; end M;", "a memory type cannot have flow specifications", 4, 2),
    (
        "process T end T;\nthread implementation T.i end T.i;",
        "thread implementation T.i implements process type T",
        4,
        23,
    ),
    ("system S end T;", "system type S ends with 'end T': expected 'end S'", 3, 14),
    ("system S end S;\nsystem implementation S.i end S.j;", "ends with 'end S.j'", 4, 31),
    ("system S end S;\nend Q;", None, None, None),
]


@pytest.mark.parametrize(("body", "message", "line", "column"), LEGALITY[:-1])
def test_legality_rules_are_located_errors(body: str, message: str, line: int, column: int) -> None:
    with pytest.raises(ValidationError) as info:
        read_string(_pkg(body), "legal.aadl")
    error = info.value
    assert message in error.message
    assert (error.location.file, error.location.line, error.location.column) == ("legal.aadl", line, column)


def test_allowed_containment_is_accepted() -> None:
    body = """
thread T features p: in event data port; d: requires data access; s: requires subprogram access;
  end T;
thread implementation T.i subcomponents d: data; s: subprogram; g: subprogram group; a: abstract;
  calls seq: { c: subprogram s; }; connections c: port p -> d.x; k: parameter p -> s.q; end T.i;
processor C features b: requires bus access; v: requires virtual bus access; end C;
processor implementation C.i subcomponents m: memory; vp: virtual processor; vb: virtual bus; end C.i;
system S end S;
system implementation S.i subcomponents c: processor C.i; p: process; d: device; m: memory; b: bus;
  s: system; a: abstract; end S.i;
abstract A end A;
abstract implementation A.i subcomponents t: thread T.i; tg: thread group; end A.i;
"""
    m = read_string(_pkg(body), "ok.aadl")
    assert len(m.units[0].classifiers) == 8
    assert (
        set(aadl_text.SUBCOMPONENTS_ALLOWED)
        == set(aadl_text.FEATURES_ALLOWED)
        == set(aadl_text.CONNECTIONS_ALLOWED)
    )
    assert len(aadl_text.SUBCOMPONENTS_ALLOWED) == 14


def test_the_tables_speak_the_metamodel() -> None:
    """The rules name feature kinds as the metamodel's literals do, and every category."""
    from rosaadl.importers.aadl_text.factory import literals
    from rosaadl.importers.aadl_text.tree import CATEGORIES, FEATURE_NODES

    made = literals()
    assert {node: made.feature_categories[node].name for node in FEATURE_NODES} == {
        node: name for node, (name, _) in FEATURE_NODES.items()
    }
    kinds = {name for name, _ in FEATURE_NODES.values()}
    assert set().union(*aadl_text.FEATURES_ALLOWED.values()) == kinds
    assert set(aadl_text.SUBCOMPONENTS_ALLOWED) == CATEGORIES == set(made.categories)


def test_all_legality_errors_of_a_text_are_reported_together() -> None:
    body = (
        "thread T features p: in parameter; end T;\n"
        "thread implementation T.i subcomponents b: bus; x: memory; end T.i;"
    )
    with pytest.raises(ValidationError) as info:
        read_string(_pkg(body), "many.aadl")
    assert len(info.value.errors) == 3
    assert "3 errors" in info.value.message and "many.aadl:4:" in info.value.message


def test_property_set_rules() -> None:
    with pytest.raises(AadlSyntaxError, match="must be written out"):
        read_string("property set Q is T: type aadlinteger; U: type T; end Q;", "q.aadl")
    with pytest.raises(AadlSyntaxError, match="needs a number type"):
        read_string("property set Q is R: type range of aadlboolean; end Q;", "q.aadl")
    with pytest.raises(ValidationError, match="not a unit declared before it"):
        read_string("property set Q is U: type units (a, b => c * 2); end Q;", "q.aadl")
    with pytest.raises(ValidationError, match="property set Q ends with 'end R'"):
        read_string("property set Q is end R;", "q.aadl")


def test_errors_of_parts_built_while_parsing_keep_the_order_of_a_whole_tree() -> None:
    """Classifiers are built as soon as they are parsed: a package's own errors still come
    before those of its members, the category rule still spans the package, a syntax error
    anywhere still wins over a literal out of range before it, and a private classifier is
    private."""
    text = (
        "package P\npublic\n  thread T end T;\n  process implementation T.i subcomponents b: bus; end T.i;\n"
        "end Q;\npackage R\npublic\n  system S end S;\nprivate\n  system X end Y;\nend R;\n"
    )
    with pytest.raises(ValidationError) as info:
        read_string(text, "order.aadl")
    assert [(e.location.line, e.message.split(":")[0]) for e in info.value.errors] == [
        (5, "package P ends with 'end Q'"),
        (4, "a process implementation cannot contain bus subcomponents (b); it can contain"),
        (4, "process implementation T.i implements thread type T"),
        (10, "system type X ends with 'end Y'"),
    ]
    model = read_string("package R\npublic\n  system S end S;\nprivate\n  system X end X;\nend R;\n")
    assert [(c.name, c.visibility.name) for c in model.units[0].classifiers] == [
        ("S", "public"),
        ("X", "private"),
    ]
    late = (
        "package P\npublic\n  data D properties Data_Size => 1e999 Bytes; end D;\n  system S end;\nend P;\n"
    )
    with pytest.raises(AadlSyntaxError, match="unexpected ';'") as syntax:
        read_string(late, "late.aadl")
    assert (syntax.value.location.line, syntax.value.location.column) == (4, 15)
    with pytest.raises(AadlSyntaxError, match="does not fit in 64 bits") as literal:
        read_string(late.replace("end;", "end S;"), "late.aadl")
    assert literal.value.location.line == 3


def test_names_declared_twice_are_warnings() -> None:
    text = _pkg("system S features a: in data port; a: out data port; end S;\nsystem S end S;")
    warnings: list = []
    m = read_string(text, "dup.aadl", warnings=warnings)
    assert len(m.units[0].classifiers) == 2  # both kept: the writer gives the text back
    found = sorted((w.location.line, w.message.split(" is declared")[0]) for w in warnings)
    assert found == [(3, "feature a"), (4, "classifier S")]


def test_aadl_v1_port_connections_are_read_with_a_warning() -> None:
    body = "system S end S;\nsystem implementation S.i connections c: data port a -> b; end S.i;"
    warnings: list = []
    m = read_string(_pkg(body), "v1.aadl", warnings=warnings)
    (conn,) = m.units[0].classifiers[1].connections
    assert conn.eIsSet("kind") and conn.kind.name == "portConnection"
    assert ["AADL v1 syntax" in w.message for w in warnings] == [True]


# --------------------------------------------------------------------------- bad input


def test_unclosed_component() -> None:
    with pytest.raises(AadlSyntaxError) as info:
        read_string("package P public\n  system S\n    features a: in data port;\nend P;\n", "open.aadl")
    assert (info.value.location.file, info.value.location.line) == ("open.aadl", 5)  # the end of the text


def test_unknown_category() -> None:
    with pytest.raises(AadlSyntaxError) as info:
        read_string("package P public\n  sistem S end S;\nend P;\n", "cat.aadl")
    assert (info.value.location.line, info.value.location.column) == (2, 10)


def test_non_utf8_bytes() -> None:
    with pytest.raises(AadlSyntaxError) as info:
        read_string(b"package P public\n system S end S; -- \xe9t\xe9\nend P;\n", "latin1.aadl")
    assert "UTF-8" in info.value.message
    assert (info.value.location.file, info.value.location.line) == ("latin1.aadl", 2)


@pytest.mark.parametrize("kind", ["bytes", "text"])
def test_five_megabytes_of_garbage(kind: str) -> None:
    rng = random.Random(7)
    if kind == "bytes":
        data: bytes | str = bytes(rng.getrandbits(8) for _ in range(5 * 1024 * 1024))
    else:
        data = "".join(rng.choice('ab1 {}();:=>-.\n"') for _ in range(5 * 1024 * 1024))
    start = time.process_time()
    with pytest.raises(RosaadlError) as info:
        read_string(data, "garbage.aadl")
    assert time.process_time() - start < 20
    assert isinstance(info.value, AadlSyntaxError)
    assert info.value.location.file == "garbage.aadl" and info.value.location.line >= 1


def test_deep_nesting_is_a_located_error_not_a_crash() -> None:
    text = "property set Q is T: type " + "list of " * 20_000 + "aadlboolean; end Q;"
    with pytest.raises(AadlSyntaxError, match="nested more than"):
        read_string(text, "deep.aadl")
    text = "package P public system S properties X::Y => " + "not " * 50_000 + "true; end S; end P;"
    with pytest.raises(AadlSyntaxError, match="nested more than") as info:
        read_string(text, "deep.aadl")
    assert info.value.location.line == 1

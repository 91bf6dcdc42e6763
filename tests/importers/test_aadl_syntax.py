"""The AADL v2 concrete syntax: grammar coverage and tree shapes, construct by construct.

lark's own parser as the reference and the real corpus are in ``test_aadl_syntax_corpus.py``, bad
input in ``test_aadl_syntax_errors.py``."""

from __future__ import annotations

from pathlib import Path

import pytest
from aadl_syntax_helpers import ROOT, aadl_syntax, find, in_impl, in_type, only, parse, value_of, words
from lark import Tree

CATEGORIES = [
    "abstract",
    "bus",
    "data",
    "device",
    "memory",
    "process",
    "processor",
    "subprogram",
    "subprogram group",
    "system",
    "thread",
    "thread group",
    "virtual bus",
    "virtual processor",
]


# --------------------------------------------------------------------------- module surface


def test_public_api() -> None:
    assert aadl_syntax.__all__ == ["parse", "decode", "AADL_GRAMMAR"]
    assert (ROOT / "importers" / "aadl.lark").read_text(encoding="utf-8") == aadl_syntax.AADL_GRAMMAR
    lark = aadl_syntax._reader().lark
    assert lark.options.parser == "lalr"


def test_cache_file_is_under_the_cache_directory(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("ROSAADL_CACHE_DIR", str(tmp_path / "c"))
    assert Path(aadl_syntax._cache_file()).parent == tmp_path / "c"
    monkeypatch.setenv("ROSAADL_CACHE_DIR", "")
    assert aadl_syntax._cache_file() is False
    monkeypatch.delenv("ROSAADL_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert Path(aadl_syntax._cache_file()).parent == tmp_path / "xdg" / "rosaadl"
    assert not str(aadl_syntax._cache_file()).startswith(str(ROOT))


# --------------------------------------------------------------------------- lexical


def test_keywords_are_case_insensitive_and_comments_ignored() -> None:
    tree = parse("PACKAGE P PUBLIC -- comment\n SyStEm S -- another\n END S; End P;")
    node = only(tree, "component_type")
    assert words(node.children[0]) == ["SyStEm"]
    assert node.children[1] == "S"


def test_identifiers_and_qualified_end_names() -> None:
    tree = parse(
        "package A::B_2::c3 public\n system s_1 end s_1;\n"
        " system implementation s_1.i_2 end s_1.i_2;\nend A::B_2::c3;"
    )
    package = only(tree, "package")
    assert words(package.children[0]) == ["A", "B_2", "c3"]
    assert words(package.children[-1]) == ["A", "B_2", "c3"]
    impl = only(tree, "component_implementation")
    assert words(impl.children[1]) == ["s_1", "i_2"]
    assert words(impl.children[-1]) == ["s_1", "i_2"]


def test_bytes_with_bom_and_crlf() -> None:
    data = "\ufeffpackage P\r\npublic\r\n  system S\r\n  end S;\r\nend P;\r\n".encode()
    tree = parse(data, "x.aadl")
    node = only(tree, "component_type")
    assert (node.meta.line, node.meta.column) == (3, 3)


def test_positions_of_nodes_and_tokens() -> None:
    tree = parse("package P public\n  thread T\n    features\n      p: in data port;\n  end T;\nend P;\n")
    port = only(tree, "data_port")
    assert (port.meta.line, port.meta.column) == (4, 7)
    assert port.children[0].line == 4 and port.children[0].end_column == 8
    assert (only(tree, "direction").meta.line, only(tree, "direction").meta.column) == (4, 10)
    package = only(tree, "package")
    assert (package.meta.line, package.meta.end_line) == (1, 6)
    flag = only(in_type("features\n  p: refined to in data port;"), "refined")
    assert flag.meta.empty  # keywords are not in the tree, so a flag node has no position


def test_reserved_word_used_as_a_name_where_no_keyword_fits() -> None:
    tree = in_type("features\n  data: out event data port;\n  source: in data port;", "process")
    names = [node.children[0] for node in find(tree, "event_data_port") + find(tree, "data_port")]
    assert names == ["data", "source"]


# --------------------------------------------------------------------------- packages


def test_package_sections_with_and_renames() -> None:
    tree = parse(
        """package P
        public
          with Base_Types, A::B;
          L renames package A::B;
          renames A::B::all;
          renames package A::B::all;
          F renames feature group A::B::FG;
          renames feature group A::B::FG2;
          C renames processor A::B::Cpu;
          renames thread group A::B::TG;
          system S end S;
        private
          with Other;
          data D end D;
          annex EMV2 {** error types end types; **};
        properties
          Period => 5 ms;
        end P;"""
    )
    package = only(tree, "package")
    public, private, props = package.children[1:4]
    assert (
        public.data == "public_section" and private.data == "private_section" and props.data == "properties"
    )
    assert [words(q) for q in find(public, "with_clause")[0].children] == [["Base_Types"], ["A", "B"]]
    rename = only(tree, "package_rename")
    assert rename.children[0] == "L" and words(rename.children[1]) == ["A", "B"]
    assert [words(n) for n in find(tree, "package_rename_all")] == [["A", "B"], ["A", "B"]]
    fg_renames = find(tree, "feature_group_type_rename")
    assert [n.children[0] for n in fg_renames] == ["F", None]
    assert words(fg_renames[0].children[1]) == ["A", "B", "FG", "None"]
    ct = find(tree, "component_type_rename")
    assert [n.children[0] for n in ct] == ["C", None]
    assert words(ct[1].children[1]) == ["thread", "group"]
    assert only(tree, "annex_library").children[1].value[3:-3] == " error types end types; "


def test_several_model_units_in_one_file() -> None:
    tree = parse("package A public end A; property set B is end B; package C public end C;")
    assert [child.data for child in tree.children] == ["package", "property_set", "package"]


# --------------------------------------------------------------------------- classifiers


@pytest.mark.parametrize("category", CATEGORIES)
def test_component_type_and_implementation_of_every_category(category: str) -> None:
    tree = parse(
        f"package P public\n"
        f"{category} T extends Q::Base end T;\n"
        f"{category} implementation T.impl extends T.base end T.impl;\n"
        f"end P;"
    )
    ctype = only(tree, "component_type")
    assert words(ctype.children[0]) == category.split()
    assert ctype.children[1] == "T" and ctype.children[-1] == "T"
    assert words(ctype.children[2].children[0]) == ["Q", "Base", "None"]
    impl = only(tree, "component_implementation")
    assert words(impl.children[0]) == category.split()
    assert words(impl.children[1]) == ["T", "impl"]
    assert words(only(impl, "extends").children[0]) == ["T", "base"]


def test_type_sections_in_order_and_none() -> None:
    tree = in_type(
        "prototypes none;\nfeatures none;\nflows none;\nrequires modes\n r: initial mode;\n"
        "modes none;\nproperties none;\nannex A {** x **};\nannex B none;"
    )
    ctype = only(tree, "component_type")
    sections = [c.data for c in ctype.children[4:-1]]
    assert sections == [
        "prototypes",
        "features",
        "flow_specs",
        "requires_modes",
        "modes",
        "properties",
        "annex_subclause",
        "annex_subclause",
    ]
    assert [len(ctype.children[i].children) for i in (4, 5, 6, 8, 9)] == [0, 0, 0, 0, 0]
    annexes = find(tree, "annex_subclause")
    assert annexes[0].children[1].type == "ANNEX_TEXT" and annexes[1].children[1].data == "annex_none"


def test_implementation_sections_in_order() -> None:
    tree = in_impl(
        "prototypes p: data;\nsubcomponents none;\ncalls none;\nconnections none;\nflows none;\n"
        "modes none;\nproperties none;\nannex A {** x **} in modes (m);"
    )
    impl = only(tree, "component_implementation")
    assert [c.data for c in impl.children[4:-1]] == [
        "prototypes",
        "subcomponents",
        "calls",
        "connections",
        "flow_impls",
        "modes",
        "properties",
        "annex_subclause",
    ]
    assert words(only(tree, "annex_subclause").children[2].children[0]) == ["m", "None"]


def test_extends_with_prototype_bindings_and_prototypes() -> None:
    tree = parse(
        """package P public
        system S extends Q::Base (d => data Base_Types::Integer, fg => feature group Q::FGT,
                                  po => in data port Q::D, ac => requires data access Q::D,
                                  fp => out feature, cs => (system A, system B (x => bus C)))
          prototypes
            d: data;
            r: refined to data Q::D;
            fg: feature group Q::FGT;
            fp: in feature;
            arr: thread Q::T [];
            withprops: system {Period => 1 ms;};
        end S;
        system implementation S.i (d => data Q::D) end S.i;
        end P;"""
    )
    bindings = only(tree, "component_type").children[3]
    actuals = [b.children[1].data for b in bindings.children]
    assert actuals == [
        "component_prototype_actual",
        "feature_group_prototype_actual",
        "port_prototype_actual",
        "access_prototype_actual",
        "feature_prototype_actual",
        "component_prototype_actuals",
    ]
    assert words(only(tree, "port_prototype_actual").children[1]) == ["data", "port"]
    protos = only(tree, "prototypes").children
    assert [p.data for p in protos] == [
        "component_prototype",
        "component_prototype",
        "feature_group_prototype",
        "feature_prototype",
        "component_prototype",
        "component_prototype",
    ]
    assert protos[1].children[1].data == "refined"
    assert protos[4].children[4].data == "array_dimension"
    impl = only(tree, "component_implementation")
    assert impl.children[2] is None and impl.children[3].data == "prototype_bindings"


FEATURES = [
    # text, node, direction or access kind, classifier words
    ("p: in data port Base_Types::Integer;", "data_port", ["in"], ["Base_Types", "Integer", "None"]),
    ("p: out event port;", "event_port", ["out"], None),
    ("p: in out event data port D.impl [3];", "event_data_port", ["in", "out"], ["D", "impl"]),
    ("p: in parameter D;", "parameter", ["in"], ["D", "None"]),
    ("p: feature group inverse of Q::FGT;", "feature_group", None, ["Q", "FGT", "None"]),
    ("p: out feature group FGT;", "feature_group", ["out"], ["FGT", "None"]),
    ("p: feature;", "abstract_feature", None, None),
    ("p: in feature prototype fp;", "abstract_feature", ["in"], ["fp"]),
    ("p: requires data access D;", "data_access", ["requires"], ["D", "None"]),
    ("p: provides bus access B.impl;", "bus_access", ["provides"], ["B", "impl"]),
    ("p: requires virtual bus access VB;", "virtual_bus_access", ["requires"], ["VB", "None"]),
    ("p: provides subprogram access S;", "subprogram_access", ["provides"], ["S", "None"]),
    (
        "p: requires subprogram group access SG {X => 1;};",
        "subprogram_group_access",
        ["requires"],
        ["SG", "None"],
    ),
    ("p: refined to out data port D;", "data_port", ["out"], ["D", "None"]),
]


@pytest.mark.parametrize(("text", "node", "direction", "classifier"), FEATURES)
def test_features_of_every_kind(
    text: str, node: str, direction: list[str] | None, classifier: list[str] | None
) -> None:
    feature = only(in_type(f"features\n  {text}"), node)
    assert feature.children[0] == "p"
    assert (feature.children[1] is not None) == ("refined" in text)
    assert words(feature.children[2]) == direction
    if node == "feature_group":
        assert (feature.children[3] is not None) == ("inverse" in text)
    found, array, block = feature.children[-3:]
    assert words(found) == classifier
    if "prototype" in text:
        assert found.data == "prototype_ref"
    assert words(array) == (["3"] if "[3]" in text else None)
    assert (block is not None) == ("{" in text)


def test_feature_group_type_with_inverse() -> None:
    tree = parse(
        "package P public\n feature group F extends Q::G\n features\n  a: in data port;\n"
        " inverse of Q::H\n properties none;\n end F;\n"
        " feature group F2 inverse of F end F2;\nend P;"
    )
    fgts = find(tree, "feature_group_type")
    assert [f.children[0] for f in fgts] == ["F", "F2"]
    assert [c.data for c in fgts[0].children[3:-1]] == ["features", "inverse_of", "properties"]
    assert words(fgts[1].children[3].children[0]) == ["F", "None"]


def test_subcomponents() -> None:
    tree = in_impl(
        "subcomponents\n"
        "  a: thread T.impl;\n"
        "  b: process P.impl [3][] (P.x, P.y) {Priority => 1;} in modes (m1, m2 => m3);\n"
        "  c: refined to system Q::S.i (p => data D);\n"
        "  d: memory;\n"
        "  e: processor [Max_Cpus];\n"
    )
    subs = find(tree, "subcomponent")
    assert [s.children[0] for s in subs] == ["a", "b", "c", "d", "e"]
    b = subs[1]
    dims = b.children[5]
    assert [words(d) for d in dims.children] == [["3"], ["None"]]
    assert [words(r.children[0]) for r in b.children[6].children] == [["P", "x"], ["P", "y"]]
    assert b.children[7].data == "property_block"
    assert [words(m) for m in b.children[8].children] == [["m1", "None"], ["m2", "m3"]]
    assert subs[2].children[1].data == "refined" and subs[2].children[4].data == "prototype_bindings"
    assert subs[3].children[3:] == [None] * 6
    assert words(only(subs[4], "array_dimension").children[0]) == ["Max_Cpus"]


def test_calls() -> None:
    tree = in_impl(
        "calls\n  seq: { c1: subprogram S.impl; c2: subprogram sub.spg {X => 1;};"
        " c3: subprogram processor.spg; } in modes (m);",
        "thread",
    )
    seq = only(tree, "call_sequence")
    calls = seq.children[1:-2]
    assert [c.children[0] for c in calls] == ["c1", "c2", "c3"]
    assert words(calls[1].children[1]) == ["sub", "spg"]
    assert calls[2].children[1].data == "processor_subprogram"
    assert seq.children[-1].data == "in_modes"


CONNECTIONS = [
    ("c: port a.b -> c.d;", "port_connection", ["port"]),
    ("port a -> b;", "port_connection", ["port"]),
    ("c: data port a -> b;", "port_connection", ["data", "port"]),
    ("c: event port a -> b;", "port_connection", ["event", "port"]),
    ("c: event data port a <-> b;", "port_connection", ["event", "data", "port"]),
    ("c: feature group a <-> b.c;", "feature_group_connection", None),
    ("c: feature a -> b;", "feature_connection", None),
    ("c: parameter a.r -> b;", "parameter_connection", None),
    ("c: bus access b -> cpu.ba;", "access_connection", ["bus"]),
    ("c: data access a -> b;", "access_connection", ["data"]),
    ("c: subprogram access a -> b;", "access_connection", ["subprogram"]),
    ("c: subprogram group access a -> b;", "access_connection", ["subprogram", "group"]),
    ("c: port a[1].p -> b[2].q {Latency => 1 ms .. 2 ms;} in modes (m1, m2);", "port_connection", ["port"]),
    ("c: refined to port {Latency => 1 ms .. 2 ms;};", "port_connection", ["port"]),
    ("c: port processor.clk -> self.tick;", "port_connection", ["port"]),
]


@pytest.mark.parametrize(("text", "node", "kind"), CONNECTIONS)
def test_connections(text: str, node: str, kind: list[str] | None) -> None:
    conn = only(in_impl(f"connections\n  {text}"), node)
    name = None if text.startswith(("port", "data", "event")) else "c"
    assert conn.children[0] == name
    has_kind = node in ("port_connection", "access_connection")
    if has_kind:
        assert words(conn.children[2]) == kind
    source, direction, destination = conn.children[3:6] if has_kind else conn.children[2:5]
    if "refined" in text:
        assert conn.children[1].data == "refined" and source is direction is destination is None
    else:
        assert words(direction) == ["<->" if "<->" in text else "->"]
        assert source is not None and destination is not None
    if "processor." in text:
        assert source.data == "processor_port" and destination.data == "internal_event"
    if "[1]" in text:
        assert source.children[0].data == "indexed_element"


def test_flows_in_types_and_implementations() -> None:
    tree = parse(
        """package P public
        system S
          features i: in data port; o: out data port;
          flows
            src: flow source o {Latency => 1 ms .. 2 ms;};
            snk: flow sink i in modes (m);
            pth: flow path i -> o;
            ref: refined to flow path {Latency => 1 ms .. 3 ms;};
        end S;
        system implementation S.i
          flows
            src: flow source t.f -> c1 -> o;
            snk: flow sink i -> c2 -> t.g;
            pth: flow path i -> c1 -> t.p -> c2 -> o;
            e2e: end to end flow t.f -> c1 -> u.g {Latency => 0 ms .. 9 ms;} in modes (m);
            e2r: refined to end to end flow {Latency => 0 ms .. 8 ms;};
        end S.i;
        end P;"""
    )
    specs = only(tree, "flow_specs").children
    assert [s.data for s in specs] == [
        "flow_source_spec",
        "flow_sink_spec",
        "flow_path_spec",
        "flow_path_spec",
    ]
    assert words(specs[2].children[2]) == ["i"] and words(specs[2].children[3]) == ["o"]
    assert specs[3].children[1].data == "refined" and specs[3].children[2] is None
    impls = only(tree, "flow_impls").children
    assert [i.data for i in impls] == [
        "flow_source_impl",
        "flow_sink_impl",
        "flow_path_impl",
        "end_to_end_flow",
        "end_to_end_flow",
    ]
    segments = impls[2].children[1]
    assert [words(p) for p in segments.children] == [["i"], ["c1"], ["t", "p"], ["c2"], ["o"]]
    assert impls[3].children[-1].data == "in_modes" and impls[4].children[1].data == "refined"


def test_modes_and_transitions() -> None:
    tree = in_impl(
        "modes\n  m1: initial mode;\n  m2: mode {Period => 5 ms;};\n  m1 -[ e ]-> m2;\n"
        "  t: m2 -[ e, sub.p, self.tick, processor.clk ]-> m1 {X => 1;};"
    )
    modes = only(tree, "modes").children
    assert [m.data for m in modes] == ["mode", "mode", "mode_transition", "mode_transition"]
    assert modes[0].children[1].data == "initial" and modes[1].children[1] is None
    unnamed, named = modes[2], modes[3]
    assert unnamed.children[:2] == [None, "m1"] and unnamed.children[3] == "m2"
    assert named.children[:2] == ["t", "m2"]
    assert [t.data for t in named.children[2].children] == [
        "path",
        "path",
        "internal_event",
        "processor_port",
    ]


# --------------------------------------------------------------------------- property associations


def test_property_association_forms() -> None:
    tree = in_type(
        "properties\n"
        "  Period => 10 ms;\n"
        "  TP::Deadline +=> constant 5 ms applies to a.b, c[1].d[2 .. 3];\n"
        "  Period => 10 ms in modes (m1), 20 ms in modes (m2);\n"
        "  Period => (10 ms in modes (m1), 20 ms);\n"
        "  X => 5 in binding (Q::Cpu.impl, Q::Cpu2);\n"
        "  Y => 1 applies to t.annex {** EMV2 **};\n"
    )
    pas = find(tree, "property_association")
    first, second, modal, modal2, bound, annexed = pas
    assert words(first.children[0]) == ["Period"] and first.children[1:3] == [None, None]
    assert words(second.children[0]) == ["TP", "Deadline"]
    assert second.children[1].data == "append" and second.children[2].data == "constant"
    paths = second.children[4].children
    assert words(paths[0]) == ["a", "b"]
    assert paths[1].children[0].data == "indexed_element"
    assert words(paths[1].children[1].children[1]) == ["2", "3"]
    for pa in (modal, modal2):
        assert pa.children[3].data == "modal_property_value"
        assert [mv.data for mv in pa.children[3].children] == ["modal_value", "modal_value"]
    assert modal2.children[3].children[1].children[1] is None
    assert [words(c) for c in bound.children[5].children] == [["Q", "Cpu", "impl"], ["Q", "Cpu2", "None"]]
    assert annexed.children[4].children[0].children[1].data == "annex_element"


VALUES = [
    ("10", "integer_value", [None, "10", None]),
    ("-10 ms", "integer_value", ["sign", "10", "ms"]),
    ("+5", "integer_value", ["sign", "5", None]),
    ("16#FF#", "integer_value", [None, "16#FF#", None]),
    ("2#1#e32 Bytes", "integer_value", [None, "2#1#e32", "Bytes"]),
    ("1_000", "integer_value", [None, "1_000", None]),
    ("1.5", "real_value", [None, "1.5", None]),
    ("-1.5e-3 ms", "real_value", ["sign", "1.5e-3", "ms"]),
    ("10ms", "integer_value", [None, "10", "ms"]),
    ("true", "boolean_value", ["true"]),
    ("FALSE", "boolean_value", ["FALSE"]),
    ('"hello ""world"""', "string_value", ['"hello ""world"""']),
    ("Periodic", "named_value", ["Periodic"]),
    ("Some_Set::Max", "named_value", ["Some_Set", "Max"]),
    ("- Some_Set::Max", "signed_constant", None),
    ("reference (a.b[2].c)", "reference_value", None),
    ("classifier (Q::T.impl)", "classifier_value", None),
    ("compute (my_fn)", "computed_value", ["my_fn"]),
    ("(1, (2, 3), ())", "list_value", None),
    ("()", "list_value", []),
    ("[a => 1; b => [c => 2;];]", "record_value", None),
    ("1 ms .. 5 ms", "range_value", None),
    ("1 ms .. 5 ms delta 1 ms", "range_value", None),
    ("-Max .. Max", "range_value", None),
    ("not true", "not_value", None),
    ("a and b and c", "and_value", None),
    ("a or b and not c", "or_value", None),
    ("(a or b) and c", "and_value", None),
]


@pytest.mark.parametrize(("text", "node", "children"), VALUES)
def test_property_values(text: str, node: str, children: list | None) -> None:
    value = value_of(text)
    assert isinstance(value, Tree) and value.data == node, value
    if children is not None:
        shown = [c.data if isinstance(c, Tree) else c for c in value.children]
        assert shown == children


def test_value_details() -> None:
    assert len(value_of("1 ms .. 5 ms delta 1 ms").children) == 3
    assert value_of("1 ms .. 5 ms").children[2] is None
    assert [c.data for c in value_of("a or b and not c").children] == ["named_value", "and_value"]
    nested = value_of("(1, (2, 3), ())")
    assert [len(c.children) for c in nested.children[1:]] == [2, 0]
    record = value_of("[a => 1; b => [c => 2;];]")
    assert [f.children[0] for f in record.children] == ["a", "b"]
    assert record.children[1].children[1].data == "record_value"
    reference = value_of("reference (a.b[2].c)")
    assert reference.children[0].children[1].data == "indexed_element"
    assert words(value_of("classifier (Q::T.impl)").children[0]) == ["Q", "T", "impl"]


def test_property_set_declarations() -> None:
    tree = parse(
        """property set PS is
          with Other_Set;
          B: aadlboolean applies to (all);
          S: inherit aadlstring => "x" applies to (thread, thread group, event data port,
                                                    end to end flow, {emv2}**error type, Q::S.impl);
          I: aadlinteger 0 .. 10 units (bits, Bytes => bits * 8) applies to (memory);
          R: aadlreal -1.0 .. 1.0 units PS::Speed applies to (processor, virtual processor);
          Speed: type units (Hz, KHz => Hz * 1000, MHz => KHz * 1_000.0);
          Kind: type enumeration (Fast, Slow);
          Lat: type range of aadlreal units Time_Units;
          RR: range of Time applies to (connection, flow, mode, port, subprogram access, feature group);
          C: classifier (system, process) applies to (system);
          Ref: list of reference (processor, Q::Mem) applies to (thread);
          Rec: record (Low: aadlinteger; Names: list of aadlstring; K: PS::Kind;) applies to (all);
          L: list of list of aadlinteger => ((1, 2), (3)) applies to (system);
          Max: constant aadlinteger => 2#1#e32;
          T0: constant Time => 5 ms;
        end PS;"""
    )
    ps = only(tree, "property_set")
    assert ps.children[0] == "PS" and ps.children[-1] == "PS"
    kinds = [c.data for c in ps.children[1:-1]]
    assert (
        kinds
        == ["with_clause"]
        + ["property_definition"] * 4
        + ["property_type_declaration"] * 3
        + ["property_definition"] * 5
        + ["property_constant"] * 2
    )
    defs = {d.children[0]: d for d in find(ps, "property_definition")}
    assert defs["B"].children[4].data == "all_owners"
    assert defs["S"].children[1].data == "inherit" and defs["S"].children[3].data == "string_value"
    owners = defs["S"].children[4].children
    assert [o.data for o in owners] == ["metaclass_ref"] * 5 + ["classifier_ref"]
    assert [words(o)[1:] for o in owners[:5]] == [
        ["thread"],
        ["thread", "group"],
        ["event", "data", "port"],
        ["end", "to", "end", "flow"],
        ["error", "type"],
    ]
    assert owners[4].children[0].type == "ANNEX_PREFIX" and owners[0].children[0] is None
    integer = defs["I"].children[2]
    assert integer.data == "integer_type" and integer.children[0].data == "range_value"
    assert integer.children[1].data == "units_type"
    assert [c.data for c in integer.children[1].children[1:]] == ["unit_conversion"]
    assert defs["R"].children[2].children[1].data == "units_ref"
    decls = {d.children[0]: d.children[1] for d in find(ps, "property_type_declaration")}
    assert decls["Speed"].data == "units_type" and len(decls["Speed"].children) == 3
    assert decls["Kind"].children == ["Fast", "Slow"]
    assert decls["Lat"].data == "range_type" and decls["Lat"].children[0].data == "real_type"
    assert defs["RR"].children[2].data == "range_type"
    assert defs["C"].children[2].data == "classifier_type"
    ref = defs["Ref"].children[2]
    assert ref.data == "list_type" and ref.children[0].data == "reference_type"
    assert [c.data for c in ref.children[0].children] == ["metaclass_ref", "classifier_ref"]
    record = defs["Rec"].children[2]
    assert [f.children[0] for f in record.children] == ["Low", "Names", "K"]
    assert record.children[2].children[1].data == "qname"
    assert defs["L"].children[2].children[0].data == "list_type"
    consts = {c.children[0]: c for c in find(ps, "property_constant")}
    assert consts["Max"].children[1].data == "integer_type"
    assert words(consts["T0"].children[1]) == ["Time"]


# --------------------------------------------------------------------------- annexes


def test_annex_text_is_kept_verbatim() -> None:
    inner = ' use types E;\n  -- a comment with {* and * and } \r\n  "quoted **" ; end; '
    tree = in_type(f"annex EMV2 {{**{inner}**}};")
    token = only(tree, "annex_subclause").children[1]
    assert token.type == "ANNEX_TEXT" and token.value[3:-3] == inner

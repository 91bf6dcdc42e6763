"""The AADL v2 concrete syntax against references: every construct of the grammar, and every
AADL file of the real-world corpus, gives exactly the trees (and token positions) that lark's own
LALR front end builds from the same grammar; every corpus file parses."""

from __future__ import annotations

from pathlib import Path

import pytest
from aadl_syntax_helpers import aadl_syntax, find, parse
from lark import Token, Tree

from benchmarks.generators.corpus import aadl_files, corpus_dir

# Every construct of the grammar at least once (hand-written; also compared with lark's own
# LALR front end, which must build exactly the same trees).
KITCHEN_SINK = '''\
-- a comment
PACKAGE Demo::Pkg
PUBLIC
  with Base_Types, Other::Lib;
  with Timing_Properties;
  Lib renames package Other::Lib;
  renames Other::Lib::all;
  renames package Other::Lib::all;
  FG renames feature group Other::Lib::FGT;
  renames feature group Other::Lib::FGT2;
  Cpu renames processor Other::Lib::CPU;

  system S extends Other::Lib::Base (p => data Base_Types::Integer,
                                    q => feature group Other::Lib::FGT)
    prototypes
      p: data;
      q: refined to data Base_Types::Float;
      r: feature group Other::Lib::FGT;
      t: in feature;
      arr: thread T [];
    features
      d_in: in data port Base_Types::Integer;
      d_out: out data port Base_Types::Integer [4] {Period => 5 ms;};
      e: in out event port;
      ed: in event data port Pkg::Msg.impl;
      prm: in parameter Base_Types::Integer;
      fg: feature group inverse of Other::Lib::FGT;
      fg2: out feature group FGT;
      af: feature;
      af2: in feature prototype t;
      da: requires data access Base_Types::Integer;
      ba: provides bus access Bus1;
      vba: requires virtual bus access VB;
      sa: requires subprogram access Sp;
      sga: provides subprogram group access SG;
      d_ref: refined to in data port Base_Types::Float;
    flows
      fsrc: flow source d_out {Latency => 1 ms .. 2 ms;};
      fsnk: flow sink d_in in modes (m1);
      fpth: flow path d_in -> d_out;
      fref: refined to flow path {Latency => 1 ms .. 3 ms;};
    requires modes
      rm: initial mode;
    modes
      m1: initial mode;
      m2: mode {Period => 5 ms;};
      m1 -[ e ]-> m2;
      t2: m2 -[ e, self.tick, processor.clk, sub.p ]-> m1;
    properties
      Period => 10 ms;
      Timing_Properties::Deadline +=> constant 5 ms applies to d_out;
      Compute_Execution_Time => 1 ms .. 5 ms delta 1 ms;
    annex EMV2 {** use types ErrorLibrary; -- {* not closed *}
       error propagations end propagations; **};
    annex Behavior_Specification none;
  end S;

  system implementation S.impl extends Other::Lib::Base.impl (p => data Base_Types::Float)
    prototypes
      pr: system;
    subcomponents
      t1: thread T.impl;
      t2: thread group TG.impl in modes (m1, m2 => m3);
      arr: process P.impl [3][] (P.a, P.b) {Priority => 3;};
      mem: memory;
      vp: virtual processor VP;
      vb: virtual bus VB.i;
      sg: subprogram group SG;
      sp: subprogram Sp;
      ab: abstract A (x => system S.impl);
      t1x: refined to thread T.impl2;
      dev: device D;
      b: bus B;
      cpu: processor CPU [Max_Cpus];
      dat: data Base_Types::Integer;
      sys: system S;
    calls
      seq1: { c1: subprogram Sp.impl;
              c2: subprogram sp.foo {Period => 1 ms;};
              c3: subprogram processor.spg; } in modes (m1);
    connections
      c1: port d_in -> t1.d_in;
      port t1.e <-> t2.e;
      c3: data port a.b -> c.d;
      c4: event port a -> b;
      c5: event data port a -> b;
      c6: feature group fg <-> t1.fg;
      c7: feature a.b -> c;
      c8: parameter c1.r -> d;
      c9: bus access b -> cpu.ba;
      c10: data access dat -> t1.da;
      c11: subprogram access sp -> t1.sa {Period => 3 ms;} in modes (m1);
      c12: subprogram group access sg -> t1.sga;
      c13: access a -> b;
      c14: refined to port {Latency => 1 ms .. 2 ms;};
      c15: port processor.clk -> self.tick;
      c16: port arr[1].x -> arr[2].y;
    flows
      fsrc: flow source t1.f -> c1 -> d_out;
      fpth: flow path d_in -> c1 -> t1.fp -> c2 -> d_out {Latency => 1 ms .. 3 ms;};
      fsnk: flow sink d_in;
      e2e: end to end flow t1.fsrc -> c1 -> t2.fsnk {Latency => 0 ms .. 20 ms;} in modes (m1);
      e2e2: refined to end to end flow {Latency => 0 ms .. 30 ms;};
    modes
      none;
    properties
      Actual_Processor_Binding => (reference (cpu)) applies to t1, arr[1..2].x;
      Source_Text => ("a.c", "say ""hi""");
      Some::Flag => not (true and false) or false;
      Some::Rec => [Field1 => 3; Field2 => "x"; Nested => [A => 1;];];
      Some::Cls => classifier (Demo::Pkg::S.impl);
      Some::Cmp => compute (my_function);
      Some::Based => 16#FF#;
      Some::Exp => 1.5e-3 ms;
      Some::Neg => -5 .. +5;
      Some::NegC => - Max_Value .. Max_Value;
      Some::Lst => ((1, 2), (3), ());
      Some::Enum => Periodic;
      Some::Const => Some::Max_Value;
      Period => 10 ms in modes (m1), 20 ms in modes (m2);
      Period => (10 ms in modes (m1), 20 ms);
      Some::Bind => 5 in binding (Other::Lib::CPU.impl);
      Some::Ann => 1 applies to t1.annex {** EMV2 **};
  end S.impl;

  feature group FGT extends Base::FGT0
    prototypes none;
    features
      a: in data port;
    inverse of Other::Lib::FGT
    properties
      none;
  end FGT;

  abstract A end A;
  bus B end B;
  data Dt end Dt;
  device D end D;
  memory M end M;
  process P end P;
  processor CPU end CPU;
  subprogram Sp features r: out parameter; end Sp;
  subprogram group SG end SG;
  thread T end T;
  thread group TG end TG;
  virtual bus VB end VB;
  virtual processor VP end VP;
  thread implementation T.impl calls none; end T.impl;
  annex EMV2 {** error types E: type; end types; **};
PRIVATE
  data Msg end Msg;
  data implementation Msg.impl end Msg.impl;
PROPERTIES
  Period => 1 ms;
END Demo::Pkg;

property set My_Props is
  with Other_Set;
  Flag: aadlboolean applies to (all);
  Name: inherit aadlstring => "x"
    applies to (thread, thread group, event data port, {emv2}**error type, Demo::Pkg::S);
  Count: aadlinteger 0 .. 100 units (bits, Bytes => bits * 8, KByte => Bytes * 1000)
    applies to (memory, bus);
  Speed: aadlreal 0.0 .. 10.0e3 units My_Props::Speed_Units applies to (processor);
  Speed_Units: type units (Hz, KHz => Hz * 1000);
  Mode_Kind: type enumeration (Fast, Slow);
  Lat: type range of aadlreal units Time_Units;
  Cls: classifier (system, process) applies to (virtual processor, end to end flow, connection,
                                                flow, mode, feature group, subprogram access, port);
  Ref: list of reference (processor, memory) applies to (thread);
  Rec: record (Low: aadlinteger; Names: list of aadlstring; Kind: My_Props::Mode_Kind;)
    applies to (all);
  Nested_List: list of list of aadlinteger => ((1, 2), (3)) applies to (system);
  Max_Value: constant aadlinteger => 2#1#e32;
  Default_Time: constant Time => 5 ms;
  Big: constant aadlreal => -1_000.5;
end My_Props;
'''


@pytest.fixture(scope="module")
def lark_front_end():
    """lark's own LALR parser and contextual lexer for the same grammar (the reference)."""
    from lark import Lark

    grammar = aadl_syntax.AADL_GRAMMAR
    return Lark(grammar, parser="lalr", lexer="contextual", start="specification", maybe_placeholders=True)


def token_positions(tree: Tree) -> list[tuple]:
    return [
        (t.type, str(t), t.line, t.column, t.end_line, t.end_column, t.start_pos, t.end_pos)
        for t in tree.scan_values(lambda v: isinstance(v, Token))
    ]


def test_kitchen_sink_matches_larks_own_parser(lark_front_end) -> None:
    ours, reference = parse(KITCHEN_SINK), lark_front_end.parse(KITCHEN_SINK)
    assert ours == reference
    assert token_positions(ours) == token_positions(reference)
    assert len(find(ours, "component_type")) == 15 and len(find(ours, "property_definition")) == 8


# --------------------------------------------------------------------------- real-world corpus


EXPECTED_CORPUS_FILES = 120
CORPUS = corpus_dir()
CORPUS_FILES = aadl_files(CORPUS)
NO_CORPUS = f"real-world corpus not found at {CORPUS} (set ROSAADL_CORPUS to its folder)"


@pytest.mark.corpus
@pytest.mark.parametrize(
    "path",
    [pytest.param(p, id=str(p.relative_to(CORPUS))) for p in CORPUS_FILES]
    or [pytest.param(None, marks=pytest.mark.skip(reason=NO_CORPUS))],
)
def test_corpus_file_parses(path: Path) -> None:
    tree = parse(path.read_bytes(), str(path))
    assert tree.data == "specification" and tree.children


@pytest.mark.corpus
def test_corpus_count(corpus: Path) -> None:
    parsed = 0
    for path in CORPUS_FILES:
        parse(path.read_bytes(), str(path))
        parsed += 1
    assert parsed == len(CORPUS_FILES) == EXPECTED_CORPUS_FILES, (
        f"parsed {parsed} of {len(CORPUS_FILES)} .aadl/.aadl2 files, expected {EXPECTED_CORPUS_FILES}"
    )
    covered = {"/".join(p.relative_to(corpus).parts[:2]) for p in CORPUS_FILES}
    for folder in ("osate/predeclared", "osate/aaxl2", "osate/busload"):
        assert folder in covered, folder
    assert any(f.startswith("aadl-ros/") for f in covered) and any(f.startswith("cheddar/") for f in covered)


@pytest.mark.corpus
def test_corpus_trees_match_larks_own_parser(corpus: Path, lark_front_end) -> None:
    for path in CORPUS_FILES:
        text = path.read_text(encoding="utf-8-sig")
        ours, reference = parse(text), lark_front_end.parse(text)
        assert ours == reference, path
        assert token_positions(ours) == token_positions(reference), path

"""The AADL text writer: every construct, golden texts of layout and sections."""

from __future__ import annotations

import pytest
from aadl_writer_models import (
    EXPECTED_NODES,
    N,
    everything_model,
    i,
    named,
    node_names,
    pa,
    package,
    write_unit,
    write_units,
)

from rosaadl.errors import ExportError
from rosaadl.importers.aadl_syntax import parse


def test_everything_model_is_written_and_parses() -> None:
    ws = everything_model()
    texts = write_units(ws.units)
    assert list(texts) == ["robot-nav.aadl", "Nav_Props.aadl"]
    seen: set[str] = set()
    for name, text in texts.items():
        seen |= node_names(parse(text, name))
    missing = EXPECTED_NODES - seen
    assert not missing, f"constructs not written: {sorted(missing)}\n{texts['robot-nav.aadl']}"


def test_everything_model_details() -> None:
    text = write_unit(everything_model().units[0])
    expected_lines = [
        "package robot::nav",
        "  with Base_Types, Nav_Props;",
        "  BT renames package Base_Types;",
        "  renames package Nav_Props::all;",
        "  Int renames data Base_Types::Integer;",
        "  Grp renames feature group robot::nav::sensors;",
        "  thread planner extends robot::nav::base_thread (msg => data Base_Types::Integer)",
        "      msg: data Base_Types::Float;",
        "      cmd: out data port prototype msg;",
        "      arg: in out parameter;",
        "      lan: requires bus access;",
        "      vb: requires virtual bus access;",
        "      fg: feature group inverse of robot::nav::sensors;",
        "      fg2: out feature group sensors;",
        "      af: in feature;",
        "      tick2: refined to in event port;",
        "      f_path: flow path goal -> cmd { Latency => 1 ms .. 5 ms; };",
        "      f_ref: refined to flow source in modes (nominal);",
        "      fail: nominal -[ tick, self.ev ]-> degraded;",
        "      degraded -[ processor.reset ]-> nominal;",
        "      Period => (100 ms in modes (nominal), 200 ms in modes (degraded));",
        "    annex EMV2 {** use types ErrorLibrary; **} in modes (nominal);",
        "    annex BA none;",
        "  thread base_thread",
        "    requires modes",
        "      odom: in data port [4];",
        "    inverse of sensors",
        "      plan: thread planner (msg => data Base_Types::Integer) [2] "
        "(planner, robot::nav::planner (msg => data Base_Types::Float)) {",
        "        Priority => 3;",
        "      } in modes (nominal);",
        "      grid: data map_t in modes (a => b);",
        "      grid2: refined to data;",
        "      matrix: abstract [2][Nav_Props::Size][];",
        "      cs: {",
        "        c1: subprogram robot::nav::solve.impl;",
        "        c2: subprogram processor.rt;",
        "      } { Priority => 1; } in modes (nominal);",
        "      c_goal: port goal -> plan.goal;",
        "      c_map: data access grid -> plan.map;",
        "      c_lan: bus access net <-> r.lan;",
        "      c_vb: virtual bus access vbus -> r.vb;",
        "      c_fg: feature group plan.fg -> plan.fg2;",
        "      c_p: parameter c1.arg -> c2.x;",
        "      c_old: refined to port goal -> plan.tick;",
        "      port processor.clk -> plan.tick;",
        "      f_path: flow path goal -> c_goal -> plan.f_path -> cmd;",
        "      e2e_old: refined to end to end flow in modes (nominal);",
        "      Actual_Processor_Binding => (reference (cpu.core[1]))",
        "        applies to plan[1], a.b[1].c in binding (robot::nav::cpu_t.impl);",
        "      Nav_Props::Weights +=> ((1, 2), (), (0.0025, 1.0e-5));",
        "      Nav_Props::Limit => constant -4 m;",
        '      Nav_Props::Config => [name => "the ""best"" map"; size => 3; inner => [flag => true;];];',
        "      Nav_Props::Impl => classifier (robot::nav::nav_proc.impl);",
        "      Nav_Props::Dyn => compute (speed_fn);",
        "      Nav_Props::Flag => A and not B or false;",
        "      Nav_Props::Neg => -Nav_Props::Max .. Nav_Props::Max delta 0.5;",
        "      Nav_Props::Annexed => 1 applies to plan.annex {** EMV2 **};",
        "private",
        "  with Data_Model;",
        "  device hidden",
        "properties",
        '  Nav_Props::Version => "1.0";',
        "end robot::nav;",
    ]
    lines = text.splitlines()
    for line in expected_lines:
        assert line in lines, f"missing line {line!r} in:\n{text}"
    # sections in the standard's order, public before private before the package properties
    assert lines.index("public") < lines.index("private") < lines.index("properties")
    assert text.index("  annex EMV2 {** error types") > text.index("  end nav_proc.impl;")


def test_property_set_details() -> None:
    text = write_unit(everything_model().units[1])
    assert text == (
        "property set Nav_Props is\n"
        "  with AADL_Project, Timing_Properties;\n"
        "\n"
        "  Switch: type aadlboolean;\n"
        "  Label: type aadlstring;\n"
        "  Kind: type enumeration (Input, Output);\n"
        "  Length_Units: type units (mm, cm => mm * 10, m => cm * 100, inch => mm * 25.4);\n"
        "  Distance: type aadlinteger 0 .. 100 units Length_Units;\n"
        "  Speed: type aadlreal units (mps, kph => mps * 0.27);\n"
        "  Span: type range of Nav_Props::Distance;\n"
        "  Span2: type range of aadlreal;\n"
        "  Cl: type classifier (thread, thread group, {emv2}** error type);\n"
        "  Ref: type reference;\n"
        "  Pair: type record (first: aadlinteger_alias; second: list of aadlstring;);\n"
        "  Names: type list of Nav_Props::Label;\n"
        "\n"
        "  Max_Speed: aadlreal units Nav_Props::Length_Units applies to (\n"
        "    thread,\n"
        "    device,\n"
        "    robot::nav::planner);\n"
        "  Weights: inherit list of list of aadlinteger => () applies to (all);\n"
        "  Kind_Of: Nav_Props::Kind => Input applies to (feature group type);\n"
        "\n"
        "  Max: constant aadlinteger_alias => 10;\n"
        "  Size: constant aadlinteger => 3;\n"
        "end Nav_Props;\n"
    )
    parse(text, "Nav_Props.aadl")


# --------------------------------------------------------------------------- golden texts


def test_minimal_package_golden() -> None:
    pkg = package("P", N("ComponentType", name="T", category="system"))
    assert write_unit(pkg) == "package P\npublic\n  system T\n  end T;\nend P;\n"


def test_empty_package_still_has_a_public_section() -> None:
    assert write_unit(package("P")) == "package P\npublic\nend P;\n"


def test_indentation_and_sections_golden() -> None:
    t = N("ComponentType", name="node", category="process")
    t.features.append(
        N("Feature", name="img", category="event data port", direction="in", classifier="msgs::Image")
    )
    t.features.append(
        N(
            "Feature",
            name="out1",
            category="data port",
            direction="out",
            ownedPropertyAssociations=[pa("Queue_Size", i(2)), pa("Timing", named("Delayed"))],
        )
    )
    impl = N("ComponentImplementation", name="node.impl", type="node", category="process")
    impl.subcomponents.append(N("Subcomponent", name="th", category="thread", classifier="worker.impl"))
    impl.connections.append(N("Connection", name="c1", kind="port", source="img", destination="th.img"))
    impl.ownedPropertyAssociations.append(pa("Priority", i(5), appliesTo=["th"]))
    private = N("ComponentType", name="worker", category="thread", visibility="private")
    pkg = package("ros::nodes", t, impl, private, withs=["msgs"], privateWiths=["Base_Types"])
    expected = """\
package ros::nodes
public
  with msgs;

  process node
    features
      img: in event data port msgs::Image;
      out1: out data port {
        Queue_Size => 2;
        Timing => Delayed;
      };
  end node;

  process implementation node.impl
    subcomponents
      th: thread worker.impl;
    connections
      c1: port img -> th.img;
    properties
      Priority => 5 applies to th;
  end node.impl;
private
  with Base_Types;

  thread worker
  end worker;
end ros::nodes;
"""
    assert write_unit(pkg) == expected
    parse(expected, "ros-nodes.aadl")


def test_private_section_only_when_needed() -> None:
    assert "private" not in write_unit(package("P", N("ComponentType", name="T", category="data")))
    text = write_unit(package("P", privateWiths=["Q"]))
    assert text == "package P\npublic\nprivate\n  with Q;\nend P;\n"
    parse(text, "p.aadl")


def test_implementation_name_from_type_and_name() -> None:
    impl = N("ComponentImplementation", name="impl", type="T", category="bus")
    assert "  bus implementation T.impl\n  end T.impl;\n" in write_unit(package("P", impl))
    wrong = N("ComponentImplementation", name="U.impl", type="T", category="bus")
    with pytest.raises(ExportError, match="implements type 'T'"):
        write_unit(package("P", wrong))


def test_long_enumeration_and_units_are_wrapped() -> None:
    ps = N("PropertySet", name="Wide")
    ps.ownedPropertyTypes.append(
        N(
            "EnumerationType",
            name="Langs",
            ownedLiterals=[N("EnumerationLiteral", name=f"Language_{n}") for n in range(12)],
        )
    )
    owners = ["thread", "thread group", "process", "system", "device", "virtual processor", "virtual bus"]
    owners += ["processor", "memory", "bus", "data", "subprogram", "subprogram group", "abstract"]
    ps.ownedProperties.append(N("Property", name="Owned", ownedType=N("AadlBoolean"), appliesTo=owners))
    text = write_unit(ps)
    assert "  Langs: type enumeration (\n    Language_0,\n" in text
    assert "    Language_11);\n" in text
    assert "  Owned: aadlboolean applies to (\n    thread,\n    thread group,\n" in text
    assert "    abstract);\n" in text
    assert all(len(line) <= 100 for line in text.splitlines())
    parse(text, "wide.aadl")

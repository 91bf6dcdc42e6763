"""Deep component hierarchies: instantiation needs no Python recursion, rosaadl reads back every
model it writes (a bounded round-trip property over deep models), absurd depth is a located error."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rosaadl import model
from rosaadl.cli import main
from rosaadl.errors import ModelError, ValidationError
from rosaadl.importers.aadl_text import read_string
from rosaadl.transforms.instantiate import instantiate
from rosaadl.transforms.instantiate.hierarchy import MAX_HIERARCHY_DEPTH


def nested_systems(levels: int) -> str:
    """AADL text: ``s0.impl`` holds ``s1.impl`` holds ... ``s{levels-1}.impl`` (``levels`` components)."""
    lines = ["package deep", "public"]
    for i in range(levels):
        lines.append(f"  system s{i}\n  end s{i};")
        sub = f"  subcomponents\n    c: system s{i + 1}.impl;\n" if i < levels - 1 else ""
        lines.append(f"  system implementation s{i}.impl\n{sub}  end s{i}.impl;")
    lines.append("end deep;")
    return "\n".join(lines) + "\n"


def depth_of(instance) -> int:
    depth = 0
    while instance is not None:
        depth += 1
        instance = instance.componentInstances[0] if instance.componentInstances else None
    return depth


@pytest.mark.parametrize("levels", [500, MAX_HIERARCHY_DEPTH + 1])
def test_deep_hierarchies_instantiate_and_read_back(tmp_path: Path, capsys, levels: int) -> None:
    source = tmp_path / "deep.aadl"
    source.write_text(nested_systems(levels))
    for suffix in (".xmi", ".json"):
        out = tmp_path / f"deep{suffix}"
        code = main(["instantiate", str(source), "--root", "deep::s0.impl", "-o", str(out)])
        captured = capsys.readouterr()
        assert code == 0, captured.err
        assert main(["check", str(out)]) == 0, capsys.readouterr()
        capsys.readouterr()
        (instance,) = model.load(out).instances
        assert depth_of(instance) == levels


def test_a_hierarchy_past_the_bound_is_a_located_error(tmp_path: Path, capsys) -> None:
    text = nested_systems(MAX_HIERARCHY_DEPTH + 2)
    with pytest.raises(ModelError) as info:
        instantiate(read_string(text, "deep.aadl"), "deep::s0.impl")
    assert f"deeper than {MAX_HIERARCHY_DEPTH} levels" in info.value.message
    assert info.value.location.file == "deep.aadl" and info.value.location.line
    source = tmp_path / "deep.aadl"
    source.write_text(text)
    out = tmp_path / "deep.xmi"
    assert main(["instantiate", str(source), "--root", "deep::s0.impl", "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert "deeper than" in err and "Traceback" not in err and not out.exists()


def _chain_xmi(depth: int) -> bytes:
    head = (
        '<?xml version="1.0" encoding="UTF-8"?>\n<aadl:AadlModel xmlns:xmi="http://www.omg.org/XMI" '
        'xmlns:aadl="urn:rosaadl:aadl:1.0" xmi:version="2.0">\n<instances name="r" category="system">'
    )
    inner = '<componentInstances name="c" category="system">' * depth + "</componentInstances>" * depth
    return (head + inner + "</instances></aadl:AadlModel>\n").encode()


def _chain_json(depth: int) -> bytes:
    head = (
        '{"eClass": "urn:rosaadl:aadl:1.0#//AadlModel", "instances": [{"name": "r", "componentInstances": ['
    )
    inner = '{"name": "c", "componentInstances": [' * depth + "]}" * depth
    return (head + inner + "]}]}").encode()


def test_absurd_depth_is_a_located_error() -> None:
    assert depth_of(model.loads_xmi(_chain_xmi(1_500)).instances[0]) == 1_501
    assert depth_of(model.loads_json(_chain_json(1_500)).instances[0]) == 1_501
    with pytest.raises(ValidationError) as info:
        model.loads_xmi(_chain_xmi(5_000), "deep.xmi")
    assert info.value.location.file == "deep.xmi" and info.value.location.line == 3
    assert "nested too deeply (more than 2048 elements)" in info.value.message
    with pytest.raises(ValidationError) as info:
        model.loads_json(_chain_json(5_000), "deep.json")
    assert info.value.location.file == "deep.json" and "nested too deeply" in info.value.message


def test_a_model_deeper_than_rosaadl_writes_is_refused_on_writing() -> None:
    deep = model.loads_xmi(_chain_xmi(model.MAX_MODEL_DEPTH))
    assert model.model_depth(deep) == model.MAX_MODEL_DEPTH + 2
    with pytest.raises(ModelError, match="rosaadl writes at most"):
        model.dumps_xmi(deep)


@st.composite
def deep_instances(draw):
    """An instance tree: a spine of up to 1 200 levels, side branches, names and array indexes."""
    depth = draw(st.integers(1, 1_200))
    names = st.text("abcxyz_", min_size=1, max_size=4).map(lambda s: "n" + s)
    root = model.new("SystemInstance", name="root", category="system")
    current = root
    for level in range(depth):
        child = model.new("ComponentInstance", name=draw(names), category="system")
        if draw(st.booleans()):
            child.index.extend(draw(st.lists(st.integers(1, 2**31 - 1), min_size=1, max_size=2)))
        current.componentInstances.append(child)
        if level % 97 == 0:
            current.componentInstances.append(model.new("ComponentInstance", name="side", category="thread"))
        current = child
    aadl = model.new("AadlModel")
    aadl.instances.append(root)
    return aadl


@settings(
    max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large]
)
@given(deep_instances())
def test_rosaadl_reads_back_every_deep_model_it_writes(aadl) -> None:
    assert model.model_equal(model.loads_xmi(model.dumps_xmi(aadl)), aadl)
    assert model.model_equal(model.loads_json(model.dumps_json(aadl)), aadl)

"""The rule engine: dispatch, guards, lazy unique rules, resolve, phases, trace, errors."""

from __future__ import annotations

from decimal import Decimal

import pytest

from rosaadl import model
from rosaadl.errors import TransformationError
from rosaadl.transforms.engine import Transformation
from rosaadl.transforms.trace import TraceIndex, element_key, find_by_key, load_trace, save_trace


def _component():
    comp = model.new("rosmod.Component", name="tracker", line=12)
    comp.ports.extend(
        [
            model.new("rosmod.Subscriber", name="image_in", type="sensor_msgs/Image", priority=50),
            model.new("rosmod.Publisher", name="point_out", type="geometry_msgs/Point"),
            model.new("rosmod.Server", name="reset", type="std_srvs/Trigger"),
        ]
    )
    comp.timers.append(model.new("rosmod.Timer", name="tick", period=Decimal("0.1")))
    software = model.new("rosmod.Software", name="sw", sourceFile="proj/01-Software/sw.rml")
    pkg = model.new("rosmod.Package", name="pkg")
    pkg.components.append(comp)
    software.packages.append(pkg)
    return software, comp


def _to_aadl() -> Transformation:
    t = Transformation("test")

    @t.rule("rosmod.Component", to="ComponentType")
    def component(ctx, src, tgt):
        tgt.name = src.name
        tgt.category = (
            model.eclass_of("ComponentType")
            .findEStructuralFeature("category")
            .eType.from_string("thread group")
        )

    @t.rule("rosmod.Port", to="Feature")
    def any_port(ctx, src, tgt):
        tgt.name = src.name
        tgt.classifier = "generic"

    @t.rule("rosmod.CallbackPort", to="Feature")
    def callback_port(ctx, src, tgt):
        tgt.name = src.name
        tgt.classifier = "callback"

    @t.rule("rosmod.Subscriber", to="Feature")
    def subscriber(ctx, src, tgt):
        tgt.name = src.name
        tgt.classifier = "subscriber"

    @t.rule("rosmod.Timer", to="Feature", when=lambda ctx, timer: timer.period is not None)
    def timer(ctx, src, tgt):
        tgt.name = src.name
        tgt.classifier = "timer"

    @component.bind
    def component_bind(ctx, src, tgt):
        for port in list(src.ports) + list(src.timers):
            tgt.features.append(ctx.resolve_one(port, "Feature"))

    return t


def test_most_specific_rule_wins_and_binding_after_creation() -> None:
    software, comp = _component()
    result = _to_aadl().run(software)
    (ct,) = [r for r in result.roots if r.eClass.name == "ComponentType"]
    kinds = {f.name: f.classifier for f in ct.features}
    assert kinds == {"image_in": "subscriber", "point_out": "generic", "reset": "callback", "tick": "timer"}
    assert ct.category.literal == "thread group"


def test_guard_excludes_objects() -> None:
    software, comp = _component()
    comp.timers[0].period = None
    t = _to_aadl()
    t.get_rule("component_bind" if False else "component").bind_fn = lambda ctx, s, tgt: None
    result = t.run(software)
    assert "tick" not in {r.name for r in result.roots}


def test_ambiguous_rules_are_an_error_naming_both() -> None:
    software, _ = _component()
    t = _to_aadl()

    @t.rule("rosmod.Subscriber", to="Feature")
    def subscriber_again(ctx, src, tgt):
        tgt.name = src.name

    with pytest.raises(
        TransformationError, match="subscriber.*subscriber_again|subscriber_again.*subscriber"
    ):
        t.run(software)


def test_lazy_rules_are_unique_and_only_run_when_asked() -> None:
    software, comp = _component()
    t = Transformation("lazy")
    calls = []

    @t.rule("rosmod.Timer", to="Subcomponent", lazy=True)
    def thread_for(ctx, src, tgt):
        calls.append(src.name)
        tgt.name = f"{src.name}_thread"

    @t.rule("rosmod.Component", to="ComponentImplementation")
    def impl(ctx, src, tgt):
        tgt.name = f"{src.name}.impl"

    @impl.bind
    def impl_bind(ctx, src, tgt):
        first = ctx.lazy(thread_for, src.timers[0])
        second = ctx.lazy("thread_for", src.timers[0])
        assert first is second
        tgt.subcomponents.append(first)

    result = t.run(software)
    assert calls == ["tick"]
    (impl_obj,) = result.roots
    assert [s.name for s in impl_obj.subcomponents] == ["tick_thread"]
    assert result.context.resolve(comp.timers[0]) == [impl_obj.subcomponents[0]]


def test_resolve_in_create_phase_explains_bind_phase() -> None:
    software, comp = _component()
    t = Transformation("early")

    @t.rule("rosmod.Component", to="ComponentType")
    def component(ctx, src, tgt):
        ctx.resolve_one(src.timers[0])

    @t.rule("rosmod.Timer", to="Feature")
    def timer(ctx, src, tgt):
        tgt.name = src.name

    with pytest.raises(TransformationError) as info:
        t.run(software)
    err = info.value
    assert err.rule == "component"
    assert "bind part" in err.message
    # located on the object that could not be resolved yet
    assert err.location.file == "proj/01-Software/sw.rml"
    assert err.location.path == "/packages[pkg]/components[tracker]/timers[tick]"


def test_rule_failure_names_rule_source_file_and_line() -> None:
    software, comp = _component()
    t = Transformation("boom")

    @t.rule("rosmod.Component", to="ComponentType")
    def component(ctx, src, tgt):
        raise ValueError("period missing")

    with pytest.raises(TransformationError) as info:
        t.run(software)
    text = str(info.value)
    assert "rule 'component'" in text and "Component 'tracker'" in text and "period missing" in text
    assert "sw.rml:12" in text


def test_misspelled_target_feature_in_rule_is_reported() -> None:
    software, _ = _component()
    t = Transformation("typo")

    @t.rule("rosmod.Component", to=None)
    def component(ctx, src):
        return model.new("ComponentType", nmae=src.name)

    with pytest.raises(TransformationError, match="nmae"):
        t.run(software)


def test_trace_records_links_and_survives_save_and_load(tmp_path) -> None:
    software, comp = _component()
    result = _to_aadl().run(software)
    index = TraceIndex(result.trace)
    assert index.rules() == ["any_port", "callback_port", "component", "subscriber", "timer"]
    key = element_key(comp)
    assert key == "/packages[pkg]/components[tracker]"
    assert find_by_key(software, key) is comp
    for suffix in ("xmi", "json"):
        path = save_trace(result.trace, tmp_path / f"run.trace.{suffix}")
        back = load_trace(path)
        again = TraceIndex(back)
        (link,) = again.links_from(key)
        assert link.rule == "component" and link.targets[0].className == "ComponentType"
        assert [
            e.path for e in again.links_from("/packages[pkg]/components[tracker]/ports[image_in]")[0].sources
        ] == ["/packages[pkg]/components[tracker]/ports[image_in]"]


def test_duplicate_rule_names_are_refused() -> None:
    t = Transformation("dup")

    @t.rule("rosmod.Timer", to="Feature")
    def r(ctx, s, tgt):
        pass

    with pytest.raises(ValueError, match="declared twice"):

        @t.rule("rosmod.Timer", to="Feature", name="r")
        def other(ctx, s, tgt):
            pass

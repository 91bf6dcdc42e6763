"""The rule engine: dispatch, guards, lazy unique rules, walks, resolve, phases, trace, errors."""

from __future__ import annotations

from decimal import Decimal

import pytest

from rosaadl import model
from rosaadl.errors import TransformationError
from rosaadl.transforms.engine import Transformation
from rosaadl.transforms.trace import (
    TraceIndex,
    element_key,
    find_by_key,
    key_targets,
    load_trace,
    save_trace,
)


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


def _feature(src, classifier: str):
    return model.new("Feature", name=src.name, classifier=classifier)


def _to_aadl() -> Transformation:
    t = Transformation("test")

    @t.rule("rosmod.Component")
    def component(ctx, src):
        return model.new("ComponentType", name=src.name, category="thread group")

    @t.rule("rosmod.Port")
    def any_port(ctx, src):
        return _feature(src, "generic")

    @t.rule("rosmod.CallbackPort")
    def callback_port(ctx, src):
        return _feature(src, "callback")

    @t.rule("rosmod.Subscriber")
    def subscriber(ctx, src):
        return _feature(src, "subscriber")

    @t.rule("rosmod.Timer", when=lambda ctx, timer: timer.period is not None)
    def timer(ctx, src):
        return _feature(src, "timer")

    @component.bind
    def component_bind(ctx, src, tgt):
        for port in list(src.ports) + list(src.timers):
            tgt.features.extend(ctx.resolve(port))

    return t


def _made(result, source, rule=None):
    (target,) = result.context.resolve(source, rule)
    return target


def test_most_specific_rule_wins_and_binding_after_creation() -> None:
    software, comp = _component()
    result = _to_aadl().run(software)
    ct = _made(result, comp)
    kinds = {f.name: f.classifier for f in ct.features}
    assert kinds == {"image_in": "subscriber", "point_out": "generic", "reset": "callback", "tick": "timer"}
    assert ct.category.literal == "thread group"
    made = result.context.resolve_all([*comp.timers, *comp.ports])
    assert [f.name for f in made] == ["tick", "image_in", "point_out", "reset"]
    assert [f.name for f in result.context.resolve_all(comp.ports, "subscriber")] == ["image_in"]


def test_guard_excludes_objects() -> None:
    software, comp = _component()
    comp.timers[0].period = None
    result = _to_aadl().run(software)
    assert result.context.resolve(comp.timers[0]) == []
    assert "tick" not in {f.name for f in _made(result, comp).features}


def test_rules_keyed_by_where_share_one_question_per_object() -> None:
    software, comp = _component()
    t = Transformation("keyed")
    asked = []

    def kind(ctx, port):
        asked.append(port.name)
        return port.eClass.name

    @t.rule("rosmod.Port", where=(kind, "Publisher"))
    def publisher(ctx, src):
        return _feature(src, "out")

    @t.rule("rosmod.Port", where=(kind, "Subscriber"), when=lambda ctx, p: p.priority == 50)
    def urgent_subscriber(ctx, src):
        return _feature(src, "urgent")

    @t.rule("rosmod.Port", where=(kind, "Subscriber"), when=lambda ctx, p: p.priority != 50)
    def subscriber(ctx, src):
        return _feature(src, "in")

    result = t.run(software)
    made = {f.name: f.classifier for f in result.context.resolve_all(comp.ports)}
    assert made == {"image_in": "urgent", "point_out": "out"}  # no rule for the server
    assert asked == ["image_in", "point_out", "reset"]  # once per port, for the three rules


def test_ambiguous_rules_are_an_error_naming_both() -> None:
    software, _ = _component()
    t = _to_aadl()

    @t.rule("rosmod.Subscriber")
    def subscriber_again(ctx, src):
        return _feature(src, "again")

    with pytest.raises(
        TransformationError, match="subscriber.*subscriber_again|subscriber_again.*subscriber"
    ):
        t.run(software)


def test_lazy_rules_are_unique_and_only_run_when_asked() -> None:
    software, comp = _component()
    t = Transformation("lazy")
    calls = []

    @t.rule("rosmod.Timer", lazy=True)
    def thread_for(ctx, src):
        calls.append(src.name)
        return model.new("Subcomponent", name=f"{src.name}_thread")

    @t.rule("rosmod.Component")
    def impl(ctx, src):
        return model.new("ComponentImplementation", name=f"{src.name}.impl")

    @impl.bind
    def impl_bind(ctx, src, tgt):
        first = ctx.lazy(thread_for, src.timers[0])
        second = ctx.lazy("thread_for", src.timers[0])
        assert first is second
        tgt.subcomponents.append(first)

    result = t.run(software)
    assert calls == ["tick"]
    impl_obj = _made(result, comp)
    assert [s.name for s in impl_obj.subcomponents] == ["tick_thread"]
    assert result.context.resolve(comp.timers[0]) == [impl_obj.subcomponents[0]]


def test_a_lazy_rule_maps_pairs_and_binds_what_it_makes_while_binding() -> None:
    """One target per pair of sources (a port of each component instance, say), and a lazy
    application made in the bind phase has its bind part run too."""
    software, comp = _component()
    t = Transformation("pairs")
    bound = []

    @t.rule("rosmod.Port", lazy=True)
    def port_of(ctx, port, timer):
        return model.new("Feature", name=f"{timer.name}_{port.name}")

    @port_of.bind
    def port_of_bind(ctx, port, timer, feature):
        bound.append(feature.name)

    @t.rule("rosmod.Component")
    def group(ctx, src):
        return model.new("ComponentType", name=src.name)

    @group.bind
    def group_bind(ctx, src, tgt):
        for timer in src.timers:
            for port in src.ports:
                tgt.features.append(ctx.lazy(port_of, port, timer))
        assert ctx.lazy(port_of, src.ports[0], src.timers[0]) is tgt.features[0]

    result = t.run(software)
    assert [f.name for f in _made(result, comp).features] == ["tick_image_in", "tick_point_out", "tick_reset"]
    assert bound == ["tick_image_in", "tick_point_out", "tick_reset"]
    (link,) = [
        link for link in result.trace.links if link.targets and link.targets[0].object.name == "tick_reset"
    ]
    assert [e.className for e in link.sources] == ["Server", "Timer"]


def test_the_walk_chooses_what_is_visited_and_in_which_order() -> None:
    software, comp = _component()
    t = Transformation("ordered")
    seen = []

    @t.rule("rosmod.Port")
    def port(ctx, src):
        seen.append(src.name)

    def ports_backwards(root):
        yield from reversed(list(comp.ports))

    result = t.run(software, walk=ports_backwards)
    assert seen == ["reset", "point_out", "image_in"]
    assert [link.rule for link in result.trace.links] == ["port"] * 3  # no target, still traced


def test_a_run_without_trace_resolves_all_the_same() -> None:
    software, comp = _component()
    result = _to_aadl().run(software, trace=False)
    assert result.trace is None
    assert {f.name for f in _made(result, comp).features} == {"image_in", "point_out", "reset", "tick"}


def test_targets_are_keyed_again_where_they_end_up() -> None:
    software, comp = _component()
    t = _to_aadl()

    @t.rule("rosmod.Package")
    def package(ctx, src):
        return model.new("AadlPackage", name=src.name)

    @package.bind
    def package_bind(ctx, src, tgt):
        for component in src.components:
            tgt.classifiers.extend(ctx.resolve(component))

    result = t.run(software)
    (link,) = TraceIndex(result.trace).links_from(comp.ports[0])
    assert [e.path for e in link.targets] == ["/"]  # made before it had a container
    key_targets(result.trace)
    (link,) = TraceIndex(result.trace).links_from(comp.ports[0])
    assert [e.path for e in link.targets] == ["/classifiers[tracker]/features[image_in]"]


def test_rule_failure_names_rule_source_file_and_line() -> None:
    software, comp = _component()
    t = Transformation("boom")

    @t.rule("rosmod.Component")
    def component(ctx, src):
        raise ValueError("period missing")

    with pytest.raises(TransformationError) as info:
        t.run(software)
    text = str(info.value)
    assert "rule 'component'" in text and "Component 'tracker'" in text and "period missing" in text
    assert "sw.rml:12" in text


def test_misspelled_target_feature_in_rule_is_reported() -> None:
    software, _ = _component()
    t = Transformation("typo")

    @t.rule("rosmod.Component")
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

    @t.rule("rosmod.Timer")
    def r(ctx, s):
        pass

    with pytest.raises(TransformationError, match="declared twice"):

        @t.rule("rosmod.Timer", name="r")
        def other(ctx, s):
            pass

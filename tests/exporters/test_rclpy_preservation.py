"""User code between preservation markers survives regeneration: kept in place, moved when a
trace knows the element's rename, kept in the orphan section when the element is gone, put back
when it returns; malformed markers are located errors that write nothing."""

from __future__ import annotations

import compileall
import io
import re
from contextlib import redirect_stdout
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_rclpy_models import services_instance, tracking_instance

from rosaadl import model
from rosaadl.errors import GenerationError
from rosaadl.exporters.rclpy import MANIFEST_NAME, GenerationOptions, generate_workspace, preservation
from rosaadl.transforms import trace as tracing

OPTIONS = GenerationOptions(year=2024)
TRACKER = "nd_ocv_color_tracking/nd_ocv_color_tracking/ocv_color_tracking.py"
BLOCK_RE = re.compile(
    r'^(?P<indent>[ \t]*)# <user-code name="(?P<name>[^"]+)">\n(?P<body>.*?)^[ \t]*# </user-code>\n',
    re.M | re.S,
)


def fill(path: Path, tokens: dict[str, str]) -> None:
    """Replace the content of every block of ``path`` by a token comment (recorded in ``tokens``)."""
    text = path.read_text()

    def repl(match: re.Match) -> str:
        token = f"token-{len(tokens)}"
        tokens[token] = match["name"]
        indent = match["indent"]
        opening = f'{indent}# <user-code name="{match["name"]}">'
        return f"{opening}\n{indent}# {token} hand-written\n{indent}# </user-code>\n"

    path.write_text(BLOCK_RE.sub(repl, text))


def rename_link(trace, obj, new_name: str) -> None:
    old_key = tracing.element_key(obj)
    obj.name = new_name
    if obj.eClass.findEStructuralFeature("subcomponent") is not None:
        obj.subcomponent = new_name
    if obj.eClass.findEStructuralFeature("feature") is not None:
        obj.feature = new_name
    link = model.new("trace.TraceLink", rule="rename")
    link.sources.append(model.new("trace.TraceElement", path=old_key))
    link.targets.append(model.new("trace.TraceElement", path=tracing.element_key(obj)))
    trace.links.append(link)


def blocks(path: Path) -> dict[str, str]:
    parsed = preservation.parse(path.read_text(), "hash", str(path))
    return {name: block.text() for name, block in parsed.blocks.items()}


def orphans(path: Path) -> dict[str, str]:
    parsed = preservation.parse(path.read_text(), "hash", str(path))
    return {name: block.text() for name, block in parsed.orphans.items()}


# --------------------------------------------------------------------------- markers


def test_parse_and_render_round_trip():
    text = (
        "a = 1\n"
        "def f():\n"
        '    # <user-code name="m.f">\n'
        "    x = 2\n"
        "\n"
        "  weird = 3\n"
        "    # </user-code>\n"
        "    return 4\n"
    )
    parsed = preservation.parse(text, "hash")
    assert list(parsed.blocks) == ["m.f"]
    assert parsed.blocks["m.f"].content == [(True, "x = 2"), (True, ""), (False, "  weird = 3")]
    assert preservation.render(parsed, lambda b: None, [], "hash") == text


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        (
            '# <user-code name="a">\n# <user-code name="b">\n# </user-code>\n# </user-code>\n',
            2,
            "inside block",
        ),
        ('x\n# <user-code name="a">\ny\n', 2, "never closed"),
        (
            '# <user-code name="a">\n# </user-code>\n# <user-code name="a">\n# </user-code>\n',
            3,
            "appears twice",
        ),
        ("x\n# </user-code>\n", 2, "without an opening"),
        ("# <orphaned-user-code>\n# x\n", 1, "never closed"),
    ],
)
def test_malformed_markers_are_located_errors(text, line, words):
    with pytest.raises(GenerationError) as caught:
        preservation.parse(text, "hash", "f.py")
    assert caught.value.location.file == "f.py" and caught.value.location.line == line
    assert words in caught.value.message


@pytest.mark.parametrize("style", ["hash", "xml"])
def test_orphans_survive_their_comment_form(style):
    content = [
        (True, "x = '--' # -- -> -->"),
        (True, "\\ backslash"),
        (True, '<user-code name="fake">'),
        (True, "# </orphaned-user-code>"),
        (True, ""),
        (True, "    indented"),
    ]
    opening, closing = preservation.marker_lines("kept", style)
    generated = preservation.parse(f"head\n{opening}\n{closing}\n", style)
    text = preservation.render(generated, lambda b: None, [("gone", content)], style)
    if style == "xml":
        comments = re.findall(r"<!--(.*?)-->", text, re.S)
        assert all("--" not in c and not c.endswith("-") for c in comments)
    back = preservation.parse(text, style)
    assert back.orphans["gone"].content == content
    again = preservation.render(preservation.parse(text, style), lambda b: None, [("gone", content)], style)
    assert (
        preservation.render(
            back, lambda b: None, list((n, b.content) for n, b in back.orphans.items()), style
        )
        == again
    )


def test_a_malformed_file_stops_generation_before_any_write(tmp_path):
    _, instance = tracking_instance()
    generate_workspace(instance, tmp_path, options=OPTIONS)
    broken = tmp_path / TRACKER
    broken.write_text(broken.read_text().replace("        # </user-code>\n", "", 1))
    snapshot = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    thread = model.find_instance(instance, "rem_trk_sw.tracker.image_tracker")
    thread.name = "renamed"  # would change several files
    with pytest.raises(GenerationError) as caught:
        generate_workspace(instance, tmp_path, options=OPTIONS)
    assert caught.value.location.file.endswith("ocv_color_tracking.py") and caught.value.location.line
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == snapshot


# --------------------------------------------------------------------------- regeneration


def test_blocks_are_kept_and_moved_and_orphaned_and_restored(tmp_path):
    ws, instance = tracking_instance()
    generate_workspace(instance, tmp_path, options=OPTIONS)
    tokens: dict[str, str] = {}
    for path in sorted(tmp_path.rglob("*.py")):
        fill(path, tokens)
    tracker = tmp_path / TRACKER
    before = blocks(tracker)
    assert "token" in before["ocv_color_tracking.image_tracker.cb_msg"]

    # 1. same model: nothing changes
    again = generate_workspace(instance, tmp_path, options=OPTIONS)
    assert not again.written and blocks(tracker) == before

    # 2. rename a thread (the trace knows it) and remove another
    edits = tracing.new_trace("edit")
    rename_link(edits, model.find_instance(instance, "rem_trk_sw.tracker.image_tracker"), "finder")
    gone = model.find_instance(instance, "rem_trk_sw.tracker.point_broadcaster")
    gone.eContainer().componentInstances.remove(gone)
    result = generate_workspace(instance, tmp_path, options=OPTIONS, trace=edits)
    now = blocks(tracker)
    assert now["ocv_color_tracking.finder.cb_msg"] == before["ocv_color_tracking.image_tracker.cb_msg"]
    assert "ocv_color_tracking.image_tracker.cb_msg" not in now
    assert [(m.name, m.target_name) for m in result.moved] == [
        ("ocv_color_tracking.image_tracker.cb_msg", "ocv_color_tracking.finder.cb_msg")
    ]
    assert [m.name for m in result.orphaned] == ["ocv_color_tracking.point_broadcaster"]
    text = tracker.read_text()
    section = text[text.index("# <orphaned-user-code>") :]
    assert section == (
        "# <orphaned-user-code>\n"
        "# User code whose model element is no longer in the model, kept here commented out.\n"
        "# A block comes back into place when an element of the same name appears again;\n"
        "# move what you still need into a current block, then delete it from here.\n"
        '# <user-code name="ocv_color_tracking.point_broadcaster">\n'
        f"# {before['ocv_color_tracking.point_broadcaster']}\n"
        "# </user-code>\n"
        "# </orphaned-user-code>\n"
    )
    compile(text, str(tracker), "exec")

    # 3. regenerate again: the orphan stays, nothing else moves
    stable = generate_workspace(instance, tmp_path, options=OPTIONS)
    assert not stable.written and orphans(tracker) == {
        "ocv_color_tracking.point_broadcaster": before["ocv_color_tracking.point_broadcaster"]
    }

    # 4. the element comes back: its block is restored in place
    _, fresh = tracking_instance()
    restored_thread = model.find_instance(fresh, "rem_trk_sw.tracker.point_broadcaster")
    restored_thread.eContainer().componentInstances.remove(restored_thread)
    model.find_instance(instance, "rem_trk_sw.tracker").componentInstances.append(restored_thread)
    back = generate_workspace(instance, tmp_path, options=OPTIONS)
    assert [m.name for m in back.restored] == ["ocv_color_tracking.point_broadcaster"]
    assert (
        blocks(tracker)["ocv_color_tracking.point_broadcaster"]
        == before["ocv_color_tracking.point_broadcaster"]
    )
    assert "orphaned-user-code" not in tracker.read_text()


def test_a_rename_without_trace_keeps_the_block_as_an_orphan(tmp_path):
    _, instance = tracking_instance()
    generate_workspace(instance, tmp_path, options=OPTIONS)
    tokens: dict[str, str] = {}
    fill(tmp_path / TRACKER, tokens)
    thread = model.find_instance(instance, "rem_trk_sw.tracker.image_tracker")
    thread.name = "finder"
    result = generate_workspace(instance, tmp_path, options=OPTIONS)
    assert [m.name for m in result.orphaned] == ["ocv_color_tracking.image_tracker.cb_msg"]
    assert "token" in orphans(tmp_path / TRACKER)["ocv_color_tracking.image_tracker.cb_msg"]


def test_blocks_follow_their_element_to_another_file(tmp_path):
    """The node's package changes (a property, not a rename): the module moves to a new package
    and its blocks follow their elements there; the old files are left alone and reported."""
    _, instance = tracking_instance()
    generate_workspace(instance, tmp_path, options=OPTIONS)
    tokens: dict[str, str] = {}
    fill(tmp_path / TRACKER, tokens)
    old_blocks = blocks(tmp_path / TRACKER)
    tracker = model.find_instance(instance, "rem_trk_sw.tracker")
    tracker.ownedPropertyAssociations.append(
        model.new(
            "PropertyAssociation",
            property="ROS_Properties::Package_Name",
            ownedValues=[model.new("ModalPropertyValue", value=model.new("StringValue", value="vision"))],
        )
    )
    result = generate_workspace(instance, tmp_path, options=OPTIONS)
    moved = tmp_path / "vision/vision/ocv_color_tracking.py"
    assert blocks(moved) == old_blocks
    assert {m.target for m in result.moved} == {"vision/vision/ocv_color_tracking.py"}
    assert TRACKER in result.stale and (tmp_path / TRACKER).is_file()


def test_launch_blocks_per_node(tmp_path):
    _, instance = services_instance()
    generate_workspace(instance, tmp_path, options=OPTIONS)
    launch = tmp_path / "app_bringup/launch/app.launch.py"
    text = launch.read_text().replace(
        '            # <user-code name="app.pool">\n',
        '            # <user-code name="app.pool">\n'
        "            arguments=['--ros-args', '--log-level', 'debug'],\n",
    )
    launch.write_text(text)
    pool = model.find_instance(instance, "pool")
    trace = tracing.new_trace("edit")
    rename_link(trace, pool, "workers_pool")
    generate_workspace(instance, tmp_path, options=OPTIONS, trace=trace)
    assert "--log-level" in blocks(launch)["app.workers_pool"]
    compile(launch.read_text(), str(launch), "exec")


def test_the_generation_trace_is_a_trace_model(tmp_path):
    _, instance = tracking_instance()
    generate_workspace(instance, tmp_path, options=OPTIONS)
    trace = tracing.load_trace(tmp_path / MANIFEST_NAME)
    index = tracing.TraceIndex(trace)
    thread = model.find_instance(instance, "rem_trk_sw.tracker.image_tracker")
    port = model.find_instance(instance, "rem_trk_sw.tracker.image_tracker.cb_msg")
    targets = [(e.uri, e.path) for link in index.links_from(port) for e in link.targets]
    assert targets == [(TRACKER, "ocv_color_tracking.image_tracker.cb_msg")]
    assert index.links_from(thread)
    (tmp_path / MANIFEST_NAME).write_text('{"links": 3}')
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    with pytest.raises(GenerationError, match="trace is unreadable.*delete it to regenerate without it"):
        generate_workspace(instance, tmp_path, options=OPTIONS)
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before
    (tmp_path / MANIFEST_NAME).unlink()  # the way on the message gives
    assert generate_workspace(instance, tmp_path, options=OPTIONS).changes


def test_a_hostile_generation_trace_reads_nothing_outside(tmp_path):
    _, instance = tracking_instance()
    out = tmp_path / "src"
    generate_workspace(instance, out, options=OPTIONS)
    secret = tmp_path / "secret.py"
    secret.write_text('# <user-code name="x">\nsecret\n# </user-code>\n')
    trace = model.new("trace.Trace", transformation="x")
    link = model.new("trace.TraceLink", rule="file")
    link.targets.append(model.new("trace.TraceElement", uri="../secret.py"))
    trace.links.append(link)
    model.save(trace, out / MANIFEST_NAME, fmt="json")
    result = generate_workspace(instance, out, options=OPTIONS)
    assert "../secret.py" not in result.stale
    assert any("'../secret.py' ignored" in d.message for d in result.diagnostics)
    assert secret.read_text() == '# <user-code name="x">\nsecret\n# </user-code>\n'
    assert all("secret" not in p.read_text() for p in out.rglob("*.py"))


# --------------------------------------------------------------------------- property-based

NAMES = ["image_tracker", "point_broadcaster", "alpha", "beta", "cb_msg", "pub_msg", "imports", "class"]
edit = st.one_of(
    st.tuples(st.just("rename_thread"), st.integers(0, 9), st.sampled_from(NAMES)),
    st.tuples(st.just("remove_thread"), st.integers(0, 9), st.just("")),
    st.tuples(st.just("add_thread"), st.integers(0, 9), st.sampled_from(NAMES)),
    st.tuples(st.just("rename_port"), st.integers(0, 19), st.sampled_from(NAMES)),
    st.tuples(st.just("remove_port"), st.integers(0, 19), st.just("")),
    st.tuples(st.just("add_port"), st.integers(0, 9), st.sampled_from(NAMES)),
)


def _threads(instance):
    return [
        o
        for o in model.walk(instance)
        if o.eClass.name == "ComponentInstance" and o.category.name == "thread"
    ]


def _ports(instance):
    return [o for t in _threads(instance) for o in t.featureInstances]


def _apply(instance, operation, trace, counter) -> None:
    kind, index, name = operation
    threads, ports = _threads(instance), _ports(instance)
    if kind == "rename_thread" and threads:
        rename_link(trace, threads[index % len(threads)], name)
    elif kind == "remove_thread" and threads:
        thread = threads[index % len(threads)]
        thread.eContainer().componentInstances.remove(thread)
    elif kind == "add_thread" and threads:
        process = threads[index % len(threads)].eContainer()
        dispatch = model.new("NamedValue", name="Periodic")
        period = model.new("IntegerValue", value=10000 + counter, unit="us")
        process.componentInstances.append(
            model.new(
                "ComponentInstance",
                name=name,
                category="thread",
                ownedPropertyAssociations=[
                    model.new(
                        "PropertyAssociation",
                        property="Thread_Properties::Dispatch_Protocol",
                        ownedValues=[model.new("ModalPropertyValue", value=dispatch)],
                    ),
                    model.new(
                        "PropertyAssociation",
                        property="Timing_Properties::Period",
                        ownedValues=[model.new("ModalPropertyValue", value=period)],
                    ),
                ],
            )
        )
    elif kind == "rename_port" and ports:
        rename_link(trace, ports[index % len(ports)], name)
    elif kind == "remove_port" and ports:
        port = ports[index % len(ports)]
        port.eContainer().featureInstances.remove(port)
    elif kind == "add_port" and threads:
        direction = "in" if counter % 2 else "out"
        threads[index % len(threads)].featureInstances.append(
            model.new(
                "FeatureInstance", name=name, feature=name, category="event data port", direction=direction
            )
        )


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(rounds=st.lists(st.lists(edit, min_size=1, max_size=4), min_size=1, max_size=3))
def test_random_model_edits_never_lose_user_code(tmp_path_factory, rounds):
    out = tmp_path_factory.mktemp("regen")
    _, instance = tracking_instance()
    generate_workspace(instance, out, options=OPTIONS)
    tokens: dict[str, str] = {}
    for path in sorted(out.rglob("*.py")):
        fill(path, tokens)
    counter = 0
    for operations in rounds:
        trace = tracing.new_trace("edit")
        for operation in operations:
            counter += 1
            _apply(instance, operation, trace, counter)
        generate_workspace(instance, out, options=OPTIONS, trace=trace)
        everything = "\n".join(p.read_text() for p in out.rglob("*.py"))
        missing = [t for t in tokens if f"{t} hand-written" not in everything]
        assert not missing, f"lost user code: {[(t, tokens[t]) for t in missing]}"
        with redirect_stdout(io.StringIO()):
            assert compileall.compile_dir(str(out), quiet=1, force=True)


def test_a_saved_rename_trace_moves_blocks(tmp_path):
    _, instance = tracking_instance()
    out = tmp_path / "src"
    generate_workspace(instance, out, options=OPTIONS)
    tokens: dict[str, str] = {}
    fill(out / TRACKER, tokens)
    before = blocks(out / TRACKER)
    edits = tracing.new_trace("edit")
    rename_link(edits, model.find_instance(instance, "rem_trk_sw.tracker.image_tracker.cb_msg"), "frames")
    saved = tracing.save_trace(edits, tmp_path / "edits.trace")
    result = generate_workspace(instance, out, options=OPTIONS, trace=saved)
    assert [(m.name, m.target_name) for m in result.moved] == [
        ("ocv_color_tracking.image_tracker.cb_msg", "ocv_color_tracking.image_tracker.frames")
    ]
    assert (
        blocks(out / TRACKER)["ocv_color_tracking.image_tracker.frames"]
        == before["ocv_color_tracking.image_tracker.cb_msg"]
    )

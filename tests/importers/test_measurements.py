"""measurements.json: the schema, the reader, and located refusals of truncated or edited files."""

from __future__ import annotations

import json

import pytest

from rosaadl.errors import ParseError
from rosaadl.importers.json_schema import schema_problems, value_lines
from rosaadl.importers.measurements import (
    Statistics,
    measurements_schema,
    parse_measurements,
    read_measurements,
)
from tests.measurements_sample import (
    tracking_measurements,
    tracking_measurements_text,
    write_tracking_measurements,
)


def test_the_sample_reads_into_typed_rows(tmp_path) -> None:
    target = write_tracking_measurements(tmp_path)
    read = read_measurements(target)
    assert read.root == "sys_tracking::tracking.impl"
    assert [t.path for t in read.threads] == [
        "rem_trk_sw.usbcam.image_broadcaster",
        "rem_trk_sw.poscmd.cmd_publisher",
    ]
    broadcaster = read.threads[0]
    assert broadcaster.execution_time_us.mean == 2330.0
    assert broadcaster.load_percent == pytest.approx(2330 / 33340 * 100)
    assert read.processes[1].core == 1
    assert read.topics[0].port == "rem_trk_sw.usbcam.image_broadcaster.pub_msg"
    assert read.chains[0].latency_us.max == 120000.0
    assert read.run_value("duration_s") == 15.0


def test_the_schema_is_versioned_and_documents_every_member() -> None:
    schema = measurements_schema()
    assert schema["properties"]["version"] == {"enum": [1, 2, 3, 4]}
    assert set(schema["$defs"]) >= {"thread", "process", "topic", "chain", "statistics"}


def test_a_truncated_file_is_refused_at_its_line(tmp_path) -> None:
    text = tracking_measurements_text()
    target = tmp_path / "measurements.json"
    target.write_text(text[: len(text) // 2])
    with pytest.raises(ParseError) as caught:
        read_measurements(target)
    assert caught.value.location.file == str(target)
    assert caught.value.location.line == len(text[: len(text) // 2].splitlines())


def test_a_hand_edited_value_is_refused_at_its_json_path_and_line() -> None:
    document = tracking_measurements()
    document["threads"][1]["dispatches"] = "many"
    text = tracking_measurements_text(document)
    with pytest.raises(ParseError) as caught:
        parse_measurements(text, "m.json")
    where = caught.value.location
    assert where.path == "$.threads[1].dispatches"
    assert text.splitlines()[where.line - 1].strip() == '"dispatches": "many",'
    assert "expected integer, found string" in caught.value.message


@pytest.mark.parametrize(
    ("edit", "path", "words"),
    [
        (lambda d: d["processes"][0].update(cpu=3), "$.processes[0].cpu", "unknown member"),
        (lambda d: d["chains"][0].pop("samples"), "$.chains[0]", "missing 'samples'"),
        (lambda d: d["topics"][0].update(rate_hz=-1), "$.topics[0].rate_hz", "below the minimum"),
        (lambda d: d.update(format="other"), "$.format", "expected"),
        (
            lambda d: d["threads"][0]["execution_time_us"].update(min=9e9),
            "$.threads[0].execution_time_us",
            "min <= mean",
        ),
        (
            lambda d: d["threads"][0].update(deadline_misses=True),
            "$.threads[0].deadline_misses",
            "found boolean",
        ),
        # what version 2 added, in a version 1 file (a hand edit), or edited wrong
        (lambda d: d["run"].update(period_scale=1.9), "$.run.period_scale", "version 2"),
        (
            lambda d: d["processes"][1].update(profile={"board": "a", "core": "b"}),
            "$.processes[1].profile",
            "version 2",
        ),
        (
            lambda d: d.update(version=2) or d["run"].update(period_scale=0),
            "$.run.period_scale",
            "not above 0",
        ),
        (
            lambda d: d.update(version=2) or d["processes"][0].update(profile={"board": "a"}),
            "$.processes[0].profile",
            "missing 'core'",
        ),
        # what version 3 added, in a version 1 or 2 file, or edited wrong
        (
            lambda d: d["threads"][1].update(dispatch_latency_us=_LATENCY),
            "$.threads[1].dispatch_latency_us",
            "a member of version 3 in a version 1 file",
        ),
        (
            lambda d: d.update(version=2) or d["threads"][0].update(dispatch_latency_us=None),
            "$.threads[0].dispatch_latency_us",
            "a member of version 3 in a version 2 file",
        ),
        (
            lambda d: (
                d.update(version=3)
                or d["threads"][0].update(dispatch_latency_us={"min": 900.0, "mean": 1000.0, "max": 800.0})
            ),
            "$.threads[0].dispatch_latency_us",
            "min <= mean <= max",
        ),
        (
            lambda d: d.update(version=3) or d["threads"][0].update(dispatch_latency_us={"min": -1}),
            "$.threads[0].dispatch_latency_us",
            "missing 'mean'",
        ),
        # what version 4 added, in a version 3 file, or edited wrong
        (
            lambda d: d.update(version=3) or d["processes"][1].update(cpu_speed=331.2),
            "$.processes[1].cpu_speed",
            "a member of version 4 in a version 3 file",
        ),
        (
            lambda d: d.update(version=3) or d["threads"][1].update(twin_execution_time_us=2210.5),
            "$.threads[1].twin_execution_time_us",
            "a member of version 4 in a version 3 file",
        ),
        (
            lambda d: d.update(version=4) or d["processes"][0].update(cpu_speed=0),
            "$.processes[0].cpu_speed",
            "not above 0",
        ),
        (
            lambda d: d.update(version=4) or d["threads"][0].update(twin_execution_time_us="all"),
            "$.threads[0].twin_execution_time_us",
            "expected number",
        ),
    ],
)
def test_edits_that_break_the_schema_are_located(edit, path, words) -> None:
    document = tracking_measurements()
    edit(document)
    with pytest.raises(ParseError) as caught:
        parse_measurements(tracking_measurements_text(document), "m.json")
    assert caught.value.location.path == path
    assert caught.value.location.line is not None
    assert words in caught.value.message


def test_an_unknown_version_is_named() -> None:
    document = tracking_measurements()
    document["version"] = 5
    with pytest.raises(ParseError, match=r"version 5 is not known \(this release reads 1, 2, 3 and 4\)"):
        parse_measurements(json.dumps(document))


def test_version_2_records_the_period_scale_and_the_profile_of_each_process() -> None:
    document = tracking_measurements()
    document["version"] = 2
    document["run"]["period_scale"] = 1.9
    document["processes"][0]["profile"] = {"board": "xu4", "core": "a15"}
    read = parse_measurements(tracking_measurements_text(document))
    assert read.period_scale == 1.9
    assert read.processes[0].profile == ("xu4", "a15") and read.processes[1].profile is None


_LATENCY = {"min": 612.5, "mean": 1034.25, "max": 4871.2}


def test_version_4_records_the_twin_s_time_and_the_speed_of_each_process_s_cpus() -> None:
    document = tracking_measurements()
    document["version"] = 4
    document["threads"][0]["twin_execution_time_us"] = 2210.5
    document["processes"][0]["cpu_speed"] = 331.2
    read = parse_measurements(tracking_measurements_text(document))
    assert [t.twin_execution_time_us for t in read.threads] == [2210.5, None]
    assert [p.cpu_speed for p in read.processes] == [331.2, None]


def test_version_3_records_the_dispatch_latency_of_timer_threads() -> None:
    document = tracking_measurements()
    document["version"] = 3
    document["threads"][0]["dispatch_latency_us"] = _LATENCY
    document["threads"][1]["dispatch_latency_us"] = None  # a timer thread never released idle
    read = parse_measurements(tracking_measurements_text(document))
    assert read.threads[0].dispatch_latency_us == Statistics(612.5, 1034.25, 4871.2)
    assert read.threads[1].dispatch_latency_us is None


def test_a_version_2_file_still_reads_without_dispatch_latencies() -> None:
    document = tracking_measurements()
    document["version"] = 2
    read = parse_measurements(tracking_measurements_text(document))
    assert [t.dispatch_latency_us for t in read.threads] == [None, None]


def test_a_version_3_member_in_a_version_2_file_is_refused_at_its_line() -> None:
    document = tracking_measurements()
    document["version"] = 2
    document["threads"][1]["dispatch_latency_us"] = _LATENCY
    text = tracking_measurements_text(document)
    with pytest.raises(ParseError) as caught:
        parse_measurements(text, "m.json")
    where = caught.value.location
    assert (where.file, where.path) == ("m.json", "$.threads[1].dispatch_latency_us")
    assert text.splitlines()[where.line - 1].strip() == '"dispatch_latency_us": {'


def test_a_version_1_file_still_reads_unscaled() -> None:
    read = parse_measurements(tracking_measurements_text())
    assert read.period_scale == 1.0 and read.processes[0].profile is None


def test_every_problem_is_listed() -> None:
    document = tracking_measurements()
    document["threads"][0]["dispatches"] = -1
    document["topics"][0]["messages"] = 1.5
    with pytest.raises(ParseError) as caught:
        parse_measurements(json.dumps(document, indent=1))
    assert [e.location.path for e in caught.value.errors] == [
        "$.threads[0].dispatches",
        "$.topics[0].messages",
    ]


@pytest.mark.parametrize(
    "text", ["", "[]", "null", "{" * 100_000, '{"format": "rosaadl-measurements"', "\ufeff{}"]
)
def test_hostile_texts_give_a_parse_error(text) -> None:
    with pytest.raises(ParseError):
        parse_measurements(text)


def test_value_lines_follow_nesting_and_odd_keys() -> None:
    text = '{\n "a": [1,\n {"b": 2, "c": [3,\n 4]}],\n "d x": null\n}'
    assert value_lines(text) == {
        "$": 1, "$.a": 2, "$.a[0]": 2, "$.a[1]": 3, "$.a[1].b": 3, "$.a[1].c": 3,
        "$.a[1].c[0]": 3, "$.a[1].c[1]": 4, '$["d x"]': 5,
    }  # fmt: skip


def test_schema_problems_know_integers_and_booleans() -> None:
    schema = {"type": "integer"}
    assert list(schema_problems(3.0, schema)) == []
    assert list(schema_problems(True, schema)) == [("$", "expected integer, found boolean")]

"""Input at fault is a located error with exit 1, never an internal error: comments and
processing instructions inside an ``.xmi``, numbers that are not numbers or do not fit, JSON with
integers past Python's conversion limit or nested beyond reason, a corrupted generation trace."""

from __future__ import annotations

import json
import re
import shutil
import zipfile
from pathlib import Path

import pytest

from rosaadl import model
from rosaadl.cli import main
from rosaadl.exporters.rclpy import MANIFEST_NAME

ROOT = Path(__file__).resolve().parents[2]
TRACKING = ROOT / "examples" / "tracking"
SYSTEMS = ROOT / "library" / "systems"
LONG_INT = "9" * 5_000


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def assert_located_failure(args: list[str], capsys, file: Path, *words: str) -> str:
    """Exit 1, no traceback, an error line naming ``file`` (with a line or a path) and ``words``."""
    code, out, err = run(args, capsys)
    text = out + err
    assert code == 1, text
    assert "Traceback" not in text and "internal error" not in text, text
    (line,) = [x for x in text.splitlines() if x.startswith("error:")]
    assert f"{file.name}" in line, line
    for word in words:
        assert word in line, line
    return line


@pytest.fixture(scope="module")
def tracking_files(tmp_path_factory) -> tuple[bytes, bytes]:
    """The tracking example imported as XMI and as JSON."""
    folder = tmp_path_factory.mktemp("tracking")
    assert main(["import", str(TRACKING), "-o", str(folder / "t.xmi")]) == 0
    assert main(["import", str(TRACKING), "-o", str(folder / "t.json")]) == 0
    return (folder / "t.xmi").read_bytes(), (folder / "t.json").read_bytes()


# --------------------------------------------------------------------------- .xmi


@pytest.mark.parametrize("insert", ["<!-- a comment -->", "<?editor fold?>", "<!-- a --><?pi x?><!-- b -->"])
@pytest.mark.parametrize("before", ["<software ", "<fields "])
def test_xmi_comments_and_processing_instructions_are_skipped(
    tmp_path, capsys, tracking_files, insert, before
):
    xmi, _ = tracking_files
    path = tmp_path / "c.xmi"
    path.write_bytes(xmi.replace(before.encode(), (insert + before).encode(), 1))
    code, out, err = run(["check", str(path)], capsys)
    assert code == 0 and out.strip() == f"{path}: ok", out + err
    assert model.model_equal(model.load(path), model.loads_xmi(xmi))


@pytest.mark.parametrize(
    ("attribute", "value", "words"),
    [
        ("arrayLength", "NaN", ["fields", "NaN"]),
        ("arrayLength", "", ["fields"]),
        ("arrayLength", "1e309", ["fields", "1e309"]),
        ("arrayLength", "x", ["fields", "'x'"]),
        ("arrayLength", "2147483648", ["fields", "out of range"]),
        ("arrayLength", LONG_INT, ["fields"]),
        ("deadline", "NaN", ["finite", "NaN"]),
        ("deadline", "-Infinity", ["finite"]),
        ("deadline", "x", ["'x'"]),
        ("deadline", "", ["timers"]),
    ],
)
def test_xmi_numbers_that_are_not_numbers_or_do_not_fit(
    tmp_path, capsys, tracking_files, attribute, value, words
):
    xmi, _ = tracking_files
    text, count = re.subn(rf'{attribute}="[^"]*"', f'{attribute}="{value}"', xmi.decode(), count=1)
    assert count == 1
    path = tmp_path / "bad.xmi"
    path.write_text(text)
    line = assert_located_failure(["check", str(path)], capsys, path, *words)
    assert re.search(r"bad\.xmi:\d+ /rosmod:Project/", line), line


# --------------------------------------------------------------------------- .json


def _json_with(json_text: bytes, value: str) -> str:
    text, count = re.subn(r'"arrayLength": \d+', f'"arrayLength": {value}', json_text.decode(), count=1)
    assert count == 1
    return text


@pytest.mark.parametrize(
    ("value", "words"),
    [
        (LONG_INT, ["5000 digits"]),
        ("-" + LONG_INT, ["5000 digits"]),
        ("NaN", ["NaN is not a JSON number"]),
        ("Infinity", ["Infinity is not a JSON number"]),
        ("99999999999", ["Field", "arrayLength 99999999999 is out of range"]),
    ],
)
def test_json_numbers_beyond_limits(tmp_path, capsys, tracking_files, value, words):
    _, json_text = tracking_files
    path = tmp_path / "bad.json"
    path.write_text(_json_with(json_text, value))
    assert_located_failure(["check", str(path)], capsys, path, *words)


@pytest.mark.parametrize("payload", ["[" * 100_000 + "]" * 100_000, '{"eClass": ' + "[" * 100_000])
def test_json_nested_beyond_reason(tmp_path, capsys, payload):
    path = tmp_path / "deep.json"
    path.write_text(payload)
    assert_located_failure(["check", str(path)], capsys, path, "nested too deeply")


# --------------------------------------------------------------------------- ROSMOD v0.4 and .webgmex


@pytest.mark.parametrize("value", [LONG_INT, "[" * 100_000 + "]" * 100_000])
def test_rosmod_v04_with_an_integer_past_the_limit(tmp_path, capsys, value):
    folder = tmp_path / "v04"
    folder.mkdir()
    (folder / "x.rml").write_text('{"py/object": "__main__.Project",\n "children": ' + value + "}")
    out = tmp_path / "out.xmi"
    line = assert_located_failure(["import", str(folder), "-o", str(out)], capsys, folder / "x.rml")
    assert "digits" in line or "nested too deeply" in line
    assert not out.exists()


def test_webgmex_with_an_integer_past_the_limit(tmp_path, capsys):
    path = tmp_path / "big.webgmex"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("project.json", '{"rootHash": "#1", "objects": [], "n": ' + LONG_INT + "}")
    out = tmp_path / "out.xmi"
    assert_located_failure(["import", str(path), "-o", str(out)], capsys, path, "project.json", "5000 digits")
    assert_located_failure(["check", str(path)], capsys, path, "5000 digits")
    assert not out.exists()


# --------------------------------------------------------------------------- generation trace


@pytest.mark.parametrize(
    "payload",
    [
        b'{"links": ' + b"[" * 100_000 + b"]" * 100_000 + b"}",
        b'{"links": [], "n": ' + LONG_INT.encode() + b"}",
        b"\xff\xfe{",
        b'{"links": [{"rule": "file", "targets": [5]}]}',
        b'{"links": [',
    ],
)
def test_a_corrupted_generation_trace_is_a_located_error_with_the_way_on(tmp_path, capsys, payload):
    out = tmp_path / "ws" / "src"
    args = ["generate", "rclpy", str(SYSTEMS), "--root", "sys_rover::rover.impl", "-o", str(out)]
    assert run(args, capsys)[0] == 0
    (out / MANIFEST_NAME).write_bytes(payload)
    before = {p: p.read_bytes() for p in out.rglob("*") if p.is_file()}
    code, stdout, err = run(args, capsys)
    text = stdout + err
    assert code == 1 and "Traceback" not in text and "internal error" not in text, text
    (line,) = [x for x in text.splitlines() if "trace is unreadable" in x]
    assert line.startswith(f"error: {out / MANIFEST_NAME}:"), line
    assert "delete it to regenerate without it" in line and "restore the file" in line
    assert {p: p.read_bytes() for p in out.rglob("*") if p.is_file()} == before  # nothing written
    (out / MANIFEST_NAME).unlink()
    assert run(args, capsys)[0] == 0
    json.loads((out / MANIFEST_NAME).read_text())  # the next trace is whole again


# --------------------------------------------------------------------------- ROSMOD times out of range

_V01 = """workspace WS;
package robot
{
    components
    {
        component Sensor
        {
            timer Sample { period = PERIOD; }
        }
    }
}
"""


def _v04_project(period: object) -> str:
    def element(kind: str, name: str, children: list, **attributes: object) -> dict:
        pairs = [["name", name], *([key, value] for key, value in attributes.items())]
        return {
            "py/object": f"__main__.{kind}",
            "attributes": {"__reduce__": [{}, {"py/tuple": [pairs]}]},
            "children": {"_inner": children},
        }

    timer = element("Timer", "tick", [], period=period, priority=50)
    component = element("Component", "Sensor", [timer])
    software = element("Software", "sw", [element("Package", "robot", [component])])
    return json.dumps(element("Project", "p", [software]), indent=1)


@pytest.mark.parametrize(
    ("period", "words"),
    [
        ("1e309", ["out of range", "at most 1.798e+308 s"]),
        ("1e-400", ["out of range", "at least"]),
    ],
)
@pytest.mark.parametrize("dialect", ["v0.1", "v0.2", "v0.3"])
def test_rosmod_text_time_out_of_the_float_range(tmp_path, capsys, dialect, period, words):
    """A time that overflows to infinity (or underflows to zero) as a float is a located error."""
    if dialect == "v0.1":
        given = path = tmp_path / "input.rosml"
        path.write_text(_V01.replace("PERIOD", period))
    elif dialect == "v0.2":
        given = tmp_path / "v02"
        given.mkdir()
        path = given / "workspace.rml"
        path.write_text(_V01.removeprefix("workspace WS;\n").replace("PERIOD", period + "s"))
    else:
        given = tmp_path / "tracking"
        shutil.copytree(TRACKING, given)
        path = given / "01-Software" / "tracking.rml"
        text, count = re.subn(r"period = [\d.]+;", f"period = {period};", path.read_text(), count=1)
        assert count == 1
        path.write_text(text)
    out = tmp_path / "out.xmi"
    line = assert_located_failure(["import", str(given), "-o", str(out)], capsys, path, "period", *words)
    assert re.search(rf"{path.name}:\d+:\d+: ", line), line
    assert not out.exists()


@pytest.mark.parametrize(
    ("period", "words"),
    [
        ('"1e309"', ["out of range"]),
        ("1e309", ["expected a finite number of seconds"]),  # JSON reads it as infinity
        ('"NaN"', ["expected a finite number of seconds"]),
        ('"-1"', ["must not be negative"]),
        ('"1e-400"', ["out of range"]),
    ],
)
def test_rosmod_v04_time_out_of_range(tmp_path, capsys, period, words):
    folder = tmp_path / "v04"
    folder.mkdir()
    text = _v04_project("PERIOD").replace('"PERIOD"', period)
    (folder / "x.rml").write_text(text)
    out = tmp_path / "out.xmi"
    line = assert_located_failure(["import", str(folder), "-o", str(out)], capsys, folder / "x.rml", *words)
    assert "Project/robot/Sensor/tick" in line, line
    assert not out.exists()


def test_rosmod_v04_time_in_range_is_read(tmp_path, capsys):
    folder = tmp_path / "v04"
    folder.mkdir()
    (folder / "x.rml").write_text(_v04_project("1e300"))
    assert run(["check", str(folder)], capsys)[0] == 0

"""The command line: verbs, global options, exit codes, the JSON document, located errors."""

from __future__ import annotations

import json
import subprocess
import sys

import click
import pytest

from rosaadl import __version__, model
from rosaadl.cli import cli, main

VERBS = ["check", "import", "convert", "instantiate", "analyze", "export", "generate", "library", "demo"]


def run_main(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_help_lists_every_verb(capsys) -> None:
    code, out, _ = run_main(["--help"], capsys)
    assert code == 0
    for verb in VERBS:
        assert f"  {verb} " in out


def test_version(capsys) -> None:
    code, out, _ = run_main(["--version"], capsys)
    assert code == 0 and __version__ in out


@pytest.mark.parametrize(
    "args", [["--bogus"], ["check"], ["no-such-verb"], ["--format", "yaml", "check", "x"]]
)
def test_usage_errors_exit_2(args, capsys) -> None:
    code, _, err = run_main(args, capsys)
    assert code == 2 and err


def _good_model(tmp_path):
    ws = model.new("AadlModel", name="ws", units=[model.new("AadlPackage", name="p")])
    return model.save(ws, tmp_path / "good.xmi"), model.save(ws, tmp_path / "good.json")


def test_check_good_files(tmp_path, capsys) -> None:
    xmi, js = _good_model(tmp_path)
    code, out, err = run_main(["check", str(xmi), str(js)], capsys)
    assert code == 0, err
    assert f"{xmi}: ok" in out


def test_check_truncated_file_names_file_and_line(tmp_path, capsys) -> None:
    xmi, _ = _good_model(tmp_path)
    broken = tmp_path / "broken.xmi"
    data = xmi.read_bytes()
    broken.write_bytes(data[: len(data) // 2])
    code, out, err = run_main(["check", str(broken)], capsys)
    assert code == 1
    assert f"{broken}:" in err and "malformed XML" in err
    code, out, err = run_main(["--format", "json", "check", str(broken)], capsys)
    assert code == 1
    doc = json.loads(out)
    assert doc["ok"] is False and doc["warnings"] == []
    (error,) = doc["errors"]
    assert error["file"] == str(broken) and isinstance(error["line"], int) and error["line"] >= 1
    assert {"message", "file", "line", "path"} <= set(error)


def test_check_json_document_when_ok(tmp_path, capsys) -> None:
    xmi, js = _good_model(tmp_path)
    code, out, _ = run_main(["--format", "json", "check", str(xmi), str(js)], capsys)
    doc = json.loads(out)
    assert code == 0 and doc["ok"] is True and doc["errors"] == []
    assert [f["file"] for f in doc["files"]] == [str(xmi), str(js)]


def test_check_invalid_model_is_exit_1(tmp_path, capsys) -> None:
    unnamed = model.save(model.new("AadlModel", units=[model.new("AadlPackage")]), tmp_path / "unnamed.json")
    code, _, err = run_main(["check", str(unnamed)], capsys)
    assert code == 1 and "has no name" in err


def test_check_missing_file_and_unknown_type(tmp_path, capsys) -> None:
    code, _, err = run_main(["check", str(tmp_path / "nope.xmi")], capsys)
    assert code == 2 and "no such file" in err
    other = tmp_path / "notes.txt"
    other.write_text("hi")
    code, _, err = run_main(["check", str(other)], capsys)
    assert code == 2 and "no reader" in err


def test_internal_errors_exit_3_without_traceback_unless_debug(capsys) -> None:
    @click.command("explode")
    def explode() -> None:
        raise KeyError("boom")

    cli.add_command(explode)
    try:
        code, _, err = run_main(["explode"], capsys)
        assert code == 3 and "internal error" in err and "Traceback" not in err
        code, _, err = run_main(["--debug", "explode"], capsys)
        assert code == 3 and "Traceback" in err
        code, _, err = run_main(["explode", "--debug"], capsys)  # after the verb, too
        assert code == 3 and "Traceback" in err
    finally:
        cli.commands.pop("explode")


def test_console_script_runs_as_a_process(tmp_path) -> None:
    xmi, _ = _good_model(tmp_path)
    proc = subprocess.run(
        [sys.executable, "-m", "rosaadl", "check", str(xmi)], capture_output=True, text=True
    )
    assert proc.returncode == 0, proc.stderr

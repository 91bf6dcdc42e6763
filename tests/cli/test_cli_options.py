"""The run options ``--format`` and ``--debug``: before the verb, or after it, for every verb."""

from __future__ import annotations

import json
from pathlib import Path

import click
import pytest

from rosaadl import model
from rosaadl.cli import cli, main


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def _command_paths(group: click.Group, prefix: tuple[str, ...] = ()) -> list[tuple[str, ...]]:
    """Every verb and sub-verb of the command line, as the words that name it."""
    paths = []
    for name, command in sorted(group.commands.items()):
        paths.append((*prefix, name))
        if isinstance(command, click.Group):
            paths.extend(_command_paths(command, (*prefix, name)))
    return paths


COMMANDS = _command_paths(cli)


def test_every_verb_and_sub_verb_is_listed() -> None:
    assert ("check",) in COMMANDS and ("export", "aaxl2") in COMMANDS and ("library", "list") in COMMANDS
    assert len(COMMANDS) >= 15


@pytest.mark.parametrize("words", COMMANDS, ids=[" ".join(w) for w in COMMANDS])
@pytest.mark.parametrize("options", [["--format", "json"], ["--format=text"], ["--debug"]])
def test_run_options_are_accepted_after_every_verb(words, options, capsys) -> None:
    code, out, err = run([*words, *options, "--help"], capsys)
    assert code == 0, err
    assert "--format [text|json]" in out and "--debug" in out


def _good_model(tmp_path: Path) -> Path:
    ws = model.new("AadlModel", name="ws", units=[model.new("AadlPackage", name="p")])
    return model.save(ws, tmp_path / "good.xmi")


def test_format_after_the_verb_gives_the_json_document(tmp_path, capsys) -> None:
    good = _good_model(tmp_path)
    code, out, err = run(["check", str(good), "--format", "json"], capsys)
    assert code == 0, err
    assert json.loads(out)["ok"] is True
    code, out, _ = run(["check", "--format=json", str(good)], capsys)
    assert code == 0 and json.loads(out)["files"] == [{"file": str(good), "errors": 0, "warnings": 0}]


def test_format_after_the_verb_wins_over_the_one_before(tmp_path, capsys) -> None:
    good = _good_model(tmp_path)
    code, out, _ = run(["--format", "json", "check", str(good), "--format", "text"], capsys)
    assert code == 0 and out.startswith(f"{good}: ok")
    code, out, _ = run(["--format", "text", "check", str(good), "--format", "json"], capsys)
    assert code == 0 and json.loads(out)["ok"] is True


def test_a_bad_format_after_the_verb_is_a_usage_error(tmp_path, capsys) -> None:
    code, _, err = run(["check", str(_good_model(tmp_path)), "--format", "yaml"], capsys)
    assert code == 2 and "yaml" in err


def test_sub_verbs_take_them_too(tmp_path, capsys) -> None:
    code, out, err = run(["library", "show", "ros", "--format", "json"], capsys)
    assert code == 0, err
    assert json.loads(out)["ok"] is True
    code, out, err = run(["export", "aadl", str(_good_model(tmp_path)), "-o", str(tmp_path / "o")], capsys)
    assert code == 0, err
    code, out, err = run(
        ["export", "aadl", str(_good_model(tmp_path)), "-o", str(tmp_path / "o"), "--format", "json"], capsys
    )
    assert code == 0, err
    assert json.loads(out)["ok"] is True

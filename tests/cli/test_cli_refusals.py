"""Inputs the command line refuses with a located reason and exit code 1, never a usage error
(exit 2) nor a success that wrote nothing."""

from __future__ import annotations

from pathlib import Path

import pytest

from rosaadl.cli import main
from tests.importers.test_aaxl2 import GOOD, D, _replace
from tests.importers.test_rosmod_webgme import _n, build_export, write_export


def run(args: list[str], capsys) -> tuple[int, str, str]:
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def _no_project_reasons(archive: Path, tmp_path: Path, capsys) -> None:
    out = tmp_path / "out"
    for args in (["check", str(archive)], ["convert", str(archive), "-o", str(out)]):
        code, _, err = run(args, capsys)
        assert code == 1, (args, err)
        assert f"error: {archive}: the archive holds no ROSMOD project" in err
    assert not out.exists()


def test_webgmex_without_a_project_is_refused_by_check_and_convert(tmp_path: Path, capsys) -> None:
    """A ``.webgmex`` whose tree holds a META but no node of type Project: nothing to read."""
    archive = write_export(tmp_path / "empty.webgmex", build_export(_n("Projects", "Ps", {})))
    _no_project_reasons(archive, tmp_path, capsys)


@pytest.mark.corpus
def test_meta_only_webgmex_is_refused_by_check_and_convert(corpus: Path, tmp_path: Path, capsys) -> None:
    _no_project_reasons(corpus / "rosmod/webgme/meta-2018-07.webgmex", tmp_path, capsys)


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("@ownedPropertyType.16/", "@ownedPropertyType.-1/"),  # a predeclared unit's href
        ("@ownedLiteral.2", "@ownedLiteral.1_0"),
        (f"{D}0/@ownedDataPort.0", f"{D}0/@ownedDataPort.-1"),  # a link into the declarative model
    ],
)
def test_aaxl2_positions_that_are_not_list_indexes_are_located_errors(
    old: str, new: str, tmp_path: Path, capsys
) -> None:
    """EMF reads ``@feature.k`` with ``Integer.parseInt``: ``-1`` and ``1_0`` name no item."""
    path = tmp_path / "bad_Instance.aaxl2"
    path.write_bytes(_replace(GOOD, old, new))
    code, _, err = run(["check", str(path)], capsys)
    assert code == 1, err
    position = new.rpartition(".")[2].rstrip("/")
    assert f"error: {path}:" in err and f"position {position!r}" in err and "/@href" in err


CYCLIC_CONSTANTS = """property set Cyc is
  A : constant aadlinteger => Cyc::B;
  B : constant aadlinteger => Cyc::A;
  Alone : constant aadlinteger => 3;
  Uses : constant list of aadlinteger => (Cyc::Alone, 4);
  Self : constant aadlinteger => 1 .. Cyc::Self;
end Cyc;
"""


def test_cyclic_property_constants_are_reported_at_check_with_the_cycle(tmp_path: Path, capsys) -> None:
    path = tmp_path / "cyc.aadl"
    path.write_text(CYCLIC_CONSTANTS)
    code, _, err = run(["check", str(path)], capsys)
    assert code == 1, err
    assert (
        f"{path}:2:3 Cyc::A: error: property constants defined in a cycle: Cyc::A => Cyc::B; Cyc::B => Cyc::A"
        in err
    )
    assert (
        f"{path}:6:3 Cyc::Self: error: property constants defined in a cycle: Cyc::Self => Cyc::Self" in err
    )
    assert err.count("cycle") == 2  # Alone and Uses are no cycle


SECRET = "package Secret\npublic\n  system S\n  SECRET_LINE is here;\nend Secret;\n"


def test_a_syntax_error_in_a_file_linked_from_outside_the_input_quotes_none_of_it(
    tmp_path: Path, capsys
) -> None:
    """The error names the link and its line, never the outside file's text."""
    outside, project = tmp_path / "outside", tmp_path / "project"
    outside.mkdir()
    project.mkdir()
    (outside / "secret.aadl").write_text(SECRET)
    (project / "linked.aadl").symlink_to(outside / "secret.aadl")
    (project / "folder").symlink_to(outside, target_is_directory=True)
    for given, named in (
        (project, project / "linked.aadl"),
        (project / "linked.aadl", project / "linked.aadl"),
        (project / "folder", project / "folder" / "secret.aadl"),
    ):
        code, out, err = run(["check", str(given)], capsys)
        assert code == 1, err
        assert f"error: {named}:4:3: unexpected text (not shown" in err
        assert "SECRET" not in err + out and "'S'" not in err
    code, _, err = run(["check", str(outside / "secret.aadl")], capsys)  # inside what was given
    assert code == 1 and "unexpected 'SECRET_LINE' after 'S'" in err

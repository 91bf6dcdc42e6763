"""All-or-nothing multi-file writes, short temporaries, the user's umask, stale temporaries."""

from __future__ import annotations

import os
import stat
import subprocess
import sys

import pytest

from rosaadl import fileio
from rosaadl.errors import ExportError
from rosaadl.fileio import atomic_write_text


def _dead_pid() -> int:
    """The id of a process that has ended (and was reaped)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_a_failure_on_the_sixth_file_leaves_none_written(tmp_path) -> None:
    (tmp_path / "f6.txt").mkdir()  # a folder where the sixth file goes
    files = [(tmp_path / f"f{index}.txt", f"text {index}") for index in range(1, 9)]
    with pytest.raises(ExportError, match="folder") as info:
        fileio.write_files(files)
    assert info.value.location.file == str(tmp_path / "f6.txt")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f6.txt"]


def test_a_refused_rename_puts_back_the_files_already_renamed(tmp_path) -> None:
    """The sixth name is too long for the file system: only its rename fails (the temporary
    has a short name), and the five renamed before it are put back as they were."""
    for index in (1, 3):
        (tmp_path / f"f{index}.txt").write_text("old")
    files = [(tmp_path / f"f{index}.txt", "new") for index in range(1, 6)]
    files.append((tmp_path / ("x" * 300), "new"))
    with pytest.raises(ExportError, match="too long"):
        fileio.write_files(files, workers=4)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f1.txt", "f3.txt"]
    assert (tmp_path / "f1.txt").read_text() == "old" == (tmp_path / "f3.txt").read_text()


def test_write_files_writes_every_file_in_threads(tmp_path) -> None:
    files = [(tmp_path / "sub" / f"f{index}.bin", bytes([index])) for index in range(40)]
    assert fileio.write_files(files, workers=8) == [target for target, _ in files]
    assert all(target.read_bytes() == data for target, data in files)
    assert sorted(p.name for p in (tmp_path / "sub").iterdir()) == sorted(f"f{i}.bin" for i in range(40))


def test_a_name_within_14_characters_of_the_limit_is_written(tmp_path) -> None:
    limit = os.pathconf(tmp_path, "PC_NAME_MAX")
    for name in ("a" * (limit - 14), "b" * limit):
        atomic_write_text(tmp_path / name, "ok")
        assert (tmp_path / name).read_text() == "ok"
    fileio.write_files([(tmp_path / ("c" * (limit - 1)), "ok"), (tmp_path / ("d" * limit), b"ok")])
    assert len(list(tmp_path.iterdir())) == 4


def test_outputs_get_the_users_umask(tmp_path) -> None:
    previous = os.umask(0o022)
    try:
        atomic_write_text(tmp_path / "one.txt", "x")
        fileio.write_files([(tmp_path / "two.txt", "x"), (tmp_path / "three.bin", b"x")])
        os.umask(0o077)
        atomic_write_text(tmp_path / "private.txt", "x")
    finally:
        os.umask(previous)
    for name in ("one.txt", "two.txt", "three.bin"):
        assert stat.S_IMODE((tmp_path / name).stat().st_mode) == 0o644, name
    assert stat.S_IMODE((tmp_path / "private.txt").stat().st_mode) == 0o600


def test_stale_temporaries_of_our_naming_are_swept(tmp_path) -> None:
    dead = tmp_path / f".rosaadl-{_dead_pid()}-0123456789ab.tmp"
    alive = tmp_path / f".rosaadl-{os.getppid()}-0123456789ab.tmp"  # a running writer
    legacy = tmp_path / ".out.aaxl2.k3j_x9a2.tmp"  # tempfile.mkstemp's name, of earlier versions
    foreign = [tmp_path / ".other.k3j_x9a2.tmp", tmp_path / ".rosaadl-notes.tmp", tmp_path / "keep.tmp"]
    for path in (dead, alive, legacy, *foreign):
        path.write_text("partial")
    fileio.write_files([(tmp_path / "out.aaxl2", "x")])
    left = {p.name for p in tmp_path.iterdir()}
    assert left == {"out.aaxl2", alive.name, *(p.name for p in foreign)}


def test_an_interrupt_while_writing_leaves_no_temporary(tmp_path, monkeypatch) -> None:
    """An interrupt on the fourth file's sync: the three temporaries written before it and the
    fourth are removed, and no target was renamed into place."""
    synced = []
    real_fsync = os.fsync

    def fsync(fd: int) -> None:
        synced.append(fd)
        if len(synced) == 4:
            raise KeyboardInterrupt
        real_fsync(fd)

    monkeypatch.setattr(os, "fsync", fsync)
    with pytest.raises(KeyboardInterrupt):
        fileio.write_files([(tmp_path / f"f{index}.txt", "x") for index in range(6)])
    assert list(tmp_path.iterdir()) == []

"""The writers of xroute.atomic_files beside atomic_write_bytes: a serialiser's output, a copy, and a
log of lines that is whole at every moment."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from xroute.atomic_files import AtomicLog, atomic_copy, atomic_write_from


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def test_a_serialisers_output_is_published_whole(tmp_path: Path) -> None:
    path = tmp_path / "a.npz"
    atomic_write_from(path, lambda f: np.savez_compressed(f, x=np.arange(5)))
    assert list(np.load(path)["x"]) == [0, 1, 2, 3, 4]

    def broken(f) -> None:
        f.write(b"half")
        raise RuntimeError("serialiser failed")

    with pytest.raises(RuntimeError):
        atomic_write_from(path, broken)
    assert list(np.load(path)["x"]) == [0, 1, 2, 3, 4] and not leftovers(tmp_path)  # the old file stays


def test_a_copy(tmp_path: Path) -> None:
    (tmp_path / "src.lef").write_bytes(b"VERSION 5.8 ;\n")
    atomic_copy(tmp_path / "src.lef", tmp_path / "dst.lef")
    assert (tmp_path / "dst.lef").read_bytes() == b"VERSION 5.8 ;\n" and not leftovers(tmp_path)


def test_a_log_is_published_on_open_after_each_interval_and_on_close(tmp_path: Path) -> None:
    path = tmp_path / "metrics.jsonl"
    with AtomicLog(path, interval=0.0) as log:  # every line published at once
        assert path.read_text() == ""
        log.write_line("1")
        log.write_line("2")
        assert path.read_text() == "1\n2\n"
    slow = AtomicLog(path, interval=3600.0)  # nothing but the opening and the closing
    slow.write_line("a")
    assert path.read_text() == ""
    slow.close()
    assert path.read_text() == "a\n" and not leftovers(tmp_path)


def test_a_log_keeps_its_lines_when_the_run_fails(tmp_path: Path) -> None:
    path = tmp_path / "metrics.jsonl"
    with pytest.raises(ValueError), AtomicLog(path, interval=3600.0) as log:
        log.write_line("episode 1")
        raise ValueError("training failed")
    assert path.read_text() == "episode 1\n"

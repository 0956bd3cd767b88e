"""bench/real_designs.py's manifest and file fetching (the routing itself is the bench's, not a test's)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from conftest import load_file

bench = load_file("bench/real_designs.py")
MANIFEST = Path(__file__).resolve().parents[1] / "bench" / "real_designs.tsv"


def test_the_shipped_manifest_names_repository_commit_and_paths() -> None:
    rows = bench.read_manifest(MANIFEST)
    assert len(rows) >= 6
    assert len({r["id"] for r in rows}) == len(rows)
    for r in rows:
        assert re.fullmatch(r"[0-9a-f]{40}", r["commit"]), r["id"]
        assert re.fullmatch(r"[\w.-]+/[\w.-]+", r["repo"]), r["id"]
        assert r["def"].endswith((".def", ".defok", ".def.gz")) and r["lefs"], r["id"]
        assert all(not p.startswith("/") and ".." not in p for p in bench.paths_of(r)), r["id"]
    assert {r["pdk"] for r in rows} >= {"Nangate45", "sky130hd", "sky130hs", "asap7"}


def test_a_malformed_line_names_the_file_and_line(tmp_path: Path) -> None:
    bad = tmp_path / "m.tsv"
    bad.write_text("# comment\nid\tpdk\n" + "\t".join(["a"] * 9) + "\n" + "only\tthree\tfields\n")
    with pytest.raises(SystemExit, match=rf"error: {re.escape(str(bad))}:4: 3 fields, expected 9"):
        bench.read_manifest(bad)


def git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True, text=True).stdout


def test_files_come_from_a_clone_at_the_commit_with_links_followed(tmp_path: Path) -> None:
    repo = tmp_path / "repo"
    (repo / "test" / "tech").mkdir(parents=True)
    (repo / "test" / "tech" / "cells.lef").write_text("cells v1\n")
    (repo / "src").mkdir()
    (repo / "src" / "d.def").write_text("def v1\n")
    (repo / "src" / "tech").symlink_to("../test/tech")
    git(repo, "init", "-q")
    git(repo, "add", "-A")
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "one")
    commit = git(repo, "rev-parse", "HEAD").strip()
    (repo / "src" / "d.def").write_text("def v2\n")  # a later change the manifest's commit does not have
    git(repo, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qam", "two")
    row = {"id": "d", "commit": commit, "def": "src/d.def", "lefs": "src/tech/cells.lef", "guide": "-",
           "openroad": "-"}
    root = tmp_path / "root"
    assert bench.ensure_files(row, root, repo / ".git") is None
    assert (root / "src" / "d.def").read_text() == "def v1\n"
    assert (root / "src" / "tech" / "cells.lef").read_text() == "cells v1\n"
    missing = dict(row, guide="src/d.guide")
    assert bench.ensure_files(missing, root, repo / ".git") == f"src/d.guide not under {root} nor in {repo / '.git'}"
    assert bench.ensure_files(missing, tmp_path / "other", None).endswith("(give --git-dir)")

"""bench/pdk_rules.py: the rules a technology states, each checked, read for the router only, or not modelled."""

from __future__ import annotations

import json
from pathlib import Path

from conftest import load_file

bench = load_file("bench/pdk_rules.py")
DEMO = Path(__file__).resolve().parents[1] / "testcases" / "data" / "demo"


def test_each_rule_of_the_demo_with_minstep_added_has_its_status(tmp_path: Path, capsys) -> None:
    root = tmp_path / "root"
    root.mkdir()
    lef = (DEMO / "demo.lef").read_text()
    assert lef.count("  MINWIDTH 0.0700 ;") >= 2
    lef = lef.replace("  MINWIDTH 0.0700 ;", "  MINWIDTH 0.0700 ;\n  MINSTEP 0.05 ;", 2)
    (root / "demo.lef").write_text(lef)
    (root / "demo.def").write_text((DEMO / "demo.def").read_text())
    manifest = tmp_path / "m.tsv"
    manifest.write_text("\t".join(["demo", "demo", "owner/repo", "0" * 40, "demo.def", "demo.lef", "-", "-", "n"]) + "\n")
    out = tmp_path / "rules.json"
    assert bench.main(["--manifest", str(manifest), "--root", str(root), "--json", str(out)]) == 0
    [report] = json.loads(out.read_text())
    by_rule = {r["rule"]: r for r in report["rules"]}
    assert by_rule["MINSTEP"] == {"rule": "MINSTEP", "status": "not modelled", "layers": ["Metal1", "Metal2"]}
    assert by_rule["MINWIDTH"]["status"] == "router only"
    assert by_rule["SPACING"]["status"] == "checked" and "Metal1" in by_rule["SPACING"]["layers"]
    checked = {r["rule"] for r in report["rules"] if r["status"] == "checked"}
    assert report["counts"] == {"checked": len(checked), "router only": 1, "not modelled": 1}
    assert {"SPACING", "MINAREA", "SPACING (cut)"} <= checked
    assert "| MINSTEP | not modelled | Metal1, Metal2 |" in capsys.readouterr().out


def test_a_pdk_whose_files_are_missing_is_skipped_with_the_reason(tmp_path: Path, capsys) -> None:
    manifest = tmp_path / "m.tsv"
    manifest.write_text("\t".join(["d", "P", "owner/repo", "0" * 40, "x.def", "x.lef", "-", "-", "n"]) + "\n")
    assert bench.main(["--manifest", str(manifest), "--root", str(tmp_path)]) == 0
    assert f"P: skipped: x.def not under {tmp_path} (give --git-dir)" in capsys.readouterr().out

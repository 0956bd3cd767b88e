"""bench/quality.py's floor lines: the quality floors judged on its rows."""

from __future__ import annotations

from conftest import load_file

quality = load_file("bench/quality.py")


def a_row(testcase: str, router: str = "xroute", **fields: object) -> dict:
    r = {"testcase": testcase, "router": router, "wall_s": 10.0, "rss_mb": 173.0, "wl_um": 86_615.2, "vias": 34_961,
         "violations": 0, "by_type": {}, "opens": 0, "off_track_vias": 163, "out_of_guide_um": 791.1,
         "score": 296_212.0}
    r.update(fields)
    return r


def test_floor_lines_name_each_floor_and_whether_it_holds() -> None:
    rows = [a_row("ispd18_test1"), a_row("ispd18_test1", "tritonroute", rss_mb=None),
            a_row("ispd19_test3", wl_um=83_534.5, vias=61_510, rss_mb=301.0, score=None),
            a_row("demo", violations=2, wl_um=1_185.4), a_row("ispd18_test1", score=None)]
    assert quality.floor_lines(rows) == [
        "ispd18_test1: violations 0 <= 0: holds; opens 0 <= 0: holds; score 296,212 <= 290,260: NOT MET; "
        "vias 34,961 <= 34,000: NOT MET; peak RSS MB 173.0 <= 300: holds",
        "ispd19_test3: violations 0 <= 0: holds; opens 0 <= 0: holds; WL µm 83,534.5 <= 84,000: holds; "
        "peak RSS MB 301.0 <= 300: NOT MET",
        "demo: violations 2 <= 0: NOT MET; opens 0 <= 0: holds; peak RSS MB 173.0 <= 300: holds",
        "ispd18_test1: violations 0 <= 0: holds; opens 0 <= 0: holds; score unknown (floor 290,260); "
        "vias 34,961 <= 34,000: NOT MET; peak RSS MB 173.0 <= 300: holds",
    ]

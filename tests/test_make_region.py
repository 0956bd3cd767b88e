"""make-region (testcases/regions.py, ``xroute make-region``) and the static region env."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from conftest import pick, require_testcase
from xroute.cli.app import app

# ispd18_test1, or its generated stand-in (7 x 7 GCells) without the contest data.
BIG = pick("ispd18_test1")
CONTEST = BIG == "ispd18_test1"
LOCATION = (30, 30) if CONTEST else (3, 3)  # a GCell in the middle of the die


@pytest.fixture(scope="module")
def region3(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The XRoute paper's Region3 of ispd18_test1 (without the contest data: the GCell at LOCATION of the
    stand-in), made once for the module."""
    from xroute.design import load_design
    from xroute.testcases.regions import make_region, paper_region_box

    require_testcase(BIG)
    out = tmp_path_factory.mktemp("regions") / "region3"
    if CONTEST:
        testcase, box = paper_region_box(3)
    else:
        d = load_design(BIG)
        xs, ys = d.gcell_lines("x"), d.gcell_lines("y")
        (i, j), testcase = LOCATION, BIG
        box = (int(xs[i]), int(ys[j]), int(xs[i + 1]), int(ys[j + 1]))
    make_region(testcase, out, box=box)
    return out


def test_paper_region3_folder_and_counts(region3: Path) -> None:
    require_testcase("ispd18_test1")  # the paper's region and our counts for it
    assert sorted(p.name for p in region3.iterdir()) == ["region.def", "region.guide", "region.lef", "region.yaml"]
    meta = yaml.safe_load((region3 / "region.yaml").read_text())
    assert meta["testcase"] == "ispd18_test1"
    assert meta["box"] == [148200, 210900, 153900, 216600] and meta["origin"] == [148200, 210900]
    # Our counts for the paper's Region3 (the paper reports 49 nets / 66 pins; see policies/rl/README.md).
    assert (meta["nets"], meta["pins"]) == (38, 12)
    assert len(meta["net_names"]) == meta["nets"]
    assert meta["sparsity"] == pytest.approx(meta["grid_nodes"] / meta["nets"], abs=1e-3)
    die = meta["die"]
    assert die[0] <= 148200 and die[1] <= 210900 and die[2] >= 153900 and die[3] >= 216600


def test_region_round_trip_loads_and_routes_without_opens(region3: Path) -> None:
    from xroute.testcases.regions import load_region
    from xroute.router import route_design

    design, meta = load_region(region3)
    assert design.num_nets == meta["nets"]
    assert tuple(int(v) for v in design.die_area) == tuple(meta["die"])
    route_design(design, iterations=2)
    conn = design.engine.check_connectivity()
    assert conn["open_nets"] == 0 and conn["unrouted_nets"] == 0


def test_static_region_env_check_env_and_determinism(region3: Path) -> None:
    gym = pytest.importorskip("gymnasium")
    from gymnasium.utils.env_checker import check_env

    import xroute.envs  # noqa: F401  (registers the environments)

    env = gym.make("xroute/StaticRegion-v0", region_dir=str(region3), max_candidates=64)
    with pytest.warns(UserWarning, match="infinity"):
        check_env(env.unwrapped, skip_render_check=True)

    def rollout(seed: int) -> list[tuple[float, float]]:
        rng = np.random.default_rng(seed)
        obs, info = env.reset(seed=seed)
        assert info["candidates"] == nets
        out, done = [], False
        while not done:
            obs, reward, done, _, _ = env.step(int(rng.choice(np.flatnonzero(env.unwrapped.action_masks()))))
            out.append((reward, float(obs["obstacle"].sum())))
        return out

    nets = 38 if CONTEST else yaml.safe_load((region3 / "region.yaml").read_text())["nets"]
    assert nets > 0
    first = rollout(7)
    assert len(first) == nets
    assert rollout(7) == first


def test_cli_make_region_location_and_errors(tmp_path: Path) -> None:
    require_testcase(BIG)
    runner = CliRunner()
    out = tmp_path / "r"
    loc = f"{LOCATION[0]},{LOCATION[1]}"
    result = runner.invoke(app, ["make-region", BIG, "--location", loc, "--size", "1", "--out", str(out), "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["location"] == list(LOCATION) and data["size"] == 1
    if CONTEST:
        assert data["box"] == [180000, 171000, 186000, 176700]  # GCells of 6000 x 5700 DBU
    else:
        from xroute.design import load_design

        d = load_design(BIG)
        xs, ys = d.gcell_lines("x"), d.gcell_lines("y")
        assert data["box"] == [int(xs[3]), int(ys[3]), int(xs[4]), int(ys[4])]
    assert yaml.safe_load((out / "region.yaml").read_text())["nets"] == data["nets"] > 0
    # Writing again replaces the region folder.
    again = runner.invoke(app, ["make-region", BIG, "--location", loc, "--out", str(out)])
    assert again.exit_code == 0 and "nets" in again.stdout

    for args, message in (
        (["--location", "99,1"], "error: location 99,1 is outside the GCell grid"),
        (["--box", "1,2"], "error: --box must be 4 comma-separated integers"),
        (["--box", "0,0,10,10", "--location", "1,1"], "exactly one of"),
    ):
        bad = runner.invoke(app, ["make-region", BIG, "--out", str(tmp_path / "bad"), *args])
        assert bad.exit_code == 2 and message in bad.output + bad.stderr
        assert not (tmp_path / "bad").exists()
    not_region = tmp_path / "file_here"
    not_region.mkdir()
    (not_region / "x.txt").write_text("keep")
    bad = runner.invoke(app, ["make-region", BIG, "--location", loc, "--out", str(not_region)])
    assert bad.exit_code == 2 and "is not a region folder" in bad.stderr
    assert (not_region / "x.txt").read_text() == "keep"

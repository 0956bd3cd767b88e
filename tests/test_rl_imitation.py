"""The set scorer learned by imitation of teacher orders (policies/rl/{set_features,teacher,set_scorer,imitation}.py)
and its ONNX path through OnnxPolicy, on a generated design (no contest data)."""

from __future__ import annotations

import numpy as np
import pytest

torch = pytest.importorskip("torch")
pytest.importorskip("onnxruntime")

SIZE = 2  # regions of the imitation_sample fixture (conftest): 64 of 2x2 GCells
HOLD_OUT = 3


def test_set_features_shape_and_ranges(imitation_sample: str) -> None:
    from xroute import load_design
    from xroute.policies.rl.set_features import SET_FEATURES, region_set_features
    from xroute.session import first_pass, open_session

    fp = first_pass(open_session(load_design(imitation_sample)), SIZE)
    region = fp.open_region(0)
    f = region_set_features(region)
    assert f.shape == (len(region.candidates), len(SET_FEATURES)) and f.dtype == np.float32
    assert np.isfinite(f).all() and f.nbytes < 1 << 20
    dens = f[:, SET_FEATURES.index("obstacle_density")]
    assert (dens >= 0).all() and (dens <= 1).all() and dens.max() > 0  # something is routed around it
    assert np.ptp(f[:, SET_FEATURES.index("half_perimeter")]) > 0


def test_plackett_luce_prefers_the_teacher_order() -> None:
    from xroute.policies.rl.imitation import plackett_luce_loss

    scores = torch.tensor([[3.0, 2.0, 1.0, 0.0]])
    mask = torch.ones(1, 4, dtype=torch.bool)
    w = torch.tensor([[1.0]])
    good = plackett_luce_loss(scores, mask, torch.tensor([[[0, 1, 2, 3]]]), w)
    bad = plackett_luce_loss(scores, mask, torch.tensor([[[3, 2, 1, 0]]]), w)
    assert good < bad
    # Padding rows (mask False) change nothing.
    padded = plackett_luce_loss(torch.tensor([[3.0, 2.0, 1.0, 0.0, 9.0]]), torch.tensor([[True] * 4 + [False]]),
                                torch.tensor([[[0, 1, 2, 3, 4]]]), w)
    assert torch.isclose(good, padded)


@pytest.mark.slow
def test_imitation_beats_a_random_order_on_held_out_regions(imitation_sample: str, tmp_path) -> None:
    """Teacher orders on the training regions, a few hundred steps of imitation (no heuristic prior, fixed
    seeds), then the held-out regions routed in the scorer's order (ties by row, not by the heuristic)
    against random orders; the exported ONNX model gives the same scores through OnnxPolicy."""
    from xroute import load_design
    from xroute.policies.onnx_policy import OnnxPolicy
    from xroute.policies.rl.imitation import ImitationConfig, train
    from xroute.policies.rl.set_features import region_set_features
    from xroute.policies.rl.region_filter import held_out
    from xroute.policies.rl.set_scorer import export_onnx
    from xroute.policies.rl.teacher import collect, score_orders
    from xroute.session import first_pass, open_session

    torch.set_num_threads(1)
    regions = collect([imitation_sample], workers=1, region_size=SIZE, hold_out_every=HOLD_OUT, orders=6, seed=1)
    assert len(regions) >= 30 and all(len(r.costs) == 7 for r in regions)
    model, log = train(regions, ImitationConfig(width=32, heads=2, steps=300, batch=8, prior=0.0, log_every=100))
    assert log[-1]["loss"] < log[0]["loss"] + 0.05

    def scores(f: np.ndarray) -> np.ndarray:
        with torch.no_grad():
            t = torch.from_numpy(f)[None]
            return model(t, torch.ones(t.shape[:2], dtype=torch.bool))[0].numpy()

    design = load_design(imitation_sample)
    fp = first_pass(open_session(design), SIZE)
    held = [i for i, (loc, _box, _colour, _nets) in enumerate(fp.regions)
            if held_out(tuple(loc), HOLD_OUT, SIZE) and len(fp.open_region(i).candidates) >= 2]
    assert len(held) >= 5 and not {r.index for r in regions} & set(held)
    fns = {"model": lambda f: np.argsort(-scores(f), kind="stable")}
    for s in range(6):
        fns[f"random{s}"] = lambda f, s=s: np.random.default_rng([s, len(f)]).permutation(len(f))
    got = score_orders(fp, held, fns, design.dbu_per_micron)
    learned = sum(got["model"])
    randoms = [sum(got[f"random{s}"]) for s in range(6)]
    # Measured after the contest-quality router changes: 5,287 against 5,783 / 5,295 / 5,787 / 4,291 / 5,786 /
    # 5,787 (mean 5,455; before them the learned order was more than 10% below the mean). Markers
    # dominate these costs, and the router now leaves few: below the mean and most of the seeds.
    assert learned < float(np.mean(randoms)), (learned, randoms)
    assert sum(learned < r for r in randoms) >= 4, (learned, randoms)

    path = export_onnx(model, tmp_path / "set.onnx")
    policy = OnnxPolicy(path)
    assert policy.kind == "set"
    f = region_set_features(fp.open_region(held[0]))
    assert np.allclose(policy.set_scores(f, np.ones(len(f), bool)), scores(f), atol=1e-4)


def test_an_untrained_set_scorer_routes_like_the_heuristic_through_the_router(imitation_sample: str, tmp_path) -> None:
    """Zero head + heuristic prior = the heuristic order: route_design with the exported model (one call per
    region) routes exactly what the heuristic routes; a set model with wrong metadata is refused."""
    import onnx

    from xroute import load_design
    from xroute.policies.onnx_policy import OnnxPolicy
    from xroute.policies.registry import get_policy
    from xroute.policies.rl.set_scorer import SetScorer, export_onnx
    from xroute.net_order import PolicyError
    from xroute.router import route_design

    torch.manual_seed(0)
    path = export_onnx(SetScorer(width=16, heads=2, layers=1, prior=4.0), tmp_path / "prior.onnx")
    policy = get_policy(str(path))
    assert isinstance(policy, OnnxPolicy) and policy.kind == "set" and policy.algorithm == "set"
    calls = []
    set_scores = policy.set_scores
    policy.set_scores = lambda f, m: calls.append(len(f)) or set_scores(f, m)
    got = route_design(load_design(imitation_sample), region_size=SIZE, iterations=1, policy=policy)
    heuristic = route_design(load_design(imitation_sample), region_size=SIZE, iterations=1)
    assert calls and len(calls) == got.iterations[0].regions
    assert (got.final.wirelength_dbu, got.final.vias) == (heuristic.final.wirelength_dbu, heuristic.final.vias)

    proto = onnx.load(str(path))
    for entry in proto.metadata_props:
        if entry.key == "xroute_set_features":
            entry.value = "pins"
    onnx.save(proto, str(tmp_path / "bad.onnx"))
    with pytest.raises(PolicyError, match="bad.onnx: not an xroute net-order model: metadata xroute_set_features"):
        OnnxPolicy(tmp_path / "bad.onnx")


@pytest.mark.slow
def test_xroute_train_imitate_writes_a_model_the_router_takes(imitation_sample: str, tmp_path) -> None:
    import json

    from typer.testing import CliRunner

    from xroute.cli.app import app
    from xroute.policies.onnx_policy import OnnxPolicy

    out = tmp_path / "run"
    runner = CliRunner()
    res = runner.invoke(app, ["train", "imitate", "--testcase", imitation_sample, "--episodes", "20", "--region-size",
                              str(SIZE), "--hold-out-every", "3", "--orders", "2", "--workers", "1", "--out", str(out),
                              "--json"])
    assert res.exit_code == 0, res.output
    summary = json.loads(res.stdout)["summary"]
    assert summary["teacher_regions"] >= 30 and summary["steps"] == 20
    assert OnnxPolicy(out / "set.onnx").kind == "set" and (out / "teacher.npz").is_file()
    # Training again from the saved teacher data routes nothing; bad teacher data is one line.
    res = runner.invoke(app, ["train", "imitate", "--testcase", imitation_sample, "--episodes", "5", "--teacher",
                              str(out / "teacher.npz"), "--out", str(tmp_path / "again"), "--json"])
    assert res.exit_code == 0, res.output
    (tmp_path / "junk.npz").write_bytes(b"junk")
    res = runner.invoke(app, ["train", "imitate", "--testcase", imitation_sample, "--episodes", "5", "--teacher",
                              str(tmp_path / "junk.npz"), "--out", str(tmp_path / "bad")])
    assert res.exit_code == 2 and "junk.npz: not teacher data" in res.output
    assert not (tmp_path / "bad").exists()
    # Teacher data where no order changed the cost teaches nothing: one line, exit 2, no output folder.
    from xroute.policies.rl.teacher import TeacherRegion, load, save

    flat = [TeacherRegion(r.testcase, r.index, r.features, r.orders, np.full_like(r.costs, 100.0))
            for r in load(out / "teacher.npz")]
    save(flat, tmp_path / "flat.npz")
    res = runner.invoke(app, ["train", "imitate", "--testcase", imitation_sample, "--episodes", "5", "--teacher",
                              str(tmp_path / "flat.npz"), "--out", str(tmp_path / "flat")])
    assert res.exit_code == 2 and "nothing to imitate" in res.output and "Traceback" not in res.output
    assert not (tmp_path / "flat").exists()


def test_promoted_teacher_orders_move_a_drawn_subset_to_the_front(imitation_sample: str) -> None:
    """``promote``: every teacher order is the heuristic's with the nets its draw picks first, both parts
    in heuristic order; the draw is the region's (seed, index) generator, so the subsets can be recovered."""
    from xroute.policies.rl.set_features import SET_FEATURES
    from xroute.policies.rl.teacher import collect, promoted, promoted_order

    h = np.array([3, 0, 4, 1, 2], dtype=np.int32)
    mask = np.array([False, True, False, True, True])  # nets 1, 3 and 4
    assert promoted_order(h, mask).tolist() == [3, 4, 1, 0, 2]
    assert promoted_order(h, np.zeros(5, bool)).tolist() == h.tolist()
    regions = collect([imitation_sample], workers=1, region_size=SIZE, hold_out_every=HOLD_OUT, orders=3, seed=2,
                      max_regions=12, promote=0.5)
    assert len(regions) >= 5
    moved = 0
    for r in regions:
        n = len(r.features)
        heuristic = r.orders[0]
        assert np.array_equal(heuristic, np.argsort(r.features[:, SET_FEATURES.index("heuristic_rank")], kind="stable"))
        masks = promoted(np.random.default_rng([2, r.index]), n, 3, 0.5)
        for k in range(3):
            assert np.array_equal(r.orders[k + 1], promoted_order(heuristic, masks[k]))
            moved += int(not np.array_equal(r.orders[k + 1], heuristic))
    assert moved > 0

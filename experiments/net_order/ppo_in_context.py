"""MaskablePPO on the compact observation, trained on in-context training regions, scored on held-out ones.

    python -m experiments.net_order.ppo_in_context [--testcase ispd18_test1 --testcase ispd19_test1] [--steps 20000]
                                   [--seed 1] [--max-candidates 64] [--json out.json]

The planned route to a learned order, with its pieces: the net-ordering env in context (the router's first pass,
regions of its size, ``--hold-out-every`` regions never drawn), the compact observation
(``observation="compact"``), sb3-contrib's MaskablePPO with :class:`~xroute.policies.rl.sb3.SetOrderExtractor`
(a critic that sees every net) and rewards per violation (:class:`~xroute.policies.rl.sb3.PerViolation`).
One env per testcase, stepped together (a DummyVecEnv); regions drawn in random order.

The policy starts as the heuristic: its action head reads the set scorer's row scores, whose untrained
value is the heuristic prior (-4 x heuristic rank), times ``--start-sharpness``. So its greedy order is
the heuristic's before training, and training moves it where the rewards say.

Scored like ``experiments/net_order/rl_holdout.py``: each held-out region opened in context and routed in the greedy
order of the model (one net at a time, the compact observation recomputed after each), its cost
against the heuristic's, before and after training.
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

HOLD_OUT_EVERY = 3


def make_env(testcase: str, region_size: int, max_candidates: int) -> Any:
    from xroute.envs.ordering_training import ordering_training_env
    from xroute.policies.rl.region_filter import RegionFilter
    from xroute.policies.rl.sb3 import PerViolation

    env = ordering_training_env(testcase, region_size=region_size, in_context=True, max_candidates=max_candidates,
                                observation="compact", region_order="random")
    return PerViolation(RegionFilter(env, hold_out_every=HOLD_OUT_EVERY, min_candidates=2))


def start_as_heuristic(model: Any, rows: int, sharpness: float) -> None:
    """Sets the action head to ``sharpness`` x the extractor's row scores (the rows' logits)."""
    import torch

    head = model.policy.action_net
    with torch.no_grad():
        head.weight.zero_()
        head.bias.zero_()
        head.weight[:, :rows] = sharpness * torch.eye(rows)


def greedy_in_context(model: Any, first_pass: Any, index: int, dbu: int, max_candidates: int) -> tuple[float, list[int]]:
    """(cost, candidates in the order routed) of held-out region ``index`` routed in ``model``'s greedy order."""
    from xroute.config import CostSection
    from xroute.envs.core import RegionStepper
    from .holdout import region_score

    region = first_pass.open_region(index)
    stepper = RegionStepper(region, dbu, max_candidates, CostSection(), observation="compact")
    obs = stepper.observation()
    while not stepper.done:
        action, _ = model.predict(obs, deterministic=True, action_masks=stepper.action_mask())
        stepper.step(int(action))
        obs = stepper.observation()
    return region_score(region, dbu).cost, stepper.order


@dataclass
class HeldOut:
    """A testcase's first pass, its held-out regions and the heuristic's cost on each (routed once)."""

    first_pass: Any
    dbu: int
    regions: list[Any]
    heuristic: list[float]


def held_out(testcases: list[str], region_size: int) -> dict[str, HeldOut]:
    from .holdout import held_out_regions, route_in_context
    from xroute.policies.rl.teacher import load_first_pass

    out = {}
    for t in testcases:
        fp, dbu = load_first_pass(t, region_size)
        regions = list(held_out_regions(fp, HOLD_OUT_EVERY, region_size, 2))
        out[t] = HeldOut(fp, dbu, regions, [route_in_context(fp, h, "heuristic", 1, dbu).cost for h in regions])
    return out


def score_held_out(model: Any, sets: dict[str, HeldOut], max_candidates: int) -> dict[str, dict]:
    """Per testcase: held-out regions, the heuristic's summed cost and the model's greedy order's."""
    out = {}
    for t, h in sets.items():
        learned = [greedy_in_context(model, h.first_pass, r.index, h.dbu, max_candidates)[0] for r in h.regions]
        out[t] = {"regions": len(h.regions), "heuristic": float(sum(h.heuristic)), "model": float(sum(learned)),
                  "better": int(sum(m < c - 1e-6 for m, c in zip(learned, h.heuristic))),
                  "worse": int(sum(m > c + 1e-6 for m, c in zip(learned, h.heuristic)))}
    return out


def new_model(testcases: list[str], seed: int, region_size: int, max_candidates: int, sharpness: float) -> Any:
    """MaskablePPO on one in-context training env per testcase, started as the heuristic."""
    from stable_baselines3.common.vec_env import DummyVecEnv

    from xroute.policies.rl.sb3 import make_maskable_ppo

    venv = DummyVecEnv([lambda t=t: make_env(t, region_size, max_candidates) for t in testcases])
    model = make_maskable_ppo(venv, seed=seed, learning_rate=3e-4)
    start_as_heuristic(model, max_candidates, sharpness)
    return model


def run(testcases: list[str], steps: int, seed: int, region_size: int, max_candidates: int,
        sharpness: float) -> dict[str, Any]:
    import torch

    torch.set_num_threads(1)
    t0 = time.perf_counter()
    model = new_model(testcases, seed, region_size, max_candidates, sharpness)
    sets = held_out(testcases, region_size)
    before = score_held_out(model, sets, max_candidates)
    t1 = time.perf_counter()
    model.learn(total_timesteps=steps)
    trained = time.perf_counter() - t1
    after = score_held_out(model, sets, max_candidates)
    return {"steps": steps, "seed": seed, "before": before, "after": after, "seconds": time.perf_counter() - t0,
            "training_seconds": trained}


def main(argv: list[str] | None = None) -> None:
    from xroute.defaults import REGION_SIZE

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--testcase", action="append")
    ap.add_argument("--steps", type=int, default=20000, help="environment steps in all (nets routed)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--region-size", type=int, default=REGION_SIZE)
    ap.add_argument("--max-candidates", type=int, default=64)
    ap.add_argument("--start-sharpness", type=float, default=5.0)
    ap.add_argument("--json", type=Path)
    a = ap.parse_args(argv)
    res = run(a.testcase or ["ispd18_test1", "ispd19_test1"], a.steps, a.seed, a.region_size, a.max_candidates,
              a.start_sharpness)
    for when in ("before", "after"):
        for t, r in res[when].items():
            print(f"{when} training, {t}: {r['regions']} held-out regions, heuristic {r['heuristic']:,.1f}, model "
                  f"{r['model']:,.1f} ({100 * (r['model'] / r['heuristic'] - 1):+.2f}%), better / worse "
                  f"{r['better']} / {r['worse']}")
    print(f"{res['steps']} steps, {res['training_seconds']:.0f} s training, {res['seconds']:.0f} s in all")
    if a.json:
        a.json.write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()

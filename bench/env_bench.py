"""Net-ordering env throughput: steps per second on 1x1 (or --region-size) regions of a testcase.

    python bench/env_bench.py [TESTCASE] [--region-size C] [--steps N] [--max-candidates M]
                              [--location X,Y]

Runs the training env (``xroute/NetOrdering-v0``) with uniformly random legal actions (seeded)
for N steps, walking regions from the lower-left (or the 6 x 6 block of regions from
``--location``, default 20,20: the die's edge regions are nearly empty). Printed: steps/s of
the whole ``env.step`` and the share of its time in routing one net (``route_net``), the
region's design-rule check (``metrics()``: the reward) and building the observation; plus
resets/s (opening a region). Loading the design is not counted.
"""

from __future__ import annotations

import argparse
import time
from collections import defaultdict

import numpy as np



def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("testcase", nargs="?", default="ispd18_test1")
    ap.add_argument("--region-size", type=int, default=1)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--max-candidates", type=int, default=64)
    ap.add_argument("--location", default="20,20")
    args = ap.parse_args()

    from xroute.envs import core
    from xroute.envs.ordering_training import NetOrderingTrainingEnv

    gx, gy = (int(v) for v in args.location.split(","))
    spent: dict[str, float] = defaultdict(float)

    def timed(name, fn):
        def wrapper(*a, **k):
            t = time.perf_counter()
            try:
                return fn(*a, **k)
            finally:
                spent[name] += time.perf_counter() - t
        return wrapper

    # Time the parts by wrapping the stepper's calls.
    original_init = core.RegionStepper.__init__

    def init(self, region, *a, **k):
        original_init(self, region, *a, **k)
        region_proxy = _Proxy(region, {"route_net": timed("route_net", region.route_net),
                                       "metrics": timed("metrics (DRC)", region.metrics)})
        self.region = region_proxy

    core.RegionStepper.__init__ = init
    core.RegionStepper.observation = timed("observation", core.RegionStepper.observation)

    locations = [(gx + i * args.region_size, gy + j * args.region_size) for j in range(6) for i in range(6)]
    env = NetOrderingTrainingEnv(args.testcase, args.region_size, region_location=locations[0],
                                 max_candidates=args.max_candidates)
    rng = np.random.default_rng(0)
    env.reset(seed=0)
    steps = resets = 0
    candidates = []
    step_time = reset_time = 0.0
    spent.clear()
    k = 0
    while steps < args.steps:
        t = time.perf_counter()
        _, _, done, _, info = env.step(int(rng.choice(np.flatnonzero(env.action_masks()))))
        step_time += time.perf_counter() - t
        steps += 1
        if done:
            candidates.append(info["candidates"])
            k = (k + 1) % len(locations)
            env.region_location = locations[k]
            t = time.perf_counter()
            env._fresh_design()  # walk the next location (the design stays loaded)
            env._stepper = None
            env.reset()
            reset_time += time.perf_counter() - t
            resets += 1
    parts = {name: s for name, s in spent.items()}
    print(f"{args.testcase}: {args.region_size}x{args.region_size} regions, {steps} steps over {resets} episodes "
          f"(mean {np.mean(candidates) if candidates else 0:.1f} candidates, max_candidates {args.max_candidates})")
    print(f"env.step: {steps / step_time:,.1f} steps/s ({1000 * step_time / steps:.2f} ms a step)")
    for name in ("route_net", "metrics (DRC)", "observation"):
        print(f"  {name:14s} {100 * parts.get(name, 0.0) / (step_time + reset_time):5.1f}% of step + reset time")
    print(f"reset (open a region + first observation): {resets / reset_time if reset_time else 0:,.1f} resets/s")


class _Proxy:
    """Forwards attribute access to ``target`` except for the overridden callables."""

    def __init__(self, target, overrides):
        self._target = target
        self._overrides = overrides

    def __getattr__(self, name):
        return self._overrides.get(name) or getattr(self._target, name)


if __name__ == "__main__":
    main()

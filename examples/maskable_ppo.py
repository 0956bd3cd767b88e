"""MaskablePPO (sb3-contrib) learns the net order of one static region: the example of xroute.policies.rl.sb3.

    python examples/maskable_ppo.py REGION_DIR [--steps 512] [--max-candidates 8] [--seed 1]
                                 [--observation grid|compact]

REGION_DIR is a static region (``xroute make-region`` or :func:`xroute.envs.generate_static_region`).
The script trains MaskablePPO on it (rewards per violation, :class:`~xroute.policies.rl.sb3.PerViolation`)
and prints the cost of the region routed in the policy's greedy order before and after training,
against 20 random legal orders. Needs ``pip install '.[sb3]'``.
"""

from __future__ import annotations

import argparse

import numpy as np


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("region_dir")
    ap.add_argument("--steps", type=int, default=512, help="environment steps (nets routed) to train for")
    ap.add_argument("--max-candidates", type=int, default=8)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--observation", choices=("grid", "compact"), default="grid")
    a = ap.parse_args(argv)
    import torch

    from xroute.envs import static_region_env
    from xroute.policies.rl.sb3 import PerViolation, greedy_cost, make_maskable_ppo, random_costs

    torch.set_num_threads(1)
    env = PerViolation(static_region_env(a.region_dir, max_candidates=a.max_candidates, observation=a.observation))
    judge = static_region_env(a.region_dir, max_candidates=a.max_candidates, observation=a.observation)
    model = make_maskable_ppo(env, seed=a.seed)
    before = greedy_cost(model, judge)
    model.learn(total_timesteps=a.steps)
    after = greedy_cost(model, judge)
    rand = random_costs(judge, 20, a.seed)
    print(f"greedy order: cost {before:,.1f} before training, {after:,.1f} after {a.steps} steps; "
          f"random orders: mean {np.mean(rand):,.1f}, best {min(rand):,.1f} of {len(rand)}")


if __name__ == "__main__":
    main()

"""Trains the paper's net-routing DQN on ``xroute/NetRouting-v0`` and compares it with A* on held-out
regions (prints a table, writes JSON; ``--out`` writes the ONNX model).

    python -m experiments.net_router.net_router_dqn [--episodes 4000] [--seconds 240] [--out policies/models/net_router_dqn.onnx]
                                   [--json out.json] [--model M.onnx (evaluate only)]

Regions: 1x1-GCell regions. Held out: lower-left GCell x % K == K // 2 and y % K == K // 2
(K = 4 on the demo, 8 on ispd18_test1; the convention of ``xroute train --hold-out-every``),
the first ``--eval-regions`` of them; training: the first ``--train-regions`` other regions with a
routable net. ispd18_test1 joins when it is on the search path.

Evaluation: each held-out region opened on the freshly loaded design; its routable nets (two or more
terminals on the grid) in the heuristic order. DQN: one episode per net (greedy over the legal
moves, the net's paths committed whether connected or not, the following nets see them). A*: the
maze (``Region.route_net``) on the same nets in the same order. Per router: nets connected, and
the region's wirelength, vias and design-rule violations (``Region.metrics()`` after the last
net), summed over the regions.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

import xroute.envs  # noqa: F401
from xroute.envs.net_routing import NetRoutingEnv
from xroute.errors import TestcaseNotFound
from xroute.policies.rl.net_dqn import (
    NetDQNConfig,
    OnnxNetRouter,
    export_onnx,
    greedy,
    train_net_router,
)
from xroute.testcases.registry import find_testcase


def _present(name: str) -> bool:
    try:
        find_testcase(name)
        return True
    except TestcaseNotFound:
        return False


def split(env: NetRoutingEnv, k: int, n_train: int, n_eval: int) -> tuple[list, list]:
    """(train, held-out) region locations of env's testcase with a routable net."""
    env._load()
    train, held = [], []
    for loc, box in env._session.regions(1):
        is_held = loc[0] % k == k // 2 and loc[1] % k == k // 2
        if (len(held) >= n_eval) if is_held else (len(train) >= n_train):
            continue
        if not env._routable(env._session.open_region(box)):
            continue
        (held if is_held else train).append(tuple(loc))
        if len(train) >= n_train and len(held) >= n_eval:
            break
    return train, held


def toward_target(obs: np.ndarray, legal: np.ndarray) -> int:
    """A scripted reference: the legal move that shrinks the largest distance to the target (x, y, then z
    order on ties), else the cheapest legal move."""
    d = obs[3:6]
    prefs = []
    for axis in np.argsort(-np.abs(d), kind="stable"):
        if d[axis] != 0:
            prefs.append({0: (4, 5), 1: (2, 3), 2: (0, 1)}[int(axis)][0 if d[axis] > 0 else 1])
    for a in prefs:
        if legal[a]:
            return int(a)
    if legal.any():
        costs = np.where(legal, obs[6:12], np.inf)
        return int(np.argmin(costs))
    return 0


def evaluate(testcase: str, locations: list, act, with_astar: bool = True) -> dict:
    """DQN (``act(obs, legal)``) and A* on the nets of each region (see the module docstring)."""
    env = NetRoutingEnv(testcase, region_location=locations)
    obs, info = env.reset(seed=0)
    out = {"regions": len(locations), "nets": 0,
           "dqn": {"connected": 0, "wirelength_um": 0.0, "vias": 0, "violations": 0, "steps": 0, "cut": 0,
                   "illegal": 0},
           "astar": {"connected": 0, "wirelength_um": 0.0, "vias": 0, "violations": 0}}
    for i in range(len(locations)):
        nets = list(env._nets)
        box = info["box"]
        # A* on a fresh copy of the region
        if with_astar:
            region = env._session.open_region(box)
            for c in nets:
                r = region.route_net(c)
                out["astar"]["connected"] += int(r["unreached"] == 0)
            m = region.metrics()
            out["astar"]["wirelength_um"] += m["wirelength_dbu"] / env.dbu
            out["astar"]["vias"] += m["vias"]
            out["astar"]["violations"] += m["violations"]
        # DQN: one episode per net
        for k in range(len(nets)):
            done = False
            while not done:
                a = act(obs, env.legal_actions())
                obs, _, term, trunc, info = env.step(a)
                done = term or trunc
                out["dqn"]["steps"] += 1
            out["nets"] += 1
            out["dqn"]["connected"] += int(info["connected"])
            out["dqn"]["cut"] += int(info["cut"])
            out["dqn"]["illegal"] += int(info["illegal"])
            last = info["metrics"]
            obs, info = env.reset()
        out["dqn"]["wirelength_um"] += last["wirelength_dbu"] / env.dbu
        out["dqn"]["vias"] += last["vias"]
        out["dqn"]["violations"] += last["violations"]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=NetDQNConfig.episodes)
    ap.add_argument("--seconds", type=float, default=240.0, help="CPU seconds of training at most")
    ap.add_argument("--train-regions", type=int, default=24)
    ap.add_argument("--eval-regions", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--eps-episodes", type=int, default=NetDQNConfig.eps_episodes)
    ap.add_argument("--gamma", type=float, default=NetDQNConfig.gamma)
    ap.add_argument("--shaping", type=float, default=NetDQNConfig.shaping)
    ap.add_argument("--reward-clip", type=float, default=NetDQNConfig.reward_clip)
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--model", type=Path, default=None, help="evaluate this ONNX model, no training")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()

    cases = [("demo", 4)] + ([("ispd18_test1", 8)] if _present("ispd18_test1") else [])
    splits = {}
    for name, k in cases:
        splits[name] = split(NetRoutingEnv(name), k, args.train_regions, args.eval_regions)
        print(f"{name}: train regions {splits[name][0]}\n  held out {splits[name][1]}", flush=True)

    report: dict = {"cases": {}}
    if args.model is None:
        envs = [NetRoutingEnv(name, region_location=splits[name][0]) for name, _ in cases]
        cfg = NetDQNConfig(episodes=args.episodes, max_seconds=args.seconds, eps_episodes=args.eps_episodes,
                           gamma=args.gamma, shaping=args.shaping,
                           reward_clip=args.reward_clip)
        res = train_net_router(envs, cfg, seed=args.seed, log=lambda s: print(s, flush=True))
        print(f"trained: {res.episodes} episodes, {res.transitions} transitions, {res.seconds:.0f} s CPU, "
              f"connected {res.connected}/{res.episodes}", flush=True)
        report["training"] = {"episodes": res.episodes, "transitions": res.transitions, "cpu_seconds": res.seconds,
                              "connected": res.connected, "config": vars(cfg),
                              "train_regions": {n: s[0] for n, s in splits.items()}}
        import torch

        model = res.model

        def act(obs, legal):
            with torch.no_grad():
                return greedy(model(torch.as_tensor(obs[None])).numpy()[0], legal)

        if args.out is not None:
            export_onnx(model, args.out, {"xroute_algorithm": "dqn", "xroute_episodes": str(res.episodes),
                                          "xroute_transitions": str(res.transitions)})
            print(f"wrote {args.out}")
    else:
        router = OnnxNetRouter(args.model)
        act = router.act

    for name, _ in cases:
        t = time.time()
        r = evaluate(name, splits[name][1], act)
        r["seconds"] = time.time() - t
        r["toward_target"] = evaluate(name, splits[name][1], toward_target, with_astar=False)["dqn"]
        report["cases"][name] = r
        print(f"\n{name}: {r['regions']} held-out regions, {r['nets']} nets")
        print(f"  {'router':6} {'connected':>10} {'WL um':>9} {'vias':>6} {'DRVs':>6}")
        for key in ("dqn", "toward_target", "astar"):
            v = r[key]
            print(f"  {key[:6]:6} {v['connected']:>5}/{r['nets']:<4} {v['wirelength_um']:>9.1f} {v['vias']:>6} "
                  f"{v['violations']:>6}")
        print(f"  dqn episodes cut by T_min {r['dqn']['cut']}, illegal {r['dqn']['illegal']}, steps {r['dqn']['steps']}")
    if args.json is not None:
        args.json.write_text(json.dumps(report, indent=1, default=str))


if __name__ == "__main__":
    main()

"""``NetRouterPolicy(model)``: routes every net with a learned net router, A* taking over.

The router lends the policy each region (``needs_region``); the policy walks each candidate net
with two or more terminals, in the heuristic order, from its head as ``xroute/NetRouting-v0`` does
(:class:`xroute.policies.rl.net_walk.NetWalk`, greedy over the model's Q-values and the legal
moves). A net the model connects is committed along its paths (``Region.route_net_paths``: the
maze's own commit); a net it does not connect (illegal move, T_min cut, ``max_moves``) is routed
by the maze (``Region.route_net``) instead, as are nets with fewer than two terminals on the grid
(by the seam, in the heuristic order). ``stats`` counts both. Later iterations rip up and reroute
as always, with the same policy.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from xroute.config import CostSection
from xroute.net_order import heuristic_order

DEFAULT_MAX_MOVES = 2000


class NetRouterPolicy:
    """A net-order policy that routes the nets itself with a net-router ONNX model (see the module)."""

    needs_region = True

    def __init__(self, model: str | Path, dbu_per_micron: int, *, t_min_scale: float = 1.0,
                 max_moves: int = DEFAULT_MAX_MOVES) -> None:
        from xroute.policies.rl.net_dqn import OnnxNetRouter

        self.model = OnnxNetRouter(model)
        self.name = f"net-router:{Path(model).name}"
        self.source = str(model)  # named by every failure of the model (xroute.policy_guard)
        self.dbu = int(dbu_per_micron)
        self.t_min_scale = float(t_min_scale)
        self.max_moves = int(max_moves)
        self.weights = CostSection()
        self.stats = {"agent_connected": 0, "astar_fallback": 0}

    def order(self, region: dict[str, Any], features: np.ndarray) -> list[int]:
        from xroute.policies.rl.net_walk import NetWalk, routable_terminals, walk_net

        r = region["engine_region"]
        rows = np.asarray(r.candidates)
        for c in heuristic_order(rows):
            c = int(c)
            if r.is_routed(c) or len(routable_terminals(r, c)) < 2:
                continue
            walk = NetWalk(r, c, self.dbu, self.weights, self.t_min_scale)
            if walk_net(walk, self.model.act, max_moves=self.max_moves) == "connected":
                r.route_net_paths(c, walk.paths())
                self.stats["agent_connected"] += 1
            else:
                r.route_net(c)
                self.stats["astar_fallback"] += 1
        return [int(i) for i in heuristic_order(np.asarray(features))]

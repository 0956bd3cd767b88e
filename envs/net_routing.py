"""``xroute/NetRouting-v0``: the paper's second task, routing one net step by step from its head.

One episode routes one net of a region (a region of ``testcase_name`` cut as the router's first
iteration cuts them: ``region_size`` x ``region_size`` GCells, all of them row by row or the ones
whose lower-left GCell ``region_location`` names, one (column, row) or a list; or the static
region of ``region_dir`` written by ``xroute make-region``).
The nets of a region come in the built-in heuristic order (:func:`xroute.net_order.heuristic_order`;
nets with fewer than two terminals on the grid are skipped); each is routed ``net_loop`` times
(episodes), the last result is kept and the following nets are routed around it. After the last
net of a region the env moves on to the next region with a routable net (regions are never
committed into the design: each starts from the design as loaded); after the last region, the
first again.

The grid graph is the maze router's (``Region.moves``): node = (x, y, z) grid index of the region
grid, the six edges UP, DOWN (vias), NORTH, SOUTH (y), EAST, WEST (x); along a layer's preferred
direction an edge goes to the next track node, against it to the next existing node.

Episode: the head starts on the net's first terminal (the maze's start: a pin's access point,
the one closest to the nearest other terminal; ``reset(options={"start_node": n})`` picks one of
its nodes). Each action moves the head; reaching a node of an unreached terminal connects it; with
more terminals left, the head jumps to the node of the tree built so far (the paths, and the
terminals reached: all of a pin's access points, of a free crossing's alternatives only the node
reached) closest to the nearest unreached terminal. The walk itself is
:class:`xroute.policies.rl.net_walk.NetWalk`, shared with ``xroute route --net-router``. The episode terminates when every terminal is
connected or on an illegal move (no edge that way, or onto a node of the net's own tree or path:
a loop); it is truncated when the total reward falls below ``T_min``. Either way the paths walked
so far (a partial path included) are committed into the region through the maze's own commit
(``Region.route_net_paths``: wires, vias, min-area fix, grid marks; so rule checks, metrics and the
routed DEF are as for the maze router).

Spaces::

    observation = Box(-inf, inf, (12,), float32):
        [0:3]  head (x, y, z) grid indices
        [3:6]  target - head in grid indices (target: the nearest node, in DBU, of an unreached terminal)
        [6:12] per direction (UP, DOWN, NORTH, SOUTH, EAST, WEST) the maze's cost of that edge
               (Region.moves, in µm of wire equivalent: maze cost units / DBU per µm; a plain
               track step is its length, a via 1200 DBU, other nets' shapes add penalties), -1 where
               the move is illegal (no edge, or onto the net's own tree / path)
    action      = Discrete(6)  # direction; the head moves ``steps`` edges that way (default 1)

    with full_state=True: Dict(state = the 12-d Box above,
                               obstacle = Box(0, 1, (3, 64, 64)): the region's obstacle grid as the
                                          net-ordering envs see it (policies/rl/observation.py), aligned,
                               net = Box(0, 1, (3, 3, 64, 64)): channels head, the net's tree and path,
                                     its unreached terminals; aligned the same way)

Reward of a step: ``cost(s) - cost(s')`` with the paper's cost ``0.5 WL(µm) + 4 vias + 500
violations`` (:class:`xroute.config.CostSection`). Wirelength and vias are counted per move; the
violations (``Region.metrics()``, a full check of the box) once, when the net's paths are committed
at the end of the episode: the last step's reward carries the difference, so an episode's rewards
add up to exactly cost(before the net) - cost(after it). Plus ``HPWL(net)`` when every terminal
is connected. ``HPWL`` is the half perimeter of the net's terminal nodes in grid steps, x + y + z
(the paper's grid unit; see :func:`net_hpwl`), ``pin_count`` its terminals in the region, and
``T_min = -t_min_scale * HPWL * pin_count``.

``info``: box, candidate, net (design net id), attempt, head, pins, hpwl, t_min, total_reward,
connected, moves, cost (the region's, before the episode's commit); at the end also illegal, cut,
paths (the node paths committed), unreached (terminals they miss, the engine's count) and metrics
(``Region.metrics()`` after the commit). ``env.legal_actions()``: bool[6], the legal directions.

Seeding: ``reset(seed=s)`` restarts from the first net of the first region (attempt 1); the env
draws nothing from ``self.np_random``: same seed and actions, same episode.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from xroute.config import CostSection
from xroute.policies.rl.net_walk import (
    DIRECTIONS,
    OBSERVATION_SIZE,
    STATE_FIELDS,
    NetWalk,
    net_hpwl,
    routable_terminals,
)
from xroute.net_order import FEATURE_COLUMNS, heuristic_order

__all__ = ["DIRECTIONS", "OBSERVATION_SIZE", "STATE_FIELDS", "NetRoutingEnv", "net_hpwl", "net_routing_env"]


def _locations(value: Any) -> list[tuple[int, int]] | None:
    """region_location: None, one (column, row), or a list of them."""
    if value is None:
        return None
    if len(value) == 2 and all(isinstance(v, (int, np.integer)) for v in value):
        return [(int(value[0]), int(value[1]))]
    return [(int(v[0]), int(v[1])) for v in value]


class NetRoutingEnv(gym.Env):
    """Routing one net per episode, step by step from its head (see the module docstring).

    observation_space: Box(-inf, inf, (12,), float32); action_space: Discrete(6).
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        testcase_name: str = "demo",
        region_size: int = 1,
        region_location: tuple[int, int] | list[tuple[int, int]] | None = None,
        net_loop: int = 1,
        *,
        region_dir: str | None = None,
        steps: int = 1,
        weights: CostSection | None = None,
        t_min_scale: float = 1.0,
        full_state: bool = False,
    ) -> None:
        for name, value in (("region_size", region_size), ("net_loop", net_loop), ("steps", steps)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
        if not t_min_scale > 0:
            raise ValueError(f"t_min_scale must be > 0, got {t_min_scale!r}")
        self.testcase_name = testcase_name
        self.region_dir = None if region_dir is None else str(region_dir)
        self.region_size = int(region_size)
        self.region_locations = _locations(region_location)
        self.net_loop = int(net_loop)
        self.steps = int(steps)
        self.weights = weights if weights is not None else CostSection()
        self.t_min_scale = float(t_min_scale)
        self.full_state = bool(full_state)
        state = spaces.Box(-np.inf, np.inf, (OBSERVATION_SIZE,), np.float32)
        if self.full_state:
            from xroute.policies.rl.observation import ALIGNED_SHAPE

            self.observation_space = spaces.Dict({
                "state": state,
                "obstacle": spaces.Box(0.0, 1.0, ALIGNED_SHAPE, np.float32),
                "net": spaces.Box(0.0, 1.0, (3, *ALIGNED_SHAPE), np.float32),
            })
        else:
            self.observation_space = state
        self.action_space = spaces.Discrete(len(DIRECTIONS))
        self._design: Any = None
        self._session: Any = None
        self._walk: list[tuple[int, int, int, int]] = []
        self._region: Any = None
        self._region_i = -1
        self._nets: list[int] = []
        self._k = 0
        self._attempt = 0
        self._kept: dict[int, list[list[int]]] = {}
        self._region_holds = -1  # the open region holds the kept paths of nets [0, _region_holds)
        self._cost = 0.0
        self._net: NetWalk | None = None
        self._obstacle: np.ndarray | None = None
        self._total = 0.0
        self._end: dict[str, Any] | None = None

    # -- the walk over regions and nets ------------------------------------------------------------

    def _load(self) -> None:
        from xroute.session import open_session

        if self._design is None:
            if self.region_dir is not None:
                from xroute.testcases.regions import load_region

                self._design, meta = load_region(self.region_dir)
                self._session = open_session(self._design)
                self._walk = [tuple(int(v) for v in meta["die"])]
            else:
                from xroute import load_design

                self._design = load_design(self.testcase_name)
                self._session = open_session(self._design)
                walk = [(tuple(loc), tuple(box)) for loc, box in self._session.regions(self.region_size)]
                if self.region_locations is not None:
                    by_location = dict(walk)
                    missing = [loc for loc in self.region_locations if loc not in by_location]
                    if missing:
                        raise ValueError(f"region_location {missing[0]} is not the lower-left GCell of a "
                                         f"{self.region_size}x{self.region_size} region of {self.testcase_name}")
                    walk = [(loc, by_location[loc]) for loc in self.region_locations]
                self._walk = [box for _, box in walk]
        self.dbu = int(self._design.dbu_per_micron)
        self._region_i = -1
        self._next_region()

    def _routable(self, region: Any) -> list[int]:
        rows = np.asarray(region.candidates, dtype=np.int32)
        out = []
        for c in heuristic_order(rows):
            if len(routable_terminals(region, int(c))) >= 2:
                out.append(int(c))
        return out

    def _next_region(self) -> None:
        for _ in range(len(self._walk)):
            self._region_i = (self._region_i + 1) % len(self._walk)
            region = self._session.open_region(self._walk[self._region_i])
            nets = self._routable(region)
            if nets:
                self._set_region(region)
                self._nets, self._k, self._attempt, self._kept = nets, 0, 0, {}
                self._region_holds = 0
                return
        raise RuntimeError(f"no region of {self.region_dir or self.testcase_name} has a net with two terminals")

    def _set_region(self, region: Any) -> None:
        self._region = region
        self._cost = self.weights.region_cost(region.metrics(), self.dbu)

    def _advance(self) -> None:
        """The next (net, attempt): another attempt at this net, or the next net, or the next region."""
        if self._attempt < self.net_loop and self._attempt > 0:
            self._attempt += 1
        else:
            self._k += 1 if self._attempt > 0 else 0
            self._attempt = 1
            if self._k >= len(self._nets):
                self._next_region()
                self._attempt = 1
        if self._region_holds != self._k:  # the net was tried already here: replay the kept nets on a fresh copy
            region = self._session.open_region(self._walk[self._region_i])
            for c in self._nets[: self._k]:
                region.route_net_paths(c, self._kept.get(c, []))
            self._set_region(region)
            self._region_holds = self._k

    # -- gymnasium ---------------------------------------------------------------------------------

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        if seed is not None or self._session is None:
            self._net = None
            self._load()
        self._advance()
        start = None if options is None else options.get("start_node")
        self._net = NetWalk(self._region, self._nets[self._k], self.dbu, self.weights, self.t_min_scale, start)
        self._total = 0.0
        self._end: dict[str, Any] | None = None
        self._obstacle = None
        return self._observation(), self._info()

    def legal_actions(self) -> np.ndarray:
        """bool[6]: the directions that are legal moves from the head now."""
        if self._net is None:
            return np.zeros(len(DIRECTIONS), dtype=bool)
        return self._net.legal()

    def step(self, action: Any):
        n = self._net
        if n is None or self._end is not None:
            raise RuntimeError("the episode is over (or never started): call reset()")
        a = int(np.asarray(action).reshape(-1)[0])
        if not 0 <= a < len(DIRECTIONS):
            raise ValueError(f"action must be a direction 0..5, got {action!r}")
        reward = 0.0
        illegal = False
        for _ in range(self.steps):
            r, illegal, hit = n.move(a)
            reward += r
            if illegal or hit:
                break
        terminated = illegal or n.connected
        truncated = not terminated and self._total + reward < n.t_min
        self._total += reward
        if terminated or truncated:
            reward += self._finish(illegal, truncated)
        return self._observation(), float(reward), terminated, truncated, self._info()

    def _observation(self) -> Any:
        """The 12-d state, or with ``full_state`` the Dict of it and the region's aligned grids."""
        state = self._net.observation()
        if not self.full_state:
            return state
        from xroute.policies.rl.observation import align, obstacle_grid

        grid = self._region.grid()
        if self._obstacle is None:  # the region changes only when the episode's paths are committed
            rows = np.asarray(self._region.candidates)
            nets = rows[:, FEATURE_COLUMNS.index("net")]
            routed = np.array([self._region.is_routed(i) for i in range(len(rows))], dtype=bool)
            self._obstacle = align(obstacle_grid(grid, nets[~routed], nets[routed]).astype(np.float32))
        n = self._net
        shape = grid["flags"].shape
        net = np.zeros((3, *shape), np.float32)
        for ch, nodes in enumerate(([n.head], sorted(n.visited),
                                    [int(v) for t, r in zip(n.terminals, n.reached) if not r for v in t])):
            if len(nodes):
                net[ch].reshape(-1)[np.asarray(nodes, dtype=np.int64)] = 1.0
        return {"state": state, "obstacle": self._obstacle.copy(), "net": align(net)}

    def _finish(self, illegal: bool, truncated: bool) -> float:
        """Commits the net's paths; the reward the end of the episode adds (violations, HPWL bonus)."""
        n = self._net
        paths = n.paths()
        unreached = int(self._region.route_net_paths(n.cand, paths)["unreached"])
        self._kept[n.cand] = paths
        self._region_holds = self._k + 1
        metrics = self._region.metrics()
        cost = self.weights.region_cost(metrics, self.dbu)
        correction = (self._cost - cost) - self._total  # the violations (and nothing else, up to rounding)
        self._cost = cost
        bonus = float(n.hpwl) if n.connected else 0.0
        self._total += correction + bonus
        self._end = {"illegal": illegal, "cut": truncated, "paths": paths, "metrics": metrics, "unreached": unreached}
        return correction + bonus

    def _info(self) -> dict[str, Any]:
        n = self._net
        info = {"box": tuple(self._walk[self._region_i]), "candidate": n.cand,
                "net": int(self._region.candidates[n.cand][FEATURE_COLUMNS.index("net")]), "attempt": self._attempt, "head": n.head,
                "pins": n.pins, "hpwl": n.hpwl, "t_min": n.t_min, "total_reward": self._total,
                "connected": n.connected, "moves": n.moves, "cost": self._cost}
        if self._end is not None:
            info.update(self._end)
        return info

    @property
    def region(self) -> Any:
        """The engine Region of the current episode."""
        return self._region

    def close(self) -> None:
        self._net = None
        self._region = None
        self._session = None
        self._design = None


def net_routing_env(testcase_name: str = "demo", region_size: int = 1,
                    region_location: tuple[int, int] | list[tuple[int, int]] | None = None,
                    net_loop: int = 1, **kwargs: Any) -> NetRoutingEnv:
    """The paper's net-routing env (see :class:`NetRoutingEnv`)."""
    return NetRoutingEnv(testcase_name, region_size, region_location, net_loop, **kwargs)

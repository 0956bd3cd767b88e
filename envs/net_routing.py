"""``xroute/NetRouting-v0``: the paper's second task, routing one net step by step from its head.

One episode routes one net of a region (a region of ``testcase_name`` cut as the router's first
iteration cuts them, or the static region of ``region_dir`` written by ``xroute make-region``).
The nets of a region come in the built-in heuristic order (:func:`xroute.policy.heuristic_order`;
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
more terminals left, the head jumps to the node of the tree built so far (terminals reached and
paths) closest to the nearest unreached terminal. The episode terminates when every terminal is
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

Reward of a step: ``cost(s) - cost(s')`` with the paper's cost ``0.5 WL(µm) + 4 vias + 500
violations`` (:class:`xroute.config.CostSection`). Wirelength and vias are counted per move; the
violations (``Region.metrics()``, a full check of the box) once, when the net's paths are committed
at the end of the episode: the last step's reward carries the difference, so an episode's rewards
add up to exactly cost(before the net) - cost(after it). Plus ``HPWL(net)`` when every terminal
is connected. ``HPWL`` is the half perimeter of the net's terminal nodes in grid steps, x + y + z
(the paper's grid unit; see :func:`net_hpwl`), ``pin_count`` its terminals in the region, and
``T_min = -t_min_scale * HPWL * pin_count``.

Seeding: ``reset(seed=s)`` restarts from the first net of the first region (attempt 1); the env
draws nothing from ``self.np_random``: same seed and actions, same episode.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from xroute.config import CostSection
from xroute.policy import FEATURE_COLUMNS, heuristic_order

DIRECTIONS = ("UP", "DOWN", "NORTH", "SOUTH", "EAST", "WEST")
OBSERVATION_SIZE = 12
STATE_FIELDS = ("head_x", "head_y", "head_z", "dx", "dy", "dz") + tuple(f"edge_{d.lower()}" for d in DIRECTIONS)


def net_hpwl(coords: np.ndarray) -> int:
    """HPWL of terminal nodes in grid steps: (max - min) over x, y and z of their (x, y, z) indices."""
    c = np.asarray(coords, dtype=np.int64).reshape(-1, 3)
    if len(c) == 0:
        return 0
    return int((c.max(axis=0) - c.min(axis=0)).sum())


class _Net:
    """The episode's net: terminals, tree, paths, head."""

    def __init__(self, env: NetRoutingEnv, cand: int, terminals: list[np.ndarray], start: int) -> None:
        self.cand = cand
        self.terminals = terminals
        self.reached = [False] * len(terminals)
        self.reached[0] = True
        self.tree: set[int] = set(int(v) for v in terminals[0])
        self.paths: list[list[int]] = []
        self.path = [int(start)]
        self.visited: set[int] = set(self.tree)
        self.head = int(start)
        coords = env._coords(np.concatenate(terminals))
        self.hpwl = net_hpwl(coords)
        self.pins = len(terminals)
        self.t_min = -float(env.t_min_scale) * max(1, self.hpwl) * self.pins
        self.total = 0.0
        self.moves = 0

    @property
    def connected(self) -> bool:
        return all(self.reached)

    def terminal_of(self, v: int) -> int:
        for t, nodes in enumerate(self.terminals):
            if not self.reached[t] and v in self._sets[t]:
                return t
        return -1

    def index_sets(self) -> None:
        self._sets = [set(int(v) for v in nodes) for nodes in self.terminals]


class NetRoutingEnv(gym.Env):
    """Routing one net per episode, step by step from its head (see the module docstring).

    observation_space: Box(-inf, inf, (12,), float32); action_space: Discrete(6).
    """

    metadata = {"render_modes": []}

    def __init__(
        self,
        testcase_name: str = "demo",
        region_size: int = 1,
        region_location: tuple[int, int] | None = None,
        net_loop: int = 1,
        *,
        region_dir: str | None = None,
        steps: int = 1,
        weights: CostSection = CostSection(),
        t_min_scale: float = 1.0,
    ) -> None:
        for name, value in (("region_size", region_size), ("net_loop", net_loop), ("steps", steps)):
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
        if not t_min_scale > 0:
            raise ValueError(f"t_min_scale must be > 0, got {t_min_scale!r}")
        self.testcase_name = testcase_name
        self.region_dir = None if region_dir is None else str(region_dir)
        self.region_size = int(region_size)
        self.region_location = None if region_location is None else (int(region_location[0]), int(region_location[1]))
        self.net_loop = int(net_loop)
        self.steps = int(steps)
        self.weights = weights
        self.t_min_scale = float(t_min_scale)
        self.observation_space = spaces.Box(-np.inf, np.inf, (OBSERVATION_SIZE,), np.float32)
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
        self._net: _Net | None = None

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
                if self.region_location is not None:
                    walk = [w for w in walk if w[0] == self.region_location]
                    if not walk:
                        raise ValueError(f"region_location {self.region_location} is not the lower-left GCell of a "
                                         f"{self.region_size}x{self.region_size} region of {self.testcase_name}")
                self._walk = [box for _, box in walk]
        self.dbu = int(self._design.dbu_per_micron)
        self._region_i = -1
        self._next_region()

    def _routable(self, region: Any) -> list[int]:
        rows = np.asarray(region.candidates, dtype=np.int32)
        out = []
        for c in heuristic_order(rows):
            terms = [t for t in region.terminal_nodes(int(c)) if len(t)]
            if len(terms) >= 2:
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
        g = region.grid()
        self._xs = np.asarray(g["xs"], dtype=np.int64)
        self._ys = np.asarray(g["ys"], dtype=np.int64)
        self._nz, self._ny, self._nx = g["flags"].shape
        self._cost = self.weights.region_cost(region.metrics(), self.dbu)

    def _coords(self, nodes: Any) -> np.ndarray:
        n = np.asarray(nodes, dtype=np.int64)
        return np.stack([n % self._nx, (n // self._nx) % self._ny, n // (self._nx * self._ny)], axis=-1)

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
        cand = self._nets[self._k]
        terms = [np.asarray(t, dtype=np.int64) for t in self._region.terminal_nodes(cand) if len(t)]
        start = None if options is None else options.get("start_node")
        if start is None:
            start = self._default_start(terms)
        elif int(start) not in set(int(v) for v in terms[0]):
            raise ValueError(f"start_node {start} is not a node of the net's first terminal {terms[0].tolist()}")
        self._net = _Net(self, cand, terms, int(start))
        self._net.index_sets()
        return self._observation(), self._info()

    def _dbu_xy(self, nodes: Any) -> np.ndarray:
        c = self._coords(nodes)
        return np.stack([self._xs[c[..., 0]], self._ys[c[..., 1]], c[..., 2]], axis=-1)

    def _nearest(self, sources: np.ndarray, targets: np.ndarray) -> tuple[int, int]:
        """(source, target) pair closest in DBU (then in z), first in order on ties."""
        a = self._dbu_xy(sources)[:, None, :]
        b = self._dbu_xy(targets)[None, :, :]
        d = np.abs(a[..., 0] - b[..., 0]) + np.abs(a[..., 1] - b[..., 1])
        key = d * 64 + np.abs(a[..., 2] - b[..., 2])
        i, j = np.unravel_index(int(np.argmin(key)), key.shape)
        return int(sources[i]), int(targets[j])

    def _default_start(self, terms: list[np.ndarray]) -> int:
        return self._nearest(terms[0], np.concatenate(terms[1:]))[0]

    def _unreached_nodes(self) -> np.ndarray:
        n = self._net
        return np.concatenate([t for t, r in zip(n.terminals, n.reached) if not r])

    def _moves(self) -> tuple[np.ndarray, np.ndarray]:
        nodes, costs = self._region.moves(self._net.cand, self._net.head)
        return np.asarray(nodes, dtype=np.int64), np.asarray(costs, dtype=np.float64)

    def _observation(self) -> np.ndarray:
        n = self._net
        obs = np.zeros(OBSERVATION_SIZE, np.float32)
        head = self._coords(n.head)
        obs[0:3] = head
        if not n.connected:
            _, target = self._nearest(np.asarray([n.head]), self._unreached_nodes())
            obs[3:6] = self._coords(target) - head
        nodes, costs = self._moves()
        for d in range(len(DIRECTIONS)):
            v = int(nodes[d])
            obs[6 + d] = -1.0 if v < 0 or v in n.visited else costs[d] / self.dbu
        return obs

    def legal_actions(self) -> np.ndarray:
        """bool[6]: the directions that are legal moves from the head now."""
        if self._net is None:
            return np.zeros(len(DIRECTIONS), dtype=bool)
        nodes, _ = self._moves()
        return np.array([v >= 0 and int(v) not in self._net.visited for v in nodes], dtype=bool)

    def _move_cost(self, u: int, v: int) -> float:
        cu, cv = self._coords(u), self._coords(v)
        if cu[2] != cv[2]:
            return self.weights.via_weight
        length = abs(int(self._xs[cu[0]] - self._xs[cv[0]])) + abs(int(self._ys[cu[1]] - self._ys[cv[1]]))
        return self.weights.wirelength_weight * length / self.dbu

    def step(self, action: Any):
        n = self._net
        if n is None or getattr(n, "done", False):
            raise RuntimeError("the episode is over (or never started): call reset()")
        a = int(np.asarray(action).reshape(-1)[0])
        if not 0 <= a < len(DIRECTIONS):
            raise ValueError(f"action must be a direction 0..5, got {action!r}")
        reward = 0.0
        illegal = False
        for _ in range(self.steps):
            nodes, _ = self._moves()
            v = int(nodes[a])
            if v < 0 or v in n.visited:
                illegal = True
                break
            reward -= self._move_cost(n.head, v)
            n.moves += 1
            n.head = v
            n.path.append(v)
            n.visited.add(v)
            t = n.terminal_of(v)
            if t >= 0:
                self._connect(t)
                break
        terminated = illegal or n.connected
        truncated = False
        if not terminated and n.total + reward < n.t_min:
            truncated = True
        n.total += reward
        info: dict[str, Any] = {}
        if terminated or truncated:
            reward += self._finish(illegal, truncated)
            info = self._info()
        else:
            info = self._info()
        return self._observation(), float(reward), terminated, truncated, info

    def _connect(self, t: int) -> None:
        n = self._net
        n.reached[t] = True
        n.paths.append(n.path)
        n.tree.update(n.path)
        n.tree.update(int(v) for v in n.terminals[t])
        n.visited = set(n.tree)
        if not n.connected:  # the next segment starts from the tree node closest to what is left
            head, _ = self._nearest(np.asarray(sorted(n.tree), dtype=np.int64), self._unreached_nodes())
            n.head = head
        n.path = [n.head]

    def _finish(self, illegal: bool, truncated: bool) -> float:
        """Commits the net's paths; the reward the end of the episode adds (violations, HPWL bonus)."""
        n = self._net
        paths = list(n.paths)
        if len(n.path) > 1:
            paths.append(n.path)
        self._region.route_net_paths(n.cand, paths)
        self._kept[n.cand] = paths
        self._region_holds = self._k + 1
        metrics = self._region.metrics()
        cost = self.weights.region_cost(metrics, self.dbu)
        correction = (self._cost - cost) - n.total  # the violations (and nothing else, up to rounding)
        self._cost = cost
        n.total += correction
        bonus = float(n.hpwl) if n.connected else 0.0
        n.total += bonus
        n.done = True
        n.illegal, n.truncated, n.metrics = illegal, truncated, metrics
        return correction + bonus

    def _info(self) -> dict[str, Any]:
        n = self._net
        info = {"box": tuple(self._walk[self._region_i]), "candidate": n.cand,
                "net": int(self._region.candidates[n.cand][FEATURE_COLUMNS.index("net")]), "attempt": self._attempt, "head": n.head,
                "pins": n.pins, "hpwl": n.hpwl, "t_min": n.t_min, "total_reward": n.total,
                "connected": n.connected, "moves": n.moves, "cost": self._cost}
        if getattr(n, "done", False):
            info.update({"illegal": n.illegal, "cut": n.truncated, "paths": [list(p) for p in self._kept[n.cand]],
                         "metrics": n.metrics})
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


def net_routing_env(testcase_name: str = "demo", region_size: int = 1, region_location: tuple[int, int] | None = None,
                    net_loop: int = 1, **kwargs: Any) -> NetRoutingEnv:
    """The paper's net-routing env (see :class:`NetRoutingEnv`)."""
    return NetRoutingEnv(testcase_name, region_size, region_location, net_loop, **kwargs)

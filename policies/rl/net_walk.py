"""One net walked step by step from its head on an engine Region's grid graph: the core of
``xroute/NetRouting-v0`` (:mod:`xroute.envs.net_routing`, which documents the semantics) and of
the net-router policy (:mod:`xroute.policies.net_router`). Reads the region (``terminal_nodes``,
``moves``, ``grid``); commits nothing: the caller hands :meth:`NetWalk.paths` to
``Region.route_net_paths``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from xroute.config import CostSection

DIRECTIONS = ("UP", "DOWN", "NORTH", "SOUTH", "EAST", "WEST")
OBSERVATION_SIZE = 12
STATE_FIELDS = ("head_x", "head_y", "head_z", "dx", "dy", "dz") + tuple(f"edge_{d.lower()}" for d in DIRECTIONS)


def net_hpwl(coords: np.ndarray) -> int:
    """HPWL of terminal nodes in grid steps: (max - min) over x, y and z of their (x, y, z) indices."""
    c = np.asarray(coords, dtype=np.int64).reshape(-1, 3)
    if len(c) == 0:
        return 0
    return int((c.max(axis=0) - c.min(axis=0)).sum())


def routable_terminals(region: Any, cand: int) -> list[np.ndarray]:
    """The candidate's terminals that have grid nodes (a net needs two to be walked)."""
    return [np.asarray(t, dtype=np.int64) for t in region.terminal_nodes(int(cand)) if len(t)]


def _terminals(region: Any, cand: int) -> tuple[list[np.ndarray], list[bool]]:
    nodes = region.terminal_nodes(int(cand))
    joined = region.terminal_joined(int(cand))
    keep = [k for k, t in enumerate(nodes) if len(t)]
    return [np.asarray(nodes[k], dtype=np.int64) for k in keep], [bool(joined[k]) for k in keep]


class NetWalk:
    """The head, terminals, tree and paths of one net being walked (see the module docstring)."""

    def __init__(self, region: Any, cand: int, dbu_per_micron: int, weights: CostSection | None = None,
                 t_min_scale: float = 1.0, start: int | None = None) -> None:
        self.region = region
        self.cand = int(cand)
        self.dbu = int(dbu_per_micron)
        self.weights = weights if weights is not None else CostSection()
        g = region.grid()
        self._xs = np.asarray(g["xs"], dtype=np.int64)
        self._ys = np.asarray(g["ys"], dtype=np.int64)
        self._nz, self._ny, self._nx = g["flags"].shape
        self.terminals, self.joined = _terminals(region, cand)
        if len(self.terminals) < 2:
            raise ValueError(f"candidate {cand} has fewer than two terminals on the grid")
        self._sets = [{int(v) for v in t} for t in self.terminals]
        if start is None:
            start = self._nearest(self.terminals[0], np.concatenate(self.terminals[1:]))[0]
        elif int(start) not in self._sets[0]:
            raise ValueError(f"start_node {start} is not a node of the net's first terminal {self.terminals[0].tolist()}")
        self.reached = [False] * len(self.terminals)
        self.reached[0] = True
        # A pin's access points are one conductor: all of them are on the tree; of a free crossing's
        # alternatives, only the node used.
        self.tree: set[int] = set(self._sets[0]) if self.joined[0] else {int(start)}
        self.visited: set[int] = set(self.tree)
        self.done_paths: list[list[int]] = []
        self.head = int(start)
        self.path = [self.head]
        self.hpwl = net_hpwl(self.coords(np.concatenate(self.terminals)))
        self.pins = len(self.terminals)
        self.t_min = -float(t_min_scale) * max(1, self.hpwl) * self.pins
        self.moves = 0
        self.move_cost = 0.0  # the paper's cost of the moves so far (wirelength and vias)

    # -- geometry ----------------------------------------------------------------------------------

    def coords(self, nodes: Any) -> np.ndarray:
        n = np.asarray(nodes, dtype=np.int64)
        return np.stack([n % self._nx, (n // self._nx) % self._ny, n // (self._nx * self._ny)], axis=-1)

    def _dbu_xyz(self, nodes: Any) -> np.ndarray:
        c = self.coords(nodes)
        return np.stack([self._xs[c[..., 0]], self._ys[c[..., 1]], c[..., 2]], axis=-1)

    def _nearest(self, sources: np.ndarray, targets: np.ndarray) -> tuple[int, int]:
        """(source, target) pair closest in DBU (then in z), first in order on ties."""
        a = self._dbu_xyz(sources)[:, None, :]
        b = self._dbu_xyz(targets)[None, :, :]
        key = (np.abs(a[..., 0] - b[..., 0]) + np.abs(a[..., 1] - b[..., 1])) * 64 + np.abs(a[..., 2] - b[..., 2])
        i, j = np.unravel_index(int(np.argmin(key)), key.shape)
        return int(sources[i]), int(targets[j])

    def _unreached_nodes(self) -> np.ndarray:
        return np.concatenate([t for t, r in zip(self.terminals, self.reached) if not r])

    # -- state -------------------------------------------------------------------------------------

    @property
    def connected(self) -> bool:
        return all(self.reached)

    def paths(self) -> list[list[int]]:
        """The node paths walked: one per terminal reached, plus the partial one (two nodes or more)."""
        out = [list(p) for p in self.done_paths]
        if len(self.path) > 1:
            out.append(list(self.path))
        return out

    def _edges(self) -> tuple[np.ndarray, np.ndarray]:
        nodes, costs = self.region.moves(self.cand, self.head)
        return np.asarray(nodes, dtype=np.int64), np.asarray(costs, dtype=np.float64)

    def legal(self) -> np.ndarray:
        """bool[6]: the directions that are legal moves from the head."""
        nodes, _ = self._edges()
        return np.array([v >= 0 and int(v) not in self.visited for v in nodes], dtype=bool)

    def observation(self) -> np.ndarray:
        obs = np.zeros(OBSERVATION_SIZE, np.float32)
        head = self.coords(self.head)
        obs[0:3] = head
        if not self.connected:
            _, target = self._nearest(np.asarray([self.head]), self._unreached_nodes())
            obs[3:6] = self.coords(target) - head
        nodes, costs = self._edges()
        for d in range(len(DIRECTIONS)):
            v = int(nodes[d])
            obs[6 + d] = -1.0 if v < 0 or v in self.visited else costs[d] / self.dbu
        return obs

    # -- moves -------------------------------------------------------------------------------------

    def _cost(self, u: int, v: int) -> float:
        cu, cv = self.coords(u), self.coords(v)
        if cu[2] != cv[2]:
            return self.weights.via_weight
        length = abs(int(self._xs[cu[0]] - self._xs[cv[0]])) + abs(int(self._ys[cu[1]] - self._ys[cv[1]]))
        return self.weights.wirelength_weight * length / self.dbu

    def move(self, direction: int) -> tuple[float, bool, bool]:
        """One edge from the head: (reward = -cost of the move, illegal, a terminal was reached)."""
        nodes, _ = self._edges()
        v = int(nodes[direction])
        if v < 0 or v in self.visited:
            return 0.0, True, False
        cost = self._cost(self.head, v)
        self.move_cost += cost
        self.moves += 1
        self.head = v
        self.path.append(v)
        self.visited.add(v)
        for t, s in enumerate(self._sets):
            if not self.reached[t] and v in s:
                self._connect(t)
                return -cost, False, True
        return -cost, False, False

    def _connect(self, t: int) -> None:
        self.reached[t] = True
        self.done_paths.append(self.path)
        self.tree.update(self.path)
        if self.joined[t]:
            self.tree.update(int(v) for v in self.terminals[t])
        self.visited = set(self.tree)
        if not self.connected:  # the next segment starts from the tree node closest to what is left
            self.head, _ = self._nearest(np.asarray(sorted(self.tree), dtype=np.int64), self._unreached_nodes())
        self.path = [self.head]


def walk_net(walk: NetWalk, act: Any, steps: int = 1, max_moves: int | None = None) -> str:
    """Walks a net with ``act(observation, legal) -> direction`` until it ends as the env's episode
    would: "connected", "illegal" or "cut" (total reward below T_min), or "moves" (``max_moves``)."""
    total = 0.0
    while True:
        a = int(act(walk.observation(), walk.legal()))
        reward = 0.0
        for _ in range(steps):
            r, illegal, hit = walk.move(a)
            reward += r
            if illegal:
                return "illegal"
            if hit:
                break
        if walk.connected:
            return "connected"
        total += reward
        if total < walk.t_min:
            return "cut"
        if max_moves is not None and walk.moves >= max_moves:
            return "moves"

"""``xroute/NetOrdering-v0``: net ordering, training mode. Each region of a testcase is an episode.

The env walks the regions of ``testcase_name`` (``region_size`` x ``region_size`` GCells, row by
row from the lower-left, as the router's first iteration cuts them; regions with no candidate net
are skipped). Each region is replayed ``region_loop`` times from the same state (only the last
replay is committed into the design, so later regions see it as routed neighbours); after the last
region the walk starts again on a freshly loaded design, ``testcase_loop`` passes in all
(:attr:`finished` turns True after them; the env keeps going if asked). ``region_location``
(GCell column, row of a region's lower-left) restricts the walk to that one region, which is then
never committed: every episode starts from the same state.

``in_context=True`` draws the regions of the router's own first pass instead
(:func:`xroute.session.first_pass`, routed once per env with the heuristic at ``region_size``,
default then the router's region size): each episode opens its region in the state the first pass
routed it in, every region of an earlier colour (``(rx % 2) + 2 (ry % 2)``) committed with its
crossing points chosen and the rest unrouted, so the cost counts what the order causes next to
real neighbours rather than next to an empty design. Nothing is committed; the walk follows the
flow's order (colour, then row by row), or a permutation with ``region_order="random"``, and
starts over after the last region without reloading anything.

Spaces and reward: see :mod:`xroute.envs.core`. One step routes one net; the episode
terminates when every candidate of the region is routed.

Seeding: ``reset(seed=s)`` restarts the walk from the first region on a fresh design (with
``region_order="random"``, a permutation of the regions drawn from ``self.np_random``);
``reset()`` moves on to the next episode. Same seed and actions, same observations and rewards.
"""

from __future__ import annotations

from typing import Any


from xroute.envs.core import (
    DEFAULT_MAX_CANDIDATES,
    CostWeights,
    RegionEnv,
    RegionStepper,
    RewardFn,
)


class NetOrderingTrainingEnv(RegionEnv):
    """Net ordering on the regions of a testcase, one region per episode (see the module docstring).

    observation_space: Dict(obstacle (3, 64, 64), nets (M, 7, 3, 64, 64), net_features (M, S),
    action_mask MultiBinary(M)), or with ``observation="compact"`` Dict(set_features (M, F), action_mask);
    action_space: Discrete(M), M = ``max_candidates``.
    """

    def __init__(
        self,
        testcase_name: str = "ispd18_test1",
        region_size: int | None = None,
        testcase_loop: int = 1,
        region_location: tuple[int, int] | None = None,
        region_loop: int = 1,
        *,
        max_candidates: int = DEFAULT_MAX_CANDIDATES,
        weights: CostWeights = CostWeights(),
        reward_fn: RewardFn | None = None,
        region_order: str = "sequential",
        in_context: bool = False,
        render_mode: str | None = None,
        observation: str = "grid",
    ) -> None:
        if region_size is None:
            from xroute.defaults import REGION_SIZE

            region_size = REGION_SIZE if in_context else 1  # in context 0: the router's (the first pass's)
        for name, value in (("region_size", region_size), ("testcase_loop", testcase_loop), ("region_loop", region_loop)):
            auto = name == "region_size" and in_context and value == 0
            if isinstance(value, bool) or not isinstance(value, int) or (value < 1 and not auto):
                raise ValueError(f"{name} must be a positive integer, got {value!r}")
        if region_order not in ("sequential", "random"):
            raise ValueError(f"region_order must be 'sequential' or 'random', got {region_order!r}")
        self._init_spaces(max_candidates, observation, render_mode, weights, reward_fn)
        self.in_context = bool(in_context)
        self.testcase_name = testcase_name
        self.region_size = region_size
        self.testcase_loop = testcase_loop
        self.region_location = None if region_location is None else (int(region_location[0]), int(region_location[1]))
        self.region_loop = region_loop
        self.region_order = region_order
        self.passes_done = 0
        self._design: Any = None
        self._session: Any = None
        self._first_pass: Any = None  # in context: the first pass, routed once
        self._dirty = True  # the design holds committed regions (or none is loaded)
        # (location, box, index of the region in the first pass or -1)
        self._walk: list[tuple[tuple[int, int], tuple[int, int, int, int], int]] = []
        self._next = 0  # position in _walk of the next region
        self._replay = 0  # replays of the current region done
        self._stepper: RegionStepper | None = None
        self._box: tuple[int, int, int, int] | None = None
        self._location: tuple[int, int] | None = None
        self._index = -1

    @property
    def finished(self) -> bool:
        """True once ``testcase_loop`` passes over the testcase are done."""
        return self.passes_done >= self.testcase_loop

    def _fresh_design(self) -> None:
        from xroute import load_design
        from xroute.session import first_pass, open_session

        if self.in_context:
            if self._first_pass is None:
                self._design = load_design(self.testcase_name)
                self._session = open_session(self._design)
                self._first_pass = first_pass(self._session, self.region_size)
                self.region_size = int(self._first_pass.report["region_size"])  # 0 resolved
            walk = [(tuple(loc), tuple(box), i) for i, (loc, box, _colour, _nets) in enumerate(self._first_pass.regions)]
        else:
            if self._dirty or self._design is None:
                self._session = None
                self._design = load_design(self.testcase_name)
                self._session = open_session(self._design)
                self._dirty = False
            walk = [(tuple(loc), tuple(box), -1) for loc, box in self._session.regions(self.region_size)]
        if self.region_location is not None:
            walk = [w for w in walk if w[0] == self.region_location]
            if not walk:
                raise ValueError(f"region_location {self.region_location} is not the lower-left GCell of a "
                                 f"{self.region_size}x{self.region_size} region of {self.testcase_name}")
        if self.region_order == "random":
            walk = [walk[i] for i in self.np_random.permutation(len(walk))]
        self._walk = walk
        self._next = 0
        self._replay = 0

    def _open(self, box: tuple[int, int, int, int], index: int) -> Any:
        """The engine Region: the first pass's region ``index`` in context, else ``box`` as the design is."""
        return self._first_pass.open_region(index) if index >= 0 else self._session.open_region(box)

    def _open_next(self) -> None:
        """Replays the current region, or commits it and opens the next one with a candidate net."""
        current = self._stepper
        if current is not None and self._replay < self.region_loop:
            self._replay += 1  # the unfinished copy is dropped, never committed
            self._stepper = self._stepper_for(self._open(self._box, self._index))
            return
        # A lone region (region_location) or one in context is never committed.
        if current is not None and len(self._walk) > 1 and not self.in_context:
            current.region.route_rest("heuristic")  # an episode cut short still leaves a routed region
            current.region.commit()
            self._dirty = True
        skipped = 0
        while True:
            if self._next >= len(self._walk):
                self.passes_done += 1
                self._fresh_design()
            location, box, index = self._walk[self._next]
            self._next += 1
            region = self._open(box, index)
            if len(region.candidates):
                break
            skipped += 1
            if skipped > len(self._walk):
                raise RuntimeError(f"no region of {self.testcase_name} has a net to route")
        self._stepper = self._stepper_for(region)
        self._box, self._location, self._index, self._replay = box, location, index, 1

    def _stepper_for(self, region: Any) -> RegionStepper:
        return RegionStepper(region, self._design.dbu_per_micron, self.max_candidates, self.weights, self.reward_fn,
                             self.observation)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        if seed is not None or self._session is None:
            self._dirty = True  # a seeded reset starts from a freshly loaded design
            self._stepper = None
            self.passes_done = 0
            self._fresh_design()
        self._open_next()
        observation = self._stepper.observation()
        return observation, self._with_mask(self._info())

    def _info(self) -> dict[str, Any]:
        s = self._stepper
        return {"region_location": self._location, "box": self._box, "candidates": len(s.rows),
                "replay": self._replay, "pass": self.passes_done, "cost": s.cost, "metrics": s.metrics,
                "region_size": self.region_size, "in_context": self.in_context}

    def step(self, action: int):
        observation, reward, done, info = self._step_region(action)
        return observation, reward, done, False, info

    def close(self) -> None:
        self._stepper = None
        self._first_pass = None
        self._session = None
        self._design = None


def ordering_training_env(testcase_name: str = "ispd18_test1", region_size: int | None = None, testcase_loop: int = 1,
                          region_location: tuple[int, int] | None = None, region_loop: int = 1,
                          **kwargs: Any) -> NetOrderingTrainingEnv:
    """The paper's training-mode env (see :class:`NetOrderingTrainingEnv`)."""
    return NetOrderingTrainingEnv(testcase_name, region_size, testcase_loop, region_location, region_loop, **kwargs)

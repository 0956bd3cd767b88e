"""The net-order policy seam: in every region the router asks a policy in which order to route its nets.

A policy is any object with a ``name`` and an ``order(region, features)`` method (the
:class:`NetOrderPolicy` protocol):

* ``region`` is a dict ``{"iteration": int, "region": int, "box": (xlo, ylo, xhi, yhi)}`` (box in DBU);
* ``features`` is an ``int32[n, len(FEATURE_COLUMNS)]`` array, one row per candidate net of the
  region, columns :data:`FEATURE_COLUMNS` (the engine's ``POLICY_FEATURES``; read them by name,
  new columns are added at the end):

  ========== ===================================================================
  net        net id (index into the design's nets)
  pins       pins of the net inside the region
  terminals  all terminals of the net in the region (pins + region-edge crossings)
  access_points  terminal nodes in the region's grid
  bbox_xlo .. bbox_yhi  bounding box of those terminal nodes (DBU)
  net_pins   pins of the whole net
  crossings  terminals on the region edge (where the net crosses into a neighbour)
  guide_xlo .. guide_yhi  bounding box of the net's route guides inside the region (DBU; the
             region box when no guide of the net overlaps it)
  routed_nearby  grid nodes (all layers) inside the net's terminal bounding box that routing
             of this region already uses: 0 before any net is routed, then updated
  ========== ===================================================================

* the result is a permutation of ``range(n)``: the candidates' row indices, first routed first.

**Sequential policies** (the MDP of the XRoute paper): an object with ``name`` and
``next_net(region, features) -> int`` (the :class:`SequentialPolicy` protocol) is asked for one
net at a time: the router calls it after every routed net with the candidates still unrouted
(``features`` has their rows only, ``routed_nearby`` as the region is now) and routes the row it
returns. A policy with ``next_net`` is used that way even if it also has ``order``; one with
``order`` only gives the whole order in one call (the fast path).

**Search policies** ``rollout``, ``victims`` and ``best-of-K`` (:class:`RolloutPolicy`,
:class:`VictimsPolicy`, :class:`BestOfPolicy`) run in the engine: they route trial orders on
copies of the region, score each by the region's cost (0.5 WL(um) + 4 vias + 500 markers inside
the region) and keep the cheapest, the heuristic's order among the trials, so a region never
ends costlier than the heuristic's routing. ``budget`` = trial routings per region (see engine_cpp/loop/README.md).

A policy that sets ``needs_region = True`` (an ONNX model, a learning environment) also finds, in
``region["engine_region"]``, the engine's Region being routed, lent for that one call: its live
grid views (``grid()``), ``candidates``, ``unrouted()`` and ``route_net(i)``. It may route some
nets itself; the returned order then applies to those still unrouted. The built-ins never ask.

The built-ins :class:`HeuristicPolicy` and :class:`RandomPolicy` carry a ``builtin`` name, which
tells the router to run the engine's own C++ implementation (no Python call per region); their
``order`` methods are Python versions for use outside the router. Any other policy is called
from the routing threads once per region (with the GIL held, one call at a time).

This module imports no engine and no torch.
"""

from __future__ import annotations

import re
from typing import Any, Callable, Protocol, Sequence, runtime_checkable

import numpy as np

from xroute.errors import PolicyError, did_you_mean

FEATURE_COLUMNS: tuple[str, ...] = (
    "net",
    "pins",
    "terminals",
    "access_points",
    "bbox_xlo",
    "bbox_ylo",
    "bbox_xhi",
    "bbox_yhi",
    "net_pins",
    "crossings",
    "guide_xlo",
    "guide_ylo",
    "guide_xhi",
    "guide_yhi",
    "routed_nearby",
)
"""Columns of the ``features`` array (the same as ``xroute._engine.POLICY_FEATURES``)."""

_COL = {name: i for i, name in enumerate(FEATURE_COLUMNS)}


_BEST_OF = re.compile(r"best-of-([0-9]{1,6})")


def is_builtin_name(name: str) -> bool:
    """True for a built-in policy's name: one of :data:`BUILTIN_POLICIES` or ``best-of-K``."""
    return name in BUILTIN_POLICIES or _BEST_OF.fullmatch(name) is not None



@runtime_checkable
class NetOrderPolicy(Protocol):
    """What the router needs from a net-order policy."""

    name: str

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        """A permutation of ``range(len(features))``: the order in which the region's nets are routed."""
        ...


@runtime_checkable
class SequentialPolicy(Protocol):
    """A policy asked for one net at a time, after every routed net."""

    name: str

    def next_net(self, region: dict[str, Any], features: np.ndarray) -> int:
        """The row index (into ``features``, the unrouted candidates) of the net to route next."""
        ...


def heuristic_order(features: np.ndarray) -> np.ndarray:
    """The engine's heuristic order, in numpy: smallest terminal bounding box (half perimeter) first,
    then more terminals first, then lower net id (short, constrained nets take the scarce tracks
    before long flexible ones detour around them)."""
    f = np.asarray(features, dtype=np.int64)
    if len(f) == 0:
        return np.zeros(0, dtype=np.int64)
    half_perimeter = (f[:, _COL["bbox_xhi"]] - f[:, _COL["bbox_xlo"]]) + (f[:, _COL["bbox_yhi"]] - f[:, _COL["bbox_ylo"]])
    # np.lexsort sorts by the last key first.
    return np.lexsort((f[:, _COL["net"]], -f[:, _COL["terminals"]], half_perimeter))


class HeuristicPolicy:
    """The built-in heuristic order (see :func:`heuristic_order`); the router runs the C++ version."""

    name = "heuristic"
    builtin = "heuristic"

    @classmethod
    def from_settings(cls, seed: int, search_budget: int | None) -> HeuristicPolicy:
        return cls()

    def engine_arguments(self, seed: int) -> dict[str, Any]:
        return {"policy": "heuristic"}

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        return heuristic_order(features)

    def __repr__(self) -> str:
        return "HeuristicPolicy()"


class RandomPolicy:
    """A uniformly random order, reproducible from ``seed`` (with the iteration and region).

    The router runs the engine's C++ generator (seeded from seed, iteration, region); the
    Python :meth:`order` is seeded from the same values but uses numpy's generator, so its
    permutations are reproducible too but not the engine's.
    """

    name = "random"
    builtin = "random"

    def __init__(self, seed: int = 1) -> None:
        if seed < 0:
            raise PolicyError(f"random policy seed must be >= 0, got {seed}")
        self.seed = int(seed)

    @classmethod
    def from_settings(cls, seed: int, search_budget: int | None) -> RandomPolicy:
        return cls(seed)

    def engine_arguments(self, seed: int) -> dict[str, Any]:
        return {"policy": "random", "seed": self.seed}  # its own seed, not the route's

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        rng = np.random.default_rng([self.seed, int(region["iteration"]), int(region["region"])])
        return rng.permutation(len(features))

    def __repr__(self) -> str:
        return f"RandomPolicy(seed={self.seed})"


def _check_count(what: str, value: Any) -> int | None:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise PolicyError(f"{what} must be an integer >= 1, got {value!r}")
    return int(value)


class RolloutPolicy:
    """The engine's rollout search (see the module doc): in each region, nets named by the cheapest
    trial's markers are tried as the next net, the rest finished in heuristic order, and the best
    is committed, until none is left or ``budget`` trial routings are spent (None: the engine's
    default, ``xroute.defaults.SEARCH_BUDGET``). ``width``: at most this many candidates per step
    (0: all). Outside the router (no region to try orders on) :meth:`order` is the heuristic's."""

    name = "rollout"
    builtin = "rollout"

    def __init__(self, budget: int | None = None, width: int = 0) -> None:
        self.budget = _check_count("rollout search budget (trial routings per region)", budget)
        if isinstance(width, bool) or not isinstance(width, (int, np.integer)) or width < 0:
            raise PolicyError(f"rollout width must be an integer >= 0 (0: every candidate), got {width!r}")
        self.width = int(width)

    @classmethod
    def from_settings(cls, seed: int, search_budget: int | None) -> RolloutPolicy:
        return cls(search_budget)

    def engine_arguments(self, seed: int) -> dict[str, Any]:
        return {"policy": "rollout", "search_budget": check_search_budget("rollout search budget", self.budget),
                "search_width": self.width}

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        return heuristic_order(features)

    def __repr__(self) -> str:
        return f"RolloutPolicy(budget={self.budget}, width={self.width})"


class VictimsPolicy:
    """The engine's victims search (see the module doc): in each region the heuristic order is
    routed, then again with the *victims* of every trial so far first (the nets its markers leave
    in violation: of a two-net marker the net routed later, a one-net marker's own net), the
    others after them, both in heuristic order, until a trial names no new victim; the rest of
    ``budget`` trial routings (None: the engine's default) route the victims first in seeded random
    orders (seeded from the route's seed, the iteration, the region and the trial). The cheapest
    trial is kept. Outside the router :meth:`order` is the heuristic's."""

    name = "victims"
    builtin = "victims"

    def __init__(self, budget: int | None = None) -> None:
        self.budget = _check_count("victims search budget (trial routings per region)", budget)

    @classmethod
    def from_settings(cls, seed: int, search_budget: int | None) -> VictimsPolicy:
        return cls(search_budget)

    def engine_arguments(self, seed: int) -> dict[str, Any]:
        return {"policy": "victims", "search_budget": check_search_budget("victims search budget", self.budget),
                "seed": seed}

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        return heuristic_order(features)

    def __repr__(self) -> str:
        return f"VictimsPolicy(budget={self.budget})"


class BestOfPolicy:
    """The engine's best-of-K search: each region routed in K orders (the heuristic's and K-1
    random orders seeded from ``seed``, the iteration, the region and the trial), the cheapest
    kept. ``k`` None: the engine's default budget. Outside the router :meth:`order` is the heuristic's."""

    builtin = "bestof"

    def __init__(self, k: int | None = None, seed: int = 1) -> None:
        self.k = _check_count("best-of-K: K (trial routings per region)", k)
        if seed < 0:
            raise PolicyError(f"best-of-K seed must be >= 0, got {seed}")
        self.seed = int(seed)
        self.name = f"best-of-{self.k}" if self.k is not None else "bestof"

    @classmethod
    def from_settings(cls, seed: int, search_budget: int | None) -> BestOfPolicy:
        return cls(search_budget, seed)

    def engine_arguments(self, seed: int) -> dict[str, Any]:
        return {"policy": f"best-of-{check_search_budget('best-of-K: K', self.k)}", "seed": self.seed}

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        return heuristic_order(features)

    def __repr__(self) -> str:
        return f"BestOfPolicy(k={self.k}, seed={self.seed})"


BUILTINS: dict[str, Any] = {cls.builtin: cls for cls in (HeuristicPolicy, RandomPolicy, RolloutPolicy,
                                                          VictimsPolicy, BestOfPolicy)}
"""The one table of built-in policies: the engine runs each in C++, under its ``builtin`` name.
Each class makes itself from the run's settings (``from_settings(seed, search_budget)``, for
:func:`builtin_policy`) and gives the engine's arguments (``engine_arguments(seed)``, for the
router); a new built-in is a class here, added to this table, and its C++ side."""

BUILTIN_POLICIES: tuple[str, ...] = tuple(BUILTINS)
"""Policies the engine runs in C++, by name (files and models are resolved by :mod:`xroute.policies`);
``best-of-K`` (K an integer, e.g. ``best-of-8``) names :class:`BestOfPolicy` with that K too
(:func:`is_builtin_name`)."""


def check_search_budget(what: str, value: int | None) -> int:
    """A search policy's trial routings per region (None: the engine's default), checked against
    the engine's limit; :class:`RouteArgumentError` (one line) otherwise."""
    from xroute import defaults  # loads the engine: only when a route starts
    from xroute.errors import RouteArgumentError

    if value is None:
        return defaults.SEARCH_BUDGET
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= defaults.MAX_SEARCH_BUDGET:
        raise RouteArgumentError(f"{what} must be an integer in 1..{defaults.MAX_SEARCH_BUDGET}, got {value!r}")
    return value


class CallablePolicy:
    """Wraps any Python callable ``fn(region, features) -> order`` as a policy.

    ``name`` defaults to the callable's ``__name__``. The router calls it once per region.
    """

    builtin = None

    def __init__(self, fn: Callable[[dict[str, Any], np.ndarray], Sequence[int]], name: str | None = None) -> None:
        if not callable(fn):
            raise PolicyError(f"a policy needs a callable order(region, features), got {type(fn).__name__}")
        self.fn = fn
        self.name = name or getattr(fn, "__name__", None) or type(fn).__name__

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        return self.fn(region, features)

    def __repr__(self) -> str:
        return f"CallablePolicy({self.name!r})"


class CallableSequentialPolicy:
    """Wraps a Python callable ``fn(region, features) -> int`` as a sequential policy (its
    ``next_net``): asked after every routed net, with the unrouted candidates' rows."""

    builtin = None

    def __init__(self, fn: Callable[[dict[str, Any], np.ndarray], int], name: str | None = None) -> None:
        if not callable(fn):
            raise PolicyError(f"a sequential policy needs a callable next_net(region, features), got {type(fn).__name__}")
        self.fn = fn
        self.name = name or getattr(fn, "__name__", None) or type(fn).__name__

    def next_net(self, region: dict[str, Any], features: np.ndarray) -> int:
        return self.fn(region, features)

    def __repr__(self) -> str:
        return f"CallableSequentialPolicy({self.name!r})"


def check_order(order: Any, n: int, policy_name: str, source: str = "") -> list[int]:
    """``order`` as a list of ints if it is a permutation of ``range(n)``; otherwise a
    :class:`PolicyError` naming the policy (and ``source``, its file) and what is wrong."""
    where = (f"{source}: " if source else "") + f"net-order policy '{policy_name}'"
    try:
        values = np.asarray(order)
    except Exception as exc:  # noqa: BLE001 - anything that is not array-like
        raise PolicyError(f"{where} returned {type(order).__name__}, not a sequence of ints") from exc
    if values.ndim != 1 or (values.size and values.dtype.kind not in "iu"):
        raise PolicyError(f"{where} returned {type(order).__name__} of {values.dtype} with shape {values.shape}, "
                          f"not a sequence of {n} ints")
    if values.size != n:
        raise PolicyError(f"{where} returned {values.size} indices for {n} candidate nets; it must return a "
                          f"permutation of range({n})")
    out = [int(v) for v in values]
    seen = [False] * n
    for v in out:
        if v < 0 or v >= n:
            raise PolicyError(f"{where} returned index {v}, outside range({n})")
        if seen[v]:
            raise PolicyError(f"{where} returned index {v} twice; it must return a permutation of range({n})")
        seen[v] = True
    return out


def builtin_policy(name: str, seed: int = 1, search_budget: int | None = None) -> NetOrderPolicy:
    """The built-in policy called ``name`` (:func:`is_builtin_name`); ``random`` and best-of-K are
    seeded with ``seed``; ``search_budget`` is rollout's and victims' budget and ``bestof``'s K
    (None: the engine's default); ``best-of-K`` takes its K from the name."""
    if name in BUILTINS:
        return BUILTINS[name].from_settings(seed, search_budget)
    m = _BEST_OF.fullmatch(name)
    if m is not None:
        return BestOfPolicy(int(m.group(1)), seed)
    raise PolicyError(
        f"unknown policy '{name}'{did_you_mean(name, BUILTIN_POLICIES)}: use {', '.join(BUILTIN_POLICIES)}, best-of-K, "
        "or load a policy file or model with xroute.policies.get_policy"
    )

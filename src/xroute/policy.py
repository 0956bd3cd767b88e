"""The net-order policy seam: in every region the router asks a policy in which order to route its nets.

A policy is any object with a ``name`` and an ``order(region, features)`` method (the
:class:`NetOrderPolicy` protocol):

* ``region`` is a dict ``{"iteration": int, "region": int, "box": (xlo, ylo, xhi, yhi)}`` (box in DBU);
* ``features`` is an ``int32[n, 9]`` array, one row per candidate net of the region, columns
  :data:`FEATURE_COLUMNS` (the engine's ``POLICY_FEATURES``):

  ========== ===================================================================
  net        net id (index into the design's nets)
  pins       pins of the net inside the region
  terminals  all terminals of the net in the region (pins + region-edge crossings)
  access_points  terminal nodes in the region's grid
  bbox_xlo .. bbox_yhi  bounding box of those terminal nodes (DBU)
  net_pins   pins of the whole net
  ========== ===================================================================

* the result is a permutation of ``range(n)``: the candidates' row indices, first routed first.

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

from typing import Any, Callable, Protocol, Sequence, runtime_checkable

import numpy as np

from xroute.errors import PolicyError

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
)
"""Columns of the ``features`` array (the same as ``xroute._engine.POLICY_FEATURES``)."""

_COL = {name: i for i, name in enumerate(FEATURE_COLUMNS)}


BUILTIN_POLICIES: tuple[str, ...] = ("heuristic", "random")
"""Policies the engine runs in C++, by name (files and models are resolved by :mod:`xroute.policies`)."""



@runtime_checkable
class NetOrderPolicy(Protocol):
    """What the router needs from a net-order policy."""

    name: str

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        """A permutation of ``range(len(features))``: the order in which the region's nets are routed."""
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

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        rng = np.random.default_rng([self.seed, int(region["iteration"]), int(region["region"])])
        return rng.permutation(len(features))

    def __repr__(self) -> str:
        return f"RandomPolicy(seed={self.seed})"


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


def check_order(order: Any, n: int, policy_name: str) -> list[int]:
    """``order`` as a list of ints if it is a permutation of ``range(n)``; otherwise a
    :class:`PolicyError` naming the policy and what is wrong."""
    where = f"net-order policy '{policy_name}'"
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


def builtin_policy(name: str, seed: int = 1) -> NetOrderPolicy:
    """The built-in policy called ``name`` (one of :data:`BUILTIN_POLICIES`); ``random`` is seeded with ``seed``."""
    if name == "heuristic":
        return HeuristicPolicy()
    if name == "random":
        return RandomPolicy(seed)
    raise PolicyError(
        f"unknown policy '{name}': use {', '.join(BUILTIN_POLICIES)}, or load a policy file or model with "
        "xroute.policies.get_policy"
    )

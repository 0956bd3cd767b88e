"""Net-order policies scored on held-out regions of the router's own first pass (in context).

A held-out region (:func:`~xroute.policies.rl.region_filter.held_out`) is a region of the first
pass (iteration 0, regions of the router's size, :func:`xroute.session.first_pass`) that training
never draws. It is opened in context: every region of an earlier colour routed and committed as
the first pass did, its crossing points chosen, the rest unrouted; the policy orders (or routes)
its nets; the score is the region's first-pass cost ``0.5 WL(um) + 4 vias + 500 violations``
(:class:`xroute.config.CostSection`): the region's new routing and the design-rule markers inside
its box. Every policy starts from the same state (nothing is committed).

A policy is named by a spec: a built-in name the engine routes itself (``heuristic``, ``random``,
the searches ``rollout``, ``victims``, ``bestof`` and ``best-of-K``:
:func:`xroute.net_order.is_builtin_name`, through ``Region.route_rest(name, seed, search_budget)``),
or anything :func:`xroute.policies.registry.get_policy` resolves (a ``.py`` file, an ``.onnx``
model), asked once per region for an order (a sequential one, with ``next_net``, once per net).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any, Iterator

import numpy as np

from xroute.config import CostSection
from xroute.defaults import SEARCH_BUDGET
from xroute.net_order import BUILTIN_POLICIES, check_order, is_builtin_name
from xroute.policies.rl.region_filter import held_out

FIGURES = ("cost", "wl_um", "vias", "drvs")


@dataclass(frozen=True)
class HeldOutRegion:
    """A region of the first pass kept out of training."""

    index: int  # in FirstPass.regions
    location: tuple[int, int]  # lower-left GCell
    box: tuple[int, int, int, int]  # DBU
    colour: int  # 0..3: the flow's order
    candidates: int  # candidate nets when opened in context


@dataclass
class PolicyScore:
    """One policy's figures on one region (``seconds``: routing, policy included)."""

    cost: float
    wl_um: float
    vias: int
    drvs: int
    seconds: float = 0.0
    extra: dict[str, Any] = field(default_factory=dict)


def region_score(region: Any, dbu_per_micron: int, weights: CostSection = CostSection()) -> PolicyScore:
    """The cost of an engine Region's new routing and the markers inside its box."""
    m = region.metrics()
    return PolicyScore(cost=weights.region_cost(m, dbu_per_micron), wl_um=m["wirelength_dbu"] / dbu_per_micron,
                       vias=int(m["vias"]), drvs=int(m["violations"]))


def marker_roles(region: Any) -> tuple[dict[int, int], dict[int, int], dict[int, int]]:
    """(victims, aggressors, alone) of a routed engine Region's markers (``Region.markers()``), each a
    net -> marker count. Of a two-net marker the net routed later is its victim and the other its
    aggressor (a net the region did not route counts as routed earliest); a one-net marker (minimum
    area, an obstruction) names its own net as victim, and counts in ``alone`` too. A net in two
    parts counts at its first part."""
    nets = np.asarray(region.candidates)[:, 0]
    position: dict[int, int] = {}
    for p, k in enumerate(region.route_order):
        position.setdefault(int(nets[k]), p)
    victims: dict[int, int] = {}
    aggressors: dict[int, int] = {}
    alone: dict[int, int] = {}
    for m in region.markers():
        a, b = (int(n) for n in m["nets"])
        if a >= 0 and b >= 0 and a != b:
            v, g = (a, b) if position.get(a, -1) > position.get(b, -1) else (b, a)
            victims[v] = victims.get(v, 0) + 1
            aggressors[g] = aggressors.get(g, 0) + 1
        else:
            for n in {x for x in (a, b) if x >= 0}:
                victims[n] = victims.get(n, 0) + 1
                alone[n] = alone.get(n, 0) + 1
    return victims, aggressors, alone


def moved_first(order: Any, first: Any) -> np.ndarray:
    """int32 ``order`` (candidate rows) with the rows where the bool[N] mask ``first`` is set moved to
    the front, both parts in their order there (victims first: ``first`` from :func:`marker_roles`)."""
    order = np.asarray(order, np.int64)
    f = np.asarray(first, bool)[order]
    return np.concatenate([order[f], order[~f]]).astype(np.int32)


def held_out_regions(first_pass: Any, hold_out_every: int, region_size: int,
                     min_candidates: int = 2) -> Iterator[HeldOutRegion]:
    """The held-out regions of ``first_pass`` with at least ``min_candidates`` nets, in the flow's order
    (each is opened once to count its candidates)."""
    for i, (loc, box, colour, _nets) in enumerate(first_pass.regions):
        if not held_out(tuple(loc), hold_out_every, region_size):
            continue
        n = len(first_pass.open_region(i).candidates)
        if n >= min_candidates:
            yield HeldOutRegion(i, tuple(loc), tuple(box), int(colour), n)


def route_in_context(first_pass: Any, region: HeldOutRegion, spec: str | Any, seed: int, dbu_per_micron: int,
                     weights: CostSection = CostSection(), search_budget: int = SEARCH_BUDGET) -> PolicyScore:
    """Opens ``region`` in context and routes it with ``spec`` (a built-in name, or a policy object with
    ``order(region, features)`` or ``next_net(region, features)``); returns its score. ``search_budget``:
    the trial routings per region of rollout and victims (and ``bestof``'s K)."""
    r = first_pass.open_region(region.index)
    t0 = time.perf_counter()
    if isinstance(spec, str):
        if not is_builtin_name(spec):
            raise ValueError(f"{spec!r} is not a built-in policy ({', '.join(BUILTIN_POLICIES)}, best-of-K)")
        r.route_rest(spec, seed, search_budget)
    elif callable(getattr(spec, "next_net", None)):
        _route_sequential(r, spec, {"iteration": 0, "region": region.index, "box": region.box})
    else:
        info = {"iteration": 0, "region": region.index, "box": region.box}
        if getattr(spec, "needs_region", False):
            info["engine_region"] = r
        features = r.candidates
        order = spec.order(info, features)
        if not getattr(spec, "needs_region", False):
            order = check_order(order, len(features), str(getattr(spec, "name", spec)))
        for i in order:
            if not r.is_routed(int(i)):  # a policy that needs the region may route some itself
                r.route_net(int(i))
        r.route_rest("heuristic", 1)  # anything it left out
    score = region_score(r, dbu_per_micron, weights)
    score.seconds = time.perf_counter() - t0
    return score


def _route_sequential(r: Any, spec: Any, info: dict[str, Any]) -> None:
    """Routes the region one net at a time as the router does for a sequential policy: ``next_net``
    sees the unrouted candidates' rows (``routed_nearby`` as the region is now)."""
    if getattr(spec, "needs_region", False):
        info = {**info, "engine_region": r}
    while pending := list(r.unrouted()):
        k = int(spec.next_net(info, r.candidates[pending]))
        if not 0 <= k < len(pending):
            raise ValueError(f"policy {getattr(spec, 'name', spec)!r}: next_net returned {k}, outside range({len(pending)})")
        if not r.is_routed(pending[k]):
            r.route_net(pending[k])


def best_of_random(first_pass: Any, region: HeldOutRegion, seeds: int, dbu_per_micron: int,
                   weights: CostSection = CostSection()) -> list[PolicyScore]:
    """The scores of random orders seeded 1..seeds (the mean of the first k is "random", the minimum of
    all of them "best-of-k")."""
    return [route_in_context(first_pass, region, "random", s, dbu_per_micron, weights) for s in range(1, seeds + 1)]


def mean_score(scores: list[PolicyScore]) -> PolicyScore:
    return PolicyScore(cost=float(np.mean([s.cost for s in scores])), wl_um=float(np.mean([s.wl_um for s in scores])),
                       vias=float(np.mean([s.vias for s in scores])), drvs=float(np.mean([s.drvs for s in scores])),
                       seconds=float(np.mean([s.seconds for s in scores])))


def best_score(scores: list[PolicyScore]) -> PolicyScore:
    """The lowest-cost score (the first on ties); ``seconds`` is the sum (what finding it cost)."""
    best = min(scores, key=lambda s: s.cost)
    return PolicyScore(best.cost, best.wl_um, best.vias, best.drvs, float(sum(s.seconds for s in scores)))

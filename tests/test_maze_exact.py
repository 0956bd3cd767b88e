"""The maze's A* search is exact: each round's path costs what the cheapest path costs.

The heuristic (engine_cpp/route/maze.cpp) adds a via for each layer between a node and the nearest
unreached terminal to the planar distance. It must never overestimate, or the search returns a
dearer path than the grid offers. A plain Dijkstra search over the region's own edges
(``region.moves``) gives the cheapest cost from a net's first terminal to any other; the maze's
first path for that net, priced edge by edge, must cost exactly that. On a generated design (no
contest data), the whole die opened as one region, nets routed in the candidates' order so the later
nets see the earlier ones' metal. Twice: with the default costs, where the open list packs its
entries into 16 bytes, and with a via dear enough that the heuristic can pass 32 bits, where it
keeps them whole.
"""

from __future__ import annotations

import heapq

import pytest
from conftest import require_testcase

DESIGN = "standin_sample4"  # generated: 120 cells


def edges(region, i: int, node: int, cache: dict[int, list[tuple[int, int]]]) -> list[tuple[int, int]]:
    if node not in cache:
        nodes, costs = region.moves(i, node)
        cache[node] = [(v, c) for v, c in zip(nodes, costs) if v >= 0]
    return cache[node]


def cheapest(region, i: int, sources: list[int], targets: set[int], cache) -> int:
    """Dijkstra over candidate i's edges from any source (cost 0) to the first target settled."""
    best = {s: 0 for s in sources}
    heap = [(0, s) for s in sources]
    heapq.heapify(heap)
    done: set[int] = set()
    while heap:
        d, u = heapq.heappop(heap)
        if u in done:
            continue
        done.add(u)
        if u in targets:
            return d
        for v, c in edges(region, i, u, cache):
            if v not in done and d + c < best.get(v, 1 << 62):
                best[v] = d + c
                heapq.heappush(heap, (d + c, v))
    raise AssertionError(f"candidate {i}: no path between its terminals")


@pytest.mark.parametrize("via_cost", [None, 1 << 33], ids=["packed", "wide"])
def test_each_nets_first_maze_path_costs_what_the_cheapest_path_costs(via_cost: int | None) -> None:
    from xroute import _engine, load_design

    require_testcase(DESIGN)
    design = load_design(DESIGN)
    costs = _engine.MazeCosts() if via_cost is None else _engine.MazeCosts(via_cost=via_cost)
    session = _engine.RoutingSession(design.engine, costs=costs)
    region = session.open_region(tuple(int(v) for v in design.die_area))
    _, ny, nx = region.grid()["flags"].shape
    checked = multi_layer = 0
    for i in range(len(region.candidates)):
        terms = region.terminal_nodes(i)
        joined = region.terminal_joined(i)
        first = set(terms[0])
        others = set().union(*map(set, terms[1:])) if len(terms) > 1 else set()
        # Plain pin terminals only (no crossings: those carry an exit cost the edges do not show), the
        # first with nodes (the maze starts there), none sharing a node with it (reached without a path).
        if len(terms) < 2 or not all(joined) or not first or first & others:
            region.route_net(i)
            continue
        cache: dict[int, list[tuple[int, int]]] = {}
        want = cheapest(region, i, terms[0], others, cache)
        result = region.route_net(i)
        assert result["unreached"] == 0
        path = region.net_paths(i)[0]
        assert path[0] in first and path[-1] in others
        got = 0
        for u, v in zip(path, path[1:]):
            step = [c for w, c in edges(region, i, u, cache) if w == v]
            assert step, f"candidate {i}: {u} -> {v} is no edge"
            got += step[0]
        assert got == want, f"candidate {i}: the maze's path costs {got}, the cheapest {want}"
        checked += 1
        multi_layer += len({n // (nx * ny) for n in path}) > 1
    assert checked >= 20, checked
    # Paths that change layers, where the layer term counts (with the dear via, only where the pins'
    # layers make them).
    assert multi_layer >= (10 if via_cost is None else 1), multi_layer

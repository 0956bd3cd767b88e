"""Route guides for a generated testcase, by a deliberately simple global route of our own.

Per net: the GCells holding its pins are joined by a minimum spanning tree (Prim, Manhattan
distance, ties by GCell order). Each tree edge is covered by both of its L shapes: the horizontal
legs on a horizontal layer, the vertical legs on a vertical layer (Metal3/Metal2 for edges up to
``LONG_EDGE`` GCells, Metal5/Metal4 beyond), so the detailed router may take either bend. Every
pin GCell gets a via stack from the pin's layer up to the highest layer of its edges (at least
Metal3). Guides are GCell-aligned rectangles in DBU; layers are routing-layer indices 0..5.
"""

from __future__ import annotations

from xroute.testcases.gen_tech import LAYERS

LONG_EDGE = 8  # GCells: a tree edge longer than this is guided on Metal4/Metal5
SHORT_PAIR = (1, 2)  # (vertical, horizontal) routing-layer indices: Metal2, Metal3
LONG_PAIR = (3, 4)  # Metal4, Metal5
MIN_STACK_TOP = 2  # Metal3


def _mst(points: list[tuple[int, int]]) -> list[tuple[int, int]]:
    """Edges (index pairs) of a Manhattan minimum spanning tree, deterministic."""
    if len(points) < 2:
        return []
    inf = 1 << 60
    best = [inf] * len(points)
    parent = [-1] * len(points)
    done = [False] * len(points)
    best[0] = 0
    edges: list[tuple[int, int]] = []
    for _ in range(len(points)):
        i = min((k for k in range(len(points)) if not done[k]), key=lambda k: (best[k], k))
        done[i] = True
        if parent[i] >= 0:
            edges.append((parent[i], i))
        for k in range(len(points)):
            if not done[k]:
                d = abs(points[k][0] - points[i][0]) + abs(points[k][1] - points[i][1])
                if d < best[k]:
                    best[k], parent[k] = d, i
    return edges


def net_guides(pins: list[tuple[int, int, int]], gcell_w: int, gcell_h: int) -> list[tuple[int, int, int, int, str]]:
    """Guide rectangles ``(xlo, ylo, xhi, yhi, layer name)`` of one net.

    ``pins``: (GCell column, GCell row, routing-layer index of the pin) per pin.
    """
    cells: dict[tuple[int, int], list[int]] = {}  # GCell -> [lowest layer, highest layer]
    for gx, gy, layer in pins:
        lo_hi = cells.setdefault((gx, gy), [layer, MIN_STACK_TOP])
        lo_hi[0] = min(lo_hi[0], layer)
        lo_hi[1] = max(lo_hi[1], layer)
    points = sorted(cells)
    boxes: dict[tuple[int, int, int, int, int], None] = {}  # (layer, gx0, gy0, gx1, gy1), in order

    def add(layer: int, gx0: int, gy0: int, gx1: int, gy1: int) -> None:
        boxes[(layer, min(gx0, gx1), min(gy0, gy1), max(gx0, gx1), max(gy0, gy1))] = None

    for i, j in _mst(points):
        (ax, ay), (bx, by) = points[i], points[j]
        vertical, horizontal = LONG_PAIR if abs(ax - bx) + abs(ay - by) > LONG_EDGE else SHORT_PAIR
        for end in (points[i], points[j]):
            cells[end][1] = max(cells[end][1], horizontal, vertical)
        add(horizontal, ax, ay, bx, ay)
        add(horizontal, ax, by, bx, by)
        add(vertical, ax, ay, ax, by)
        add(vertical, bx, ay, bx, by)
    for (gx, gy), (lo, hi) in sorted(cells.items()):
        for layer in range(lo, hi + 1):
            add(layer, gx, gy, gx, gy)
    out = []
    for layer, gx0, gy0, gx1, gy1 in sorted(boxes):
        out.append((gx0 * gcell_w, gy0 * gcell_h, (gx1 + 1) * gcell_w, (gy1 + 1) * gcell_h, LAYERS[layer].name))
    return out

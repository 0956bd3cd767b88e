"""Placement and netlist of a generated testcase: cells legally placed on rows, local nets, IO pins.

Everything comes from one ``random.Random(seed)``, consumed in a fixed order, so a seed gives the
same design every time. Coordinates are DBU.

* Floorplan: a square-ish die of whole GCells (15 sites by 2 rows each), sized for about 65 %
  utilisation; rows alternate N / FS from the bottom.
* Placement: the cells (drawn by the library's weights) fill the rows in order; each row's spare
  sites are scattered as gaps, and one spare site in ten gets a filler cell.
* Nets: every cell output (and each input IO pin) drives one net whose sinks are the nearest free
  cell inputs, with a little noise: 2-pin nets about half of them, 3-5 pins most of the rest, and
  one in twenty a fanout of 6-14. Drivers that find no free input drive nothing (no net). Output
  IO pins join the net of the nearest driver.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from xroute.testcases.def_text import IoPin
from xroute.testcases.gen_tech import CELL_BY_NAME, CELLS, M1_PITCH, ROW_H, SITE_W, Cell

GCELL_SITES = 15  # GCell width in sites (5700 DBU)
GCELL_ROWS = 2  # GCell height in rows (5600 DBU)
GCELL_W, GCELL_H = GCELL_SITES * SITE_W, GCELL_ROWS * ROW_H
UTILISATION = 0.65
BIN = 4000  # DBU: side of the buckets used to find nearby inputs


@dataclass
class Placed:
    name: str
    cell: Cell
    x: int  # DBU, lower-left corner
    y: int
    orient: str  # N or FS



@dataclass
class Netlist:
    width: int  # DBU (die from the origin)
    height: int
    rows: int
    sites: int  # per row
    comps: list[Placed] = field(default_factory=list)
    ios: list[IoPin] = field(default_factory=list)
    nets: list[list[tuple[str, str]]] = field(default_factory=list)  # (component or "PIN", pin)


def pin_center(p: Placed, pin: str) -> tuple[int, int]:
    """Centre of a cell pin's first rectangle, in die coordinates (DBU)."""
    x0, y0, x1, y1 = next(q for q in p.cell.pins if q.name == pin).rects[0]
    cy = (y0 + y1) // 2
    return p.x + (x0 + x1) // 2, p.y + (cy if p.orient == "N" else ROW_H - cy)


def _floorplan(cells: list[Cell]) -> tuple[int, int]:
    sites = sum(c.sites for c in cells) / UTILISATION
    side = math.sqrt(sites * SITE_W * ROW_H)
    return max(2, math.ceil(side / GCELL_W)), max(2, math.ceil(side / GCELL_H))


def _place(rng: random.Random, cells: list[Cell], n_rows: int, n_sites: int) -> list[Placed]:
    out: list[Placed] = []
    total = sum(c.sites for c in cells)
    target = total / n_rows
    k = 0
    fills = 0
    for r in range(n_rows):
        row: list[Cell] = []
        used = 0
        while k < len(cells) and used + cells[k].sites <= n_sites and (used < target or r == n_rows - 1):
            row.append(cells[k])
            used += cells[k].sites
            k += 1
        gaps = [0] * (len(row) + 1)
        for _ in range(n_sites - used):
            gaps[rng.randrange(len(gaps))] += 1
        x = 0
        orient = "N" if r % 2 == 0 else "FS"
        for i, cell in enumerate(row + [None]):
            for _ in range(gaps[i]):
                if rng.random() < 0.1:
                    fills += 1
                    out.append(Placed(f"fill{fills}", CELL_BY_NAME["FILL_X1"], x, r * ROW_H, orient))
                x += SITE_W
            if cell is not None:
                out.append(Placed("", cell, x, r * ROW_H, orient))
                x += cell.width
    if k < len(cells):
        raise ValueError("cells do not fit the rows")  # cannot happen at 65 % utilisation
    logic = 0
    for p in out:
        if not p.name:
            logic += 1
            p.name = f"u{logic}"
    return out


def _fanout(rng: random.Random) -> int:
    r = rng.random()
    if r < 0.50:
        return 1
    if r < 0.75:
        return 2
    if r < 0.88:
        return 3
    if r < 0.95:
        return 4
    return rng.randint(6, 14)


class _FreeInputs:
    """Unconnected cell inputs bucketed by position, to find the nearest ones."""

    def __init__(self, comps: list[Placed]) -> None:
        self.bins: dict[tuple[int, int], list[tuple[int, int, str, str]]] = {}
        for p in comps:
            for pin in p.cell.inputs:
                x, y = pin_center(p, pin)
                self.bins.setdefault((x // BIN, y // BIN), []).append((x, y, p.name, pin))

    def take(self, rng: random.Random, x: int, y: int, k: int, exclude: str) -> list[tuple[str, str]]:
        bx, by = x // BIN, y // BIN
        found: list[tuple[float, tuple[int, int], int]] = []
        for radius in range(0, 8):
            for gx in range(bx - radius, bx + radius + 1):
                for gy in range(by - radius, by + radius + 1):
                    if max(abs(gx - bx), abs(gy - by)) != radius:
                        continue
                    for i, (px, py, comp, _) in enumerate(self.bins.get((gx, gy), ())):
                        if comp != exclude:
                            dist = abs(px - x) + abs(py - y)
                            found.append((dist * (1.0 + 0.6 * rng.random()), (gx, gy), i))
            if len(found) >= 3 * k:
                break
        found.sort()
        chosen = found[:k]
        out = []
        for _, key, i in sorted(chosen, key=lambda c: (c[1], -c[2])):  # pop from the back first
            _, _, comp, pin = self.bins[key].pop(i)
            out.append((comp, pin))
        return sorted(out)


def _io_pins(rng: random.Random, count: int, width: int, height: int) -> list[IoPin]:
    """IO pins on the die edge: Metal4 on the bottom and top edges, Metal3 on the left and right."""
    pins: list[IoPin] = []
    for i in range(count):
        side = i % 4
        direction = "INPUT" if i % 2 == 0 else "OUTPUT"
        if side in (0, 1):  # bottom, top: on a Metal4 track
            x = SITE_W // 2 + SITE_W * rng.randrange(2, width // SITE_W - 2)
            y = 0 if side == 0 else height - 360
            pins.append(IoPin(f"io{i}", direction, "Metal4", (-70, 0, 70, 360), x, y))
        else:  # left, right: on a Metal3 track away from the rails
            t = rng.randrange(2, height // M1_PITCH - 2)
            t += 1 if t % 10 == 0 else 0
            x = 0 if side == 2 else width - 360
            pins.append(IoPin(f"io{i}", direction, "Metal3", (0, -70, 360, 70), x, t * M1_PITCH))
    return pins


def make_netlist(cells: int, seed: int) -> Netlist:
    """A placed, connected design of ``cells`` logic cells (plus fillers), deterministic for ``seed``."""
    if cells < 2:
        raise ValueError("a testcase needs at least 2 cells")
    rng = random.Random(seed)
    logic = [c for c in CELLS if c.weight > 0]
    chosen = rng.choices(logic, weights=[c.weight for c in logic], k=cells)
    gx, gy = _floorplan(chosen)
    n_rows, n_sites = gy * GCELL_ROWS, gx * GCELL_SITES
    nl = Netlist(n_sites * SITE_W, n_rows * ROW_H, n_rows, n_sites)
    nl.comps = _place(rng, chosen, n_rows, n_sites)
    nl.ios = _io_pins(rng, max(4, min(48, cells // 40)), nl.width, nl.height)
    free = _FreeInputs(nl.comps)
    drivers: list[tuple[str, str, int, int]] = []  # (component or PIN, pin, x, y)
    for io in nl.ios:
        if io.direction == "INPUT":
            x0, y0, x1, y1 = io.rect
            drivers.append(("PIN", io.name, io.x + (x0 + x1) // 2, io.y + (y0 + y1) // 2))
    cell_drivers = [(p.name, p.cell.output, *pin_center(p, p.cell.output)) for p in nl.comps if p.cell.output]
    rng.shuffle(cell_drivers)
    drivers += cell_drivers
    net_of_driver: list[tuple[int, int, int]] = []  # (x, y, net index)
    for comp, pin, x, y in drivers:
        sinks = free.take(rng, x, y, _fanout(rng), comp)
        if sinks:
            net_of_driver.append((x, y, len(nl.nets)))
            nl.nets.append([(comp, pin)] + sinks)
    for io in nl.ios:
        if io.direction == "OUTPUT" and net_of_driver:
            x, y = io.x + (io.rect[0] + io.rect[2]) // 2, io.y + (io.rect[1] + io.rect[3]) // 2
            _, _, k = min(net_of_driver, key=lambda d: (abs(d[0] - x) + abs(d[1] - y), d[2]))
            nl.nets[k].append(("PIN", io.name))
    return nl

"""The technology of generated testcases: six routing layers, vias, a site and a small cell library.

Our own numbers in the spirit of a 45 nm process (not taken from any real kit). All lengths are
DEF database units (DBU, 2000 per micron) except where a name says um; the LEF is written in
microns. Geometry that the generator relies on:

* site 380 x 2800 DBU (0.19 x 1.40 um); a row holds 10 Metal1 tracks, of which the one on the
  row boundary lies under the power rail;
* Metal1/3 horizontal, pitch 280; Metal2/4 vertical, pitch 380 (one per site, at the site
  centre); Metal5 horizontal, pitch 560; Metal6 vertical, pitch 760;
* every signal pin of a cell is a vertical Metal1 bar 140 DBU wide centred on a site centre
  (so on a Metal2 track), spanning several Metal1 tracks; rails are Metal1, 60 DBU inside the
  cell at its bottom (VSS) and top (VDD).
"""

from __future__ import annotations

from dataclasses import dataclass

DBU = 2000  # DBU per micron
SITE_W = 380  # DBU
ROW_H = 2800  # DBU
RAIL_HALF = 60  # DBU: half the rail's height (each cell holds half a rail)
PIN_HALF_W = 70  # DBU: half a pin bar's width
M1_PITCH = 280  # DBU: horizontal tracks of Metal1/3 (y = k * 280)


@dataclass(frozen=True)
class RoutingLayer:
    name: str
    direction: str  # HORIZONTAL or VERTICAL
    pitch: int  # DBU
    offset: int  # DBU: first track (from the die origin)
    width: int  # DBU
    spacing: int  # DBU
    eol: tuple[int, int, int]  # ENDOFLINE spacing, eol width, within (DBU)
    area_um2: float
    prl: tuple[int, int]  # spacing table: (parallel run length, spacing for wires >= wide_width) (DBU)
    wide_width: int  # DBU


LAYERS = (
    RoutingLayer("Metal1", "HORIZONTAL", 280, 0, 140, 140, (180, 180, 50), 0.012, (600, 240), 400),
    RoutingLayer("Metal2", "VERTICAL", 380, 190, 140, 160, (200, 180, 60), 0.012, (600, 260), 400),
    RoutingLayer("Metal3", "HORIZONTAL", 280, 0, 140, 140, (180, 180, 50), 0.012, (600, 240), 400),
    RoutingLayer("Metal4", "VERTICAL", 380, 190, 140, 160, (200, 180, 60), 0.012, (600, 260), 400),
    RoutingLayer("Metal5", "HORIZONTAL", 560, 0, 200, 200, (240, 220, 60), 0.02, (800, 320), 600),
    RoutingLayer("Metal6", "VERTICAL", 760, 190, 200, 200, (240, 220, 60), 0.02, (800, 320), 600),
)
CUT_WIDTH = 140  # DBU: every cut is a square of this side
CUT_SPACING = (160, 160, 160, 180, 180)  # DBU, Via1..Via5


@dataclass(frozen=True)
class Pin:
    name: str
    direction: str  # INPUT, OUTPUT, INOUT
    use: str  # SIGNAL, POWER, GROUND
    rects: tuple[tuple[int, int, int, int], ...]  # Metal1, cell coordinates (DBU)


@dataclass(frozen=True)
class Cell:
    name: str
    sites: int
    pins: tuple[Pin, ...]
    obs: tuple[tuple[int, int, int, int], ...]  # Metal1 obstructions (DBU)
    weight: int  # relative frequency in a generated netlist (0: filler only)

    @property
    def width(self) -> int:
        return self.sites * SITE_W

    @property
    def output(self) -> str | None:
        return next((p.name for p in self.pins if p.direction == "OUTPUT"), None)

    @property
    def inputs(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.pins if p.direction == "INPUT")


def column_x(col: int) -> int:
    """Centre of site column ``col`` of a cell (DBU from its left edge): a Metal2 track."""
    return col * SITE_W + SITE_W // 2


def bar(col: int, t0: int, t1: int) -> tuple[int, int, int, int]:
    """A vertical Metal1 bar on column ``col`` covering Metal1 tracks t0..t1 of the row."""
    x = column_x(col)
    return (x - PIN_HALF_W, t0 * M1_PITCH - PIN_HALF_W, x + PIN_HALF_W, t1 * M1_PITCH + PIN_HALF_W)


def block(c0: int, c1: int, t0: int, t1: int) -> tuple[int, int, int, int]:
    """A Metal1 rectangle over columns c0..c1 and tracks t0..t1."""
    return (column_x(c0) - PIN_HALF_W, t0 * M1_PITCH - PIN_HALF_W, column_x(c1) + PIN_HALF_W, t1 * M1_PITCH + PIN_HALF_W)


def _cell(name: str, sites: int, signals: list[tuple[str, str, tuple]], obs: tuple = (), weight: int = 0) -> Cell:
    w = sites * SITE_W
    pins = [Pin(n, d, "SIGNAL", tuple(r)) for n, d, r in signals]
    pins.append(Pin("VDD", "INOUT", "POWER", ((0, ROW_H - RAIL_HALF, w, ROW_H),)))
    pins.append(Pin("VSS", "INOUT", "GROUND", ((0, 0, w, RAIL_HALF),)))
    return Cell(name, sites, tuple(pins), tuple(obs), weight)


I, O = "INPUT", "OUTPUT"
CELLS = (
    _cell("INV_X1", 3, [("A", I, [bar(0, 3, 6)]), ("Y", O, [bar(2, 2, 7)])], weight=18),
    _cell("BUF_X1", 4, [("A", I, [bar(0, 3, 6)]), ("Y", O, [bar(3, 2, 7)])], [block(1, 2, 3, 6)], weight=8),
    _cell("NAND2_X1", 4, [("A", I, [bar(0, 3, 6)]), ("B", I, [bar(1, 3, 6)]), ("Y", O, [bar(3, 2, 7)])],
          [block(2, 2, 4, 5)], weight=20),
    _cell("NOR2_X1", 4, [("A", I, [bar(0, 2, 5)]), ("B", I, [bar(2, 4, 7)]), ("Y", O, [bar(3, 2, 7)])], weight=14),
    _cell("NAND3_X1", 5, [("A", I, [bar(0, 3, 6)]), ("B", I, [bar(1, 3, 6)]), ("C", I, [bar(2, 3, 6)]),
                          ("Y", O, [bar(4, 2, 7)])], weight=10),
    _cell("XOR2_X1", 6, [("A", I, [bar(0, 3, 6)]), ("B", I, [bar(2, 3, 6)]), ("Y", O, [bar(5, 2, 7)])],
          [block(1, 1, 2, 7), block(3, 4, 3, 6)], weight=7),
    _cell("DFF_X1", 12, [("D", I, [bar(1, 3, 6)]), ("CK", I, [bar(3, 2, 5)]), ("Q", O, [bar(10, 2, 7)])],
          [block(5, 8, 2, 7), block(11, 11, 3, 5)], weight=15),
    _cell("BUF_X4", 6, [("A", I, [bar(0, 3, 6)]),
                        ("Y", O, [bar(3, 2, 8), bar(5, 2, 8), block(3, 5, 8, 8)])], [block(1, 2, 3, 6)], weight=3),
    _cell("FILL_X1", 1, []),
)
CELL_BY_NAME = {c.name: c for c in CELLS}


def _um(v: int) -> str:
    return f"{v / DBU:.4f}"


def _rect(r: tuple[int, int, int, int]) -> str:
    return "RECT " + " ".join(_um(v) for v in r) + " ;"


def _layer_lef(layer: RoutingLayer) -> list[str]:
    eol, eol_w, within = layer.eol
    prl, wide_sp = layer.prl
    return [
        f"LAYER {layer.name}",
        "  TYPE ROUTING ;",
        f"  DIRECTION {layer.direction} ;",
        f"  PITCH {_um(layer.pitch)} ;",
        f"  OFFSET {_um(layer.offset)} ;",
        f"  WIDTH {_um(layer.width)} ;",
        f"  MINWIDTH {_um(layer.width)} ;",
        f"  AREA {layer.area_um2:.4f} ;",
        f"  SPACING {_um(layer.spacing)} ;",
        f"  SPACING {_um(eol)} ENDOFLINE {_um(eol_w)} WITHIN {_um(within)} ;",
        "  SPACINGTABLE",
        f"    PARALLELRUNLENGTH 0.0000 {_um(prl)}",
        f"    WIDTH 0.0000 {_um(layer.spacing)} {_um(layer.spacing)}",
        f"    WIDTH {_um(layer.wide_width)} {_um(layer.spacing)} {_um(wide_sp)} ;",
        f"END {layer.name}",
        "",
    ]


def _enclosure(layer: RoutingLayer) -> tuple[int, int, int, int]:
    """A via's metal on ``layer``: the layer's width across, longer along its direction (DBU)."""
    half_w, half_l = layer.width // 2, layer.width // 2 + 60
    if layer.direction == "HORIZONTAL":
        return (-half_l, -half_w, half_l, half_w)
    return (-half_w, -half_l, half_w, half_l)


def _via_lef(k: int) -> list[str]:
    lo, hi = LAYERS[k], LAYERS[k + 1]
    bottom = (-70, -130, 70, 130) if k == 0 else _enclosure(lo)  # Metal1: along the vertical pin bars
    h = CUT_WIDTH // 2
    name = f"VIA{k + 1}{k + 2}"
    return [
        f"VIA {name} DEFAULT",
        f"  LAYER {lo.name} ;",
        f"    {_rect(bottom)}",
        f"  LAYER Via{k + 1} ;",
        f"    {_rect((-h, -h, h, h))}",
        f"  LAYER {hi.name} ;",
        f"    {_rect(_enclosure(hi))}",
        f"END {name}",
        "",
    ]


def _macro_lef(cell: Cell) -> list[str]:
    out = [
        f"MACRO {cell.name}",
        "  CLASS CORE ;" if cell.pins[0].use == "SIGNAL" else "  CLASS CORE SPACER ;",
        "  ORIGIN 0.0000 0.0000 ;",
        f"  SIZE {_um(cell.width)} BY {_um(ROW_H)} ;",
        "  SYMMETRY X Y ;",
        "  SITE core ;",
    ]
    for pin in cell.pins:
        out += [f"  PIN {pin.name}", f"    DIRECTION {pin.direction} ;", f"    USE {pin.use} ;"]
        if pin.use != "SIGNAL":
            out.append("    SHAPE ABUTMENT ;")
        out += ["    PORT", "      LAYER Metal1 ;"] + [f"        {_rect(r)}" for r in pin.rects]
        out += ["    END", f"  END {pin.name}"]
    if cell.obs:
        out += ["  OBS", "    LAYER Metal1 ;"] + [f"      {_rect(r)}" for r in cell.obs] + ["  END"]
    return out + [f"END {cell.name}", ""]


def technology_lef() -> str:
    """The whole technology and cell LEF (the same for every seed and size)."""
    out = [
        "# Technology and cells of an xroute-generated testcase (synthetic, 45 nm-like; see testcases/gen_tech.py).",
        "VERSION 5.8 ;",
        'BUSBITCHARS "[]" ;',
        'DIVIDERCHAR "/" ;',
        "UNITS",
        f"  DATABASE MICRONS {DBU} ;",
        "END UNITS",
        "MANUFACTURINGGRID 0.0050 ;",
        "",
        "SITE core",
        "  CLASS CORE ;",
        "  SYMMETRY Y ;",
        f"  SIZE {_um(SITE_W)} BY {_um(ROW_H)} ;",
        "END core",
        "",
    ]
    for k, layer in enumerate(LAYERS):
        out += _layer_lef(layer)
        if k + 1 < len(LAYERS):
            out += [f"LAYER Via{k + 1}", "  TYPE CUT ;", f"  WIDTH {_um(CUT_WIDTH)} ;",
                    f"  SPACING {_um(CUT_SPACING[k])} ;", f"END Via{k + 1}", ""]
    for k in range(len(LAYERS) - 1):
        out += _via_lef(k)
    for cell in CELLS:
        out += _macro_lef(cell)
    out.append("END LIBRARY")
    return "\n".join(out) + "\n"

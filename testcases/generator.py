"""Generated testcases: ``make_testcase(cells, seed, out_dir)`` writes a technology LEF, a placed DEF and guides.

The folder's name is the testcase (and DEF design) name: ``out_dir/<name>.{lef,def,guide}``
with ``<name> = out_dir.name``, so a folder under a search-path root is found by that name. The
same (cells, seed, name) gives byte-identical files. The pieces:

* ``gen_tech``: the technology and cell library (the LEF is the same for every testcase);
* ``gen_netlist``: floorplan, legal placement on rows, local nets, IO pins;
* ``gen_guides``: guides from a minimum spanning tree and L shapes per net;
* this module: the DEF (die, rows, tracks for every layer, GCELLGRID, components, IO pins,
  power rails as special nets, nets) and the files.

The shipped demo (``testcases/data/demo``) is ``make_testcase(DEMO_CELLS, DEMO_SEED, ".../demo")``;
regenerate it with ``python -m xroute.testcases.generator`` after changing the generator (a test checks
that the shipped files equal the generator's output).
"""

from __future__ import annotations

from pathlib import Path

from xroute.atomic_files import atomic_write_text
from xroute.testcases.def_text import GuideNet, components_and_pins, write_guides
from xroute.testcases.gen_guides import net_guides
from xroute.testcases.gen_netlist import GCELL_H, GCELL_W, Netlist, make_netlist, pin_center
from xroute.testcases.gen_tech import DBU, LAYERS, RAIL_HALF, ROW_H, SITE_W, technology_lef
from xroute.errors import XrouteError

MAX_CELLS = 2_000_000
DEMO_CELLS, DEMO_SEED = 400, 1  # the shipped demo: testcases/data/demo (about 320 nets)
CROSS_PITCH = {"HORIZONTAL": (SITE_W // 2, SITE_W), "VERTICAL": (280, 280)}  # (start, step) across the direction


def _tracks(nl: Netlist) -> list[str]:
    """TRACKS for every layer: its preferred direction at its pitch, and across it on the site grid."""
    out = []
    for layer in LAYERS:
        start = layer.offset if layer.offset > 0 else layer.pitch  # no track on the die edge
        along = "Y" if layer.direction == "HORIZONTAL" else "X"
        across = "X" if along == "Y" else "Y"
        cross_start, cross_step = CROSS_PITCH[layer.direction]
        for axis, s, step in ((along, start, layer.pitch), (across, cross_start, cross_step)):
            extent = nl.height if axis == "Y" else nl.width
            count = (extent - 1 - s) // step + 1
            out.append(f"TRACKS {axis} {s} DO {count} STEP {step} LAYER {layer.name} ;")
    return out


def _special_nets(nl: Netlist) -> list[str]:
    """Metal1 rails on every row boundary: VSS on even ones (y = 0, 5600, ...), VDD on odd ones."""
    rails: dict[str, list[str]] = {"VDD": [], "VSS": []}
    for k in range(nl.rows + 1):
        y0, y1 = max(0, k * ROW_H - RAIL_HALF), min(nl.height, k * ROW_H + RAIL_HALF)
        rails["VSS" if k % 2 == 0 else "VDD"].append(f"    + RECT Metal1 ( 0 {y0} ) ( {nl.width} {y1} )")
    out = ["SPECIALNETS 2 ;"]
    for name, use in (("VDD", "POWER"), ("VSS", "GROUND")):
        out += [f"- {name} ( * {name} )"] + rails[name] + [f"    + USE {use} ;"]
    return out + ["END SPECIALNETS"]


def _def_text(name: str, nl: Netlist, net_names: list[str]) -> str:
    net_of_io = {pin: net_names[k] for k, net in enumerate(nl.nets) for comp, pin in net if comp == "PIN"}
    ios = [io for io in nl.ios if io.name in net_of_io]
    out = [
        "VERSION 5.8 ;",
        'DIVIDERCHAR "/" ;',
        'BUSBITCHARS "[]" ;',
        f"DESIGN {name} ;",
        f"UNITS DISTANCE MICRONS {DBU} ;",
        "",
        f"DIEAREA ( 0 0 ) ( {nl.width} {nl.height} ) ;",
        "",
    ]
    out += [f"ROW row{r} core 0 {r * ROW_H} {'N' if r % 2 == 0 else 'FS'} DO {nl.sites} BY 1 STEP {SITE_W} 0 ;"
            for r in range(nl.rows)]
    out += [""] + _tracks(nl) + [""]
    out += [f"GCELLGRID X 0 DO {nl.width // GCELL_W + 1} STEP {GCELL_W} ;",
            f"GCELLGRID Y 0 DO {nl.height // GCELL_H + 1} STEP {GCELL_H} ;", ""]
    out += components_and_pins(nl.comps, ios, net_of_io)
    out += _special_nets(nl) + ["", f"NETS {len(nl.nets)} ;"]
    for net_name, net in zip(net_names, nl.nets):
        out.append(f"- {net_name}")
        out.append("  " + " ".join(f"( {comp} {pin} )" for comp, pin in net) + " ;")
    out += ["END NETS", "", "END DESIGN"]
    return "\n".join(out) + "\n"


def _guides(nl: Netlist, net_names: list[str]) -> list[GuideNet]:
    comps = {p.name: p for p in nl.comps}
    layer_index = {layer.name: k for k, layer in enumerate(LAYERS)}
    ios = {io.name: io for io in nl.ios}
    out = []
    for net_name, net in zip(net_names, nl.nets):
        pins = []
        for comp, pin in net:
            if comp == "PIN":
                io = ios[pin]
                x, y = io.x + (io.rect[0] + io.rect[2]) // 2, io.y + (io.rect[1] + io.rect[3]) // 2
                pins.append((x // GCELL_W, y // GCELL_H, layer_index[io.layer]))
            else:
                x, y = pin_center(comps[comp], pin)
                pins.append((x // GCELL_W, y // GCELL_H, 0))
        out.append(GuideNet(net_name, net_guides(pins, GCELL_W, GCELL_H)))
    return out


def make_testcase(cells: int, seed: int, out_dir: str | Path) -> Path:
    """Writes the testcase ``out_dir.name`` into ``out_dir`` (created if needed) and returns the folder."""
    if not 2 <= cells <= MAX_CELLS:
        raise XrouteError(f"--cells must be 2..{MAX_CELLS:,}, not {cells}")
    folder = Path(out_dir)
    name = folder.resolve().name
    if not name or any(c.isspace() for c in name):
        raise XrouteError(f"cannot name a testcase after the folder {str(out_dir)!r}")
    nl = make_netlist(cells, seed)
    net_names = [f"n{k + 1}" for k in range(len(nl.nets))]
    folder.mkdir(parents=True, exist_ok=True)
    files = {
        "lef": technology_lef(),
        "def": _def_text(name, nl, net_names),
        "guide": write_guides(_guides(nl, net_names)),
    }
    for ext, text in files.items():
        atomic_write_text(folder / f"{name}.{ext}", text)
    return folder


if __name__ == "__main__":  # regenerate the shipped demo
    print(make_testcase(DEMO_CELLS, DEMO_SEED, Path(__file__).resolve().parent / "data" / "demo"))

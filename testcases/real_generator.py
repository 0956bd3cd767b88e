"""Generated designs on a real technology: ``make_real_testcase(lefs, cells, seed, out_dir)``.

Writes ``out_dir/<name>.def`` (``<name>`` = the folder's name) and ``out_dir/<name>.guide``; the
LEF files stay where they are (the DEF names none: give the same ``--lef`` files to the router).
The technology comes from the LEFs through the engine's reader (``real_tech``); placement and
netlist from ``real_netlist``; the guides from the built-in global router (``xroute.groute``).
Same LEFs, cells, seed, utilisation and folder name: byte-identical files.

The DEF holds: the die (origin 0, whole GCells), rows of the core site alternating N/FS, TRACKS
for every routing layer (its PITCH in its direction at the phase ``real_tech.track_phase`` gives
relative to the rows, the nearest other-direction layer's across it),
a GCELLGRID of ``gcell_size``, the placed cells, IO pins on the die edge, the rails as
SPECIALNETS when the cells have POWER/GROUND pins on their row edges, and the nets. With
``ndr_nets`` K > 0, K nets spread evenly over the list carry ``+ NONDEFAULTRULE NDR_2W2S``, a DEF
rule of twice the default width and twice the minimum spacing on every routing layer above the
lowest (the pins' layer keeps its defaults).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Sequence

from xroute.atomic_files import atomic_write_text
from xroute.errors import XrouteError
from xroute.testcases.def_text import components_and_pins
from xroute.testcases.real_netlist import RealNetlist, make_real_netlist, track_start
from xroute.testcases.real_tech import RealLayer, RealTech, read_real_tech

MAX_CELLS = 2_000_000
# Share of the row area the cells fill. Measured from the contest DEFs (cell area / row area):
# ispd19_test3 0.72, ispd19_test1 0.83, ispd18_test1 0.85; 0.75 lies in that range, nearer its low end
# because our nets are drawn, not optimised by a placer.
DEFAULT_UTILIZATION = 0.75
UTILIZATION_RANGE = (0.2, 0.9)


def _start(layer: RealLayer, core: int) -> int:
    """The first track inside the die (DBU, never on its edge) of ``layer``, whose rows start at ``core``."""
    return track_start(layer, core)


def _tracks(tech: RealTech, width: int, height: int, core: tuple[int, int]) -> list[str]:
    """Per layer: tracks in its direction at its pitch, and across it at the nearest other-direction layer's."""
    out = []
    for layer in tech.layers:
        others = [o for o in tech.layers if o.horizontal != layer.horizontal]
        cross = min(others, key=lambda o: (abs(o.routing_index - layer.routing_index), -o.routing_index))
        for lay in (layer, cross):
            axis = "Y" if lay.horizontal else "X"
            extent = height if axis == "Y" else width
            start = _start(lay, core[1] if axis == "Y" else core[0])
            count = (extent - 1 - start) // lay.pitch + 1
            out.append(f"TRACKS {axis} {start} DO {count} STEP {lay.pitch} LAYER {layer.name} ;")
    return out


def _special_nets(tech: RealTech, nl: RealNetlist) -> list[str]:
    """A rail on every row boundary, on the supply pins' layer, as high as the pins inside two abutting cells."""
    if not tech.rails:
        return []
    fp = nl.fp
    bottom = next(r for r in tech.rails if r.at_bottom)  # the net on row 0's bottom edge (row 0 is N)
    top = next(r for r in tech.rails if not r.at_bottom)
    x0, x1 = fp.core_x, fp.core_x + fp.sites * tech.site_w
    rects: dict[str, list[str]] = {bottom.net: [], top.net: []}
    for k in range(fp.rows + 1):
        rail = bottom if k % 2 == 0 else top
        y = fp.core_y + k * tech.row_h
        rects[rail.net].append(f"    + RECT {rail.layer} ( {x0} {y - rail.half} ) ( {x1} {y + rail.half} )")
    out = [f"SPECIALNETS {len(tech.rails)} ;"]
    for rail in tech.rails:
        out += [f"- {rail.net} ( * {rail.net} )"] + rects[rail.net] + [f"    + USE {rail.use} ;"]
    return out + ["END SPECIALNETS", ""]


NDR_NAME = "NDR_2W2S"


def _ndr_rule(tech: RealTech) -> list[str]:
    """The DEF NONDEFAULTRULES section of NDR_2W2S (see the module's docstring)."""
    layers = [f"  + LAYER {la.name} WIDTH {2 * la.width} SPACING {2 * la.min_spacing}"
              for la in tech.layers if la.routing_index > 0]
    return ["NONDEFAULTRULES 1 ;", f"- {NDR_NAME}"] + layers + [" ;", "END NONDEFAULTRULES", ""]


def ndr_net_indices(nets: int, count: int) -> set[int]:
    """``count`` net indices spread evenly over ``nets`` (the middle one of each equal share)."""
    count = min(count, nets)
    return {(2 * k + 1) * nets // (2 * count) for k in range(count)} if count > 0 else set()


def def_text(name: str, tech: RealTech, nl: RealNetlist, ndr_nets: int = 0) -> str:
    fp = nl.fp
    net_of_io = {pin: f"n{k + 1}" for k, net in enumerate(nl.nets) for comp, pin in net if comp == "PIN"}
    ios = [io for io in nl.ios if io.name in net_of_io]
    out = ["VERSION 5.8 ;", 'DIVIDERCHAR "/" ;', 'BUSBITCHARS "[]" ;', f"DESIGN {name} ;",
           f"UNITS DISTANCE MICRONS {tech.dbu} ;", "", f"DIEAREA ( 0 0 ) ( {fp.width} {fp.height} ) ;", ""]
    out += [f"ROW row{r} {tech.site} {fp.core_x} {fp.core_y + r * tech.row_h} {'N' if r % 2 == 0 else 'FS'} "
            f"DO {fp.sites} BY 1 STEP {tech.site_w} 0 ;" for r in range(fp.rows)]
    out += [""] + _tracks(tech, fp.width, fp.height, (fp.core_x, fp.core_y)) + [""]
    out += [f"GCELLGRID X 0 DO {fp.width // fp.gcell_w + 1} STEP {fp.gcell_w} ;",
            f"GCELLGRID Y 0 DO {fp.height // fp.gcell_h + 1} STEP {fp.gcell_h} ;", ""]
    ruled = ndr_net_indices(len(nl.nets), ndr_nets)
    out += _ndr_rule(tech) if ruled else []
    out += components_and_pins(nl.comps, ios, net_of_io)
    out += _special_nets(tech, nl) + [f"NETS {len(nl.nets)} ;"]
    for k, net in enumerate(nl.nets):
        out.append(f"- n{k + 1}")
        rule = f" + NONDEFAULTRULE {NDR_NAME}" if k in ruled else ""
        out.append("  " + " ".join(f"( {comp} {pin} )" for comp, pin in net) + rule + " ;")
    out += ["END NETS", "", "END DESIGN"]
    return "\n".join(out) + "\n"


def testcase_name(out_dir: str | os.PathLike[str]) -> str:
    name = Path(out_dir).resolve().name
    if not name or any(c.isspace() for c in name):
        raise XrouteError(f"cannot name a testcase after the folder {str(out_dir)!r}")
    return name


def make_real_testcase(
    lefs: Sequence[str | os.PathLike[str]],
    cells: int,
    seed: int,
    out_dir: str | os.PathLike[str],
    utilization: float = DEFAULT_UTILIZATION,
    ndr_nets: int = 0,
) -> Path:
    """Writes ``<name>.def`` and ``<name>.guide`` into ``out_dir`` (created if needed); returns the folder.
    ``ndr_nets``: how many nets carry the NDR_2W2S rule (0: none)."""
    from xroute.design import load_design
    from xroute.groute import global_route

    if not 2 <= cells <= MAX_CELLS:
        raise XrouteError(f"--cells must be 2..{MAX_CELLS:,}, not {cells}")
    lo, hi = UTILIZATION_RANGE
    if not lo <= utilization <= hi:
        raise XrouteError(f"--utilization must be {lo}..{hi}, not {utilization}")
    if ndr_nets < 0:
        raise XrouteError(f"--ndr-nets must be >= 0, not {ndr_nets}")
    folder = Path(out_dir)
    name = testcase_name(folder)
    tech = read_real_tech(lefs)
    nl = make_real_netlist(tech, cells, seed, utilization)
    folder.mkdir(parents=True, exist_ok=True)
    def_path = folder / f"{name}.def"
    atomic_write_text(def_path, def_text(name, tech, nl, ndr_nets))
    design = load_design(lef=list(tech.lef_paths), def_=def_path)
    global_route(design, out=folder / f"{name}.guide")
    return folder

"""Static regions: ``make_region(testcase, out_dir, ...)`` writes one routing region of a testcase as a
small self-contained design (what ``xroute make-region`` and the ``xroute/StaticRegion-v0`` env use).

Format of the region folder (written into a temporary folder, then renamed: all or nothing):

* ``region.lef``: a copy of the testcase's technology LEF (the only LEF; macros included);
* ``region.def``: DIEAREA = the region box grown to hold every component it keeps; TRACKS (and
  VIAS) copied; one GCELLGRID cell over the die; COMPONENTS: every component touching the box or
  owning a kept pin; NETS: the region's candidate nets, each with its pins that have an access
  point inside the box, plus boundary pins; PINS: the original IO pins kept, plus one boundary
  pin ``xr_boundary_<k>`` (a square of the layer's wire width on that layer) wherever the net's
  routing crosses the box edge. The crossing points come from routing the region once with the
  built-in heuristic on the unrouted testcase (free crossings where the guides leave the box), so
  every net has a known-routable set of terminals; nets left with fewer than two are dropped;
* ``region.guide``: the kept nets' guides clipped to the die;
* ``region.yaml``: testcase, origin (lower-left of the box, DBU; GCell column/row when made from a
  location), box, die, size (GCells), nets, pins (inside the box), boundary_pins, grid_nodes
  (existing nodes of the region grid in the testcase) and sparsity = grid_nodes / nets (as in the
  XRoute paper), the net names, and the file names.

The static region env opens the whole die of this design: that is the region.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from xroute.atomic_files import atomic_copy, atomic_write_text
from xroute.errors import XrouteError

REGION_YAML = "region.yaml"


class RegionError(XrouteError, ValueError):
    """A region that cannot be made (bad location, size, box, or no net inside)."""


@dataclass
class RegionSummary:
    """What :func:`make_region` wrote (also in region.yaml)."""

    out_dir: Path
    testcase: str
    box: tuple[int, int, int, int]  # DBU
    die: tuple[int, int, int, int]  # DBU
    size: int | None  # GCells per side (None for an explicit box)
    location: tuple[int, int] | None  # GCell column, row of the lower-left
    nets: int
    pins: int
    boundary_pins: int
    grid_nodes: int
    net_names: list[str] = field(default_factory=list)

    @property
    def sparsity(self) -> float:
        return self.grid_nodes / max(1, self.nets)

    def to_yaml(self) -> dict[str, Any]:
        return {
            "testcase": self.testcase,
            "origin": list(self.box[:2]),
            "location": None if self.location is None else list(self.location),
            "size": self.size,
            "box": list(self.box),
            "die": list(self.die),
            "nets": self.nets,
            "pins": self.pins,
            "boundary_pins": self.boundary_pins,
            "grid_nodes": self.grid_nodes,
            "sparsity": round(self.sparsity, 3),
            "files": {"lef": "region.lef", "def": "region.def", "guide": "region.guide"},
            "net_names": self.net_names,
        }


def paper_region_box(number: int | str) -> tuple[str, tuple[int, int, int, int]]:
    """(testcase, box) of the XRoute paper's static region ``number`` (1..10 or "Region3")."""
    from xroute.testcases.known import STATIC_REGIONS

    name = f"Region{number}" if str(number).isdigit() else str(number)
    for r in STATIC_REGIONS:
        if r.name.lower() == name.lower():
            return r.testcase, r.bbox
    raise RegionError(f"unknown paper region {number!r}: use 1..{len(STATIC_REGIONS)}")


def region_box(gcell_xs: np.ndarray, gcell_ys: np.ndarray, location: tuple[int, int], size: int) -> tuple[int, int, int, int]:
    """The box (DBU) of ``size`` x ``size`` GCells whose lower-left GCell is ``location`` (clipped to the grid)."""
    gx, gy = location
    nx, ny = len(gcell_xs) - 1, len(gcell_ys) - 1
    if size < 1:
        raise RegionError(f"region size must be at least 1 GCell, got {size}")
    if not (0 <= gx < nx and 0 <= gy < ny):
        raise RegionError(f"location {gx},{gy} is outside the GCell grid (0..{nx - 1}, 0..{ny - 1})")
    return (int(gcell_xs[gx]), int(gcell_ys[gy]), int(gcell_xs[min(gx + size, nx)]), int(gcell_ys[min(gy + size, ny)]))


def _section(text: str, name: str) -> str:
    """The body of a DEF section (between its header line and END name), or ''."""
    m = re.search(rf"^\s*{name}\s+\d+\s*;(.*?)^\s*END\s+{name}\b", text, re.S | re.M)
    return m.group(1) if m else ""


def _entries(body: str) -> dict[str, str]:
    """DEF section entries ``- name ... ;`` by name."""
    out = {}
    for chunk in body.split(";"):
        chunk = chunk.strip()
        if chunk.startswith("-"):
            out[chunk[1:].split()[0]] = chunk + " ;"
    return out


def _component_box(design: Any, comp: dict[str, Any], sizes: dict[str, tuple[int, int]]) -> tuple[int, int, int, int]:
    macro = comp["macro"]
    if macro not in sizes:
        sizes[macro] = tuple(int(v) for v in design.macro(macro)["size"])
    w, h = sizes[macro]
    if comp["orient"] in ("E", "W", "FE", "FW"):
        w, h = h, w
    x, y = comp["location"]
    return (int(x), int(y), int(x) + w, int(y) + h)


def _touches(a: tuple[int, ...], b: tuple[int, ...]) -> bool:
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def _boundary_points(design: Any, net: int, box: tuple[int, int, int, int]) -> list[tuple[str, int, int]]:
    """(layer, x, y) where the net's routing (all inside the box) ends on the box edge."""
    out = []
    for layer, x1, y1, x2, y2, *_ in design.engine.net_routing(net)["wires"]:
        for x, y in ((x1, y1), (x2, y2)):
            if x in (box[0], box[2]) or y in (box[1], box[3]):
                out.append((str(layer), int(x), int(y)))
    return sorted(set(out))


def make_region(
    testcase: str,
    out_dir: str | os.PathLike[str],
    *,
    location: tuple[int, int] | None = None,
    size: int = 1,
    box: tuple[int, int, int, int] | None = None,
    design: Any = None,
) -> RegionSummary:
    """Writes the static region (``location`` + ``size`` in GCells, or ``box`` in DBU) of ``testcase``
    into ``out_dir`` (see the module docstring); ``design``: the loaded, unrouted testcase to reuse
    (it is routed inside the box as a side effect). Raises :class:`RegionError` for a bad region."""
    from xroute import load_design
    from xroute.session import open_session

    if (location is None) == (box is None):
        raise RegionError("give either a GCell location (with a size) or a box")
    d = design if design is not None else load_design(testcase)
    session = open_session(d)
    box = _checked_box(d, session, location, size, box)

    region = session.open_region(box)
    rows = np.asarray(region.candidates)
    grid_nodes = int((region.grid()["flags"] != 0).sum())
    region.route_rest("heuristic")
    region.commit()

    nets = _region_nets(d, rows, box)
    def_text = Path(d.def_path).read_text()
    comp_entries = _entries(_section(def_text, "COMPONENTS"))
    keep, die = _kept_components(d, comp_entries, nets, box)
    region_def, boundary = _region_def(d, def_text, comp_entries, keep, nets, die)

    summary = RegionSummary(Path(out_dir), d.name, box, tuple(die), size if location else None,
                            tuple(location) if location else None, len(nets),
                            sum(len(p) for _, p, _ in nets), boundary, grid_nodes, [n for n, _, _ in nets])
    if not nets:
        raise RegionError(f"no net to route in box {box} of {d.name}")
    _write_atomically(Path(out_dir), {
        "region.def": region_def,
        "region.guide": _region_guides(d, nets, die),
        REGION_YAML: yaml.safe_dump(summary.to_yaml(), sort_keys=False),
    }, lef=Path(d.lef_paths[0]))
    return summary


RegionNet = tuple[str, list[tuple[str, str]], list[tuple[str, int, int]]]  # name, (comp, pin) inside, boundary points


def _checked_box(d: Any, session: Any, location: tuple[int, int] | None, size: int,
                 box: tuple[int, int, int, int] | None) -> tuple[int, int, int, int]:
    """The region's box in DBU (from a GCell location and size, or as given), inside the die."""
    xs, ys = (np.asarray(a) for a in session.gcell_lines)
    if location is not None:
        box = region_box(xs, ys, location, size)
    assert box is not None
    xlo, ylo, xhi, yhi = (int(v) for v in box)
    die0 = d.die_area
    if not (xlo < xhi and ylo < yhi) or xlo < die0[0] or ylo < die0[1] or xhi > die0[2] or yhi > die0[3]:
        raise RegionError(f"box {xlo},{ylo},{xhi},{yhi} is empty or not inside the die {tuple(die0)}")
    return (xlo, ylo, xhi, yhi)


def _region_nets(d: Any, rows: np.ndarray, box: tuple[int, int, int, int]) -> list[RegionNet]:
    """The candidates with two or more terminals in the box: pins whose access points (the
    router's) lie in it, and the points where the net's routing crosses the box edge."""
    xlo, ylo, xhi, yhi = box
    pa = d.engine.pin_access()
    points, start = np.asarray(pa["points"]), np.asarray(pa["start"])
    pin_start = np.asarray(d.net_pin_start)

    def inside(pin_ref: int) -> bool:
        p = points[start[pin_ref]:start[pin_ref + 1]]
        return bool(((p[:, 0] >= xlo) & (p[:, 0] <= xhi) & (p[:, 1] >= ylo) & (p[:, 1] <= yhi)).any())

    nets: list[RegionNet] = []
    for net in sorted(int(n) for n in rows[:, 0]):
        pins = [cp for k, cp in enumerate(d.net_pins(net)) if inside(int(pin_start[net]) + k)]
        bnd = _boundary_points(d, net, box)
        if len(pins) + len(bnd) >= 2:
            nets.append((d.net_names[net], pins, bnd))
    return nets


def _kept_components(d: Any, comp_entries: dict[str, str], nets: list[RegionNet],
                     box: tuple[int, int, int, int]) -> tuple[set[str], list[int]]:
    """(components kept: those with a region pin or touching the box, the region's die: the box
    grown over them and clipped to the design's die)."""
    sizes: dict[str, tuple[int, int]] = {}
    keep = {c for _, pins, _ in nets for c, _ in pins if c != "PIN"}
    die = list(box)
    for name in comp_entries:
        cb = _component_box(d, d.component(name), sizes)
        if name in keep or _touches(cb, box):
            keep.add(name)
            die = [min(die[0], cb[0]), min(die[1], cb[1]), max(die[2], cb[2]), max(die[3], cb[3])]
    die0 = d.die_area
    return keep, [max(die[0], die0[0]), max(die[1], die0[1]), min(die[2], die0[2]), min(die[3], die0[3])]


def _region_def(d: Any, def_text: str, comp_entries: dict[str, str], keep: set[str], nets: list[RegionNet],
                die: list[int]) -> tuple[str, int]:
    """(the region's DEF text, the number of boundary pins it got)."""
    io_entries = _entries(_section(def_text, "PINS"))
    layer_width = {layer.name: int(layer.width) for layer in d.routing_layers}
    pin_lines, net_lines, boundary = [], [], 0
    for name, pins, bnd in nets:
        conns = [f"( {'PIN' if c == 'PIN' else c} {p} )" for c, p in pins]
        pin_lines += [io_entries[p] for c, p in pins if c == "PIN" and p in io_entries]
        for layer, x, y in bnd:
            pin = f"xr_boundary_{boundary}"
            boundary += 1
            hw = max(1, layer_width.get(layer, 100) // 2)
            pin_lines.append(f"- {pin} + NET {name} + DIRECTION INOUT + USE SIGNAL\n  + LAYER {layer} ( {-hw} {-hw} ) "
                             f"( {hw} {hw} )\n  + PLACED ( {x} {y} ) N ;")
            conns.append(f"( PIN {pin} )")
        net_lines.append(f"- {name}\n  " + " ".join(conns) + "\n ;")

    out = ["VERSION 5.8 ;", 'DIVIDERCHAR "/" ;', 'BUSBITCHARS "[]" ;', f"DESIGN {d.name}_region ;",
           f"UNITS DISTANCE MICRONS {d.dbu_per_micron} ;", "",
           f"DIEAREA ( {die[0]} {die[1]} ) ( {die[2]} {die[3]} ) ;", ""]
    out += [line.strip() for line in def_text.splitlines() if line.strip().startswith("TRACKS ")]
    out += [f"GCELLGRID X {die[0]} DO 2 STEP {die[2] - die[0]} ;", f"GCELLGRID Y {die[1]} DO 2 STEP {die[3] - die[1]} ;", ""]
    vias = re.search(r"^\s*VIAS\s+\d+\s*;.*?^\s*END\s+VIAS\s*$", def_text, re.S | re.M)
    if vias:
        out += [vias.group(0).strip(), ""]
    comps = [comp_entries[c] for c in comp_entries if c in keep]
    out += [f"COMPONENTS {len(comps)} ;", *comps, "END COMPONENTS", ""]
    out += [f"PINS {len(pin_lines)} ;", *pin_lines, "END PINS", ""]
    out += [f"NETS {len(net_lines)} ;", *net_lines, "END NETS", "", "END DESIGN", ""]
    return "\n".join(out), boundary


def _region_guides(d: Any, nets: list[RegionNet], die: list[int]) -> str:
    """The region nets' guides clipped to the region's die (empty without guides)."""
    guide_lines: list[str] = []
    gstart, grects, glayers = np.asarray(d.guide_start), np.asarray(d.guide_rects), np.asarray(d.guide_layers)
    layer_names = [layer.name for layer in d.layers]
    if d.has_guides:
        for name, _, _ in nets:
            n = d.net_id(name)
            rects = []
            for g in range(gstart[n], gstart[n + 1]):
                r = grects[g]
                c = (max(r[0], die[0]), max(r[1], die[1]), min(r[2], die[2]), min(r[3], die[3]))
                if c[0] < c[2] and c[1] < c[3]:
                    rects.append(f"{c[0]} {c[1]} {c[2]} {c[3]} {layer_names[glayers[g]]}")
            guide_lines += [name, "(", *rects, ")"]
    return "\n".join(guide_lines) + "\n"


def _write_atomically(out_dir: Path, files: dict[str, str], lef: Path) -> None:
    """Writes the files and a copy of ``lef`` into a temporary sibling folder, then renames it to
    ``out_dir`` (replacing an earlier region folder: one holding region.yaml)."""
    out_dir = out_dir.resolve()
    if out_dir.exists() and not (out_dir / REGION_YAML).is_file() and any(out_dir.iterdir()):
        raise RegionError(f"{out_dir} exists and is not a region folder; choose another --out")
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.", dir=out_dir.parent))
    try:
        atomic_copy(lef, tmp / "region.lef")
        for name, text in files.items():
            atomic_write_text(tmp / name, text)
        if out_dir.exists():
            old = out_dir.with_name(f".{out_dir.name}.old")
            shutil.rmtree(old, ignore_errors=True)
            out_dir.rename(old)
            tmp.rename(out_dir)
            shutil.rmtree(old, ignore_errors=True)
        else:
            tmp.rename(out_dir)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def load_region(region_dir: str | os.PathLike[str]) -> tuple[Any, dict[str, Any]]:
    """(design, region.yaml dict) of a folder written by :func:`make_region`."""
    from xroute import load_design
    from xroute.errors import InputError

    folder = Path(region_dir)
    meta_path = folder / REGION_YAML
    if not meta_path.is_file():
        raise InputError(f"not a region folder (no {REGION_YAML}); make one with xroute make-region", str(folder), 0)
    try:
        meta = yaml.safe_load(meta_path.read_text())
        files = meta["files"]
        box = tuple(int(v) for v in meta["die"])
    except (yaml.YAMLError, KeyError, TypeError, ValueError) as exc:
        raise InputError(f"malformed region description ({type(exc).__name__}: {exc})", str(meta_path), 0) from exc
    meta["die"] = box
    guide = folder / files["guide"] if files.get("guide") else None
    design = load_design(lef=folder / files["lef"], def_=folder / files["def"], guide=guide)
    return design, meta

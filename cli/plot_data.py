"""What the pictures read (``xroute plot-region``, ``xroute plot``): a run folder's inputs, DRC
markers, the GCell grid, one colour per layer. No matplotlib here.

Coordinates are DEF database units (DBU). :func:`gcell_box` turns GCell indices into a box with the
router's GCell grid: the DEF's GCELLGRID, else the most common guide extent (the global router's
GCell pitch), as engine_cpp/grid/gcell_grid.cpp derives it.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from xroute.errors import InputError, XrouteError, safe_text

if TYPE_CHECKING:
    from xroute.design import Design

Box = tuple[int, int, int, int]  # xlo, ylo, xhi, yhi (DBU)


@dataclass(frozen=True)
class Marker:
    kind: str
    layer: str
    box: Box
    nets: str  # the report's two net fields joined by a space ('-': no net)

    @property
    def net_names(self) -> list[str]:
        """The nets the marker names (one for a same-net rule, two for a short or spacing), no '-'."""
        return [n for n in dict.fromkeys(self.nets.split()) if n != "-"]

    def label(self) -> str:
        """``type layer: net1 × net2`` for the picture."""
        nets = " × ".join(self.net_names) or "no net"
        return f"{self.kind} {self.layer}: {nets}"


# Distinct colours: routing layers from matplotlib's tab10, cut layers from a dark set of their own,
# so that Via1 and Via2 differ from each other and from every metal.
ROUTING_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf",
                   "#bcbd22", "#7f7f7f")
CUT_COLOURS = ("#000000", "#7b3294", "#00703c", "#c51b7d", "#a6611a", "#084594", "#b2182b", "#4d4d4d", "#01665e")


def layer_colours(design: Design) -> dict[str, str]:
    """One colour per routing layer and per cut (via) layer, by the layer's place in the LEF."""
    colours: dict[str, str] = {}
    routing = cut = 0
    for layer in design.layers:
        if layer.type == "ROUTING":
            colours[layer.name] = ROUTING_COLOURS[routing % len(ROUTING_COLOURS)]
            routing += 1
        elif layer.type == "CUT":
            colours[layer.name] = CUT_COLOURS[cut % len(CUT_COLOURS)]
            cut += 1
    return colours


def read_drc_report(path: Path) -> list[Marker]:
    """The markers of a DRC report written by xroute (``type layer xlo ylo xhi yhi nets...``)."""
    markers = []
    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        parts = line.split()
        try:
            box = (int(parts[2]), int(parts[3]), int(parts[4]), int(parts[5]))
        except (IndexError, ValueError) as exc:
            raise InputError("expected: type layer xlo ylo xhi yhi nets", str(path), n) from exc
        markers.append(Marker(parts[0], parts[1], box, " ".join(parts[6:])))
    return markers


def _pitch(rects: np.ndarray, axis: int) -> tuple[int, int]:
    """(most common guide extent along axis 0 = x / 1 = y, low edge of the first guide of that extent)."""
    sizes = rects[:, 2 + axis] - rects[:, axis]
    sizes = sizes[sizes > 0]
    if sizes.size == 0:
        return 0, 0
    values, counts = np.unique(sizes, return_counts=True)
    best = int(values[int(np.argmax(counts))])
    first = int(np.nonzero((rects[:, 2 + axis] - rects[:, axis]) == best)[0][0])
    return best, int(rects[first, axis])


def gcell_lines(design: Design, axis: int) -> list[int]:
    """GCell boundaries (DBU) along x (0) or y (1), die edges included."""
    lo, hi = design.die_area[axis], design.die_area[axis + 2]
    lines = [int(v) for v in design.gcell_lines("x" if axis == 0 else "y")]
    if len(lines) < 2:
        if not design.has_guides or len(design.guide_rects) == 0:
            raise XrouteError("the design has no GCELLGRID and no guides to derive GCells from: use --box")
        step, origin = _pitch(np.asarray(design.guide_rects), axis)
        first = origin - ((origin - lo) // step) * step
        if first < lo:
            first += step
        lines = list(range(first, hi, step))
        if lines and hi - lines[-1] < step // 2 and lines[-1] > lo:
            lines.pop()
    return sorted({v for v in [*lines, lo, hi] if lo <= v <= hi})


def gcell_box(design: Design, x: int, y: int, size: int) -> Box:
    """The box of ``size`` x ``size`` GCells whose lower-left GCell is (x, y)."""
    xs, ys = gcell_lines(design, 0), gcell_lines(design, 1)
    if not (0 <= x < len(xs) - 1 and 0 <= y < len(ys) - 1):
        raise XrouteError(f"GCell ({x}, {y}) is outside the design's {len(xs) - 1} x {len(ys) - 1} GCells")
    return xs[x], ys[y], xs[min(x + size, len(xs) - 1)], ys[min(y + size, len(ys) - 1)]


@dataclass(frozen=True)
class RunFiles:
    """The files of a route output folder, found through its metrics JSON."""

    metrics: Path
    lef: list[str]
    def_path: Path  # the routed DEF
    guide: str | None  # the guide file the run read, when it still exists (None: built-in or none)
    drc: Path | None  # the DRC report, when present


def run_files(folder: Path) -> RunFiles:
    """The routed DEF, LEF, guide and DRC report of a route output folder (from its metrics JSON; the
    guide gives the GCell grid when the DEF has no GCELLGRID, and the out-of-guide wire)."""
    found = sorted(folder.glob("*.metrics.json"))
    if not found:
        raise InputError("no *.metrics.json here: give a route output folder, or a DEF with --lef", str(folder), 0)
    from xroute.json_files import read_json

    m = read_json(found[0], "metrics JSON")
    try:
        lef = [str(p) for p in m["inputs"]["lef"]]
        guide = m["inputs"].get("guide")
        design = m["design"]
    except (KeyError, TypeError, AttributeError, IndexError) as exc:
        raise InputError(f"not a metrics JSON written by xroute: {type(exc).__name__}: {safe_text(exc)}",
                         str(found[0]), 0) from None
    from xroute.safe_paths import safe_stem

    def_path = folder / f"{safe_stem(str(design))}.routed.def"
    drc = folder / f"{safe_stem(str(design))}.drc.rpt"
    if not def_path.is_file():
        raise InputError("routed DEF not found", str(def_path), 0)
    guide = str(guide) if guide and Path(str(guide)).is_file() else None
    return RunFiles(found[0], lef, def_path, guide, drc if drc.is_file() else None)


def run_dir_inputs(folder: Path) -> tuple[list[str], Path, str | None, Path | None]:
    """(LEF files, routed DEF, guide or None, DRC report or None) of a route output folder."""
    f = run_files(folder)
    return f.lef, f.def_path, f.guide, f.drc


def picture_inputs(source: Path, lef: list[Path] | None, guide: Path | None,
                   drc: Path | None) -> tuple[list[str], Path, str | None, Path | None]:
    """(LEF files, routed DEF, guide or None, DRC report or None) of a picture's source: a route output
    folder (its files; --guide and --drc given replace them), or a DEF file with the LEF, guide and
    report given. InputError naming the source when it is neither."""
    if not source.exists():
        raise InputError("no such folder or file: give a route output folder, or a DEF file with --lef", str(source), 0)
    if source.is_dir():
        lef_paths, def_path, found_guide, found_drc = run_dir_inputs(source)
        return lef_paths, def_path, str(guide) if guide else found_guide, drc or found_drc
    if not lef:
        raise InputError("a DEF file needs --lef (or give a route output folder)", str(source), 0)
    return [str(p) for p in lef], source, str(guide) if guide else None, drc


def parse_ints(text: str, count: int, what: str) -> tuple[int, ...]:
    try:
        values = tuple(int(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != count:
        raise XrouteError(f"{what} must be {count} comma-separated integers, got '{text}'")
    return values


def describe(box: Box) -> str:
    return f"({box[0]},{box[1]})-({box[2]},{box[3]})"




def picture_format(out: Path) -> str:
    """'png' or 'svg' from the picture file's suffix."""
    suffix = out.suffix.lower().lstrip(".")
    if suffix not in ("png", "svg"):
        raise XrouteError(f"--out must be a .png or .svg file, got '{out.name}'")
    return suffix

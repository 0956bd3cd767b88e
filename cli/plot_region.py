"""A PNG picture of a region's routing: wires, vias and patches coloured by layer, pins, design-rule
markers and a legend (``xroute plot-region``). Needs matplotlib (optional extra ``plot``).

Coordinates are DEF database units. :func:`gcell_box` turns GCell indices into a box with the
router's GCell grid: the DEF's GCELLGRID, else the most common guide extent (the global router's
GCell pitch), as engine_cpp/flow/regions.cpp derives it.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from xroute.errors import InputError, XrouteError

if TYPE_CHECKING:
    from xroute.design import Design

Box = tuple[int, int, int, int]  # xlo, ylo, xhi, yhi (DBU)


@dataclass(frozen=True)
class Marker:
    kind: str
    layer: str
    box: Box
    nets: str


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


def _overlaps(a: Box, b: Box) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def collect_shapes(design: Design, box: Box) -> dict[str, list[Box]]:
    """Routing metal and cuts inside ``box`` by layer name (wires as rectangles of their width)."""
    width = {layer.name: layer.width for layer in design.layers}
    via_shapes: dict[str, list[tuple[str, int, int, int, int]]] = {}
    shapes: dict[str, list[Box]] = {}

    def add(layer: str, r: Box) -> None:
        if _overlaps(r, box):
            shapes.setdefault(layer, []).append(r)

    for net in range(design.num_nets):
        routing = design.net_routing(net)
        for layer, x1, y1, x2, y2, w, ext1, ext2 in routing["wires"]:
            half = (w or width.get(layer, 0)) // 2
            e1, e2 = (half if ext1 < 0 else ext1), (half if ext2 < 0 else ext2)
            if x1 == x2:
                lo, hi = (y1, y2) if y1 <= y2 else (y2, y1)
                lo_e, hi_e = (e1, e2) if y1 <= y2 else (e2, e1)
                add(layer, (x1 - half, lo - lo_e, x1 + half, hi + hi_e))
            else:
                lo, hi = (x1, x2) if x1 <= x2 else (x2, x1)
                lo_e, hi_e = (e1, e2) if x1 <= x2 else (e2, e1)
                add(layer, (lo - lo_e, y1 - half, hi + hi_e, y1 + half))
        for name, x, y in routing["vias"]:
            if name not in via_shapes:
                via_shapes[name] = design.via(name)["shapes"]
            for layer, xlo, ylo, xhi, yhi in via_shapes[name]:
                add(layer, (x + xlo, y + ylo, x + xhi, y + yhi))
        for layer, xlo, ylo, xhi, yhi in routing["patches"]:
            add(layer, (xlo, ylo, xhi, yhi))
    return shapes


def collect_pins(design: Design, box: Box) -> list[tuple[str, Box]]:
    names = [layer.name for layer in design.layers]
    pins = []
    for net in range(design.num_nets):
        for _, layer, xlo, ylo, xhi, yhi in design.net_pin_shapes(net):
            r = (int(xlo), int(ylo), int(xhi), int(yhi))
            if _overlaps(r, box):
                pins.append((names[int(layer)], r))
    return pins


def render_png(design: Design, box: Box, markers: list[Marker], title: str) -> bytes:
    """The picture as PNG bytes."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PatchCollection
        from matplotlib.patches import Patch, Rectangle
    except ImportError as exc:
        raise XrouteError("plot-region needs matplotlib: pip install 'xroute[plot]'") from exc

    shapes = collect_shapes(design, box)
    pins = collect_pins(design, box)
    order = [layer.name for layer in design.layers]
    routing = [layer.name for layer in design.layers if layer.type == "ROUTING"]
    cmap = plt.get_cmap("tab10")
    colour = {name: cmap(i % 10) for i, name in enumerate(routing)}
    aspect = (box[3] - box[1]) / max(box[2] - box[0], 1)
    fig, ax = plt.subplots(figsize=(11, min(max(7 * aspect, 3.0), 14.0) + 0.8), dpi=110)
    handles = []
    for layer in sorted(shapes, key=order.index):
        cut = layer not in colour
        rects = [Rectangle((r[0], r[1]), r[2] - r[0], r[3] - r[1]) for r in shapes[layer]]
        face = (0.15, 0.15, 0.15, 0.9) if cut else (*colour[layer][:3], 0.45)
        ax.add_collection(PatchCollection(rects, facecolor=face, edgecolor=face[:3], linewidth=0.3))
        handles.append(Patch(facecolor=face, label=f"{layer} ({len(rects)})"))
    if pins:
        rects = [Rectangle((r[0], r[1]), r[2] - r[0], r[3] - r[1]) for _, r in pins]
        ax.add_collection(PatchCollection(rects, facecolor="none", edgecolor="black", hatch="///", linewidth=0.6))
        handles.append(Patch(facecolor="none", edgecolor="black", hatch="///", label=f"pins ({len(pins)})"))
    inside = [m for m in markers  # closed boxes: a marker may be a line or a point
              if m.box[0] <= box[2] and box[0] <= m.box[2] and m.box[1] <= box[3] and box[1] <= m.box[3]]
    for m in inside:
        ax.add_patch(Rectangle((m.box[0], m.box[1]), max(m.box[2] - m.box[0], 1), max(m.box[3] - m.box[1], 1),
                               facecolor="none", edgecolor="red", linewidth=1.6))
        ax.plot([(m.box[0] + m.box[2]) / 2], [(m.box[1] + m.box[3]) / 2], marker="x", color="red", markersize=8)
    if inside:
        kinds = sorted({m.kind for m in inside})
        handles.append(Patch(facecolor="none", edgecolor="red", linewidth=1.6,
                             label=f"DRC markers ({len(inside)}: {', '.join(kinds)})"))
    ax.set_xlim(box[0], box[2])
    ax.set_ylim(box[1], box[3])
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("x (DBU)")
    ax.set_ylabel("y (DBU)")
    ax.ticklabel_format(style="plain", useOffset=False)
    ax.tick_params(labelsize=7)
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    plt.close(fig)
    return buf.getvalue()


def run_dir_inputs(folder: Path) -> tuple[list[str], Path, str | None, Path | None]:
    """(LEF files, routed DEF, guide or None, DRC report or None) of a route output folder (from its
    metrics JSON; the guide gives the GCell grid when the DEF has no GCELLGRID)."""
    import json

    found = sorted(folder.glob("*.metrics.json"))
    if not found:
        raise InputError("no *.metrics.json here: give a route output folder, or a DEF with --lef", str(folder), 0)
    try:
        m = json.loads(found[0].read_text(encoding="utf-8"))
        lef = list(m["inputs"]["lef"])
        guide = m["inputs"].get("guide")
        design = m["design"]
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError(f"not a metrics JSON written by xroute: {exc}", str(found[0]), 0) from exc
    from xroute.safe_paths import safe_stem

    def_path = folder / f"{safe_stem(str(design))}.routed.def"
    drc = folder / f"{safe_stem(str(design))}.drc.rpt"
    if not def_path.is_file():
        raise InputError("routed DEF not found", str(def_path), 0)
    return lef, def_path, guide if guide and Path(guide).is_file() else None, drc if drc.is_file() else None


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



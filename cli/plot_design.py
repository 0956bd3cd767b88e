"""A picture of a whole routed design (``xroute plot``): wire per GCell as a heat map, out-of-guide
wire in magenta, and the design-rule markers as points, one colour and shape per type, beside a bar
chart of the violations by type. PNG or SVG; needs matplotlib (optional extra ``plot``).

Out-of-guide wire: the part of a wire's centre line outside every guide of its net on its layer
(guides as closed boxes), measured here from the routed DEF and the guide file the run read; a run
routed on the built-in global router's guides has no guide file and no such layer.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from xroute.errors import XrouteError
from xroute.cli.plot_data import Marker, gcell_lines

if TYPE_CHECKING:
    from xroute.design import Design

TYPE_STYLES = (("#d62728", "o"), ("#1f77b4", "s"), ("#2ca02c", "^"), ("#ff7f0e", "D"), ("#9467bd", "v"),
               ("#8c564b", "P"), ("#e377c2", "X"), ("#17becf", "*"))  # (colour, matplotlib marker) per type
FALLBACK_GCELLS = 64  # GCells along the longer side when the design has no GCELLGRID and no guides

Segment = tuple[int, int, int, int]  # x1, y1, x2, y2 (DBU), axis-parallel


@dataclass(frozen=True)
class DesignPicture:
    xs: list[int]  # GCell lines along x (DBU)
    ys: list[int]
    wire_um: np.ndarray  # [len(ys) - 1, len(xs) - 1]: wire length per GCell (µm), all layers
    out_of_guide: list[Segment]  # pieces of wire centre lines outside their net's guides on their layer
    out_of_guide_um: float | None  # None: no guides to measure against
    markers: list[Marker]


def _grid(design: Design) -> tuple[list[int], list[int]]:
    try:
        return gcell_lines(design, 0), gcell_lines(design, 1)
    except XrouteError:
        xlo, ylo, xhi, yhi = design.die_area
        step = max(max(xhi - xlo, yhi - ylo) // FALLBACK_GCELLS, 1)
        return ([*range(xlo, xhi, step), xhi], [*range(ylo, yhi, step), yhi])


def _uncovered(lo: int, hi: int, covers: list[tuple[int, int]]) -> list[tuple[int, int]]:
    """The parts of [lo, hi] outside the union of the closed intervals ``covers``."""
    out, at = [], lo
    for a, b in sorted(covers):
        if a > at:
            out.append((at, min(a, hi)))
        at = max(at, b)
        if at >= hi:
            break
    if at < hi:
        out.append((at, hi))
    return [(a, b) for a, b in out if b > a]


def _outside_guides(seg: Segment, guides: list[tuple[int, int, int, int]]) -> list[Segment]:
    x1, y1, x2, y2 = seg
    if y1 == y2:
        lo, hi = sorted((x1, x2))
        covers = [(g[0], g[2]) for g in guides if g[1] <= y1 <= g[3]]
        return [(a, y1, b, y1) for a, b in _uncovered(lo, hi, covers)]
    lo, hi = sorted((y1, y2))
    covers = [(g[1], g[3]) for g in guides if g[0] <= x1 <= g[2]]
    return [(x1, a, x1, b) for a, b in _uncovered(lo, hi, covers)]


def _spread(segments: np.ndarray, xs: list[int], ys: list[int]) -> np.ndarray:
    """Wire length (DBU) per GCell: each segment sampled every quarter of the smallest GCell side."""
    grid = np.zeros((len(ys) - 1, len(xs) - 1))
    if segments.size == 0:
        return grid
    step = max(min(np.diff(xs).min(), np.diff(ys).min()) / 4.0, 1.0)
    length = np.abs(segments[:, 2] - segments[:, 0]) + np.abs(segments[:, 3] - segments[:, 1])
    samples = np.maximum(np.ceil(length / step), 1).astype(np.int64)
    owner = np.repeat(np.arange(len(segments)), samples)
    first = np.cumsum(samples) - samples
    t = (np.arange(samples.sum()) - np.repeat(first, samples) + 0.5) / np.repeat(samples, samples)
    px = segments[owner, 0] + t * (segments[owner, 2] - segments[owner, 0])
    py = segments[owner, 1] + t * (segments[owner, 3] - segments[owner, 1])
    weight = length[owner] / samples[owner]
    grid, _, _ = np.histogram2d(py, px, bins=[ys, xs], weights=weight)
    return grid


def measure(design: Design, markers: list[Marker], with_guides: bool) -> DesignPicture:
    """Wire per GCell, the out-of-guide pieces (when ``with_guides``) and the markers of a routed design."""
    xs, ys = _grid(design)
    names = [layer.name for layer in design.layers]
    segments: list[Segment] = []
    outside: list[Segment] = []
    use_guides = with_guides and design.has_guides
    for net in range(design.num_nets):
        wires = [w for w in design.net_routing(net)["wires"] if w[1] != w[3] or w[2] != w[4]]
        segments += [(int(w[1]), int(w[2]), int(w[3]), int(w[4])) for w in wires]
        if not use_guides or not wires:
            continue
        rects, layers = design.net_guides(net)
        by_layer: dict[str, list[tuple[int, int, int, int]]] = {}
        for r, layer in zip(rects.tolist(), layers.tolist()):
            by_layer.setdefault(names[layer], []).append(tuple(r))
        for w in wires:
            outside += _outside_guides((int(w[1]), int(w[2]), int(w[3]), int(w[4])), by_layer.get(w[0], []))
    dbu = max(design.dbu_per_micron, 1)
    wire = _spread(np.asarray(segments, dtype=np.float64).reshape(-1, 4), xs, ys) / dbu
    out_um = sum(abs(s[2] - s[0]) + abs(s[3] - s[1]) for s in outside) / dbu if use_guides else None
    return DesignPicture(xs, ys, wire, outside, out_um, markers)


def render(design: Design, pic: DesignPicture, title: str, fmt: str = "png") -> bytes:
    """The picture as PNG or SVG bytes: the map (µm axes) and the violations by type."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection
    except ImportError as exc:
        raise XrouteError("plot needs matplotlib: pip install 'xroute[plot]'") from exc

    plt.rcParams["svg.fonttype"] = "none"
    dbu = max(design.dbu_per_micron, 1)
    xlo, ylo, xhi, yhi = design.die_area
    aspect = (yhi - ylo) / max(xhi - xlo, 1)
    fig = plt.figure(figsize=(13, min(max(8 * aspect, 5.0), 12.0) + 1.2), dpi=110)
    grid = fig.add_gridspec(2, 2, width_ratios=[4, 1.3], height_ratios=[1, 1])
    ax, bars, key = fig.add_subplot(grid[:, 0]), fig.add_subplot(grid[0, 1]), fig.add_subplot(grid[1, 1])
    x_um, y_um = np.asarray(pic.xs) / dbu, np.asarray(pic.ys) / dbu
    mesh = ax.pcolormesh(x_um, y_um, np.ma.masked_equal(pic.wire_um, 0.0), cmap="Blues", shading="flat",
                         vmin=0.0, alpha=0.75)
    fig.colorbar(mesh, ax=ax, fraction=0.035, pad=0.01, label="wire per GCell (µm, all layers)")
    if pic.out_of_guide:
        lines = [[(s[0] / dbu, s[1] / dbu), (s[2] / dbu, s[3] / dbu)] for s in pic.out_of_guide]
        ax.add_collection(LineCollection(lines, colors="#e7298a", linewidths=1.4, zorder=3,
                                         label=f"out-of-guide wire ({pic.out_of_guide_um:,.1f} µm)"))
    counts: dict[str, int] = {}
    for m in pic.markers:
        counts[m.kind] = counts.get(m.kind, 0) + 1
    kinds = sorted(counts, key=lambda k: (-counts[k], k))
    for k, kind in enumerate(kinds):
        colour, shape = TYPE_STYLES[k % len(TYPE_STYLES)]
        pts = np.asarray([((m.box[0] + m.box[2]) / 2 / dbu, (m.box[1] + m.box[3]) / 2 / dbu)
                          for m in pic.markers if m.kind == kind])
        ax.scatter(pts[:, 0], pts[:, 1], s=40, c=colour, marker=shape, edgecolors="black", linewidths=0.4,
                   zorder=4, label=f"{kind} ({counts[kind]:,})")
    ax.set_xlim(xlo / dbu, xhi / dbu)
    ax.set_ylim(ylo / dbu, yhi / dbu)
    ax.set_aspect("equal")
    ax.set_xlabel("x (µm)")
    ax.set_ylabel("y (µm)")
    guide_note = ("no guide file: out-of-guide wire not measured" if pic.out_of_guide_um is None
                  else f"out-of-guide wire {pic.out_of_guide_um:,.1f} µm")
    ax.set_title(f"{title}\n{len(pic.markers):,} violations; {guide_note}; "
                 f"{len(pic.xs) - 1} x {len(pic.ys) - 1} GCells", fontsize=10)
    key.set_axis_off()
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        key.legend(handles, labels, loc="upper left", fontsize=8, frameon=False, title="on the map",
                   title_fontsize=9)
    _bars(bars, kinds, counts)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt)
    plt.close(fig)
    return buf.getvalue()


def _bars(ax, kinds: list[str], counts: dict[str, int]) -> None:  # noqa: ANN001
    """Violations by type, exact counts written on the bars."""
    ax.set_title("violations by type", fontsize=10)
    if not kinds:
        ax.text(0.5, 0.5, "no violations", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        return
    colours = [TYPE_STYLES[k % len(TYPE_STYLES)][0] for k in range(len(kinds))]
    y = np.arange(len(kinds))
    ax.barh(y, [counts[k] for k in kinds], color=colours, height=0.6)
    ax.set_ylim(max(len(kinds), 4) - 0.5, -0.5)
    ax.set_yticks(y, kinds, fontsize=8)
    for i, k in enumerate(kinds):
        ax.text(counts[k], i, f" {counts[k]:,}", va="center", fontsize=8)
    ax.set_xlabel("markers")
    ax.margins(x=0.25)

"""A picture of a region's routing (``xroute plot-region``): wires, vias and patches in one colour per
layer and per via layer, pins hatched, design-rule markers labelled with their type and nets, the
nets a marker names labelled on their shapes, and one net highlighted on request (the others
dimmed). Axes in µm (DBU on request). Needs matplotlib (optional extra ``plot``).

Coordinates stay DEF database units (DBU) inside; only the tick labels are scaled to µm.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import TYPE_CHECKING

from xroute.errors import XrouteError
from xroute.cli.plot_data import Box, Marker, layer_colours

if TYPE_CHECKING:
    from xroute.design import Design

MAX_MARKER_LABELS = 30  # markers numbered in the picture and named in the legend; more are counted only
MAX_NET_LABELS = 20  # nets named by markers that get a label on their shapes


@dataclass(frozen=True)
class Shape:
    layer: str
    box: Box  # DBU
    net: int  # net index


def overlaps(a: Box, b: Box) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def touches(a: Box, b: Box) -> bool:
    """Closed boxes: a marker may be a line or a point."""
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def wire_box(x1: int, y1: int, x2: int, y2: int, half: int, ext1: int, ext2: int) -> Box:
    """The rectangle of a DEF wire segment of half-width ``half`` (extensions -1: half the width)."""
    e1, e2 = (half if ext1 < 0 else ext1), (half if ext2 < 0 else ext2)
    if x1 == x2:
        lo, hi = (y1, y2) if y1 <= y2 else (y2, y1)
        lo_e, hi_e = (e1, e2) if y1 <= y2 else (e2, e1)
        return (x1 - half, lo - lo_e, x1 + half, hi + hi_e)
    lo, hi = (x1, x2) if x1 <= x2 else (x2, x1)
    lo_e, hi_e = (e1, e2) if x1 <= x2 else (e2, e1)
    return (lo - lo_e, y1 - half, hi + hi_e, y1 + half)


def collect_shapes(design: Design, box: Box) -> list[Shape]:
    """Routing metal and cuts of every net that overlap ``box`` (wires as rectangles of their width)."""
    width = {layer.name: layer.width for layer in design.layers}
    via_shapes: dict[str, list[tuple[str, int, int, int, int]]] = {}
    shapes: list[Shape] = []
    for net in range(design.num_nets):
        routing = design.net_routing(net)
        for layer, x1, y1, x2, y2, w, ext1, ext2 in routing["wires"]:
            r = wire_box(x1, y1, x2, y2, (w or width.get(layer, 0)) // 2, ext1, ext2)
            if overlaps(r, box):
                shapes.append(Shape(layer, r, net))
        for name, x, y in routing["vias"]:
            if name not in via_shapes:
                via_shapes[name] = design.routed_via_shapes(name)
            for layer, xlo, ylo, xhi, yhi in via_shapes[name]:
                r = (x + xlo, y + ylo, x + xhi, y + yhi)
                if overlaps(r, box):
                    shapes.append(Shape(layer, r, net))
        for layer, xlo, ylo, xhi, yhi in routing["patches"]:
            r = (int(xlo), int(ylo), int(xhi), int(yhi))
            if overlaps(r, box):
                shapes.append(Shape(layer, r, net))
    return shapes


def collect_pins(design: Design, box: Box) -> list[Shape]:
    names = [layer.name for layer in design.layers]
    pins = []
    for net in range(design.num_nets):
        for _, layer, xlo, ylo, xhi, yhi in design.net_pin_shapes(net):
            r = (int(xlo), int(ylo), int(xhi), int(yhi))
            if overlaps(r, box):
                pins.append(Shape(names[int(layer)], r, net))
    return pins


@dataclass(frozen=True)
class RegionContent:
    shapes: list[Shape]
    pins: list[Shape]
    markers: list[Marker]  # those touching the box

    @property
    def empty(self) -> bool:
        return not (self.shapes or self.pins or self.markers)


def region_content(design: Design, box: Box, markers: list[Marker]) -> RegionContent:
    return RegionContent(collect_shapes(design, box), collect_pins(design, box),
                         [m for m in markers if touches(m.box, box)])


def _centre(b: Box) -> tuple[float, float]:
    return (b[0] + b[2]) / 2, (b[1] + b[3]) / 2


def _nearest(shapes: list[Shape], point: tuple[float, float]) -> Shape:
    def dist(s: Shape) -> float:
        dx = max(s.box[0] - point[0], 0, point[0] - s.box[2])
        dy = max(s.box[1] - point[1], 0, point[1] - s.box[3])
        return dx * dx + dy * dy
    return min(shapes, key=dist)


def render(design: Design, box: Box, content: RegionContent, title: str, highlight: int | None = None,
           dbu_axes: bool = False, fmt: str = "png") -> bytes:
    """The picture as PNG (or SVG) bytes. ``highlight``: a net index drawn bold, the others dimmed."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import PatchCollection
        from matplotlib.patches import Patch, Rectangle
        from matplotlib.ticker import FuncFormatter
    except ImportError as exc:
        raise XrouteError("plot-region needs matplotlib: pip install 'xroute[plot]'") from exc

    colour = layer_colours(design)
    order = [layer.name for layer in design.layers]
    names = design.net_names
    aspect = (box[3] - box[1]) / max(box[2] - box[0], 1)
    plt.rcParams["svg.fonttype"] = "none"  # SVG text stays text: searchable, and the tests read it
    fig, ax = plt.subplots(figsize=(12, min(max(7 * aspect, 3.0), 14.0) + 0.8), dpi=110)
    handles = []
    by_layer: dict[str, list[Shape]] = {}
    for s in content.shapes:
        by_layer.setdefault(s.layer, []).append(s)
    for layer in sorted(by_layer, key=lambda n: order.index(n) if n in order else len(order)):
        c = colour.get(layer, "#555555")
        cut = layer in colour and layer not in {lay.name for lay in design.routing_layers}
        alpha = 0.85 if cut else 0.45
        for mine, a, edge in ((False, alpha if highlight is None else 0.08, 0.3), (True, 0.9, 1.2)):
            group = [s for s in by_layer[layer] if (highlight is not None and s.net == highlight) == mine]
            if not group:
                continue
            rects = [Rectangle((s.box[0], s.box[1]), s.box[2] - s.box[0], s.box[3] - s.box[1]) for s in group]
            ax.add_collection(PatchCollection(rects, facecolor=c, alpha=a, edgecolor="black" if mine else c,
                                              linewidth=edge, zorder=3 if mine else (2 if cut else 1)))
        handles.append(Patch(facecolor=c, alpha=alpha, label=f"{layer}{' (via)' if cut else ''} ({len(by_layer[layer])})"))
    if content.pins:
        rects = [Rectangle((p.box[0], p.box[1]), p.box[2] - p.box[0], p.box[3] - p.box[1]) for p in content.pins]
        ax.add_collection(PatchCollection(rects, facecolor="none", edgecolor="black", hatch="///", linewidth=0.6,
                                          zorder=2))
        handles.append(Patch(facecolor="none", edgecolor="black", hatch="///", label=f"pins ({len(content.pins)})"))
    _draw_markers(ax, content, handles, Rectangle, Patch)
    _label_nets(ax, design, content, highlight, names)
    if highlight is not None:
        handles.append(Patch(facecolor="white", edgecolor="black", linewidth=1.2,
                             label=f"net {names[highlight]} (others dimmed)"))
    ax.set_xlim(box[0], box[2])
    ax.set_ylim(box[1], box[3])
    ax.set_aspect("equal")
    dbu = max(design.dbu_per_micron, 1)
    ax.set_title(f"{title}\nx {box[0] / dbu:g} to {box[2] / dbu:g} µm, y {box[1] / dbu:g} to {box[3] / dbu:g} µm",
                 fontsize=10)
    if dbu_axes:
        ax.ticklabel_format(style="plain", useOffset=False)
    else:
        um = FuncFormatter(lambda v, _pos: f"{v / dbu:g}")
        ax.xaxis.set_major_formatter(um)
        ax.yaxis.set_major_formatter(um)
    unit = "DBU" if dbu_axes else f"µm; {dbu} DBU per µm"
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"y ({unit})")
    ax.tick_params(labelsize=7)
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt)
    plt.close(fig)
    return buf.getvalue()


def _draw_markers(ax, content: RegionContent, handles: list, Rectangle, Patch) -> None:  # noqa: ANN001, N803
    """Red boxes and crosses, each of the first MAX_MARKER_LABELS numbered, with its type, layer and nets
    under that number in the legend (labels in the picture would cover each other where markers crowd)."""
    for k, m in enumerate(content.markers):
        ax.add_patch(Rectangle((m.box[0], m.box[1]), max(m.box[2] - m.box[0], 1), max(m.box[3] - m.box[1], 1),
                               facecolor="none", edgecolor="red", linewidth=1.6, zorder=5))
        cx, cy = _centre(m.box)
        ax.plot([cx], [cy], marker="x", color="red", markersize=8, zorder=5)
        if k < MAX_MARKER_LABELS:
            ax.annotate(str(k + 1), (cx, cy), xytext=(4, 4 + 9 * (k % 2)), textcoords="offset points", fontsize=8,
                        fontweight="bold", color="#b00020", zorder=6,
                        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "#b00020", "alpha": 0.85})
    if content.markers:
        kinds = sorted({m.kind for m in content.markers})
        handles.append(Patch(facecolor="none", edgecolor="red", linewidth=1.6,
                             label=f"DRC markers ({len(content.markers)}: {', '.join(kinds)})"))
        for k, m in enumerate(content.markers[:MAX_MARKER_LABELS]):
            handles.append(Patch(facecolor="none", edgecolor="none", label=f"  {k + 1}: {m.label()}"))
        if len(content.markers) > MAX_MARKER_LABELS:
            handles.append(Patch(facecolor="none", edgecolor="none",
                                 label=f"  ... {len(content.markers) - MAX_MARKER_LABELS} more, not numbered"))


def _label_nets(ax, design: Design, content: RegionContent, highlight: int | None,  # noqa: ANN001
                names: list[str]) -> None:
    """The name of each net a marker names (on its shape nearest that marker) and of the highlighted net."""
    index = {n: i for i, n in enumerate(names)}
    wanted: dict[int, tuple[float, float]] = {}
    for m in content.markers:
        for n in m.net_names:
            if n in index and index[n] not in wanted and len(wanted) < MAX_NET_LABELS:
                wanted[index[n]] = _centre(m.box)
    if highlight is not None and highlight not in wanted:
        mine = [s for s in content.shapes if s.net == highlight]
        if mine:
            wanted[highlight] = _centre(max(mine, key=lambda s: (s.box[2] - s.box[0]) * (s.box[3] - s.box[1])).box)
    for net, point in wanted.items():
        mine = [s for s in (*content.shapes, *content.pins) if s.net == net]
        if not mine:
            continue
        at = _centre(_nearest(mine, point).box)
        ax.annotate(f"net {names[net]}", at, xytext=(-10, -18), textcoords="offset points", fontsize=8,
                    fontweight="bold", color="#111", zorder=6, ha="right",
                    arrowprops={"arrowstyle": "-", "color": "#111", "lw": 0.8},
                    bbox={"boxstyle": "round,pad=0.2", "fc": "#fff7bc", "ec": "#111", "alpha": 0.9})

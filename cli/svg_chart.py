"""Small inline-SVG line charts for the HTML report (no JavaScript, no network).

``line_chart(title, series, y_label)`` draws one polyline per series over the iteration axis
(or another: ``x_label``, ``x_start``), with axes, ticks, a legend and a ``<title>`` tooltip on each
point (up to ``MAX_POINT_MARKS`` points a series; longer series are drawn as lines only).

Every series differs in colour, dash pattern and marker shape, so none is told by colour alone. A
series equal to an earlier one is drawn with its marks shifted right by ``DUPLICATE_SHIFT`` px and
hollow, and its legend says which one it is identical to: both stay visible. ``scale="symlog"``
draws log10(1 + v) (counts that fall 10 -> 1 -> 0 stay readable; ticks 0, 1, 10, 100, ...). A
linear axis spans at least ``min_span`` (so a 0.4% change is not drawn as the whole height), and
every chart states the range of its values under the plot.
"""

from __future__ import annotations

import math
from html import escape

PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22")
DASHES = ("", "7 3", "2 3", "9 3 2 3", "4 4", "1 3")  # stroke-dasharray per series ("": solid)
SHAPES = ("circle", "square", "triangle", "diamond", "down", "cross")  # point mark per series
DUPLICATE_SHIFT = 5  # px: marks of an identical series move right by this much per earlier copy
WIDTH, HEIGHT = 440, 260  # px
LEFT, RIGHT, TOP, BOTTOM = 64, 12, 28, 40  # margins, px
NOTE_HEIGHT = 16  # px: the range line under the axis
MAX_POINT_MARKS = 200  # a series with more points gets no per-point marks


def nice_ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """About ``count`` round tick values covering [lo, hi]."""
    if hi <= lo:
        hi = lo + 1.0
    raw = (hi - lo) / max(count - 1, 1)
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    start = math.floor(lo / step) * step
    ticks = [round(start, 10)]
    while ticks[-1] < hi:
        ticks.append(round(ticks[-1] + step, 10))
    return ticks


def symlog_ticks(hi: float) -> list[float]:
    """0, 1, 10, 100, ... up to the first power of ten at or above ``hi``."""
    ticks = [0.0, 1.0]
    while ticks[-1] < hi:
        ticks.append(ticks[-1] * 10)
    return ticks


def _fmt(v: float) -> str:
    if abs(v) >= 1000:
        return f"{v:,.0f}"
    return f"{v:.4g}"


def _mark(shape: str, cx: float, cy: float, color: str, hollow: bool, tip: str) -> str:
    fill = "#fff" if hollow else color
    common = f'fill="{fill}" stroke="{color}" stroke-width="1.5"'
    r = 3.5
    if shape == "circle":
        el = f'<circle cx="{cx:.1f}" cy="{cy:.1f}" r="{r}" {common}>'
        end = "</circle>"
    elif shape == "square":
        el = f'<rect x="{cx - r:.1f}" y="{cy - r:.1f}" width="{2 * r}" height="{2 * r}" {common}>'
        end = "</rect>"
    else:
        pts = {"triangle": [(0, -r - 1), (r + 1, r), (-r - 1, r)], "down": [(0, r + 1), (r + 1, -r), (-r - 1, -r)],
               "diamond": [(0, -r - 1), (r + 1, 0), (0, r + 1), (-r - 1, 0)],
               "cross": [(-r, -r), (r, r), (0, 0), (r, -r), (-r, r), (0, 0)]}[shape]
        el = (f'<polygon points="{" ".join(f"{cx + dx:.1f},{cy + dy:.1f}" for dx, dy in pts)}" {common}>')
        end = "</polygon>"
    return f'{el}<title>{escape(tip)}</title>{end}'


def _duplicates(series: list[tuple[str, list[float]]]) -> list[tuple[int, str | None]]:
    """(how many earlier series are equal to this one, the first of them's name) per series."""
    out: list[tuple[int, str | None]] = []
    for k, (_, vs) in enumerate(series):
        same = [j for j in range(k) if series[j][1] == vs]
        out.append((len(same), series[same[0]][0] if same else None))
    return out


def _y_range(values: list[float], scale: str, min_span: float) -> list[float]:
    lo, hi = (min(values), max(values)) if values else (0.0, 1.0)
    if scale == "symlog":
        return symlog_ticks(max(hi, 1.0))
    if hi - lo < min_span:  # widen around the middle, not below 0 for positive figures
        mid = (hi + lo) / 2
        lo, hi = mid - min_span / 2, mid + min_span / 2
        if lo < 0 <= min(values, default=0.0):
            lo, hi = 0.0, hi - lo
    lo = min(lo, 0.0) if hi - lo > 0.5 * abs(hi) or hi == lo else lo  # start at 0 unless that flattens the lines
    return nice_ticks(lo, hi)


def _range_note(values: list[float], unit: str, scale: str) -> str:
    if not values:
        return "no values"
    lo, hi = min(values), max(values)
    if scale == "symlog":
        return f"values {_fmt(lo)} to {_fmt(hi)} {unit}; axis log10(1 + v)"
    spread = f" (spread {(hi - lo) / abs(hi) * 100:.3g}% of the largest)" if lo > 0 and lo != hi else ""
    return f"values {_fmt(lo)} to {_fmt(hi)} {unit}{spread}"


def line_chart(title: str, series: list[tuple[str, list[float]]], y_label: str, x_label: str = "iteration",
               x_start: int = 0, scale: str = "linear", min_span: float = 0.0, unit: str = "") -> str:
    """An SVG element (a string) with one line per ``(name, values by iteration)``; the i-th value is
    drawn at x = ``x_start + i`` (0 for iterations, 1 for episodes). ``scale``: "linear" or
    "symlog"; ``min_span``: the least extent of a linear axis, in the values' unit."""
    values = [v for _, vs in series for v in vs]
    n = max((len(vs) for _, vs in series), default=1)
    ticks = _y_range(values, scale, min_span)
    tf = (lambda v: math.log10(1 + max(v, 0.0))) if scale == "symlog" else (lambda v: v)  # noqa: E731
    y0, y1 = tf(ticks[0]), tf(ticks[-1])
    pw, ph = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM
    dups = _duplicates(series)
    legend_top = HEIGHT + NOTE_HEIGHT
    total = legend_top + 18 * len(series)

    def x(i: int) -> float:
        return LEFT + (pw * i / (n - 1) if n > 1 else pw / 2)

    def y(v: float) -> float:
        return TOP + ph * (1 - (tf(v) - y0) / (y1 - y0 if y1 > y0 else 1))

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" class="chart" width="{WIDTH}" height="{total}" '
           f'viewBox="0 0 {WIDTH} {total}" role="img" aria-label="{escape(title)}">',
           f'<text x="{WIDTH / 2}" y="16" text-anchor="middle" class="chart-title">{escape(title)}</text>',
           f'<rect x="{LEFT}" y="{TOP}" width="{pw}" height="{ph}" fill="#fafafa" stroke="#ccc"/>']
    for t in ticks:
        out.append(f'<line x1="{LEFT}" x2="{LEFT + pw}" y1="{y(t):.1f}" y2="{y(t):.1f}" stroke="#e3e3e3"/>')
        out.append(f'<text x="{LEFT - 6}" y="{y(t) + 4:.1f}" text-anchor="end" class="tick">{_fmt(t)}</text>')
    step = max(1, math.ceil(n / 10))
    for i in range(0, n, step):
        out.append(f'<text x="{x(i):.1f}" y="{TOP + ph + 16}" text-anchor="middle" class="tick">{x_start + i}</text>')
    out.append(f'<text x="{LEFT + pw / 2}" y="{TOP + ph + 32}" text-anchor="middle" class="axis">{escape(x_label)}</text>')
    out.append(f'<text x="14" y="{TOP + ph / 2}" text-anchor="middle" class="axis" '
               f'transform="rotate(-90 14 {TOP + ph / 2})">{escape(y_label)}</text>')
    out.append(f'<text x="{LEFT}" y="{HEIGHT + 6}" class="range">{escape(_range_note(values, unit, scale))}</text>')
    for k, (name, vs) in enumerate(series):
        color, dash, shape = PALETTE[k % len(PALETTE)], DASHES[k % len(DASHES)], SHAPES[k % len(SHAPES)]
        copies, twin = dups[k]
        shift = DUPLICATE_SHIFT * copies
        dash_attr = f' stroke-dasharray="{dash}"' if dash else ""
        out.append(f'<g class="series" data-series="{k}">')
        if len(vs) > 1:
            pts = " ".join(f"{x(i):.1f},{y(v):.1f}" for i, v in enumerate(vs))
            out.append(f'<polyline fill="none" stroke="{color}" stroke-width="2"{dash_attr} points="{pts}"/>')
        for i, v in enumerate(vs if len(vs) <= MAX_POINT_MARKS else []):
            out.append(_mark(shape, x(i) + shift, y(v), color, copies > 0,
                             f"{name}: {x_label} {x_start + i}: {_fmt(v)}"))
        out.append("</g>")
        ly = legend_top + 18 * k + 4
        out.append(f'<line x1="{LEFT}" x2="{LEFT + 22}" y1="{ly + 3}" y2="{ly + 3}" stroke="{color}" '
                   f'stroke-width="2"{dash_attr}/>')
        out.append(_mark(shape, LEFT + 11 + shift, ly + 3, color, copies > 0, name))
        note = f" (identical to {twin}: marks shifted {shift} px)" if twin is not None else ""
        out.append(f'<text x="{LEFT + 28}" y="{ly + 7}" class="legend">{escape(name + note)}</text>')
    out.append("</svg>")
    return "\n".join(out)

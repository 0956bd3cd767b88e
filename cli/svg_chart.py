"""Small inline-SVG line charts for the HTML report (no JavaScript, no network).

``line_chart(title, series, y_label)`` draws one polyline per series over the iteration axis
(or another: ``x_label``, ``x_start``), with axes, ticks, a legend and a ``<title>`` tooltip on each
point (up to ``MAX_POINT_MARKS`` points a series; longer series are drawn as lines only).
"""

from __future__ import annotations

import math
from html import escape

PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22")
WIDTH, HEIGHT = 440, 260  # px
LEFT, RIGHT, TOP, BOTTOM = 64, 12, 28, 40  # margins, px
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


def _fmt(v: float) -> str:
    if abs(v) >= 1000:
        return f"{v:,.0f}"
    return f"{v:g}"


def line_chart(title: str, series: list[tuple[str, list[float]]], y_label: str, x_label: str = "iteration",
               x_start: int = 0) -> str:
    """An SVG element (a string) with one line per ``(name, values by iteration)``; the i-th value is
    drawn at x = ``x_start + i`` (0 for iterations, 1 for episodes)."""
    values = [v for _, vs in series for v in vs]
    n = max((len(vs) for _, vs in series), default=1)
    lo, hi = (min(values), max(values)) if values else (0.0, 1.0)
    lo = min(lo, 0.0) if hi - lo > 0.5 * abs(hi) or hi == lo else lo  # start at 0 unless that flattens the lines
    ticks = nice_ticks(lo, hi)
    y0, y1 = ticks[0], ticks[-1]
    pw, ph = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM

    def x(i: int) -> float:
        return LEFT + (pw * i / (n - 1) if n > 1 else pw / 2)

    def y(v: float) -> float:
        return TOP + ph * (1 - (v - y0) / (y1 - y0 if y1 > y0 else 1))

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" class="chart" width="{WIDTH}" height="{HEIGHT + 18 * len(series)}" '
           f'viewBox="0 0 {WIDTH} {HEIGHT + 18 * len(series)}" role="img" aria-label="{escape(title)}">',
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
    for k, (name, vs) in enumerate(series):
        color = PALETTE[k % len(PALETTE)]
        pts = " ".join(f"{x(i):.1f},{y(v):.1f}" for i, v in enumerate(vs))
        if len(vs) > 1:
            out.append(f'<polyline fill="none" stroke="{color}" stroke-width="2" points="{pts}"/>')
        for i, v in enumerate(vs if len(vs) <= MAX_POINT_MARKS else []):
            out.append(f'<circle cx="{x(i):.1f}" cy="{y(v):.1f}" r="3" fill="{color}">'
                       f'<title>{escape(name)}: {escape(x_label)} {x_start + i}: {_fmt(v)}</title></circle>')
        ly = HEIGHT + 18 * k + 4
        out.append(f'<rect x="{LEFT}" y="{ly}" width="14" height="4" fill="{color}"/>')
        out.append(f'<text x="{LEFT + 20}" y="{ly + 6}" class="legend">{escape(name)}</text>')
    out.append("</svg>")
    return "\n".join(out)

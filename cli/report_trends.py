"""The per-design part of the HTML report: charts over the iterations and the exact violation counts.

Per design: wirelength and vias (linear axes of at least ``MIN_SPAN_FRACTION`` of the largest value,
so that a 0.4% change is drawn as one, with the range said under the plot), violations on a symlog
axis (10 -> 1 -> 0 all visible) with a table of the exact counts, time per iteration, and per run its
violations by type. When every run of a design has one iteration there is no trend to draw: the
section is a table of the figures instead.
"""

from __future__ import annotations

from html import escape
from typing import TYPE_CHECKING, Any

from xroute.cli.svg_chart import line_chart

if TYPE_CHECKING:
    from xroute.cli.report_html import Run

MIN_SPAN_FRACTION = 0.1  # a linear figure's axis spans at least this share of its largest value


def _label(r: Run) -> str:
    return f"{r.name} ({r.metrics.get('policy', '')})"


def _iterations(r: Run) -> list[dict[str, Any]]:
    return list(r.metrics["iterations"])


def _linear(title: str, runs: list[Run], key: str, unit: str, axis: str, from_zero: bool = False) -> str:
    series = [(_label(r), [float(it.get(key, 0.0)) for it in _iterations(r)]) for r in runs]
    top = max((abs(v) for _, vs in series for v in vs), default=0.0)
    span = top if from_zero else MIN_SPAN_FRACTION * top
    return line_chart(title, series, axis, min_span=span, unit=unit)


def _violation_table(runs: list[Run]) -> str:
    n = max(len(_iterations(r)) for r in runs)
    head = "".join(f"<th>{i}</th>" for i in range(n))
    rows = []
    for r in runs:
        cells = [f'<td class="n">{int(it["violations"]):,}</td>' for it in _iterations(r)]
        cells += ["<td></td>"] * (n - len(cells))
        rows.append(f'<tr class="drv"><td>{escape(_label(r))}</td>{"".join(cells)}</tr>')
    return ('<table class="drvs"><caption>violations by iteration (exact counts)</caption><thead><tr><th>run</th>'
            f'{head}</tr></thead><tbody>{"".join(rows)}</tbody></table>')


def _by_type(r: Run) -> str:
    its = _iterations(r)
    types = [t for t in dict.fromkeys(t for it in its for t in it.get("violations_by_type", {}))
             if any(it.get("violations_by_type", {}).get(t) for it in its)]
    if not types:
        return ""
    series = [(t, [float(it.get("violations_by_type", {}).get(t, 0)) for it in its]) for t in types]
    return line_chart(f"Violations by type: {r.name}", series, "count (symlog)", scale="symlog", unit="violations")


def _single_iteration_table(runs: list[Run]) -> str:
    rows = []
    for r in runs:
        it = _iterations(r)[0] if _iterations(r) else {}
        by_type = ", ".join(f"{t} {v:,}" for t, v in it.get("violations_by_type", {}).items() if v) or "none"
        rows.append(f'<tr class="single"><td>{escape(_label(r))}</td>'
                    f'<td class="n">{float(it.get("wirelength_um", 0.0)):,.1f}</td>'
                    f'<td class="n">{int(it.get("vias", 0)):,}</td><td class="n">{int(it.get("violations", 0)):,}</td>'
                    f'<td>{escape(by_type)}</td><td class="n">{float(it.get("seconds", 0.0)):.2f}</td></tr>')
    return ('<table class="single"><caption>one iteration per run: its figures (no trend to draw)</caption>'
            "<thead><tr><th>run</th><th>WL (µm)</th><th>vias</th><th>violations</th><th>by type</th>"
            f'<th>time (s)</th></tr></thead><tbody>{"".join(rows)}</tbody></table>')


def design_section(design: str, runs: list[Run]) -> str:
    """The heading, charts and tables of one design's runs."""
    if all(len(_iterations(r)) <= 1 for r in runs):
        return (f"<h2>{escape(design)}: one iteration</h2>\n" + _single_iteration_table(runs))
    charts = [
        _linear("Wirelength by iteration", runs, "wirelength_um", "µm", "µm"),
        _linear("Vias by iteration", runs, "vias", "vias", "count"),
        line_chart("Violations by iteration", [(_label(r), [float(it["violations"]) for it in _iterations(r)])
                                               for r in runs], "count (symlog)", scale="symlog", unit="violations"),
        _linear("Time per iteration", runs, "seconds", "s", "seconds", from_zero=True),
        *[c for c in (_by_type(r) for r in runs) if c],
    ]
    return (f"<h2>{escape(design)}: trends over iterations</h2>\n<div class=\"charts\">{''.join(charts)}</div>\n"
            + _violation_table(runs))

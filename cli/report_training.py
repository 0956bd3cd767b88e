"""The training dashboard of ``xroute report``: a training run's ``metrics.jsonl`` as charts and a table.

``xroute train`` (:mod:`xroute.policies.rl.train`) writes one JSON object per episode into
``metrics.jsonl``: ``episode``, ``steps``, ``reward`` (sum of the env's rewards), ``cost`` (the
region's cost at the end: 0.5 WL(um) + 4 vias + 500 DRVs), ``drvs``, ``wirelength_dbu``, ``vias``,
``seconds`` and the last losses. Per run the dashboard shows a summary row (episodes, steps, time,
mean reward / cost / violations over the first and the last tenth of the episodes) and three
charts over the episodes: reward, cost and violations, each with its moving mean over
``window(n)`` episodes beside the raw values.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from html import escape
from pathlib import Path
from typing import Any

from xroute.errors import InputError, safe_text
from xroute.cli.svg_chart import line_chart

TRAINING_LOG = "metrics.jsonl"
CHARTS = (("reward", "Reward", "sum of rewards"), ("cost", "Cost", "cost units"), ("drvs", "Violations", "count"))


@dataclass(frozen=True)
class TrainingRun:
    name: str  # the run's folder name
    path: Path  # its metrics.jsonl
    episodes: list[dict[str, Any]]


def read_training_log(path: Path) -> TrainingRun:
    """The episodes of a ``metrics.jsonl``; an :class:`InputError` naming the file and line otherwise."""
    episodes = []
    from xroute.regular_files import read_regular_bytes

    try:
        lines = read_regular_bytes(path, what="training log").decode("utf-8").splitlines()  # never a FIFO
    except UnicodeDecodeError as exc:
        raise InputError(f"cannot read the training log ({exc})", str(path), 0) from exc
    for n, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            row = json.loads(line)
            float(row["episode"]), float(row["reward"])  # noqa: B018 - the fields the dashboard needs
        except (ValueError, KeyError, TypeError, IndexError, RecursionError) as exc:
            raise InputError(f"not a training log line written by xroute train ({type(exc).__name__}: "
                             f"{safe_text(exc)[:200]})", str(path), n) from None
        episodes.append(row)
    if not episodes:
        raise InputError("the training log has no episode", str(path), 0)
    return TrainingRun(name=path.parent.name or path.stem, path=path, episodes=episodes)


def find_training_logs(folder: Path, max_depth: int) -> list[Path]:
    """Every ``metrics.jsonl`` in or below ``folder`` (``max_depth`` levels, hidden folders skipped)."""
    return sorted(p for p in folder.rglob(TRAINING_LOG)
                  if len(p.relative_to(folder).parts) <= max_depth + 1
                  and not any(part.startswith(".") for part in p.relative_to(folder).parts))


def window(n: int) -> int:
    """Episodes per moving mean: a twentieth of the run, at least 1, at most 100."""
    return max(1, min(100, n // 20))


def moving_mean(values: list[float], w: int) -> list[float]:
    """The mean of the last ``w`` values at each position (fewer at the start)."""
    out, total = [], 0.0
    for i, v in enumerate(values):
        total += v
        if i >= w:
            total -= values[i - w]
        out.append(total / min(i + 1, w))
    return out


def _values(run: TrainingRun, key: str) -> list[float]:
    return [float(e.get(key) or 0.0) for e in run.episodes]


def _mean(values: list[float]) -> float:
    return sum(values) / len(values) if values else 0.0


def summary_row(run: TrainingRun) -> dict[str, float]:
    """Episodes, steps, seconds and the means of reward, cost and violations over the first and the last
    tenth of the episodes (at least one episode each)."""
    n = len(run.episodes)
    k = max(1, n // 10)
    row: dict[str, float] = {"episodes": n, "steps": int(run.episodes[-1].get("total_steps", 0)),
                             "seconds": sum(float(e.get("seconds", 0.0)) for e in run.episodes)}
    for key, _, _ in CHARTS:
        v = _values(run, key)
        row[f"{key}_first"], row[f"{key}_last"] = _mean(v[:k]), _mean(v[-k:])
    return row


def render_training(runs: list[TrainingRun]) -> str:
    """The training section of the report page (a table and, per run, three charts)."""
    head = ["run", "episodes", "steps", "time (s)"] + [f"{label} {part}" for _, label, _ in CHARTS
                                                      for part in ("first 10%", "last 10%")]
    rows = []
    for r in runs:
        s = summary_row(r)
        cells = [f"<td>{escape(r.name)}</td>", f'<td class="n">{s["episodes"]:,}</td>',
                 f'<td class="n">{s["steps"]:,}</td>', f'<td class="n">{s["seconds"]:,.1f}</td>']
        cells += [f'<td class="n">{s[f"{key}_{part}"]:,.1f}</td>' for key, _, _ in CHARTS for part in ("first", "last")]
        rows.append(f'<tr class="training">{"".join(cells)}</tr>')
    out = ["<h2>Training</h2>",
           "<table id=\"training\"><thead><tr>" + "".join(f"<th>{escape(h)}</th>" for h in head)
           + "</tr></thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>"]
    for r in runs:
        w = window(len(r.episodes))
        charts = []
        for key, label, unit in CHARTS:
            v = _values(r, key)
            series = [(f"{label.lower()} per episode", v)]
            if w > 1:
                series.append((f"mean of {w} episodes", moving_mean(v, w)))
            charts.append(line_chart(f"{label} by episode", series, unit, x_label="episode", x_start=1))
        out.append(f"<h2>{escape(r.name)}: training by episode</h2>\n<div class=\"charts\">{''.join(charts)}</div>")
    return "\n".join(out)

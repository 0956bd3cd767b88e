"""The one wording of the two figures of merit, for every command that prints them.

* **paper cost** — the XRoute paper's weighted sum, ``wirelength_weight·WL(µm) + via_weight·vias +
  drv_weight·violations`` (:class:`xroute.config.CostSection`; 0.5, 4 and 500 by default): what
  route, evaluate, batch and report compare runs by, lower is better;
* **contest score** — the ISPD-2018/2019 evaluator's weighted sum before violations
  (:data:`xroute.check.SCORE_WEIGHTS`: wire and out-of-guide, off-track and wrong-way terms, lengths
  in M2 pitches): what ``xroute check`` prints when it has the guides.

The two are on different scales and are not comparable with each other.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from xroute.check import SCORE_WEIGHTS

if TYPE_CHECKING:
    from xroute.config import CostSection

COST_NAME = "paper cost"
SCORE_NAME = "contest score"
_SCORE_TERMS = {"wirelength": "WL", "vias": "vias", "out_of_guide_wirelength": "out-of-guide WL",
                "out_of_guide_vias": "out-of-guide vias", "off_track_wirelength": "off-track WL",
                "off_track_vias": "off-track vias", "wrong_way_wirelength": "wrong-way WL"}


def cost_line(cost: CostSection) -> str:
    """``paper cost = 0.5·WL(µm) + 4·vias + 500·violations (...)`` with the weights in use."""
    return (f"{COST_NAME} = {cost.wirelength_weight:g}·WL(µm) + {cost.via_weight:g}·vias + "
            f"{cost.drv_weight:g}·violations (the XRoute paper's figure; route, evaluate, report; lower is better)")


def score_line() -> str:
    """``contest score = 0.5·WL + 2·vias + ... (lengths in M2 pitches; ...)``, from SCORE_WEIGHTS."""
    terms = " + ".join(f"{w:g}·{_SCORE_TERMS.get(k, k)}" for k, w in SCORE_WEIGHTS.items())
    return (f"{SCORE_NAME} = {terms} (ISPD-2018/2019 evaluator, lengths in M2 pitches, before violations; "
            f"xroute check; not comparable with the {COST_NAME})")

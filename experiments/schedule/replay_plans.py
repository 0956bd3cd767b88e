"""A schedule policy that replays a list of plan changes, one per iteration (for the headroom search).

The list is a JSON file named by ``$XROUTE_REPLAY_PLANS``: entry i changes iteration i's plan, the
iterations after the list run the rule. An entry is a dict of IterationPlan fields, plus
``"weights": F``, which multiplies the rule's marker, history and other-net weights by F. A region
size without an offset takes the rule's offsets for that size (0, C/3, 2C/3 by iteration).
"""

from __future__ import annotations

import json
import os
from typing import Any

_PLANS: list[dict[str, Any]] = json.loads(open(os.environ["XROUTE_REPLAY_PLANS"]).read())


def plan(history: list[Any], rule: Any) -> dict[str, Any] | None:
    i = len(history)
    if i >= len(_PLANS) or not _PLANS[i]:
        return None
    change = dict(_PLANS[i])
    factor = change.pop("weights", None)
    if factor is not None:
        for name in ("marker_penalty", "history_penalty", "use_penalty"):
            change[name] = int(round(getattr(rule, name) * float(factor)))
    if "region_size" in change and "offset" not in change:
        change["offset"] = (i % 3) * int(change["region_size"]) // 3
    return change

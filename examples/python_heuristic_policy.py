"""The engine's heuristic net order written in Python: an example policy file, and the
measure of the policy seam's cost (route with ``--policy examples/python_heuristic_policy.py``
and compare with ``--policy heuristic``: same order, so the same routing, plus one Python
call per region).

A policy file defines ``order(region, features)`` (the protocol ``xroute.net_order.NetOrderPolicy``) and may set NAME.
"""

import numpy as np

NAME = "python-heuristic"

# Columns of features (xroute.net_order.FEATURE_COLUMNS).
NET, TERMINALS, XLO, YLO, XHI, YHI = 0, 2, 4, 5, 6, 7


def order(region, features):
    """Smallest terminal bounding box (half perimeter) first, then more terminals, then lower net id."""
    f = features.astype(np.int64)
    half_perimeter = (f[:, XHI] - f[:, XLO]) + (f[:, YHI] - f[:, YLO])
    return np.lexsort((f[:, NET], -f[:, TERMINALS], half_perimeter))

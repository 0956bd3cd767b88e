"""Net-order policies: the protocol, the built-ins and the registry (see :mod:`xroute.net_order`).

Importing this package loads no engine and no torch.
"""

from xroute.net_order import (
    FEATURE_COLUMNS,
    CallablePolicy,
    HeuristicPolicy,
    NetOrderPolicy,
    PolicyError,
    RandomPolicy,
    heuristic_order,
)
from xroute.policies.registry import BUILTIN_POLICIES, get_policy, get_schedule_policy, load_policy_file

__all__ = [
    "BUILTIN_POLICIES",
    "FEATURE_COLUMNS",
    "CallablePolicy",
    "HeuristicPolicy",
    "NetOrderPolicy",
    "PolicyError",
    "RandomPolicy",
    "get_policy",
    "get_schedule_policy",
    "heuristic_order",
    "load_policy_file",
]

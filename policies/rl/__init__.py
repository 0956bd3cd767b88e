"""Learning side of the net-order seam: observations (numpy), Gymnasium environments, models.

Importing this package imports no engine and no torch. The Gymnasium environments built on
these observations are :mod:`xroute.envs`.
"""

from xroute.policies.rl.observation import (
    ALIGNED_SHAPE,
    NET_CHANNELS,
    NET_FEATURES,
    RegionObservation,
    align,
    observe,
)

__all__ = ["ALIGNED_SHAPE", "NET_CHANNELS", "NET_FEATURES", "RegionObservation", "align", "observe"]

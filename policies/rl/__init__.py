"""Learning side of the net-order seam: observations (numpy), Gymnasium environments, models.

Importing this package imports no engine and no torch. When gymnasium is installed (the ``rl``
extra), the environments are registered under their IDs (see :mod:`policies.rl.envs`); the
environment modules themselves load on ``gymnasium.make``.
"""

from policies.rl.observation import (
    ALIGNED_SHAPE,
    NET_CHANNELS,
    NET_FEATURES,
    RegionObservation,
    align,
    observe,
)

try:  # registration needs gymnasium only; the envs load the engine when made
    from policies.rl.envs import register_envs
except ImportError:  # gymnasium not installed: observations still work
    pass
else:
    register_envs()

__all__ = ["ALIGNED_SHAPE", "NET_CHANNELS", "NET_FEATURES", "RegionObservation", "align", "observe"]

"""Gymnasium environments of net ordering, one per module:

* ``xroute/NetOrdering-v0`` (:mod:`.ordering_training`): training mode, one region an episode;
* ``xroute/NetOrderingEval-v0`` (:mod:`.ordering_evaluation`): routes a whole testcase, the agent
  ordering every region;
* ``xroute/StaticRegion-v0`` (:mod:`.static_region`): one region written by ``xroute make-region``.

:func:`register_envs` registers them (idempotent); ``import policies.rl`` calls it.
"""

from __future__ import annotations

import gymnasium

ENV_IDS: dict[str, str] = {
    "xroute/NetOrdering-v0": "policies.rl.envs.ordering_training:NetOrderingTrainingEnv",
    "xroute/NetOrderingEval-v0": "policies.rl.envs.ordering_evaluation:NetOrderingEvaluationEnv",
    "xroute/StaticRegion-v0": "policies.rl.envs.static_region:StaticRegionEnv",
}


def register_envs() -> None:
    """Registers every xroute environment with gymnasium (once)."""
    for env_id, entry_point in ENV_IDS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(id=env_id, entry_point=entry_point)

"""Gymnasium environments of net ordering (the ``rl`` extra), one per module:

* ``xroute/NetOrdering-v0`` (:mod:`.ordering_training`, :func:`ordering_training_env`): training
  mode, one region an episode;
* ``xroute/NetOrderingEval-v0`` (:mod:`.ordering_evaluation`, :func:`ordering_evaluation_env`):
  routes a whole testcase, the agent ordering every region;
* ``xroute/StaticRegion-v0`` (:mod:`.static_region`, :func:`static_region_env`): one region
  written by ``xroute make-region`` (or :func:`generate_static_region`);
* ``xroute/NetRouting-v0`` (:mod:`.net_routing`, :func:`net_routing_env`): the paper's second task,
  one net of a region routed step by step from its head;
* ``xroute/ScheduleIteration-v0`` (:mod:`.schedule_iteration`, :func:`schedule_iteration_env`):
  each iteration's plan of a whole routing run (region size, repair rounds, weights, stop).

Importing this package registers the five IDs with gymnasium (nothing else is loaded until an
environment is made), so ``import xroute.envs; gymnasium.make("xroute/NetOrdering-v0")`` works, and
so does ``gymnasium.make("xroute.envs:xroute/NetOrdering-v0")`` without the import.
"""

from __future__ import annotations

from typing import Any

from gymnasium.envs.registration import register, registry

ENV_IDS: dict[str, str] = {
    "xroute/NetOrdering-v0": "xroute.envs.ordering_training:NetOrderingTrainingEnv",
    "xroute/NetOrderingEval-v0": "xroute.envs.ordering_evaluation:NetOrderingEvaluationEnv",
    "xroute/StaticRegion-v0": "xroute.envs.static_region:StaticRegionEnv",
    "xroute/NetRouting-v0": "xroute.envs.net_routing:NetRoutingEnv",
    "xroute/ScheduleIteration-v0": "xroute.envs.schedule_iteration:ScheduleIterationEnv",
}

_FACTORIES = {
    "ordering_training_env": "xroute.envs.ordering_training",
    "ordering_evaluation_env": "xroute.envs.ordering_evaluation",
    "static_region_env": "xroute.envs.static_region",
    "generate_static_region": "xroute.envs.static_region",
    "net_routing_env": "xroute.envs.net_routing",
    "schedule_iteration_env": "xroute.envs.schedule_iteration",
}


def register_envs() -> None:
    """Registers every xroute environment with gymnasium (idempotent; done on import)."""
    for env_id, entry_point in ENV_IDS.items():
        if env_id not in registry:
            register(id=env_id, entry_point=entry_point)


def __getattr__(name: str) -> Any:
    """The factories load their module on first use (the engine is imported when an env is made)."""
    if name in _FACTORIES:
        import importlib

        return getattr(importlib.import_module(_FACTORIES[name]), name)
    raise AttributeError(f"module 'xroute.envs' has no attribute '{name}'")


register_envs()

__all__ = ["ENV_IDS", "generate_static_region", "net_routing_env", "ordering_evaluation_env", "ordering_training_env",
           "register_envs", "schedule_iteration_env", "static_region_env"]

"""The engine's settings defaults and limits, read from the C++ settings structs (``_engine.DEFAULTS``,
engine_cpp/bindings/defaults_bind.cpp): Python states none of them a second time.

Importing this module loads the compiled engine.
"""

from __future__ import annotations

from xroute import _engine

_D: dict = dict(_engine.DEFAULTS)

REGION_SIZE: int = int(_D["region_size"])  # GCells per region side; 0: auto (xroute.router.region_size_for)
REGION_GCELLS: int = int(_D["region_gcells"])  # the auto region's side, GCells, unless over the node budget
LEAST_REGION_GCELLS: int = int(_D["least_region_gcells"])  # the auto region's side, GCells at least
# ... and larger while three in four regions' grids stay within this many nodes a layer
REGION_GRID_NODES: float = float(_D["region_grid_nodes"])
ITERATIONS: int = int(_D["iterations"])  # iteration limit; the flow stops earlier at zero violations
MAX_ITERATIONS: int = int(_D["max_iterations"])
MAX_REGION_SIZE: int = int(_D["max_region_size"])  # GCells per region side at most
MAX_THREADS: int = int(_D["max_threads"])
REPAIR_ROUNDS: int = int(_D["repair_rounds"])  # check-and-reroute rounds inside a region (later iterations)
MAX_REPAIR_ROUNDS: int = int(_D["max_repair_rounds"])
ACCESS_POINTS_PER_PIN: int = int(_D["access_points_per_pin"])
SEARCH_BUDGET: int = int(_D["search_budget"])  # trial routings per region of the rollout / victims / bestof policies
# (per µm of wire, per via, per violation): the XRoute paper's cost, as the search policies score a region
REGION_COST_WEIGHTS: tuple[float, float, float] = tuple(float(w) for w in _D["region_cost_weights"])
MAX_SEARCH_BUDGET: int = int(_D["max_search_budget"])
MAX_REGION_NODES: int = int(_D["max_region_nodes"])  # grid nodes of one region at most

GROUTE_ITERATIONS: int = int(_D["groute_iterations"])  # rip-up-and-reroute rounds at most
GROUTE_CAPACITY_PERCENT: int = int(_D["groute_capacity_percent"])  # share of free tracks the global router fills
GROUTE_MIN_LAYER: int = int(_D["groute_min_layer"])
GROUTE_SLACK: int = int(_D["groute_slack"])
GROUTE_CONGESTION_COST: float = float(_D["groute_congestion_cost"])

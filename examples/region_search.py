"""A per-region search decision as a net-order policy file: spend the victims search only where it pays.

    xroute route ispd19_test1 --threads 2 --policy examples/region_search.py

The router asks ``order(region, features)`` once per region. With ``NEEDS_REGION = True`` the region
being routed is lent to the call (``region["engine_region"]``), so the policy may route the region's
nets itself: here, from the second iteration on (when only regions with markers have work) and in
regions with at least ``MIN_NETS`` nets to reroute, it runs the victims search with ``BUDGET`` trial
routings; elsewhere it returns the heuristic's order. The router routes whatever the policy left
unrouted in the order returned.
"""

from xroute.net_order import heuristic_order

NAME = "region-search"
NEEDS_REGION = True
BUDGET = 4  # trial routings per searched region
MIN_NETS = 3  # nets to reroute before a region is worth a search


def order(region, features):
    if region["iteration"] >= 1 and len(features) >= MIN_NETS:
        region["engine_region"].route_rest("victims", search_budget=BUDGET)
    return heuristic_order(features)

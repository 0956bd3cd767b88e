// _engine.DEFAULTS: the engine's settings defaults and limits, read from the C++
// settings structs themselves, so that Python states none of them a second time.
#include <nanobind/nanobind.h>

#include "grid/region_grid.hpp"
#include "groute/global_router.hpp"
#include "loop/regions.hpp"
#include "loop/router.hpp"
#include "order/search_policy.hpp"
#include "pa/pin_access.hpp"

namespace nb = nanobind;

void bindDefaults(nb::module_& m) {
  using namespace xroute;
  const RouterSettings router;
  const GlobalRouteSettings groute;
  const PinAccessSettings pa;
  nb::dict d;
  d["region_size"] = router.regionSize;  // 0: auto (autoRegionSize)
  d["region_gcells"] = kRegionGCells;
  d["least_region_gcells"] = kLeastRegionGCells;
  d["region_grid_nodes"] = kRegionGridNodes;
  d["iterations"] = router.iterations;
  d["max_iterations"] = kMaxIterations;
  d["max_region_size"] = kMaxRegionSize;
  d["max_threads"] = kMaxThreads;
  d["threads"] = router.threads;
  d["access_points_per_pin"] = pa.maxPointsPerPin;
  d["repair_rounds"] = router.repairRounds;
  d["max_repair_rounds"] = kMaxRepairRounds;
  d["marker_penalty"] = router.markerPenalty;
  d["history_penalty"] = router.historyPenalty;
  const SearchSettings search;
  d["search_budget"] = search.budget;
  d["search_width"] = search.width;
  d["max_search_budget"] = kMaxSearchBudget;
  d["region_cost_weights"] = nb::make_tuple(search.weights.wirelength, search.weights.via, search.weights.violation);
  d["max_region_nodes"] = static_cast<int64_t>(kMaxRegionNodes);
  d["groute_iterations"] = groute.iterations;
  d["groute_capacity_percent"] = groute.capacityPercent;
  d["groute_min_layer"] = groute.minLayer;
  d["groute_slack"] = groute.slack;
  d["groute_congestion_cost"] = groute.congestionCost;
  m.attr("DEFAULTS") = d;
}

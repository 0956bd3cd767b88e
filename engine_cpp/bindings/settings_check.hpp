// What the engine needs of the plans a Python iteration planner returns (IterationPlan), so that no
// value can make it crash or overflow. The friendly check, with the limits read from
// _engine.DEFAULTS, is where a plan enters (xroute.schedule.plan_from, naming the schedule policy);
// this one only refuses: SettingError -> xroute.errors.RouteArgumentError.
#pragma once

#include <cstdint>
#include <string>

#include "errors/engine_errors.hpp"
#include "loop/router.hpp"
#include "order/search_policy.hpp"

namespace xroute {

inline void requireIn(const char* what, int64_t value, int64_t lo, int64_t hi, const char* note = "") {
  if (value < lo || value > hi) {
    throw SettingError(std::string(what) + " must be in " + std::to_string(lo) + ".." + std::to_string(hi) + note +
                       ", got " + std::to_string(value));
  }
}

inline void checkPlan(const IterationPlan& p) {
  requireIn("plan: region_size", p.regionSize, 1, kMaxRegionSize);
  requireIn("plan: offset", p.offset, 0, p.regionSize - 1);
  requireIn("plan: repair_rounds", p.repairRounds, 0, kMaxRepairRounds);
  requireIn("plan: search_budget", p.searchBudget, 0, kMaxSearchBudget);
  requireIn("plan: marker_penalty", p.markerPenalty, 0, INT64_MAX);
  requireIn("plan: history_penalty", p.historyPenalty, 0, INT64_MAX);
  requireIn("plan: use_penalty", p.costs.usePenalty, 0, INT64_MAX);
}

}  // namespace xroute

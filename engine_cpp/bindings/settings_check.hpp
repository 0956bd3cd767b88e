// What the engine needs of the settings and plans Python hands it, so that no value can make it
// crash or overflow: the one check of route() and FirstPass (RouterSettings) and of the plans an
// iteration planner returns (IterationPlan). The friendly checks, with the limits read from
// _engine.DEFAULTS, are where a value enters (the command line, the YAML schema, route_design's
// keywords, a schedule policy's plan); this one only refuses: SettingError ->
// xroute.errors.RouteArgumentError.
#pragma once

#include <cstdint>
#include <limits>
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

inline void checkSettings(const RouterSettings& s) {
  requireIn("region_size", s.regionSize, 0, kMaxRegionSize, " (0: auto)");
  requireIn("iterations", s.iterations, 1, kMaxIterations);
  requireIn("threads", s.threads, 1, kMaxThreads);
  requireIn("repair_rounds", s.repairRounds, 0, kMaxRepairRounds);
  requireIn("first_repair_rounds", s.firstRepairRounds, 0, kMaxRepairRounds);
  requireIn("late_search_budget", s.lateSearchBudget, 0, kMaxSearchBudget);
  if (!(s.partialCheckShare >= 0 && s.partialCheckShare <= 1))  // NaN too
    throw SettingError("partial_check_share must be in 0..1, got " + std::to_string(s.partialCheckShare));
  requireIn("check_band_shapes", s.checkBandShapes, 0, std::numeric_limits<int64_t>::max());
  for (const ScheduleStep& step : s.schedule) {
    requireIn("schedule: region size", step.regionSize, 1, kMaxRegionSize);
    requireIn("schedule: offset", step.offset, 0, step.regionSize - 1);
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
